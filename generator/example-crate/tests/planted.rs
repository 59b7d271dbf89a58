//! The build-time generated solvers recover planted solutions: random scenes with a known
//! relative pose (and focal length), their epipolar null spaces as data, and the true
//! null-space coefficients among the solutions.

mod common;

use common::{assert_recovered, coordinates, epipolar_null_space, nearest, rows, scene, skew};
use mingen_example::{gs5pt, relpose_6pt_focal};
use mingen_runtime::nalgebra::Matrix3;
use mingen_runtime::{FlatValues, MinimalSolver};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

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
        [20, 35]
    );
    let flat: Vec<f64> = (0..27).map(f64::from).collect();
    let data = relpose_6pt_focal::Data::from_flat(&flat).expect("27 slots");
    assert_eq!(data.to_flat_vec(), flat);
    assert!(relpose_6pt_focal::Data::from_flat(&flat[..26]).is_none());
    let nan = relpose_6pt_focal::Data::from_flat(&[f64::NAN; 27]).expect("27 slots");
    assert!(relpose_6pt_focal::solve(&nan).is_empty());
}
