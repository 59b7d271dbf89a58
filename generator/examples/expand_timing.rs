//! Time of the symbolic expansion of every problem in a directory, and of one evaluation of
//! G-RSRP's equations mod p: `cargo run --release -p mingen --example expand_timing [DIR]`
//! (default `templates/`).

use mingen::__internal::algebra::{Fp, P1};
use mingen::__internal::instance::random_data_fp;
use mingen::Problem;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../templates")));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "mp"))
        .collect();
    files.sort();
    for file in &files {
        let problem = Problem::from_file(file)?;
        let start = Instant::now();
        let expanded = problem.expand();
        let seconds = start.elapsed().as_secs_f64();
        let terms: Vec<usize> = expanded
            .iter()
            .map(|q| q.terms().map(|(_, c)| c.len()).sum())
            .collect();
        println!(
            "{}: expand {:.3} ms, data terms per equation {terms:?}",
            file.display(),
            1e3 * seconds
        );
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let data = random_data_fp::<P1>(&problem.layout, &mut rng);
        let calls = 1000;
        let start = Instant::now();
        for _ in 0..calls {
            std::hint::black_box(problem.evaluate::<Fp<P1>>(&data));
        }
        println!(
            "    evaluate mod p: {:.2} µs per call",
            1e6 * start.elapsed().as_secs_f64() / calls as f64
        );
    }
    Ok(())
}
