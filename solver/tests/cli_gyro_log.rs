//! `rspose make-pair`, `estimate --r0 gyro`, `compare` and `calibrate` on gyro logs: a
//! well-formed recording makes a pair every command accepts, and each kind of bad log
//! (unsorted or duplicate times, NaN, a gap longer than the readout, samples not covering
//! a frame) exits 2 naming the file and the line, writing nothing.

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

/// A recording: calibration (600 rows, 30 ms readout), 400 Hz gyro log from t = 100 s to
/// 101 s (`gx,gy,gz,t`, one header line), frame times 30 fps, and matches of frames 5 and 6
/// (a simulated pair's pixels: only the files' handling is under test here).
struct Recording {
    dir: PathBuf,
}

impl Recording {
    fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("rspose-gyrolog-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("calibration.json"),
            r#"{"camera": {"fx": 600, "fy": 600, "cx": 400, "cy": 300, "width": 800, "height": 600, "readout": 5e-5},
                "camera_from_gyro": [[0, -1, 0], [-1, 0, 0], [0, 0, -1]], "time_offset": -0.001}"#,
        )
        .unwrap();
        let mut frames = String::new();
        for n in 0..30 {
            writeln!(frames, "{:.6}", 100.0 + n as f64 / 30.0).unwrap();
        }
        std::fs::write(dir.join("frames.txt"), frames).unwrap();
        // The matches are imaged through the recording's camera: pixels of another
        // camera's image would lie outside this one's and be refused.
        let camera = dir.join("camera.json");
        std::fs::write(
            &camera,
            r#"{"fx": 600, "fy": 600, "cx": 400, "cy": 300, "width": 800, "height": 600, "readout": 5e-5}"#,
        )
        .unwrap();
        let sim = dir.join("sim.json");
        let o = rspose(&[
            "simulate",
            "--seed",
            "1",
            "--camera",
            camera.to_str().unwrap(),
            "-o",
            sim.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&sim).unwrap()).unwrap();
        let matches = serde_json::json!({"frames": [5, 6], "matches": v["matches"]});
        std::fs::write(dir.join("matches.json"), matches.to_string()).unwrap();
        let r = Recording { dir };
        r.write_gyro(|_| {});
        r
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// Writes the gyro log after `edit` changes its lines (`lines[0]` is the header, so
    /// `lines[i]` is file line `i + 1`).
    fn write_gyro(&self, edit: impl FnOnce(&mut Vec<String>)) {
        let mut lines = vec!["gx,gy,gz,t".to_string()];
        for i in 0..400 {
            let t = 100.0 + i as f64 / 400.0;
            lines.push(format!("0.1,{:.4},-0.2,{t:.6}", 0.3 * (3.0 * t).sin()));
        }
        edit(&mut lines);
        std::fs::write(self.path("gyro.csv"), lines.join("\n") + "\n").unwrap();
    }

    fn make_pair(&self) -> Output {
        rspose(&[
            "make-pair",
            "--calibration",
            self.path("calibration.json").to_str().unwrap(),
            "--gyro",
            self.path("gyro.csv").to_str().unwrap(),
            "--frame-times",
            self.path("frames.txt").to_str().unwrap(),
            "--matches",
            self.path("matches.json").to_str().unwrap(),
            "-o",
            self.path("pair.json").to_str().unwrap(),
        ])
    }

    fn assert_rejected(&self, needle: &str) {
        let o = self.make_pair();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(needle), "expected '{needle}' in: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!self.path("pair.json").exists(), "no output on bad input");
    }
}

fn gyro_line(name: &str, line: usize) -> String {
    format!("{}:{line}:", Path::new(name).display())
}

#[test]
fn a_recording_makes_a_pair_every_command_accepts() {
    let r = Recording::new("ok");
    let o = r.make_pair();
    assert!(o.status.success(), "{}", stderr(&o));
    let pair = r.path("pair.json");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&pair).unwrap()).unwrap();
    let samples = v["gyro_log"]["samples"].as_array().unwrap();
    assert!(
        samples.len() > 20 && samples.len() < 100,
        "{}",
        samples.len()
    );
    // The mean rate in camera axes: ω_cam = M ω_gyro with M = [[0,-1,0],[-1,0,0],[0,0,-1]].
    let g = &v["gyro"][0];
    assert!((g[0].as_f64().unwrap() + 0.3 * (3.0f64 * 100.18).sin()).abs() < 0.05);
    assert!((g[1].as_f64().unwrap() + 0.1).abs() < 1e-9);
    assert!((g[2].as_f64().unwrap() - 0.2).abs() < 1e-9);
    for args in [
        vec![
            "estimate",
            pair.to_str().unwrap(),
            "--json",
            "--method",
            "rectified",
        ],
        vec![
            "estimate",
            pair.to_str().unwrap(),
            "--r0",
            "gyro",
            "--rows",
            "constant",
        ],
    ] {
        let o = rspose(&args);
        // Simulated pixels with an unrelated log: an answer or "no solution", never bad input.
        assert_ne!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    }
    let o = rspose(&["estimate", pair.to_str().unwrap(), "--json"]);
    if o.status.success() {
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(out.contains("gyro_rotation_difference_deg"), "{out}");
    }
}

#[test]
fn unsorted_times_name_the_line() {
    let r = Recording::new("unsorted");
    r.write_gyro(|l| l.swap(150, 151));
    r.assert_rejected(&gyro_line("gyro.csv", 152));
    r.assert_rejected("earlier than the previous");
}

#[test]
fn duplicate_times_name_the_line() {
    let r = Recording::new("duplicate");
    r.write_gyro(|l| l[201] = l[200].clone());
    r.assert_rejected(&gyro_line("gyro.csv", 202));
    r.assert_rejected("duplicate timestamp");
}

#[test]
fn nan_values_name_the_line() {
    let r = Recording::new("nan");
    r.write_gyro(|l| l[99] = "NaN,0,0,100.245".into());
    r.assert_rejected(&gyro_line("gyro.csv", 100));
    r.write_gyro(|l| l[99] = "0.1,zero,0,100.245".into());
    r.assert_rejected(&gyro_line("gyro.csv", 100));
}

#[test]
fn a_gap_too_long_to_interpolate_names_the_line_and_the_times() {
    let r = Recording::new("gap");
    // Frames 5 and 6 are read from 100.132 s to 100.192 s: remove 65 ms of samples there.
    r.write_gyro(|l| {
        l.drain(60..86);
    });
    r.assert_rejected(&gyro_line("gyro.csv", 61));
    r.assert_rejected("the rate is interpolated across gaps of at most 0.05 s");
}

#[test]
fn a_phone_rate_gap_is_interpolated() {
    let r = Recording::new("phone-gap");
    // 40 ms without samples (a 25 Hz stretch) inside frames 5 and 6: bridged.
    r.write_gyro(|l| {
        l.drain(60..76);
    });
    let o = r.make_pair();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(r.path("pair.json").exists());
}

#[test]
fn samples_not_covering_a_frame_are_rejected() {
    let r = Recording::new("cover");
    // Samples end at 100.145 s, inside frame 5's readout (100.132 s to 100.162 s).
    r.write_gyro(|l| l.truncate(60));
    r.assert_rejected("do not cover frame 5's readout");
    // Samples start at 100.15 s, after frame 5's row 0.
    r.write_gyro(|l| {
        l.drain(1..61);
    });
    r.assert_rejected("do not cover frame 5's readout");
}

#[test]
fn an_empty_match_list_is_refused_and_nothing_written() {
    let r = Recording::new("no-matches");
    std::fs::write(
        r.path("matches.json"),
        r#"{"frames": [5, 6], "matches": []}"#,
    )
    .unwrap();
    r.assert_rejected("`matches` is empty");
}

#[test]
fn matches_far_outside_the_image_are_refused_and_nothing_written() {
    let r = Recording::new("far-matches");
    std::fs::write(
        r.path("matches.json"),
        r#"{"frames": [5, 6], "matches": [[[1e300, 10], [20, 30]]]}"#,
    )
    .unwrap();
    r.assert_rejected("matches[0][0]");
}
