//! The generated minimal solvers on numpy input (pixels, the camera and the gyro in the
//! public conventions; the solvers' internal data are built by the library, as its RANSAC
//! builds them).

use crate::camera::camera_of;
use crate::convert::{matrix_array, matrix_rows, rows_of, vector_array, vector_of};
use nalgebra::{Matrix3, Vector3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyList;
use rspose_core::data::pair_file::{matrix_from_rows, Match};
use rspose_core::minimal::{EssentialSolver, GravitySample, GrsrpSample};
use rspose_core::model::camera::{Camera, View};
use rspose_core::model::epipolar::{observe_matches, PointData};
use rspose_core::EstimateError;

/// `n` matches from `x1`, `x2` (exactly `n` rows, or at least `n` when `at_least`), finite.
fn matches_of(
    x1: &Bound<'_, PyAny>,
    x2: &Bound<'_, PyAny>,
    n: usize,
    at_least: bool,
) -> PyResult<Vec<Match>> {
    let p1 = rows_of::<2>(x1, "x1", "pixels [u, v] in image 1")?;
    let p2 = rows_of::<2>(x2, "x2", "pixels [u, v] in image 2")?;
    let ok = |k: usize| if at_least { k >= n } else { k == n };
    if !(ok(p1.len()) && p1.len() == p2.len()) {
        return Err(PyValueError::new_err(format!(
            "x1 and x2 must hold {}{n} matches each, got {} and {}",
            if at_least { "at least " } else { "" },
            p1.len(),
            p2.len()
        )));
    }
    let matches: Vec<Match> = p1.into_iter().zip(p2).map(|(a, b)| [a, b]).collect();
    for (index, m) in matches.iter().enumerate() {
        for (k, p) in m.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                let e = EstimateError::NonFinitePixel {
                    index,
                    image: k + 1,
                };
                return Err(PyValueError::new_err(e.to_string()));
            }
        }
    }
    Ok(matches)
}

/// A match without a bearing as the estimator reports it (`ValueError`).
fn unobservable(e: rspose_core::model::epipolar::UnobservableMatch) -> PyErr {
    PyValueError::new_err(EstimateError::from(e).to_string())
}

/// Two checked constant-rate views (with gravity where given).
fn views_of(
    camera: Camera,
    gyro: [Vector3<f64>; 2],
    gravity: Option<[Vector3<f64>; 2]>,
) -> PyResult<(View, View)> {
    let mut views = [View::new(camera, gyro[0]), View::new(camera, gyro[1])];
    if let Some(g) = gravity {
        for (v, g) in views.iter_mut().zip(g) {
            *v = v.clone().with_gravity(g);
        }
    }
    for (k, v) in views.iter().enumerate() {
        v.validate().map_err(|source| {
            PyValueError::new_err(
                EstimateError::InvalidCamera {
                    view: k + 1,
                    source,
                }
                .to_string(),
            )
        })?;
    }
    let [a, b] = views;
    Ok((a, b))
}

fn gyro_of(g: &Bound<'_, PyAny>, name: &str) -> PyResult<Vector3<f64>> {
    Ok(Vector3::from(vector_of::<3>(
        g,
        name,
        "[wx, wy, wz] (rad/s, camera axes)",
    )?))
}

/// The global-shutter essential-matrix solvers: ``solver="five_point"`` (the generated
/// ``gs5pt``, exactly 5 matches, up to 10 solutions) or ``"eight_point"`` (linear, at least
/// 8 matches, one solution). ``x1``, ``x2``: pixels (N x 2); bearings are their undistorted
/// normalised coordinates (K^-1 [u, v, 1] for a pinhole).
/// Returns the essential matrices E (3 x 3, Frobenius norm 1) with x2^T E x1 = 0 on the
/// bearings.
#[pyfunction]
#[pyo3(signature = (x1, x2, camera, solver="five_point"))]
pub fn solve_essential<'py>(
    py: Python<'py>,
    x1: &Bound<'py, PyAny>,
    x2: &Bound<'py, PyAny>,
    camera: &Bound<'py, PyAny>,
    solver: &str,
) -> PyResult<Bound<'py, PyList>> {
    let solver = crate::options::essential_solver(solver)?;
    let camera = camera_of(camera)?;
    let n = solver.sample_size();
    let matches = matches_of(x1, x2, n, solver == EssentialSolver::EightPoint)?;
    views_of(camera, [Vector3::zeros(); 2], None)?;
    let observed = observe_matches(&camera, &camera, &matches).map_err(unobservable)?;
    let b1: Vec<Vector3<f64>> = observed.iter().map(|[a, _]| a.bearing).collect();
    let b2: Vec<Vector3<f64>> = observed.iter().map(|[_, b]| b.bearing).collect();
    let mut out: Vec<Matrix3<f64>> = Vec::new();
    py.detach(|| solver.solve(&b1, &b2, &mut out));
    let list = PyList::empty(py);
    for e in &out {
        list.append(matrix_array(py, e))?;
    }
    Ok(list)
}

/// The paper's G-RSRP minimal solver (``solver="ten"``: the generated ``grsrp10``, t
/// eliminated, up to 10 solutions; ``"twenty"``: ``grsrp``, up to 20 with both signs of t)
/// on 5 matches: pixels ``x1``, ``x2`` (5 x 2), the camera, each view's gyro reading
/// (rad/s, camera axes, as for ``estimate_relative_pose``) and the rotation ``r0`` the
/// model is linearised about. Returns ``(R, t)`` pairs (R = R0 exp([a]x), unit t, the sign
/// of t undetermined).
#[pyfunction]
#[pyo3(signature = (x1, x2, camera, gyro1, gyro2, r0, solver="ten"))]
#[allow(clippy::too_many_arguments)]
pub fn solve_grsrp<'py>(
    py: Python<'py>,
    x1: &Bound<'py, PyAny>,
    x2: &Bound<'py, PyAny>,
    camera: &Bound<'py, PyAny>,
    gyro1: &Bound<'py, PyAny>,
    gyro2: &Bound<'py, PyAny>,
    r0: &Bound<'py, PyAny>,
    solver: &str,
) -> PyResult<Bound<'py, PyList>> {
    let solver = crate::options::grsrp_solver(solver)?;
    let camera = camera_of(camera)?;
    let matches = matches_of(x1, x2, 5, false)?;
    let (v1, v2) = views_of(
        camera,
        [gyro_of(gyro1, "gyro1")?, gyro_of(gyro2, "gyro2")?],
        None,
    )?;
    let r0 = matrix_from_rows(&matrix_rows(r0, "r0")?);
    // The solver linearises about r0 as a rotation; any other matrix gives poses that are
    // not rotations, without an error.
    if !r0.iter().all(|x| x.is_finite())
        || (r0.transpose() * r0 - Matrix3::identity()).norm() > 1e-6
        || r0.determinant() < 0.0
    {
        return Err(PyValueError::new_err("r0 must be a rotation matrix"));
    }
    let data = PointData::new(&v1, &v2, &matches).map_err(unobservable)?;
    let sample = GrsrpSample::from_points(&data, &[0, 1, 2, 3, 4], r0);
    let mut out = Vec::new();
    py.detach(|| solver.solve(&sample, &mut out));
    poses(py, &out)
}

/// The known-gravity minimal solver (``solver="six"``: the generated ``grsrp_gravity6``, t
/// eliminated, up to 6 solutions; ``"twelve"``: ``grsrp_gravity``, up to 12 with both signs
/// of t) on 3 matches: pixels ``x1``, ``x2`` (3 x 2), the camera, each view's gyro reading
/// (rad/s, camera axes) and gravity direction (camera axes at row 0, any length). Returns
/// ``(R, t)`` pairs with R g1 parallel to g2 (unit t, the sign of t undetermined).
#[pyfunction]
#[pyo3(signature = (x1, x2, camera, gyro1, gyro2, gravity1, gravity2, solver="six"))]
#[allow(clippy::too_many_arguments)]
pub fn solve_gravity<'py>(
    py: Python<'py>,
    x1: &Bound<'py, PyAny>,
    x2: &Bound<'py, PyAny>,
    camera: &Bound<'py, PyAny>,
    gyro1: &Bound<'py, PyAny>,
    gyro2: &Bound<'py, PyAny>,
    gravity1: &Bound<'py, PyAny>,
    gravity2: &Bound<'py, PyAny>,
    solver: &str,
) -> PyResult<Bound<'py, PyList>> {
    let solver = crate::options::gravity_solver(solver)?;
    let camera = camera_of(camera)?;
    let matches = matches_of(x1, x2, 3, false)?;
    let what = "[gx, gy, gz] (camera axes)";
    let g = [
        Vector3::from(vector_of::<3>(gravity1, "gravity1", what)?),
        Vector3::from(vector_of::<3>(gravity2, "gravity2", what)?),
    ];
    let (v1, v2) = views_of(
        camera,
        [gyro_of(gyro1, "gyro1")?, gyro_of(gyro2, "gyro2")?],
        Some(g),
    )?;
    let data = PointData::new(&v1, &v2, &matches).map_err(unobservable)?;
    let sample = GravitySample::from_points(&data, &[0, 1, 2], g, [camera.lines(); 2]);
    let mut out = Vec::new();
    py.detach(|| solver.solve(&sample, &mut out));
    poses(py, &out)
}

fn poses<'py>(
    py: Python<'py>,
    out: &[(Matrix3<f64>, Vector3<f64>)],
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for (r, t) in out {
        list.append((matrix_array(py, r), vector_array(py, t)))?;
    }
    Ok(list)
}
