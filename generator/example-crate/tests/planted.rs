//! The build-time generated solvers recover planted solutions: random scenes with a known
//! relative pose (and focal length), their epipolar null spaces as data, and the true
//! null-space coefficients among the solutions.

use mingen_example::{gs5pt, relpose_6pt_focal};
use mingen_runtime::nalgebra::{Matrix3, Rotation3, SMatrix, Vector3};
use mingen_runtime::{FlatValues, MinimalSolver};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Random rotation, unit translation and `n` points in front of both cameras, as pairs
/// `(X in camera 1, X in camera 2)`, with `X2 = R X1 + t`.
fn scene(rng: &mut ChaCha8Rng, n: usize) -> (Matrix3<f64>, Vector3<f64>, Vec<[Vector3<f64>; 2]>) {
    let axis = Vector3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 1.0);
    let r = *Rotation3::new(axis.normalize() * rng.gen_range(0.05..0.4)).matrix();
    let t = Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-0.3..0.3),
    )
    .normalize();
    let mut pts = Vec::new();
    while pts.len() < n {
        let x1 = Vector3::new(
            rng.gen_range(-2.0..2.0),
            rng.gen_range(-2.0..2.0),
            rng.gen_range(4.0..8.0),
        );
        let x2 = r * x1 + t;
        if x2.z > 1.0 {
            pts.push([x1, x2]);
        }
    }
    (r, t, pts)
}

fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// An orthonormal basis of the null space of the epipolar constraints `q^T M p = 0`
/// (`M` row-major as a 9-vector), ordered by increasing singular value.
fn epipolar_null_space(pairs: &[(Vector3<f64>, Vector3<f64>)], dim: usize) -> Vec<Matrix3<f64>> {
    // Zero rows pad the system to 9 x 9 so that the SVD has the whole right null space.
    let mut a = SMatrix::<f64, 9, 9>::zeros();
    for (row, (p, q)) in pairs.iter().enumerate() {
        for k in 0..9 {
            a[(row, k)] = q[k / 3] * p[k % 3];
        }
    }
    let svd = a.svd(false, true);
    let vt = svd.v_t.expect("V requested");
    let mut order: Vec<usize> = (0..9).collect();
    order.sort_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]));
    order[..dim]
        .iter()
        .map(|&i| Matrix3::from_fn(|r, c| vt[(i, 3 * r + c)]))
        .collect()
}

fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// Coordinates of `m` in the orthonormal basis `basis` (Frobenius inner products).
fn coordinates(m: &Matrix3<f64>, basis: &[Matrix3<f64>]) -> Vec<f64> {
    basis.iter().map(|b| b.dot(m)).collect()
}

/// The distance from `truth` to the nearest solution of `S` on `data`, relative to the
/// size of `truth` (infinite if there is no solution).
fn nearest<S: MinimalSolver>(data: &S::Data, truth: &[f64]) -> f64 {
    let scale = truth.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    S::solve(data)
        .as_ref()
        .iter()
        .map(|s| {
            let v = s.to_flat_vec();
            v.iter()
                .zip(truth)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
                / scale
        })
        .fold(f64::INFINITY, f64::min)
}

/// The median error is below `median` and all but the two worst below `worst`: near-
/// degenerate random scenes may lose accuracy, not every instance must be exact.
fn assert_recovered(mut errors: Vec<f64>, median: f64, worst: f64) {
    errors.sort_by(f64::total_cmp);
    let n = errors.len();
    assert!(errors[n / 2] < median, "median {}", errors[n / 2]);
    assert!(errors[n - 3] < worst, "{errors:?}");
}

#[test]
fn five_point_recovers_the_planted_essential_matrix() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut errors = Vec::new();
    for _ in 0..50 {
        let (r, t, pts) = scene(&mut rng, 5);
        let pairs: Vec<_> = pts.iter().map(|[a, b]| (a / a.z, b / b.z)).collect();
        let basis = epipolar_null_space(&pairs, 4);
        let e = skew(&t) * r;
        let c = coordinates(&e, &basis);
        // E = c0 E1 + c1 E2 + c2 E3 + c3 E4, so the problem's (x, y, z) are c0..c2 / c3.
        let truth = [c[0] / c[3], c[1] / c[3], c[2] / c[3]];
        let data = gs5pt::Data {
            e1: rows(&basis[0]),
            e2: rows(&basis[1]),
            e3: rows(&basis[2]),
            e4: rows(&basis[3]),
        };
        errors.push(nearest::<gs5pt::Solver>(&data, &truth));
    }
    assert_recovered(errors, 1e-9, 1e-5);
}

#[test]
fn six_point_focal_recovers_the_planted_focal_length() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let mut errors = Vec::new();
    for _ in 0..50 {
        let (r, t, pts) = scene(&mut rng, 6);
        let f = rng.gen_range(0.5..2.0);
        let k = Matrix3::new(f, 0.0, 0.0, 0.0, f, 0.0, 0.0, 0.0, 1.0);
        // Image points in "pixels" (principal point at the origin): p = K X / Z.
        let pairs: Vec<_> = pts
            .iter()
            .map(|[a, b]| (k * (a / a.z), k * (b / b.z)))
            .collect();
        let basis = epipolar_null_space(&pairs, 3);
        let kinv = k.try_inverse().expect("f > 0");
        let fundamental = kinv.transpose() * skew(&t) * r * kinv;
        let c = coordinates(&fundamental, &basis);
        let truth = [c[0] / c[2], c[1] / c[2], 1.0 / (f * f)];
        let data = relpose_6pt_focal::Data {
            f1: rows(&basis[0]),
            f2: rows(&basis[1]),
            f3: rows(&basis[2]),
        };
        errors.push(nearest::<relpose_6pt_focal::Solver>(&data, &truth));
    }
    assert_recovered(errors, 1e-8, 1e-4);
}

#[test]
fn solvers_describe_themselves_through_the_trait() {
    assert_eq!(gs5pt::Solver::NAME, "gs5pt");
    assert_eq!(<gs5pt::Solver as MinimalSolver>::MAX_SOLUTIONS, 10);
    assert_eq!(relpose_6pt_focal::Solver::NAME, "relpose_6pt_focal");
    assert_eq!(
        <relpose_6pt_focal::Solver as MinimalSolver>::MAX_SOLUTIONS,
        15
    );
    assert_eq!(
        <relpose_6pt_focal::Solver as MinimalSolver>::TEMPLATE_SHAPE[..2],
        [31, 46]
    );
    let flat: Vec<f64> = (0..27).map(f64::from).collect();
    let data = relpose_6pt_focal::Data::from_flat(&flat).expect("27 slots");
    assert_eq!(data.to_flat_vec(), flat);
    assert!(relpose_6pt_focal::Data::from_flat(&flat[..26]).is_none());
    let nan = relpose_6pt_focal::Data::from_flat(&[f64::NAN; 27]).expect("27 slots");
    assert!(relpose_6pt_focal::solve(&nan).is_empty());
}
