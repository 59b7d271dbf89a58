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
//! - [`null_vector3`]: unit null vector of an n x 3 matrix (recovery of eliminated
//!   unknowns such as a translation direction).

mod eigen;
mod elim;
mod null;
mod solution_set;
mod stages;
mod sturm;

pub use eigen::{real_eigenpairs, NEAR_REAL_TOL};
pub use elim::{gauss_jordan, lu_solve_template, PIVOT_TOL};
pub use null::null_vector3;
pub use solution_set::SolutionSet;
pub use stages::Stages;
pub use sturm::real_eigenpairs_sturm;
