//! Generates a solver for every problem of the classic corpus (`templates/classic/*.mp`)
//! into `$OUT_DIR` for the planted-solution tests (`tests/corpus.rs`), and three of them again
//! in each form of the coefficient code (`tests/code_forms.rs`). Each problem is planned
//! once, whatever the number of forms it is emitted in: planning is the costly part.

use mingen::{emit_plan_in, plan_file, CodeForm, PipelineError, SolverPlan, TemplateOptions};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Corpus problems also emitted in each form of the coefficient code (`src/lib.rs`'s
/// `inline` and `table` modules): one with a large template and Newton polishing, one
/// whose affine equations planning substitutes into the others, one whose constant rows'
/// fold the inline form writes out as code (the table form walks the fold's plan).
const BOTH_FORMS: [&str; 3] = ["p35pf", "relpose_5pt_entries", "p3ll"];

/// Threads planning the corpus: its plans are independent, and planning is most of this
/// script's time.
const PLANNING_THREADS: usize = 2;

/// The plan of each file, in order, planned on [`PLANNING_THREADS`] threads, each taking
/// the next file not yet taken (plans differ in cost by orders of magnitude).
fn plan_all(files: &[PathBuf]) -> Vec<Result<SolverPlan, PipelineError>> {
    let next = AtomicUsize::new(0);
    let mut plans: Vec<(usize, Result<SolverPlan, PipelineError>)> = std::thread::scope(|scope| {
        let threads: Vec<_> = (0..PLANNING_THREADS)
            .map(|_| {
                scope.spawn(|| {
                    std::iter::from_fn(|| {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let file = files.get(i)?;
                        Some((i, plan_file(file, &TemplateOptions::default())))
                    })
                    .collect::<Vec<_>>()
                })
            })
            .collect();
        threads
            .into_iter()
            .flat_map(|h| h.join().expect("a planning thread panicked"))
            .collect()
    });
    plans.sort_by_key(|(i, _)| *i);
    plans.into_iter().map(|(_, p)| p).collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out_dir = PathBuf::from(std::env::var("OUT_DIR")?);
    let corpus = Path::new("../templates/classic");
    // A new corpus file must rerun this script, as must a changed one.
    println!("cargo:rerun-if-changed={}", corpus.display());
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "mp"))
        .collect();
    files.sort();
    let plans = plan_all(&files);
    let mut modules = String::new();
    for (file, plan) in files.iter().zip(plans) {
        println!("cargo:rerun-if-changed={}", file.display());
        let plan = plan?;
        let name = plan.module_name();
        let shown = file.display().to_string();
        let mut forms = vec![(out_dir.clone(), CodeForm::Auto)];
        if BOTH_FORMS.contains(&name.as_str()) {
            forms.push((out_dir.join("inline"), CodeForm::Inline));
            forms.push((out_dir.join("table"), CodeForm::Table));
        }
        for (dir, form) in forms {
            std::fs::create_dir_all(&dir)?;
            let source = emit_plan_in(&plan, &shown, form)?;
            std::fs::write(dir.join(format!("{name}.rs")), source)?;
        }
        writeln!(
            modules,
            "/// The solver of `templates/classic/{name}.mp` (see its module documentation).\n\
             pub mod {name} {{\n    include!(concat!(env!(\"OUT_DIR\"), \"/{name}.rs\"));\n}}"
        )?;
    }
    std::fs::write(out_dir.join("corpus.rs"), modules)?;
    Ok(())
}
