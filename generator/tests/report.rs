//! `mingen report`: one row per corpus file with the right solution counts, and a failing
//! problem is a row that still states its count.

use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn mingen(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_mingen"))
        .args(args)
        .output()
        .expect("mingen runs")
}

fn root() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The first number of the `# Macaulay2:` header line of a problem file.
fn macaulay2_count(file: &Path) -> usize {
    let text = std::fs::read_to_string(file).unwrap();
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix("# Macaulay2:"))
        .unwrap_or_else(|| panic!("{} has no Macaulay2 line", file.display()));
    line.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn report_on_the_corpus_has_one_row_per_file_with_the_independent_counts() {
    let dir = root().join("templates/classic");
    // A short budget: the counts of every problem are checked, the templates of those that
    // plan within it (the largest are planned by the example crate's build and by
    // `generate`'s tests).
    let run = mingen(&[
        "report",
        dir.to_str().unwrap(),
        "--json",
        "--instances",
        "50",
        "--max-seconds",
        "8",
        "--jobs",
        "2",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let rows: Vec<Value> = serde_json::from_slice::<Value>(&run.stdout)
        .unwrap()
        .as_array()
        .unwrap()
        .clone();
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "mp"))
        .collect();
    files.sort();
    assert!(files.len() >= 12, "the corpus has at least 12 problems");
    assert_eq!(rows.len(), files.len());
    let mut planned = 0;
    for (row, file) in rows.iter().zip(&files) {
        let stem = file.file_stem().unwrap().to_str().unwrap();
        assert_eq!(row["problem"], stem, "{row}");
        assert_eq!(row["solutions"], macaulay2_count(file), "{stem}");
        assert!(row["published"].is_string(), "{stem} has a published line");
        if row["error"].is_null() {
            assert!(row["template"]["rows"].as_u64().unwrap() >= 1, "{stem}");
            assert_eq!(row["audit"]["instances"], 50, "{stem}");
            planned += 1;
        } else {
            let e = row["error"].as_str().unwrap();
            assert!(e.contains("budget of 8 s ran out"), "{stem}: {e}");
        }
    }
    assert!(
        planned * 4 >= files.len() * 3,
        "{planned} of {} planned",
        files.len()
    );
}

/// A problem whose count is quick but whose template does not fit a 2 s budget: the
/// Cayley-form 5-point problem with t kept (40 solutions, a template search of minutes).
fn over_budget_problem() -> String {
    root()
        .join("templates/large/relpose_5pt_cayley.mp")
        .to_str()
        .unwrap()
        .to_string()
}

#[test]
fn a_problem_without_a_template_is_a_row_with_its_count_and_the_reason() {
    let file = over_budget_problem();
    let run = mingen(&["report", &file, "--markdown", "--max-seconds", "2"]);
    assert!(run.status.success());
    let text = String::from_utf8(run.stdout).unwrap();
    let row = text
        .lines()
        .find(|l| l.contains("`relpose_5pt_cayley`"))
        .unwrap();
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    assert_eq!(cells[3], "40", "{row}");
    assert_eq!(cells[5], "none", "{row}");
    assert!(text.contains("40 solutions, but no template"), "{text}");
    assert!(text.contains("time budget of 2 s ran out"), "{text}");
    assert!(!text.contains("x0") && !text.contains("x1"), "{text}");
}

#[test]
fn generate_reports_the_count_and_names_when_no_template_is_found() {
    let dir = std::env::temp_dir().join(format!("mingen-nocount-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out.rs");
    let file = over_budget_problem();
    let run = mingen(&[
        "generate",
        &file,
        "--out",
        out.to_str().unwrap(),
        "--max-seconds",
        "2",
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8(run.stderr).unwrap();
    assert!(err.contains("40 solutions, but no template"), "{err}");
    assert!(err.contains("action q1"), "{err}");
    assert!(!err.contains("x0") && !err.contains("x1"), "{err}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_unknown_outside_the_quotient_basis_is_read_off_its_reduced_row() {
    // Two solutions; the basis is {1, v} (u + v = b makes u linear in v): u is read off
    // the reduced template row of its column, `u = b - v`.
    let dir = std::env::temp_dir().join(format!("mingen-linear-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("line_circle.mp");
    std::fs::write(
        &file,
        // Planning would substitute v from the affine equation; kept, v is read off.
        "problem line_circle\nunknown u, v\ndata a: scalar, b: scalar\nu*u + v*v = a\nu + v = b\noption auto_eliminate = no\n",
    )
    .unwrap();
    let run = mingen(&[
        "audit",
        file.to_str().unwrap(),
        "--instances",
        "200",
        "--json",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let v: Value = serde_json::from_slice(&run.stdout).unwrap();
    assert!(v["median_log10_residual"].as_f64().unwrap() < -12.0, "{v}");
    let out = dir.join("line_circle.rs");
    let run = mingen(&[
        "generate",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let code = std::fs::read_to_string(&out).unwrap();
    assert!(code.contains("mingen_runtime::read_linear"), "{code}");
    std::fs::remove_dir_all(&dir).ok();
}
