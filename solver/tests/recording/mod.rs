//! A recorded rig for the `make-pair` tests: calibration, gyro log, frame times and
//! matches in a scratch directory, and the command that turns them into a pair file.
// Each test crate uses the part it needs.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::{Command, Output};

pub fn rspose(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rspose"))
        .args(args)
        .output()
        .expect("run rspose")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A recording: calibration (600 rows, 30 ms readout), 400 Hz gyro log from t = 100 s to
/// 101 s (`gx,gy,gz,t`, one header line), frame times 30 fps, and matches of frames 5 and 6
/// (a simulated pair's pixels: only the files' handling is under test here).
pub struct Recording {
    dir: PathBuf,
}

impl Recording {
    pub fn new(name: &str) -> Self {
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

    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// Writes the gyro log after `edit` changes its lines (`lines[0]` is the header, so
    /// `lines[i]` is file line `i + 1`).
    pub fn write_gyro(&self, edit: impl FnOnce(&mut Vec<String>)) {
        let mut lines = vec!["gx,gy,gz,t".to_string()];
        for i in 0..400 {
            let t = 100.0 + i as f64 / 400.0;
            lines.push(format!("0.1,{:.4},-0.2,{t:.6}", 0.3 * (3.0 * t).sin()));
        }
        edit(&mut lines);
        std::fs::write(self.path("gyro.csv"), lines.join("\n") + "\n").unwrap();
    }

    pub fn make_pair(&self) -> Output {
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

    pub fn assert_rejected(&self, needle: &str) {
        let o = self.make_pair();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(needle), "expected '{needle}' in: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!self.path("pair.json").exists(), "no output on bad input");
    }
}
