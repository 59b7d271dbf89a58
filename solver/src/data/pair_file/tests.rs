use super::*;
use crate::model::camera_model::CameraModel;

fn sample() -> PairFile {
    PairFile {
        cameras: [Camera::paper(); 2],
        gyro: Some([[0.1, 0.2, 0.3], [0.0, -1.0, 0.5]]),
        gyro_bias: None,
        gyro_log: None,
        gravity: Some([[0.0, 9.8, 0.1], [0.2, 9.7, -0.3]]),
        matches: vec![[[1.0, 2.0], [3.0, 4.0]], [[5.0, 6.0], [7.0, 8.0]]],
        ground_truth: Some(GroundTruth {
            rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            translation: [0.0, 0.0, 1.0],
            omega: [[0.0; 3]; 2],
            velocity: [[0.0; 3]; 2],
            inliers: vec![true, false],
        }),
    }
}

#[test]
fn roundtrip_and_atomic_save() {
    let dir = std::env::temp_dir().join(format!("rspose-pairfile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("pair.json");
    let p = sample();
    p.save_atomic(&path).unwrap();
    assert_eq!(PairFile::load(&path).unwrap(), p);
    let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(leftovers.len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn unknown_keys_are_refused_with_their_name() {
    // A misspelt key would otherwise silently take its default (identity, zero).
    let p = Path::new("x.json");
    let good = sample().to_json_string();
    assert!(PairFile::from_json_str(&good, p).is_ok());
    for (from, to) in [
        ("\"gravity\"", "\"gravty\""),
        ("\"fx\"", "\"focal\""),
        ("\"inliers\"", "\"inlier\""),
    ] {
        let text = good.replacen(from, to, 1);
        let e = PairFile::from_json_str(&text, p).unwrap_err().to_string();
        let key = to.trim_matches('"');
        assert!(e.contains(&format!("unknown field `{key}`")), "{e}");
    }
    let mut with_log = sample();
    with_log.gyro_log = Some(GyroLogSpec {
        camera_from_gyro: identity_rows(),
        time_offset: 0.0,
        frame_times: [0.0, 0.1],
        samples: vec![[0.0, 0.0, 0.0, 0.0], [0.2, 0.0, 0.0, 0.0]],
        gyro_bias: None,
    });
    let text = with_log
        .to_json_string()
        .replacen("camera_from_gyro", "camera_from_gyr", 1);
    let e = PairFile::from_json_str(&text, p).unwrap_err().to_string();
    assert!(e.contains("unknown field `camera_from_gyr`"), "{e}");
}

#[test]
fn errors_name_the_field() {
    let p = Path::new("x.json");
    let mut bad = sample();
    bad.cameras = [Camera {
        fx: -1.0,
        ..Camera::paper()
    }; 2];
    let err = PairFile::from_json_str(&bad.to_json_string(), p).unwrap_err();
    assert!(matches!(&err, PairFileError::InvalidField { field, .. } if field == "camera.fx"));
    let mut bad = sample();
    bad.ground_truth.as_mut().unwrap().inliers.pop();
    let err = bad.validate().unwrap_err();
    assert!(err.to_string().contains("ground_truth.inliers"));
    let mut bad = sample();
    bad.matches[1][0][1] = f64::NAN;
    assert!(bad
        .validate()
        .unwrap_err()
        .to_string()
        .contains("matches[1]"));
    // NaN serialises as null, which fails to parse with a field-naming message.
    let err = PairFile::from_json_str(&bad.to_json_string(), p).unwrap_err();
    assert!(matches!(err, PairFileError::Parse { .. }));
    let err = PairFile::from_json_str(r#"{"camera": {"fx": 1}}"#, p).unwrap_err();
    assert!(err.to_string().contains("missing field"), "{err}");
    let err = PairFile::load("/nonexistent/dir/pair.json").unwrap_err();
    assert!(matches!(err, PairFileError::Io { .. }));
    assert!(PairFile::from_json_str(&sample().to_json_string(), p).is_ok());

    // Gravity: both views or neither, each finite with a non-zero length.
    let mut bad = sample();
    bad.gravity = Some([[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let err = bad.validate().unwrap_err().to_string();
    assert!(err.contains("`gravity[0]`"), "{err}");
    bad.gravity = Some([[0.0, 1.0, 0.0], [f64::NAN, 1.0, 0.0]]);
    let err = bad.validate().unwrap_err().to_string();
    assert!(err.contains("`gravity[1]`"), "{err}");
    let text = sample().to_json_string().replacen(
        "\"gravity\": [",
        "\"gravity\": [[0, 1, 0]], \"unused\": [",
        1,
    );
    let err = PairFile::from_json_str(&text, p).unwrap_err().to_string();
    assert!(err.contains("field `gravity`"), "{err}");
    let (v1, v2) = sample().views().unwrap();
    assert_eq!(v1.gravity, Some(Vector3::new(0.0, 9.8, 0.1)));
    assert_eq!(v2.gravity, Some(Vector3::new(0.2, 9.7, -0.3)));

    // A gyro log's bad sample is named by its index; coverage is checked per frame.
    let mut with_log = sample();
    with_log.gyro = None;
    with_log.gyro_log = Some(GyroLogSpec {
        camera_from_gyro: identity_rows(),
        time_offset: 0.0,
        frame_times: [0.0, 0.1],
        samples: (0..100)
            .map(|i| [i as f64 * 0.002, 0.1, 0.2, 0.3])
            .collect(),
        gyro_bias: None,
    });
    assert!(with_log.validate().is_ok());
    assert!(with_log.gyro_relative_rotation().is_some());
    let mut bad = with_log.clone();
    bad.gyro_log.as_mut().unwrap().samples.swap(10, 11);
    let err = bad.validate().unwrap_err().to_string();
    assert!(err.contains("gyro_log.samples[11]"), "{err}");
    let mut bad = with_log.clone();
    bad.gyro_log.as_mut().unwrap().frame_times[1] = 0.19;
    let err = bad.validate().unwrap_err().to_string();
    assert!(err.contains("image 2's readout"), "{err}");
    let mut bad = with_log;
    bad.gyro_log = None;
    let err = bad.validate().unwrap_err().to_string();
    assert!(err.contains("gyro"), "{err}");
}

#[test]
fn cameras_old_form_model_form_and_one_per_view() {
    let p = Path::new("x.json");
    let good = sample().to_json_string();
    // One camera for both, written in the pinhole short form as before.
    assert!(good.contains("\"camera\": {\n    \"fx\": 640.0"), "{good}");
    let opencv = r#"{"model": "OPENCV", "width": 1920, "height": 1080,
        "params": [640, 640, 960, 540, -0.1, 0.01, 0.0, 0.0], "readout": 6e-5}"#;
    let fisheye = r#"{"model": "OPENCV_FISHEYE", "width": 1920, "height": 1080,
        "params": [600, 600, 960, 540, 0.0, 0.0, 0.0, 0.0], "readout": 3e-5,
        "readout_direction": "left_to_right"}"#;
    let (head, rest) = good.split_once("\"gyro\"").unwrap();
    assert!(head.contains("\"camera\""));
    let with = |cameras: &str| format!("{{{cameras}, \"gyro\"{rest}");
    let one = PairFile::from_json_str(&with(&format!("\"camera\": {opencv}")), p).unwrap();
    assert_eq!(one.cameras[0], one.cameras[1]);
    assert_eq!(one.cameras[0].model, CameraModel::OpenCv);
    let two =
        PairFile::from_json_str(&with(&format!("\"cameras\": [{opencv}, {fisheye}]")), p).unwrap();
    assert_eq!(two.cameras[1].model, CameraModel::OpenCvFisheye);
    let (v1, v2) = two.views().unwrap();
    assert_eq!((v1.camera, v2.camera), (two.cameras[0], two.cameras[1]));
    // Written back with `cameras`, and read again the same.
    let text = two.to_json_string();
    assert!(text.contains("\"cameras\"") && !text.contains("\"camera\""));
    assert_eq!(
        PairFile::from_json_str(&text, p).unwrap().cameras,
        two.cameras
    );
    // Both keys or neither: refused, naming them.
    let both = with(&format!(
        "\"camera\": {opencv}, \"cameras\": [{opencv}, {opencv}]"
    ));
    let e = PairFile::from_json_str(&both, p).unwrap_err().to_string();
    assert!(e.contains("`camera`") && e.contains("not both"), "{e}");
    let neither = format!("{{\"gyro\"{rest}");
    let e = PairFile::from_json_str(&neither, p)
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing field `camera`"), "{e}");
    let e = PairFile::from_json_str(&with(&format!("\"cameras\": [{opencv}]")), p)
        .unwrap_err()
        .to_string();
    assert!(e.contains("`cameras` needs one camera for each"), "{e}");
    // A bad model or parameter count names the model; a bad value names its field.
    let e = PairFile::from_json_str(
        &with(&format!(
            "\"camera\": {}",
            opencv.replace(", 0.0, 0.0]", "]")
        )),
        p,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("OPENCV takes 8 params"), "{e}");
    let e = PairFile::from_json_str(
        &with(&format!(
            "\"cameras\": [{opencv}, {}]",
            fisheye.replace("0.0, 0.0, 0.0, 0.0]", "1e300, 0, 0, 0]")
        )),
        p,
    )
    .unwrap_err();
    assert!(
        matches!(&e, PairFileError::InvalidField { field, .. } if field == "cameras[1].params[4]"),
        "{e}"
    );
    assert!(e.to_string().contains("`k1`"), "{e}");
    let mut bad = sample();
    bad.cameras[1].readout = -1.0;
    let e = bad.validate().unwrap_err();
    assert!(
        matches!(&e, PairFileError::InvalidField { field, .. } if field == "cameras[1].readout"),
        "{e}"
    );
}

#[test]
fn a_known_gyro_bias_is_subtracted_from_readings_and_samples() {
    // Plain readings: the bias is in camera axes.
    let mut p = sample();
    let (v1, _) = p.views().unwrap();
    p.gyro_bias = Some([0.01, -0.02, 0.03]);
    let text = p.to_json_string();
    assert!(text.contains("\"gyro_bias\""), "{text}");
    let back = PairFile::from_json_str(&text, Path::new("p.json")).unwrap();
    assert_eq!(back, p);
    let (b1, b2) = back.views().unwrap();
    assert!((v1.omega - b1.omega - Vector3::new(0.01, -0.02, 0.03)).norm() < 1e-15);
    assert!(
        (Vector3::new(0.0, -1.0, 0.5) - b2.omega - Vector3::new(0.01, -0.02, 0.03)).norm() < 1e-15
    );
    // A log: the bias is in the gyro's axes, subtracted before camera_from_gyro.
    let m = [[0.0, -1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]];
    let mut with_log = sample();
    with_log.gyro = None;
    with_log.gyro_log = Some(GyroLogSpec {
        camera_from_gyro: m,
        time_offset: 0.0,
        frame_times: [0.0, 0.1],
        samples: (0..100)
            .map(|i| [i as f64 * 0.002, 0.1, 0.2, 0.3])
            .collect(),
        gyro_bias: Some([0.1, 0.05, 0.3]),
    });
    let text = with_log.to_json_string();
    let back = PairFile::from_json_str(&text, Path::new("p.json")).unwrap();
    let (w1, _) = back.views().unwrap();
    // M (0, 0.15, 0) = (−0.15, 0, 0).
    assert!(
        (w1.omega - Vector3::new(-0.15, 0.0, 0.0)).norm() < 1e-12,
        "{}",
        w1.omega
    );
    // A top-level bias beside a log is ambiguous (which axes?) and refused.
    let mut both = back.clone();
    both.gyro_bias = Some([0.0; 3]);
    let e = both.validate().unwrap_err().to_string();
    assert!(
        e.contains("`gyro_bias`") && e.contains("gyro_log.gyro_bias"),
        "{e}"
    );
    // Non-finite values name their field.
    let text = with_log.to_json_string().replace("0.05", "1e999");
    let e = PairFile::from_json_str(&text, Path::new("p.json"));
    assert!(e.is_err());
    let mut bad = with_log.clone();
    bad.gyro_log.as_mut().unwrap().gyro_bias = Some([f64::NAN, 0.0, 0.0]);
    let e = bad.validate().unwrap_err().to_string();
    assert!(e.contains("gyro_log.gyro_bias"), "{e}");
    // A misspelt key is refused with its name.
    let text = p.to_json_string().replace("gyro_bias", "gyro_bais");
    let e = PairFile::from_json_str(&text, Path::new("p.json"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("gyro_bais"), "{e}");
}

#[test]
fn a_long_gravity_is_refused_at_its_first_extra_element() {
    let p = Path::new("pair.json");
    let good = sample().to_json_string();
    let long_views = format!(
        "\"gravity\": [{}[0, 1, 0]], \"unused\": [",
        "[0, 1, 0], ".repeat(100_000)
    );
    let long_vector = format!(
        "\"gravity\": [[0, 1, {}0], [0, 1, 0]], \"unused\": [",
        "0, ".repeat(100_000)
    );
    for (edit, field) in [
        (long_views, "field `gravity`"),
        (long_vector, "field `gravity[0]`"),
    ] {
        let text = good.replacen("\"gravity\": [", &edit, 1);
        let err = PairFile::from_json_str(&text, p).unwrap_err().to_string();
        assert!(err.contains(field), "{err}");
    }
    // The same messages as a gravity built from a JSON value.
    let err = gravity_from_json(&serde_json::json!([[0, 1, 0], null])).unwrap_err();
    let text = good.replacen(
        "\"gravity\": [",
        "\"gravity\": [[0, 1, 0], null], \"unused\": [",
        1,
    );
    let file_err = PairFile::from_json_str(&text, p).unwrap_err().to_string();
    assert!(file_err.contains(&err), "{file_err} / {err}");
}
