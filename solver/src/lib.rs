//! rspose: gyro-aided rolling-shutter relative pose.

// --- estimator side (camera model, geometry, simulator, robust estimation, methods) ---
pub mod camera;
pub mod epipolar;
pub mod geometry;
pub mod pair_file;
pub mod ransac;
pub mod refine;
pub mod rolling_shutter;
pub mod simulate;
// --- end estimator side ---
