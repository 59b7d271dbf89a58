use super::*;

#[test]
fn bearing_projection_roundtrip() {
    let cam = Camera::paper();
    let m = cam.undistort_bearing(100.0, 900.0).unwrap();
    assert_eq!(m.z, 1.0);
    let p = cam.project(&(m * 7.0)).unwrap();
    assert!((p.x - 100.0).abs() < 1e-9 && (p.y - 900.0).abs() < 1e-9);
    assert!(cam.project(&Vector3::new(0.0, 0.0, -1.0)).is_none());
}

#[test]
fn validation_rejects_bad_parameters() {
    let mut cam = Camera::paper();
    assert!(cam.validate().is_ok());
    cam.fx = 0.0;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidFocal { name: "fx", .. })
    ));
    let mut cam = Camera::paper();
    cam.readout = -1.0;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidReadout(_))
    ));
    let mut cam = Camera::paper();
    cam.cy = f64::NAN;
    assert!(cam.validate().is_err());
    // Finite but implausible values are rejected too, naming the parameter.
    let mut cam = Camera::paper();
    cam.fy = 1e-300;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidFocal { name: "fy", .. })
    ));
    let mut cam = Camera::paper();
    cam.cx = 1e308;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidPrincipalPoint { name: "cx", .. })
    ));
    let v = View::new(Camera::paper(), Vector3::new(1.7e308, 0.0, 0.0));
    assert!(matches!(v.validate(), Err(CameraError::InvalidGyro(..))));
    // Readout 0 is a global-shutter camera.
    let mut cam = Camera::paper();
    cam.readout = 0.0;
    assert!(cam.validate().is_ok());
    let v = View::new(Camera::paper(), Vector3::new(f64::INFINITY, 0.0, 0.0));
    assert!(matches!(v.validate(), Err(CameraError::InvalidGyro(..))));
    // Gravity: any finite non-zero length; zero, NaN and infinity are rejected.
    let v = View::new(Camera::paper(), Vector3::zeros());
    assert!(v
        .clone()
        .with_gravity(Vector3::new(0.0, 9.81, 0.0))
        .validate()
        .is_ok());
    for g in [
        Vector3::zeros(),
        Vector3::new(f64::NAN, 1.0, 0.0),
        Vector3::new(0.0, f64::INFINITY, 0.0),
    ] {
        assert!(matches!(
            v.clone().with_gravity(g).validate(),
            Err(CameraError::InvalidGravity(..))
        ));
    }
}

/// A camera of each model with moderate, invertible-over-the-image distortion.
fn cameras() -> Vec<Camera> {
    let d = ReadoutDirection::TopToBottom;
    let make = |model, params: &[f64]| {
        Camera::from_params(model, 1280.0, 960.0, params, 30e-6, d).unwrap()
    };
    vec![
        make(CameraModel::SimplePinhole, &[600.0, 640.0, 480.0]),
        make(CameraModel::Pinhole, &[600.0, 610.0, 641.0, 479.0]),
        make(CameraModel::SimpleRadial, &[600.0, 640.0, 480.0, -0.05]),
        make(CameraModel::Radial, &[600.0, 640.0, 480.0, -0.12, 0.02]),
        make(
            CameraModel::OpenCv,
            &[600.0, 605.0, 640.0, 480.0, -0.25, 0.07, 0.001, -0.0015],
        ),
        make(
            CameraModel::OpenCvFisheye,
            &[500.0, 500.0, 640.0, 480.0, 0.05, -0.01, 0.003, -0.0004],
        ),
        make(
            CameraModel::FullOpenCv,
            &[
                600.0, 605.0, 640.0, 480.0, -0.2, 0.05, 0.001, -0.001, 0.01, 0.05, 0.01, 0.002,
            ],
        ),
    ]
}

#[test]
fn distort_undistort_round_trip_for_every_model() {
    for cam in cameras() {
        assert!(cam.validate().is_ok(), "{}", cam.model);
        assert_eq!(cam.params().len(), cam.model.num_params());
        for (u, v) in [
            (0.5, 0.5),
            (100.0, 900.0),
            (640.0, 480.0),
            (1279.0, 3.0),
            (900.0, 600.0),
        ] {
            // Pixel -> bearing -> pixel.
            let m = cam.undistort_bearing(u, v).unwrap();
            assert_eq!(m.z, 1.0);
            let p = cam.project(&(m * 3.0)).unwrap();
            assert!((p - Vector2::new(u, v)).norm() < 1e-6, "{}: {p}", cam.model);
            // Point -> pixel -> bearing.
            let x = Vector3::new((u - 640.0) / 700.0, (v - 480.0) / 700.0, 1.0);
            let p = cam.project(&x).unwrap();
            let back = cam.undistort_bearing(p.x, p.y).unwrap();
            assert!((back - x).norm() < 1e-9, "{}: {back} vs {x}", cam.model);
        }
    }
}

/// COLMAP's formulas (`models.h`), evaluated by hand for one point.
#[test]
fn projections_match_colmap_reference_values() {
    // OPENCV [fx, fy, cx, cy, k1, k2, p1, p2], point (0.3, -0.2, 1):
    // r² = 0.13, radial = k1 r² + k2 r⁴ = -0.025155,
    // du = u radial + 2 p1 uv + p2 (r² + 2u²) = -0.0082865,
    // dv = v radial + 2 p2 uv + p1 (r² + 2v²) = 0.005481,
    // pixel = (500 (0.3 + du) + 320, 510 (-0.2 + dv) + 240).
    let cam = Camera::from_params(
        CameraModel::OpenCv,
        640.0,
        480.0,
        &[500.0, 510.0, 320.0, 240.0, -0.2, 0.05, 0.001, -0.002],
        0.0,
        ReadoutDirection::TopToBottom,
    )
    .unwrap();
    let p = cam.project(&Vector3::new(0.6, -0.4, 2.0)).unwrap();
    assert!(
        (p.x - 465.85675).abs() < 1e-9 && (p.y - 140.79531).abs() < 1e-9,
        "{p}"
    );
    let m = cam.undistort_bearing(465.85675, 140.79531).unwrap();
    assert!((m - Vector3::new(0.3, -0.2, 1.0)).norm() < 1e-10, "{m}");

    // OPENCV_FISHEYE [fx, fy, cx, cy, k1, k2, k3, k4], point (0.8, -0.6, 1), r = 1:
    // θ = atan(1) = π/4, θ_d = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸) = 0.8205191186006062,
    // pixel = (400 · 0.8 θ_d + 640, 400 · (-0.6) θ_d + 480).
    let cam = Camera::from_params(
        CameraModel::OpenCvFisheye,
        1280.0,
        960.0,
        &[400.0, 400.0, 640.0, 480.0, 0.1, -0.05, 0.01, -0.002],
        0.0,
        ReadoutDirection::TopToBottom,
    )
    .unwrap();
    let p = cam.project(&Vector3::new(0.8, -0.6, 1.0)).unwrap();
    assert!((p.x - 902.566117952194).abs() < 1e-9, "{p}");
    assert!((p.y - 283.0754115358545).abs() < 1e-9, "{p}");
    let m = cam
        .undistort_bearing(902.566117952194, 283.0754115358545)
        .unwrap();
    assert!((m - Vector3::new(0.8, -0.6, 1.0)).norm() < 1e-10, "{m}");
}

#[test]
fn undistortion_refuses_pixels_beyond_the_invertible_region() {
    let dir = ReadoutDirection::TopToBottom;
    // Fisheye with k1 = -0.5: θ_d' = 1 - 1.5 θ² vanishes at θ = 0.816, where θ_d peaks at
    // 0.544; a pixel at distorted radius 0.6 (300 px at f = 500) has no bearing.
    let cam = Camera::from_params(
        CameraModel::OpenCvFisheye,
        1280.0,
        960.0,
        &[500.0, 500.0, 640.0, 480.0, -0.5, 0.0, 0.0, 0.0],
        0.0,
        dir,
    )
    .unwrap();
    assert!(matches!(
        cam.undistort_bearing(640.0 + 300.0, 480.0),
        Err(CameraError::NotInvertible {
            model: "OPENCV_FISHEYE",
            ..
        })
    ));
    // Inside the fold: a bearing with θ below 0.816.
    let m = cam.undistort_bearing(640.0 + 250.0, 480.0).unwrap();
    assert!(m.x.atan() < 0.8165, "{m}");
    // Beyond the fold a point does not project (its pixel would have no unique bearing).
    assert!(cam.project(&Vector3::new(1.5f64.tan(), 0.0, 1.0)).is_none());
    // A plain equidistant fisheye reaches θ_d = π/2 at the horizon: beyond it, nothing.
    let plain = Camera {
        distortion: [0.0; 8],
        ..cam
    };
    assert!(matches!(
        plain.observe([640.0 + 500.0 * 1.6, 480.0]),
        Err(CameraError::NotInvertible { .. })
    ));
    assert!(plain.observe([640.0 + 500.0 * 1.5, 480.0]).is_ok());
    // RADIAL with k1 = -0.3: r (1 - 0.3 r²) stops increasing at r = 1.054 (r_d = 0.703).
    let radial = Camera::from_params(
        CameraModel::Radial,
        1280.0,
        960.0,
        &[500.0, 640.0, 480.0, -0.3, 0.0],
        0.0,
        dir,
    )
    .unwrap();
    for r_d in [0.71, 0.8] {
        let e = radial.observe([640.0 + 500.0 * r_d, 480.0]).unwrap_err();
        assert!(matches!(e, CameraError::NotInvertible { .. }), "{e}");
    }
    let m = radial
        .undistort_bearing(640.0 + 500.0 * 0.69, 480.0)
        .unwrap();
    assert!(m.x < 1.054, "{m}");
    assert!(radial.project(&Vector3::new(1.1, 0.0, 1.0)).is_none());
}

#[test]
fn readout_lines_follow_the_direction() {
    let mut cam = Camera::paper();
    let expect = [
        (ReadoutDirection::TopToBottom, 200.0, 1080.0),
        (ReadoutDirection::BottomToTop, 1079.0 - 200.0, 1080.0),
        (ReadoutDirection::LeftToRight, 100.0, 1920.0),
        (ReadoutDirection::RightToLeft, 1919.0 - 100.0, 1920.0),
    ];
    for (d, line, lines) in expect {
        cam.readout_direction = d;
        assert_eq!(cam.readout_line(100.0, 200.0), line, "{d:?}");
        assert_eq!(cam.observe([100.0, 200.0]).unwrap().line, line);
        assert_eq!(cam.lines(), lines);
        assert_eq!(cam.frame_readout(), lines * 60e-6);
        assert_eq!(ReadoutDirection::from_name(d.name()), Some(d));
    }
    // The first line read is line 0 in every direction.
    cam.readout_direction = ReadoutDirection::BottomToTop;
    assert_eq!(cam.readout_line(5.0, 1079.0), 0.0);
    cam.readout_direction = ReadoutDirection::RightToLeft;
    assert_eq!(cam.readout_line(1919.0, 5.0), 0.0);
}

#[test]
fn json_forms_and_their_errors() {
    let parse = |s: &str| serde_json::from_str::<Camera>(s).map_err(|e| e.to_string());
    // The pinhole short form is PINHOLE read from the top, and is written back as such.
    let old = r#"{"fx": 640, "fy": 640, "cx": 960, "cy": 540, "width": 1920, "height": 1080, "readout": 6e-5}"#;
    let cam = parse(old).unwrap();
    assert_eq!(cam, Camera::paper());
    let text = serde_json::to_string(&cam).unwrap();
    assert!(
        text.starts_with(r#"{"fx":640.0,"#) && !text.contains("model"),
        "{text}"
    );
    // COLMAP's form.
    let cv = r#"{"model": "OPENCV", "width": 1920, "height": 1080,
        "params": [700, 701, 960, 540, -0.1, 0.01, 0.001, 0.002], "readout": 3e-5,
        "readout_direction": "right_to_left"}"#;
    let cam = parse(cv).unwrap();
    assert_eq!(cam.model, CameraModel::OpenCv);
    assert_eq!(
        (cam.fx, cam.fy, cam.cx, cam.cy),
        (700.0, 701.0, 960.0, 540.0)
    );
    assert_eq!(
        cam.params(),
        vec![700.0, 701.0, 960.0, 540.0, -0.1, 0.01, 0.001, 0.002]
    );
    assert_eq!(cam.readout_direction, ReadoutDirection::RightToLeft);
    let text = serde_json::to_string(&cam).unwrap();
    assert!(
        text.contains(r#""readout_direction":"right_to_left""#),
        "{text}"
    );
    assert_eq!(parse(&text).unwrap(), cam);
    let simple = parse(r#"{"model": "SIMPLE_RADIAL", "width": 10, "height": 10, "params": [5, 4, 4, 0.1], "readout": 0}"#).unwrap();
    assert_eq!(
        (simple.fx, simple.fy, simple.distortion[0]),
        (5.0, 5.0, 0.1)
    );
    assert_eq!(simple.readout_direction, ReadoutDirection::TopToBottom);
    // Refusals name the key, the model and the expected count.
    for (text, needle) in [
        (old.replace("\"fx\"", "\"focal\""), "unknown field `focal`"),
        (
            cv.replace("\"params\": [700, 701,", "\"params\": ["),
            "OPENCV takes 8 params [fx, fy, cx, cy, k1, k2, p1, p2], got 6",
        ),
        (
            cv.replace("\"OPENCV\"", "\"KANNALA\""),
            "unknown camera model `KANNALA`",
        ),
        (
            cv.replace("\"right_to_left\"", "\"upwards\""),
            "unknown variant `upwards`",
        ),
        (
            cv.replace("\"width\"", "\"fx\": 3, \"width\""),
            "`fx` belongs to the pinhole short form",
        ),
        (old.replace("\"fy\": 640,", ""), "missing field `fy`"),
        (
            cv.replace("\"params\"", "\"parameters\""),
            "unknown field `parameters`",
        ),
    ] {
        let e = parse(&text).unwrap_err();
        assert!(e.contains(needle), "{e} (wanted {needle})");
    }
}

#[test]
fn distortion_parameters_are_validated_by_name() {
    let mut cam = cameras()[4];
    cam.distortion[2] = f64::NAN;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidDistortion { name: "p1", .. })
    ));
    let mut cam = cameras()[2];
    cam.fx = 0.0;
    cam.fy = 0.0;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidFocal { name: "f", .. })
    ));
    let mut cam = cameras()[2];
    cam.fy = 601.0;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::UnequalFocals { .. })
    ));
    let mut cam = cameras()[6];
    cam.distortion[7] = 1e300;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidDistortion { name: "k6", .. })
    ));
    // A column readout's frame is `width` lines long.
    let mut cam = Camera::paper();
    cam.readout = 9.5 / 1080.0;
    assert!(cam.validate().is_ok());
    cam.readout_direction = ReadoutDirection::LeftToRight;
    assert!(matches!(
        cam.validate(),
        Err(CameraError::InvalidReadout(_))
    ));
}
