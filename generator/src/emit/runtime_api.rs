//! The one place that names the `mingen_runtime` API the emitted solvers call. Emitted
//! code reaches nalgebra through `mingen_runtime::nalgebra`, so the crate that includes it
//! needs `mingen-runtime` only.
//!
//! If the runtime's names change, only these functions change.

use proc_macro2::TokenStream;
use quote::quote;

/// Fixed-capacity solution container: `SolutionSet<T, N>` with `new`, `push -> bool`.
pub(crate) fn solution_set() -> TokenStream {
    quote!(mingen_runtime::SolutionSet)
}

/// `unfold_signs::<N, M>(w: &[f64; N], folds: &[SignFold], out: &mut [[f64; N]; M]) ->
/// usize`: both signs of a solution of a sign-folded system (`SignFold<'a> = (usize,
/// &'a [usize])`).
pub(crate) fn unfold_signs() -> TokenStream {
    quote!(mingen_runtime::unfold_signs)
}

/// The type of one sign fold, `SignFold<'a> = (usize, &'a [usize])`.
pub(crate) fn sign_fold() -> TokenStream {
    quote!(mingen_runtime::SignFold)
}

/// `lu_solve_template_fixed::<ROWS, COLS, PIVOTS, FIRST>(m: &mut [f64]) -> bool`: like
/// Gauss-Jordan elimination for rows `FIRST..PIVOTS` (row-major, in place), the shape as
/// constants.
pub(crate) fn lu_solve_template() -> TokenStream {
    quote!(mingen_runtime::lu_solve_template_fixed)
}

/// `lu_solve_template_sparse_fixed::<COLS, PIVOTS>(m: &mut [f64], plan: &SparseLuPlan)
/// -> bool`: the same result as [`lu_solve_template`]'s along a precomputed structure.
pub(crate) fn lu_solve_template_sparse() -> TokenStream {
    quote!(mingen_runtime::lu_solve_template_sparse_fixed)
}

/// `PIVOT_TOL: f64`: the LU routines' relative pivot tolerance (times a column's largest
/// magnitude).
pub(crate) fn pivot_tol() -> TokenStream {
    quote!(mingen_runtime::PIVOT_TOL)
}

/// The structure of a sparse elimination: `SparseLuPlan<'a>` with the public fields
/// `rows, cols, pivot_cols, first_row: usize`, `pattern_start, target_start: &[u32]`,
/// `pattern, targets: &[u16]`.
pub(crate) fn sparse_lu_plan() -> TokenStream {
    quote!(mingen_runtime::SparseLuPlan)
}

/// `fold_constant_rows(filled: &[f64], plan: &ConstantFold, t: &mut [f64], out: &mut [f64])
/// -> bool`: the Schur complement of a template's constant block.
pub(crate) fn fold_constant_rows() -> TokenStream {
    quote!(mingen_runtime::fold_constant_rows)
}

/// `fold_triangular_rows(m: &mut [f64], plan: &TriangularFold, out: &mut [f64]) -> bool`:
/// the Schur complement of a template's rows with constant pivots in a triangle.
pub(crate) fn fold_triangular_rows() -> TokenStream {
    quote!(mingen_runtime::fold_triangular_rows)
}

/// The pivots of a triangular fold: `TriangularFold<'a>` with the public fields
/// `rows, folded, cols: usize`, `pivot_inv: &[f64]`.
pub(crate) fn triangular_fold() -> TokenStream {
    quote!(mingen_runtime::TriangularFold)
}

/// The constant of a fold: `ConstantFold<'a>` with the public fields
/// `rows, folded, cols: usize`, `inv_start, m12_start: &[u32]`, `inv_cols, m12_cols: &[u16]`,
/// `inv_vals: &[f64]`.
pub(crate) fn constant_fold() -> TokenStream {
    quote!(mingen_runtime::ConstantFold)
}

/// `real_eigenpairs_hqr::<N>`: same signature as `real_eigenpairs` (Hessenberg + Francis
/// double-shift QR with exceptional shifts + inverse iteration).
pub(crate) fn real_eigenpairs_hqr() -> TokenStream {
    quote!(mingen_runtime::real_eigenpairs_hqr)
}

/// `real_eigenpairs_companion::<N>(row: &[f64; N])`: the real eigenpairs of the companion
/// matrix with that first row (closed form for N of 3 or 4).
pub(crate) fn real_eigenpairs_companion() -> TokenStream {
    quote!(mingen_runtime::real_eigenpairs_companion)
}

/// `real_eigenpairs_sturm::<N>`: same signature as `real_eigenpairs` (characteristic
/// polynomial + Sturm sequences + inverse iteration; faster for small `N`).
pub(crate) fn real_eigenpairs_sturm() -> TokenStream {
    quote!(mingen_runtime::real_eigenpairs_sturm)
}

/// `pencil_action_rows(a: &mut [f64], n: usize, flipped: &[usize], scratch: &mut [f64])
/// -> bool`: the flipped rows of a pencil template's action matrix from its relations.
pub(crate) fn pencil_action_rows() -> TokenStream {
    quote!(mingen_runtime::pencil_action_rows)
}

/// `read_unknowns(v: &[f64], one: usize, pairs: &[&[(usize, usize)]], out: &mut [f64])
/// -> bool`: the unknowns read off an eigenvector.
pub(crate) fn read_unknowns() -> TokenStream {
    quote!(mingen_runtime::read_unknowns)
}

/// `read_unknowns_with_eigenvalue(v: &[f64], one: usize, pairs: &[&[(usize, usize)]],
/// action: Option<(usize, f64)>, out: &mut [f64]) -> bool`: [`read_unknowns`], the action's
/// unknown the eigenvalue where its pairs cannot be read.
pub(crate) fn read_unknowns_with_eigenvalue() -> TokenStream {
    quote!(mingen_runtime::read_unknowns_with_eigenvalue)
}

/// `read_linear(v: &[f64], one: usize, row: &[f64]) -> Option<f64>`: an unknown outside the
/// basis from its reduced template row.
pub(crate) fn read_linear() -> TokenStream {
    quote!(mingen_runtime::read_linear)
}

/// `newton_polish(x: &mut [f64], equations: &[&[NewtonTerm]], coefficients: &[f64],
/// steps: usize) -> usize`: Gauss-Newton polishing of a solution.
pub(crate) fn newton_polish() -> TokenStream {
    quote!(mingen_runtime::newton_polish)
}

/// `newton_polish_with::<N, E>(x: &mut [f64; N], steps: usize, values, jacobian) -> usize`:
/// Gauss-Newton polishing on equations written out as code.
pub(crate) fn newton_polish_with() -> TokenStream {
    quote!(mingen_runtime::newton_polish_with)
}

/// `polish_poor_solution(x: &mut [f64], equations: &[&[NewtonTerm]], coefficients: &[f64])
/// -> usize`: Gauss-Newton steps for a solution whose residual is poor only.
pub(crate) fn polish_poor_solution() -> TokenStream {
    quote!(mingen_runtime::polish_poor_solution)
}

/// `polish_poor_solution_with::<N, E>(x: &mut [f64; N], values, jacobian) -> usize`: the
/// same on equations written out as code.
pub(crate) fn polish_poor_solution_with() -> TokenStream {
    quote!(mingen_runtime::polish_poor_solution_with)
}

/// `screen_redundant_readout(x: &mut [f64], equations: &[&[NewtonTerm]], coefficients:
/// &[f64]) -> bool`: whether a read-out of a redundant basis is a solution.
pub(crate) fn screen_redundant_readout() -> TokenStream {
    quote!(mingen_runtime::screen_redundant_readout)
}

/// `screen_redundant_readout_with::<N, E>(x: &mut [f64; N], values, jacobian) -> bool`:
/// [`screen_redundant_readout`] on equations written out as code.
pub(crate) fn screen_redundant_readout_with() -> TokenStream {
    quote!(mingen_runtime::screen_redundant_readout_with)
}

/// `DistinctSolutions<N, CAP>` (`new()`, `insert(&[f64]) -> bool`): the solutions kept
/// so far, to drop a repeated read-out of a redundant basis.
pub(crate) fn distinct_solutions() -> TokenStream {
    quote!(mingen_runtime::DistinctSolutions)
}

/// The stage-observer trait `Stages` (`filled`, `eliminated`, `action`: `&[f64] -> bool`),
/// implemented by `()`.
pub(crate) fn stages() -> TokenStream {
    quote!(mingen_runtime::Stages)
}

/// `null_vector3::<R>(rows: &[[f64; 3]; R]) -> Option<[f64; 3]>` (unit null vector).
pub(crate) fn null_vector3() -> TokenStream {
    quote!(mingen_runtime::null_vector3)
}

/// `null_vector::<R, N>(rows: &[[f64; N]; R]) -> Option<[f64; N]>` (unit null vector).
pub(crate) fn null_vector() -> TokenStream {
    quote!(mingen_runtime::null_vector)
}

/// `LeastSquares::<R, K>::new(a: &[[f64; K]; R]) -> Option<Self>`, then
/// `.solve(b: &[f64; R]) -> Option<[f64; K]>` (`n` minimising `|A n + b|`).
pub(crate) fn least_squares() -> TokenStream {
    quote!(mingen_runtime::LeastSquares)
}

/// `dehomogenize(v: &[f64], out: &mut [f64]) -> bool` (`out = v[..k] / v[k]`).
pub(crate) fn dehomogenize() -> TokenStream {
    quote!(mingen_runtime::dehomogenize)
}

/// The fixed-size matrix type of the action matrix.
pub(crate) fn smatrix() -> TokenStream {
    quote!(mingen_runtime::nalgebra::SMatrix)
}

/// The trait of emitted solver types: `MinimalSolver` (`NAME`, `MAX_SOLUTIONS`,
/// `TEMPLATE_SHAPE`, `Data`, `Solution`, `Solutions`, `solve`, `solve_staged`).
pub(crate) fn minimal_solver() -> TokenStream {
    quote!(mingen_runtime::MinimalSolver)
}

/// The flat-form trait `FlatValues` (`LEN`, `from_flat`, `write_flat`) of data and solutions.
pub(crate) fn flat_values() -> TokenStream {
    quote!(mingen_runtime::FlatValues)
}

/// `fill_template(m: &mut [f64], c: &[f64], table: &[[u32; 2]])`: `m[e] = ±c[k]` for each
/// `[e, 2 k + negated]` (table form).
pub(crate) fn fill_template() -> TokenStream {
    quote!(mingen_runtime::fill_template)
}

/// `zeroed_coefficients::<N>() -> Box<[f64; N]>` (table form's coefficient array).
pub(crate) fn zeroed_coefficients() -> TokenStream {
    quote!(mingen_runtime::zeroed_coefficients)
}

/// `reduce_equations_fixed::<N_EQ, N_MON>(q: &mut [f64], pivots: &[usize; N_EQ]) -> bool`:
/// the equations' coefficient matrix row-reduced on the pivot columns, in place.
pub(crate) fn reduce_equations() -> TokenStream {
    quote!(mingen_runtime::reduce_equations_fixed)
}
