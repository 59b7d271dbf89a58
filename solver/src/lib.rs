//! # rspose — gyro-aided relative pose of rolling-shutter cameras
//!
//! Matches between two rolling-shutter (RS) images plus the gyroscope reading of each view
//! in; relative pose out. Conventions (`docs/ARCHITECTURE.md` §4): pixel (u, v) with v the
//! image row; bearing m = K⁻¹[u, v, 1]ᵀ; the gyro ω is what a gyroscope reports, the
//! camera's angular velocity in its own axes (`Ṙ_wc = R_wc [ω]×`), so the row rotation is
//! Ω(v) = exp(−[v λ ω]×) (row-0 to row-v camera frame); the relative pose refers to row 0
//! of each image, R = R₂R₁ᵀ, t = R₂(C₁ − C₂), |t| = 1.
//!
//! - Minimal solvers: [`generated`] (emitted by `mingen` from `templates/*.mp`) on the
//!   numeric back end of the `mingen-runtime` crate, adapted for the estimator in
//!   [`minimal`].
//! - Model: [`camera`], [`rolling_shutter`], [`geometry`], [`epipolar`].
//! - Estimation: [`ransac`], [`refine`], [`velocity`] (linear velocity with the gyro's
//!   rotations), [`methods`] (one file per method) behind
//!   [`estimate_relative_pose`].
//! - Data and evaluation: [`pair_file`], [`simulate`], [`evaluate`], [`experiment`];
//!   [`instances`] (G-RSRP instances on simulated geometry, for `mingen audit`).

// Minimal solvers (their numeric back end is the mingen-runtime crate).
pub mod generated;
pub mod minimal;

// Camera model and geometry.
pub mod calibrate;
pub mod camera;
pub mod epipolar;
pub mod geometry;
pub mod gyro_log;
pub mod rolling_shutter;

// Robust estimation, refinement and the methods.
pub mod methods;
pub mod ransac;
pub mod refine;
pub mod velocity;

// Data, simulation, evaluation and the paper's experiments.
pub mod atomic_file;
pub mod evaluate;
pub mod experiment;
pub mod instances;
pub mod pair_file;
pub mod simulate;

pub use methods::{estimate_relative_pose, Estimate, EstimateError, EstimateOptions, Method};
