//! Data in and out: pair files (matches, gyro, gravity, ground truth), atomic writes, the
//! paper's simulator, G-RSRP instances for `mingen audit --instances-from`, and the
//! calibration importers (Kalibr, OpenCV) with the YAML subset they read.

pub mod atomic_file;
pub mod instances;
pub mod kalibr;
pub mod mutate;
pub mod opencv_calibration;
pub mod pair_estimate;
pub mod pair_file;
pub mod simulate;
pub mod yaml;
