//! Large inputs: RANSAC, local optimisation and refinement run on a random subset of at
//! most [`super::RobustOptions::max_points`] matches (a few thousand inliers fix a pose as
//! well as a million), then every match is classified once against the final pose under the
//! method's own model and threshold, in chunks so that no per-match table of the whole input
//! is built.

use super::pose_ransac::{gs_threshold, point_data, threshold};
use super::{Estimate, EstimateOptions, Method};
use crate::camera::View;
use crate::epipolar::PoseModel;
use crate::geometry::skew;
use crate::pair_file::Match;
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
/// estimates, with the global-shutter threshold of its initialisation).
pub(crate) fn classify_all(
    view1: &View,
    view2: &View,
    matches: &[Match],
    est: &Estimate,
    options: &EstimateOptions,
) -> Vec<bool> {
    let robust = &options.robust;
    let (v1, v2, model, (kind, thr_sq)) = match options.method {
        Method::Gsrp => (
            View::new(view1.camera, Vector3::zeros()),
            View::new(view2.camera, Vector3::zeros()),
            PoseModel::GlobalShutter,
            gs_threshold(view1, view2, robust),
        ),
        Method::Rectified => (
            view1.clone(),
            view2.clone(),
            PoseModel::ExactAngular,
            threshold(view1, view2, robust.threshold),
        ),
        Method::Grsrp | Method::GrsrpPlus => (
            view1.clone(),
            view2.clone(),
            PoseModel::PaperLinear,
            threshold(view1, view2, robust.threshold),
        ),
        Method::Nrsrp => {
            let [w1, w2] = est.angular_velocity.unwrap_or([Vector3::zeros(); 2]);
            (
                View::new(view1.camera, w1),
                View::new(view2.camera, w2),
                PoseModel::ExactAngular,
                gs_threshold(view1, view2, robust),
            )
        }
    };
    let (r, t) = (est.rotation, est.translation);
    let e = skew(&t) * r;
    let mut inliers = Vec::with_capacity(matches.len());
    for chunk in matches.chunks(CHUNK) {
        let data = point_data(&v1, &v2, chunk, robust);
        inliers.extend((0..chunk.len()).map(|i| {
            let x = data.residual(model, kind, i, &r, &t, &e);
            x * x < thr_sq
        }));
    }
    inliers
}
