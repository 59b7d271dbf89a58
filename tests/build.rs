//! Generates a solver for every problem of the classic corpus (`templates/classic/*.mp`)
//! into `$OUT_DIR` for the planted-solution tests (`tests/corpus.rs`), and three of them again
//! in each form of the coefficient code (`tests/code_forms.rs`). Each problem is planned
//! once, whatever the number of forms it is emitted in: planning is the costly part.

use mingen::{emit_plan_in, plan_file, CodeForm, TemplateOptions};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Corpus problems also emitted in each form of the coefficient code (`src/lib.rs`'s
/// `inline` and `table` modules): one with a large template and Newton polishing, one
/// whose affine equations planning substitutes into the others, one whose constant rows'
/// fold the inline form writes out as code (the table form walks the fold's plan).
const BOTH_FORMS: [&str; 3] = ["p35pf", "relpose_5pt_entries", "p3ll"];

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
    let mut modules = String::new();
    for file in &files {
        println!("cargo:rerun-if-changed={}", file.display());
        let plan = plan_file(file, &TemplateOptions::default())?;
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
