//! rspose: gyro-aided rolling-shutter relative pose.
pub mod runtime;
