//! The pipeline on problem files: counts and template sizes of the shipped problems,
//! degenerate systems with clear errors, and deterministic `inspect --json`.

use mingen::Problem;
use mingen::TemplateOptions;
use mingen::{plan, plan_file};
use std::path::{Path, PathBuf};
use std::process::Command;

fn template(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("templates")
        .join(format!("{name}.mp"))
}

#[test]
fn shipped_problems_counts_and_sizes() {
    let opts = TemplateOptions::default();
    for (name, count, max_rows, max_cols) in [
        ("gs5pt", 10, 10, 20),
        ("grsrp10", 10, 10, 20),
        ("grsrp", 20, 70, 90),
        ("grsrp_gravity", 12, 51, 63),
        ("grsrp_gravity6", 6, 3, 9),
    ] {
        let p = plan_file(&template(name), &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
        // The size eliminated, after the fold of constant rows (`template/fold.rs`).
        let (rows, cols) = p.generated.built.template.eliminated_size();
        println!(
            "{name}: {count} solutions, template {rows}x{cols}, {:.3} s",
            p.seconds
        );
        assert_eq!(p.generated.count, count, "{name}");
        assert!(
            rows <= max_rows && cols <= max_cols,
            "{name}: {rows}x{cols}"
        );
        assert!(p.generated.validation.is_some(), "{name} validated");
    }
}

#[test]
fn eliminated_problem_reports_what_was_eliminated() {
    let p = plan_file(&template("grsrp10"), &TemplateOptions::default()).unwrap();
    assert_eq!(p.eliminated_names(), ["t1", "t2", "t3"]);
    assert_eq!(p.variable_names(), ["a1", "a2", "a3"]);
    let json = p.summary_json();
    assert_eq!(json["eliminated"], serde_json::json!(["t1", "t2", "t3"]));
    assert_eq!(json["template"]["rows"], 10);
}

#[test]
fn positive_dimensional_problem_is_a_clear_error() {
    // grsrp with one point equation removed: a one-parameter family of solutions.
    let src = std::fs::read_to_string(template("grsrp"))
        .unwrap()
        .replace("for k in 0..5", "for k in 0..4");
    let problem = Problem::parse(&src, "grsrp4.mp").unwrap();
    let err = plan(problem, "grsrp4.mp", &TemplateOptions::default())
        .err()
        .expect("must fail")
        .to_string();
    assert!(err.contains("positive-dimensional"), "{err}");
    assert!(err.contains("grsrp4.mp"), "{err}");
}

#[test]
fn inconsistent_problem_is_a_clear_error() {
    let src = "problem contradiction\nunknown x, y\ndata c: scalar\nx = 0\nx = 1\ny*y = c\n";
    let problem = Problem::parse(src, "contradiction.mp").unwrap();
    let err = plan(problem, "contradiction.mp", &TemplateOptions::default())
        .err()
        .expect("must fail")
        .to_string();
    assert!(err.contains("inconsistent"), "{err}");
}

#[test]
fn non_linear_elimination_is_a_clear_error() {
    let src =
        "problem bad\nunknown x, t[3]\ndata c: vec3\nx*x = 1\nt'*t*x = 1\nc'*t = x\neliminate t\n";
    let problem = Problem::parse(src, "bad.mp").unwrap();
    let err = plan(problem, "bad.mp", &TemplateOptions::default())
        .err()
        .expect("must fail")
        .to_string();
    assert!(err.contains("eliminate t1 t2 t3"), "{err}");
    // An affine (inhomogeneous) equation in t is named by the unknowns, not their numbers.
    let src =
        "problem affine\nunknown x, t[3]\ndata c: vec3\nx*x = 1\nc'*t = x\nt'*t = 1\neliminate t\n";
    let err = plan(
        Problem::parse(src, "a.mp").unwrap(),
        "a.mp",
        &TemplateOptions::default(),
    )
    .err()
    .expect("must fail")
    .to_string();
    assert!(err.contains("(t1, t2, t3)") && !err.contains('#'), "{err}");
}

fn inspect_json(file: &Path) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_mingen"))
        .arg("inspect")
        .arg(file)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn inspect_json_has_the_contract_keys_and_is_deterministic() {
    let file = template("grsrp");
    let mut a = inspect_json(&file);
    let mut b = inspect_json(&file);
    for key in [
        "name",
        "unknowns",
        "equations",
        "solutions",
        "basis",
        "action",
        "template",
        "eliminated",
        "seconds",
    ] {
        assert!(a.get(key).is_some(), "missing {key}");
    }
    assert_eq!(a["solutions"], 20);
    // Everything but the wall time is byte-identical between runs.
    a.as_object_mut().unwrap().remove("seconds");
    b.as_object_mut().unwrap().remove("seconds");
    assert_eq!(
        serde_json::to_string(&a).unwrap(),
        serde_json::to_string(&b).unwrap()
    );
}

#[test]
fn inspect_exits_2_on_a_degenerate_problem() {
    let dir = std::env::temp_dir().join(format!("mingen-pipeline-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("contradiction.mp");
    std::fs::write(&f, "problem contradiction\nunknown x\nx = 0\nx = 1\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_mingen"))
        .arg("inspect")
        .arg(&f)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("contradiction.mp") && err.contains("inconsistent"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// `--weights` takes one positive weight per unknown; anything else exits with code 2 and
/// a one-line message naming the vector, before or after planning.
#[test]
fn bad_weights_on_the_command_line_exit_2() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/classic/relpose_5pt.mp");
    for (weights, expect) in [("1,0,2", "1,0,2"), ("1,x,2", "1,x,2"), ("1,2", "[1, 2]")] {
        let out = Command::new(env!("CARGO_BIN_EXE_mingen"))
            .arg("inspect")
            .arg(&file)
            .args(["--weights", weights])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "--weights {weights}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(expect), "--weights {weights}: {err}");
    }
}
