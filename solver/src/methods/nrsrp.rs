//! `nrsrp`: the nonlinear rolling-shutter relative pose of Dai, Li and Kneip (CVPR 2016)
//! with the uniform RS model, as used by the paper: initialise `(R, t)` with `gsrp`, zero
//! velocities, then minimise the generalized epipolar (ray coplanarity) residual over all
//! points by LM with a Cauchy loss, unknowns `R, t, ω1, d1, ω2, d2` (17 parameters; see
//! [`crate::estimation::refine::NrsrpProblem`]). The gyro is not used.

use super::pose_ransac::{indices, orient};
use super::{gsrp, Estimate, EstimateError, EstimateOptions, Method};
use crate::data::pair_file::Match;
use crate::estimation::refine::{refine_nrsrp, LmOptions, NrsrpState, Pose};
use crate::model::camera::View;
use crate::model::epipolar::PointData;
use crate::model::geometry::exp_so3;
use nalgebra::Vector3;

/// Estimate with `nrsrp` (inputs already validated by the caller).
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
    let res = refine_nrsrp(&data, lines, options.nrsrp_cauchy_px / f, start, &lm);
    let s = res.state;
    let r = s.pose.matrix();
    // Cheirality on bearings undistorted with the estimated per-frame rotations: under
    // strong rolling-shutter distortion the raw bearings can put most points behind a
    // camera for the right sign of t.
    let undistort =
        |m: &[Vector3<f64>], v: &[f64], phi: &Vector3<f64>, height: f64| -> Vec<Vector3<f64>> {
            m.iter()
                .zip(v)
                .map(|(m, v)| exp_so3(&(phi * (v / height))).transpose() * m)
                .collect()
        };
    let b1 = undistort(&data.m1, &data.v1, &s.phi[0], lines[0]);
    let b2 = undistort(&data.m2, &data.v2, &s.phi[1], lines[1]);
    let t = orient(&r, &s.pose.translation, &b1, &b2, &indices(&init.inliers));
    let per_frame1 = lines[0] * view1.camera.readout;
    let per_frame2 = lines[1] * view2.camera.readout;
    Ok(Estimate {
        method: Method::Nrsrp,
        rotation: r,
        translation: t,
        inliers: init.inliers,
        iterations: init.iterations,
        ransac_score: init.ransac_score,
        refinement_iterations: res.iterations,
        refinement_cost: Some(res.cost),
        quality: Default::default(),
        // The model's per-frame rotation is `−H λ ω` (see `NrsrpState`); a global-shutter
        // camera (readout 0) has no rates to report.
        angular_velocity: (per_frame1 > 0.0 && per_frame2 > 0.0)
            .then(|| [-s.phi[0] / per_frame1, -s.phi[1] / per_frame2]),
        linear_velocity: (per_frame1 > 0.0 && per_frame2 > 0.0)
            .then(|| [s.delta[0] / per_frame1, s.delta[1] / per_frame2]),
        velocity_fit: None,
        noise_fit: None,
        readout_scale: None,
        gyro_bias: None,
    })
}
