//! `rspose make-pair`, `estimate --r0 gyro`, `compare` and `calibrate` on gyro logs: a
//! well-formed recording makes a pair every command accepts, and each kind of bad log
//! (unsorted or duplicate times, NaN, a gap longer than the readout, samples not covering
//! a frame) exits 2 naming the file and the line, writing nothing.

mod recording;

use recording::{rspose, stderr, Recording};
use std::path::Path;

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
