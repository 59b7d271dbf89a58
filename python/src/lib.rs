//! The Python module `rspose`: the Rust library `rspose` (gyro-aided relative pose of
//! rolling-shutter cameras) on numpy arrays. Everything is the library's own code: pairs
//! are the library's pair files (`pair`), checked by its validation with the command line's
//! messages; options are the fields of `EstimateOptions` on a preset, every named choice
//! parsed by the library's own name tables (`options`); estimates run the library's
//! pair-file estimate (`data::pair_estimate::estimate_pair`) with the GIL released
//! (`estimate`, which also spreads many pairs over the cores; `result` holds the `Estimate`
//! class and the failures' exceptions); the minimal solvers are the generated ones
//! (`solvers`). Conventions are the library's: pixels `[u, v]` with v the row, the gyro a
//! gyroscope's reading in camera axes (rad/s), `R = R2 R1^T`, `t = R2 (C1 - C2) / |.|`.

mod camera;
mod convert;
mod estimate;
mod options;
mod pair;
mod result;
mod solvers;

use camera::camera_of;
use convert::NoSolutionError;
use pair::Pair;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rspose_core::data::simulate::{simulate as rs_simulate, SimulationOptions};

/// Simulates one image pair with the paper's synthetic protocol (``rspose simulate``):
/// random scene, camera 2 rotated by about ``rotation_std_deg`` per axis and moved by
/// ``translation_std`` m per axis, both cameras turning at ``angular_velocity`` rad/s and
/// moving at ``linear_velocity`` m/s in random directions, rolling-shutter projections of
/// ``points`` matches with ``pixel_noise`` px of noise, gyro readings with ``gyro_noise``
/// rad/s of noise per axis, gravity directions with ``gravity_noise_deg`` per axis, a
/// fraction ``outlier_fraction`` of outliers; ``plane_depth``: every point on the plane at
/// that depth. ``camera`` (any model and readout direction) images both views, or view 1
/// only when ``camera2`` gives view 2 its own. Unset arguments take the Rust
/// ``SimulationOptions`` defaults. Deterministic given ``seed``. Returns a ``Pair`` with
/// ``ground_truth``; ``ValueError`` for an invalid option (the command line's message).
#[pyfunction]
#[pyo3(signature = (*, camera=None, camera2=None, points=None, min_depth=None, max_depth=None, rotation_std_deg=None, translation_std=None, angular_velocity=None, linear_velocity=None, pixel_noise=None, gyro_noise=None, outlier_fraction=None, gravity_noise_deg=None, seed=None, plane_depth=None))]
#[allow(clippy::too_many_arguments)]
fn simulate(
    py: Python<'_>,
    camera: Option<&Bound<'_, PyAny>>,
    camera2: Option<&Bound<'_, PyAny>>,
    points: Option<&Bound<'_, PyAny>>,
    min_depth: Option<f64>,
    max_depth: Option<f64>,
    rotation_std_deg: Option<f64>,
    translation_std: Option<f64>,
    angular_velocity: Option<f64>,
    linear_velocity: Option<f64>,
    pixel_noise: Option<f64>,
    gyro_noise: Option<f64>,
    outlier_fraction: Option<f64>,
    gravity_noise_deg: Option<f64>,
    seed: Option<&Bound<'_, PyAny>>,
    plane_depth: Option<f64>,
) -> PyResult<Pair> {
    let points = convert::int_arg(points, "points", usize::MAX as u64)?.map(|n| n as usize);
    let seed = convert::int_arg(seed, "seed", u64::MAX)?;
    let d = SimulationOptions::default();
    let options = SimulationOptions {
        camera: camera.map(camera_of).transpose()?.unwrap_or(d.camera),
        camera2: camera2.map(camera_of).transpose()?.or(d.camera2),
        points: points.unwrap_or(d.points),
        min_depth: min_depth.unwrap_or(d.min_depth),
        max_depth: max_depth.unwrap_or(d.max_depth),
        rotation_std_deg: rotation_std_deg.unwrap_or(d.rotation_std_deg),
        translation_std: translation_std.unwrap_or(d.translation_std),
        angular_velocity: angular_velocity.unwrap_or(d.angular_velocity),
        linear_velocity: linear_velocity.unwrap_or(d.linear_velocity),
        pixel_noise: pixel_noise.unwrap_or(d.pixel_noise),
        gyro_noise: gyro_noise.unwrap_or(d.gyro_noise),
        outlier_fraction: outlier_fraction.unwrap_or(d.outlier_fraction),
        gravity_noise_deg: gravity_noise_deg.unwrap_or(d.gravity_noise_deg),
        seed: seed.unwrap_or(d.seed),
        plane_depth: plane_depth.or(d.plane_depth),
    };
    let pair = py
        .detach(|| rs_simulate(&options))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(Pair::wrap(pair, None))
}

/// Rotation error in degrees, acos((tr(R_ref^T R) - 1) / 2).
#[pyfunction]
fn rotation_error_deg(reference: &Bound<'_, PyAny>, rotation: &Bound<'_, PyAny>) -> PyResult<f64> {
    let a = rspose_core::data::pair_file::matrix_from_rows(&convert::matrix_rows(
        reference,
        "reference",
    )?);
    let b = rspose_core::data::pair_file::matrix_from_rows(&convert::matrix_rows(
        rotation, "rotation",
    )?);
    Ok(rspose_core::model::geometry::rotation_error_deg(&a, &b))
}

/// Translation direction error in degrees, acos(t_ref . t) of the unit vectors.
#[pyfunction]
fn translation_error_deg(
    reference: &Bound<'_, PyAny>,
    translation: &Bound<'_, PyAny>,
) -> PyResult<f64> {
    let what = "[tx, ty, tz]";
    let a = nalgebra::Vector3::from(convert::vector_of::<3>(reference, "reference", what)?);
    let b = nalgebra::Vector3::from(convert::vector_of::<3>(translation, "translation", what)?);
    Ok(rspose_core::model::geometry::translation_error_deg(&a, &b))
}

/// The names of the methods, in the order the README's tables list them.
#[pyfunction]
fn methods() -> Vec<&'static str> {
    rspose_core::Method::ALL.iter().map(|m| m.name()).collect()
}

/// Gyro-aided relative pose of rolling-shutter cameras (the Rust library ``rspose``).
///
/// ``estimate_relative_pose(x1, x2, camera, gyro1, gyro2, method="grsrp+", **options)``
/// estimates one pair from numpy pixel arrays; ``estimate_many`` spreads many pairs over
/// all cores; ``Pair``/``load_pair`` are the command line's pair files; ``simulate`` makes
/// pairs with ground truth; ``solve_essential``, ``solve_grsrp`` and ``solve_gravity`` are
/// the generated minimal solvers; ``options()`` lists every option and its default.
#[pymodule]
fn rspose(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("NoSolutionError", m.py().get_type::<NoSolutionError>())?;
    m.add_class::<camera::Camera>()?;
    m.add_class::<pair::GyroLog>()?;
    m.add_class::<pair::GroundTruth>()?;
    m.add_class::<pair::Pair>()?;
    m.add_class::<result::Estimate>()?;
    m.add_function(wrap_pyfunction!(estimate::estimate_relative_pose, m)?)?;
    m.add_function(wrap_pyfunction!(estimate::estimate_many, m)?)?;
    m.add_function(wrap_pyfunction!(estimate::options, m)?)?;
    m.add_function(wrap_pyfunction!(pair::load_pair, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(solvers::solve_essential, m)?)?;
    m.add_function(wrap_pyfunction!(solvers::solve_grsrp, m)?)?;
    m.add_function(wrap_pyfunction!(solvers::solve_gravity, m)?)?;
    m.add_function(wrap_pyfunction!(rotation_error_deg, m)?)?;
    m.add_function(wrap_pyfunction!(translation_error_deg, m)?)?;
    m.add_function(wrap_pyfunction!(methods, m)?)?;
    // `__all__` names what `from rspose import *` (the package's `__init__`) re-exports,
    // `__version__` included.
    let mut names: Vec<String> = m
        .dict()
        .keys()
        .iter()
        .filter_map(|k| k.extract::<String>().ok())
        .filter(|k| !k.starts_with('_'))
        .collect();
    names.push("__version__".into());
    names.sort();
    m.add("__all__", names)?;
    Ok(())
}
