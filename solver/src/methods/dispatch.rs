//! The public entry [`estimate_relative_pose`]: the input checked once, the method run on
//! (a subset of) the matches, the optional post-refinements, the quality report.

use super::error::EstimateError;
use super::estimate::Estimate;
use super::method::Method;
use super::options::{EstimateOptions, R0Source, Threshold};
use super::{
    grsrp, grsrp_gravity, gsrp, nrsrp, post_refine, quality, rectified, rectified_v, subset,
};
use crate::model::camera::View;
use crate::model::matches::{distinct_matches, Match};
use nalgebra::{Matrix3, Vector3};

fn validate_options(o: &EstimateOptions) -> Result<(), EstimateError> {
    let bad = |option, reason: &str| {
        Err(EstimateError::InvalidOption {
            option,
            reason: reason.into(),
        })
    };
    for (name, t) in [
        ("robust.threshold", o.robust.threshold),
        (
            "robust.global_shutter_threshold",
            o.robust.global_shutter_threshold,
        ),
    ] {
        let (Threshold::Algebraic(x) | Threshold::SampsonPixels(x)) = t;
        if !(x.is_finite() && x > 0.0) {
            return bad(name, "must be finite and positive");
        }
    }
    // A negative or non-finite damping or step makes the refinement diverge or stall
    // without an error of its own.
    let lm = &o.refinement;
    for (name, x) in [
        ("refinement.initial_damping", lm.initial_damping),
        ("refinement.fd_step", lm.fd_step),
    ] {
        if !(x.is_finite() && x > 0.0) {
            return bad(name, "must be finite and positive");
        }
    }
    for (name, x) in [
        ("refinement.cost_tolerance", lm.cost_tolerance),
        ("refinement.step_tolerance", lm.step_tolerance),
    ] {
        if !(x.is_finite() && x >= 0.0) {
            return bad(name, "must be finite and non-negative");
        }
    }
    let a = o.robust.rolling_shutter_allowance;
    if !(a.is_finite() && a >= 0.0) {
        return bad(
            "robust.rolling_shutter_allowance",
            "must be finite and non-negative",
        );
    }
    if !(o.robust.success_probability > 0.0 && o.robust.success_probability < 1.0) {
        return bad("robust.success_probability", "must be in (0, 1)");
    }
    if o.robust.max_iterations == 0 {
        return bad("robust.max_iterations", "must be at least 1");
    }
    for (name, x) in [
        ("robust.pixel_noise", o.robust.pixel_noise),
        ("robust.gyro_noise", o.robust.gyro_noise),
        ("robust.gravity_noise_deg", o.robust.gravity_noise_deg),
    ] {
        if !(x.is_finite() && x >= 0.0) {
            return bad(name, "must be finite and non-negative");
        }
    }
    if o.robust.max_points < 20 {
        return bad("robust.max_points", "must be at least 20");
    }
    if !(o.nrsrp_cauchy_px.is_finite() && o.nrsrp_cauchy_px > 0.0) {
        return bad("nrsrp_cauchy_px", "must be finite and positive");
    }
    o.velocity.validate()?;
    if o.method == Method::RectifiedV && o.robust.pixel_noise <= 0.0 {
        return bad(
            "robust.pixel_noise",
            "must be positive for rectified+v (it scales the velocity prior and test)",
        );
    }
    if let R0Source::Given(r) = o.r0_source {
        if !r.iter().all(|x| x.is_finite())
            || (r.transpose() * r - Matrix3::identity()).norm() > 1e-6
            || r.determinant() < 0.0
        {
            return bad("r0_source", "given R_0 is not a rotation");
        }
    }
    if let Some(ro) = &o.readout {
        if matches!(o.method, Method::Gsrp | Method::Nrsrp) {
            return bad(
                "readout",
                "refining the readout needs a gyro-aided method (not gsrp or nrsrp)",
            );
        }
        if let Some((option, reason)) = ro.invalid() {
            return bad(option, reason);
        }
    }
    if let Some(bo) = &o.gyro_bias {
        if matches!(o.method, Method::Gsrp | Method::Nrsrp) {
            return bad(
                "gyro_bias",
                "refining the gyro bias needs a gyro-aided method (not gsrp or nrsrp)",
            );
        }
        if let Some((option, reason)) = bo.invalid() {
            return bad(option, reason);
        }
    }
    Ok(())
}

/// Checks what every method requires of its input: valid views (a gravity direction on
/// both for `grsrp-gravity`), finite pixels that have a bearing, at least
/// [`Method::min_matches`] distinct matches for `options.method`, and valid options.
/// [`estimate_relative_pose`] calls it; a caller of a method's own `estimate` calls it first.
pub fn validate_input(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
) -> Result<(), EstimateError> {
    view1
        .validate()
        .map_err(|source| EstimateError::InvalidCamera { view: 1, source })?;
    view2
        .validate()
        .map_err(|source| EstimateError::InvalidCamera { view: 2, source })?;
    validate_options(options)?;
    if options.method == Method::GrsrpGravity {
        for (k, v) in [view1, view2].into_iter().enumerate() {
            if v.gravity.is_none() {
                return Err(EstimateError::MissingGravity { view: k + 1 });
            }
        }
    }
    for (index, m) in matches.iter().enumerate() {
        for (k, p) in m.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(EstimateError::NonFinitePixel {
                    index,
                    image: k + 1,
                });
            }
            let camera = if k == 0 { &view1.camera } else { &view2.camera };
            if !camera.pixel_in_range(*p) {
                return Err(EstimateError::PixelOutsideImage {
                    index,
                    image: k + 1,
                    u: p[0],
                    v: p[1],
                    width: camera.width,
                    height: camera.height,
                });
            }
        }
    }
    crate::model::epipolar::observe_matches(&view1.camera, &view2.camera, matches)?;
    let method = options.method;
    let needed = method.min_matches(options.essential_solver);
    if matches.len() < needed {
        return Err(EstimateError::TooFewMatches {
            method,
            needed,
            got: matches.len(),
        });
    }
    let distinct = distinct_matches(matches);
    if distinct < needed {
        return Err(EstimateError::Degenerate {
            method,
            distinct,
            needed,
        });
    }
    Ok(())
}

/// Estimate the relative pose of two rolling-shutter views from pixel matches
/// `[[u1, v1], [u2, v2]]` with `options.method` (see the module documentation).
///
/// Errors: invalid camera/gyro, non-finite pixels, pixels without a bearing (where a
/// camera's distortion is not invertible), too few (distinct) matches, invalid
/// options, or no solution (degenerate geometry). Never panics and never
/// returns non-finite poses.
pub fn estimate_relative_pose(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
) -> Result<Estimate, EstimateError> {
    validate_input(view1, view2, matches, options)?;
    let large = matches.len() > options.robust.max_points;
    let subset: Vec<Match>;
    let working = if large {
        let idx = subset::subset_indices(
            matches.len(),
            options.robust.max_points,
            options.robust.seed,
        );
        subset = idx.iter().map(|&i| matches[i]).collect();
        &subset[..]
    } else {
        matches
    };
    let mut est = match options.method {
        Method::Gsrp => gsrp::estimate(view1, view2, working, options),
        Method::Rectified => rectified::estimate(view1, view2, working, options),
        Method::RectifiedV => rectified_v::estimate(view1, view2, working, options),
        Method::GrsrpGravity => grsrp_gravity::estimate(view1, view2, working, options),
        Method::Grsrp => grsrp::estimate(view1, view2, working, options, false),
        Method::GrsrpPlus => grsrp::estimate(view1, view2, working, options, true),
        Method::Nrsrp => nrsrp::estimate(view1, view2, working, options),
    }?;
    let corrected = post_refine::refine(view1, view2, working, &mut est, options);
    let (view1, view2) = match &corrected {
        Some((w1, w2)) => (w1, w2),
        None => (view1, view2),
    };
    if large {
        est.inliers = subset::classify_all(view1, view2, matches, &est, options);
    }
    // The bearings each method works on: gyro-undistorted, undistorted with `nrsrp`'s own
    // rotation estimates, or raw.
    let (b1, b2) = match (options.method, est.angular_velocity) {
        (
            Method::Grsrp
            | Method::GrsrpPlus
            | Method::Rectified
            | Method::RectifiedV
            | Method::GrsrpGravity,
            _,
        ) => (view1.clone(), view2.clone()),
        (_, Some([w1, w2])) => (View::new(view1.camera, w1), View::new(view2.camera, w2)),
        _ => (
            View::new(view1.camera, Vector3::zeros()),
            View::new(view2.camera, Vector3::zeros()),
        ),
    };
    est.quality = quality::assess(
        &b1,
        &b2,
        matches,
        &est.inliers,
        &est.rotation,
        &est.translation,
        &options.quality,
        options.robust.seed,
    );
    if let Some(fit) = est.noise_fit {
        est.quality.flag_gyro_noise(fit.gyro_noise);
    }
    let finite = est.rotation.iter().all(|x| x.is_finite())
        && est.translation.iter().all(|x| x.is_finite())
        && (est.translation.norm() - 1.0).abs() < 1e-6;
    if finite {
        Ok(est)
    } else {
        Err(EstimateError::NoSolution)
    }
}
