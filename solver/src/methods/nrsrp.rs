//! `nrsrp`: the nonlinear rolling-shutter relative pose of Dai, Li and Kneip (CVPR 2016)
//! with the uniform RS model, as used by the paper: initialise `(R, t)` with `gsrp`, zero
//! velocities, then minimise the generalized epipolar (ray coplanarity) residual by LM with a
//! Cauchy loss, unknowns `R, t, ω1, d1, ω2, d2` (17 parameters; see
//! [`crate::estimation::refine::NrsrpProblem`]). The gyro is not used.
//!
//! The refinement runs on the initialisation's inliers only, then the matches are
//! re-classified with the refined model (the rolling-shutter-aware threshold,
//! [`super::RobustOptions::threshold`], on [`crate::estimation::refine::nrsrp_residual`]) and the refinement repeated
//! until the inliers settle: a Cauchy loss over every match bounds each outlier's pull but
//! not their number, and with a third or more outliers their sum drags the 17 unknowns far
//! from the initialisation.

use super::pose_ransac::{indices, threshold};
use super::{gsrp, Estimate, EstimateError, EstimateOptions, Method};
use crate::estimation::refine::{
    nrsrp_cheirality, nrsrp_residual, refine_nrsrp, LmOptions, NrsrpState, Pose,
};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, ResidualKind};
use crate::model::matches::Match;
use nalgebra::Vector3;

/// Refine / re-classify rounds at most: the inliers settle within two or three.
const ROUNDS: usize = 4;

/// Estimate with `nrsrp`.
///
/// The input is not checked here: it must be what [`super::validate_input`] accepts with
/// `options.method` = `nrsrp` (valid views, finite pixels that have bearings, at
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
    // No gyro: bearings and line coordinates only.
    let still1 = View::new(view1.camera, Vector3::zeros());
    let still2 = View::new(view2.camera, Vector3::zeros());
    let data = PointData::new(&still1, &still2, matches)?;
    // The original views only size the initialisation's inlier threshold
    // (`RobustOptions::rolling_shutter_allowance`); the estimation itself uses no gyro.
    let init = gsrp::run_on(&data, view1, view2, options)?;
    let lines = [view1.camera.lines(), view2.camera.lines()];
    let f = 0.5 * (view1.camera.mean_focal() + view2.camera.mean_focal());
    let start = NrsrpState {
        pose: Pose::new(&init.rotation, &init.translation),
        phi: [Vector3::zeros(); 2],
        delta: [Vector3::zeros(); 2],
    };
    let lm = LmOptions {
        max_iterations: options.refinement.max_iterations.max(100),
        ..options.refinement.clone()
    };
    let cauchy = options.nrsrp_cauchy_px / f;
    // Always on the Sampson error: the algebraic residual scales with the distance between
    // the rays' centres, which the fitted displacements can shrink for some rows until
    // every match there passes. An algebraic threshold is applied as the same distance
    // in normalised image units (what it bounds for a unit epipolar-line normal).
    let (_, thr_sq) = threshold(view1, view2, options.robust.threshold);
    let needed = Method::Nrsrp.min_matches(options.essential_solver);
    let sampson =
        |st: &NrsrpState, i: usize| nrsrp_residual(&data, lines, st, ResidualKind::Sampson, i);
    // MSAC cost over every match (non-finite residuals count as outliers).
    let msac = |st: &NrsrpState| -> f64 {
        (0..data.len())
            .map(|i| {
                let x = sampson(st, i);
                let x = x * x;
                if x < thr_sq {
                    x
                } else {
                    thr_sq
                }
            })
            .sum()
    };
    let mut idx = indices(&init.inliers);
    let mut s = start;
    let mut best = msac(&start);
    let (mut iterations, mut cost) = (0, None);
    for _ in 0..ROUNDS {
        if idx.len() < needed {
            // Too few for the 17 unknowns: the initialisation stands.
            break;
        }
        // Each round starts from the initialisation: a state fitted to the previous inlier
        // set carries that set's errors into the next.
        let res = refine_nrsrp(&data, &idx, lines, cauchy, start, &lm);
        iterations += res.iterations;
        // 17 unknowns fitted to a few dozen matches can leave the scene (a wrong basin that
        // explains its own points at the cost of the others): a state is kept only if it
        // explains all the matches better, by MSAC, than the best state so far (at first the
        // initialisation), so the result is never worse than the initialisation by that
        // measure.
        let c = msac(&res.state);
        if c >= best {
            break;
        }
        (s, best, cost) = (res.state, c, Some(res.cost));
        let next: Vec<usize> = (0..data.len())
            .filter(|&i| {
                let x = sampson(&s, i);
                x * x < thr_sq
            })
            .collect();
        // A model that keeps fewer matches than the minimum has lost the scene: keep the
        // inliers it was refined on.
        if next == idx || next.len() < needed {
            break;
        }
        idx = next;
    }
    let r = s.pose.matrix();
    // Cheirality on bearings undistorted with the estimated rotations: under strong
    // rolling-shutter distortion the raw bearings can put most points behind a camera for
    // the right sign of t. The centres stay at row 0: the displacements have no prior here
    // and spurious ones (a still camera fitted with a baseline per frame) can turn the
    // vote. The model is homogeneous in (t, δ1, δ2), so the three change sign together.
    let rigid = NrsrpState {
        delta: [Vector3::zeros(); 2],
        ..s
    };
    let (front, behind) = nrsrp_cheirality(&data, lines, &rigid, &idx);
    let sign = if behind > front { -1.0 } else { 1.0 };
    let t = s.pose.translation * sign;
    let delta = s.delta.map(|d| d * sign);
    let mut inliers = vec![false; data.len()];
    for &i in &idx {
        inliers[i] = true;
    }
    let per_frame1 = lines[0] * view1.camera.readout;
    let per_frame2 = lines[1] * view2.camera.readout;
    Ok(Estimate {
        refinement_iterations: iterations,
        refinement_cost: cost,
        // The model's per-frame rotation is `−H λ ω` (see `NrsrpState`); a global-shutter
        // camera (readout 0) has no rates to report.
        angular_velocity: (per_frame1 > 0.0 && per_frame2 > 0.0)
            .then(|| [-s.phi[0] / per_frame1, -s.phi[1] / per_frame2]),
        linear_velocity: (per_frame1 > 0.0 && per_frame2 > 0.0)
            .then(|| [delta[0] / per_frame1, delta[1] / per_frame2]),
        ..Estimate::new(
            Method::Nrsrp,
            r,
            t,
            inliers,
            init.iterations,
            init.ransac_score,
        )
    })
}
