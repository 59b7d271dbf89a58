//! Numeric runtime shared by every emitted solver (`solver/src/generated/*.rs`).
//!
//! Everything here is allocation-free for fixed sizes and never panics on any input
//! (finite or not): degenerate or non-finite data yields `false`, `None` or an empty set.
//!
//! - [`SolutionSet`]: fixed-capacity, stack-allocated list of solutions.
//! - [`gauss_jordan`]: in-place Gauss-Jordan elimination of a row-major template;
//!   [`lu_solve_template`]: the same result for the rows that matter, by forward elimination
//!   plus a partial back substitution (faster; see its documentation for measurements).
//! - [`real_eigenpairs`]: real eigenvalues and eigenvectors of a small dense matrix (the
//!   action matrix), by nalgebra's real Schur decomposition with an iteration cap (the
//!   reference; not used by emitted solvers: it stalls on ±λ spectra).
//! - [`real_eigenpairs_hqr`]: the same contract by Hessenberg reduction, Francis
//!   double-shift QR with exceptional shifts, and inverse iteration on the Hessenberg form.
//! - [`real_eigenpairs_sturm`]: the same contract through balancing, Hessenberg form,
//!   characteristic polynomial, Sturm-sequence root isolation + Newton, and per real root
//!   the Hessenberg backward recurrence (again after a Newton step on Hyman's determinant,
//!   then inverse iteration, when its residual is not at rounding level); hands the matrix to [`real_eigenpairs_hqr`] when a root is not
//!   confirmed (residual or eigenvalue disagreement: spurious real roots of ±λ spectra) or
//!   the Sturm sequence degenerates. The emitted solvers use it at every shipped size.
//! - [`Stages`]: observer of an emitted solver's stages (`solve_staged`), for timings.
//! - [`null_vector3`]: unit null vector of an n x 3 matrix (recovery of eliminated
//!   unknowns such as a translation direction).
//!
//! Measured on the action matrices the shipped solvers build (`tests/solver_stages.rs`,
//! medians of interleaved rounds on a shared 2-core VM; absolute figures drift by up to 2x
//! with the machine's load, ratios within a run do not): Sturm / QR / Schur at 10x10
//! about 3.5 / 10 / 12 µs, 12x12 9 / 16 / 290 µs, 20x20 28 / 54 / 650 µs. Elimination:
//! `lu_solve_template_fixed` is emitted (10x20: ~0.75 µs vs `gauss_jordan` ~1.0 µs; 90x102:
//! 38 vs 69 µs; 80x100: 39 vs 76 µs).

mod eigen;
mod elim;
mod hessenberg;
mod hqr;
mod null;
mod solution_set;
mod stages;
mod sturm;

pub use eigen::{real_eigenpairs, NEAR_REAL_TOL};
pub use elim::{gauss_jordan, lu_solve_template, lu_solve_template_fixed, PIVOT_TOL};
pub use hqr::real_eigenpairs_hqr;
pub use null::null_vector3;
pub use solution_set::SolutionSet;
pub use stages::Stages;
pub use sturm::real_eigenpairs_sturm;
