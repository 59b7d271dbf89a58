//! Generates a solver for every problem of the classic corpus (`templates/classic/*.mp`)
//! into `$OUT_DIR` for the planted-solution tests (`tests/corpus.rs`), and three of them again
//! in each form of the coefficient code (`tests/code_forms.rs`). Each problem is planned
//! once, whatever the number of forms it is emitted in: planning is the costly part.
//!
//! The emitted files are also kept in a cache beside the build directories, keyed by a
//! hash of everything they are made from (the corpus, mingen's and its runtime's sources,
//! the lock file, this script, the compiler and its flags). Cargo runs this script again
//! for builds that differ only in how the workspace is compiled (`cargo clippy` compiles
//! the script with clippy-driver): the same inputs then give the same files without
//! planning the corpus a second time.

use mingen::{emit_plan_in, plan_files, CodeForm, TemplateOptions};
use std::fmt::Write as _;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

/// Corpus problems also emitted in each form of the coefficient code (`src/lib.rs`'s
/// `inline` and `table` modules): one with a large template and Newton polishing, one
/// whose affine equations planning substitutes into the others, one whose constant rows'
/// fold the inline form writes out as code (the table form walks the fold's plan).
const BOTH_FORMS: [&str; 3] = ["p35pf", "relpose_5pt_entries", "relpose_upright_3pt"];

/// Threads planning the corpus: its plans are independent, and planning is most of this
/// script's time.
const PLANNING_THREADS: usize = 2;

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
    for file in &files {
        println!("cargo:rerun-if-changed={}", file.display());
    }
    let cache = cache_dir(&out_dir, &files)?;
    if cache.is_dir() {
        return copy_tree(&cache, &out_dir);
    }
    emit_corpus(&files, &out_dir)?;
    // A whole set or none: written aside, then renamed into place (a concurrent build may
    // have stored the same set first; either copy is the same).
    let partial = cache.with_extension(format!("partial-{}", std::process::id()));
    copy_tree(&out_dir, &partial)?;
    if std::fs::rename(&partial, &cache).is_err() {
        std::fs::remove_dir_all(&partial)?;
    }
    Ok(())
}

/// Plans every corpus file and writes its solver (and the `BOTH_FORMS` ones in each form)
/// and the `corpus.rs` that includes them into `out_dir`.
fn emit_corpus(files: &[PathBuf], out_dir: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let plans = plan_files(files, &TemplateOptions::default(), PLANNING_THREADS);
    let mut modules = String::new();
    for (file, plan) in files.iter().zip(plans) {
        let plan = plan?;
        let name = plan.module_name();
        let shown = file.display().to_string();
        let mut forms = vec![(out_dir.to_path_buf(), CodeForm::Auto)];
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

/// The cache entry of this corpus: `<target>/<profile>/build/workspace-tests-corpus/<key>`,
/// the key hashing every input of the emitted files. The sources are hashed, not their
/// modification times: a checkout or a clean build with the same text is the same entry.
fn cache_dir(out_dir: &Path, files: &[PathBuf]) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    include_str!("build.rs").hash(&mut hasher);
    for file in files {
        file.hash(&mut hasher);
        std::fs::read(file)?.hash(&mut hasher);
    }
    for source in ["../generator", "../generator/runtime"] {
        for path in source_files(Path::new(source))? {
            path.hash(&mut hasher);
            std::fs::read(&path)?.hash(&mut hasher);
        }
    }
    std::fs::read("../Cargo.lock").ok().hash(&mut hasher);
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = std::process::Command::new(rustc).arg("-vV").output()?;
    version.stdout.hash(&mut hasher);
    for var in ["CARGO_ENCODED_RUSTFLAGS", "OPT_LEVEL", "PROFILE", "TARGET"] {
        std::env::var(var).ok().hash(&mut hasher);
    }
    let build = out_dir
        .ancestors()
        .nth(2)
        .ok_or("OUT_DIR is not <target>/<profile>/build/<package>/out")?;
    Ok(build
        .join("workspace-tests-corpus")
        .join(format!("{:016x}", hasher.finish())))
}

/// A crate's `Cargo.toml` and every file under its `src`, sorted.
fn source_files(krate: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files = vec![krate.join("Cargo.toml")];
    let mut dirs = vec![krate.join("src")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(dir)? {
            let path = entry?.path();
            if path.is_dir() {
                dirs.push(path);
            } else {
                files.push(path);
            }
        }
    }
    files.sort();
    Ok(files)
}

/// Copies the files of `from`, and of its subdirectories, into `to`.
fn copy_tree(from: &Path, to: &Path) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(to)?;
    for entry in std::fs::read_dir(from)? {
        let path = entry?.path();
        let target = to.join(path.file_name().ok_or("a file without a name")?);
        if path.is_dir() {
            copy_tree(&path, &target)?;
        } else {
            std::fs::copy(&path, &target)?;
        }
    }
    Ok(())
}
