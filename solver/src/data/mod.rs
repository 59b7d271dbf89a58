//! Data in and out: pair files (matches, gyro, gravity, ground truth), atomic writes, the
//! paper's simulator, and G-RSRP instances for `mingen audit --instances-from`.

pub mod atomic_file;
pub mod instances;
pub mod pair_file;
pub mod simulate;
