//! The estimating functions: `estimate_relative_pose`, `estimate_many` (all cores, the GIL
//! released) and `options`; each pair goes through the library's
//! `data::pair_estimate::estimate_pair` ([`Request::estimate`]), as `rspose estimate` does.

use crate::convert::type_name;
use crate::options::{options_dict, request, Request};
use crate::pair::Pair;
use crate::result::{failure_error, Estimate};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};
use rspose_core::data::pair_estimate::PairEstimateError;
use rspose_core::data::pair_file::PairFile;
use rspose_core::{Estimate as RsEstimate, EstimateError};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Estimates the relative pose of two rolling-shutter views from pixel matches.
///
/// ``x1``, ``x2``: N x 2 pixels ``[u, v]`` (v = row) of the matches in image 1 and 2.
/// ``camera``: a ``Camera`` or a dict with the pair file's camera keys (both images), or
/// ``cameras``: one per image (exactly one of the two). ``gyro1``, ``gyro2``: each view's
/// gyroscope reading as a gyroscope reports it, rotated into camera axes (x right, y down,
/// z forward; rad/s, bias removed); optional with ``gyro_log``. ``method``: gsrp, nrsrp,
/// grsrp, grsrp+, rectified, rectified+v or grsrp-gravity (which needs ``gravity1`` and
/// ``gravity2``, each view's gravity direction in camera axes at row 0, any length).
/// ``gyro_log``: a ``GyroLog``; its samples then give each image's row rotations
/// (``rows="constant"``: each frame's mean rate instead). ``preset``: ``"default"`` (the
/// library defaults) or ``"paper"`` (the paper's settings). ``**options``: the fields of
/// the Rust ``EstimateOptions`` with their names, applied on the preset: the
/// ``RobustOptions`` fields flat or in ``robust={...}`` (``seed``, ``threshold=("sampson_pixels",
/// 2.5)``, ``max_iterations``, ...), ``refinement``, ``quality``, ``velocity`` as dicts,
/// ``essential_solver``, ``grsrp_solver``, ``grsrp_model`` (``"exact"`` or ``"paper"``),
/// ``gravity_solver``, ``r0_source`` (``"gsrp"``,
/// ``"rectified"``, ``"gyro"`` or a 3 x 3 rotation) and ``nrsrp_cauchy_px``; see
/// ``rspose.options()`` for every name and default.
///
/// Raises ``ValueError`` (bad input, with the command line's message), ``TypeError`` (an
/// argument of the wrong type or an unknown option) or ``NoSolutionError`` (no pose found).
#[pyfunction]
#[pyo3(signature = (x1, x2, camera=None, gyro1=None, gyro2=None, method="grsrp+", *, cameras=None, gyro_log=None, gravity1=None, gravity2=None, rows="integrated", preset="default", **options))]
#[allow(clippy::too_many_arguments)]
pub fn estimate_relative_pose(
    py: Python<'_>,
    x1: &Bound<'_, PyAny>,
    x2: &Bound<'_, PyAny>,
    camera: Option<&Bound<'_, PyAny>>,
    gyro1: Option<&Bound<'_, PyAny>>,
    gyro2: Option<&Bound<'_, PyAny>>,
    method: &str,
    cameras: Option<&Bound<'_, PyAny>>,
    gyro_log: Option<&Bound<'_, PyAny>>,
    gravity1: Option<&Bound<'_, PyAny>>,
    gravity2: Option<&Bound<'_, PyAny>>,
    rows: &str,
    preset: &str,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Estimate> {
    let req = request(method, preset, rows, options, "estimate_relative_pose")?;
    let pair = Pair::from_args(
        x1, x2, camera, cameras, gyro1, gyro2, gyro_log, gravity1, gravity2,
    )?;
    pair.estimate_with(py, &req)
}

/// One item of `estimate_many`'s input once read: a pair, or a pair file still to load.
enum Item {
    Pair(Pair),
    File(PathBuf),
}

fn item_of(obj: &Bound<'_, PyAny>, index: usize) -> PyResult<Item> {
    if let Ok(p) = obj.cast::<Pair>() {
        return Ok(Item::Pair(p.get().clone()));
    }
    if obj.is_instance_of::<PyString>() || obj.hasattr("__fspath__")? {
        return Ok(Item::File(obj.extract::<PathBuf>()?));
    }
    let context = |e: PyErr| -> PyErr {
        let py = obj.py();
        let message = format!("pairs[{index}]: {}", e.value(py));
        if e.is_instance_of::<PyTypeError>(py) {
            PyTypeError::new_err(message)
        } else if e.is_instance_of::<PyValueError>(py) {
            PyValueError::new_err(message)
        } else {
            e
        }
    };
    if let Ok(d) = obj.cast::<PyDict>() {
        let get = |k: &str| d.get_item(k);
        for (k, _) in d.iter() {
            let k: String = k.extract().unwrap_or_default();
            if ![
                "x1", "x2", "camera", "cameras", "gyro1", "gyro2", "gyro_log", "gravity1",
                "gravity2",
            ]
            .contains(&k.as_str())
            {
                return Err(PyTypeError::new_err(format!(
                    "pairs[{index}]: unknown key `{k}`"
                )));
            }
        }
        let need = |k: &str| -> PyResult<Bound<'_, PyAny>> {
            get(k)?
                .ok_or_else(|| PyTypeError::new_err(format!("pairs[{index}]: missing key `{k}`")))
        };
        let (x1, x2) = (need("x1")?, need("x2")?);
        let (camera, cameras) = (get("camera")?, get("cameras")?);
        if camera.is_none() && cameras.is_none() {
            return Err(PyTypeError::new_err(format!(
                "pairs[{index}]: missing key `camera` (or `cameras`, one per image)"
            )));
        }
        let (g1, g2, log, a1, a2) = (
            get("gyro1")?,
            get("gyro2")?,
            get("gyro_log")?,
            get("gravity1")?,
            get("gravity2")?,
        );
        return Pair::from_args(
            &x1,
            &x2,
            camera.as_ref(),
            cameras.as_ref(),
            g1.as_ref(),
            g2.as_ref(),
            log.as_ref(),
            a1.as_ref(),
            a2.as_ref(),
        )
        .map(Item::Pair)
        .map_err(context);
    }
    if let Ok(t) = obj.cast::<PyTuple>() {
        if t.len() == 5 {
            let i = |k| t.get_item(k);
            return Pair::from_args(
                &i(0)?,
                &i(1)?,
                Some(&i(2)?),
                None,
                Some(&i(3)?),
                Some(&i(4)?),
                None,
                None,
                None,
            )
            .map(Item::Pair)
            .map_err(context);
        }
    }
    Err(PyTypeError::new_err(format!(
        "pairs[{index}]: expected a Pair, a pair file path, a dict with the arguments of estimate_relative_pose or a tuple (x1, x2, camera, gyro1, gyro2), got {}",
        type_name(obj)
    )))
}

/// The result of one pair in `estimate_many`: the estimate, or the failure and the path to
/// name in its message.
type Outcome = Result<RsEstimate, (PairEstimateError, Option<PathBuf>)>;

fn run_item(item: &Item, req: &Request) -> Outcome {
    match item {
        Item::Pair(p) => req
            .estimate(&p.inner)
            .map_err(|f| (f, p.source.path.clone())),
        Item::File(path) => {
            let pair = PairFile::load(path).map_err(|e| (PairEstimateError::Pair(e), None))?;
            req.estimate(&pair).map_err(|f| (f, Some(path.clone())))
        }
    }
}

/// Estimates many pairs with the same method and options, in parallel on all cores (or
/// ``threads``) with the GIL released; the result is the list of what a loop of
/// ``estimate_relative_pose`` calls would return, in order.
///
/// ``pairs``: an iterable of ``Pair`` objects, pair-file paths (``str`` or ``os.PathLike``,
/// read in parallel), dicts with the pair arguments of ``estimate_relative_pose``
/// (``x1``, ``x2``, ``camera``, ``gyro1``, ``gyro2``, ``gyro_log``, ``gravity1``,
/// ``gravity2``) or tuples ``(x1, x2, camera, gyro1, gyro2)``. ``method``, ``rows``,
/// ``preset`` and ``**options`` as for ``estimate_relative_pose``. ``errors="raise"``
/// raises the error of the first pair that failed (in input order); ``errors="return"``
/// puts the exception in that pair's place instead.
#[pyfunction]
#[pyo3(signature = (pairs, method="grsrp+", *, rows="integrated", preset="default", threads=None, errors="raise", **options))]
#[allow(clippy::too_many_arguments)]
pub fn estimate_many<'py>(
    py: Python<'py>,
    pairs: &Bound<'py, PyAny>,
    method: &str,
    rows: &str,
    preset: &str,
    threads: Option<&Bound<'py, PyAny>>,
    errors: &str,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    let req = request(method, preset, rows, options, "estimate_many")?;
    let raise = match errors {
        "raise" => true,
        "return" => false,
        other => {
            return Err(PyValueError::new_err(format!(
                "unknown errors `{other}` (expected raise or return)"
            )))
        }
    };
    let threads =
        crate::convert::int_arg(threads, "threads", usize::MAX as u64)?.map(|n| n as usize);
    if threads == Some(0) {
        return Err(PyValueError::new_err("threads must be at least 1"));
    }
    if pairs.is_instance_of::<PyString>() || pairs.is_instance_of::<Pair>() {
        return Err(PyTypeError::new_err(
            "pairs: expected an iterable of pairs, got a single one",
        ));
    }
    let items: Vec<Item> = pairs
        .try_iter()?
        .enumerate()
        .map(|(i, obj)| item_of(&obj?, i))
        .collect::<PyResult<_>>()?;
    let workers = threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .min(items.len().max(1));
    let outcomes = py.detach(|| run_parallel(&items, &req, workers));
    let out = PyList::empty(py);
    for outcome in outcomes {
        match outcome {
            Ok(e) => out.append(Estimate::new(e))?,
            Err((f, path)) => {
                let err = failure_error(&f, path.as_ref());
                if raise {
                    return Err(err);
                }
                out.append(err.into_value(py))?;
            }
        }
    }
    Ok(out)
}

/// Runs every item on `workers` scoped threads, each taking the next unclaimed item, and
/// returns the outcomes in input order.
fn run_parallel(items: &[Item], req: &Request, workers: usize) -> Vec<Outcome> {
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<Outcome>>> = items.iter().map(|_| Mutex::new(None)).collect();
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(item) = items.get(i) else { break };
                let outcome = run_item(item, req);
                if let Ok(mut slot) = slots[i].lock() {
                    *slot = Some(outcome);
                }
            });
        }
    });
    slots
        .into_iter()
        .map(|m| {
            m.into_inner().ok().flatten().unwrap_or(Err((
                PairEstimateError::Estimate(EstimateError::NoSolution),
                None,
            )))
        })
        .collect()
}

/// Every estimator option for ``method`` with ``preset`` and the given ``**options``
/// applied, as a nested dict with the Rust ``EstimateOptions`` field names: the defaults of
/// the Rust API, and the names ``estimate_relative_pose`` accepts (``robust`` fields flat
/// or as a dict; the other groups as dicts).
#[pyfunction]
#[pyo3(signature = (method="grsrp+", *, preset="default", **options))]
pub fn options<'py>(
    py: Python<'py>,
    method: &str,
    preset: &str,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let req = request(method, preset, "integrated", options, "options")?;
    options_dict(py, &req)
}
