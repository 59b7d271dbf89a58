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
//!   action matrix), by a real Schur decomposition with an iteration cap.
//! - [`real_eigenpairs_sturm`]: the same contract through balancing, Hessenberg form,
//!   characteristic polynomial, Sturm-sequence root isolation + Newton, and inverse
//!   iteration per real root; falls back to [`real_eigenpairs`] when a polynomial root and
//!   its inverse-iteration eigenvalue disagree (1-4 % of 5-point action matrices) or the
//!   Sturm sequence degenerates.
//! - [`Stages`]: observer of an emitted solver's stages (`solve_staged`), for timings.
//! - [`null_vector3`]: unit null vector of an n x 3 matrix (recovery of eliminated
//!   unknowns such as a translation direction).
//!
//! Back-end choice (the emitter's `STURM_MAX_BASIS = 20`), measured on the action
//! matrices the shipped solvers actually build (`tests/solver_stages.rs`, medians of
//! interleaved rounds, 2-core shared VM under load): 10x10 Schur 12.1 / 14.8 µs vs Sturm
//! 9.0 / 11.8 µs (gs5pt / grsrp10 matrices, read-out included);
//! 12x12 Schur ~41 µs vs Sturm ~15 µs; 20x20 Schur ~140 µs vs Sturm ~49 µs. Sturm costs
//! (10x10, random): balancing 0.1 µs, Hessenberg 1.0 µs, characteristic polynomial 0.2 µs,
//! Sturm sequence 0.35 µs, isolation + Newton ~0.5 µs per real root, inverse iteration
//! ~0.6 µs per real root. Elimination: `lu_solve_template` is emitted (10x20: ~0.8 µs vs
//! `gauss_jordan` ~1.0 µs; 90x102: 37 vs 68 µs; 228x248: 270 vs 604 µs).

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
