//! # rspose — gyro-aided relative pose of rolling-shutter cameras
//!
//! Matches between two rolling-shutter (RS) images plus the gyroscope reading of each view
//! in; relative pose out. Conventions (`docs/ARCHITECTURE.md` §4): pixel (u, v) with v the
//! image row; bearing m = K⁻¹[u, v, 1]ᵀ; the gyro ω is what a gyroscope reports, the
//! camera's angular velocity in its own axes (`Ṙ_wc = R_wc [ω]×`), so the row rotation is
//! Ω(v) = exp(−[v λ ω]×) (row-0 to row-v camera frame); the relative pose refers to row 0
//! of each image, R = R₂R₁ᵀ, t = R₂(C₁ − C₂), |t| = 1.
//!
//! The modules follow the architecture (`docs/ARCHITECTURE.md` §3):
//!
//! - [`names`]: the name tables of the option enums; [`stats`]: means and medians.
//! - [`generated`] and [`minimal`]: the minimal solvers, emitted by `mingen` from
//!   `templates/*.mp` on the numeric back end of the `mingen-runtime` crate, and their
//!   adapters for the estimator.
//! - [`model`]: the camera, rolling-shutter and gyro model, geometry, the two-view
//!   residuals.
//! - [`estimation`]: RANSAC, nonlinear refinement, linear velocity with the gyro's
//!   rotations, calibration of readout and gyro time offset.
//! - [`methods`]: one file per method behind [`estimate_relative_pose`].
//! - [`data`]: pair files, the simulator, instances for `mingen audit`.
//! - [`experiment`]: the paper's sweeps, the real-data comparison, error measures.

pub mod generated;
pub mod minimal;
pub mod names;
pub mod stats;

pub mod data;
pub mod estimation;
pub mod experiment;
pub mod methods;
pub mod model;

pub use data::pair_file::PairFile;
pub use data::simulate::{simulate, SimulationOptions};
pub use methods::{estimate_relative_pose, Estimate, EstimateError, EstimateOptions, Method};
pub use model::camera::{Camera, View};
pub use model::matches::Match;
