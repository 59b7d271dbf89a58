//! `positive` declarations: parsed with clear errors, shown by `inspect`, and applied by
//! the audit as the emitted solvers apply them. On geometric P3P instances (points in
//! front of the camera) the 8 solutions of the distance equations come in pairs `±d`;
//! `positive d` keeps at most half of them, never one with a depth that is not positive,
//! and still recovers the planted depths.

use mingen::Problem;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;
use std::process::Command;

fn parse(src: &str) -> Result<Problem, String> {
    Problem::parse(src, "t.mp").map_err(|e| e.to_string())
}

#[test]
fn positive_names_unknowns_once() {
    let base = "problem t\nunknown x, d[2]\ndata a: scalar\nx*x = a\nd[0] = x\nd[1] = a*x\n";
    let p = parse(&format!("{base}positive d, x\n")).unwrap();
    assert_eq!(p.layout.positive, [1, 2, 0]);
    let err = parse(&format!("{base}positive a\n")).unwrap_err();
    assert!(err.contains("'a' is data"), "{err}");
    let err = parse(&format!("{base}positive y\n")).unwrap_err();
    assert!(err.contains("undeclared unknown 'y'"), "{err}");
    let err = parse(&format!("{base}positive x\npositive x\n")).unwrap_err();
    assert!(err.contains("already declared positive"), "{err}");
    let err = parse("problem t\nunknown positive\npositive = 1\n").unwrap_err();
    assert!(err.contains("positive"), "{err}");
}

#[test]
fn positive_depths_of_p3p_keep_the_planted_solution() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let problem = root.join("templates/classic/p3p.mp");
    let dir = std::env::temp_dir().join(format!("mingen-positive-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (mut data, mut truth) = (String::new(), String::new());
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..200 {
        // Three points in front of the camera: normalised image points and depths.
        let pts: Vec<[f64; 3]> = (0..3)
            .map(|_| {
                let z = rng.gen_range(2.0..8.0);
                [
                    rng.gen_range(-0.6..0.6) * z,
                    rng.gen_range(-0.6..0.6) * z,
                    z,
                ]
            })
            .collect();
        let dist =
            |i: usize, j: usize| -> f64 { (0..3).map(|k| (pts[i][k] - pts[j][k]).powi(2)).sum() };
        for p in &pts {
            data.push_str(&format!("{:e} {:e} ", p[0] / p[2], p[1] / p[2]));
        }
        data.push_str(&format!(
            "{:e} {:e} {:e}\n",
            dist(0, 1),
            dist(0, 2),
            dist(1, 2)
        ));
        truth.push_str(&format!(
            "{:e} {:e} {:e}\n",
            pts[0][2], pts[1][2], pts[2][2]
        ));
    }
    let (di, si) = (dir.join("instances.txt"), dir.join("solutions.txt"));
    std::fs::write(&di, data).unwrap();
    std::fs::write(&si, truth).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_mingen"))
        .args([
            "audit",
            problem.to_str().unwrap(),
            "--json",
            "--instances-from",
        ])
        .arg(&di)
        .arg("--solutions-from")
        .arg(&si)
        .output()
        .expect("mingen runs");
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let real = report["mean_real_solutions"].as_f64().unwrap();
    let kept = report["mean_kept_solutions"]
        .as_f64()
        .expect("p3p declares positive d");
    assert!(real >= 2.0, "{report}");
    assert!(
        kept >= 1.0 && kept <= real / 2.0 + 1e-12,
        "real {real}, kept {kept}"
    );
    let planted = &report["planted"];
    assert_eq!(planted["instances"], 200);
    assert!(planted["recovered"].as_u64().unwrap() >= 198, "{planted}");
}

#[test]
fn inspect_lists_positive_unknowns() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let problem = root.join("templates/classic/p3p.mp");
    let run = Command::new(env!("CARGO_BIN_EXE_mingen"))
        .args(["inspect", problem.to_str().unwrap()])
        .output()
        .expect("mingen runs");
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("positive: d1 d2 d3"), "{text}");
}
