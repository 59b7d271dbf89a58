//! Kalibr's camera-IMU calibration (`camchain-imucam.yaml`) as a rig calibration: the
//! camera, the camera-gyro rotation and the time offset `rspose make-pair` needs.
//!
//! One camera `camN` of the file is read:
//!
//! - `camera_model: pinhole` (Kalibr's other projections are refused), `intrinsics:
//!   [fu, fv, pu, pv]`, `resolution: [w, h]`;
//! - `distortion_model` and `distortion_coeffs`: `radtan` `[k1, k2, r1, r2]` → COLMAP's
//!   `OPENCV [fx, fy, cx, cy, k1, k2, p1, p2]` (the same formula), `equidistant`
//!   `[k1, k2, k3, k4]` → `OPENCV_FISHEYE [fx, fy, cx, cy, k1, k2, k3, k4]`, `none` →
//!   `PINHOLE`;
//! - `T_cam_imu` (4x4 rows, `p_cam = R p_imu + t`): `camera_from_gyro` is its rotation `R`,
//!   since an angular velocity transforms as `ω_cam = R ω_imu`;
//! - `timeshift_cam_imu` (s): Kalibr's convention is `t_imu = t_cam + timeshift`, so a frame
//!   stamped `t` on the camera's clock is at `t + timeshift` on the gyro's, and rspose's
//!   `time_offset` (gyro time of row 0 minus the frame time) is `+timeshift` (Kalibr's
//!   rolling-shutter model dates row `r` at `t + r · line_delay`, so its image time is row
//!   0's);
//! - `line_delay` (s per row, only in Kalibr's rolling-shutter calibration): the readout
//!   time per line, read from the top. A file without it (a global-shutter calibration) is
//!   refused unless the caller gives the readout time: taking 0 would silently turn the
//!   rolling-shutter model off.
//!
//! Errors name the key (`cam0.intrinsics`) or the YAML line; the caller adds the file.

use crate::data::yaml::{self, Yaml, YamlError};
use crate::model::camera::{Camera, ReadoutDirection};
use crate::model::camera_model::CameraModel;
use nalgebra::Matrix3;
use thiserror::Error;

/// A calibration file that cannot be imported. `key` is the dotted key (`cam0.T_cam_imu`).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CalibrationImportError {
    /// Not in the YAML subset the importers read ([`crate::data::yaml`]).
    #[error("{0}")]
    Yaml(#[from] YamlError),
    /// A required key is missing.
    #[error("missing key `{key}`{hint}")]
    Missing {
        /// The key.
        key: String,
        /// What to do about it (may be empty).
        hint: String,
    },
    /// A key holds a value that cannot be used.
    #[error("key `{key}`: {reason}")]
    Invalid {
        /// The key.
        key: String,
        /// What is wrong.
        reason: String,
    },
}

/// A rig calibration imported from another tool: what `rspose make-pair` reads from its
/// JSON calibration, except the gyro CSV's time column.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportedRig {
    /// The camera.
    pub camera: Camera,
    /// `M` with `ω_cam = M ω_gyro`, row-major rows.
    pub camera_from_gyro: [[f64; 3]; 3],
    /// Gyro time of a frame's row 0 minus its frame time, s.
    pub time_offset: f64,
}

/// An [`CalibrationImportError::Invalid`] for `key` (shared with the OpenCV reader).
pub(crate) fn invalid(key: &str, reason: impl Into<String>) -> CalibrationImportError {
    CalibrationImportError::Invalid {
        key: key.to_string(),
        reason: reason.into(),
    }
}

/// A [`CalibrationImportError::Missing`] for `key`, with `hint` appended to the message
/// (empty or starting with a space).
pub(crate) fn missing(key: &str, hint: &str) -> CalibrationImportError {
    CalibrationImportError::Missing {
        key: key.to_string(),
        hint: hint.to_string(),
    }
}

/// The value under `key` of `map`, named `prefix.key` when missing.
fn field<'a>(map: &'a Yaml, prefix: &str, key: &str) -> Result<&'a Yaml, CalibrationImportError> {
    map.get(key)
        .filter(|v| **v != Yaml::Null)
        .ok_or_else(|| missing(&format!("{prefix}.{key}"), ""))
}

/// `n` finite numbers under `key`.
fn numbers(
    map: &Yaml,
    prefix: &str,
    key: &str,
    n: Option<usize>,
) -> Result<Vec<f64>, CalibrationImportError> {
    let name = format!("{prefix}.{key}");
    let v = field(map, prefix, key)?
        .as_f64_vec()
        .ok_or_else(|| invalid(&name, "expected a list of finite numbers"))?;
    match n {
        Some(n) if v.len() != n => Err(invalid(
            &name,
            format!("expected {n} numbers, got {}", v.len()),
        )),
        _ => Ok(v),
    }
}

/// Reads camera `cam` (e.g. `cam0`) of a Kalibr `camchain-imucam.yaml` (see the module
/// documentation). `readout`, when given (s per line), is the camera's readout time and
/// takes precedence over the file's `line_delay`; without it the file must have one.
pub fn parse_kalibr(
    text: &str,
    cam: &str,
    readout: Option<f64>,
) -> Result<ImportedRig, CalibrationImportError> {
    let doc = yaml::parse(text)?;
    let c = doc.get(cam).ok_or_else(|| {
        let cams: Vec<&str> = doc
            .keys()
            .into_iter()
            .filter(|k| k.starts_with("cam"))
            .collect();
        missing(
            cam,
            &format!(
                " (cameras in the file: {})",
                if cams.is_empty() {
                    "none".to_string()
                } else {
                    cams.join(", ")
                }
            ),
        )
    })?;
    let model = field(c, cam, "camera_model")?.as_str().unwrap_or("");
    if model != "pinhole" {
        return Err(invalid(
            &format!("{cam}.camera_model"),
            format!("`{model}`: only Kalibr's `pinhole` projection is imported"),
        ));
    }
    let k = numbers(c, cam, "intrinsics", Some(4))?;
    let size = numbers(c, cam, "resolution", Some(2))?;
    let distortion = field(c, cam, "distortion_model")?.as_str().unwrap_or("");
    let (colmap, coeffs) = match distortion {
        "radtan" => (
            CameraModel::OpenCv,
            numbers(c, cam, "distortion_coeffs", Some(4))?,
        ),
        "equidistant" => (
            CameraModel::OpenCvFisheye,
            numbers(c, cam, "distortion_coeffs", Some(4))?,
        ),
        "none" => (CameraModel::Pinhole, Vec::new()),
        other => {
            return Err(invalid(
                &format!("{cam}.distortion_model"),
                format!("`{other}`: expected radtan, equidistant or none"),
            ))
        }
    };
    let readout =
        match (readout, c.get("line_delay")) {
            (Some(r), _) => r,
            (None, Some(v)) => v
                .as_f64()
                .ok_or_else(|| invalid(&format!("{cam}.line_delay"), "not a finite number"))?,
            (None, None) => return Err(missing(
                &format!("{cam}.line_delay"),
                " (a global-shutter calibration: give the readout time per line with --readout)",
            )),
        };
    let mut params = k.clone();
    params.extend(coeffs);
    let camera = Camera::from_params(
        colmap,
        size[0],
        size[1],
        &params,
        readout,
        ReadoutDirection::TopToBottom,
    )
    .and_then(|c| c.validate().map(|_| c))
    .map_err(|e| invalid(cam, e.to_string()))?;
    let t_key = format!("{cam}.T_cam_imu");
    let rows = match field(c, cam, "T_cam_imu").map_err(|_| {
        missing(
            &t_key,
            " (a camera-only camchain.yaml: the camera-IMU calibration is camchain-imucam.yaml)",
        )
    })? {
        Yaml::Seq(rows) if rows.len() == 4 => rows
            .iter()
            .map(|r| r.as_f64_vec().filter(|r| r.len() == 4))
            .collect::<Option<Vec<_>>>(),
        _ => None,
    }
    .ok_or_else(|| invalid(&t_key, "expected 4 rows of 4 finite numbers"))?;
    let r = Matrix3::from_fn(|i, j| rows[i][j]);
    if (r.transpose() * r - Matrix3::identity()).norm() > 1e-6
        || (r.determinant() - 1.0).abs() > 1e-6
    {
        return Err(invalid(
            &t_key,
            "its upper-left 3x3 block is not a rotation",
        ));
    }
    let time_offset = field(c, cam, "timeshift_cam_imu")?
        .as_f64()
        .ok_or_else(|| invalid(&format!("{cam}.timeshift_cam_imu"), "not a finite number"))?;
    Ok(ImportedRig {
        camera,
        camera_from_gyro: std::array::from_fn(|i| std::array::from_fn(|j| rows[i][j])),
        time_offset,
    })
}

#[cfg(test)]
mod tests;
