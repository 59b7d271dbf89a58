//! `mingen audit FILE --instances-from DATA`: instances read from a file give the same
//! report as the library on the same data, `inspect --json` documents the slot order, and
//! malformed lines are rejected naming the line and the column count.

use mingen::__internal::instance::random_data_f64;
use mingen::__internal::instances_file::format_instances;
use mingen::audit_plan_on;
use mingen::plan_file;
use mingen::TemplateOptions;
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
    // serde_json's float parsing may be one ulp off: the floats to rounding (in nested
    // objects too), the rest exactly.
    fn same(got: &Value, want: &Value, key: &str) {
        match (want.as_f64(), want.as_object()) {
            (Some(w), _) if !want.is_u64() => {
                let g = got.as_f64().unwrap();
                assert!(
                    (g - w).abs() <= 1e-12 * w.abs().max(1.0),
                    "{key}: {g} vs {w}"
                );
            }
            (_, Some(fields)) => {
                for (k, v) in fields {
                    same(&got[k], v, &format!("{key}.{k}"));
                }
            }
            _ => assert_eq!(got, want, "{key}"),
        }
    }
    same(&json, &want, "audit");
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

/// `audit --solutions-from`: planted solutions of a problem with a linearly eliminated
/// unknown (`t`, compared up to sign) are recovered; a wrong one is not; a solutions file
/// of the wrong shape is bad input.
#[test]
fn planted_solutions_are_recovered_and_wrong_ones_are_not() {
    let problem = scratch(
        "planted.mp",
        "problem planted\nunknown a, t[3]\ndata u[3]: vec3, w[3]: vec3\n\
         for i in 0..3 {\n  t' * (u[i] + a * w[i]) = 0\n}\nt' * t = 1\neliminate t\n",
    );
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    use rand::Rng;
    let (mut data, mut truth, mut flipped, mut wrong) = (vec![], vec![], vec![], vec![]);
    for _ in 0..20 {
        let a: f64 = rng.gen_range(-1.0..1.0);
        let t: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let n = t.iter().map(|x| x * x).sum::<f64>().sqrt();
        let t = t.map(|x| x / n);
        let (mut us, mut ws) = (vec![], vec![]);
        for _ in 0..3 {
            let q: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let d: f64 = (0..3).map(|k| q[k] * t[k]).sum();
            let q: [f64; 3] = std::array::from_fn(|k| q[k] - d * t[k]);
            let w: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            us.extend((0..3).map(|k| q[k] - a * w[k]));
            ws.extend(w);
        }
        data.push([us, ws].concat());
        truth.push(vec![a, t[0], t[1], t[2]]);
        flipped.push(vec![a, -t[0], -t[1], -t[2]]);
        wrong.push(vec![a + 1e-3, t[0], t[1], t[2]]);
    }
    let data_file = scratch(
        "planted_data.txt",
        &format_instances(data.iter().map(Vec::as_slice)),
    );
    let run_with = |name: &str, solutions: &[Vec<f64>]| {
        let file = scratch(name, &format_instances(solutions.iter().map(Vec::as_slice)));
        mingen(&[
            "audit",
            problem.to_str().unwrap(),
            "--instances-from",
            data_file.to_str().unwrap(),
            "--solutions-from",
            file.to_str().unwrap(),
            "--json",
        ])
    };
    for (name, solutions, recovered) in [
        ("planted_truth.txt", &truth, 20),
        ("planted_flipped.txt", &flipped, 20),
        ("planted_wrong.txt", &wrong, 0),
    ] {
        let run = run_with(name, solutions);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let json: Value = serde_json::from_slice(&run.stdout).unwrap();
        assert_eq!(json["planted"]["instances"], 20, "{name}: {json}");
        assert_eq!(json["planted"]["recovered"], recovered, "{name}: {json}");
        if recovered == 20 {
            assert!(json["planted"]["median_log10_error"].as_f64().unwrap() < -10.0);
        }
    }
    let run = run_with("planted_short.txt", &truth[..19]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("19 solutions for the 20 instances"), "{err}");
    let narrow: Vec<Vec<f64>> = truth.iter().map(|s| s[..3].to_vec()).collect();
    let run = run_with("planted_narrow.txt", &narrow);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("line 1: 3 numbers, but the problem has 4 unknowns (a t1 t2 t3)"),
        "{err}"
    );
}
