//! The sparse elimination against the dense LU on a problem's own template: operation
//! counts, instances where exactly one of them fails, the largest difference of the
//! reduced rows (relative to each row's largest entry), and the time per call of each, on
//! random instances (`mingen audit`'s data).
//!
//! `cargo run --release -p mingen --example sparse_elimination [PROBLEM.mp ...]`
//! (default: every problem in `templates/`).

use mingen::__internal::instance::random_data_f64;
use mingen::__internal::interpret::fill_template;
use mingen::plan_file;
use mingen::TemplateOptions;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut files: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    if files.is_empty() {
        let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../templates"));
        files = std::fs::read_dir(&dir)?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "mp"))
            .collect();
        files.sort();
    }
    println!("problem | template | dense / sparse multiply-adds | one fails | max |sparse - dense| | dense µs | sparse µs");
    for file in &files {
        let plan = plan_file(file, &TemplateOptions::default())?;
        let t = &plan.generated.built.template;
        let (rows, cols) = t.eliminated_size();
        let Some(sparse) = &t.sparse else {
            println!(
                "{} | {rows} x {cols} | dense (no sparse plan)",
                file.display()
            );
            continue;
        };
        let lu_plan = sparse.as_plan(t);
        let (pivots, first) = (t.pivot_columns(), t.n_excess - t.n_dependent);
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let instances = 2000;
        let mut filled = Vec::with_capacity(instances);
        while filled.len() < instances {
            let data = random_data_f64(&plan.problem.layout, &mut rng);
            let (equations, _) = plan.equations(&data);
            if let Ok(m) = fill_template(t, &equations) {
                filled.push(m);
            }
        }
        let (mut disagree, mut worst) = (0usize, 0.0f64);
        for m in &filled {
            let (mut s, mut d) = (m.clone(), m.clone());
            let dense_ok = mingen_runtime::lu_solve_template(&mut d, rows, cols, pivots, first);
            let sparse_ok = mingen_runtime::lu_solve_template_sparse(&mut s, &lu_plan);
            disagree += usize::from(dense_ok != sparse_ok);
            if dense_ok && sparse_ok {
                for r in first..pivots {
                    let row = r * cols + pivots..(r + 1) * cols;
                    let scale = d[row.clone()].iter().fold(1.0f64, |a, x| a.max(x.abs()));
                    for (a, b) in s[row.clone()].iter().zip(&d[row]) {
                        worst = worst.max((a - b).abs() / scale);
                    }
                }
            }
        }
        let time = |f: &dyn Fn(&mut [f64]) -> bool| {
            let mut work = filled[0].clone();
            let start = Instant::now();
            let mut ok = 0usize;
            for m in &filled {
                work.copy_from_slice(m);
                ok += usize::from(f(&mut work));
            }
            std::hint::black_box(ok);
            1e6 * start.elapsed().as_secs_f64() / filled.len() as f64
        };
        let dense_us = time(&|m| mingen_runtime::lu_solve_template(m, rows, cols, pivots, first));
        let sparse_us = time(&|m| mingen_runtime::lu_solve_template_sparse(m, &lu_plan));
        println!(
            "{} | {rows} x {cols} | {} / {} | {:.2} % | {worst:.1e} | {dense_us:.1} | {sparse_us:.1}",
            file.display(),
            sparse.dense_updates,
            sparse.sparse_updates,
            100.0 * disagree as f64 / instances as f64,
        );
    }
    Ok(())
}
