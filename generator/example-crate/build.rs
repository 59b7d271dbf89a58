//! Generates the crate's solvers from problem files at build time: the 5-point problem and
//! every problem of the classic corpus (`templates/classic/*.mp`), so that building the
//! crate checks that each corpus solver is emitted and compiles.

use std::fmt::Write as _;
use std::path::PathBuf;

/// Corpus problems also emitted in each form of the coefficient code (`src/lib.rs`'s
/// `inline` and `table` modules): one with a large template and Newton polishing, one
/// whose affine equations planning substitutes into the others.
const BOTH_FORMS: [&str; 2] = ["p35pf", "relpose_5pt_entries"];

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
    let out_dir = PathBuf::from(std::env::var("OUT_DIR")?);
    std::fs::write(out_dir.join("corpus.rs"), modules)?;
    // Two corpus solvers again in both forms of the coefficient code (the table form is the
    // one `mingen` picks for large templates), so that the tests can check that both
    // compute the same bits.
    for (dir, form) in [
        ("inline", mingen::CodeForm::Inline),
        ("table", mingen::CodeForm::Table),
    ] {
        mingen::build::Config::new()
            .problems(&BOTH_FORMS.map(|n| format!("../../templates/classic/{n}.mp")))
            .out_dir(out_dir.join(dir))
            .code_form(form)
            .compile()?;
    }
    Ok(())
}
