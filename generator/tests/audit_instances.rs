//! `mingen audit FILE --instances-from DATA`: instances read from a file give the same
//! report as the library on the same data, `inspect --json` documents the slot order, and
//! malformed lines are rejected naming the line and the column count.

use mingen::audit::audit_plan_on;
use mingen::instance::random_data_f64;
use mingen::instances_file::format_instances;
use mingen::pipeline::plan_file;
use mingen::template::TemplateOptions;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn mingen(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_mingen"))
        .args(args)
        .output()
        .expect("mingen runs")
}

fn problem() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/gs5pt.mp")
}

fn scratch(name: &str, text: &str) -> PathBuf {
    let p = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn audit_reads_instances_from_a_file() {
    let plan = plan_file(&problem(), &TemplateOptions::default()).unwrap();
    let layout = &plan.problem.layout;
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let data: Vec<Vec<f64>> = (0..40).map(|_| random_data_f64(layout, &mut rng)).collect();
    let text = format!(
        "# a comment\n\n{}",
        format_instances(data.iter().map(Vec::as_slice))
    );
    let file = scratch("gs5pt_instances.txt", &text);
    let run = mingen(&[
        "audit",
        problem().to_str().unwrap(),
        "--instances-from",
        file.to_str().unwrap(),
        "--json",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json: Value = serde_json::from_slice(&run.stdout).unwrap();
    let want = audit_plan_on(&plan, &data).to_json();
    assert_eq!(json["instances"], 40);
    // serde_json's float parsing may be one ulp off: the floats to rounding, the rest exactly.
    for (key, value) in want.as_object().unwrap() {
        match value.as_f64() {
            Some(w) if !value.is_u64() => {
                let got = json[key].as_f64().unwrap();
                assert!(
                    (got - w).abs() <= 1e-12 * w.abs().max(1.0),
                    "{key}: {got} vs {w}"
                );
            }
            _ => assert_eq!(&json[key], value, "{key}"),
        }
    }
    assert_eq!(json["failures"], 0, "{json}");

    let inspect = mingen(&["inspect", problem().to_str().unwrap(), "--json"]);
    let summary: Value = serde_json::from_slice(&inspect.stdout).unwrap();
    let names = summary["data_slot_names"].as_array().unwrap();
    assert_eq!(names.len(), layout.data_slot_count());
    assert_eq!(summary["data_slots"], layout.data_slot_count());
    assert_eq!(names[0], layout.data_slot_names()[0].as_str());
}

#[test]
fn malformed_lines_are_rejected_with_their_line_and_column_count() {
    let plan = plan_file(&problem(), &TemplateOptions::default()).unwrap();
    let n = plan.problem.layout.data_slot_count();
    let good: Vec<String> = (0..n).map(|k| format!("{}", 0.1 * k as f64)).collect();
    let short = good[..n - 1].join(" ");
    let file = scratch(
        "gs5pt_short.txt",
        &format!("{}\n# comment\n{short}\n", good.join(" ")),
    );
    let run = mingen(&[
        "audit",
        problem().to_str().unwrap(),
        "--instances-from",
        file.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains(&format!(
            "line 3: {} numbers, but the problem has {n} data slots",
            n - 1
        )),
        "{err}"
    );
    let mut bad = good.clone();
    bad[4] = "1.2.3".into();
    let file = scratch("gs5pt_bad.txt", &format!("{}\n", bad.join(" ")));
    let run = mingen(&[
        "audit",
        problem().to_str().unwrap(),
        "--instances-from",
        file.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("line 1, column 5: `1.2.3` is not a finite number"),
        "{err}"
    );
    let run = mingen(&[
        "audit",
        problem().to_str().unwrap(),
        "--instances-from",
        "/nonexistent/instances.txt",
    ]);
    assert_eq!(run.status.code(), Some(2));
}
