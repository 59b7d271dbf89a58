//! An OpenCV camera calibration (`cv::FileStorage` YAML, `%YAML:1.0`, as
//! `cv::calibrateCamera` samples and many tools write it; also ROS's `camera_info` YAML) as a
//! camera.
//!
//! Keys, in the spellings found in the wild: the camera matrix `camera_matrix` or `K`, the
//! distortion `distortion_coefficients`, `dist_coeffs` or `D`, each a matrix
//! `{rows, cols, data}` (OpenCV's `!!opencv-matrix` with `dt`, or ROS's form) or a plain
//! list; the size `image_width` and `image_height`. The camera matrix must be
//! `[fx, 0, cx; 0, fy, cy; 0, 0, 1]` (a skew is refused). The coefficients map to COLMAP's
//! models by their count, in OpenCV's order `k1, k2, p1, p2[, k3[, k4, k5, k6]]`:
//!
//! | coefficients | model |
//! |---|---|
//! | none, or all zero | `PINHOLE` |
//! | 4; 5 with `k3 = 0`; 8 with `k3..k6 = 0` | `OPENCV [fx, fy, cx, cy, k1, k2, p1, p2]` |
//! | 5 with `k3 ≠ 0` | `FULL_OPENCV` with `k4 = k5 = k6 = 0` |
//! | 8 | `FULL_OPENCV [.., k1, k2, p1, p2, k3, k4, k5, k6]` |
//! | 4 with a fisheye flag | `OPENCV_FISHEYE [fx, fy, cx, cy, k1, k2, k3, k4]` |
//!
//! `cv::fisheye` stores its four coefficients like the others, so a fisheye file is told
//! apart only by a flag beside them: `distortion_model` (ROS; `equidistant`, `fisheye` or
//! `kannala_brandt`, any case) or `fisheye: 1`/`true`. Without one, four coefficients are
//! taken as `OPENCV`'s. Other counts (12, 14: thin-prism and tilted models) are refused.
//! The file has no readout time; the caller gives it (the camera is read from the top).

use crate::data::kalibr::{invalid, missing, CalibrationImportError};
use crate::data::yaml::{self, Yaml};
use crate::model::camera::{Camera, ReadoutDirection};
use crate::model::camera_model::CameraModel;

/// The first of `keys` present in `doc`, with its name.
fn first_of<'a>(doc: &'a Yaml, keys: &[&'static str]) -> Option<(&'static str, &'a Yaml)> {
    keys.iter()
        .find_map(|k| doc.get(k).filter(|v| **v != Yaml::Null).map(|v| (*k, v)))
}

/// A matrix's numbers: `{rows, cols, data}` (checked `rows · cols = data.len()`) or a list.
fn matrix_data(key: &str, v: &Yaml) -> Result<Vec<f64>, CalibrationImportError> {
    if let Some(list) = v.as_f64_vec() {
        return Ok(list);
    }
    let data = v
        .get("data")
        .ok_or_else(|| missing(&format!("{key}.data"), ""))?
        .as_f64_vec()
        .ok_or_else(|| invalid(&format!("{key}.data"), "expected a list of finite numbers"))?;
    let dim = |name: &str| {
        v.get(name)
            .and_then(Yaml::as_f64)
            .ok_or_else(|| invalid(&format!("{key}.{name}"), "expected a number"))
    };
    let (rows, cols) = (dim("rows")?, dim("cols")?);
    if rows * cols != data.len() as f64 {
        return Err(invalid(
            &format!("{key}.data"),
            format!("{} numbers for {rows} x {cols}", data.len()),
        ));
    }
    Ok(data)
}

/// Whether the file flags its distortion as `cv::fisheye`'s (see the module documentation).
fn fisheye_flag(doc: &Yaml) -> bool {
    let model = doc
        .get("distortion_model")
        .and_then(Yaml::as_str)
        .map(str::to_ascii_lowercase);
    let flag = doc.get("fisheye").and_then(Yaml::as_str);
    matches!(
        model.as_deref(),
        Some("equidistant" | "fisheye" | "kannala_brandt")
    ) || matches!(flag, Some("1" | "true" | "True"))
}

/// Reads an OpenCV calibration (see the module documentation) as a camera read from top
/// to bottom with `readout` seconds per line.
pub fn parse_opencv_calibration(
    text: &str,
    readout: f64,
) -> Result<Camera, CalibrationImportError> {
    let doc = yaml::parse(text)?;
    let (k_key, k) = first_of(&doc, &["camera_matrix", "K"])
        .ok_or_else(|| missing("camera_matrix", " (or `K`)"))?;
    let k = matrix_data(k_key, k)?;
    if k.len() != 9 {
        return Err(invalid(
            k_key,
            format!("expected 3 x 3, got {} numbers", k.len()),
        ));
    }
    let scale = k[0].abs().max(k[4].abs()).max(1.0);
    if k[1].abs() > 1e-9 * scale
        || k[3] != 0.0
        || k[6] != 0.0
        || k[7] != 0.0
        || (k[8] - 1.0).abs() > 1e-12
    {
        return Err(invalid(
            k_key,
            "expected [fx, 0, cx; 0, fy, cy; 0, 0, 1] (a skew is not supported)",
        ));
    }
    let d = match first_of(&doc, &["distortion_coefficients", "dist_coeffs", "D"]) {
        Some((key, v)) => (key, matrix_data(key, v)?),
        None => ("distortion_coefficients", Vec::new()),
    };
    let (d_key, d) = d;
    let size = |key: &str| {
        doc.get(key)
            .filter(|v| **v != Yaml::Null)
            .ok_or_else(|| missing(key, ""))?
            .as_f64()
            .ok_or_else(|| invalid(key, "expected a number"))
    };
    let (width, height) = (size("image_width")?, size("image_height")?);
    let zero = |s: &[f64]| s.iter().all(|&x| x == 0.0);
    let fisheye = fisheye_flag(&doc);
    let (model, coeffs): (CameraModel, Vec<f64>) = match d.len() {
        4 if fisheye => (CameraModel::OpenCvFisheye, d.clone()),
        _ if fisheye => {
            return Err(invalid(
                d_key,
                format!("a fisheye calibration has 4 coefficients, got {}", d.len()),
            ))
        }
        0 => (CameraModel::Pinhole, Vec::new()),
        _ if zero(&d) => (CameraModel::Pinhole, Vec::new()),
        4 => (CameraModel::OpenCv, d.clone()),
        5 | 8 if zero(&d[4..]) => (CameraModel::OpenCv, d[..4].to_vec()),
        5 => (CameraModel::FullOpenCv, [&d[..], &[0.0; 3]].concat()),
        8 => (CameraModel::FullOpenCv, d.clone()),
        n => {
            return Err(invalid(
                d_key,
                format!(
                    "{n} coefficients: expected 4, 5 or 8 (k1, k2, p1, p2[, k3[, k4, k5, k6]])"
                ),
            ))
        }
    };
    let mut params = vec![k[0], k[4], k[2], k[5]];
    params.extend(coeffs);
    Camera::from_params(
        model,
        width,
        height,
        &params,
        readout,
        ReadoutDirection::TopToBottom,
    )
    .and_then(|c| c.validate().map(|_| c))
    .map_err(|e| invalid(k_key, e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const CV: &str = "%YAML:1.0\n---\ncalibration_time: \"Mon Jan  1 12:00:00 2024\"\nimage_width: 1280\nimage_height: 720\nflags: 0\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 9.1e+02, 0., 6.4e+02, 0., 9.0e+02,\n       3.6e+02, 0., 0., 1. ]\ndistortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n   data: [ -0.12, 0.05, 1.0e-03, -2.0e-04, K3 ]\navg_reprojection_error: 0.21\n";

    fn with_k3(k3: &str) -> String {
        CV.replace("K3", k3)
    }

    #[test]
    fn coefficient_counts_map_to_colmap_models() {
        let c = parse_opencv_calibration(&with_k3("0."), 3e-5).unwrap();
        assert_eq!(c.model, CameraModel::OpenCv);
        assert_eq!(
            c.params(),
            vec![910.0, 900.0, 640.0, 360.0, -0.12, 0.05, 1e-3, -2e-4]
        );
        assert_eq!((c.width, c.height, c.readout), (1280.0, 720.0, 3e-5));
        let c = parse_opencv_calibration(&with_k3("0.01"), 3e-5).unwrap();
        assert_eq!(c.model, CameraModel::FullOpenCv);
        assert_eq!(
            c.params(),
            vec![910.0, 900.0, 640.0, 360.0, -0.12, 0.05, 1e-3, -2e-4, 0.01, 0.0, 0.0, 0.0]
        );
        // ROS camera_info spellings, 4 coefficients flagged as a fisheye's.
        let ros = "image_width: 640\nimage_height: 480\ncamera_name: cam\ncamera_matrix:\n  rows: 3\n  cols: 3\n  data: [400, 0, 320, 0, 401, 240, 0, 0, 1]\ndistortion_model: equidistant\ndistortion_coefficients:\n  rows: 1\n  cols: 4\n  data: [0.01, -0.02, 0.003, -0.001]\n";
        let c = parse_opencv_calibration(ros, 2e-5).unwrap();
        assert_eq!(c.model, CameraModel::OpenCvFisheye);
        assert_eq!(
            c.params(),
            vec![400.0, 401.0, 320.0, 240.0, 0.01, -0.02, 0.003, -0.001]
        );
        let plumb = ros.replace("equidistant", "plumb_bob");
        let c = parse_opencv_calibration(&plumb, 2e-5).unwrap();
        assert_eq!(c.model, CameraModel::OpenCv);
        // `K` and `D` as plain lists, 8 coefficients: the rational model.
        let kd = "image_width: 640\nimage_height: 480\nK: [400, 0, 320, 0, 400, 240, 0, 0, 1]\nD: [0.1, 0.01, 0, 0, 0.001, 0.05, 0.002, 0.0001]\n";
        let c = parse_opencv_calibration(kd, 2e-5).unwrap();
        assert_eq!(c.model, CameraModel::FullOpenCv);
        assert_eq!(c.params()[8..], [0.001, 0.05, 0.002, 0.0001]);
        let none = "image_width: 640\nimage_height: 480\nK: [400, 0, 320, 0, 400, 240, 0, 0, 1]\n";
        assert_eq!(
            parse_opencv_calibration(none, 2e-5).unwrap().model,
            CameraModel::Pinhole
        );
    }

    #[test]
    fn bad_files_name_the_key() {
        let cases = [
            (
                with_k3("0.").replace("camera_matrix", "camera_matrx"),
                "camera_matrix",
            ),
            (
                with_k3("0.").replace("image_height", "image_heigth"),
                "image_height",
            ),
            (
                with_k3("0.").replace("cols: 5", "cols: 4"),
                "distortion_coefficients.data",
            ),
            (
                with_k3("0.")
                    .replace("1.0e-03, -2.0e-04, ", "")
                    .replace("cols: 5", "cols: 3"),
                "distortion_coefficients",
            ),
            (
                with_k3("0.").replace("9.1e+02, 0.,", "9.1e+02, 3.,"),
                "camera_matrix",
            ),
            (
                with_k3("0.").replace("flags: 0", "fisheye: 1"),
                "distortion_coefficients",
            ),
            (
                with_k3("0.").replace("9.1e+02", "-9.1e+02"),
                "camera_matrix",
            ),
        ];
        for (text, key) in cases {
            let e = parse_opencv_calibration(&text, 3e-5)
                .unwrap_err()
                .to_string();
            assert!(e.contains(&format!("`{key}`")), "{key}: {e}");
        }
        let e = parse_opencv_calibration("a: [1,\n", 3e-5).unwrap_err();
        assert!(
            matches!(e, CalibrationImportError::Yaml(ref y) if y.line == 1),
            "{e}"
        );
    }
}
