//! rspose: gyro-aided rolling-shutter relative pose.

// --- estimator side (camera model, geometry, simulator, robust estimation, methods) ---
pub mod camera;
pub mod epipolar;
pub mod evaluate;
pub mod geometry;
pub mod methods;
pub mod minimal;
pub mod pair_file;
pub mod ransac;
pub mod refine;
pub mod rolling_shutter;
pub mod simulate;

pub use methods::{estimate_relative_pose, Estimate, EstimateError, EstimateOptions, Method};
// --- end estimator side ---

pub mod experiment;

// --- numeric runtime used by the emitted solvers ---
pub mod runtime;
