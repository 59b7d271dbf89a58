//! The checked-in generated solvers must be exactly what the problem files produce
//! (rust-analyzer's `xtask codegen` pattern): regenerate in memory and compare byte for byte.

use std::path::Path;

#[test]
fn generated_solvers_are_fresh() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root");
    let files = mingen::generate::problem_files(root).expect("templates/ is readable");
    assert!(
        files.len() >= 4,
        "expected the shipped problems in templates/, found {files:?}"
    );
    let report = mingen::generate::generate(root, &files, true, true)
        .expect("every shipped problem generates");
    let stale: Vec<String> = report
        .iter()
        .filter(|f| !f.fresh)
        .map(|f| f.path.display().to_string())
        .collect();
    assert!(
        stale.is_empty(),
        "stale generated files (run `cargo run --release -p mingen -- generate --all`): {stale:?}"
    );
}
