//! The pair classes: `Camera`, `GyroLog`, `GroundTruth` and `Pair`, each a view of the
//! library's pair-file types (`rspose::pair_file`), so that a pair made in Python is checked
//! by the same code, with the same messages, as a pair file the command line reads.

use crate::convert::{pair_file_error, rows_array, rows_of, type_name, vector_array, vector_of};
use numpy::ndarray::Array1;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use rspose_core::data::pair_file::{
    gravity_from_json, matrix_from_rows, GroundTruth as RsGroundTruth, GyroLogSpec, Match, PairFile,
};
use rspose_core::model::camera::{Camera as RsCamera, CameraError, ReadoutDirection};
use rspose_core::model::camera_model::CameraModel;
use std::path::PathBuf;
use std::sync::Arc;

/// A rolling-shutter camera: a COLMAP camera model (``model``, ``params`` in COLMAP's
/// order), image size ``width`` x ``height`` (pixels), ``readout`` the readout time per line
/// (s/line; 0 for a global shutter) and ``readout_direction`` (``"top_to_bottom"``,
/// ``"bottom_to_top"``, ``"left_to_right"``, ``"right_to_left"``). ``Camera(fx, fy, cx, cy,
/// width, height, readout)`` is a ``PINHOLE``; ``Camera.from_params`` any model. A pixel's
/// bearing is its undistorted normalised coordinates, its time ``readout_line(u, v) x
/// readout``. Values are checked when a pair is made from it, with the command line's
/// messages (``invalid field `camera.fx`: ...``).
#[pyclass(module = "rspose", frozen, eq, from_py_object)]
#[derive(Clone, PartialEq)]
pub struct Camera {
    /// The library's camera.
    pub inner: RsCamera,
}

fn direction_of(name: &str) -> PyResult<ReadoutDirection> {
    ReadoutDirection::from_name(name).ok_or_else(|| {
        PyValueError::new_err(format!(
            "readout_direction: expected top_to_bottom, bottom_to_top, left_to_right or right_to_left, got `{name}`"
        ))
    })
}

#[pymethods]
impl Camera {
    #[new]
    #[pyo3(signature = (fx, fy, cx, cy, width, height, readout, *, readout_direction="top_to_bottom"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        fx: f64,
        fy: f64,
        cx: f64,
        cy: f64,
        width: f64,
        height: f64,
        readout: f64,
        readout_direction: &str,
    ) -> PyResult<Self> {
        Ok(Camera {
            inner: RsCamera {
                readout_direction: direction_of(readout_direction)?,
                ..RsCamera::pinhole(fx, fy, cx, cy, width, height, readout)
            },
        })
    }

    /// A camera of COLMAP's ``model`` (``SIMPLE_PINHOLE``, ``PINHOLE``, ``SIMPLE_RADIAL``,
    /// ``RADIAL``, ``OPENCV``, ``OPENCV_FISHEYE``, ``FULL_OPENCV``) with COLMAP's ``params``
    /// (e.g. ``[fx, fy, cx, cy, k1, k2, p1, p2]`` for ``OPENCV``). ``ValueError`` for an
    /// unknown model or a wrong number of params.
    #[staticmethod]
    #[pyo3(signature = (model, width, height, params, readout, readout_direction="top_to_bottom"))]
    fn from_params(
        model: &str,
        width: f64,
        height: f64,
        params: Vec<f64>,
        readout: f64,
        readout_direction: &str,
    ) -> PyResult<Self> {
        let m = CameraModel::from_name(model).ok_or_else(|| {
            PyValueError::new_err(CameraError::UnknownModel(model.to_string()).to_string())
        })?;
        let direction = direction_of(readout_direction)?;
        RsCamera::from_params(m, width, height, &params, readout, direction)
            .map(|inner| Camera { inner })
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// The paper's synthetic camera: 1920 x 1080, f = 640 px, principal point at the
    /// centre, 60 µs per row.
    #[staticmethod]
    fn paper() -> Self {
        Camera {
            inner: RsCamera::paper(),
        }
    }

    /// COLMAP's model name, e.g. ``"OPENCV"``.
    #[getter]
    fn model(&self) -> &'static str {
        self.inner.model.name()
    }
    /// COLMAP's parameters of the model, in its order.
    #[getter]
    fn params(&self) -> Vec<f64> {
        self.inner.params()
    }
    /// Focal length along u, pixels.
    #[getter]
    fn fx(&self) -> f64 {
        self.inner.fx
    }
    /// Focal length along v, pixels.
    #[getter]
    fn fy(&self) -> f64 {
        self.inner.fy
    }
    /// Principal point u, pixels.
    #[getter]
    fn cx(&self) -> f64 {
        self.inner.cx
    }
    /// Principal point v, pixels.
    #[getter]
    fn cy(&self) -> f64 {
        self.inner.cy
    }
    /// Image width, pixels.
    #[getter]
    fn width(&self) -> f64 {
        self.inner.width
    }
    /// Image height (rows), pixels.
    #[getter]
    fn height(&self) -> f64 {
        self.inner.height
    }
    /// Readout time per line, s.
    #[getter]
    fn readout(&self) -> f64 {
        self.inner.readout
    }
    /// The order in which lines are read, e.g. ``"top_to_bottom"``.
    #[getter]
    fn readout_direction(&self) -> &'static str {
        self.inner.readout_direction.name()
    }
    /// Lines read per frame (``height``, or ``width`` for a column readout).
    #[getter]
    fn lines(&self) -> f64 {
        self.inner.lines()
    }

    /// The bearing ``[x, y, 1]`` of pixel ``(u, v)``: its undistorted normalised
    /// coordinates. ``ValueError`` where the distortion is not invertible.
    fn undistort_bearing<'py>(
        &self,
        py: Python<'py>,
        u: f64,
        v: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.inner
            .undistort_bearing(u, v)
            .map(|b| vector_array(py, &b))
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// The line coordinate of raw pixel ``(u, v)``: ``v``, ``height - 1 - v``, ``u`` or
    /// ``width - 1 - u`` by the readout direction; read ``line x readout`` s after line 0.
    fn readout_line(&self, u: f64, v: f64) -> f64 {
        self.inner.readout_line(u, v)
    }

    /// The pixel ``[u, v]`` of camera-frame point ``point`` (distorted), or None behind the
    /// camera or where the distortion is not invertible.
    fn project<'py>(
        &self,
        py: Python<'py>,
        point: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyArray1<f64>>>> {
        let x = nalgebra::Vector3::from(vector_of::<3>(point, "point", "[x, y, z]")?);
        Ok(self
            .inner
            .project(&x)
            .map(|p| Array1::from_vec(vec![p.x, p.y]).into_pyarray(py)))
    }

    /// The camera as a dict, the pair file's ``camera`` object: the pinhole short form for a
    /// ``PINHOLE`` read from the top, else ``model``, ``width``, ``height``, ``params``,
    /// ``readout``, ``readout_direction``.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let value =
            serde_json::to_value(self.inner).map_err(|e| PyValueError::new_err(e.to_string()))?;
        if let serde_json::Value::Object(map) = value {
            for (k, v) in map {
                match v {
                    serde_json::Value::String(s) => d.set_item(k, s)?,
                    serde_json::Value::Array(a) => {
                        let numbers: Vec<f64> = a.iter().filter_map(|x| x.as_f64()).collect();
                        d.set_item(k, numbers)?
                    }
                    other => d.set_item(k, other.as_f64())?,
                }
            }
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let c = &self.inner;
        if c.model == CameraModel::Pinhole && c.readout_direction == ReadoutDirection::TopToBottom {
            return format!(
                "Camera(fx={}, fy={}, cx={}, cy={}, width={}, height={}, readout={})",
                c.fx, c.fy, c.cx, c.cy, c.width, c.height, c.readout
            );
        }
        format!(
            "Camera.from_params({:?}, {}, {}, {:?}, {}, {:?})",
            c.model.name(),
            c.width,
            c.height,
            c.params(),
            c.readout,
            c.readout_direction.name()
        )
    }
}

/// A camera from a `Camera` or a mapping with the pair file's keys: the pinhole short form
/// (`fx`, `fy`, `cx`, `cy`, `width`, `height`, `readout`) or COLMAP's (`model`, `width`,
/// `height`, `params`, `readout`, `readout_direction`), read by the pair file's own parser
/// (the same messages).
pub fn camera_of(obj: &Bound<'_, PyAny>) -> PyResult<RsCamera> {
    if let Ok(c) = obj.cast::<Camera>() {
        return Ok(c.get().inner);
    }
    let Ok(d) = obj.cast::<PyDict>() else {
        return Err(PyTypeError::new_err(format!(
            "camera: expected rspose.Camera or a dict (fx, fy, cx, cy, width, height, readout; or model, width, height, params, readout, readout_direction), got {}",
            type_name(obj)
        )));
    };
    let mut map = serde_json::Map::new();
    let mut raw_params = None;
    for (k, v) in d.iter() {
        let k: String = k.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "camera: keys must be strings, got {}",
                type_name(&k)
            ))
        })?;
        let value = match k.as_str() {
            "model" | "readout_direction" => {
                serde_json::Value::from(v.extract::<String>().map_err(|_| {
                    PyTypeError::new_err(format!(
                        "camera: field `{k}`: expected a string, got {}",
                        type_name(&v)
                    ))
                })?)
            }
            "params" => {
                let params = v.extract::<Vec<f64>>().map_err(|_| {
                    PyTypeError::new_err(format!(
                        "camera: field `params`: expected a list of numbers, got {}",
                        type_name(&v)
                    ))
                })?;
                let finite: Vec<f64> = params
                    .iter()
                    .map(|x| if x.is_finite() { *x } else { 0.0 })
                    .collect();
                raw_params = Some(params);
                serde_json::Value::from(finite)
            }
            _ => {
                let x = v.extract::<f64>().map_err(|_| {
                    PyTypeError::new_err(format!(
                        "camera: field `{k}`: expected a number, got {}",
                        type_name(&v)
                    ))
                })?;
                // Non-finite numbers, which JSON cannot hold, are checked with the pair.
                serde_json::Number::from_f64(x).map_or(serde_json::Value::from(0.0), Into::into)
            }
        };
        map.insert(k, value);
    }
    let nonfinite: Vec<(String, f64)> = d
        .iter()
        .filter_map(|(k, v)| Some((k.extract::<String>().ok()?, v.extract::<f64>().ok()?)))
        .filter(|(_, x)| !x.is_finite())
        .collect();
    let mut camera: RsCamera =
        serde_json::from_value(serde_json::Value::Object(map)).map_err(|e| {
            let e = e.to_string();
            PyValueError::new_err(if e.starts_with("camera:") {
                e
            } else {
                format!("camera: {e}")
            })
        })?;
    // Non-finite params, which JSON cannot hold, are put back for the pair's validation to
    // name them (the count was checked by the parser).
    if let Some(params) = raw_params.filter(|p| p.iter().any(|x| !x.is_finite())) {
        camera = RsCamera::from_params(
            camera.model,
            camera.width,
            camera.height,
            &params,
            camera.readout,
            camera.readout_direction,
        )
        .map_err(|e| PyValueError::new_err(format!("camera: {e}")))?;
    }
    for (k, x) in nonfinite {
        match k.as_str() {
            "fx" => camera.fx = x,
            "fy" => camera.fy = x,
            "cx" => camera.cx = x,
            "cy" => camera.cy = x,
            "width" => camera.width = x,
            "height" => camera.height = x,
            "readout" => camera.readout = x,
            _ => {}
        }
    }
    Ok(camera)
}

/// The two images' cameras from `camera` (both images) or `cameras` (one per image, a list
/// or tuple of two), exactly one of them, as the pair file's keys.
pub fn cameras_of(
    camera: Option<&Bound<'_, PyAny>>,
    cameras: Option<&Bound<'_, PyAny>>,
) -> PyResult<[RsCamera; 2]> {
    match (camera, cameras) {
        (Some(c), None) => {
            let c = camera_of(c)?;
            Ok([c, c])
        }
        (None, Some(cs)) => {
            let items: Vec<Bound<'_, PyAny>> = if let Ok(l) = cs.cast::<PyList>() {
                l.iter().collect()
            } else if let Ok(t) = cs.cast::<PyTuple>() {
                t.iter().collect()
            } else {
                return Err(PyTypeError::new_err(format!(
                    "cameras: expected a list or tuple of two cameras (image 1, image 2), got {}",
                    type_name(cs)
                )));
            };
            if items.len() != 2 {
                return Err(PyValueError::new_err(format!(
                    "`cameras` needs one camera for each of the two images, got {}",
                    items.len()
                )));
            }
            let one = |k: usize| {
                camera_of(&items[k]).map_err(|e| {
                    let py = cs.py();
                    let message = format!("cameras[{k}]: {}", e.value(py));
                    if e.is_instance_of::<PyTypeError>(py) {
                        PyTypeError::new_err(message)
                    } else {
                        PyValueError::new_err(message)
                    }
                })
            };
            Ok([one(0)?, one(1)?])
        }
        (Some(_), Some(_)) => Err(PyValueError::new_err(
            "give `camera` (both images) or `cameras` (one per image), not both",
        )),
        (None, None) => Err(PyTypeError::new_err(
            "missing `camera` (both images) or `cameras` (one per image)",
        )),
    }
}

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
    ) -> PyResult<crate::estimate::Estimate> {
        crate::estimate::estimate_wrapped(py, self, method, rows, preset, options)
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
