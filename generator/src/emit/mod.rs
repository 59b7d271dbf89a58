//! Code emission: from a problem's traced coefficients and its elimination template to one
//! Rust source file, `solver/src/generated/<name>.rs`, compiled into `rspose`.
//!
//! - [`traced`]: the [`Traced`] ring — evaluating the problem with traced data records a
//!   hash-consed expression DAG (common subexpressions shared) for every coefficient.
//! - [`coefficients`]: the needed part of the DAG as straight-line code ([`Program`]),
//!   with an f64 interpreter that computes exactly what the emitted code computes.
//! - `solver`: [`emit_solver`] — data/solution structs and `solve` (template fill,
//!   Gauss-Jordan, action matrix, real eigenvectors, read-out, null-vector recovery of
//!   eliminated unknowns), built with `quote!` and formatted with `prettyplease`.
//! - `fill`: the coefficient code and the template fill (inline or table form, the fold).
//! - `solution_loop`: the loop over the action matrix's real eigenvectors that reads,
//!   unfolds, recovers, polishes, filters and pushes each solution.
//! - `structs`: the emitted `Data` / `Solution` structs and their slot conversions.
//! - `unrolled`: a small template's elimination written out as straight-line code.
//! - `tokens`: literal and doc-attribute helpers both of the above use.
//! - `files`: header line, atomic write, freshness check.
//!
//! All calls into `mingen_runtime` are spelled in `runtime_api` only.
//!
//! Determinism: everything iterates in a fixed order (template rows, `Poly` terms in their
//! `BTreeMap` order, DAG nodes in creation order), no hash map order reaches the output, and
//! the same spec always gives the same bytes.

mod action;
pub mod coefficients;
mod files;
mod fill;
pub(crate) mod polish;
mod reduction;
mod runtime_api;
mod solution_loop;
mod solver;
mod structs;
mod table_form;
mod tokens;
pub mod traced;
mod unrolled;

pub use coefficients::Program;
pub use files::{generated_header, generated_header_for_path, is_fresh, write_output};
pub use solver::{emit_solver, MAX_INLINE_STATEMENTS, SMALL_TEMPLATE_ROWS, TABLE_FORM_MIN_SIZE};
pub use traced::{Traced, Tracer};

use crate::algebra::Poly;
use crate::problem::ProblemLayout;
use crate::template::EliminationTemplate;

/// Why a solver could not be emitted.
#[derive(Debug, thiserror::Error)]
pub enum EmitError {
    /// The spec is inconsistent (template, equations, layout or elimination disagree).
    #[error("cannot emit solver: {0}")]
    Invalid(String),
    /// The spec is consistent but asks for something the emitter does not support.
    #[error("cannot emit solver (unsupported): {0}")]
    Unsupported(String),
    /// Traced values from different tracers were mixed.
    #[error("cannot emit solver: traced coefficients come from different tracers")]
    MixedTracers,
    /// Internal error: the generated tokens did not parse as a Rust file.
    #[error("internal error: generated code does not parse: {0}")]
    Internal(String),
}

/// Linear elimination info: which unknowns the solver recovers as a null vector.
#[derive(Clone, Debug)]
pub struct EliminationSpec {
    /// Flat indices (original unknown numbering) of the eliminated unknown scalars, in the
    /// order of the coefficient matrix columns.
    pub eliminated: Vec<usize>,
    /// Flat indices (original numbering) of the unknowns the template solves for, in
    /// template variable order.
    pub remaining: Vec<usize>,
    /// `rows x eliminated.len()` matrix (one column more, the free terms, if
    /// `inhomogeneous`) whose entries are polynomials in the remaining unknowns (template
    /// variables) with traced coefficients; the eliminated unknowns are its unit null
    /// vector at a solution, or its null vector divided by the last entry.
    pub coefficient_matrix: Vec<Vec<Poly<Traced>>>,
    /// Whether the matrix has the column of free terms (`crate::eliminate::Eliminated`).
    pub inhomogeneous: bool,
}

/// Polishing of every solution by Gauss-Newton steps (`option newton = N`) or of the poor
/// ones only, and the residual check that drops the spurious read-outs of a redundant
/// basis.
#[derive(Clone, Debug)]
pub struct PolishSpec {
    /// Steps per solution (at most; each is kept only if it lowers the residual); 0 with
    /// `reject_spurious` only checks.
    pub steps: usize,
    /// Polish only a solution whose worst relative residual is above
    /// `mingen_runtime::POOR_SOLUTION_RESIDUAL`, by `mingen_runtime::POOR_SOLUTION_STEPS`
    /// steps (`steps` must be that number): the plan found its template accurate and
    /// chose not to polish every solution.
    pub poor_only: bool,
    /// Drop a solution whose worst relative residual on `equations`, before polishing, is
    /// above `mingen_runtime::SPURIOUS_RESIDUAL` (the template's basis is redundant:
    /// [`crate::template::EliminationTemplate::spurious_eigenvalues`]).
    pub reject_spurious: bool,
    /// The problem's original equations in its declared unknowns (flat numbering; those
    /// involving hidden unknowns left out), with traced coefficients.
    pub equations: Vec<Poly<Traced>>,
    /// The number of declared (visible) unknowns: the equations' first variables.
    pub unknowns: usize,
}

/// Everything needed to emit one solver.
#[derive(Clone, Debug)]
pub struct SolverSpec {
    /// The problem's symbols (names, kinds, slot numbering).
    pub layout: ProblemLayout,
    /// The elimination template (see `crate::template` for the convention).
    pub template: EliminationTemplate,
    /// The equations the template rows refer to, as polynomials in the template's
    /// variables whose coefficients are traced data (all from one [`Tracer`]).
    pub equations: Vec<Poly<Traced>>,
    /// Workspace-relative problem file path for the header, e.g. `templates/fivept.mp`;
    /// empty means `templates/<layout.name>.mp`.
    pub problem_path: String,
    /// Linear elimination info, if the problem eliminates unknowns.
    pub elimination: Option<EliminationSpec>,
    /// Newton polishing of the solutions, if the problem asks for it.
    pub polish: Option<PolishSpec>,
    /// The sign folds of the system, in the order applied (`crate::symmetry`; empty: none):
    /// each solution of the template gives both signs.
    pub sign_folds: Vec<crate::symmetry::SignFold>,
    /// The form of the coefficient code.
    pub code_form: CodeForm,
}

/// The form of an emitted solver's coefficient code. Both compute the same bits.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CodeForm {
    /// [`CodeForm::Table`] when the template entries plus coefficient statements exceed
    /// [`TABLE_FORM_MIN_SIZE`], else [`CodeForm::Inline`] (the default).
    #[default]
    Auto,
    /// Straight-line code inside `solve`: shared coefficients as locals, one assignment per
    /// template entry. Fastest for small and medium templates; refused (an
    /// [`EmitError::Unsupported`]) above [`MAX_INLINE_STATEMENTS`] coefficient statements.
    Inline,
    /// Coefficients written to one array by functions of bounded size, the template filled
    /// through a constant table (`mingen_runtime::fill_template`): compile time linear in
    /// the problem's size, for templates of hundreds of rows.
    Table,
}
