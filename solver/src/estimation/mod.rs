//! Robust estimation and refinement shared by the methods: RANSAC, Levenberg-Marquardt
//! problems, the linear-velocity model, and calibration from real pairs.

pub mod calibrate;
pub mod ransac;
pub mod refine;
pub mod velocity;
