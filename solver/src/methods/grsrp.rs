//! `grsrp` / `grsrp+`: the paper's method. `R_0` comes from `gsrp` (the paper), `rectified`
//! (the library default)
//! or is given ([`super::R0Source`]); the generated G-RSRP solver (10 or 20 solutions,
//! [`crate::minimal::GrsrpSolver`]) runs on 5-point samples in RANSAC, each solution
//! `R = R_0 exp([a]×)`, `t` (sign by cheirality on the sample). The hypotheses are scored,
//! locally optimised and (`grsrp+`) refined with [`super::GrsrpModel`]: the paper's model
//! `m2^T [t]× (I + v2 [w2]×) R (I - v1 [w1]×) m1` with `w = −λω` (the paper preset) or the
//! exact angular model it linearises (the default), algebraic or Sampson.
//! `grsrp+` refines `(R, t)` by LM with unit-quaternion tangent steps and unit `t` over
//! the RANSAC inliers: on the algebraic cost with the paper's algebraic threshold,
//! on the row-noise-weighted Sampson residual with a pixel threshold.

use super::noise_fit::{final_inliers, refine_and_classify};
use super::pose_ransac::{indices, orient, point_data, run, threshold, GrsrpRansac, PoseScorer};
use super::{
    gsrp, rectified, Estimate, EstimateError, EstimateOptions, Method, R0Source, Threshold,
};
use crate::model::camera::View;
use crate::model::epipolar::ResidualKind;
use crate::model::matches::Match;

/// Estimate with `grsrp` (`plus = false`) or `grsrp+` (`plus = true`).
///
/// The input is not checked here: it must be what [`super::validate_input`] accepts with
/// `options.method` = `grsrp` or `grsrp+` (valid views, finite pixels that have bearings, at
/// least [`super::Method::min_matches`] distinct matches, valid options); call that first, or
/// use [`super::estimate_relative_pose`], which checks the input and adds the subset of large
/// inputs, the optional readout and gyro-bias refinements and the quality report. Unchecked
/// input may give an error or a meaningless estimate.
pub fn estimate(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
    plus: bool,
) -> Result<Estimate, EstimateError> {
    let data = point_data(view1, view2, matches, &options.robust)?;
    let r0 = match options.r0_source {
        R0Source::Gsrp => gsrp::run_on(&data, view1, view2, options)?.rotation,
        R0Source::Rectified => rectified::run_on(&data, view1, view2, options)?.rotation,
        R0Source::Given(r) => r,
    };
    let (kind, thr_sq) = threshold(view1, view2, options.robust.threshold);
    let model = options.grsrp_model.pose_model();
    let mut est = GrsrpRansac {
        scorer: PoseScorer {
            data: &data,
            model,
            kind,
            lm: options.refinement.clone(),
        },
        solver: options.grsrp_solver,
        r0,
        sols: Vec::new(),
    };
    let (mut h, res) = run(&mut est, options, thr_sq)?;
    let mut refinement_iterations = 0;
    let mut refinement_cost = None;
    let (inliers, noise_fit) = if plus {
        // The paper refines the algebraic residual; with a pixel threshold the inliers
        // reach rows a gyro error moves further, and the row-noise-weighted Sampson residual
        // (the same the inliers were chosen with) keeps those from pulling the pose.
        let refine_kind = match options.robust.threshold {
            Threshold::Algebraic(_) => ResidualKind::Algebraic,
            Threshold::SampsonPixels(_) => ResidualKind::Sampson,
        };
        let r = refine_and_classify(
            &data,
            (view1, view2),
            (model, refine_kind),
            (kind, thr_sq),
            (&h, &res.inliers),
            options,
        );
        refinement_iterations = r.iterations;
        refinement_cost = Some(r.cost);
        h = r.h;
        (r.inliers, r.noise_fit)
    } else if options.robust.fit_gyro_noise {
        final_inliers(
            &data,
            (view1, view2),
            model,
            (kind, thr_sq),
            &h,
            &options.robust,
        )
    } else {
        (res.inliers, None)
    };
    let t = orient(&h.r, &h.t, &data.b1, &data.b2, &indices(&inliers));
    let method = if plus {
        Method::GrsrpPlus
    } else {
        Method::Grsrp
    };
    Ok(Estimate {
        refinement_iterations,
        refinement_cost,
        noise_fit,
        ..Estimate::new(method, h.r, t, inliers, res.iterations, res.score.msac)
    })
}
