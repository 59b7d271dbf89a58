//! The checked-in generated solvers must be exactly what the problem files produce
//! (rust-analyzer's `xtask codegen` pattern): `mingen generate --all --check` regenerates
//! them in memory and compares byte for byte. Which files those are is the binary's
//! knowledge of this repository, not the library's, so the test runs the binary.

use std::path::Path;
use std::process::Command;

#[test]
fn generated_solvers_are_fresh() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root");
    let out = Command::new(env!("CARGO_BIN_EXE_mingen"))
        .args(["generate", "--all", "--check", "--jobs", "2"])
        .current_dir(root)
        .output()
        .expect("mingen runs");
    let log = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "stale generated files (run `cargo run --release -p mingen -- generate --all`):\n{log}"
    );
    assert!(
        log.lines().filter(|l| l.starts_with("fresh")).count() >= 5,
        "expected the shipped problems in templates/ and the module list:\n{log}"
    );
}
