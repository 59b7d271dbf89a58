//! `rectified`: undistort every bearing by its gyro row rotation, `b = Ω(v)^T m`
//! (row-0 frame), which turns the exact angular model into a global-shutter essential
//! matrix; run the 5-point solver on `b` in RANSAC scored with the exact angular residual
//! (algebraic `b2^T E b1` or Sampson of `m2^T Ω2 E Ω1^T m1`); then refine `(R, t)` by LM on
//! the Sampson error of the exact angular model over the inliers.

use super::noise_fit::{refine_and_classify, Refined};
use super::pose_ransac::{
    decompose_on_inliers, indices, point_data, run, threshold, EssentialRansac, Hypothesis,
};
use super::{Estimate, EstimateError, EstimateOptions, Method};
use crate::estimation::ransac::RansacResult;
use crate::model::camera::View;
use crate::model::epipolar::{PointData, PoseModel, ResidualKind};
use crate::model::matches::Match;

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
        (view1, view2),
        h0,
        res,
        (kind, thr_sq),
        options,
        Method::Rectified,
    ))
}

/// `rectified`'s refinement of a RANSAC result: `(R, t)` by LM on the Sampson error of the
/// exact angular model over the inliers, the inliers re-classified with the threshold
/// `(kind, thr_sq)`, the decomposition of `[t]× R` by cheirality over the inliers.
pub(crate) fn refine_exact(
    data: &PointData,
    (view1, view2): (&View, &View),
    h0: Hypothesis,
    res: RansacResult<Hypothesis>,
    (kind, thr_sq): (ResidualKind, f64),
    options: &EstimateOptions,
    method: Method,
) -> Estimate {
    let Refined {
        h,
        inliers,
        noise_fit,
        iterations,
        cost,
    } = refine_and_classify(
        data,
        (view1, view2),
        (PoseModel::ExactAngular, ResidualKind::Sampson),
        (kind, thr_sq),
        (&h0, &res.inliers),
        options,
    );
    let (rotation, t) = decompose_on_inliers(&h, &data.b1, &data.b2, &indices(&inliers));
    Estimate {
        refinement_iterations: iterations,
        refinement_cost: Some(cost),
        noise_fit,
        ..Estimate::new(method, rotation, t, inliers, res.iterations, res.score.msac)
    }
}

/// Estimate with `rectified`.
///
/// The input is not checked here: it must be what [`super::validate_input`] accepts with
/// `options.method` = `rectified` (valid views, finite pixels that have bearings, at
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
    let data = point_data(view1, view2, matches, &options.robust)?;
    run_on(&data, view1, view2, options)
}
