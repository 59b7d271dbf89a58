//! Conversions between Python objects (numpy arrays, sequences, dicts) and the library's
//! types, and between the library's errors and Python exceptions.

use nalgebra::{Matrix3, Vector3};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rspose_core::data::pair_file::PairFileError;
use rspose_core::EstimateError;

pyo3::create_exception!(
    rspose,
    NoSolutionError,
    pyo3::exceptions::PyRuntimeError,
    "Valid input without an answer: every RANSAC hypothesis failed or the geometry is \
     degenerate (the command line's exit code 1, `no solution found`)."
);

/// An estimation error as a Python exception: `NoSolutionError` for valid input without an
/// answer, `ValueError` for bad input; `prefix` (a pair file's path) as the command line
/// writes it.
pub fn estimate_error(e: &EstimateError, prefix: Option<&str>) -> PyErr {
    let message = match prefix {
        Some(p) => format!("{p}: {e}"),
        None => e.to_string(),
    };
    match e {
        EstimateError::NoSolution => NoSolutionError::new_err(message),
        _ => PyValueError::new_err(message),
    }
}

/// A pair-file error as a Python exception: `OSError` for a file that cannot be read or
/// written, `ValueError` otherwise; the message is the command line's.
pub fn pair_file_error(e: &PairFileError) -> PyErr {
    match e {
        PairFileError::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// `obj` as a float64 numpy array (`numpy.asarray(obj, dtype=float64)`); `TypeError`
/// naming `name` if it is not numbers or is complex.
pub fn float_array<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let py = obj.py();
    let np = py.import("numpy")?;
    // numpy converts complex to float64 by dropping the imaginary part (a warning only).
    if np.getattr("iscomplexobj")?.call1((obj,))?.is_truthy()? {
        return Err(PyTypeError::new_err(format!(
            "{name}: expected an array of real numbers, got complex values"
        )));
    }
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", np.getattr("float64")?)?;
    let array = np
        .getattr("asarray")?
        .call((obj,), Some(&kwargs))
        .map_err(|e| {
            PyTypeError::new_err(format!(
                "{name}: expected an array of numbers, got {} ({})",
                type_name(obj),
                e.value(py)
            ))
        })?;
    array
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected an array of numbers")))
}

/// An optional non-negative integer argument `name` (at most `max`): `TypeError` for
/// anything but an int (a bool included), `ValueError` for an int out of range (which pyo3
/// would raise as `OverflowError`, an error callers validating input do not expect).
pub fn int_arg(v: Option<&Bound<'_, PyAny>>, name: &str, max: u64) -> PyResult<Option<u64>> {
    let Some(v) = v.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    let not_an_int =
        || PyTypeError::new_err(format!("{name}: expected an integer, got {}", type_name(v)));
    if v.is_instance_of::<pyo3::types::PyBool>() {
        return Err(not_an_int());
    }
    let out_of_range = || {
        PyValueError::new_err(format!(
            "{name} must be an integer from 0 to {max}, got {v}"
        ))
    };
    match v.extract::<u64>() {
        Ok(x) if x <= max => Ok(Some(x)),
        Ok(_) => Err(out_of_range()),
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(v.py()) => {
            Err(out_of_range())
        }
        Err(_) => Err(not_an_int()),
    }
}

/// The Python type name of `obj`.
pub fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "object".into())
}

fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// An `N x cols` array of floats as rows; `ValueError` naming `name` and `what` on another
/// shape.
pub fn rows_of<const C: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    what: &str,
) -> PyResult<Vec<[f64; C]>> {
    let array = float_array(obj, name)?;
    let shape = array.shape().to_vec();
    if shape.len() != 2 || shape[1] != C {
        return Err(PyValueError::new_err(format!(
            "{name} must have shape (N, {C}) ({what}), got shape {}",
            shape_text(&shape)
        )));
    }
    let view = array.readonly();
    let a = view.as_array();
    Ok((0..shape[0])
        .map(|i| std::array::from_fn(|j| a[[i, j]]))
        .collect())
}

/// A fixed-size vector of floats; `ValueError` naming `name` and `what` on another shape.
pub fn vector_of<const N: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    what: &str,
) -> PyResult<[f64; N]> {
    let array = float_array(obj, name)?;
    let shape = array.shape().to_vec();
    if shape != [N] {
        return Err(PyValueError::new_err(format!(
            "{name} must be {N} numbers {what}, got shape {}",
            shape_text(&shape)
        )));
    }
    let view = array.readonly();
    let a = view.as_array();
    Ok(std::array::from_fn(|i| a[[i]]))
}

/// A 3 x 3 matrix of floats (row-major rows); `ValueError` naming `name` on another shape.
pub fn matrix_rows(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<[[f64; 3]; 3]> {
    let array = float_array(obj, name)?;
    let shape = array.shape().to_vec();
    if shape != [3, 3] {
        return Err(PyValueError::new_err(format!(
            "{name} must be a 3 x 3 matrix, got shape {}",
            shape_text(&shape)
        )));
    }
    let view = array.readonly();
    let a = view.as_array();
    Ok(std::array::from_fn(|i| std::array::from_fn(|j| a[[i, j]])))
}

/// A 3 x 3 matrix as a numpy array.
pub fn matrix_array<'py>(py: Python<'py>, m: &Matrix3<f64>) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((3, 3), |(i, j)| m[(i, j)]).into_pyarray(py)
}

/// Row-major rows as a numpy array.
pub fn rows_array<'py, const C: usize>(
    py: Python<'py>,
    rows: &[[f64; C]],
) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((rows.len(), C), |(i, j)| rows[i][j]).into_pyarray(py)
}

/// A 3-vector as a numpy array.
pub fn vector_array<'py>(py: Python<'py>, v: &Vector3<f64>) -> Bound<'py, PyArray1<f64>> {
    Array1::from_iter(v.iter().copied()).into_pyarray(py)
}

/// A JSON value as the Python object `json.loads` would make of its text (floats round-trip
/// exactly).
pub fn json_to_python<'py>(
    py: Python<'py>,
    value: &serde_json::Value,
) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?
        .getattr("loads")?
        .call1((value.to_string(),))
}
