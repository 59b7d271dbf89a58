//! The model: a pinhole camera read row by row while it turns (the gyro) and moves, and
//! the residuals of two views under it.

pub mod camera;
pub mod camera_model;
pub mod epipolar;
pub mod geometry;
pub mod gyro_log;
pub mod matches;
pub mod rolling_shutter;
pub mod sampson_kernel;
