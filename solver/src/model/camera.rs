//! Rolling-shutter camera (a COLMAP camera model read line by line) and a gyro-equipped view.
//!
//! Conventions (ARCHITECTURE §4): pixel `(u, v)` with `u` the column and `v` the row, pixel
//! centres at integer coordinates. The camera model ([`CameraModel`], COLMAP's names,
//! parameter orders and formulas, [`crate::model::camera_model`]) maps a camera-frame point
//! to a pixel; a pixel's **bearing** is its undistorted normalised coordinates
//! `m = (x, y, 1)` ([`Camera::undistort_bearing`]; for a pinhole `m = K^-1 [u, v, 1]^T`).
//! Its **time** comes from its raw (distorted) sensor coordinate: the *line coordinate*
//! `l` along the readout direction ([`ReadoutDirection`], [`Camera::readout_line`]; for the
//! default `top_to_bottom` `l = v`), read `l λ` seconds after line 0, with
//! `readout = λ` in seconds per line. A [`View`] adds the gyroscope reading: the camera's
//! angular velocity `ω` in its own axes (x right, y down, z forward; rad/s; extrinsics and
//! bias applied), as a gyroscope reports it, i.e. `Ṙ_wc = R_wc [ω]×` for the
//! camera-to-world rotation, so line `l`'s world-to-camera rotation is
//! `exp(−[l λ ω]×) R_cw(0)` ([`crate::model::rolling_shutter`]). A view may also carry the
//! orientation over its readout integrated from gyro samples ([`RowTrack`]), and the
//! direction of gravity in its camera axes at line 0, from an accelerometer.

use crate::model::camera_model::{self, CameraModel, UndistortFailure};
pub use crate::model::gyro_log::MAX_ANGULAR_VELOCITY;
use crate::model::gyro_log::{plausible_rate, row_rotation, RowTrack};
use nalgebra::{Matrix3, Vector2, Vector3};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use thiserror::Error;

/// Largest focal length, principal-point coordinate and image size accepted, pixels:
/// beyond any real sensor, and small enough that products of pixel quantities stay finite.
pub const MAX_PIXELS: f64 = 1e7;
/// Smallest focal length accepted, pixels.
pub const MIN_FOCAL: f64 = 1e-3;
/// Smallest image width or height, pixels: an image narrower than one pixel has no pixels.
pub const MIN_IMAGE_SIZE: f64 = 1.0;
/// How far the principal point and a match's pixels may lie outside the image, as a
/// multiple of its width (for `u`, `cx`) or height (for `v`, `cy`): lenient enough for a
/// decentred lens or a keypoint refined just past the border, and it refuses coordinates
/// in another frame (shifted, swapped or in other units).
pub const OUTSIDE_IMAGE_MARGIN: f64 = 1.0;
/// Largest magnitude of a distortion coefficient accepted (finite, and small enough that
/// the distortion polynomials stay finite over any image).
pub const MAX_DISTORTION: f64 = 1e6;
/// Longest frame readout accepted, `lines × readout`, seconds.
pub const MAX_FRAME_READOUT: f64 = 10.0;
/// Accepted lengths of a gravity vector: any unit (g, m/s², a unit vector) but neither
/// zero nor absurd.
pub const GRAVITY_NORM_RANGE: std::ops::RangeInclusive<f64> = 1e-6..=1e6;

/// Why a camera or view is invalid, or a pixel has no bearing. Each variant names the
/// offending parameter, model or pixel.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CameraError {
    /// A focal length is not finite or outside `[MIN_FOCAL, MAX_PIXELS]`.
    #[error("camera focal length `{name}` must be between 1e-3 and 1e7 pixels, got {value:?}")]
    InvalidFocal {
        /// `"f"`, `"fx"` or `"fy"`.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A single-focal model (`SIMPLE_PINHOLE`, `SIMPLE_RADIAL`, `RADIAL`) with `fx != fy`.
    #[error("camera model {model} has one focal length `f`, but fx = {fx:?} and fy = {fy:?}")]
    UnequalFocals {
        /// The model's name.
        model: &'static str,
        /// `fx`.
        fx: f64,
        /// `fy`.
        fy: f64,
    },
    /// The principal point is not finite, further than `MAX_PIXELS` from the origin, or
    /// further outside the image than [`OUTSIDE_IMAGE_MARGIN`] times its size.
    #[error("camera principal point `{name}` must be within the image extended by its size on each side ({min:?} to {max:?} pixels), got {value:?}")]
    InvalidPrincipalPoint {
        /// `"cx"` or `"cy"`.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The smallest accepted value.
        min: f64,
        /// The largest accepted value.
        max: f64,
    },
    /// A distortion coefficient is not finite or larger than `MAX_DISTORTION` in magnitude.
    #[error(
        "camera distortion coefficient `{name}` must be finite and within ±1e6, got {value:?}"
    )]
    InvalidDistortion {
        /// COLMAP's name of the coefficient, e.g. `"k1"` or `"p2"`.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The readout time per line is negative, not finite, or makes a frame's readout longer
    /// than `MAX_FRAME_READOUT` (0 is a global-shutter camera).
    #[error("camera readout time per line must be >= 0 with lines x readout <= 10 s, got {0:?}")]
    InvalidReadout(f64),
    /// The image size is not finite or outside `[MIN_IMAGE_SIZE, MAX_PIXELS]`.
    #[error("camera image size must be between 1 and 1e7 pixels, got {width:?}x{height:?}")]
    InvalidSize {
        /// Width in pixels.
        width: f64,
        /// Height in pixels.
        height: f64,
    },
    /// A camera object's `model` is not one of COLMAP's models this crate implements.
    #[error("unknown camera model `{0}` (expected one of SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, OPENCV_FISHEYE, FULL_OPENCV)")]
    UnknownModel(String),
    /// A camera object's `params` has the wrong length for its model.
    #[error("camera model {model} takes {expected} params [{names}], got {got}")]
    WrongParamCount {
        /// The model's name.
        model: &'static str,
        /// Its number of parameters.
        expected: usize,
        /// Their names, comma-separated, in COLMAP's order.
        names: String,
        /// The number given.
        got: usize,
    },
    /// A camera object mixes or lacks keys of its two forms (`model` with `params`, or the
    /// pinhole `fx, fy, cx, cy`).
    #[error("camera: {0}")]
    InvalidObject(String),
    /// A pixel lies where the camera's distortion is not invertible (a fisheye's or a
    /// polynomial model's fold, beyond the radius where the distortion stops increasing),
    /// so it has no unique bearing.
    #[error("pixel ({u:?}, {v:?}) lies where the {model} distortion is not invertible")]
    NotInvertible {
        /// The model's name.
        model: &'static str,
        /// Pixel column.
        u: f64,
        /// Pixel row.
        v: f64,
    },
    /// Newton's iteration undistorting a pixel did not reach its tolerance.
    #[error("undistorting pixel ({u:?}, {v:?}) with the {model} model did not converge")]
    NotConverged {
        /// The model's name.
        model: &'static str,
        /// Pixel column.
        u: f64,
        /// Pixel row.
        v: f64,
    },
    /// The gyroscope angular velocity is not finite or faster than `MAX_ANGULAR_VELOCITY`.
    #[error(
        "gyro angular velocity must be finite and at most {max} rad/s, got [{0}, {1}, {2}]",
        max = MAX_ANGULAR_VELOCITY
    )]
    InvalidGyro(f64, f64, f64),
    /// The gravity direction is not finite or its length is zero (or absurd).
    #[error("gravity must be a finite vector of non-zero length, got [{0:?}, {1:?}, {2:?}]")]
    InvalidGravity(f64, f64, f64),
}

/// The order in which a rolling-shutter sensor reads its lines. The *line coordinate* of a
/// raw (distorted) pixel `(u, v)` is its distance in pixels from the centre of the first
/// line read (pixel centres at integer coordinates, so the first line read is line 0 in
/// every direction):
///
/// | direction | line coordinate `l` | lines |
/// |---|---|---|
/// | `top_to_bottom` (default) | `v` | `height` |
/// | `bottom_to_top` | `height − 1 − v` | `height` |
/// | `left_to_right` | `u` | `width` |
/// | `right_to_left` | `width − 1 − u` | `width` |
///
/// The line is read `l λ` seconds after line 0 (`λ = readout`, seconds per line).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReadoutDirection {
    /// Rows from the top (`v = 0`) down: `l = v`.
    #[default]
    TopToBottom,
    /// Rows from the bottom up: `l = height − 1 − v`.
    BottomToTop,
    /// Columns from the left (`u = 0`): `l = u`.
    LeftToRight,
    /// Columns from the right: `l = width − 1 − u`.
    RightToLeft,
}

impl ReadoutDirection {
    /// Every direction.
    pub const ALL: [ReadoutDirection; 4] = [
        ReadoutDirection::TopToBottom,
        ReadoutDirection::BottomToTop,
        ReadoutDirection::LeftToRight,
        ReadoutDirection::RightToLeft,
    ];

    /// The name used in the pair file, e.g. `"top_to_bottom"`.
    pub fn name(self) -> &'static str {
        match self {
            ReadoutDirection::TopToBottom => "top_to_bottom",
            ReadoutDirection::BottomToTop => "bottom_to_top",
            ReadoutDirection::LeftToRight => "left_to_right",
            ReadoutDirection::RightToLeft => "right_to_left",
        }
    }

    /// The direction named `name` (as [`name`](Self::name) writes it).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|d| d.name() == name)
    }

    /// Whether lines are columns (`left_to_right`, `right_to_left`).
    pub fn is_horizontal(self) -> bool {
        matches!(
            self,
            ReadoutDirection::LeftToRight | ReadoutDirection::RightToLeft
        )
    }
}

/// A pixel as the estimator uses it: its bearing and the line coordinate that dates it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    /// Undistorted normalised coordinates `(x, y, 1)` ([`Camera::undistort_bearing`]).
    pub bearing: Vector3<f64>,
    /// Line coordinate of the raw pixel ([`Camera::readout_line`]), pixels.
    pub line: f64,
}

/// Rolling-shutter camera: a COLMAP camera model with focal lengths `fx, fy`, principal
/// point `cx, cy` (pixels) and distortion coefficients, image size `width x height`
/// (pixels), readout time per line `readout = λ` (s/line) and the readout direction.
///
/// In JSON (see `docs/PAIR_FILE.md`) a camera is either COLMAP's object
/// `{"model": "OPENCV", "width": W, "height": H, "params": [...], "readout": λ,
/// "readout_direction": "top_to_bottom"}` or the pinhole short form
/// `{"fx", "fy", "cx", "cy", "width", "height", "readout"}` (`PINHOLE`); unknown keys are
/// refused with their name. A `PINHOLE` camera read from top to bottom is written in the
/// short form, every other camera in COLMAP's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "CameraJson", into = "CameraJson")]
pub struct Camera {
    /// The camera model (COLMAP's).
    pub model: CameraModel,
    /// Focal length along u, pixels (`f` of the single-focal models, which need `fy = fx`).
    pub fx: f64,
    /// Focal length along v, pixels.
    pub fy: f64,
    /// Principal point u, pixels.
    pub cx: f64,
    /// Principal point v, pixels.
    pub cy: f64,
    /// The model's distortion coefficients, COLMAP's parameters after the focal length(s)
    /// and principal point in COLMAP's order (e.g. `k1, k2, p1, p2` for `OPENCV`),
    /// zero-padded.
    pub distortion: [f64; 8],
    /// Image width, pixels.
    pub width: f64,
    /// Image height, pixels.
    pub height: f64,
    /// Readout time per line λ, seconds per line.
    pub readout: f64,
    /// The order in which lines are read.
    pub readout_direction: ReadoutDirection,
}

/// A camera object as JSON holds it (both forms; see [`Camera`]).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraJson {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    model: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    fx: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    fy: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cx: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cy: Option<f64>,
    width: f64,
    height: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    params: Option<Vec<f64>>,
    readout: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    readout_direction: Option<ReadoutDirection>,
}

impl TryFrom<CameraJson> for Camera {
    type Error = CameraError;

    fn try_from(j: CameraJson) -> Result<Self, CameraError> {
        let direction = j.readout_direction.unwrap_or_default();
        let legacy = [("fx", j.fx), ("fy", j.fy), ("cx", j.cx), ("cy", j.cy)];
        match (j.model, j.params) {
            (Some(name), Some(params)) => {
                if let Some((key, _)) = legacy.iter().find(|(_, v)| v.is_some()) {
                    return Err(CameraError::InvalidObject(format!(
                        "`{key}` belongs to the pinhole short form; with `model` give every parameter in `params`"
                    )));
                }
                let model = CameraModel::from_name(&name).ok_or(CameraError::UnknownModel(name))?;
                Camera::from_params(model, j.width, j.height, &params, j.readout, direction)
            }
            (Some(_), None) => Err(CameraError::InvalidObject(
                "`model` needs its `params`".into(),
            )),
            (None, Some(_)) => Err(CameraError::InvalidObject(
                "`params` needs its `model` (e.g. \"OPENCV\")".into(),
            )),
            (None, None) => {
                if let Some((key, _)) = legacy.iter().find(|(_, v)| v.is_none()) {
                    return Err(CameraError::InvalidObject(format!(
                        "missing field `{key}` (give `fx, fy, cx, cy`, or `model` and `params`)"
                    )));
                }
                let [fx, fy, cx, cy] = legacy.map(|(_, v)| v.unwrap_or_default());
                Ok(Camera {
                    readout_direction: direction,
                    ..Camera::pinhole(fx, fy, cx, cy, j.width, j.height, j.readout)
                })
            }
        }
    }
}

impl From<Camera> for CameraJson {
    fn from(c: Camera) -> Self {
        let short =
            c.model == CameraModel::Pinhole && c.readout_direction == ReadoutDirection::TopToBottom;
        CameraJson {
            model: (!short).then(|| c.model.name().to_string()),
            fx: short.then_some(c.fx),
            fy: short.then_some(c.fy),
            cx: short.then_some(c.cx),
            cy: short.then_some(c.cy),
            width: c.width,
            height: c.height,
            params: (!short).then(|| c.params()),
            readout: c.readout,
            readout_direction: (!short).then_some(c.readout_direction),
        }
    }
}

impl Camera {
    /// The paper's synthetic camera: a 1920x1080 pinhole, f = 640 px, principal point at
    /// the image centre, readout 60 µs per row from top to bottom.
    pub fn paper() -> Self {
        Camera::pinhole(640.0, 640.0, 960.0, 540.0, 1920.0, 1080.0, 60e-6)
    }

    /// A `PINHOLE` camera read from top to bottom.
    pub fn pinhole(
        fx: f64,
        fy: f64,
        cx: f64,
        cy: f64,
        width: f64,
        height: f64,
        readout: f64,
    ) -> Self {
        Camera {
            model: CameraModel::Pinhole,
            fx,
            fy,
            cx,
            cy,
            distortion: [0.0; 8],
            width,
            height,
            readout,
            readout_direction: ReadoutDirection::TopToBottom,
        }
    }

    /// A camera from COLMAP's model and parameter vector (COLMAP's order, see
    /// [`CameraModel::param_names`]). Refuses a parameter vector of the wrong length; the
    /// values are checked by [`validate`](Self::validate).
    pub fn from_params(
        model: CameraModel,
        width: f64,
        height: f64,
        params: &[f64],
        readout: f64,
        readout_direction: ReadoutDirection,
    ) -> Result<Self, CameraError> {
        if params.len() != model.num_params() {
            return Err(CameraError::WrongParamCount {
                model: model.name(),
                expected: model.num_params(),
                names: model.param_names().join(", "),
                got: params.len(),
            });
        }
        let (fx, fy, rest) = if model.single_focal() {
            (params[0], params[0], &params[1..])
        } else {
            (params[0], params[1], &params[2..])
        };
        let mut distortion = [0.0; 8];
        distortion[..rest.len() - 2].copy_from_slice(&rest[2..]);
        Ok(Camera {
            model,
            fx,
            fy,
            cx: rest[0],
            cy: rest[1],
            distortion,
            width,
            height,
            readout,
            readout_direction,
        })
    }

    /// COLMAP's parameter vector of this camera (its model's order).
    pub fn params(&self) -> Vec<f64> {
        let mut p = if self.model.single_focal() {
            vec![self.fx]
        } else {
            vec![self.fx, self.fy]
        };
        p.extend([self.cx, self.cy]);
        p.extend_from_slice(&self.distortion[..self.model.num_distortion()]);
        p
    }

    /// The accepted range of a pixel coordinate (and the principal point) along an image
    /// side of `size` pixels: the image extended by [`OUTSIDE_IMAGE_MARGIN`] times its size
    /// on each side.
    pub fn coordinate_range(size: f64) -> (f64, f64) {
        (
            -OUTSIDE_IMAGE_MARGIN * size,
            (1.0 + OUTSIDE_IMAGE_MARGIN) * size,
        )
    }

    /// Whether pixel `p` lies within [`coordinate_range`](Self::coordinate_range) of the
    /// image in both coordinates (false for a non-finite one).
    pub fn pixel_in_range(&self, p: [f64; 2]) -> bool {
        let (u0, u1) = Self::coordinate_range(self.width);
        let (v0, v1) = Self::coordinate_range(self.height);
        (u0..=u1).contains(&p[0]) && (v0..=v1).contains(&p[1])
    }

    /// Check that every parameter is finite and physically plausible: focal lengths in
    /// `[MIN_FOCAL, MAX_PIXELS]` (`fx = fy` for single-focal models), size in
    /// `[MIN_IMAGE_SIZE, MAX_PIXELS]`, principal point within the image extended by
    /// [`OUTSIDE_IMAGE_MARGIN`] times its size, distortion coefficients within
    /// `±MAX_DISTORTION`, readout `>= 0` (0: global shutter) with a frame readout
    /// (`lines × readout`) of at most `MAX_FRAME_READOUT`.
    pub fn validate(&self) -> Result<(), CameraError> {
        let single = self.model.single_focal();
        let focals: &[(&'static str, f64)] = if single {
            &[("f", self.fx)]
        } else {
            &[("fx", self.fx), ("fy", self.fy)]
        };
        for &(name, value) in focals {
            if !(MIN_FOCAL..=MAX_PIXELS).contains(&value) {
                return Err(CameraError::InvalidFocal { name, value });
            }
        }
        if single && self.fx != self.fy {
            return Err(CameraError::UnequalFocals {
                model: self.model.name(),
                fx: self.fx,
                fy: self.fy,
            });
        }
        let size_ok = |x: f64| (MIN_IMAGE_SIZE..=MAX_PIXELS).contains(&x);
        if !(size_ok(self.width) && size_ok(self.height)) {
            return Err(CameraError::InvalidSize {
                width: self.width,
                height: self.height,
            });
        }
        for (name, value, size) in [("cx", self.cx, self.width), ("cy", self.cy, self.height)] {
            let (min, max) = Self::coordinate_range(size);
            if !(min..=max).contains(&value) {
                return Err(CameraError::InvalidPrincipalPoint {
                    name,
                    value,
                    min,
                    max,
                });
            }
        }
        let names = self.model.param_names();
        let first = names.len() - self.model.num_distortion();
        for (i, &name) in names[first..].iter().enumerate() {
            let value = self.distortion[i];
            if value.is_nan() || value.abs() > MAX_DISTORTION {
                return Err(CameraError::InvalidDistortion { name, value });
            }
        }
        if !(self.readout >= 0.0 && self.readout * self.lines() <= MAX_FRAME_READOUT) {
            return Err(CameraError::InvalidReadout(self.readout));
        }
        Ok(())
    }

    /// Calibration matrix `K` (row-major `[[fx,0,cx],[0,fy,cy],[0,0,1]]`), which maps
    /// distorted normalised coordinates to pixels.
    pub fn k(&self) -> Matrix3<f64> {
        Matrix3::new(self.fx, 0.0, self.cx, 0.0, self.fy, self.cy, 0.0, 0.0, 1.0)
    }

    /// Number of lines read per frame: `height` for the row directions, `width` for the
    /// column directions.
    pub fn lines(&self) -> f64 {
        if self.readout_direction.is_horizontal() {
            self.width
        } else {
            self.height
        }
    }

    /// A frame's readout time, `lines × readout`, seconds.
    pub fn frame_readout(&self) -> f64 {
        self.lines() * self.readout
    }

    /// The line coordinate of the raw (distorted) pixel `(u, v)` ([`ReadoutDirection`]):
    /// `v`, `height − 1 − v`, `u` or `width − 1 − u`.
    pub fn readout_line(&self, u: f64, v: f64) -> f64 {
        match self.readout_direction {
            ReadoutDirection::TopToBottom => v,
            ReadoutDirection::BottomToTop => self.height - 1.0 - v,
            ReadoutDirection::LeftToRight => u,
            ReadoutDirection::RightToLeft => self.width - 1.0 - u,
        }
    }

    /// The bearing `m = (x, y, 1)` of pixel `(u, v)`: its undistorted normalised
    /// coordinates, the `x` with `d(x) = ((u − cx) / fx, (v − cy) / fy)`
    /// ([`crate::model::camera_model`]); `K^-1 [u, v, 1]^T` for a pinhole. Errors where the
    /// distortion is not invertible or its Newton iteration does not converge.
    pub fn undistort_bearing(&self, u: f64, v: f64) -> Result<Vector3<f64>, CameraError> {
        let xd = Vector2::new((u - self.cx) / self.fx, (v - self.cy) / self.fy);
        let model = self.model.name();
        let x = camera_model::undistort(self.model, &self.distortion, xd).map_err(|e| match e {
            UndistortFailure::NotInvertible => CameraError::NotInvertible { model, u, v },
            UndistortFailure::NotConverged => CameraError::NotConverged { model, u, v },
        })?;
        Ok(Vector3::new(x.x, x.y, 1.0))
    }

    /// A pixel's bearing ([`undistort_bearing`](Self::undistort_bearing)) and line
    /// coordinate ([`readout_line`](Self::readout_line)).
    pub fn observe(&self, pixel: [f64; 2]) -> Result<Observation, CameraError> {
        Ok(Observation {
            bearing: self.undistort_bearing(pixel[0], pixel[1])?,
            line: self.readout_line(pixel[0], pixel[1]),
        })
    }

    /// Pixel of a camera-frame point `x`: `K d(x.xy / x.z)` with the model's distortion `d`;
    /// `None` if `x.z <= 0`, `x` is not finite, or the point lies where the distortion is
    /// not invertible (its pixel would have no unique bearing).
    pub fn project(&self, x: &Vector3<f64>) -> Option<Vector2<f64>> {
        if x.z.is_nan() || x.z <= 0.0 || !x.iter().all(|c| c.is_finite()) {
            return None;
        }
        if self.model.is_pinhole() {
            return Some(Vector2::new(
                self.fx * x.x / x.z + self.cx,
                self.fy * x.y / x.z + self.cy,
            ));
        }
        let n = Vector2::new(x.x / x.z, x.y / x.z);
        if !camera_model::invertible_at(self.model, &self.distortion, n) {
            return None;
        }
        let (d, _) = camera_model::distort_with_jacobian(self.model, &self.distortion, n);
        let p = Vector2::new(self.fx * d.x + self.cx, self.fy * d.y + self.cy);
        p.iter().all(|c| c.is_finite()).then_some(p)
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

    /// Validate the camera, that `ω` is finite and at most [`MAX_ANGULAR_VELOCITY`], and that a
    /// gravity vector is finite with a length in [`GRAVITY_NORM_RANGE`].
    pub fn validate(&self) -> Result<(), CameraError> {
        self.camera.validate()?;
        if !plausible_rate(&self.omega) {
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

    /// Line rotation `Ω(l)` (line-0 camera frame to line-`l` camera frame, `l` the line
    /// coordinate, [`Camera::readout_line`]): from the track where present, else
    /// `exp(−[l λ ω]×)`.
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
mod tests;
