//! Robust estimation and refinement shared by the methods: RANSAC, Levenberg-Marquardt
//! problems, the linear-velocity model, one pair's readout time or gyro bias refined with
//! its pose, and calibration from real pairs.

pub mod calibrate;
pub mod gyro_bias;
pub mod ransac;
pub mod readout;
pub mod refine;
pub mod velocity;
