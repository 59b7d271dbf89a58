//! The image-pair file (`PAIR.json`) read by `rspose estimate` and written by `rspose simulate`.
//!
//! Schema (JSON object; all angles in radians, all pixels in pixels):
//!
//! ```text
//! {
//!   "camera": { "fx": f64, "fy": f64, "cx": f64, "cy": f64,
//!               "width": f64, "height": f64, "readout": f64 },   // readout: λ, s/line
//!   // or "camera": { "model": "OPENCV", "width": f64, "height": f64, "params": [...],
//!   //               "readout": f64, "readout_direction": "top_to_bottom" }
//!   // or "cameras": [camera1, camera2]
//!   "gyro": [[wx, wy, wz], [wx, wy, wz]],   // ω of view 1 and view 2 (see below); optional
//!                                          // when "gyro_log" is given
//!   "gyro_bias": [bx, by, bz],             // optional, without "gyro_log" only: a known
//!                                          // constant bias of "gyro", camera axes (rad/s),
//!                                          // subtracted from both readings
//!   "gyro_log": {                          // optional: gyro samples instead of (or beside) "gyro"
//!     "camera_from_gyro": [[..3..], [..3..], [..3..]],  // M, ω_cam = M ω_gyro (default I)
//!     "time_offset": f64,                  // s (default 0): row 0 of an image is read at
//!                                          // gyro time frame_time + time_offset
//!     "frame_times": [t1, t2],             // frame times of image 1 and 2, s
//!     "gyro_bias": [bx, by, bz],           // optional: a known constant bias, gyro axes
//!                                          // (rad/s): ω_cam = M (ω_gyro − b)
//!     "samples": [[t, wx, wy, wz], ...]    // gyro clock (s), gyro axes (rad/s), increasing t
//!   },
//!   "gravity": [[gx, gy, gz], [gx, gy, gz]],  // optional: gravity in camera axes at row 0
//!                                          // of image 1 and 2 (accelerometer; any length)
//!   "matches": [ [[u1, v1], [u2, v2]], ... ],  // pixel in image 1, pixel in image 2
//!   "ground_truth": {                      // optional
//!     "rotation": [[r00, r01, r02], [r10, r11, r12], [r20, r21, r22]],  // R = R2 R1^T, rows
//!     "translation": [tx, ty, tz],         // t = R2 (C1 - C2), unit length
//!     "omega": [[..3..], [..3..]],         // true ω1, ω2 (rad/s, camera frames)
//!     "velocity": [[..3..], [..3..]],      // true d1, d2 (m/s, world frame)
//!     "inliers": [bool, ...]               // one flag per match (false: simulated outlier)
//!   }
//! }
//! ```
//!
//! `gyro` and the samples are what a gyroscope reports: the camera's angular velocity in its
//! own axes (x right, y down, z forward once rotated by `camera_from_gyro`; rad/s, bias
//! removed, or a known constant bias given as `gyro_bias`), `Ṙ_wc = R_wc [ω]×`, so row
//! `v`'s world-to-camera rotation is
//! `exp(−[v λ ω]×) R_cw(0)` for a constant rate. With a log, each view's row rotations are
//! integrated from the samples over its readout `[t_k + offset, t_k + offset + H λ]` (which
//! the samples must cover, with no gap longer than `H λ`), and its constant rate is the mean
//! rate over that interval ([`crate::model::gyro_log`]).
//!
//! `gravity` is the direction of gravity in each camera's axes when its row 0 is read, as an
//! accelerometer reports it (any length and either sign, the same for both views; only the
//! line's direction is used): for both views or neither.
//!
//! `"camera"` is one camera for both images; `"cameras": [camera1, camera2]` gives each
//! image its own (exactly one of the two keys). A camera is COLMAP's object
//! `{"model", "width", "height", "params", "readout", "readout_direction"}` or the pinhole
//! short form above ([`Camera`], `docs/PAIR_FILE.md`); a pixel's bearing is its
//! undistorted normalised coordinates and its time `l λ`, `l` the line coordinate of the
//! raw pixel along the readout direction. [`PairFile::load`] parses and then validates every field,
//! returning a [`PairFileError`] that names the offending field (`camera.fx`, `matches[3]`,
//! `ground_truth.rotation`, ...).

use crate::model::camera::{Camera, CameraError, View};
use crate::model::gyro_log::{
    plausible_rate, GyroLog, GyroLogError, MAX_ANGULAR_VELOCITY, MAX_SAMPLE_GAP,
};
use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The pair file's matches are the model's ([`crate::model::matches::Match`]).
pub use crate::model::matches::Match;

/// Ground truth stored with a simulated pair (see the module documentation for conventions).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundTruth {
    /// Relative rotation `R = R2 R1^T`, row-major rows.
    pub rotation: [[f64; 3]; 3],
    /// Unit relative translation `t = R2 (C1 - C2) / |.|`.
    pub translation: [f64; 3],
    /// True angular velocities ω1, ω2 (rad/s, camera frames).
    pub omega: [[f64; 3]; 2],
    /// True linear velocities d1, d2 (m/s, world frame).
    pub velocity: [[f64; 3]; 2],
    /// Per-match inlier flag (false: the simulator replaced the match by a random one).
    pub inliers: Vec<bool>,
}

impl GroundTruth {
    /// Rotation as a matrix.
    pub fn rotation_matrix(&self) -> Matrix3<f64> {
        let r = &self.rotation;
        Matrix3::new(
            r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
        )
    }

    /// Translation as a vector.
    pub fn translation_vector(&self) -> Vector3<f64> {
        Vector3::from(self.translation)
    }
}

/// Gyro samples of a pair (see the module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GyroLogSpec {
    /// `M` with `ω_cam = M ω_gyro`, row-major rows (default identity).
    #[serde(default = "identity_rows")]
    pub camera_from_gyro: [[f64; 3]; 3],
    /// Gyro-clock time of an image's row 0 minus its frame time, s (default 0).
    #[serde(default)]
    pub time_offset: f64,
    /// Frame times of image 1 and image 2, s.
    pub frame_times: [f64; 2],
    /// Samples `[t, ωx, ωy, ωz]`: gyro clock (s), gyro axes (rad/s), increasing `t`.
    pub samples: Vec<[f64; 4]>,
    /// A known constant bias of the samples, in the gyro's own axes (rad/s), subtracted
    /// from every sample before `camera_from_gyro` is applied: `ω_cam = M (ω_gyro − b)`
    /// (default none: the samples are taken as unbiased).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyro_bias: Option<[f64; 3]>,
}

fn identity_rows() -> [[f64; 3]; 3] {
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
}

/// Row-major rows as a matrix.
pub fn matrix_from_rows(r: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| r[i][j])
}

/// A matrix as row-major rows.
pub fn rows_of_matrix(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

impl GyroLogSpec {
    /// The samples as a validated [`GyroLog`] in camera axes, [`gyro_bias`](Self::gyro_bias)
    /// removed.
    pub fn log(&self) -> Result<GyroLog, GyroLogError> {
        let m = matrix_from_rows(&self.camera_from_gyro);
        match self.gyro_bias {
            Some(b) => GyroLog::with_bias(&self.samples, &m, &Vector3::from(b)),
            None => GyroLog::new(&self.samples, &m),
        }
    }

    /// The part of a long log a pair needs: the samples within `margin` seconds of the two
    /// frames' readouts (`[t_k + offset, t_k + offset + duration]`, `duration = H λ`) and
    /// everything between them, plus one sample beyond each end. `samples` must be sorted.
    /// No bias is set (`gyro_bias` is `None`); a caller with a known bias sets it.
    pub fn excerpt(
        samples: &[[f64; 4]],
        camera_from_gyro: [[f64; 3]; 3],
        time_offset: f64,
        frame_times: [f64; 2],
        duration: f64,
        margin: f64,
    ) -> Self {
        let start = frame_times[0].min(frame_times[1]) + time_offset - margin;
        let end = frame_times[0].max(frame_times[1]) + time_offset + duration + margin;
        let lo = samples.partition_point(|s| s[0] < start).saturating_sub(1);
        let hi = (samples.partition_point(|s| s[0] <= end) + 1).min(samples.len());
        GyroLogSpec {
            camera_from_gyro,
            time_offset,
            frame_times,
            samples: samples[lo..hi.max(lo)].to_vec(),
            gyro_bias: None,
        }
    }

    /// Gyro-clock time of row 0 of image `k` (0 or 1).
    pub fn row0_time(&self, k: usize) -> f64 {
        self.frame_times[k] + self.time_offset
    }
}

/// A pair of rolling-shutter images with gyro readings and pixel matches (`PAIR.json`).
/// Unknown keys, here and in the nested objects, are refused with their name: a misspelt
/// optional key would otherwise silently take its default. In JSON the cameras are
/// `"camera"` (one for both images) or `"cameras": [camera1, camera2]`, exactly one of
/// the two; a file is written with `"camera"` when both cameras are equal.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "PairFileJson")]
pub struct PairFile {
    /// The cameras of image 1 and image 2.
    pub cameras: [Camera; 2],
    /// Angular velocities of view 1 and view 2 (rad/s, camera axes, as a gyroscope reports
    /// them), constant over each frame. Optional when `gyro_log` is given.
    pub gyro: Option<[[f64; 3]; 2]>,
    /// A known constant bias of the `gyro` readings, camera axes (rad/s), subtracted from
    /// both before use. Only without a `gyro_log` (a log's bias is
    /// [`GyroLogSpec::gyro_bias`], in the gyro's axes); default none.
    pub gyro_bias: Option<[f64; 3]>,
    /// Gyro samples: exact row rotations, and the rotation between the frames.
    pub gyro_log: Option<GyroLogSpec>,
    /// Gravity in the camera axes of view 1 and view 2 at row 0 (accelerometer readings).
    pub gravity: Option<[[f64; 3]; 2]>,
    /// Pixel matches `[[u1, v1], [u2, v2]]`.
    pub matches: Vec<Match>,
    /// Ground truth, present in simulated files.
    pub ground_truth: Option<GroundTruth>,
}

/// The pair file as JSON holds it (`camera` or `cameras`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PairFileJson {
    #[serde(default)]
    camera: Option<Camera>,
    #[serde(default)]
    cameras: Option<Vec<Camera>>,
    #[serde(default)]
    gyro: Option<[[f64; 3]; 2]>,
    #[serde(default)]
    gyro_bias: Option<[f64; 3]>,
    #[serde(default)]
    gyro_log: Option<GyroLogSpec>,
    #[serde(default, deserialize_with = "gravity_field")]
    gravity: Option<[[f64; 3]; 2]>,
    matches: Vec<Match>,
    #[serde(default)]
    ground_truth: Option<GroundTruth>,
}

/// The pair file as it is written (borrowing the file's fields).
#[derive(Serialize)]
struct PairFileOut<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    camera: Option<&'a Camera>,
    #[serde(skip_serializing_if = "Option::is_none")]
    cameras: Option<&'a [Camera; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    gyro: Option<&'a [[f64; 3]; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    gyro_bias: Option<&'a [f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    gyro_log: Option<&'a GyroLogSpec>,
    #[serde(skip_serializing_if = "Option::is_none")]
    gravity: Option<&'a [[f64; 3]; 2]>,
    matches: &'a [Match],
    #[serde(skip_serializing_if = "Option::is_none")]
    ground_truth: Option<&'a GroundTruth>,
}

impl TryFrom<PairFileJson> for PairFile {
    type Error = String;

    fn try_from(j: PairFileJson) -> Result<Self, String> {
        let cameras = match (j.camera, j.cameras) {
            (Some(c), None) => [c, c],
            (None, Some(cs)) => match cs[..] {
                [c1, c2] => [c1, c2],
                _ => {
                    return Err(format!(
                        "`cameras` needs one camera for each of the two images, got {}",
                        cs.len()
                    ))
                }
            },
            (Some(_), Some(_)) => {
                return Err(
                    "give `camera` (both images) or `cameras` (one per image), not both".into(),
                )
            }
            (None, None) => {
                return Err(
                    "missing field `camera` (both images) or `cameras` (one per image)".into(),
                )
            }
        };
        Ok(PairFile {
            cameras,
            gyro: j.gyro,
            gyro_bias: j.gyro_bias,
            gyro_log: j.gyro_log,
            gravity: j.gravity,
            matches: j.matches,
            ground_truth: j.ground_truth,
        })
    }
}

/// Whether two cameras are the same, bit for bit (a NaN parameter equal to itself: a file
/// with one `camera` holding a NaN names `camera`, not `cameras[0]`).
fn same_camera(a: &Camera, b: &Camera) -> bool {
    let numbers = |c: &Camera| {
        let mut v = vec![c.fx, c.fy, c.cx, c.cy, c.width, c.height, c.readout];
        v.extend(c.distortion);
        v.into_iter().map(f64::to_bits).collect::<Vec<_>>()
    };
    a.model == b.model && a.readout_direction == b.readout_direction && numbers(a) == numbers(b)
}

impl Serialize for PairFile {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let shared = same_camera(&self.cameras[0], &self.cameras[1]);
        PairFileOut {
            camera: shared.then_some(&self.cameras[0]),
            cameras: (!shared).then_some(&self.cameras),
            gyro: self.gyro.as_ref(),
            gyro_bias: self.gyro_bias.as_ref(),
            gyro_log: self.gyro_log.as_ref(),
            gravity: self.gravity.as_ref(),
            matches: &self.matches,
            ground_truth: self.ground_truth.as_ref(),
        }
        .serialize(s)
    }
}

/// Errors reading, validating or writing a pair file.
#[derive(Debug, Error)]
pub enum PairFileError {
    /// The file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The JSON is malformed or a field is missing or has the wrong type (serde names it).
    #[error("{path}: invalid pair file: {source}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parse error (names the field, line and column).
        source: serde_json::Error,
    },
    /// A field parsed but holds an invalid value.
    #[error("invalid field `{field}`: {reason}")]
    InvalidField {
        /// Dotted path of the field, e.g. `camera.fx` or `matches[3]`.
        field: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// A gyro-log error as an invalid field naming the sample (`gyro_log.samples[i]`).
fn log_error(e: GyroLogError) -> PairFileError {
    let field = match &e {
        GyroLogError::NonFinite { index }
        | GyroLogError::Implausible { index }
        | GyroLogError::DuplicateTime { index, .. }
        | GyroLogError::Unsorted { index, .. }
        | GyroLogError::Gap { index, .. } => format!("gyro_log.samples[{index}]"),
        GyroLogError::TooFewSamples(_) | GyroLogError::NotCovered { .. } => {
            "gyro_log.samples".into()
        }
        GyroLogError::NotARotation => "gyro_log.camera_from_gyro".into(),
    };
    invalid(field, e.to_string())
}

/// `gravity`: two 3-vectors, or absent/null. Read with a bounded shape (at most two views
/// of three numbers; anything longer is refused at its first extra element, without
/// building it in memory), and every shape error (one view only, a vector of two numbers,
/// a string) names the field with [`gravity_from_json`]'s messages.
fn gravity_field<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<Option<[[f64; 3]; 2]>, D::Error> {
    d.deserialize_any(GravityVisitor)
}

/// The message of a `gravity` that is not two views.
const GRAVITY_VIEWS: &str =
    "field `gravity`: expected one direction [gx, gy, gz] for each of the two views";

/// The message of a view `k` of `gravity` that is not three numbers.
fn gravity_view_message(k: usize) -> String {
    format!(
        "field `gravity[{k}]`: expected three numbers [gx, gy, gz] (gravity is given for both views or neither)"
    )
}

/// Reads `gravity` as null or a sequence of exactly two [`GravityView`]s.
struct GravityVisitor;

impl<'de> serde::de::Visitor<'de> for GravityVisitor {
    type Value = Option<[[f64; 3]; 2]>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(GRAVITY_VIEWS)
    }

    fn visit_unit<E: serde::de::Error>(self) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_none<E: serde::de::Error>(self) -> Result<Self::Value, E> {
        Ok(None)
    }

    fn visit_bool<E: serde::de::Error>(self, _: bool) -> Result<Self::Value, E> {
        Err(E::custom(GRAVITY_VIEWS))
    }

    fn visit_i64<E: serde::de::Error>(self, _: i64) -> Result<Self::Value, E> {
        Err(E::custom(GRAVITY_VIEWS))
    }

    fn visit_u64<E: serde::de::Error>(self, _: u64) -> Result<Self::Value, E> {
        Err(E::custom(GRAVITY_VIEWS))
    }

    fn visit_f64<E: serde::de::Error>(self, _: f64) -> Result<Self::Value, E> {
        Err(E::custom(GRAVITY_VIEWS))
    }

    fn visit_str<E: serde::de::Error>(self, _: &str) -> Result<Self::Value, E> {
        Err(E::custom(GRAVITY_VIEWS))
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, _: A) -> Result<Self::Value, A::Error> {
        Err(serde::de::Error::custom(GRAVITY_VIEWS))
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        use serde::de::Error;
        let mut out = [[0.0; 3]; 2];
        for (k, view) in out.iter_mut().enumerate() {
            *view = seq
                .next_element::<GravityView>()
                .map_err(|_| A::Error::custom(gravity_view_message(k)))?
                .ok_or_else(|| A::Error::custom(GRAVITY_VIEWS))?
                .0;
        }
        if seq.next_element::<serde::de::IgnoredAny>()?.is_some() {
            return Err(A::Error::custom(GRAVITY_VIEWS));
        }
        Ok(Some(out))
    }
}

/// One view of `gravity`: exactly three numbers (any other shape is an error the caller
/// replaces with the field's message).
struct GravityView([f64; 3]);

impl<'de> Deserialize<'de> for GravityView {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Ok(GravityView(<[f64; 3]>::deserialize(d)?))
    }
}

/// The `gravity` field of a pair file from its JSON value: `null` (no gravity) or one
/// direction `[gx, gy, gz]` for each of the two views. The error names the field
/// (`gravity` or `gravity[k]`), as `rspose estimate` reports it; the Python package builds
/// this value from its `gravity1`/`gravity2` arguments for the same messages.
pub fn gravity_from_json(value: &serde_json::Value) -> Result<Option<[[f64; 3]; 2]>, String> {
    if value.is_null() {
        return Ok(None);
    }
    let views = value
        .as_array()
        .filter(|a| a.len() == 2)
        .ok_or_else(|| GRAVITY_VIEWS.to_string())?;
    let mut out = [[0.0; 3]; 2];
    for (k, v) in views.iter().enumerate() {
        let numbers: Option<Vec<f64>> = v
            .as_array()
            .filter(|a| a.len() == 3)
            .map(|a| a.iter().map(|x| x.as_f64()).collect())
            .and_then(|x: Option<Vec<f64>>| x);
        let numbers = numbers.ok_or_else(|| gravity_view_message(k))?;
        out[k].copy_from_slice(&numbers);
    }
    Ok(Some(out))
}

/// The dotted field a camera error names: `camera.fx` (the short pinhole form's key, also
/// for a `PINHOLE` written with `params`), `camera.params[4]` (`k1` of an `OPENCV`),
/// `camera.readout`, ... (`key` is `camera` or `cameras[k]`).
fn camera_field(key: &str, camera: &Camera, e: &CameraError) -> String {
    let param = |name: &str| {
        let names = camera.model.param_names();
        match names.iter().position(|n| *n == name) {
            Some(_) if camera.model == crate::model::camera_model::CameraModel::Pinhole => {
                format!("{key}.{name}")
            }
            Some(i) => format!("{key}.params[{i}]"),
            None => format!("{key}.params"),
        }
    };
    match e {
        CameraError::InvalidFocal { name, .. }
        | CameraError::InvalidPrincipalPoint { name, .. }
        | CameraError::InvalidDistortion { name, .. } => param(name),
        CameraError::UnequalFocals { .. } => format!("{key}.params"),
        CameraError::InvalidReadout(_) => format!("{key}.readout"),
        CameraError::InvalidSize { .. } => format!("{key}.width/height"),
        CameraError::UnknownModel(_) => format!("{key}.model"),
        CameraError::WrongParamCount { .. } => format!("{key}.params"),
        CameraError::InvalidObject(_)
        | CameraError::NotInvertible { .. }
        | CameraError::NotConverged { .. } => key.to_string(),
        CameraError::InvalidGyro(..) => "gyro".into(),
        CameraError::InvalidGravity(..) => "gravity".into(),
    }
}

/// A gyro bias must be finite and below the plausible rate (a larger one is a unit or
/// sign mistake, not a bias).
fn check_bias(field: &str, b: &[f64; 3]) -> Result<(), PairFileError> {
    if plausible_rate(&Vector3::from(*b)) {
        Ok(())
    } else {
        Err(invalid(
            field,
            format!("must be finite and at most {MAX_ANGULAR_VELOCITY} rad/s"),
        ))
    }
}

fn invalid(field: impl Into<String>, reason: impl Into<String>) -> PairFileError {
    PairFileError::InvalidField {
        field: field.into(),
        reason: reason.into(),
    }
}

impl PairFile {
    /// The two views: with a gyro log, row rotations integrated from its samples and the
    /// mean rate over each readout; otherwise the constant `gyro` rates; with `gravity`
    /// where the file has it. Errors as [`validate`](Self::validate) would.
    pub fn views(&self) -> Result<(View, View), PairFileError> {
        let (v1, v2) = self.views_without_gravity()?;
        Ok(match self.gravity {
            Some([g1, g2]) => (
                v1.with_gravity(Vector3::from(g1)),
                v2.with_gravity(Vector3::from(g2)),
            ),
            None => (v1, v2),
        })
    }

    fn views_without_gravity(&self) -> Result<(View, View), PairFileError> {
        let Some(spec) = &self.gyro_log else {
            let Some(g) = self.gyro else {
                return Err(invalid("gyro", "missing (give `gyro` or `gyro_log`)"));
            };
            let bias = self.gyro_bias.map_or_else(Vector3::zeros, Vector3::from);
            return Ok((
                View::new(self.cameras[0], Vector3::from(g[0]) - bias),
                View::new(self.cameras[1], Vector3::from(g[1]) - bias),
            ));
        };
        let log = spec.log().map_err(log_error)?;
        log.check_gaps(MAX_SAMPLE_GAP).map_err(log_error)?;
        let view = |k: usize| -> Result<View, PairFileError> {
            let t0 = spec.row0_time(k);
            let duration = self.cameras[k].frame_readout();
            log.check_covers(t0, t0 + duration, &format!("image {}'s readout", k + 1))
                .map_err(log_error)?;
            Ok(View::with_track(
                self.cameras[k],
                log.mean_rate(t0, t0 + duration),
                log.row_track(t0, duration),
            ))
        };
        Ok((view(0)?, view(1)?))
    }

    /// The relative rotation `R = R2 R1^T` between the row-0 poses of the two images,
    /// integrated from the gyro log (`Q^T` with `Q` the orientation at image 2's row 0 in
    /// image 1's): `None` without a log or when its samples do not span both row-0 times.
    /// A rotation reference on real recordings, and a source of `R_0` for G-RSRP.
    pub fn gyro_relative_rotation(&self) -> Option<Matrix3<f64>> {
        let spec = self.gyro_log.as_ref()?;
        let log = spec.log().ok()?;
        let (t1, t2) = (spec.row0_time(0), spec.row0_time(1));
        log.check_covers(t1.min(t2), t1.max(t2), "both frames")
            .ok()?;
        Some(log.rotation_between(t1, t2).transpose())
    }

    /// Check every field: camera parameters, finite gyro, finite pixels within the image
    /// extended by [`crate::model::camera::OUTSIDE_IMAGE_MARGIN`] times its size, and (if present) a
    /// rotation ground truth that is a rotation, a unit translation, finite velocities and one
    /// inlier flag per match.
    pub fn validate(&self) -> Result<(), PairFileError> {
        let shared = same_camera(&self.cameras[0], &self.cameras[1]);
        for (k, camera) in self.cameras.iter().enumerate() {
            let key = if shared {
                "camera".to_string()
            } else {
                format!("cameras[{k}]")
            };
            camera
                .validate()
                .map_err(|e| invalid(camera_field(&key, camera, &e), e.to_string()))?;
        }
        if let Some(g) = &self.gyro {
            for (i, w) in g.iter().enumerate() {
                if !plausible_rate(&Vector3::from(*w)) {
                    return Err(invalid(
                        format!("gyro[{i}]"),
                        format!(
                            "angular velocity must be finite and at most {MAX_ANGULAR_VELOCITY} rad/s"
                        ),
                    ));
                }
            }
        }
        if let Some(spec) = &self.gyro_log {
            if !spec.frame_times.iter().all(|t| t.is_finite()) {
                return Err(invalid("gyro_log.frame_times", "non-finite time"));
            }
            if !spec.time_offset.is_finite() {
                return Err(invalid("gyro_log.time_offset", "non-finite value"));
            }
            if let Some(b) = spec.gyro_bias {
                check_bias("gyro_log.gyro_bias", &b)?;
            }
        }
        if let Some(b) = &self.gyro_bias {
            check_bias("gyro_bias", b)?;
            if self.gyro_log.is_some() {
                return Err(invalid(
                    "gyro_bias",
                    "applies to `gyro` without a log; with `gyro_log` give the bias as `gyro_log.gyro_bias`, in the gyro's axes",
                ));
            }
        }
        if let Some(g) = &self.gravity {
            for (i, v) in g.iter().enumerate() {
                if !crate::model::camera::GRAVITY_NORM_RANGE.contains(&Vector3::from(*v).norm()) {
                    return Err(invalid(
                        format!("gravity[{i}]"),
                        "must be finite with a non-zero length",
                    ));
                }
            }
        }
        self.views()?;
        for (i, m) in self.matches.iter().enumerate() {
            if !m.iter().flatten().all(|x| x.is_finite()) {
                return Err(invalid(
                    format!("matches[{i}]"),
                    "non-finite pixel coordinate",
                ));
            }
            for (k, p) in m.iter().enumerate() {
                let camera = &self.cameras[k];
                if !camera.pixel_in_range(*p) {
                    return Err(invalid(
                        format!("matches[{i}][{k}]"),
                        format!(
                            "pixel ({:?}, {:?}) of image {} is far outside the {:?}x{:?} image (at most one image size beyond each side)",
                            p[0], p[1], k + 1, camera.width, camera.height
                        ),
                    ));
                }
            }
        }
        if let Some(gt) = &self.ground_truth {
            let r = gt.rotation_matrix();
            if !r.iter().all(|x| x.is_finite())
                || (r.transpose() * r - Matrix3::identity()).norm() > 1e-6
                || (r.determinant() - 1.0).abs() > 1e-6
            {
                return Err(invalid("ground_truth.rotation", "not a rotation matrix"));
            }
            let t = gt.translation_vector();
            if !t.iter().all(|x| x.is_finite()) || (t.norm() - 1.0).abs() > 1e-6 {
                return Err(invalid("ground_truth.translation", "not a unit vector"));
            }
            if !gt.omega.iter().flatten().all(|x| x.is_finite()) {
                return Err(invalid("ground_truth.omega", "non-finite value"));
            }
            if !gt.velocity.iter().flatten().all(|x| x.is_finite()) {
                return Err(invalid("ground_truth.velocity", "non-finite value"));
            }
            if gt.inliers.len() != self.matches.len() {
                return Err(invalid(
                    "ground_truth.inliers",
                    format!(
                        "{} flags for {} matches",
                        gt.inliers.len(),
                        self.matches.len()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Parse from a JSON string and [`validate`](Self::validate). `path` is only used in
    /// error messages.
    pub fn from_json_str(s: &str, path: &Path) -> Result<Self, PairFileError> {
        let pair: PairFile = serde_json::from_str(s).map_err(|source| PairFileError::Parse {
            path: path.to_path_buf(),
            source,
        })?;
        pair.validate()?;
        Ok(pair)
    }

    /// Read, parse and validate a pair file, streaming from the file into the typed
    /// structure (no copy of the whole text in memory).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, PairFileError> {
        let path = path.as_ref();
        let file = std::fs::File::open(path).map_err(|source| PairFileError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let reader = std::io::BufReader::with_capacity(1 << 16, file);
        let pair: PairFile =
            serde_json::from_reader(reader).map_err(|source| PairFileError::Parse {
                path: path.to_path_buf(),
                source,
            })?;
        pair.validate()?;
        Ok(pair)
    }

    /// Compact JSON text of this file (one line).
    pub fn to_compact_json_string(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// Pretty JSON text of this file.
    pub fn to_json_string(&self) -> String {
        // Serialising plain numbers, arrays and bools cannot fail except on non-finite
        // floats, which serde_json writes as `null`.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Write atomically: validate, write `PATH.tmp-PID` in the same directory, sync, then
    /// rename over `path`. On error no partial file is left at `path`.
    pub fn save_atomic(&self, path: impl AsRef<Path>) -> Result<(), PairFileError> {
        self.save_atomic_as(path, false)
    }

    /// [`save_atomic`](Self::save_atomic), as one compact line when `compact` (real pairs
    /// with many matches and samples), else pretty-printed.
    pub fn save_atomic_as(
        &self,
        path: impl AsRef<Path>,
        compact: bool,
    ) -> Result<(), PairFileError> {
        self.save_output(path.as_ref(), compact, &[])
    }

    /// [`save_atomic_as`](Self::save_atomic_as) that refuses to overwrite any of `inputs`
    /// (the files the pair was made from), through whatever name; see
    /// [`crate::data::atomic_file::write_output`] for devices, links and read-only files.
    pub fn save_output(
        &self,
        path: &Path,
        compact: bool,
        inputs: &[&Path],
    ) -> Result<(), PairFileError> {
        self.validate()?;
        let io = |source| PairFileError::Io {
            path: path.to_path_buf(),
            source,
        };
        let mut text = if compact {
            self.to_compact_json_string()
        } else {
            self.to_json_string()
        };
        text.push('\n');
        crate::data::atomic_file::write_output(path, text.as_bytes(), inputs).map_err(io)
    }
}

#[cfg(test)]
mod tests;
