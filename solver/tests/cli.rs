//! End-to-end tests of the `rspose` binary: every bad input exits 2 with one clear line on
//! stderr and leaves no output file behind.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rspose(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rspose"))
        .args(args)
        .output()
        .expect("run rspose")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rspose-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts exit code 2, a non-empty message mentioning `needle`, and no panic.
fn assert_bad_input(o: &Output, needle: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(err.contains(needle), "expected '{needle}' in: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

fn simulated_pair(dir: &Path) -> PathBuf {
    let p = dir.join("pair.json");
    let o = rspose(&["simulate", "--seed", "3", "-o", p.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    p
}

/// Rewrites a field of the simulated pair file.
fn edited_pair(dir: &Path, edit: impl FnOnce(&mut serde_json::Value)) -> PathBuf {
    let src = simulated_pair(dir);
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&src).unwrap()).unwrap();
    edit(&mut v);
    let p = dir.join("edited.json");
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    p
}

#[test]
fn estimate_missing_file() {
    let o = rspose(&["estimate", "/nonexistent/pair.json"]);
    assert_bad_input(&o, "/nonexistent/pair.json");
}

#[test]
fn estimate_malformed_json() {
    let d = scratch("malformed");
    let p = d.join("bad.json");
    std::fs::write(&p, "{ \"camera\": ").unwrap();
    assert_bad_input(&rspose(&["estimate", p.to_str().unwrap()]), "bad.json");
}

#[test]
fn estimate_missing_field() {
    let d = scratch("missing");
    let p = edited_pair(&d, |v| {
        v.as_object_mut().unwrap().remove("gyro");
    });
    assert_bad_input(&rspose(&["estimate", p.to_str().unwrap()]), "gyro");
}

#[test]
fn estimate_non_finite_pixel() {
    let d = scratch("nan");
    let p = d.join("nan.json");
    let src = std::fs::read_to_string(simulated_pair(&d)).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&src).unwrap();
    v["matches"][0][0][0] = serde_json::Value::String("NaN".into());
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    // serde names the place (line and column) of a value that is not a number.
    assert_bad_input(&rspose(&["estimate", p.to_str().unwrap()]), "column");
    let text = std::fs::read_to_string(&p)
        .unwrap()
        .replacen("\"NaN\"", "1e999", 1);
    std::fs::write(&p, text).unwrap();
    let o = rspose(&["estimate", p.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn estimate_too_few_matches() {
    let d = scratch("few");
    let p = edited_pair(&d, |v| {
        v["matches"].as_array_mut().unwrap().truncate(3);
        v.as_object_mut().unwrap().remove("ground_truth");
    });
    assert_bad_input(
        &rspose(&["estimate", p.to_str().unwrap(), "--method", "gsrp"]),
        "match",
    );
}

#[test]
fn estimate_non_positive_focal_length() {
    let d = scratch("focal");
    let p = edited_pair(&d, |v| v["camera"]["fx"] = serde_json::json!(-640.0));
    assert_bad_input(&rspose(&["estimate", p.to_str().unwrap()]), "fx");
}

#[test]
fn estimate_unknown_method() {
    let d = scratch("method");
    let p = simulated_pair(&d);
    assert_bad_input(
        &rspose(&["estimate", p.to_str().unwrap(), "--method", "eight-point"]),
        "eight-point",
    );
}

#[test]
fn experiment_unknown_sweep() {
    assert_bad_input(
        &rspose(&["experiment", "rotation", "--trials", "1"]),
        "rotation",
    );
}

#[test]
fn experiment_unwritable_output_directory() {
    let d = scratch("unwritable");
    let file = d.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let out = file.join("sub");
    assert_bad_input(
        &rspose(&[
            "experiment",
            "angular",
            "--trials",
            "1",
            "--out",
            out.to_str().unwrap(),
        ]),
        "a-file",
    );
}

#[test]
fn experiment_zero_trials() {
    assert_bad_input(
        &rspose(&["experiment", "angular", "--trials", "0"]),
        "--trials",
    );
}

#[test]
fn simulate_missing_output_directory_writes_nothing() {
    let d = scratch("simdir");
    let out = d.join("missing/pair.json");
    assert_bad_input(
        &rspose(&["simulate", "-o", out.to_str().unwrap()]),
        "missing",
    );
    assert!(!out.exists());
}

#[test]
fn simulate_invalid_option_writes_nothing() {
    let d = scratch("simopt");
    let out = d.join("pair.json");
    assert_bad_input(
        &rspose(&["simulate", "--outliers", "1.5", "-o", out.to_str().unwrap()]),
        "outlier",
    );
    assert!(!out.exists());
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        0,
        "no temporary file left behind"
    );
}

#[test]
fn unknown_flag_is_a_usage_error() {
    let o = rspose(&["demo", "--frobnicate"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn simulate_then_estimate_json_has_the_contract_keys() {
    let d = scratch("json");
    let p = simulated_pair(&d);
    let o = rspose(&[
        "estimate",
        p.to_str().unwrap(),
        "--method",
        "rectified",
        "--json",
    ]);
    if o.status.code() == Some(1) {
        return; // valid input without an answer is exit 1, checked elsewhere
    }
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for key in [
        "method",
        "rotation",
        "translation",
        "inliers",
        "iterations",
        "seconds",
        "rotation_error_deg",
        "translation_error_deg",
    ] {
        assert!(v.get(key).is_some(), "missing {key} in {v}");
    }
}

/// The CSV without the timing column (wall time varies from run to run).
fn csv_without_timing(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| {
            let mut cells: Vec<&str> = l.split(',').collect();
            cells.remove(8); // seconds_median
            cells.join(",")
        })
        .collect()
}

#[test]
fn experiment_writes_csv_and_svg_for_every_method_and_level_independent_of_threads() {
    let d = scratch("experiment");
    let (one, two) = (d.join("one"), d.join("two"));
    for (out, threads) in [(&one, "1"), (&two, "2")] {
        let o = rspose(&[
            "experiment",
            "angular",
            "--trials",
            "3",
            "--threads",
            threads,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(out.join("angular.svg").exists());
    }
    let rows = csv_without_timing(&one.join("angular.csv"));
    let methods = rspose::Method::ALL.map(|m| m.name());
    assert_eq!(
        rows.len(),
        1 + 5 * methods.len(),
        "header + 5 levels x every method"
    );
    for m in methods {
        assert_eq!(
            rows.iter()
                .filter(|r| r.split(',').nth(1) == Some(m))
                .count(),
            5,
            "{m}"
        );
    }
    assert_eq!(
        rows,
        csv_without_timing(&two.join("angular.csv")),
        "results depend on the thread count"
    );
}

#[test]
fn demo_prints_every_method() {
    let o = rspose(&["demo"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for m in rspose::Method::ALL.map(|m| m.name()) {
        assert!(
            out.lines().any(|l| l.starts_with(&format!("{m} "))),
            "{m} missing in {out}"
        );
    }
    assert!(!out.contains("failed"), "{out}");
}

#[test]
fn implausible_finite_values_are_bad_input_naming_the_field() {
    let d = scratch("implausible");
    for (field, edit) in [
        ("camera.fy", ["camera", "fy", "1e-300"]),
        ("camera.cx", ["camera", "cx", "1e308"]),
    ] {
        let p = edited_pair(&d, |v| {
            v[edit[0]][edit[1]] = serde_json::Value::from(edit[2].parse::<f64>().unwrap())
        });
        assert_bad_input(&rspose(&["estimate", p.to_str().unwrap()]), field);
    }
    let p = edited_pair(&d, |v| v["gyro"][0][0] = serde_json::Value::from(1.7e308));
    assert_bad_input(&rspose(&["estimate", p.to_str().unwrap()]), "gyro[0]");
}

#[test]
fn simulate_refuses_point_counts_above_the_cap() {
    let d = scratch("cap");
    let out = d.join("huge.json");
    let o = rspose(&[
        "simulate",
        "--points",
        "1000000000",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_bad_input(&o, "points");
    assert!(!out.exists());
}

#[test]
fn rectified_v_reports_its_velocities_and_what_it_did() {
    let d = scratch("rectified-v");
    let p = d.join("pair.json");
    let o = rspose(&[
        "simulate",
        "--linear",
        "20",
        "--seed",
        "5",
        "-o",
        p.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rspose(&[
        "estimate",
        p.to_str().unwrap(),
        "--method",
        "rectified+v",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["method"], "rectified+v");
    assert_eq!(v["velocity_fit"]["outcome"], "estimated", "{v}");
    assert_eq!(v["linear_velocity"].as_array().map(|a| a.len()), Some(2));
    assert!(v["translation_error_deg"].as_f64().unwrap() < 5.0, "{v}");
}

#[test]
fn bad_gravity_is_bad_input_naming_the_field() {
    let d = scratch("gravity");
    let cases = [
        (serde_json::json!([[0, 0, 0], [0, 1, 0]]), "gravity[0]"),
        (serde_json::json!([[0, 1, 0], [0, 0, 0]]), "gravity[1]"),
        (serde_json::json!([["NaN", 1, 0], [0, 1, 0]]), "gravity[0]"),
        (serde_json::json!([[0, 1, 0], [0, 1, null]]), "gravity[1]"),
        (serde_json::json!([[0, 1, 0]]), "gravity"),
        (serde_json::json!([[0, 1, 0], null]), "gravity[1]"),
        (serde_json::json!([[0, 1]]), "gravity"),
        (serde_json::json!("down"), "gravity"),
    ];
    for (value, needle) in cases {
        let p = edited_pair(&d, |v| v["gravity"] = value.clone());
        for method in ["grsrp-gravity", "rectified"] {
            let o = rspose(&["estimate", p.to_str().unwrap(), "--method", method]);
            assert_bad_input(&o, needle);
        }
    }
    // Without gravity the other methods run; grsrp-gravity names what it lacks.
    let p = edited_pair(&d, |v| {
        v.as_object_mut().unwrap().remove("gravity");
    });
    let o = rspose(&["estimate", p.to_str().unwrap(), "--method", "rectified"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rspose(&["estimate", p.to_str().unwrap(), "--method", "grsrp-gravity"]);
    assert_bad_input(&o, "gravity");
}

#[test]
fn simulate_writes_gravity_that_grsrp_gravity_uses() {
    let d = scratch("gravity-ok");
    let p = d.join("pair.json");
    let o = rspose(&[
        "simulate",
        "--gravity-noise",
        "0.5",
        "--outliers",
        "0.5",
        "--seed",
        "8",
        "-o",
        p.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
    assert_eq!(v["gravity"].as_array().map(|a| a.len()), Some(2));
    let o = rspose(&[
        "estimate",
        p.to_str().unwrap(),
        "--method",
        "grsrp-gravity",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["rotation_error_deg"].as_f64().unwrap() < 1.0, "{v}");
    assert!(v["translation_error_deg"].as_f64().unwrap() < 5.0, "{v}");
    let o = rspose(&["simulate", "--gravity-noise=-1", "-o", p.to_str().unwrap()]);
    assert_bad_input(&o, "gravity_noise_deg");
}

#[test]
fn compare_runs_every_method_the_pairs_support() {
    let d = scratch("compare");
    let names = |o: &Output| -> Vec<String> {
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["methods"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| m["method"].as_str().unwrap().to_string())
            .collect()
    };
    let p = simulated_pair(&d);
    let o = rspose(&["compare", p.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let all: Vec<String> = rspose::Method::ALL
        .iter()
        .map(|m| m.name().to_string())
        .collect();
    assert_eq!(names(&o), all);
    let p = edited_pair(&d, |v| {
        v.as_object_mut().unwrap().remove("gravity");
    });
    let o = rspose(&["compare", p.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("grsrp-gravity left out"),
        "{}",
        stderr(&o)
    );
    assert_eq!(names(&o), all[..all.len() - 1]);
    // The readout-refined `rectified` comes last, and its rotation is a real estimate.
    let o = rspose(&["compare", p.to_str().unwrap(), "--json", "--refine-readout"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let got = names(&o);
    assert_eq!(got.last().map(String::as_str), Some("rectified+k"));
    assert_eq!(got[..got.len() - 1], all[..all.len() - 1]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let last = v["methods"].as_array().unwrap().last().unwrap().clone();
    assert_eq!(last["failures"], 0, "{last}");
    assert!(last["rot_median"].as_f64().unwrap() < 1.0, "{last}");
}

#[test]
fn the_default_preset_reports_the_fitted_gyro_noise_and_the_paper_preset_does_not() {
    let d = scratch("noise-fit");
    let p = d.join("pair.json");
    let o = rspose(&[
        "simulate",
        "--gyro-noise",
        "0.5",
        "--seed",
        "3",
        "-o",
        p.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let run = |extra: &[&str]| {
        let mut args = vec![
            "estimate",
            p.to_str().unwrap(),
            "--method",
            "rectified",
            "--json",
        ];
        args.extend_from_slice(extra);
        let o = rspose(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()
    };
    let v = run(&[]);
    let fitted = v["noise_fit"]["gyro_noise"].as_f64().unwrap();
    assert!(fitted.is_finite() && fitted > 0.0, "{v}");
    let v = run(&["--preset", "paper"]);
    assert!(v.get("noise_fit").is_none(), "{v}");
}

/// `simulate --camera` images the scene through a fisheye read right to left; `estimate`
/// reads the camera back from the pair file; a pixel outside the fisheye's invertible
/// region, a wrong parameter count and both `camera` and `cameras` are bad input.
#[test]
fn fisheye_cameras_simulate_estimate_and_refuse_bad_pixels() {
    let d = scratch("fisheye");
    let cam = d.join("camera.json");
    std::fs::write(
        &cam,
        r#"{"model": "OPENCV_FISHEYE", "width": 1920, "height": 1080,
            "params": [600, 600, 960, 540, 0.05, -0.01, 0.002, -0.0005],
            "readout": 3.4e-5, "readout_direction": "right_to_left"}"#,
    )
    .unwrap();
    let p = d.join("pair.json");
    let o = rspose(&[
        "simulate",
        "--camera",
        cam.to_str().unwrap(),
        "--pixel-noise",
        "0",
        "--gyro-noise",
        "0",
        "-o",
        p.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.contains("OPENCV_FISHEYE") && text.contains("right_to_left"));
    let o = rspose(&["estimate", p.to_str().unwrap(), "--method", "rectified"]);
    assert!(o.status.success(), "{}", stderr(&o));

    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    // The image corner (1100 px from the centre) lies beyond the fisheye's horizon:
    // θ_d(π/2) = 1.69, 1012 px at f = 600.
    v["matches"][4][1] = serde_json::json!([1919.0, 1079.0]);
    let bad = d.join("corner.json");
    std::fs::write(&bad, v.to_string()).unwrap();
    let o = rspose(&["estimate", bad.to_str().unwrap()]);
    assert_bad_input(&o, "match 4: image 2's pixel has no bearing");
    assert_eq!(stderr(&o).trim().lines().count(), 1, "{}", stderr(&o));

    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["camera"]["params"].as_array_mut().unwrap().pop();
    let bad = d.join("params.json");
    std::fs::write(&bad, v.to_string()).unwrap();
    assert_bad_input(
        &rspose(&["estimate", bad.to_str().unwrap()]),
        "OPENCV_FISHEYE takes 8 params",
    );

    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["cameras"] = serde_json::json!([v["camera"], v["camera"]]);
    let bad = d.join("both.json");
    std::fs::write(&bad, v.to_string()).unwrap();
    assert_bad_input(&rspose(&["estimate", bad.to_str().unwrap()]), "not both");
    let _ = std::fs::remove_dir_all(&d);
}

/// Asserts exit 2 with exactly one line on stderr naming `needle`, at most 300 characters.
fn assert_one_line_refusal(o: &Output, needle: &str) {
    assert_bad_input(o, needle);
    let err = stderr(o);
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.len() < 300, "{err}");
}

#[test]
fn pixels_far_outside_the_image_are_refused_naming_the_match() {
    let d = scratch("outside");
    let p = edited_pair(&d, |v| v["matches"][4][0][0] = serde_json::json!(-1e6));
    let o = rspose(&["estimate", p.to_str().unwrap()]);
    assert_one_line_refusal(&o, "matches[4][0]");
}

#[test]
fn a_sub_pixel_image_size_is_refused_in_one_short_line() {
    let d = scratch("tiny-width");
    let p = edited_pair(&d, |v| v["camera"]["width"] = serde_json::json!(1e-320));
    let o = rspose(&["estimate", p.to_str().unwrap()]);
    assert_one_line_refusal(&o, "camera.width/height");
}

#[test]
fn a_principal_point_far_outside_the_image_is_refused() {
    let d = scratch("far-cx");
    let p = edited_pair(&d, |v| v["camera"]["cx"] = serde_json::json!(1e6));
    let o = rspose(&["estimate", p.to_str().unwrap()]);
    assert_one_line_refusal(&o, "camera.cx");
}

/// The quality flags `rspose estimate --json` reports for the simulated pair with its
/// matches replaced by `matches`.
fn flags_with_matches(name: &str, method: &str, matches: serde_json::Value) -> Vec<String> {
    let d = scratch(name);
    let p = edited_pair(&d, |v| {
        v["matches"] = matches;
        v.as_object_mut().unwrap().remove("ground_truth");
    });
    let o = rspose(&[
        "estimate",
        p.to_str().unwrap(),
        "--method",
        method,
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let flags = v["flags"].as_array().expect("flags");
    flags
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect()
}

#[test]
fn random_matches_raise_low_inlier_ratio_or_gyro_noise_runaway() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let matches: Vec<_> = (0..500)
        .map(|_| {
            let mut p = || [rng.gen_range(0.0..1920.0), rng.gen_range(0.0..1080.0)];
            [p(), p()]
        })
        .collect();
    for method in ["grsrp+", "rectified", "gsrp"] {
        let flags = flags_with_matches("random", method, serde_json::json!(matches));
        // Few chance inliers, or many because the gyro-noise fit ran away to accept them.
        let warned = ["low_inlier_ratio", "gyro_noise_runaway"]
            .iter()
            .any(|f| flags.contains(&f.to_string()));
        assert!(warned, "{method}: {flags:?}");
    }
}

#[test]
fn collinear_matches_raise_collinear() {
    let matches: Vec<_> = (0..300)
        .map(|i| {
            let i = i as f64;
            [
                [10.0 + 3.0 * i, 20.0 + 2.0 * i],
                [15.0 + 3.0 * i, 22.0 + 2.0 * i],
            ]
        })
        .collect();
    for method in ["grsrp+", "rectified"] {
        let flags = flags_with_matches("collinear", method, serde_json::json!(matches));
        assert!(flags.contains(&"collinear".into()), "{method}: {flags:?}");
    }
}

#[test]
fn usage_errors_are_one_line() {
    for args in [
        &["estimate"][..],
        &["estimate", "x.json", "--bogus"],
        &["frobnicate"],
    ] {
        let o = rspose(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("rspose: "), "{err}");
    }
    let help = rspose(&["--help"]);
    assert_eq!(help.status.code(), Some(0));
}

#[test]
fn compare_names_the_file_of_an_invalid_field() {
    let d = scratch("compare-field");
    let p = edited_pair(&d, |v| v["matches"][0][1][1] = serde_json::json!(-1e7));
    let o = rspose(&["compare", p.to_str().unwrap()]);
    assert_one_line_refusal(
        &o,
        &format!("{}: invalid field `matches[0][1]`", p.display()),
    );
}

#[test]
fn compare_exits_1_when_no_method_estimates_any_pair() {
    let d = scratch("compare-none");
    // Three matches: too few for every method but `grsrp-gravity`, whose one minimal
    // sample of random matches has no solution.
    let p = edited_pair(&d, |v| {
        v["matches"] = serde_json::json!([
            [[100, 200], [300, 40]],
            [[1500, 200], [1300, 40]],
            [[800, 900], [700, 1000]]
        ]);
        v["ground_truth"]["inliers"] = serde_json::json!([true, true, true]);
    });
    let o = rspose(&["compare", p.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("no method estimated any"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn calibrate_refuses_a_grid_too_large_to_search() {
    let pair = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/cc9pro/pair-100-101.json"
    );
    let o = rspose(&[
        "calibrate",
        pair,
        "--readout-ms",
        "0:40:0.01",
        "--offset-ms",
        "-15:15:0.01",
    ]);
    assert_one_line_refusal(&o, "too large");
}

#[test]
fn compare_refuses_a_pair_every_method_refuses() {
    let d = scratch("compare-identical");
    let p = edited_pair(&d, |v| {
        let first = v["matches"][0].clone();
        v["matches"] = serde_json::json!(vec![first; 50]);
        v["ground_truth"]["inliers"] = serde_json::json!(vec![true; 50]);
    });
    let o = rspose(&["compare", p.to_str().unwrap()]);
    assert_one_line_refusal(&o, &format!("{}: degenerate input", p.display()));
}

#[test]
fn compare_counts_the_flagged_estimates_of_random_matches() {
    let d = scratch("compare-random");
    // The second image's points rotated by a third of the list: every match is wrong.
    let p = edited_pair(&d, |v| {
        let m = v["matches"].as_array().unwrap().clone();
        let n = m.len();
        let shuffled: Vec<serde_json::Value> = (0..n)
            .map(|i| serde_json::json!([m[i][0], m[(i + n / 3) % n][1]]))
            .collect();
        v["matches"] = serde_json::json!(shuffled);
        v["ground_truth"]["inliers"] = serde_json::json!(vec![false; n]);
    });
    let o = rspose(&["compare", p.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = v["methods"].as_array().unwrap();
    let mut estimated = 0;
    for r in rows {
        let done = r["pairs"].as_u64().unwrap() - r["failures"].as_u64().unwrap();
        estimated += done;
        assert_eq!(r["flagged"].as_u64().unwrap(), done, "{r}");
        assert!(
            !r["flags"].as_object().unwrap().is_empty() || done == 0,
            "{r}"
        );
    }
    assert!(estimated > 0, "{v}");
    let table = rspose(&["compare", p.to_str().unwrap()]);
    assert!(
        String::from_utf8_lossy(&table.stdout).contains("| flagged |"),
        "{}",
        String::from_utf8_lossy(&table.stdout)
    );
}
