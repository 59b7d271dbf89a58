//! The pair classes: `GyroLog`, `GroundTruth` and `Pair` (`Camera` is in `camera.rs`), each
//! a view of the library's pair-file types (`rspose::pair_file`), so that a pair made in
//! Python is checked by the same code, with the same messages, as a pair file the command
//! line reads.

use crate::camera::{cameras_of, Camera};
use crate::convert::{pair_file_error, rows_array, rows_of, type_name, vector_array, vector_of};
use crate::options::{request, Request};
use crate::result::{failure_error, Estimate};
use numpy::ndarray::Array1;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rspose_core::data::pair_file::{
    gravity_from_json, matrix_from_rows, GroundTruth as RsGroundTruth, GyroLogSpec, Match, PairFile,
};
use std::path::PathBuf;
use std::sync::Arc;

/// Gyroscope samples around the two frames of a pair (the pair file's ``gyro_log``):
/// ``samples`` is N x 4, ``[t, wx, wy, wz]`` on the gyro's clock (s) and in the gyro's axes
/// (rad/s, bias removed), increasing ``t``; ``frame_times`` the times of image 1 and 2;
/// ``camera_from_gyro`` the rotation ``M`` with ``w_cam = M w_gyro`` (default identity);
/// ``time_offset`` the gyro time of an image's row 0 minus its frame time (s). With a log,
/// each image's row rotations are integrated from the samples over its readout, which they
/// must cover with no gap longer than the readout (checked when a pair is made from it).
#[pyclass(module = "rspose", frozen, from_py_object)]
#[derive(Clone)]
pub struct GyroLog {
    /// The library's log specification.
    pub inner: Arc<GyroLogSpec>,
}

/// A log specification from Python arguments (shapes checked; values when a pair uses it).
fn spec_of(
    samples: &Bound<'_, PyAny>,
    frame_times: &Bound<'_, PyAny>,
    camera_from_gyro: Option<&Bound<'_, PyAny>>,
    time_offset: f64,
) -> PyResult<GyroLogSpec> {
    Ok(GyroLogSpec {
        samples: rows_of::<4>(samples, "samples", "[t, wx, wy, wz] per sample")?,
        frame_times: vector_of::<2>(frame_times, "frame_times", "[t1, t2]")?,
        camera_from_gyro: match camera_from_gyro {
            Some(m) => crate::convert::matrix_rows(m, "camera_from_gyro")?,
            None => rspose_core::data::pair_file::rows_of_matrix(&nalgebra::Matrix3::identity()),
        },
        time_offset,
        gyro_bias: None,
    })
}

#[pymethods]
impl GyroLog {
    #[new]
    #[pyo3(signature = (samples, frame_times, camera_from_gyro=None, time_offset=0.0))]
    fn new(
        samples: &Bound<'_, PyAny>,
        frame_times: &Bound<'_, PyAny>,
        camera_from_gyro: Option<&Bound<'_, PyAny>>,
        time_offset: f64,
    ) -> PyResult<Self> {
        Ok(GyroLog {
            inner: Arc::new(spec_of(
                samples,
                frame_times,
                camera_from_gyro,
                time_offset,
            )?),
        })
    }

    /// The part of a long, sorted log that a pair needs, as ``rspose make-pair`` keeps it:
    /// the samples within ``margin`` seconds of the two readouts
    /// ``[t_k + time_offset, t_k + time_offset + duration]`` (``duration`` = height x
    /// readout of the camera) and everything between them, plus one sample beyond each end.
    #[staticmethod]
    #[pyo3(signature = (samples, frame_times, duration, margin=0.03, camera_from_gyro=None, time_offset=0.0))]
    fn excerpt(
        samples: &Bound<'_, PyAny>,
        frame_times: &Bound<'_, PyAny>,
        duration: f64,
        margin: f64,
        camera_from_gyro: Option<&Bound<'_, PyAny>>,
        time_offset: f64,
    ) -> PyResult<Self> {
        let spec = spec_of(samples, frame_times, camera_from_gyro, time_offset)?;
        if !(margin.is_finite() && margin >= 0.0) {
            return Err(PyValueError::new_err(
                "margin must be finite and non-negative",
            ));
        }
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(PyValueError::new_err(
                "duration must be finite and non-negative",
            ));
        }
        Ok(GyroLog {
            inner: Arc::new(GyroLogSpec::excerpt(
                &spec.samples,
                spec.camera_from_gyro,
                spec.time_offset,
                spec.frame_times,
                duration,
                margin,
            )),
        })
    }

    /// The samples, N x 4 ``[t, wx, wy, wz]`` (gyro clock and axes).
    #[getter]
    fn samples<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_array(py, &self.inner.samples)
    }
    /// Frame times of image 1 and image 2, s.
    #[getter]
    fn frame_times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        Array1::from_iter(self.inner.frame_times).into_pyarray(py)
    }
    /// ``M`` with ``w_cam = M w_gyro``.
    #[getter]
    fn camera_from_gyro<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        crate::convert::matrix_array(py, &matrix_from_rows(&self.inner.camera_from_gyro))
    }
    /// Gyro time of an image's row 0 minus its frame time, s.
    #[getter]
    fn time_offset(&self) -> f64 {
        self.inner.time_offset
    }

    fn __len__(&self) -> usize {
        self.inner.samples.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "GyroLog({} samples, frame_times=[{}, {}], time_offset={})",
            self.inner.samples.len(),
            self.inner.frame_times[0],
            self.inner.frame_times[1],
            self.inner.time_offset
        )
    }
}

/// The ground truth of a simulated pair: ``rotation`` R = R2 R1^T (3 x 3), unit
/// ``translation`` t = R2 (C1 - C2) / |.|, the true rates ``omega`` (2 x 3, rad/s, camera
/// axes), the true linear ``velocity`` (2 x 3, m/s, world axes) and the ``inliers`` mask
/// (False: a simulated outlier).
#[pyclass(module = "rspose", frozen)]
pub struct GroundTruth {
    inner: RsGroundTruth,
}

#[pymethods]
impl GroundTruth {
    /// R = R2 R1^T, 3 x 3.
    #[getter]
    fn rotation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_array(py, &self.inner.rotation)
    }
    /// Unit t = R2 (C1 - C2) / |.|.
    #[getter]
    fn translation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector_array(py, &self.inner.translation_vector())
    }
    /// True angular velocities of both views, 2 x 3, rad/s, camera axes.
    #[getter]
    fn omega<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_array(py, &self.inner.omega)
    }
    /// True linear velocities of both cameras, 2 x 3, m/s, world axes.
    #[getter]
    fn velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_array(py, &self.inner.velocity)
    }
    /// One flag per match (False: a simulated outlier).
    #[getter]
    fn inliers<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        Array1::from_vec(self.inner.inliers.clone()).into_pyarray(py)
    }
}

/// Where a pair came from: its file (errors of its estimates are prefixed with the path, as
/// on the command line) or Python.
#[derive(Clone)]
pub struct Source {
    /// The file, if loaded from one.
    pub path: Option<PathBuf>,
}

/// Two rolling-shutter images: pixel matches ``x1``, ``x2`` (N x 2, ``[u, v]`` with v the
/// row), ``camera`` for both images or ``cameras`` (one per image), the gyroscope reading of each view in camera axes (rad/s) or a
/// ``GyroLog``, optionally each view's gravity direction (camera axes, any length), and for
/// simulated pairs the ground truth. The pair file of the command line
/// (``rspose.load_pair``, ``Pair.save``); made in Python, it is checked by the same code
/// with the same messages (``ValueError``).
#[pyclass(module = "rspose", frozen)]
#[derive(Clone)]
pub struct Pair {
    /// The library's pair file.
    pub inner: Arc<PairFile>,
    /// Its file, if any.
    pub source: Source,
}

/// Gravity of the two views, through the pair file's own reading of its `gravity` field
/// (both views or neither; the same messages).
fn gravity_value(
    g1: Option<&Bound<'_, PyAny>>,
    g2: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<[[f64; 3]; 2]>> {
    let what = "[gx, gy, gz] (camera axes)";
    let g = [
        g1.map(|g| vector_of::<3>(g, "gravity1", what))
            .transpose()?,
        g2.map(|g| vector_of::<3>(g, "gravity2", what))
            .transpose()?,
    ];
    if g == [None, None] {
        return Ok(None);
    }
    // The shape as the file would hold it (zeros stand for the numbers, which JSON could
    // not hold if non-finite; the pair's validation checks the numbers themselves).
    let shape = serde_json::json!(g.map(|v| v.map(|_| [0.0; 3])));
    gravity_from_json(&shape).map_err(PyValueError::new_err)?;
    Ok(Some([g[0].unwrap_or_default(), g[1].unwrap_or_default()]))
}

impl Pair {
    /// Estimates this pair with the GIL released; errors of a pair loaded from a file name
    /// the file.
    pub fn estimate_with(&self, py: Python<'_>, req: &Request) -> PyResult<Estimate> {
        let inner = self.inner.clone();
        py.detach(|| req.estimate(&inner))
            .map(Estimate::new)
            .map_err(|f| failure_error(&f, self.source.path.as_ref()))
    }

    /// A checked pair from Python arguments (see the class documentation).
    #[allow(clippy::too_many_arguments)]
    pub fn from_args(
        x1: &Bound<'_, PyAny>,
        x2: &Bound<'_, PyAny>,
        camera: Option<&Bound<'_, PyAny>>,
        cameras: Option<&Bound<'_, PyAny>>,
        gyro1: Option<&Bound<'_, PyAny>>,
        gyro2: Option<&Bound<'_, PyAny>>,
        gyro_log: Option<&Bound<'_, PyAny>>,
        gravity1: Option<&Bound<'_, PyAny>>,
        gravity2: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let p1 = rows_of::<2>(x1, "x1", "pixels [u, v] in image 1")?;
        let p2 = rows_of::<2>(x2, "x2", "pixels [u, v] in image 2")?;
        if p1.len() != p2.len() {
            return Err(PyValueError::new_err(format!(
                "x1 and x2 must have the same number of rows (one per match), got {} and {}",
                p1.len(),
                p2.len()
            )));
        }
        let matches: Vec<Match> = p1.into_iter().zip(p2).map(|(a, b)| [a, b]).collect();
        let cameras = cameras_of(camera, cameras)?;
        let gyro = match (gyro1, gyro2) {
            (None, None) => None,
            (Some(a), Some(b)) => Some([
                vector_of::<3>(a, "gyro1", "[wx, wy, wz] (rad/s, camera axes)")?,
                vector_of::<3>(b, "gyro2", "[wx, wy, wz] (rad/s, camera axes)")?,
            ]),
            _ => {
                return Err(PyValueError::new_err(
                    "give the gyro readings of both views (gyro1 and gyro2) or neither",
                ))
            }
        };
        let gyro_log = match gyro_log {
            None => None,
            Some(g) => Some(
                g.cast::<GyroLog>()
                    .map_err(|_| {
                        PyTypeError::new_err(format!(
                            "gyro_log: expected rspose.GyroLog, got {}",
                            type_name(g)
                        ))
                    })?
                    .get()
                    .inner
                    .as_ref()
                    .clone(),
            ),
        };
        let gravity = gravity_value(gravity1, gravity2)?;
        let pair = PairFile {
            cameras,
            gyro,
            gyro_bias: None,
            gyro_log,
            gravity,
            matches,
            ground_truth: None,
        };
        pair.validate().map_err(|e| pair_file_error(&e))?;
        Ok(Pair {
            inner: Arc::new(pair),
            source: Source { path: None },
        })
    }

    /// A pair of the library (already checked), from `path` if given.
    pub fn wrap(pair: PairFile, path: Option<PathBuf>) -> Self {
        Pair {
            inner: Arc::new(pair),
            source: Source { path },
        }
    }
}

#[pymethods]
impl Pair {
    #[new]
    #[pyo3(signature = (x1, x2, camera=None, gyro1=None, gyro2=None, *, cameras=None, gyro_log=None, gravity1=None, gravity2=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        x1: &Bound<'_, PyAny>,
        x2: &Bound<'_, PyAny>,
        camera: Option<&Bound<'_, PyAny>>,
        gyro1: Option<&Bound<'_, PyAny>>,
        gyro2: Option<&Bound<'_, PyAny>>,
        cameras: Option<&Bound<'_, PyAny>>,
        gyro_log: Option<&Bound<'_, PyAny>>,
        gravity1: Option<&Bound<'_, PyAny>>,
        gravity2: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        Pair::from_args(
            x1, x2, camera, cameras, gyro1, gyro2, gyro_log, gravity1, gravity2,
        )
    }

    /// Pixels in image 1, N x 2 ``[u, v]``.
    #[getter]
    fn x1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let rows: Vec<[f64; 2]> = self.inner.matches.iter().map(|m| m[0]).collect();
        rows_array(py, &rows)
    }
    /// Pixels in image 2, N x 2 ``[u, v]``.
    #[getter]
    fn x2<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let rows: Vec<[f64; 2]> = self.inner.matches.iter().map(|m| m[1]).collect();
        rows_array(py, &rows)
    }
    /// The camera of both images; ``ValueError`` if the images have different cameras
    /// (see ``cameras``).
    #[getter]
    fn camera(&self) -> PyResult<Camera> {
        let [c1, c2] = self.inner.cameras;
        if c1 != c2 {
            return Err(PyValueError::new_err(
                "the two images have different cameras: use Pair.cameras",
            ));
        }
        Ok(Camera { inner: c1 })
    }
    /// The cameras of image 1 and image 2.
    #[getter]
    fn cameras(&self) -> (Camera, Camera) {
        let [c1, c2] = self.inner.cameras;
        (Camera { inner: c1 }, Camera { inner: c2 })
    }
    /// Gyro reading of view 1 (rad/s, camera axes), or None.
    #[getter]
    fn gyro1<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.inner
            .gyro
            .map(|g| vector_array(py, &nalgebra::Vector3::from(g[0])))
    }
    /// Gyro reading of view 2 (rad/s, camera axes), or None.
    #[getter]
    fn gyro2<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.inner
            .gyro
            .map(|g| vector_array(py, &nalgebra::Vector3::from(g[1])))
    }
    /// Gravity direction of view 1 (camera axes at row 0), or None.
    #[getter]
    fn gravity1<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.inner
            .gravity
            .map(|g| vector_array(py, &nalgebra::Vector3::from(g[0])))
    }
    /// Gravity direction of view 2 (camera axes at row 0), or None.
    #[getter]
    fn gravity2<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.inner
            .gravity
            .map(|g| vector_array(py, &nalgebra::Vector3::from(g[1])))
    }
    /// The gyro samples, or None.
    #[getter]
    fn gyro_log(&self) -> Option<GyroLog> {
        self.inner.gyro_log.as_ref().map(|s| GyroLog {
            inner: Arc::new(s.clone()),
        })
    }
    /// The ground truth of a simulated pair, or None.
    #[getter]
    fn ground_truth(&self) -> Option<GroundTruth> {
        self.inner
            .ground_truth
            .as_ref()
            .map(|g| GroundTruth { inner: g.clone() })
    }
    /// The file the pair was loaded from, or None.
    #[getter]
    fn path(&self) -> Option<PathBuf> {
        self.source.path.clone()
    }

    /// The relative rotation R = R2 R1^T integrated from the gyro log between the two
    /// frames' first rows (the rotation reference of real recordings), or None without a
    /// log whose samples span both frames.
    fn gyro_relative_rotation<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.inner
            .gyro_relative_rotation()
            .map(|r| crate::convert::matrix_array(py, &r))
    }

    /// Estimates the relative pose of this pair: ``method``, ``rows``, ``preset`` and
    /// ``**options`` as for ``estimate_relative_pose``. Errors of a pair loaded from a file
    /// name the file, as ``rspose estimate`` does.
    #[pyo3(signature = (method="grsrp+", *, rows="integrated", preset="default", **options))]
    fn estimate(
        &self,
        py: Python<'_>,
        method: &str,
        rows: &str,
        preset: &str,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Estimate> {
        let req = request(method, preset, rows, options, "estimate")?;
        self.estimate_with(py, &req)
    }

    /// Writes the pair file (JSON) atomically; ``compact`` writes one line.
    #[pyo3(signature = (path, compact=false))]
    fn save(&self, path: PathBuf, compact: bool) -> PyResult<()> {
        self.inner
            .save_atomic_as(&path, compact)
            .map_err(|e| pair_file_error(&e))
    }

    /// The pair file's JSON text.
    fn to_json(&self) -> String {
        self.inner.to_json_string()
    }

    fn __len__(&self) -> usize {
        self.inner.matches.len()
    }

    fn __repr__(&self) -> String {
        let from = match &self.source.path {
            Some(p) => format!(", path={:?}", p.display().to_string()),
            None => String::new(),
        };
        format!(
            "Pair({} matches, gyro_log={}, gravity={}, ground_truth={}{from})",
            self.inner.matches.len(),
            self.inner.gyro_log.is_some(),
            self.inner.gravity.is_some(),
            self.inner.ground_truth.is_some()
        )
    }
}

/// Reads and checks a pair file (errors as ``rspose estimate`` reports them: ``OSError`` for
/// an unreadable file, ``ValueError`` for a malformed one).
#[pyfunction]
pub fn load_pair(path: PathBuf) -> PyResult<Pair> {
    let pair = PairFile::load(&path).map_err(|e| pair_file_error(&e))?;
    Ok(Pair::wrap(pair, Some(path)))
}
