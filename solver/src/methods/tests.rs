use super::*;
use crate::data::pair_file::PairFile;
use crate::data::simulate::{simulate, SimulationOptions};
use crate::estimation::readout::ReadoutOptions;
use crate::experiment::evaluate::pose_errors;
use crate::minimal::{EssentialSolver, GrsrpSolver};
use crate::model::camera::{Camera, View};
use crate::model::matches::Match;
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn pair(opts: SimulationOptions) -> PairFile {
    simulate(&opts).unwrap()
}

fn run(p: &PairFile, o: &EstimateOptions) -> Result<Estimate, EstimateError> {
    let (v1, v2) = p.views().unwrap();
    estimate_relative_pose(&v1, &v2, &p.matches, o)
}

fn eight_point(method: Method) -> EstimateOptions {
    EstimateOptions {
        essential_solver: EssentialSolver::EightPoint,
        ..EstimateOptions::for_method(method)
    }
}

#[test]
fn method_names_roundtrip() {
    for m in Method::ALL {
        assert_eq!(m.to_string().parse::<Method>().unwrap(), m);
    }
    assert_eq!("grsrp+".parse::<Method>().unwrap(), Method::GrsrpPlus);
    assert!("foo".parse::<Method>().is_err());
}

#[test]
fn input_errors_are_typed() {
    let p = pair(SimulationOptions {
        points: 30,
        ..Default::default()
    });
    let (v1, v2) = p.views().unwrap();
    let o = EstimateOptions::for_method(Method::Gsrp);
    let mut m = p.matches.clone();
    m[3][1][0] = f64::NAN;
    assert_eq!(
        estimate_relative_pose(&v1, &v2, &m, &o),
        Err(EstimateError::NonFinitePixel { index: 3, image: 2 })
    );
    let mut m = p.matches.clone();
    m[2][0][0] -= 1e6;
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &m, &o),
        Err(EstimateError::PixelOutsideImage {
            index: 2,
            image: 1,
            ..
        })
    ));
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &p.matches[..4], &o),
        Err(EstimateError::TooFewMatches {
            needed: 5,
            got: 4,
            ..
        })
    ));
    let nr = EstimateOptions::for_method(Method::Nrsrp);
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &p.matches[..16], &nr),
        Err(EstimateError::TooFewMatches { needed: 17, .. })
    ));
    let dup = vec![p.matches[0]; 40];
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &dup, &o),
        Err(EstimateError::Degenerate { distinct: 1, .. })
    ));
    let mut bad = v1.clone();
    bad.camera.fy = -3.0;
    assert!(matches!(
        estimate_relative_pose(&bad, &v2, &p.matches, &o),
        Err(EstimateError::InvalidCamera { view: 1, .. })
    ));
    let mut bad = v2.clone();
    bad.omega.x = f64::INFINITY;
    assert!(matches!(
        estimate_relative_pose(&v1, &bad, &p.matches, &o),
        Err(EstimateError::InvalidCamera { view: 2, .. })
    ));
    let mut o2 = o.clone();
    o2.robust.threshold = Threshold::SampsonPixels(-1.0);
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &p.matches, &o2),
        Err(EstimateError::InvalidOption { .. })
    ));
}

#[test]
fn garbage_input_never_panics() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let specials = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e300,
        -1e300,
        0.0,
        1e-300,
        5.0,
    ];
    let cam = Camera::paper();
    for trial in 0..60 {
        let n = rng.gen_range(0..40);
        let mut matches: Vec<Match> = (0..n)
            .map(|_| {
                let mut g = || {
                    if rng.gen_bool(0.15) {
                        specials[rng.gen_range(0..specials.len())]
                    } else {
                        rng.gen_range(-3000.0..3000.0)
                    }
                };
                [[g(), g()], [g(), g()]]
            })
            .collect();
        if trial % 3 == 0 && !matches.is_empty() {
            // Mostly duplicates / finite garbage.
            let m0 = [[1e300, -1e300], [1e-300, 7.0]];
            for (i, m) in matches.iter_mut().enumerate() {
                *m = if i % 2 == 0 {
                    m0
                } else {
                    [[3.0, 3.0], [3.0, 3.0]]
                };
            }
        }
        let w = Vector3::new(
            specials[rng.gen_range(0..specials.len())],
            rng.gen_range(-10.0..10.0),
            0.0,
        );
        let g = Vector3::new(0.1, rng.gen_range(-10.0..10.0), 0.2);
        let views = [
            View::new(cam, Vector3::new(0.5, 0.1, -0.3)).with_gravity(g),
            View::new(cam, w).with_gravity(g),
        ];
        for method in Method::ALL {
            for solver in [EssentialSolver::FivePoint, EssentialSolver::EightPoint] {
                let o = EstimateOptions {
                    essential_solver: solver,
                    ..EstimateOptions::paper(method)
                };
                if let Ok(e) = estimate_relative_pose(&views[0], &views[1], &matches, &o) {
                    assert!(e.rotation.iter().all(|x| x.is_finite()));
                    assert!((e.translation.norm() - 1.0).abs() < 1e-6);
                    assert_eq!(e.inliers.len(), matches.len());
                }
            }
        }
    }
}

#[test]
fn degenerate_geometry_gives_no_nan() {
    // All points on one ray pair: rank-deficient; must be an error or a finite pose.
    let cam = Camera::paper();
    let v = View::new(cam, Vector3::zeros()).with_gravity(Vector3::y());
    let matches: Vec<Match> = (0..20)
        .map(|k| {
            [
                [100.0 + k as f64 * 1e-9, 200.0],
                [100.0, 200.0 + k as f64 * 1e-9],
            ]
        })
        .collect();
    for method in Method::ALL {
        let o = eight_point(method);
        match estimate_relative_pose(&v, &v, &matches, &o) {
            Ok(e) => assert!(e
                .rotation
                .iter()
                .chain(e.translation.iter())
                .all(|x| x.is_finite())),
            Err(e) => assert!(matches!(e, EstimateError::NoSolution)),
        }
    }
}

// ---- methods with the non-minimal 8-point essential solver ----

#[test]
fn rectified_noise_free_with_eight_point_is_exact() {
    for seed in 0..3 {
        let p = pair(SimulationOptions {
            pixel_noise: 0.0,
            gyro_noise: 0.0,
            angular_velocity: 2.5,
            seed,
            ..Default::default()
        });
        let e = run(&p, &eight_point(Method::Rectified)).unwrap();
        let err = pose_errors(&e, p.ground_truth.as_ref().unwrap());
        assert!(err.rotation_error_deg < 1e-4, "{err:?}");
        assert!(err.translation_error_deg < 1e-3, "{err:?}");
        assert_eq!(e.num_inliers(), 150);
    }
}

#[test]
fn gsrp_is_exact_without_motion_and_robust_to_outliers() {
    let p = pair(SimulationOptions {
        pixel_noise: 0.0,
        gyro_noise: 0.0,
        angular_velocity: 0.0,
        outlier_fraction: 0.3,
        seed: 4,
        ..Default::default()
    });
    let e = run(&p, &eight_point(Method::Gsrp)).unwrap();
    let gt = p.ground_truth.as_ref().unwrap();
    let err = pose_errors(&e, gt);
    assert!(
        err.rotation_error_deg < 1e-4 && err.translation_error_deg < 1e-3,
        "{err:?}"
    );
    assert_eq!(e.inliers, gt.inliers);
}

#[test]
fn rectified_beats_gsrp_under_rs_distortion_eight_point() {
    let (mut rect, mut gs) = (0.0, 0.0);
    for seed in 0..5 {
        let p = pair(SimulationOptions {
            seed,
            ..Default::default()
        });
        let gt = p.ground_truth.as_ref().unwrap();
        rect +=
            pose_errors(&run(&p, &eight_point(Method::Rectified)).unwrap(), gt).rotation_error_deg;
        gs += pose_errors(&run(&p, &eight_point(Method::Gsrp)).unwrap(), gt).rotation_error_deg;
    }
    assert!(rect / 5.0 < 1.0, "{}", rect / 5.0);
    assert!(rect < gs, "{rect} {gs}");
}

#[test]
fn nrsrp_runs_and_reports_velocities() {
    let p = pair(SimulationOptions {
        seed: 2,
        angular_velocity: 1.0,
        linear_velocity: 4.0,
        ..Default::default()
    });
    let e = run(&p, &eight_point(Method::Nrsrp)).unwrap();
    assert!(e.angular_velocity.is_some() && e.linear_velocity.is_some());
    let err = pose_errors(&e, p.ground_truth.as_ref().unwrap());
    assert!(err.rotation_error_deg < 5.0, "{err:?}");
}

// ---- method-level tests that need the generated minimal solvers ----

#[test]
fn rectified_noise_free_is_exact() {
    let p = pair(SimulationOptions {
        pixel_noise: 0.0,
        gyro_noise: 0.0,
        seed: 1,
        ..Default::default()
    });
    for o in [
        EstimateOptions::for_method(Method::Rectified),
        EstimateOptions::paper(Method::Rectified),
    ] {
        let err = pose_errors(&run(&p, &o).unwrap(), p.ground_truth.as_ref().unwrap());
        assert!(err.rotation_error_deg < 1e-4, "{err:?}");
        assert!(err.translation_error_deg < 1e-3, "{err:?}");
    }
}

#[test]
fn paper_accuracy_at_2_5_rad_s() {
    let methods = [
        Method::Gsrp,
        Method::Grsrp,
        Method::GrsrpPlus,
        Method::Rectified,
        Method::Nrsrp,
    ];
    let mut rot = [0.0; 5];
    let mut tra = [0.0; 5];
    for seed in 0..10 {
        let p = pair(SimulationOptions {
            angular_velocity: 2.5,
            pixel_noise: 1.0,
            gyro_noise: 0.1,
            seed,
            ..Default::default()
        });
        let gt = p.ground_truth.as_ref().unwrap();
        for (k, m) in methods.iter().enumerate() {
            let e = run(&p, &EstimateOptions::paper(*m)).unwrap();
            if std::env::var_os("RSPOSE_DEBUG").is_some() {
                eprintln!("{m} seed {seed}: {} lm iterations", e.refinement_iterations);
            }
            let err = pose_errors(&e, gt);
            rot[k] += err.rotation_error_deg / 10.0;
            tra[k] += err.translation_error_deg / 10.0;
        }
    }
    for (k, m) in methods.iter().enumerate() {
        eprintln!(
            "paper preset, 10 seeds: {m:<9} mean rotation {:.4} deg, mean translation {:.4} deg",
            rot[k], tra[k]
        );
    }
    assert!(rot[2] < 1.0 && tra[2] < 5.0, "grsrp+ {} {}", rot[2], tra[2]);
    assert!(rot[0] > rot[2] && tra[0] > tra[2], "gsrp should be worse");
    assert!(
        rot[3] <= rot[2] * 1.05 + 1e-3,
        "rectified no worse than grsrp+"
    );
}

#[test]
fn grsrp_variants_and_r0_sources_agree() {
    let p = pair(SimulationOptions {
        seed: 2,
        ..Default::default()
    });
    let gt = p.ground_truth.as_ref().unwrap();
    for solver in [GrsrpSolver::Ten, GrsrpSolver::Twenty] {
        for src in [
            R0Source::Gsrp,
            R0Source::Rectified,
            R0Source::Given(gt.rotation_matrix()),
        ] {
            let o = EstimateOptions {
                grsrp_solver: solver,
                r0_source: src,
                ..EstimateOptions::for_method(Method::GrsrpPlus)
            };
            let err = pose_errors(&run(&p, &o).unwrap(), gt);
            assert!(
                err.rotation_error_deg < 1.0 && err.translation_error_deg < 5.0,
                "{solver:?} {src:?} {err:?}"
            );
        }
    }
}

/// At 2.5 rad/s the paper's first-order row rotations are off by pixels at late rows: scored
/// and refined with the exact angular model, the same G-RSRP hypotheses give a less biased
/// pose and a tighter inlier test, so fewer outliers pass and the translation is closer.
#[test]
fn grsrp_on_the_exact_model_beats_the_paper_model_at_fast_rotation() {
    let (mut accepted, mut outliers) = ([0usize; 2], 0usize);
    let mut translation = [0.0; 2];
    for seed in 0..10 {
        let p = pair(SimulationOptions {
            angular_velocity: 2.5,
            outlier_fraction: 0.6,
            seed,
            ..Default::default()
        });
        let gt = p.ground_truth.as_ref().unwrap();
        outliers += gt.inliers.iter().filter(|&&b| !b).count();
        for (k, model) in [GrsrpModel::Paper, GrsrpModel::Exact]
            .into_iter()
            .enumerate()
        {
            let o = EstimateOptions {
                grsrp_model: model,
                ..EstimateOptions::for_method(Method::GrsrpPlus)
            };
            let e = run(&p, &o).unwrap();
            translation[k] += pose_errors(&e, gt).translation_error_deg / 10.0;
            accepted[k] += e
                .inliers
                .iter()
                .zip(&gt.inliers)
                .filter(|(&flagged, &truth)| flagged && !truth)
                .count();
        }
    }
    let rate = accepted.map(|a| a as f64 / outliers as f64);
    eprintln!("outliers accepted {rate:?}, mean translation error {translation:?} deg");
    assert!(rate[1] < rate[0] && rate[1] < 0.02, "{rate:?}");
    assert!(translation[1] < 0.5 * translation[0], "{translation:?}");
}

/// Scenes at 2.5 rad/s where NRSRP's translation sign, chosen by cheirality on the raw
/// bearings, came out reversed (most points triangulate behind a camera until the bearings
/// are undistorted with the estimated rotations). Seeds 12 and 23, also such scenes, now
/// refine to a rotation 10-25° off on their re-classified inliers (a wrong minimum of the 17
/// unknowns, not a sign choice), so they no longer test the sign.
#[test]
fn nrsrp_chooses_the_sign_of_t_on_undistorted_bearings() {
    for seed in [16, 22] {
        let p = pair(SimulationOptions {
            angular_velocity: 2.5,
            seed,
            ..Default::default()
        });
        let e = run(&p, &EstimateOptions::paper(Method::Nrsrp)).unwrap();
        let err = pose_errors(&e, p.ground_truth.as_ref().unwrap());
        assert!(
            err.translation_error_deg < 90.0,
            "seed {seed}: translation error {} deg",
            err.translation_error_deg
        );
    }
}

fn flags(p: &PairFile, method: Method) -> Vec<&'static str> {
    run(p, &EstimateOptions::for_method(method))
        .unwrap()
        .quality
        .flags()
}

#[test]
fn quality_flags_fire_on_a_plane_and_a_one_centimetre_baseline() {
    for seed in 1..4 {
        let plane = pair(SimulationOptions {
            plane_depth: Some(10.0),
            seed,
            ..Default::default()
        });
        // |C2| of about 1 cm.
        let tiny = pair(SimulationOptions {
            translation_std: 0.01 / 3f64.sqrt(),
            seed,
            ..Default::default()
        });
        for m in [Method::Rectified, Method::GrsrpPlus] {
            assert!(
                flags(&plane, m).contains(&"near_planar"),
                "plane, {m}, seed {seed}"
            );
            assert!(
                flags(&tiny, m).contains(&"translation_undetermined"),
                "1 cm, {m}, seed {seed}"
            );
        }
    }
}

#[test]
fn quality_flags_stay_silent_on_the_papers_scenes() {
    for (angular, seed) in [(0.5, 0), (0.5, 1), (1.5, 2), (2.5, 3), (2.5, 4), (2.5, 5)] {
        let p = pair(SimulationOptions {
            angular_velocity: angular,
            seed,
            ..Default::default()
        });
        for m in [
            Method::Nrsrp,
            Method::Grsrp,
            Method::GrsrpPlus,
            Method::Rectified,
        ] {
            let e = run(&p, &EstimateOptions::for_method(m)).unwrap();
            assert!(
                e.quality.flags().is_empty(),
                "{m} at {angular} rad/s, seed {seed}: {:?}",
                e.quality
            );
            assert!(e.quality.inlier_ratio > 0.3 && e.ransac_score.is_finite());
        }
    }
    let few = pair(SimulationOptions {
        points: 12,
        seed: 2,
        ..Default::default()
    });
    assert!(flags(&few, Method::Rectified).contains(&"too_few_inliers"));
}

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

/// `rectified+v` at 2.5 rad/s and 20 m/s with the paper preset: the sign of `(t, d1, d2)`
/// is chosen by cheirality with the cameras' moving centres. Seed 680 was returned mirrored
/// (the rigid test on the row-0 centres flipped `t` and both velocities); seed 606 refined
/// to a turned-around `t` with displacements of several baselines per frame, now rejected
/// ([`VelocityFit::Implausible`]). Over 200 scenes no estimate with velocities is mirrored.
#[test]
fn rectified_v_is_never_mirrored_at_fast_linear_motion() {
    let scene = |seed| {
        pair(SimulationOptions {
            angular_velocity: 2.5,
            linear_velocity: 20.0,
            seed,
            ..Default::default()
        })
    };
    let o = EstimateOptions::paper(Method::RectifiedV);
    let p = scene(680);
    let e = run(&p, &o).unwrap();
    let gt = p.ground_truth.as_ref().unwrap();
    assert!(pose_errors(&e, gt).translation_error_deg < 5.0);
    let d = e.linear_velocity.expect("velocities estimated");
    for (est, truth) in d.iter().zip(&gt.velocity) {
        assert!(est.dot(&Vector3::from(*truth)) > 0.0, "{est:?} {truth:?}");
    }
    let e = run(&scene(606), &o).unwrap();
    assert!(matches!(
        e.velocity_fit,
        Some(VelocityFit::Implausible { .. })
    ));
    assert!(
        pose_errors(&e, scene(606).ground_truth.as_ref().unwrap()).translation_error_deg < 90.0
    );
    let mut mirrored = vec![];
    for seed in 540..740 {
        let p = scene(seed);
        let e = run(&p, &o).unwrap();
        let with_velocity = e.velocity_fit.is_some_and(|f| !f.fell_back());
        if with_velocity
            && pose_errors(&e, p.ground_truth.as_ref().unwrap()).translation_error_deg > 90.0
        {
            mirrored.push(seed);
        }
    }
    assert!(mirrored.is_empty(), "mirrored: {mirrored:?}");
}

/// `nrsrp` with half the matches outliers (20 scenes at 2.5 rad/s, paper preset and
/// defaults): refined on its initialisation's inliers and re-classified with its own model,
/// it is at least as accurate as the `gsrp` initialisation on average. Refined on every
/// match, the outliers dragged it to about 20° mean rotation error.
#[test]
fn nrsrp_is_as_robust_as_its_initialisation_at_half_outliers() {
    for preset in [EstimateOptions::paper, EstimateOptions::for_method] {
        let (mut nrsrp, mut gsrp) = (0.0, 0.0);
        for seed in 0..20 {
            let p = pair(SimulationOptions {
                outlier_fraction: 0.5,
                seed,
                ..Default::default()
            });
            let gt = p.ground_truth.as_ref().unwrap();
            let err = |m| pose_errors(&run(&p, &preset(m)).unwrap(), gt).rotation_error_deg / 20.0;
            nrsrp += err(Method::Nrsrp);
            gsrp += err(Method::Gsrp);
        }
        assert!(
            nrsrp < 10.0 && nrsrp <= gsrp * 1.05,
            "nrsrp {nrsrp}, gsrp {gsrp}"
        );
    }
}

/// With half the matches outliers and the paper preset, `gsrp` returned the twisted pair
/// (the rotation turned 180° about `t`) on 29 of 2000 scenes, e.g. seeds 73, 260 and 297:
/// RANSAC scores the essential matrix, which both rotations share, and the 5-point sample's
/// cheirality vote picked the wrong one. The vote over all inliers decides now; `grsrp`
/// takes `R_0` from it.
#[test]
fn gsrp_never_returns_the_twisted_pair() {
    let mut twisted = vec![];
    for seed in 0..300 {
        let p = pair(SimulationOptions {
            outlier_fraction: 0.5,
            seed,
            ..Default::default()
        });
        let gt = p.ground_truth.as_ref().unwrap();
        for m in [Method::Gsrp, Method::Grsrp] {
            if [73, 260, 297].contains(&seed) || m == Method::Gsrp {
                let e = run(&p, &EstimateOptions::paper(m)).unwrap();
                if pose_errors(&e, gt).rotation_error_deg > 90.0 {
                    twisted.push((m, seed));
                }
            }
        }
    }
    assert!(twisted.is_empty(), "{twisted:?}");
}

#[test]
fn refinement_options_out_of_range_are_refused_naming_the_option() {
    let p = pair(SimulationOptions {
        points: 30,
        ..Default::default()
    });
    let (v1, v2) = p.views().unwrap();
    type Edit = fn(&mut EstimateOptions);
    let edits: [(Edit, &str); 3] = [
        (
            |o| o.refinement.initial_damping = -1.0,
            "refinement.initial_damping",
        ),
        (|o| o.refinement.fd_step = f64::NAN, "refinement.fd_step"),
        (
            |o| o.refinement.cost_tolerance = -1e-3,
            "refinement.cost_tolerance",
        ),
    ];
    for (edit, name) in edits {
        let mut o = EstimateOptions::for_method(Method::Rectified);
        edit(&mut o);
        let e = estimate_relative_pose(&v1, &v2, &p.matches, &o).unwrap_err();
        assert!(matches!(e, EstimateError::InvalidOption { .. }), "{e}");
        assert!(e.to_string().contains(name), "{e}");
    }
}
