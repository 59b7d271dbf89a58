//! `grsrp` / `grsrp+`: the paper's method. `R_0` comes from `gsrp` (the paper), `rectified`
//! (the library default)
//! or is given ([`super::R0Source`]); the generated G-RSRP solver (10 or 20 solutions,
//! [`crate::minimal::GrsrpSolver`]) runs on 5-point samples in RANSAC, each solution
//! `R = R_0 exp([a]×)`, `t` (sign by cheirality on the sample), scored with the paper's model
//! `m2^T [t]× (I + v2 [w2]×) R (I - v1 [w1]×) m1` with `w = −λω` (algebraic or Sampson).
//! `grsrp+` then refines `(R, t)` by LM with unit-quaternion tangent steps and unit `t` over
//! the RANSAC inliers: on the paper's algebraic cost with the paper's algebraic threshold,
//! on the row-noise-weighted Sampson residual of the same model with a pixel threshold.

use super::pose_ransac::{indices, orient, point_data, run, threshold, GrsrpRansac, Hypothesis};
use super::{
    gsrp, rectified, Estimate, EstimateError, EstimateOptions, Method, R0Source, Threshold,
};
use crate::camera::View;
use crate::epipolar::{PoseModel, ResidualKind};
use crate::pair_file::Match;
use crate::refine::{refine_pose, Loss};

/// Estimate with `grsrp` (`plus = false`) or `grsrp+` (`plus = true`); inputs already
/// validated by the caller.
pub fn estimate(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
    plus: bool,
) -> Result<Estimate, EstimateError> {
    let data = point_data(view1, view2, matches, &options.robust);
    let r0 = match options.r0_source {
        R0Source::Gsrp => gsrp::run_on(&data, view1, view2, options)?.rotation,
        R0Source::Rectified => rectified::run_on(&data, view1, view2, options)?.rotation,
        R0Source::Given(r) => r,
    };
    let (kind, thr_sq) = threshold(view1, view2, options.robust.threshold);
    let mut est = GrsrpRansac {
        data: &data,
        kind,
        solver: options.grsrp_solver,
        r0,
        lm: options.refinement.clone(),
        sols: Vec::new(),
    };
    let (mut h, res) = run(&mut est, options, thr_sq)?;
    let mut inliers = res.inliers;
    let mut refinement_iterations = 0;
    let mut refinement_cost = None;
    if plus {
        let idx = indices(&inliers);
        // The paper refines the algebraic residual; with a pixel threshold the inliers
        // reach rows a gyro error moves further, and the row-noise-weighted Sampson residual
        // (the same the inliers were chosen with) keeps those from pulling the pose.
        let refine_kind = match options.robust.threshold {
            Threshold::Algebraic(_) => ResidualKind::Algebraic,
            Threshold::SampsonPixels(_) => ResidualKind::Sampson,
        };
        let r = refine_pose(
            &data,
            &idx,
            PoseModel::PaperLinear,
            refine_kind,
            Loss::Trivial,
            h.pose(),
            &options.refinement,
        );
        refinement_iterations = r.iterations;
        refinement_cost = Some(r.cost);
        h = Hypothesis::from_pose(&r.state);
        for (i, f) in inliers.iter_mut().enumerate() {
            let x = data.residual(PoseModel::PaperLinear, kind, i, &h.r, &h.t, &h.e);
            *f = x * x < thr_sq;
        }
    }
    let t = orient(&h.r, &h.t, &data.b1, &data.b2, &indices(&inliers));
    Ok(Estimate {
        method: if plus {
            Method::GrsrpPlus
        } else {
            Method::Grsrp
        },
        rotation: h.r,
        translation: t,
        inliers,
        iterations: res.iterations,
        ransac_score: res.score.msac,
        refinement_iterations,
        refinement_cost,
        quality: Default::default(),
        angular_velocity: None,
        linear_velocity: None,
        velocity_fit: None,
    })
}
