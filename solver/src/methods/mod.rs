//! The relative-pose methods (ARCHITECTURE §3) and the public entry [`estimate_relative_pose`].
//!
//! Output convention (ARCHITECTURE §4): `R = R2 R1^T`, `t = R2 (C1 - C2) / |.|` between the row-0
//! poses of the two images, so `x2 = R x1 + t`; the sign of `t` is chosen by cheirality
//! (most inliers triangulating in front of both cameras).
//!
//! | method | file |
//! |---|---|
//! | `gsrp` | [`gsrp`]: global-shutter 5-point RANSAC (gyro ignored) |
//! | `nrsrp` | [`nrsrp`]: Dai et al. uniform RS model by LM, Cauchy loss, init from `gsrp` |
//! | `grsrp`, `grsrp+` | [`grsrp`]: the paper's G-RSRP solver in RANSAC (+ refinement) |
//! | `rectified` | [`rectified`]: gyro-undistorted bearings, 5-point RANSAC, Sampson refinement |
//! | `rectified+v` | [`rectified_v`]: `rectified`, then pose and linear velocities on the generalised epipolar model |
//! | `grsrp-gravity` | [`grsrp_gravity`]: known gravity, 3-point RANSAC on the generated solver, `rectified`'s refinement |

pub mod grsrp;
pub mod grsrp_gravity;
pub mod gsrp;
pub mod noise_fit;
pub mod nrsrp;
mod pose_ransac;
mod post_refine;
pub mod quality;
pub mod rectified;
pub mod rectified_v;
mod subset;

mod dispatch;
mod error;
mod estimate;
mod method;
mod options;

pub use dispatch::estimate_relative_pose;
pub use dispatch::validate_input;
pub use error::EstimateError;
pub use estimate::Estimate;
pub use method::{Method, ParseMethodError};
pub use noise_fit::NoiseFit;
pub use options::{EstimateOptions, GrsrpModel, Preset, R0Source, RobustOptions, Threshold};
pub use quality::{Quality, QualityOptions};
pub use rectified_v::{VelocityFit, VelocityOptions};

#[cfg(test)]
mod tests;
