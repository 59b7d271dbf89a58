//! Why [`estimate_relative_pose`](super::estimate_relative_pose) gave no estimate.

use super::method::Method;
use crate::model::camera::CameraError;
use thiserror::Error;

/// Why no estimate was produced.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EstimateError {
    /// A camera or gyro reading is invalid.
    #[error("invalid view {view}: {source}")]
    InvalidCamera {
        /// 1 or 2.
        view: usize,
        /// What is wrong.
        source: CameraError,
    },
    /// A pixel lies where its camera's distortion is not invertible (or its undistortion
    /// does not converge), so it has no bearing.
    #[error("match {index}: image {image}'s pixel has no bearing: {source}")]
    Unobservable {
        /// Index of the match.
        index: usize,
        /// 1 or 2.
        image: usize,
        /// Why ([`CameraError::NotInvertible`] or [`CameraError::NotConverged`]).
        source: CameraError,
    },
    /// A pixel coordinate is NaN or infinite.
    #[error("match {index}: non-finite pixel coordinate in image {image}")]
    NonFinitePixel {
        /// Index of the match.
        index: usize,
        /// 1 or 2.
        image: usize,
    },
    /// A pixel lies further outside its image than
    /// [`OUTSIDE_IMAGE_MARGIN`](crate::model::camera::OUTSIDE_IMAGE_MARGIN) times its size
    /// (coordinates in another frame or unit).
    #[error("match {index}: pixel ({u:?}, {v:?}) in image {image} is far outside the image ({width:?}x{height:?}; at most one image size beyond each side)")]
    PixelOutsideImage {
        /// Index of the match.
        index: usize,
        /// 1 or 2.
        image: usize,
        /// Column.
        u: f64,
        /// Row.
        v: f64,
        /// The image's width, pixels.
        width: f64,
        /// The image's height, pixels.
        height: f64,
    },
    /// Too few matches for the method.
    #[error("method {method} needs at least {needed} matches, got {got}")]
    TooFewMatches {
        /// The method.
        method: Method,
        /// Matches needed.
        needed: usize,
        /// Matches given.
        got: usize,
    },
    /// Too few distinct matches (e.g. only duplicates).
    #[error("degenerate input: only {distinct} distinct matches, method {method} needs {needed}")]
    Degenerate {
        /// The method.
        method: Method,
        /// Distinct matches.
        distinct: usize,
        /// Matches needed.
        needed: usize,
    },
    /// No model was found (degenerate geometry or every sample failed).
    #[error("no solution found")]
    NoSolution,
    /// The method needs a gravity direction on both views ([`View::gravity`](crate::model::camera::View::gravity)).
    #[error(
        "method grsrp-gravity needs the gravity direction of both views; view {view} has none"
    )]
    MissingGravity {
        /// 1 or 2.
        view: usize,
    },
    /// Invalid option value.
    #[error("invalid option `{option}`: {reason}")]
    InvalidOption {
        /// Option name.
        option: &'static str,
        /// What is wrong.
        reason: String,
    },
}

impl From<crate::model::epipolar::UnobservableMatch> for EstimateError {
    fn from(e: crate::model::epipolar::UnobservableMatch) -> Self {
        EstimateError::Unobservable {
            index: e.index,
            image: e.image,
            source: e.source,
        }
    }
}
