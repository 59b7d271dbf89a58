//! Large inputs: RANSAC, local optimisation and refinement run on a random subset of at
//! most [`super::RobustOptions::max_points`] matches (a few thousand inliers fix a pose as
//! well as a million), then every match is classified once against the final pose under the
//! method's own model and threshold, in chunks so that no per-match table of the whole input
//! is built.

use super::noise_fit::NoiseFit;
use super::pose_ransac::{gs_threshold, point_data, threshold};
use super::{Estimate, EstimateOptions, Method, RobustOptions};
use crate::estimation::refine::{nrsrp_residual, NrsrpState, Pose};
use crate::estimation::velocity::{VelocityModel, VelocityState};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, PoseModel, ResidualKind};
use crate::model::geometry::skew;
use crate::model::matches::Match;
use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Matches classified per chunk.
const CHUNK: usize = 4096;

/// A random subset of `max` of the `n` match indices, in increasing order (seeded).
pub(crate) fn subset_indices(n: usize, max: usize, seed: u64) -> Vec<usize> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed_5ab5e7);
    let mut idx = rand::seq::index::sample(&mut rng, n, max.min(n)).into_vec();
    idx.sort_unstable();
    idx
}

/// The inlier mask of every match under the estimate's pose, with the model and threshold
/// the method classifies with (`nrsrp`: the exact angular model on its own rotation
/// estimates, with the global-shutter threshold of its initialisation; `rectified+v`: the
/// generalised epipolar model with its velocities, unless it fell back to `rectified`), and
/// the gyro noise fitted to the subset where there is one.
pub(crate) fn classify_all(
    view1: &View,
    view2: &View,
    matches: &[Match],
    est: &Estimate,
    options: &EstimateOptions,
) -> Vec<bool> {
    let robust = &options.robust;
    let fit = est.noise_fit;
    if let (Method::RectifiedV, Some(d), Some(row_time)) = (
        options.method,
        est.linear_velocity,
        super::rectified_v::row_times(view1, view2),
    ) {
        let duration = crate::estimation::velocity::reference_duration(view1, view2);
        let state = VelocityState {
            pose: Pose::new(&est.rotation, &est.translation),
            delta: d.map(|d| d * duration),
        };
        let model = VelocityModel::new(&state, row_time);
        let (kind, thr_sq) = threshold(view1, view2, robust.threshold);
        return classify_chunks(view1, view2, matches, robust, fit, |data, i| {
            let x = model.residual(data, kind, i);
            x * x < thr_sq
        });
    }
    let (v1, v2, model, (kind, thr_sq)) = match options.method {
        Method::Gsrp => (
            View::new(view1.camera, Vector3::zeros()),
            View::new(view2.camera, Vector3::zeros()),
            PoseModel::GlobalShutter,
            gs_threshold(view1, view2, robust),
        ),
        Method::Rectified | Method::RectifiedV | Method::GrsrpGravity => (
            view1.clone(),
            view2.clone(),
            PoseModel::ExactAngular,
            threshold(view1, view2, robust.threshold),
        ),
        Method::Grsrp | Method::GrsrpPlus => (
            view1.clone(),
            view2.clone(),
            options.grsrp_model.pose_model(),
            threshold(view1, view2, robust.threshold),
        ),
        Method::Nrsrp => {
            // With the model and test `nrsrp` classified its own matches with: its rotations and
            // displacements over a frame (`NrsrpState`), the Sampson error, the
            // rolling-shutter-aware threshold.
            let lines = [view1.camera.lines(), view2.camera.lines()];
            let frame = [
                lines[0] * view1.camera.readout,
                lines[1] * view2.camera.readout,
            ];
            let [w1, w2] = est.angular_velocity.unwrap_or([Vector3::zeros(); 2]);
            let [d1, d2] = est.linear_velocity.unwrap_or([Vector3::zeros(); 2]);
            let state = NrsrpState {
                pose: Pose::new(&est.rotation, &est.translation),
                phi: [-w1 * frame[0], -w2 * frame[1]],
                delta: [d1 * frame[0], d2 * frame[1]],
            };
            let (_, thr_sq) = threshold(view1, view2, robust.threshold);
            let still1 = View::new(view1.camera, Vector3::zeros());
            let still2 = View::new(view2.camera, Vector3::zeros());
            return classify_chunks(&still1, &still2, matches, robust, None, |data, i| {
                let x = nrsrp_residual(data, lines, &state, ResidualKind::Sampson, i);
                x * x < thr_sq
            });
        }
    };
    let (r, t) = (est.rotation, est.translation);
    let e = skew(&t) * r;
    classify_chunks(&v1, &v2, matches, robust, fit, |data, i| {
        let x = data.residual(model, kind, i, &r, &t, &e);
        x * x < thr_sq
    })
}

/// `inlier(data, i)` for every match, on point data built one chunk at a time (weighted by
/// the fitted noise `fit` where there is one).
fn classify_chunks(
    view1: &View,
    view2: &View,
    matches: &[Match],
    robust: &RobustOptions,
    fit: Option<NoiseFit>,
    inlier: impl Fn(&PointData, usize) -> bool,
) -> Vec<bool> {
    let mut inliers = Vec::with_capacity(matches.len());
    for chunk in matches.chunks(CHUNK) {
        // Every match was observed when the input was validated; a chunk that could not be
        // is classified as outliers.
        let Ok(mut data) = point_data(view1, view2, chunk, robust) else {
            inliers.extend(chunk.iter().map(|_| false));
            continue;
        };
        if let Some(fit) = fit {
            data.set_row_noise(fit.row_noise(view1, view2, robust.pixel_noise));
        }
        inliers.extend((0..chunk.len()).map(|i| inlier(&data, i)));
    }
    inliers
}
