use super::*;
use crate::data::pair_file::{GyroLogSpec, PairFile};
use nalgebra::Vector3;

const CAMCHAIN: &str = include_str!("../../../tests/data/calibration/camchain-imucam.yaml");

#[test]
fn radtan_and_equidistant_cameras_map_to_colmap_models() {
    let rig = parse_kalibr(CAMCHAIN, "cam0", None).unwrap();
    assert_eq!(rig.camera.model, CameraModel::OpenCv);
    assert_eq!(
        rig.camera.params(),
        vec![
            458.654,
            457.296,
            367.215,
            248.375,
            -0.28340811,
            0.07395907,
            0.00019359,
            1.76187114e-05
        ]
    );
    assert_eq!((rig.camera.width, rig.camera.height), (752.0, 480.0));
    assert_eq!(rig.camera.readout, 3.1e-5);
    assert_eq!(rig.camera.readout_direction, ReadoutDirection::TopToBottom);
    assert_eq!(
        rig.camera_from_gyro[0],
        [0.0148655429818, -0.999880929698, 0.00414029679422]
    );
    assert_eq!(rig.camera_from_gyro[2][2], 0.999660727178);
    assert_eq!(rig.time_offset, 0.00481);

    // cam1: a fisheye with a distortion list spanning two lines, no line_delay.
    let e = parse_kalibr(CAMCHAIN, "cam1", None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`cam1.line_delay`") && e.contains("--readout"),
        "{e}"
    );
    let rig = parse_kalibr(CAMCHAIN, "cam1", Some(2e-5)).unwrap();
    assert_eq!(rig.camera.model, CameraModel::OpenCvFisheye);
    assert_eq!(
        rig.camera.params()[4..],
        [
            0.0034823894022493434,
            0.0007150348452162257,
            -0.0020532361418706202,
            0.00020293673591811182
        ]
    );
    assert_eq!(rig.camera.readout, 2e-5);
    assert_eq!(rig.time_offset, -0.0021);
    // The given readout takes precedence over the file's line_delay.
    assert_eq!(
        parse_kalibr(CAMCHAIN, "cam0", Some(1e-5))
            .unwrap()
            .camera
            .readout,
        1e-5
    );
}

#[test]
fn bad_files_name_the_key() {
    let cases = [
        (CAMCHAIN.to_string(), "cam2", "`cam2`"),
        (
            CAMCHAIN.replace(
                "camera_model: pinhole\n  distortion_coeffs: [-0.28",
                "camera_model: omni\n  distortion_coeffs: [-0.28",
            ),
            "cam0",
            "`cam0.camera_model`",
        ),
        (
            CAMCHAIN.replace(
                "intrinsics: [458.654, 457.296, 367.215, 248.375]",
                "intrinsics: [458.654, 457.296, 367.215]",
            ),
            "cam0",
            "`cam0.intrinsics`",
        ),
        (
            CAMCHAIN.replace("distortion_model: radtan", "distortion_model: fov"),
            "cam0",
            "`cam0.distortion_model`",
        ),
        (
            CAMCHAIN.replace("[0.0148655429818, -0.999880929698", "[0.5, -0.999880929698"),
            "cam0",
            "`cam0.T_cam_imu`",
        ),
        (
            CAMCHAIN.replace(
                "  - [0.0, 0.0, 0.0, 1.0]\n  cam_overlaps: [1]",
                "  cam_overlaps: [1]",
            ),
            "cam0",
            "`cam0.T_cam_imu`",
        ),
        (
            CAMCHAIN.replace("timeshift_cam_imu: 0.00481", "timeshift_cam_imu: soon"),
            "cam0",
            "`cam0.timeshift_cam_imu`",
        ),
        (
            CAMCHAIN.replace("line_delay: 3.1e-05", "line_delay: -3.1e-05"),
            "cam0",
            "`cam0`",
        ),
    ];
    for (text, cam, key) in cases {
        let e = parse_kalibr(&text, cam, None).unwrap_err().to_string();
        assert!(e.contains(key), "{key}: {e}");
    }
    let e = parse_kalibr(CAMCHAIN, "cam2", None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("cam0, cam1"), "{e}");
}

/// Kalibr: `t_imu = t_cam + timeshift_cam_imu`. A camera that starts turning at IMU time
/// 10.005 s, a frame stamped 10.000 s on the camera's clock and a timeshift of +5 ms: row
/// 0 is read at IMU time 10.005, so the whole readout sees the turn. The opposite sign
/// would date row 0 at 9.995 s, before it.
#[test]
fn the_time_shift_dates_row_zero_on_the_gyro_clock() {
    let text = CAMCHAIN.replace("timeshift_cam_imu: 0.00481", "timeshift_cam_imu: 0.005");
    let rig = parse_kalibr(&text, "cam0", None).unwrap();
    let w_imu = Vector3::new(0.0, 1.0, 0.0);
    let samples: Vec<[f64; 4]> = (0..=200)
        .map(|i| {
            let t = 9.9 + i as f64 * 1e-3;
            let w = if t >= 10.005 - 1e-9 {
                w_imu
            } else {
                Vector3::zeros()
            };
            [t, w.x, w.y, w.z]
        })
        .collect();
    let spec = |time_offset: f64| GyroLogSpec {
        camera_from_gyro: rig.camera_from_gyro,
        time_offset,
        frame_times: [10.0, 10.05],
        samples: samples.clone(),
        gyro_bias: None,
    };
    let view1_rate = |time_offset: f64| {
        let pair = PairFile {
            cameras: [rig.camera; 2],
            gyro: None,
            gyro_bias: None,
            gyro_log: Some(spec(time_offset)),
            gravity: None,
            matches: vec![],
            ground_truth: None,
        };
        pair.views().unwrap().0.omega
    };
    let m = crate::data::pair_file::matrix_from_rows(&rig.camera_from_gyro);
    let expected = m * w_imu;
    assert!((view1_rate(rig.time_offset) - expected).norm() < 1e-6);
    assert!((view1_rate(-rig.time_offset) - expected).norm() > 0.3);
}
