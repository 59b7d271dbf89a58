//! `rectified`: undistort every bearing by its gyro row rotation, `b = Ω(v)^T m`
//! (row-0 frame), which turns the exact angular model into a global-shutter essential
//! matrix; run the 5-point solver on `b` in RANSAC scored with the exact angular residual
//! (algebraic `b2^T E b1` or Sampson of `m2^T Ω2 E Ω1^T m1`); then refine `(R, t)` by LM on
//! the Sampson error of the exact angular model over the inliers.

use super::pose_ransac::{
    indices, orient, point_data, run, threshold, EssentialRansac, Hypothesis,
};
use super::{Estimate, EstimateError, EstimateOptions, Method};
use crate::camera::View;
use crate::epipolar::{PointData, PoseModel, ResidualKind};
use crate::pair_file::Match;
use crate::ransac::RansacResult;
use crate::refine::{refine_pose, Loss};

/// Run `rectified` on prepared data (inputs already validated).
pub(crate) fn run_on(
    data: &PointData,
    view1: &View,
    view2: &View,
    options: &EstimateOptions,
) -> Result<Estimate, EstimateError> {
    let (kind, thr_sq) = threshold(view1, view2, options.robust.threshold);
    let (h0, res) = run(
        &mut EssentialRansac::exact(data, kind, options),
        options,
        thr_sq,
    )?;
    Ok(refine_exact(
        data,
        h0,
        res,
        (kind, thr_sq),
        options,
        Method::Rectified,
    ))
}

/// `rectified`'s refinement of a RANSAC result: `(R, t)` by LM on the Sampson error of the
/// exact angular model over the inliers, the inliers re-classified with the threshold
/// `(kind, thr_sq)`, the sign of `t` by cheirality.
pub(crate) fn refine_exact(
    data: &PointData,
    h0: Hypothesis,
    res: RansacResult<Hypothesis>,
    (kind, thr_sq): (ResidualKind, f64),
    options: &EstimateOptions,
    method: Method,
) -> Estimate {
    let mut inliers = res.inliers;
    let idx = indices(&inliers);
    let r = refine_pose(
        data,
        &idx,
        PoseModel::ExactAngular,
        ResidualKind::Sampson,
        Loss::Trivial,
        h0.pose(),
        &options.refinement,
    );
    let h = Hypothesis::from_pose(&r.state);
    for (i, f) in inliers.iter_mut().enumerate() {
        let x = data.residual(PoseModel::ExactAngular, kind, i, &h.r, &h.t, &h.e);
        *f = x * x < thr_sq;
    }
    let t = orient(&h.r, &h.t, &data.b1, &data.b2, &indices(&inliers));
    Estimate {
        method,
        rotation: h.r,
        translation: t,
        inliers,
        iterations: res.iterations,
        ransac_score: res.score.msac,
        refinement_iterations: r.iterations,
        refinement_cost: Some(r.cost),
        quality: Default::default(),
        angular_velocity: None,
        linear_velocity: None,
        velocity_fit: None,
    }
}

/// Estimate with `rectified` (inputs already validated by the caller).
pub fn estimate(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
) -> Result<Estimate, EstimateError> {
    let data = point_data(view1, view2, matches, &options.robust);
    run_on(&data, view1, view2, options)
}
