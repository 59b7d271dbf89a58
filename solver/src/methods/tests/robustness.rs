//! Outliers and fast motion: mirrored and twisted solutions, refinement options.

use super::*;

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
