//! The `mingen` binary on hostile input and hostile surroundings: a full output device,
//! no workspace, out-of-range options, and a symbolic expansion that would not fit: each
//! exits 2 with one line on stderr, quickly.

use std::path::Path;
use std::process::Command;

fn mingen(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_mingen"))
        .args(args)
        .output()
        .expect("mingen runs")
}

#[test]
fn a_full_device_fails_quickly_on_one_line() {
    if !Path::new("/dev/full").exists() {
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let problem = root.join("templates/gs5pt.mp");
    let start = std::time::Instant::now();
    let run = mingen(&["generate", problem.to_str().unwrap(), "--out", "/dev/full"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("/dev/full"), "{stderr}");
    assert!(start.elapsed().as_secs_f64() < 30.0);
}

#[test]
fn generate_outside_a_workspace_writes_nothing() {
    // Without --out, `generate` writes under the workspace found above the current
    // directory, never into the tree the binary was built from.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let generated = root.join("solver/src/generated/gs5pt.rs");
    let before = std::fs::metadata(&generated)
        .and_then(|m| m.modified())
        .ok();
    let dir = std::env::temp_dir().join(format!("mingen-nowhere-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let problem = root.join("templates/gs5pt.mp");
    let run = Command::new(env!("CARGO_BIN_EXE_mingen"))
        .args(["generate", problem.to_str().unwrap()])
        .current_dir(&dir)
        .output()
        .expect("mingen runs");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("workspace root"), "{stderr}");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    let after = std::fs::metadata(&generated)
        .and_then(|m| m.modified())
        .ok();
    assert_eq!(before, after);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn usage_errors_and_limits_are_one_line() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let problem = root.join("templates/gs5pt.mp");
    let p = problem.to_str().unwrap();
    for args in [
        vec!["audit", p, "--instances", "100000000000"],
        vec!["report", p, "--instances", "0"],
        vec!["inspect", p, "--max-seconds", "nope"],
        vec!["inspect", p, "--no-such-option"],
    ] {
        let run = mingen(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: {stderr}");
    }
    let run = mingen(&["audit", p, "--instances", "100000000000"]);
    assert!(String::from_utf8_lossy(&run.stderr).contains("10000000"));
}

#[test]
fn inspect_expands_within_the_budget() {
    // Mod p the data are numbers and the equation is x^2 times one number; with the data
    // as symbols, (a1 + ... + a12)^32 has about 10^10 terms.
    let dir = std::env::temp_dir().join(format!("mingen-expand-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("wide.mp");
    let sum = "(a[0]+a[1]+a[2]+a[3]+a[4]+a[5]+a[6]+a[7]+a[8]+a[9]+a[10]+a[11])";
    std::fs::write(
        &file,
        format!("problem wide\nunknown x\ndata a[12]: scalar\nx^2 * {sum}^32 = 1\n"),
    )
    .unwrap();
    let start = std::time::Instant::now();
    let run = mingen(&["inspect", file.to_str().unwrap(), "--max-seconds", "2"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("expanding the equations"), "{stderr}");
    assert!(start.elapsed().as_secs_f64() < 20.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn audit_stops_at_its_time_budget() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let problem = root.join("templates/gs5pt.mp");
    let p = problem.to_str().unwrap();
    let start = std::time::Instant::now();
    let run = mingen(&["audit", p, "--instances", "10000000", "--max-seconds", "1"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("audit stopped after"), "{stderr}");
    assert!(start.elapsed().as_secs_f64() < 30.0);
    // The instances' figures are counted against the memory budget before any is run.
    let run = mingen(&["audit", p, "--instances", "10000000", "--max-memory", "16"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--max-memory"), "{stderr}");
}
