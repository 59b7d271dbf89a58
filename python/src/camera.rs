//! The `Camera` class and the cameras of a pair from Python arguments: a view of the
//! library's `Camera` (`rspose::model::camera`), read from dicts by the pair file's own
//! parser, so that the messages are the command line's.

use crate::convert::{type_name, vector_array, vector_of};
use numpy::ndarray::Array1;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use rspose_core::model::camera::{Camera as RsCamera, CameraError, ReadoutDirection};
use rspose_core::model::camera_model::CameraModel;

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

/// A camera parameter `name` as a float: `TypeError` for a bool (which Python would take
/// as 0 or 1, hiding a misplaced flag) or anything that is not a real number.
fn real(v: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    let not_a_number = || {
        PyTypeError::new_err(format!(
            "Camera: `{name}` must be a number, got {}",
            type_name(v)
        ))
    };
    if v.is_instance_of::<pyo3::types::PyBool>() {
        return Err(not_a_number());
    }
    v.extract::<f64>().map_err(|_| not_a_number())
}

#[pymethods]
impl Camera {
    #[new]
    #[pyo3(signature = (fx, fy, cx, cy, width, height, readout, *, readout_direction="top_to_bottom"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        fx: &Bound<'_, PyAny>,
        fy: &Bound<'_, PyAny>,
        cx: &Bound<'_, PyAny>,
        cy: &Bound<'_, PyAny>,
        width: &Bound<'_, PyAny>,
        height: &Bound<'_, PyAny>,
        readout: &Bound<'_, PyAny>,
        readout_direction: &str,
    ) -> PyResult<Self> {
        let [fx, fy, cx, cy, width, height, readout] = [
            (fx, "fx"),
            (fy, "fy"),
            (cx, "cx"),
            (cy, "cy"),
            (width, "width"),
            (height, "height"),
            (readout, "readout"),
        ]
        .map(|(v, name)| real(v, name));
        Ok(Camera {
            inner: RsCamera {
                readout_direction: direction_of(readout_direction)?,
                ..RsCamera::pinhole(fx?, fy?, cx?, cy?, width?, height?, readout?)
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
