//! The `Estimate` class (the library's estimate with its quality report) and a failed
//! pair's exception, with the command line's messages.

use crate::convert::{
    estimate_error, json_to_python, matrix_array, pair_file_error, rows_array, vector_array,
};
use numpy::ndarray::Array1;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rspose_core::data::pair_estimate::PairEstimateError;
use rspose_core::data::pair_file::PairFileError;
use rspose_core::Estimate as RsEstimate;
use std::path::PathBuf;

/// A relative pose and its quality report. ``rotation`` R (3 x 3) and unit ``translation``
/// t take row-0 camera-1 coordinates to row-0 camera-2 coordinates, x2 = R x1 + t;
/// ``inliers`` is a bool mask over the matches. ``to_dict()`` is the object
/// ``rspose estimate --json`` prints (without its timing and reference errors).
#[pyclass(module = "rspose", frozen)]
pub struct Estimate {
    inner: RsEstimate,
}

impl Estimate {
    /// Wraps the library's estimate.
    pub fn new(inner: RsEstimate) -> Self {
        Estimate { inner }
    }
}

#[pymethods]
impl Estimate {
    /// The method's name.
    #[getter]
    fn method(&self) -> &'static str {
        self.inner.method.name()
    }
    /// Relative rotation R = R2 R1^T, 3 x 3.
    #[getter]
    fn rotation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        matrix_array(py, &self.inner.rotation)
    }
    /// Unit relative translation t = R2 (C1 - C2) / |.|.
    #[getter]
    fn translation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_array(py, &self.inner.translation)
    }
    /// Inlier mask, one flag per match (for ``nrsrp``: its ``gsrp`` initialisation's).
    #[getter]
    fn inliers<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        Array1::from_vec(self.inner.inliers.clone()).into_pyarray(py)
    }
    /// Number of inliers.
    #[getter]
    fn num_inliers(&self) -> usize {
        self.inner.num_inliers()
    }
    /// RANSAC iterations of the final RANSAC stage.
    #[getter]
    fn iterations(&self) -> usize {
        self.inner.iterations
    }
    /// MSAC score of the best hypothesis (squared threshold units).
    #[getter]
    fn ransac_score(&self) -> f64 {
        self.inner.ransac_score
    }
    /// Levenberg-Marquardt iterations of the final refinement (0 if none).
    #[getter]
    fn refinement_iterations(&self) -> usize {
        self.inner.refinement_iterations
    }
    /// Final cost of the refinement, or None without one.
    #[getter]
    fn refinement_cost(&self) -> Option<f64> {
        self.inner.refinement_cost
    }
    /// Inliers over matches.
    #[getter]
    fn inlier_ratio(&self) -> f64 {
        self.inner.quality.inlier_ratio
    }
    /// Median parallax of the inliers left by the best pure rotation, pixels.
    #[getter]
    fn parallax_px(&self) -> f64 {
        self.inner.quality.parallax_px
    }
    /// Median distance of the inliers from their epipolar planes, pixels.
    #[getter]
    fn epipolar_px(&self) -> f64 {
        self.inner.quality.epipolar_px
    }
    /// Median transfer error of the inliers under the best homography, pixels.
    #[getter]
    fn homography_px(&self) -> f64 {
        self.inner.quality.homography_px
    }
    /// Names of the raised quality flags: ``too_few_inliers``,
    /// ``translation_undetermined``, ``near_planar``, ``low_inlier_ratio``, ``collinear``,
    /// ``gyro_noise_runaway`` (``docs/ROBUSTNESS.md``).
    #[getter]
    fn flags(&self) -> Vec<&'static str> {
        self.inner.quality.flags()
    }
    /// The whole quality report as a dict (as in ``rspose estimate --json``).
    #[getter]
    fn quality<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_python(py, &serde_json::json!(self.inner.quality))
    }
    /// ``nrsrp`` only: estimated angular velocities, 2 x 3 (rad/s, camera axes); else None.
    #[getter]
    fn angular_velocity<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.inner
            .angular_velocity
            .map(|w| rows_array(py, &w.map(|v| [v.x, v.y, v.z])))
    }
    /// ``nrsrp`` and ``rectified+v``: estimated linear velocities, 2 x 3 (baselines per
    /// second, camera-1 row-0 frame); else None.
    #[getter]
    fn linear_velocity<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.inner
            .linear_velocity
            .map(|w| rows_array(py, &w.map(|v| [v.x, v.y, v.z])))
    }
    /// ``rectified+v`` only: what its velocity stage did, a dict with ``outcome`` and its
    /// statistics; else None.
    #[getter]
    fn velocity_fit<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.inner
            .velocity_fit
            .map(|f| json_to_python(py, &serde_json::json!(f)))
            .transpose()
    }

    /// The gyro-rate noise fitted to the final pose's residuals (``fit_gyro_noise``), a
    /// dict with ``gyro_noise`` (rad/s per axis) and ``truncation``; else None.
    #[getter]
    fn noise_fit<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.inner
            .noise_fit
            .map(|f| {
                let d = PyDict::new(py);
                d.set_item("gyro_noise", f.gyro_noise)?;
                d.set_item("truncation", f.truncation)?;
                Ok(d.into_any())
            })
            .transpose()
    }

    /// With ``refine_readout=True``: the readout time the pose was refined with, over the
    /// views' nominal one; else None.
    #[getter]
    fn readout_scale(&self) -> Option<f64> {
        self.inner.readout_scale
    }

    /// The object ``rspose estimate --json`` prints, without ``seconds`` and the pair file's
    /// reference errors (``inliers`` is the count there).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_python(py, &self.inner.report_json())
    }

    fn __repr__(&self) -> String {
        let q = &self.inner.quality;
        format!(
            "Estimate(method={:?}, inliers={}/{}, iterations={}, inlier_ratio={:.3}, flags={:?})",
            self.inner.method.name(),
            self.inner.num_inliers(),
            self.inner.inliers.len(),
            self.inner.iterations,
            q.inlier_ratio,
            q.flags()
        )
    }
}

/// A failed pair estimate as a Python exception, with the pair file's path as the command
/// line writes it.
pub fn failure_error(f: &PairEstimateError, path: Option<&PathBuf>) -> PyErr {
    let prefix = path.map(|p| p.display().to_string());
    match f {
        PairEstimateError::Pair(e @ PairFileError::InvalidField { .. }) => match &prefix {
            Some(p) => PyValueError::new_err(format!("{p}: {e}")),
            None => pair_file_error(e),
        },
        PairEstimateError::Pair(e) => pair_file_error(e),
        PairEstimateError::NoGyroRotation(_) => {
            let message = "r0_source `gyro` needs a gyro_log whose samples span both frames";
            PyValueError::new_err(match &prefix {
                Some(p) => format!("{p}: {message}"),
                None => message.to_string(),
            })
        }
        PairEstimateError::Estimate(e) => estimate_error(e, prefix.as_deref()),
    }
}
