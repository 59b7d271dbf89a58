//! The one place that names the `rspose::runtime` API the emitted solvers call.
//!
//! If the runtime's names change, only these functions change.

use proc_macro2::TokenStream;
use quote::quote;

/// Fixed-capacity solution container: `SolutionSet<T, N>` with `new`, `push -> bool`.
pub(crate) fn solution_set() -> TokenStream {
    quote!(crate::runtime::SolutionSet)
}

/// `lu_solve_template_fixed::<ROWS, COLS, PIVOTS, FIRST>(m: &mut [f64]) -> bool`: like
/// Gauss-Jordan elimination for rows `FIRST..PIVOTS` (row-major, in place), the shape as
/// constants.
pub(crate) fn lu_solve_template() -> TokenStream {
    quote!(crate::runtime::lu_solve_template_fixed)
}

/// `real_eigenpairs_hqr::<N>`: same signature as `real_eigenpairs` (Hessenberg + Francis
/// double-shift QR with exceptional shifts + inverse iteration).
pub(crate) fn real_eigenpairs_hqr() -> TokenStream {
    quote!(crate::runtime::real_eigenpairs_hqr)
}

/// `real_eigenpairs_sturm::<N>`: same signature as `real_eigenpairs` (characteristic
/// polynomial + Sturm sequences + inverse iteration; faster for small `N`).
pub(crate) fn real_eigenpairs_sturm() -> TokenStream {
    quote!(crate::runtime::real_eigenpairs_sturm)
}

/// The stage-observer trait `Stages` (`filled`, `eliminated`, `action`: `&[f64] -> bool`),
/// implemented by `()`.
pub(crate) fn stages() -> TokenStream {
    quote!(crate::runtime::Stages)
}

/// `null_vector3::<R>(rows: &[[f64; 3]; R]) -> Option<[f64; 3]>` (unit null vector).
pub(crate) fn null_vector3() -> TokenStream {
    quote!(crate::runtime::null_vector3)
}

/// The fixed-size matrix type of the action matrix.
pub(crate) fn smatrix() -> TokenStream {
    quote!(nalgebra::SMatrix)
}
