//! # mingen-runtime — the numeric back end of the solvers `mingen` emits
//!
//! A crate that uses generated solvers depends on this crate only (the generator, `mingen`,
//! is at most a build-dependency). Emitted code refers to items of this crate as
//! `mingen_runtime::…` and to nalgebra through the re-export [`nalgebra`], so the crate
//! that includes it needs no other dependency.
//!
//! - [`MinimalSolver`]: the trait every emitted solver type implements; [`FlatValues`]:
//!   the flat forms of its data and solutions.
//!
//! Everything here is allocation-free for fixed sizes and never panics on any input
//! (finite or not): degenerate or non-finite data yields `false`, `None` or an empty set.
//!
//! - [`SolutionSet`]: fixed-capacity, stack-allocated list of solutions.
//! - [`gauss_jordan`]: in-place Gauss-Jordan elimination of a row-major template;
//!   [`lu_solve_template`]: the same result for the rows that matter, by forward elimination
//!   plus a partial back substitution (faster; see its documentation for measurements);
//!   [`lu_solve_template_sparse`]: the same pivots and numbers along a structure the
//!   generator bounds over every pivot choice (large sparse templates). Both LU routines run
//!   an AVX2 build when the CPU has it (no FMA: bit-identical results).
//! - [`real_eigenpairs`]: real eigenvalues and eigenvectors of a small dense matrix (the
//!   action matrix), by nalgebra's real Schur decomposition with an iteration cap (the
//!   reference; not used by emitted solvers: it stalls on ±λ spectra).
//! - [`real_eigenpairs_hqr`]: the same contract by Hessenberg reduction, Francis
//!   double-shift QR with exceptional shifts, and inverse iteration on the Hessenberg form,
//!   on the heap at any size ([`real_eigenpairs_hqr_dyn`] for sizes known at run time, the
//!   same bits).
//! - [`real_eigenpairs_sturm`]: the same contract through balancing, Hessenberg form,
//!   characteristic polynomial, its real roots (closed forms up to degree 4, else
//!   Sturm-sequence root isolation) + Newton, and per real root
//!   the Hessenberg backward recurrence (again after a Newton step on Hyman's determinant,
//!   then inverse iteration, when its residual is not at rounding level); hands the matrix to [`real_eigenpairs_hqr`] when a root is not
//!   confirmed (residual or eigenvalue disagreement: spurious real roots of ±λ spectra) or
//!   the Sturm sequence degenerates. The emitted solvers use it at every shipped size.
//! - [`LeastSquares`]: a matrix factored once for many right-hand sides (eliminated
//!   unknowns with data-only coefficients, recovered per solution).
//! - [`reduce_equations`]: the equations row-reduced on their data to the pivot monomials
//!   the generator chose, before the template is filled (smaller templates).
//! - [`fold_constant_rows`]: the Schur complement of a template's constant rows (multiples
//!   of equations with numeric coefficients), eliminated by the generator in exact
//!   arithmetic.
//! - [`fold_triangular_rows`]: the Schur complement of rows whose pivots are constants in
//!   a triangle (entries below it may depend on the data), by forward substitution.
//! - [`fill_template`], [`zeroed_coefficients`]: the table form of large solvers (the
//!   template filled from a coefficient array through a constant table).
//! - [`Stages`]: observer of an emitted solver's stages (`solve_staged`), for timings.
//! - [`null_vector`], [`dehomogenize`]: null vectors of n x N matrices and their affine
//!   points (eliminated unknowns other than three, or inhomogeneous in them).
//! - [`null_vector3`]: unit null vector of an n x 3 matrix (recovery of eliminated
//!   unknowns such as a translation direction).
//! - [`pencil_action_rows`]: the action matrix of a pencil template (relations of some
//!   basis monomials taken the other way round) from its relation matrix.
//! - [`read_unknowns`]: the unknowns read off an eigenvector of the action matrix.
//! - [`newton_polish`] / [`newton_polish_with`]: Gauss-Newton polishing of a solution on the original equations
//!   (`option newton`); [`polish_poor_solution`] / [`polish_poor_solution_with`]: the
//!   same for a solution whose residual is poor only (solvers that do not polish every
//!   solution); [`worst_relative_residual`] and [`screen_redundant_readout`]: a
//!   read-out's residual, and whether a read-out of a redundant basis is a solution (its
//!   action matrix has spurious eigenvalues); [`DistinctSolutions`]: drops a solution that
//!   repeats one kept before it.
//! - [`real_eigenpairs_dyn`], [`lu_solve_template`], [`null_vector3_rows`]: the same
//!   code at sizes known only at run time, for `mingen`'s interpreter (`mingen audit`),
//!   so that it measures exactly what the emitted solvers compute.
//!
//! The back ends are compared side by side in `benches/runtime.rs` (`cargo bench -p
//! mingen-runtime`) and, on the action matrices of the shipped solvers, in `rspose`'s
//! `benches/stages.rs`.

pub use nalgebra;

mod closed_form;
mod coefficient_table;
mod companion;
mod constant_fold;
mod distinct;
mod dynamic;
mod eigen;
mod elim;
mod equation_reduction;
mod hessenberg;
mod hessenberg_dyn;
mod hqr;
mod least_squares;
mod newton;
mod null;
mod null_general;
mod pencil;
mod readout;
mod sign_symmetry;
mod solution_set;
mod solver;
mod sparse_elim;
mod stages;
mod sturm;
mod sturm_sequence;
mod triangular_fold;

pub use coefficient_table::{fill_template, zeroed_coefficients};
pub use companion::real_eigenpairs_companion;
pub use constant_fold::{fold_constant_rows, ConstantFold};
pub use distinct::{repeats, DistinctSolutions, DUPLICATE_TOLERANCE};
pub use dynamic::{real_eigenpairs_dyn, DynEigenpair, MAX_DYNAMIC_BASIS, STURM_MAX_BASIS};
pub use eigen::{real_eigenpairs, NEAR_REAL_TOL};
pub use elim::{gauss_jordan, lu_solve_template, lu_solve_template_fixed, PIVOT_TOL};
pub use equation_reduction::{reduce_equations, reduce_equations_fixed};
pub use hqr::{real_eigenpairs_hqr, real_eigenpairs_hqr_dyn};
pub use least_squares::{least_squares_dyn, LeastSquares};
pub use newton::{
    newton_polish, newton_polish_with, polish_poor_solution, polish_poor_solution_with,
    screen_redundant_readout, screen_redundant_readout_with, worst_relative_residual, NewtonTerm,
    AT_ROUNDING_LEVEL, MAX_NEWTON_UNKNOWNS, MAX_TABULATED_POWER, POOR_SOLUTION_RESIDUAL,
    POOR_SOLUTION_STEPS, RESCUED_RESIDUAL, SPURIOUS_RESCUE, SPURIOUS_RESCUE_STEPS,
    SPURIOUS_RESIDUAL, STEP_HALVINGS,
};
pub use null::{null_vector3, null_vector3_rows};
pub use null_general::{dehomogenize, null_vector, null_vector_dyn};
pub use pencil::pencil_action_rows;
pub use readout::{read_linear, read_unknowns, read_unknowns_with_eigenvalue, MIN_UNIT_ENTRY};
pub use sign_symmetry::{flip_sign, unfold_sign, unfold_signs, SignFold};
pub use solution_set::SolutionSet;
pub use solver::{FlatValues, MinimalSolver};
pub use sparse_elim::{lu_solve_template_sparse, lu_solve_template_sparse_fixed, SparseLuPlan};
pub use stages::Stages;
pub use sturm::real_eigenpairs_sturm;
pub use triangular_fold::{fold_triangular_rows, TriangularFold};
