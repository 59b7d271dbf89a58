//! Keyword options of the estimators: the fields of `rspose::EstimateOptions` with their
//! Rust names, read onto a preset's options (the defaults are never restated here), and the
//! options back as a nested dict (`rspose.options()`). Every name of a choice (preset, rows,
//! solver, model, `R_0` source) is the library's (`FromStr`/`name()`).

use crate::convert::{matrix_array, matrix_rows, type_name};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};
use rspose_core::data::pair_estimate::{estimate_pair, PairEstimateError, R0Choice, RowModel};
use rspose_core::data::pair_file::PairFile;
use rspose_core::estimation::refine::LmOptions;
use rspose_core::methods::{
    Preset, QualityOptions, R0Source, RobustOptions, Threshold, VelocityOptions,
};
use rspose_core::minimal::{EssentialSolver, GravitySolver, GrsrpSolver};
use rspose_core::{Estimate, EstimateOptions, Method};

/// Everything an estimate of one pair needs besides the pair.
#[derive(Debug, Clone)]
pub struct Request {
    /// The options.
    pub options: EstimateOptions,
    /// `Some(R0Choice::Gyro)`: `R_0` from the pair's gyro log instead of
    /// `options.r0_source` (resolved per pair, as the command line's `--r0 gyro`).
    pub r0: Option<R0Choice>,
    /// The row rotations of pairs with a gyro log.
    pub rows: RowModel,
}

impl Request {
    /// Estimates `pair` with these options, rows and `R_0` (the library's
    /// `estimate_pair`, as `rspose estimate` does).
    pub fn estimate(&self, pair: &PairFile) -> Result<Estimate, PairEstimateError> {
        estimate_pair(pair, &self.options, self.rows, self.r0)
    }
}

/// A `ValueError` with the library's message.
fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// The method named `name` (`ValueError` with the library's message otherwise).
pub fn parse_method(name: &str) -> PyResult<Method> {
    name.parse::<Method>().map_err(value_error)
}

/// The essential solver named `name` (`five_point`, `eight_point`).
pub fn essential_solver(name: &str) -> PyResult<EssentialSolver> {
    name.parse().map_err(value_error)
}

/// The G-RSRP solver named `name` (`ten`, `twenty`).
pub fn grsrp_solver(name: &str) -> PyResult<GrsrpSolver> {
    name.parse().map_err(value_error)
}

/// The known-gravity solver named `name` (`six`, `twelve`).
pub fn gravity_solver(name: &str) -> PyResult<GravitySolver> {
    name.parse().map_err(value_error)
}

fn value<'py, T: for<'a> FromPyObject<'a, 'py>>(
    v: &Bound<'py, PyAny>,
    name: &str,
    expected: &str,
) -> PyResult<T> {
    v.extract::<T>().map_err(|_| {
        PyTypeError::new_err(format!(
            "option `{name}`: expected {expected}, got {}",
            type_name(v)
        ))
    })
}

fn float(v: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    value::<f64>(v, name, "a number")
}

fn count(v: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    if v.is_instance_of::<pyo3::types::PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "option `{name}`: expected a non-negative integer, got bool"
        )));
    }
    value::<usize>(v, name, "a non-negative integer")
}

fn flag(v: &Bound<'_, PyAny>, name: &str) -> PyResult<bool> {
    value::<bool>(v, name, "a bool")
}

fn text(v: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    value::<String>(v, name, "a string")
}

fn threshold(v: &Bound<'_, PyAny>, name: &str) -> PyResult<Threshold> {
    let expected = "a tuple (\"sampson_pixels\" or \"algebraic\", value)";
    let t = v.cast::<PyTuple>().map_err(|_| {
        PyTypeError::new_err(format!(
            "option `{name}`: expected {expected}, got {}",
            type_name(v)
        ))
    })?;
    if t.len() != 2 {
        return Err(PyTypeError::new_err(format!(
            "option `{name}`: expected {expected}, got a tuple of {}",
            t.len()
        )));
    }
    let kind = text(&t.get_item(0)?, name)?;
    let x = float(&t.get_item(1)?, name)?;
    match kind.as_str() {
        "sampson_pixels" => Ok(Threshold::SampsonPixels(x)),
        "algebraic" => Ok(Threshold::Algebraic(x)),
        other => Err(PyValueError::new_err(format!(
            "option `{name}`: unknown threshold kind `{other}` (expected sampson_pixels or algebraic)"
        ))),
    }
}

fn set_robust(r: &mut RobustOptions, key: &str, v: &Bound<'_, PyAny>) -> PyResult<bool> {
    let name = format!("robust.{key}");
    let name = name.as_str();
    match key {
        "threshold" => r.threshold = threshold(v, name)?,
        "global_shutter_threshold" => r.global_shutter_threshold = threshold(v, name)?,
        "rolling_shutter_allowance" => r.rolling_shutter_allowance = float(v, name)?,
        "adaptive" => r.adaptive = flag(v, name)?,
        "success_probability" => r.success_probability = float(v, name)?,
        "min_iterations" => r.min_iterations = count(v, name)?,
        "max_iterations" => r.max_iterations = count(v, name)?,
        "local_optimisation" => r.local_optimisation = flag(v, name)?,
        "final_refinement" => r.final_refinement = flag(v, name)?,
        "seed" => r.seed = value::<u64>(v, name, "a non-negative integer")?,
        "pixel_noise" => r.pixel_noise = float(v, name)?,
        "gyro_noise" => r.gyro_noise = float(v, name)?,
        "fit_gyro_noise" => r.fit_gyro_noise = flag(v, name)?,
        "max_points" => r.max_points = count(v, name)?,
        "gravity_noise_deg" => r.gravity_noise_deg = float(v, name)?,
        _ => return Ok(false),
    }
    Ok(true)
}

fn set_refinement(r: &mut LmOptions, key: &str, v: &Bound<'_, PyAny>) -> PyResult<bool> {
    let name = format!("refinement.{key}");
    let name = name.as_str();
    match key {
        "max_iterations" => r.max_iterations = count(v, name)?,
        "initial_damping" => r.initial_damping = float(v, name)?,
        "cost_tolerance" => r.cost_tolerance = float(v, name)?,
        "step_tolerance" => r.step_tolerance = float(v, name)?,
        "fd_step" => r.fd_step = float(v, name)?,
        _ => return Ok(false),
    }
    Ok(true)
}

fn set_quality(q: &mut QualityOptions, key: &str, v: &Bound<'_, PyAny>) -> PyResult<bool> {
    let name = format!("quality.{key}");
    let name = name.as_str();
    match key {
        "min_inliers" => q.min_inliers = count(v, name)?,
        "min_parallax_ratio" => q.min_parallax_ratio = float(v, name)?,
        "max_homography_ratio" => q.max_homography_ratio = float(v, name)?,
        "homography_threshold_px" => q.homography_threshold_px = float(v, name)?,
        _ => return Ok(false),
    }
    Ok(true)
}

fn set_velocity(o: &mut VelocityOptions, key: &str, v: &Bound<'_, PyAny>) -> PyResult<bool> {
    let name = format!("velocity.{key}");
    let name = name.as_str();
    match key {
        "prior_std" => o.prior_std = float(v, name)?,
        "loss_px" => o.loss_px = float(v, name)?,
        "significance" => o.significance = float(v, name)?,
        "rate_error_std" => o.rate_error_std = float(v, name)?,
        "rate_margin" => o.rate_margin = float(v, name)?,
        "min_inliers" => o.min_inliers = count(v, name)?,
        "rounds" => o.rounds = count(v, name)?,
        _ => return Ok(false),
    }
    Ok(true)
}

/// Applies the entries of the dict `v` (option `group`) with `set`; `TypeError` for an
/// entry the group does not have.
fn set_group<T>(
    target: &mut T,
    group: &str,
    v: &Bound<'_, PyAny>,
    set: fn(&mut T, &str, &Bound<'_, PyAny>) -> PyResult<bool>,
) -> PyResult<()> {
    let d = v.cast::<PyDict>().map_err(|_| {
        PyTypeError::new_err(format!(
            "option `{group}`: expected a dict, got {}",
            type_name(v)
        ))
    })?;
    for (k, v) in d.iter() {
        let key = text(&k, group)?;
        if !set(target, &key, &v)? {
            return Err(PyTypeError::new_err(format!(
                "unknown option `{group}.{key}`"
            )));
        }
    }
    Ok(())
}

/// `r0_source`: a name (`gyro` deferred to each pair) or a 3 x 3 rotation, set on `o`.
fn set_r0(o: &mut EstimateOptions, v: &Bound<'_, PyAny>) -> PyResult<Option<R0Choice>> {
    if let Ok(s) = v.cast::<PyString>() {
        let name = s.to_cow()?;
        let choice: R0Choice = name.parse().map_err(|_| {
            PyValueError::new_err(format!(
                "option `r0_source`: unknown source `{name}` (expected {} or a 3 x 3 rotation)",
                R0Choice::NAMES.join(", ")
            ))
        })?;
        if let Some(source) = choice.fixed_source() {
            o.r0_source = source;
            return Ok(None);
        }
        return Ok(Some(choice));
    }
    let rows = matrix_rows(v, "option `r0_source`")?;
    o.r0_source = R0Source::Given(rspose_core::data::pair_file::matrix_from_rows(&rows));
    Ok(None)
}

/// A `ValueError` about option `name`.
fn in_option(name: &str, e: PyErr) -> PyErr {
    Python::attach(|py| PyValueError::new_err(format!("option `{name}`: {}", e.value(py))))
}

/// The request for `method` with `preset`, `rows` and the keyword options applied (see the
/// module documentation); `TypeError` for an unknown keyword or a value of the wrong type,
/// `ValueError` for an unknown name. Values are checked by the library when it estimates.
pub fn request(
    method: &str,
    preset: &str,
    rows: &str,
    options: Option<&Bound<'_, PyDict>>,
    function: &str,
) -> PyResult<Request> {
    let method = parse_method(method)?;
    let mut o = preset
        .parse::<Preset>()
        .map_err(value_error)?
        .options(method);
    let mut r0 = None;
    if let Some(d) = options {
        for (k, v) in d.iter() {
            let key = text(&k, "keyword")?;
            match key.as_str() {
                "robust" => set_group(&mut o.robust, "robust", &v, set_robust)?,
                "refinement" => set_group(&mut o.refinement, "refinement", &v, set_refinement)?,
                "quality" => set_group(&mut o.quality, "quality", &v, set_quality)?,
                "velocity" => set_group(&mut o.velocity, "velocity", &v, set_velocity)?,
                "essential_solver" => {
                    o.essential_solver =
                        essential_solver(&text(&v, &key)?).map_err(|e| in_option(&key, e))?
                }
                "grsrp_solver" => {
                    o.grsrp_solver =
                        grsrp_solver(&text(&v, &key)?).map_err(|e| in_option(&key, e))?
                }
                "grsrp_model" => {
                    o.grsrp_model = text(&v, &key)?
                        .parse()
                        .map_err(|e| in_option(&key, value_error(e)))?
                }
                "gravity_solver" => {
                    o.gravity_solver =
                        gravity_solver(&text(&v, &key)?).map_err(|e| in_option(&key, e))?
                }
                "r0_source" => r0 = set_r0(&mut o, &v)?,
                "nrsrp_cauchy_px" => o.nrsrp_cauchy_px = float(&v, &key)?,
                "refine_readout" => {
                    o.readout = flag(&v, &key)?
                        .then(rspose_core::estimation::readout::ReadoutOptions::default)
                }
                other => {
                    if !set_robust(&mut o.robust, other, &v)? {
                        return Err(PyTypeError::new_err(format!(
                            "{function}() got an unexpected keyword argument '{other}'"
                        )));
                    }
                }
            }
        }
    }
    Ok(Request {
        options: o,
        r0,
        rows: rows.parse().map_err(value_error)?,
    })
}

fn threshold_value<'py>(py: Python<'py>, t: Threshold) -> PyResult<Bound<'py, PyAny>> {
    let (kind, x) = match t {
        Threshold::SampsonPixels(x) => ("sampson_pixels", x),
        Threshold::Algebraic(x) => ("algebraic", x),
    };
    Ok((kind, x).into_pyobject(py)?.into_any())
}

/// The request's options as a nested dict with the Rust field names (the input of
/// `**options` round-trips through it).
pub fn options_dict<'py>(py: Python<'py>, req: &Request) -> PyResult<Bound<'py, PyDict>> {
    let o = &req.options;
    let d = PyDict::new(py);
    d.set_item("method", o.method.name())?;
    let r = &o.robust;
    let robust = PyDict::new(py);
    robust.set_item("threshold", threshold_value(py, r.threshold)?)?;
    robust.set_item(
        "global_shutter_threshold",
        threshold_value(py, r.global_shutter_threshold)?,
    )?;
    robust.set_item("rolling_shutter_allowance", r.rolling_shutter_allowance)?;
    robust.set_item("adaptive", r.adaptive)?;
    robust.set_item("success_probability", r.success_probability)?;
    robust.set_item("min_iterations", r.min_iterations)?;
    robust.set_item("max_iterations", r.max_iterations)?;
    robust.set_item("local_optimisation", r.local_optimisation)?;
    robust.set_item("final_refinement", r.final_refinement)?;
    robust.set_item("seed", r.seed)?;
    robust.set_item("pixel_noise", r.pixel_noise)?;
    robust.set_item("gyro_noise", r.gyro_noise)?;
    robust.set_item("fit_gyro_noise", r.fit_gyro_noise)?;
    robust.set_item("max_points", r.max_points)?;
    robust.set_item("gravity_noise_deg", r.gravity_noise_deg)?;
    d.set_item("robust", robust)?;
    let l = &o.refinement;
    let refinement = PyDict::new(py);
    refinement.set_item("max_iterations", l.max_iterations)?;
    refinement.set_item("initial_damping", l.initial_damping)?;
    refinement.set_item("cost_tolerance", l.cost_tolerance)?;
    refinement.set_item("step_tolerance", l.step_tolerance)?;
    refinement.set_item("fd_step", l.fd_step)?;
    d.set_item("refinement", refinement)?;
    d.set_item("essential_solver", o.essential_solver.name())?;
    d.set_item("grsrp_solver", o.grsrp_solver.name())?;
    d.set_item("grsrp_model", o.grsrp_model.name())?;
    d.set_item("gravity_solver", o.gravity_solver.name())?;
    match (req.r0, o.r0_source) {
        (Some(choice), _) => d.set_item("r0_source", choice.name())?,
        (None, R0Source::Gsrp) => d.set_item("r0_source", R0Choice::Gsrp.name())?,
        (None, R0Source::Rectified) => d.set_item("r0_source", R0Choice::Rectified.name())?,
        (None, R0Source::Given(m)) => d.set_item("r0_source", matrix_array(py, &m))?,
    }
    d.set_item("nrsrp_cauchy_px", o.nrsrp_cauchy_px)?;
    d.set_item("refine_readout", o.readout.is_some())?;
    let q = &o.quality;
    let quality = PyDict::new(py);
    quality.set_item("min_inliers", q.min_inliers)?;
    quality.set_item("min_parallax_ratio", q.min_parallax_ratio)?;
    quality.set_item("max_homography_ratio", q.max_homography_ratio)?;
    quality.set_item("homography_threshold_px", q.homography_threshold_px)?;
    d.set_item("quality", quality)?;
    let v = &o.velocity;
    let velocity = PyDict::new(py);
    velocity.set_item("prior_std", v.prior_std)?;
    velocity.set_item("loss_px", v.loss_px)?;
    velocity.set_item("significance", v.significance)?;
    velocity.set_item("rate_error_std", v.rate_error_std)?;
    velocity.set_item("rate_margin", v.rate_margin)?;
    velocity.set_item("min_inliers", v.min_inliers)?;
    velocity.set_item("rounds", v.rounds)?;
    d.set_item("velocity", velocity)?;
    Ok(d)
}
