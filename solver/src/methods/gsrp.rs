//! `gsrp`: global-shutter relative pose. The generated 5-point solver (Nistér/Stewénius) on
//! bearings `m = K^-1 [u, v, 1]^T` in RANSAC, scored with the global-shutter epipolar
//! residual `m2^T [t]× R m1` (algebraic or Sampson, per
//! [`super::RobustOptions::global_shutter_threshold`]); the gyro is
//! ignored. With [`super::RobustOptions::final_refinement`] the result is refined by LM on
//! the Sampson error over the inliers. Also the initialiser of `nrsrp` and (by default) the
//! source of `R_0` for `grsrp`.

use super::pose_ransac::{
    decompose_on_inliers, gs_threshold, indices, run, EssentialRansac, Hypothesis,
};
use super::{Estimate, EstimateError, EstimateOptions, Method};
use crate::estimation::refine::{refine_pose, Loss};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, PoseModel, ResidualKind};
use crate::model::matches::Match;

/// Run `gsrp` on prepared data (inputs already validated).
pub(crate) fn run_on(
    data: &PointData,
    view1: &View,
    view2: &View,
    options: &EstimateOptions,
) -> Result<Estimate, EstimateError> {
    let (kind, thr_sq) = gs_threshold(view1, view2, &options.robust);
    let mut est = EssentialRansac::new(data, false, PoseModel::GlobalShutter, kind, options);
    let (mut h, res) = run(&mut est, options, thr_sq)?;
    let mut inliers = res.inliers;
    let mut refinement_iterations = 0;
    let mut refinement_cost = None;
    if options.robust.final_refinement {
        let idx = indices(&inliers);
        let r = refine_pose(
            data,
            &idx,
            PoseModel::GlobalShutter,
            ResidualKind::Sampson,
            Loss::Trivial,
            h.pose(),
            &options.refinement,
        );
        refinement_iterations = r.iterations;
        refinement_cost = Some(r.cost);
        h = Hypothesis::from_pose(&r.state);
        for (i, f) in inliers.iter_mut().enumerate() {
            let x = data.residual(PoseModel::GlobalShutter, kind, i, &h.r, &h.t, &h.e);
            *f = x * x < thr_sq;
        }
    }
    let (rotation, t) = decompose_on_inliers(&h, &data.m1, &data.m2, &indices(&inliers));
    Ok(Estimate {
        refinement_iterations,
        refinement_cost,
        ..Estimate::new(
            Method::Gsrp,
            rotation,
            t,
            inliers,
            res.iterations,
            res.score.msac,
        )
    })
}

/// Estimate with `gsrp`.
///
/// The input is not checked here: it must be what [`super::validate_input`] accepts with
/// `options.method` = `gsrp` (valid views, finite pixels that have bearings, at
/// least [`super::Method::min_matches`] distinct matches, valid options); call that first, or
/// use [`super::estimate_relative_pose`], which checks the input and adds the subset of large
/// inputs, the optional readout and gyro-bias refinements and the quality report. Unchecked
/// input may give an error or a meaningless estimate.
pub fn estimate(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
) -> Result<Estimate, EstimateError> {
    let data = PointData::new(view1, view2, matches)?;
    run_on(&data, view1, view2, options)
}
