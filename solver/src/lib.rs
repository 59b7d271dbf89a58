//! rspose: gyro-aided rolling-shutter relative pose.
