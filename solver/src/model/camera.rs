//! Pinhole rolling-shutter camera and a gyro-equipped view.
//!
//! Conventions (ARCHITECTURE §4): pixel `(u, v)` with `v` the image row, row 0 read first.
//! The calibration matrix is `K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]` and the bearing of a
//! pixel is `m = K^-1 [u, v, 1]^T` (so `m.z == 1`, "normalised image coordinates").
//! `readout` is the readout time per row `λ` in seconds per row. A [`View`] adds the gyroscope
//! reading: the camera's angular velocity `ω` in its own axes (x right, y down, z forward;
//! rad/s; extrinsics and bias applied), as a gyroscope reports it, i.e. `Ṙ_wc = R_wc [ω]×`
//! for the camera-to-world rotation, so row `v`'s world-to-camera rotation is
//! `exp(−[v λ ω]×) R_cw(0)` ([`crate::model::rolling_shutter`]). A view may also carry the
//! orientation over its readout integrated from gyro samples ([`RowTrack`]), and the
//! direction of gravity in its camera axes at row 0, from an accelerometer.

use crate::model::gyro_log::RowTrack;
use crate::model::rolling_shutter::row_rotation;
use nalgebra::{Matrix3, Vector2, Vector3};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use thiserror::Error;

/// Largest focal length, principal-point coordinate and image size accepted, pixels:
/// beyond any real sensor, and small enough that products of pixel quantities stay finite.
pub const MAX_PIXELS: f64 = 1e7;
/// Smallest focal length accepted, pixels.
pub const MIN_FOCAL: f64 = 1e-3;
/// Longest frame readout accepted, `height × readout`, seconds.
pub const MAX_FRAME_READOUT: f64 = 10.0;
/// Largest angular velocity accepted, rad/s (consumer gyroscopes saturate near 35 rad/s).
pub const MAX_ANGULAR_VELOCITY: f64 = 100.0;
/// Accepted lengths of a gravity vector: any unit (g, m/s², a unit vector) but neither
/// zero nor absurd.
pub const GRAVITY_NORM_RANGE: std::ops::RangeInclusive<f64> = 1e-6..=1e6;

/// Why a camera or view is invalid. Each variant names the offending parameter.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CameraError {
    /// A focal length is not finite or outside `[MIN_FOCAL, MAX_PIXELS]`.
    #[error("camera focal length `{name}` must be between 1e-3 and 1e7 pixels, got {value}")]
    InvalidFocal {
        /// `"fx"` or `"fy"`.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The principal point is not finite or further than `MAX_PIXELS` from the origin.
    #[error("camera principal point `{name}` must be within ±1e7 pixels, got {value}")]
    InvalidPrincipalPoint {
        /// `"cx"` or `"cy"`.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The readout time per row is negative, not finite, or makes a frame's readout longer
    /// than `MAX_FRAME_READOUT` (0 is a global-shutter camera).
    #[error("camera readout time per row must be >= 0 with height x readout <= 10 s, got {0}")]
    InvalidReadout(f64),
    /// The image size is not finite or outside `(0, MAX_PIXELS]`.
    #[error("camera image size must be positive and at most 1e7 pixels, got {width}x{height}")]
    InvalidSize {
        /// Width in pixels.
        width: f64,
        /// Height in pixels.
        height: f64,
    },
    /// The gyroscope angular velocity is not finite or faster than `MAX_ANGULAR_VELOCITY`.
    #[error("gyro angular velocity must be finite and at most 100 rad/s, got [{0}, {1}, {2}]")]
    InvalidGyro(f64, f64, f64),
    /// The gravity direction is not finite or its length is zero (or absurd).
    #[error("gravity must be a finite vector of non-zero length, got [{0}, {1}, {2}]")]
    InvalidGravity(f64, f64, f64),
}

/// Pinhole rolling-shutter camera: intrinsics `fx, fy, cx, cy` (pixels), image size
/// `width x height` (pixels) and readout time per row `readout = λ` (s/row).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Focal length along u, pixels.
    pub fx: f64,
    /// Focal length along v, pixels.
    pub fy: f64,
    /// Principal point u, pixels.
    pub cx: f64,
    /// Principal point v, pixels.
    pub cy: f64,
    /// Image width, pixels (used by the simulator for visibility).
    pub width: f64,
    /// Image height (number of rows), pixels.
    pub height: f64,
    /// Readout time per row λ, seconds per row.
    pub readout: f64,
}

impl Camera {
    /// The paper's synthetic camera: 1920x1080, f = 640 px, principal point at the image
    /// centre, readout 60 µs per row.
    pub fn paper() -> Self {
        Camera {
            fx: 640.0,
            fy: 640.0,
            cx: 960.0,
            cy: 540.0,
            width: 1920.0,
            height: 1080.0,
            readout: 60e-6,
        }
    }

    /// Check that every parameter is finite and physically plausible: focal lengths in
    /// `[MIN_FOCAL, MAX_PIXELS]`, principal point within `±MAX_PIXELS`, size in
    /// `(0, MAX_PIXELS]`, readout `>= 0` (0: global shutter) with a frame readout of at most
    /// `MAX_FRAME_READOUT`.
    pub fn validate(&self) -> Result<(), CameraError> {
        for (name, value) in [("fx", self.fx), ("fy", self.fy)] {
            if !(MIN_FOCAL..=MAX_PIXELS).contains(&value) {
                return Err(CameraError::InvalidFocal { name, value });
            }
        }
        for (name, value) in [("cx", self.cx), ("cy", self.cy)] {
            if value.is_nan() || value.abs() > MAX_PIXELS {
                return Err(CameraError::InvalidPrincipalPoint { name, value });
            }
        }
        let size_ok = |x: f64| x > 0.0 && x <= MAX_PIXELS;
        if !(size_ok(self.width) && size_ok(self.height)) {
            return Err(CameraError::InvalidSize {
                width: self.width,
                height: self.height,
            });
        }
        if !(self.readout >= 0.0 && self.readout * self.height <= MAX_FRAME_READOUT) {
            return Err(CameraError::InvalidReadout(self.readout));
        }
        Ok(())
    }

    /// Calibration matrix `K` (row-major `[[fx,0,cx],[0,fy,cy],[0,0,1]]`).
    pub fn k(&self) -> Matrix3<f64> {
        Matrix3::new(self.fx, 0.0, self.cx, 0.0, self.fy, self.cy, 0.0, 0.0, 1.0)
    }

    /// Bearing `m = K^-1 [u, v, 1]^T` of pixel `(u, v)`; its third component is 1.
    pub fn bearing(&self, u: f64, v: f64) -> Vector3<f64> {
        Vector3::new((u - self.cx) / self.fx, (v - self.cy) / self.fy, 1.0)
    }

    /// Pixel of a camera-frame point `x` (`K x / x.z`); `None` if `x.z <= 0` or non-finite.
    pub fn project(&self, x: &Vector3<f64>) -> Option<Vector2<f64>> {
        if x.z.is_nan() || x.z <= 0.0 || !x.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Vector2::new(
            self.fx * x.x / x.z + self.cx,
            self.fy * x.y / x.z + self.cy,
        ))
    }

    /// Mean focal length `(fx + fy) / 2`, pixels: converts pixel thresholds to normalised
    /// image coordinates.
    pub fn mean_focal(&self) -> f64 {
        0.5 * (self.fx + self.fy)
    }
}

/// One image of a pair: the camera and its gyroscope reading. `omega = ω` is the camera's
/// angular velocity in its own axes (rad/s, as a gyroscope reports it), constant over the
/// frame or the mean over its readout; `track`, where present, is the orientation over the
/// readout integrated from gyro samples, and then gives the exact row rotations; `gravity`,
/// where present, the direction of gravity in the camera's axes at row 0 (from an
/// accelerometer; any length, either sign as long as both views of a pair use the same:
/// only the direction of the line is used, `R g1 ∥ g2`).
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// The camera that took the image.
    pub camera: Camera,
    /// Angular velocity ω, rad/s, camera axes (a gyroscope's reading).
    pub omega: Vector3<f64>,
    /// Orientation over the readout from gyro samples (`None`: constant `omega`).
    pub track: Option<Arc<RowTrack>>,
    /// Gravity direction in camera axes at row 0 (`None`: no accelerometer).
    pub gravity: Option<Vector3<f64>>,
}

impl View {
    /// A view from a camera and a constant gyro reading `ω` (rad/s, camera axes).
    pub fn new(camera: Camera, omega: Vector3<f64>) -> Self {
        View {
            camera,
            omega,
            track: None,
            gravity: None,
        }
    }

    /// A view whose row rotations come from integrated gyro samples (`track`), with `omega`
    /// the mean rate over the readout (what the G-RSRP solvers use).
    pub fn with_track(camera: Camera, omega: Vector3<f64>, track: RowTrack) -> Self {
        View {
            camera,
            omega,
            track: Some(Arc::new(track)),
            gravity: None,
        }
    }

    /// The same view with a gravity direction `g` (camera axes, row 0).
    pub fn with_gravity(self, g: Vector3<f64>) -> Self {
        View {
            gravity: Some(g),
            ..self
        }
    }

    /// The same view with a constant rate `omega` only (the integrated track dropped; the
    /// gravity kept).
    pub fn constant_rate(&self) -> Self {
        View {
            track: None,
            ..self.clone()
        }
    }

    /// Validate the camera, that `ω` is finite and at most `MAX_ANGULAR_VELOCITY`, and that a
    /// gravity vector is finite with a length in [`GRAVITY_NORM_RANGE`].
    pub fn validate(&self) -> Result<(), CameraError> {
        self.camera.validate()?;
        let speed = self.omega.norm();
        if speed.is_nan() || speed > MAX_ANGULAR_VELOCITY {
            return Err(CameraError::InvalidGyro(
                self.omega.x,
                self.omega.y,
                self.omega.z,
            ));
        }
        if let Some(g) = self.gravity {
            if !GRAVITY_NORM_RANGE.contains(&g.norm()) {
                return Err(CameraError::InvalidGravity(g.x, g.y, g.z));
            }
        }
        Ok(())
    }

    /// Row rotation `Ω(v)` (row-0 camera frame to row-`v` camera frame): from the track where
    /// present, else `exp(−[v λ ω]×)`.
    pub fn row_rotation(&self, v: f64) -> Matrix3<f64> {
        match &self.track {
            Some(track) => track.row_rotation(v, self.camera.readout),
            None => row_rotation(v, self.camera.readout, &self.omega),
        }
    }

    /// The G-RSRP templates' data `w = λ ω̃` (rad/row) with the paper's sign `ω̃ = −ω`: the
    /// paper writes row `v`'s undistortion as `(I − v [w]×) m`, which to first order is
    /// `Ω(v)^T m = exp([v λ ω]×) m`.
    pub fn paper_rate_per_row(&self) -> Vector3<f64> {
        -self.omega * self.camera.readout
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bearing_projection_roundtrip() {
        let cam = Camera::paper();
        let m = cam.bearing(100.0, 900.0);
        assert_eq!(m.z, 1.0);
        let p = cam.project(&(m * 7.0)).unwrap();
        assert!((p.x - 100.0).abs() < 1e-9 && (p.y - 900.0).abs() < 1e-9);
        assert!(cam.project(&Vector3::new(0.0, 0.0, -1.0)).is_none());
    }

    #[test]
    fn validation_rejects_bad_parameters() {
        let mut cam = Camera::paper();
        assert!(cam.validate().is_ok());
        cam.fx = 0.0;
        assert!(matches!(
            cam.validate(),
            Err(CameraError::InvalidFocal { name: "fx", .. })
        ));
        let mut cam = Camera::paper();
        cam.readout = -1.0;
        assert!(matches!(
            cam.validate(),
            Err(CameraError::InvalidReadout(_))
        ));
        let mut cam = Camera::paper();
        cam.cy = f64::NAN;
        assert!(cam.validate().is_err());
        // Finite but implausible values are rejected too, naming the parameter.
        let mut cam = Camera::paper();
        cam.fy = 1e-300;
        assert!(matches!(
            cam.validate(),
            Err(CameraError::InvalidFocal { name: "fy", .. })
        ));
        let mut cam = Camera::paper();
        cam.cx = 1e308;
        assert!(matches!(
            cam.validate(),
            Err(CameraError::InvalidPrincipalPoint { name: "cx", .. })
        ));
        let v = View::new(Camera::paper(), Vector3::new(1.7e308, 0.0, 0.0));
        assert!(matches!(v.validate(), Err(CameraError::InvalidGyro(..))));
        // Readout 0 is a global-shutter camera.
        let mut cam = Camera::paper();
        cam.readout = 0.0;
        assert!(cam.validate().is_ok());
        let v = View::new(Camera::paper(), Vector3::new(f64::INFINITY, 0.0, 0.0));
        assert!(matches!(v.validate(), Err(CameraError::InvalidGyro(..))));
        // Gravity: any finite non-zero length; zero, NaN and infinity are rejected.
        let v = View::new(Camera::paper(), Vector3::zeros());
        assert!(v
            .clone()
            .with_gravity(Vector3::new(0.0, 9.81, 0.0))
            .validate()
            .is_ok());
        for g in [
            Vector3::zeros(),
            Vector3::new(f64::NAN, 1.0, 0.0),
            Vector3::new(0.0, f64::INFINITY, 0.0),
        ] {
            assert!(matches!(
                v.clone().with_gravity(g).validate(),
                Err(CameraError::InvalidGravity(..))
            ));
        }
    }
}
