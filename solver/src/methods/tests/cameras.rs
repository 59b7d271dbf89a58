//! Cameras beyond the paper's: global shutter, large inputs, the readout option, lens
//! distortion, every readout direction, a camera per view.

use super::*;

/// Readout 0 is a global-shutter camera: every row is read at once, the gyro changes
/// nothing, and the gyro-aided methods must give the global-shutter answer.
#[test]
fn a_global_shutter_camera_makes_the_gyro_methods_agree_with_gsrp() {
    let p = pair(SimulationOptions {
        camera: crate::model::camera::Camera {
            readout: 0.0,
            ..crate::model::camera::Camera::paper()
        },
        angular_velocity: 2.5,
        seed: 4,
        ..Default::default()
    });
    let gt = p.ground_truth.as_ref().unwrap();
    let gs = run(&p, &EstimateOptions::for_method(Method::Gsrp)).unwrap();
    for m in [
        Method::Rectified,
        Method::Grsrp,
        Method::GrsrpPlus,
        Method::RectifiedV,
        Method::GrsrpGravity,
    ] {
        let e = run(&p, &EstimateOptions::for_method(m)).unwrap();
        let err = pose_errors(&e, gt);
        assert!(
            err.rotation_error_deg < 0.5 && err.translation_error_deg < 3.0,
            "{m}: {err:?}"
        );
        let d = crate::model::geometry::rotation_error_deg(&gs.rotation, &e.rotation);
        assert!(d < 0.2, "{m} differs from gsrp by {d} deg");
    }
}

/// Above `max_points` matches the estimate comes from a random subset and every match is
/// classified against it: the mask covers all matches, keeps most true inliers and
/// rejects the outliers, and the pose is as accurate as from all matches.
#[test]
fn large_inputs_estimate_on_a_subset_and_classify_every_match() {
    let p = pair(SimulationOptions {
        points: 1500,
        outlier_fraction: 0.3,
        angular_velocity: 1.5,
        seed: 6,
        ..Default::default()
    });
    let gt = p.ground_truth.as_ref().unwrap();
    for m in Method::ALL {
        let mut o = EstimateOptions::for_method(m);
        o.robust.max_points = 300;
        let e = run(&p, &o).unwrap();
        assert_eq!(e.inliers.len(), p.matches.len());
        let kept_true = (0..p.matches.len())
            .filter(|&i| gt.inliers[i] && e.inliers[i])
            .count();
        let kept_false = (0..p.matches.len())
            .filter(|&i| !gt.inliers[i] && e.inliers[i])
            .count();
        assert!(kept_true > 600, "{m}: {kept_true} true inliers kept");
        assert!(kept_false < 30, "{m}: {kept_false} outliers accepted");
        // The global-shutter methods are inaccurate at 1.5 rad/s with or without a subset.
        if !matches!(m, Method::Nrsrp | Method::Gsrp) {
            let err = pose_errors(&e, gt);
            assert!(err.rotation_error_deg < 1.0, "{m}: {err:?}");
        }
    }
}

#[test]
fn the_readout_option_refines_a_wrong_nominal_readout() {
    let p = pair(SimulationOptions {
        angular_velocity: 2.5,
        seed: 8,
        ..Default::default()
    });
    let gt = p.ground_truth.clone().unwrap();
    let (mut v1, mut v2) = p.views().unwrap();
    v1.camera.readout *= 1.3;
    v2.camera.readout *= 1.3;
    let plain = EstimateOptions::for_method(Method::Rectified);
    let with = EstimateOptions {
        readout: Some(ReadoutOptions::default()),
        ..plain.clone()
    };
    let a = estimate_relative_pose(&v1, &v2, &p.matches, &plain).unwrap();
    let b = estimate_relative_pose(&v1, &v2, &p.matches, &with).unwrap();
    assert_eq!(a.readout_scale, None);
    let k = b.readout_scale.unwrap();
    assert!((k * 1.3 - 1.0).abs() < 0.1, "{k}");
    let (ea, eb) = (pose_errors(&a, &gt), pose_errors(&b, &gt));
    assert!(
        eb.rotation_error_deg < ea.rotation_error_deg,
        "{ea:?} {eb:?}"
    );
    assert_eq!(b.report_json()["readout_scale"], serde_json::json!(k));
    // Methods that ignore the gyro cannot refine it; bad settings are named.
    for (m, bad) in [
        (Method::Gsrp, ReadoutOptions::default()),
        (
            Method::Rectified,
            ReadoutOptions {
                scale_range: (1.5, 2.0),
                ..ReadoutOptions::default()
            },
        ),
    ] {
        let o = EstimateOptions {
            readout: Some(bad),
            ..EstimateOptions::for_method(m)
        };
        let e = estimate_relative_pose(&v1, &v2, &p.matches, &o).unwrap_err();
        assert!(matches!(e, EstimateError::InvalidOption { .. }), "{e}");
    }
}

/// Distorted lenses and every readout direction: a pixel's bearing comes from undistorting
/// it and its time from its raw line, so on noise-free data every gyro-aided method still
/// recovers the pose exactly; and dating the pixels by the wrong direction does not.
#[test]
fn gyro_methods_are_exact_with_distortion_and_any_readout_direction() {
    use crate::model::camera::ReadoutDirection;
    use crate::model::camera_model::CameraModel;
    let camera = |model, params: &[f64], direction: ReadoutDirection| {
        // About the paper's frame readout (65 ms) whichever way the lines run.
        let readout = if direction.is_horizontal() {
            34e-6
        } else {
            60e-6
        };
        Camera::from_params(model, 1920.0, 1080.0, params, readout, direction).unwrap()
    };
    let opencv = [700.0, 690.0, 955.0, 545.0, -0.28, 0.08, 0.0008, -0.0005];
    let fisheye = [600.0, 600.0, 960.0, 540.0, 0.05, -0.01, 0.002, -0.0005];
    let mut scenes: Vec<Camera> = ReadoutDirection::ALL
        .iter()
        .map(|&d| camera(CameraModel::OpenCv, &opencv, d))
        .collect();
    for d in [ReadoutDirection::TopToBottom, ReadoutDirection::RightToLeft] {
        scenes.push(camera(CameraModel::OpenCvFisheye, &fisheye, d));
    }
    let mut scenes: Vec<(Camera, Option<Camera>)> = scenes.into_iter().map(|c| (c, None)).collect();
    // A camera per view: different lenses read in different directions.
    scenes.push((
        camera(CameraModel::OpenCv, &opencv, ReadoutDirection::BottomToTop),
        Some(camera(
            CameraModel::OpenCvFisheye,
            &fisheye,
            ReadoutDirection::LeftToRight,
        )),
    ));
    let gyro_methods = [
        Method::Rectified,
        Method::RectifiedV,
        Method::Grsrp,
        Method::GrsrpPlus,
        Method::GrsrpGravity,
    ];
    for (seed, (cam, camera2)) in scenes.into_iter().enumerate() {
        let p = pair(SimulationOptions {
            camera: cam,
            camera2,
            pixel_noise: 0.0,
            gyro_noise: 0.0,
            gravity_noise_deg: 0.0,
            angular_velocity: 2.5,
            seed: seed as u64,
            ..Default::default()
        });
        let gt = p.ground_truth.as_ref().unwrap();
        assert_eq!(p.cameras, [cam, camera2.unwrap_or(cam)]);
        let label = format!(
            "{} {} / {:?}",
            cam.model,
            cam.readout_direction.name(),
            camera2.map(|c| (c.model, c.readout_direction))
        );
        for m in gyro_methods {
            let e = run(&p, &EstimateOptions::for_method(m)).unwrap();
            let err = pose_errors(&e, gt);
            assert!(
                err.rotation_error_deg < 1e-4 && err.translation_error_deg < 1e-3,
                "{label} {m}: {err:?}"
            );
            assert_eq!(e.num_inliers(), p.matches.len(), "{label} {m}");
        }
        // The same pixels dated by the opposite direction: the row rotations are wrong.
        let mut wrong = p.clone();
        for c in &mut wrong.cameras {
            c.readout_direction = match c.readout_direction {
                ReadoutDirection::TopToBottom => ReadoutDirection::BottomToTop,
                ReadoutDirection::BottomToTop => ReadoutDirection::TopToBottom,
                ReadoutDirection::LeftToRight => ReadoutDirection::RightToLeft,
                ReadoutDirection::RightToLeft => ReadoutDirection::LeftToRight,
            };
        }
        let e = run(&wrong, &EstimateOptions::for_method(Method::Rectified)).unwrap();
        let err = pose_errors(&e, gt);
        assert!(err.rotation_error_deg > 1e-2, "{label} reversed: {err:?}");
    }
}

/// A camera per view: different lenses and readouts in the two images.
#[test]
fn a_camera_per_view_is_used_for_its_own_pixels() {
    use crate::model::camera::ReadoutDirection;
    use crate::model::camera_model::CameraModel;
    // Re-image image 2 of a still scene through an OPENCV lens: each pixel's bearing
    // through the paper's pinhole, projected by the distorted camera.
    let still = pair(SimulationOptions {
        pixel_noise: 0.0,
        gyro_noise: 0.0,
        angular_velocity: 0.0,
        seed: 3,
        ..Default::default()
    });
    let cam2 = Camera::from_params(
        CameraModel::OpenCv,
        1920.0,
        1080.0,
        &[640.0, 640.0, 960.0, 540.0, -0.1, 0.01, 0.0, 0.0],
        60e-6,
        ReadoutDirection::TopToBottom,
    )
    .unwrap();
    let mut two = still.clone();
    for m in &mut two.matches {
        let b = still.cameras[1]
            .undistort_bearing(m[1][0], m[1][1])
            .unwrap();
        let q = cam2.project(&b).unwrap();
        m[1] = [q.x, q.y];
    }
    two.cameras[1] = cam2;
    let text = two.to_json_string();
    assert!(text.contains("\"cameras\"") && !text.contains("\"camera\""));
    let back = PairFile::from_json_str(&text, std::path::Path::new("x.json")).unwrap();
    assert_eq!(back.cameras, two.cameras);
    let e = run(&back, &eight_point(Method::Gsrp)).unwrap();
    let err = pose_errors(&e, still.ground_truth.as_ref().unwrap());
    assert!(
        err.rotation_error_deg < 1e-4 && err.translation_error_deg < 1e-3,
        "{err:?}"
    );
    // Read with one camera for both images, image 2's pixels are mis-undistorted.
    let mut shared = back.clone();
    shared.cameras[1] = shared.cameras[0];
    let e = run(&shared, &eight_point(Method::Gsrp)).unwrap();
    let bad = pose_errors(&e, still.ground_truth.as_ref().unwrap());
    assert!(bad.rotation_error_deg > 1e-2, "{bad:?}");
}
