//! # mingen-example — a minimal solver generated at build time
//!
//! How a crate uses `mingen` without checking generated code in: `build.rs` runs
//! `mingen::build::Config` on a problem file, and the solver is `include!`d from
//! `$OUT_DIR`. The crate depends on `mingen-runtime` only (`mingen` is a build-dependency,
//! without its command line: `default-features = false`).
//!
//! [`gs5pt`] is the 5-point relative pose problem (`templates/gs5pt.mp`): 10 solutions.
//! Its module has the emitted `Data`, `Solution`, `solve` and a `Solver` type that
//! implements [`mingen_runtime::MinimalSolver`].

/// The 5-point solver: `E = x E1 + y E2 + z E3 + E4` from a basis of the null space of the
/// five epipolar constraints.
pub mod gs5pt {
    include!(concat!(env!("OUT_DIR"), "/gs5pt.rs"));
}

#[cfg(test)]
mod tests {
    use super::gs5pt;
    use mingen_runtime::nalgebra::{Matrix3, Rotation3, Vector3};

    /// Every solution is an essential matrix (`det E = 0`, `2 E Eᵀ E = tr(E Eᵀ) E`: the
    /// equations of `templates/gs5pt.mp`), and the planted one is among them.
    #[test]
    fn solutions_are_essential_matrices() {
        let r = Rotation3::new(Vector3::new(0.1, -0.2, 0.3)).into_inner();
        let planted = Vector3::new(0.3, -0.5, 1.0).cross_matrix() * r;
        let truth = [0.3, -0.2, 0.5];
        // Fixed entries in [-1, 1] without structure (a sine table would make the
        // matrices degenerate: its rows obey a linear recurrence).
        let entry = |n: usize| (n * 7919 % 101) as f64 / 50.0 - 1.0;
        let mut basis: [Matrix3<f64>; 4] =
            std::array::from_fn(|k| Matrix3::from_fn(|i, j| entry(k * 9 + i * 3 + j)));
        basis[3] = planted - basis[0] * truth[0] - basis[1] * truth[1] - basis[2] * truth[2];
        let rows = |m: &Matrix3<f64>| std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]));
        let data = gs5pt::Data {
            e1: rows(&basis[0]),
            e2: rows(&basis[1]),
            e3: rows(&basis[2]),
            e4: rows(&basis[3]),
        };
        let solutions = gs5pt::solve(&data);
        let error = |s: &gs5pt::Solution| {
            let d = [s.x - truth[0], s.y - truth[1], s.z - truth[2]];
            d.iter().fold(0.0f64, |m, x| m.max(x.abs()))
        };
        assert!(solutions.iter().any(|s| error(s) < 1e-8));
        for s in solutions.iter() {
            let e = basis[0] * s.x + basis[1] * s.y + basis[2] * s.z + basis[3];
            let e = e / e.norm();
            let trace = (e * e.transpose()).trace();
            let residual = 2.0 * e * e.transpose() * e - trace * e;
            assert!(e.determinant().abs() < 1e-9, "det E = {}", e.determinant());
            assert!(
                residual.norm() < 1e-9,
                "trace constraint {}",
                residual.norm()
            );
        }
    }
}
