//! Generates the crate's solvers from problem files at build time: the 5-point problem and
//! every problem of the classic corpus (`templates/classic/*.mp`), so that building the
//! crate checks that each corpus solver is emitted and compiles.

use std::fmt::Write as _;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    mingen::build::Config::new()
        .problems(&["../../templates/gs5pt.mp"])
        .compile()?;
    let mut corpus: Vec<PathBuf> = std::fs::read_dir("../../templates/classic")?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "mp"))
        .collect();
    corpus.sort();
    // A new corpus file must rerun this script (a changed one reruns through `compile`).
    println!("cargo:rerun-if-changed=../../templates/classic");
    let compiled = mingen::build::Config::new().problems(&corpus).compile()?;
    // One module per corpus problem, included by src/lib.rs.
    let mut modules = String::new();
    for c in &compiled {
        writeln!(
            modules,
            "/// The solver of `templates/classic/{name}.mp` (see its module documentation).\n\
             pub mod {name} {{\n    include!(concat!(env!(\"OUT_DIR\"), \"/{name}.rs\"));\n}}",
            name = c.name
        )?;
    }
    let out = PathBuf::from(std::env::var("OUT_DIR")?).join("corpus.rs");
    std::fs::write(out, modules)?;
    Ok(())
}
