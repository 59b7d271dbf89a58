//! Emitted solvers of the largest shipped problems build in a user's crate in the dev
//! profile and the 2018 edition (`tools/emitted_solver/run.sh` with `PROFILE=dev
//! EDITION=2018 BUILD_ONLY=1`): the default code form keeps every function within what
//! rustc's debug build compiles, and the code names nothing a 2018 prelude lacks.
//! Ignored by default (planning r6p alone takes minutes); `.ci/run` runs the same script.

use std::path::Path;
use std::process::Command;

fn builds_in_dev_2018(problem: &str) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let run = Command::new("bash")
        .arg(root.join("tools/emitted_solver/run.sh"))
        .args([problem, "random:1"])
        .current_dir(&root)
        .env("PROFILE", "dev")
        .env("EDITION", "2018")
        .env("BUILD_ONLY", "1")
        .output()
        .expect("bash runs");
    assert!(
        run.status.success(),
        "{problem}: {}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
}

#[test]
#[ignore = "minutes: plans r6p and builds its solver crate"]
fn r6p_builds_in_dev_and_edition_2018() {
    builds_in_dev_2018("templates/classic/r6p.mp");
}

#[test]
#[ignore = "a minute: builds a solver crate in the dev profile"]
fn relpose_5pt_cayley_sat_builds_in_dev_and_edition_2018() {
    builds_in_dev_2018("templates/classic/relpose_5pt_cayley_sat.mp");
}
