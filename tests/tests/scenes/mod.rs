//! Scene construction and solution matching of the planted-solution tests (`corpus.rs`).

#![allow(dead_code)]

use mingen_runtime::nalgebra::{DMatrix, Matrix3, Rotation3, UnitQuaternion, Vector3};
use mingen_runtime::{FlatValues, MinimalSolver};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A random rotation of moderate angle (0.05 to 0.4 rad) about an axis near z.
pub fn rotation(rng: &mut ChaCha8Rng) -> Matrix3<f64> {
    let axis = Vector3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 1.0);
    *Rotation3::new(axis.normalize() * rng.gen_range(0.05..0.4)).matrix()
}

/// A random rotation about the y axis (the upright case): `[[c, 0, s], [0, 1, 0], [-s, 0, c]]`.
pub fn rotation_y(rng: &mut ChaCha8Rng) -> (Matrix3<f64>, f64, f64) {
    let a: f64 = rng.gen_range(-0.6..0.6);
    let (s, c) = a.sin_cos();
    (Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c), c, s)
}

/// A random unit vector.
pub fn unit(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    )
    .normalize()
}

/// A random translation, mostly sideways, of unit length.
pub fn translation(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-0.3..0.3),
    )
    .normalize()
}

/// A random point in front of a camera at the origin (depth 4 to 8).
pub fn point_ahead(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    Vector3::new(
        rng.gen_range(-2.0..2.0),
        rng.gen_range(-2.0..2.0),
        rng.gen_range(4.0..8.0),
    )
}

/// `n` points in front of both cameras as pairs `(X in camera 1, X in camera 2)`, with
/// `X2 = r X1 + t`.
pub fn points_seen_by_both(
    rng: &mut ChaCha8Rng,
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    n: usize,
) -> Vec<[Vector3<f64>; 2]> {
    let mut pts = Vec::new();
    while pts.len() < n {
        let x1 = point_ahead(rng);
        let x2 = r * x1 + t;
        if x2.z > 1.0 {
            pts.push([x1, x2]);
        }
    }
    pts
}

/// Random rotation, unit translation and `n` points in front of both cameras.
pub fn scene(
    rng: &mut ChaCha8Rng,
    n: usize,
) -> (Matrix3<f64>, Vector3<f64>, Vec<[Vector3<f64>; 2]>) {
    let r = rotation(rng);
    let t = translation(rng);
    let pts = points_seen_by_both(rng, &r, &t, n);
    (r, t, pts)
}

/// `[v]x`.
pub fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// The `dim` right singular vectors of the square `a` with the smallest singular values:
/// an orthonormal basis of the null space of its rows (zero rows pad a shorter system to
/// square, so that the SVD has the whole right null space), by increasing singular value.
pub fn null_space(a: DMatrix<f64>, dim: usize) -> Vec<Vec<f64>> {
    let n = a.ncols();
    let svd = a.svd(false, true);
    let vt = svd.v_t.expect("V requested");
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]));
    order[..dim]
        .iter()
        .map(|&i| vt.row(i).iter().copied().collect())
        .collect()
}

/// An orthonormal basis of the null space of the epipolar constraints `q^T M p = 0`
/// (`M` row-major as a 9-vector), ordered by increasing singular value.
pub fn epipolar_null_space(
    pairs: &[(Vector3<f64>, Vector3<f64>)],
    dim: usize,
) -> Vec<Matrix3<f64>> {
    let mut a = DMatrix::<f64>::zeros(9, 9);
    for (row, (p, q)) in pairs.iter().enumerate() {
        for k in 0..9 {
            a[(row, k)] = q[k / 3] * p[k % 3];
        }
    }
    null_space(a, dim)
        .iter()
        .map(|v| Matrix3::from_fn(|r, c| v[3 * r + c]))
        .collect()
}

/// The matrix as row-major arrays (the emitted `mat3` field type).
pub fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// Coordinates of `m` in the orthonormal basis `basis` (Frobenius inner products).
pub fn coordinates(m: &Matrix3<f64>, basis: &[Matrix3<f64>]) -> Vec<f64> {
    basis.iter().map(|b| b.dot(m)).collect()
}

/// The quaternion `(1, b, c, d)` of rotation `r` scaled to a unit real part: `r` is the
/// rotation `Rq / (1 + b^2 + c^2 + d^2)` of the problem files.
pub fn quaternion_bcd(r: &Matrix3<f64>) -> [f64; 3] {
    let q = UnitQuaternion::from_matrix(r);
    [q.i / q.w, q.j / q.w, q.k / q.w]
}

/// Appends a flat view of `m` (row-major) to `out`.
pub fn push_mat(out: &mut Vec<f64>, m: &Matrix3<f64>) {
    out.extend(rows(m).iter().flatten());
}

/// Appends a 3-vector to `out`.
pub fn push_vec(out: &mut Vec<f64>, v: &Vector3<f64>) {
    out.extend(v.iter());
}

/// Appends the image point `v / v.z` as `[x, y]` (a `point` data slot pair) to `out`.
pub fn push_point(out: &mut Vec<f64>, v: &Vector3<f64>) {
    out.extend([v.x / v.z, v.y / v.z]);
}

/// The distance from the nearest of `truths` to the nearest solution of `S` on `data`,
/// relative to the size of that truth (infinite if there is no solution).
pub fn nearest_of<S: MinimalSolver>(data: &S::Data, truths: &[Vec<f64>]) -> f64 {
    let solutions = S::solve(data);
    let mut best = f64::INFINITY;
    for truth in truths {
        let scale = truth.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for s in solutions.as_ref() {
            let d = s
                .to_flat_vec()
                .iter()
                .zip(truth)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
                / scale;
            best = best.min(d);
        }
    }
    best
}

/// [`nearest_of`] with one truth.
pub fn nearest<S: MinimalSolver>(data: &S::Data, truth: &[f64]) -> f64 {
    nearest_of::<S>(data, &[truth.to_vec()])
}

/// Solves `S` on the flat data slots `flat` (slot order of the problem file) and returns
/// the distance to the nearest of `truths` (see [`nearest_of`]).
pub fn solve_flat<S: MinimalSolver>(flat: &[f64], truths: &[Vec<f64>]) -> f64 {
    let data = S::Data::from_flat(flat).expect("the problem's number of data slots");
    nearest_of::<S>(&data, truths)
}

/// The median error is below `median` and all but the two worst below `worst`: near-
/// degenerate random scenes may lose accuracy, not every instance must be exact.
pub fn assert_recovered(mut errors: Vec<f64>, median: f64, worst: f64) {
    errors.sort_by(f64::total_cmp);
    let n = errors.len();
    assert!(errors[n / 2] < median, "median {}", errors[n / 2]);
    assert!(errors[n - 3] < worst, "{errors:?}");
}
