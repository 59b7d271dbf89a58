//! `rspose make-pair` with a Kalibr or OpenCV calibration instead of the JSON one, a known
//! gyro bias in the JSON calibration, and `estimate`/`compare --refine-gyro-bias`: the
//! imported values reach the pair file, and bad input exits 2 with one line naming the file
//! and the key, writing nothing.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rspose(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rspose"))
        .args(args)
        .output()
        .expect("run rspose")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/calibration")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// A recording: a 400 Hz gyro log from t = 100 s to 101 s, frame times at 30 fps, and 20
/// matches of frames 5 and 6 inside a 512 x 480 image (only the files' handling is under
/// test).
struct Recording {
    dir: PathBuf,
}

impl Recording {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("rspose-import-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut frames = String::new();
        for n in 0..30 {
            writeln!(frames, "{:.6}", 100.0 + n as f64 / 30.0).unwrap();
        }
        std::fs::write(dir.join("frames.txt"), frames).unwrap();
        let mut gyro = String::from("gx,gy,gz,t\n");
        for i in 0..400 {
            let t = 100.0 + i as f64 / 400.0;
            writeln!(gyro, "0.1,{:.4},-0.2,{t:.6}", 0.3 * (3.0 * t).sin()).unwrap();
        }
        std::fs::write(dir.join("gyro.csv"), gyro).unwrap();
        let matches: Vec<[[f64; 2]; 2]> = (0..20)
            .map(|i| {
                let (u, v) = (150.0 + 10.0 * i as f64, 100.0 + 13.0 * i as f64);
                [[u, v], [u + 3.0, v - 2.0]]
            })
            .collect();
        let m = serde_json::json!({"frames": [5, 6], "matches": matches});
        std::fs::write(dir.join("matches.json"), m.to_string()).unwrap();
        Recording { dir }
    }

    fn path(&self, name: &str) -> String {
        self.dir.join(name).to_string_lossy().into_owned()
    }

    /// `make-pair` with the recording's files, `calibration` (flags) and output `out.json`.
    fn make_pair(&self, calibration: &[&str]) -> Output {
        let (gyro, frames, matches, out) = (
            self.path("gyro.csv"),
            self.path("frames.txt"),
            self.path("matches.json"),
            self.path("out.json"),
        );
        let mut args = vec!["make-pair"];
        args.extend_from_slice(calibration);
        args.extend_from_slice(&[
            "--gyro",
            &gyro,
            "--frame-times",
            &frames,
            "--matches",
            &matches,
            "-o",
            &out,
        ]);
        rspose(&args)
    }

    fn output(&self) -> Option<serde_json::Value> {
        let text = std::fs::read_to_string(self.path("out.json")).ok()?;
        Some(serde_json::from_str(&text).unwrap())
    }
}

/// Exit 2, one stderr line naming every one of `names`, no output file.
fn refused(r: &Recording, o: &Output, names: &[&str]) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    for n in names {
        assert!(e.contains(n), "`{n}` not in: {e}");
    }
    assert!(r.output().is_none(), "an output was written");
}

#[test]
fn make_pair_imports_a_kalibr_camchain() {
    let r = Recording::new("kalibr");
    let camchain = fixture("camchain-imucam.yaml");
    let o = r.make_pair(&["--kalibr", &camchain]);
    assert!(o.status.success(), "{}", stderr(&o));
    let p = r.output().unwrap();
    assert_eq!(p["camera"]["model"], "OPENCV");
    assert_eq!(
        p["camera"]["params"],
        serde_json::json!([
            458.654,
            457.296,
            367.215,
            248.375,
            -0.28340811,
            0.07395907,
            0.00019359,
            1.76187114e-05
        ])
    );
    assert_eq!(p["camera"]["readout"], 3.1e-5);
    assert_eq!(p["gyro_log"]["time_offset"], 0.00481);
    assert_eq!(p["gyro_log"]["camera_from_gyro"][1][0], 0.999557249008);

    // cam1 has no line_delay: refused unless --readout gives it.
    std::fs::remove_file(r.path("out.json")).unwrap();
    let o = r.make_pair(&["--kalibr", &camchain, "--cam", "cam1"]);
    refused(
        &r,
        &o,
        &["camchain-imucam.yaml", "`cam1.line_delay`", "--readout"],
    );
    let o = r.make_pair(&["--kalibr", &camchain, "--cam", "cam1", "--readout", "2e-5"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let p = r.output().unwrap();
    assert_eq!(p["camera"]["model"], "OPENCV_FISHEYE");
    assert_eq!(p["gyro_log"]["time_offset"], -0.0021);
    std::fs::remove_file(r.path("out.json")).unwrap();

    // A broken file names the file and the key, or the YAML line.
    let text = std::fs::read_to_string(&camchain).unwrap();
    let bad = r.path("bad.yaml");
    std::fs::write(
        &bad,
        text.replace("intrinsics: [458.654, 457.296,", "intrinsics: [458.654,"),
    )
    .unwrap();
    refused(
        &r,
        &r.make_pair(&["--kalibr", &bad]),
        &["bad.yaml", "`cam0.intrinsics`"],
    );
    std::fs::write(
        &bad,
        text.replace("resolution: [752, 480]", "resolution: [752, 480"),
    )
    .unwrap();
    refused(&r, &r.make_pair(&["--kalibr", &bad]), &["bad.yaml", "line"]);
    refused(
        &r,
        &r.make_pair(&["--kalibr", &camchain, "--cam", "cam7"]),
        &["`cam7`", "cam0, cam1"],
    );
}

#[test]
fn make_pair_imports_an_opencv_calibration() {
    let r = Recording::new("opencv");
    let file = fixture("opencv_camera.yaml");
    refused(
        &r,
        &r.make_pair(&["--opencv-calibration", &file]),
        &["opencv_camera.yaml", "--readout"],
    );
    let o = r.make_pair(&["--opencv-calibration", &file, "--readout", "3e-5"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let p = r.output().unwrap();
    // Five coefficients with k3 ≠ 0: FULL_OPENCV, k4..k6 = 0.
    assert_eq!(p["camera"]["model"], "FULL_OPENCV");
    assert_eq!(p["camera"]["params"][8], 0.13158845901489258);
    assert_eq!(p["camera"]["params"][11], 0.0);
    assert_eq!(p["camera"]["width"], 1920.0);
    assert_eq!(p["gyro_log"]["time_offset"], 0.0);
    std::fs::remove_file(r.path("out.json")).unwrap();
    let bad = r.path("bad.yaml");
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::write(&bad, text.replace("camera_matrix", "camera_matrx")).unwrap();
    refused(
        &r,
        &r.make_pair(&["--opencv-calibration", &bad, "--readout", "3e-5"]),
        &["bad.yaml", "`camera_matrix`"],
    );
}

#[test]
fn make_pair_takes_exactly_one_calibration_and_a_known_bias() {
    let r = Recording::new("sources");
    let camchain = fixture("camchain-imucam.yaml");
    let opencv = fixture("opencv_camera.yaml");
    refused(&r, &r.make_pair(&[]), &["exactly one"]);
    refused(
        &r,
        &r.make_pair(&["--kalibr", &camchain, "--opencv-calibration", &opencv]),
        &["exactly one"],
    );
    let calib = r.path("calibration.json");
    std::fs::write(
        &calib,
        r#"{"camera": {"fx": 600, "fy": 600, "cx": 256, "cy": 240, "width": 512, "height": 480, "readout": 5e-5},
            "camera_from_gyro": [[0, -1, 0], [-1, 0, 0], [0, 0, -1]], "gyro_bias": [0.01, 0.02, -0.03]}"#,
    )
    .unwrap();
    refused(
        &r,
        &r.make_pair(&["--calibration", &calib, "--readout", "1e-5"]),
        &["--readout"],
    );
    let o = r.make_pair(&["--calibration", &calib]);
    assert!(o.status.success(), "{}", stderr(&o));
    let p = r.output().unwrap();
    assert_eq!(
        p["gyro_log"]["gyro_bias"],
        serde_json::json!([0.01, 0.02, -0.03])
    );
    // The mean rates written beside the log have the bias removed: M (0.1 − 0.01, ·, −0.2 + 0.03).
    let z = p["gyro"][0][2].as_f64().unwrap();
    assert!((z - 0.17).abs() < 1e-9, "{z}");
    std::fs::remove_file(r.path("out.json")).unwrap();
    std::fs::write(
        &calib,
        std::fs::read_to_string(&calib)
            .unwrap()
            .replace("-0.03", "1e999"),
    )
    .unwrap();
    refused(
        &r,
        &r.make_pair(&["--calibration", &calib]),
        &["calibration.json"],
    );
}

#[test]
fn estimate_and_compare_refine_the_gyro_bias() {
    let r = Recording::new("estimate");
    let pair = r.path("pair.json");
    let o = rspose(&["simulate", "--seed", "3", "--gyro-noise", "0", "-o", &pair]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rspose(&[
        "estimate",
        &pair,
        "--method",
        "rectified",
        "--refine-gyro-bias",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let b = v["gyro_bias"].as_array().unwrap();
    assert_eq!(b.len(), 3);
    assert!(b.iter().all(|x| x.as_f64().unwrap().abs() <= 0.5));
    let s = v["gyro_bias_std"].as_array().unwrap();
    assert_eq!(s.len(), 3);
    assert!(s.iter().all(|x| x.as_f64().unwrap() > 0.0));
    let o = rspose(&["estimate", &pair, "--method", "rectified", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v.get("gyro_bias").is_none());
    let o = rspose(&["estimate", &pair, "--method", "gsrp", "--refine-gyro-bias"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("gyro_bias"), "{}", stderr(&o));
    let o = rspose(&["compare", &pair, "--refine-gyro-bias"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("rectified+b"));
}
