//! Accuracy of an estimate against ground truth (ARCHITECTURE §4 metrics, degrees):
//! rotation `acos((tr(R_gt^T R) - 1) / 2)`, translation `acos(t_gt · t)` for unit vectors
//! (the estimate's sign was already chosen by cheirality; it is not folded here).

use crate::data::pair_file::GroundTruth;
use crate::methods::Estimate;
use crate::model::geometry::{rotation_error_deg, translation_error_deg};
use serde::Serialize;

/// Rotation and translation errors in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PoseErrors {
    /// Rotation error, degrees.
    pub rotation_error_deg: f64,
    /// Translation direction error, degrees.
    pub translation_error_deg: f64,
}

/// Errors of `estimate` against `ground_truth`.
pub fn pose_errors(estimate: &Estimate, ground_truth: &GroundTruth) -> PoseErrors {
    PoseErrors {
        rotation_error_deg: rotation_error_deg(&ground_truth.rotation_matrix(), &estimate.rotation),
        translation_error_deg: translation_error_deg(
            &ground_truth.translation_vector(),
            &estimate.translation,
        ),
    }
}
