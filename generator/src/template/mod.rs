//! Elimination templates: which monomial multiples of which equations, and how their
//! reduction yields the action matrix.
//!
//! ## Convention (shared by the interpreter and the emitted solvers)
//! A template is a matrix whose row `i` holds the coefficients of the polynomial
//! `rows[i].multiplier * equations[rows[i].equation]`, one column per monomial of
//! `columns`; `equations` are the problem's equations as given, or, when the template has
//! a [`EliminationTemplate::reduction`], their reduced row echelon form on the instance's
//! data (see [`reduction`]). Columns are ordered `excess | reducible | basis`:
//! - `basis` (the last `basis.len()` columns) is the quotient-ring basis B, in the order of
//!   [`EliminationTemplate::basis`];
//! - `reducible` (the `n_reducible` columns before) are the monomials `action * b`, b in B,
//!   that are not in B, and the unknowns that are not in B;
//! - `excess` (the first `n_excess` columns) are all other monomials the rows contain;
//!   the last `n_dependent` of them are linear combinations of the other excess columns
//!   (on generic instances: the excess block may be rank-deficient) and are left out of the
//!   elimination (see `shape.rs`).
//!
//! Gauss-Jordan elimination of the template with this column order leaves, for each
//! reducible monomial r, a row `r + sum_k T[r,k] b_k` (zero on excess and other reducible
//! columns). The action matrix M (|B| x |B|) is then defined row by row: for `b_j` with
//! `action * b_j = b_k` in B, row j is the unit vector e_k; otherwise `action * b_j = r`
//! reducible and row j is `-T[r, :]`. For every solution s, the vector
//! `v = (b_0(s), ..., b_{n-1}(s))` satisfies `M v = action(s) v`: solutions are the
//! eigenvectors of M, and each unknown `x_i` in B is read off as `v[x_i] / v[1]`, or better
//! as the least-squares combination of the ratios `v[x_i b] / v[b]` over every b in B with
//! `x_i b` in B (`mingen_runtime::read_unknowns`). An unknown outside B (a linear equation
//! makes it a combination of basis monomials, e.g. `t1 = c t3` for a direction `t`) is a
//! reducible column, and its reduced row `x_i + sum_k T[x_i, k] b_k` gives the linear
//! read-out `x_i = -sum_k T[x_i, k] v[k] / v[1]` (`mingen_runtime::read_linear`). B must
//! contain 1.
//!
//! ## Pencil templates
//! A template may take some basis monomials' relations the other way round
//! ([`EliminationTemplate::flipped`], monomial actions only): for a flipped `b_j` the rows
//! reduce `b_j / action` (`b_j / x_v` for the action `x_v`, `x_v b_j` for `1 / x_v`)
//! instead of `action * b_j`. With `R` the matrix of relations (row j: the basis
//! coordinates of `action * b_j`, or of `b_j / action` when flipped, a unit vector or a
//! negated reduced row as above), every solution satisfies `action(s) T1 v = T0 v`, where
//! row j of `T1` is `e_j` and of `T0` is `R_j` for an unflipped `b_j`, the other way round
//! for a flipped one. The action matrix is `M = T1^-1 T0`: its unflipped rows are `R`'s,
//! and its flipped rows `F` solve the `|F| x |F|` system `R_FF M_F = E_F - R_FU R_U` (`U` the
//! unflipped rows, `E_F` the flipped rows of the identity). A redundant basis whose spurious
//! eigenvalues come from relations that map basis monomials onto each other deflates to
//! such a pencil on a basis of the solution count (`deflate.rs`), with no spurious
//! eigenvalue.
//!
//! ## Modules, lowest first
//! Each uses only those before it (and the types of this file), so dependencies go one way:
//! - `action`, `linalg`, `shape`: the action, arithmetic mod p, the emittability predicate;
//! - `error`, `options`: [`TemplateError`] and [`TemplateOptions`], shared by all stages;
//! - `candidates`: candidate rows, column blocks and the reducibility test;
//! - [`shrink`]: removal of rows and columns reducibility does not need;
//! - `exclude`: greedy exclusion of excess monomials from the candidate pool (a local
//!   search over the independent sets shrinking chooses among);
//! - `pools`: the candidate pools basis selection chooses among (total degrees and
//!   multidegrees);
//! - [`select`]: quotient bases chosen among a template's columns;
//! - [`reduction`]: the equations row-reduced on their data, which templates may be built
//!   from;
//! - [`fold`]: the Schur complement of the rows with constant pivots (a block of numbers
//!   the generator inverts exactly, then a triangle), which the search counts in every
//!   comparison;
//! - [`explore`]: size tables over orders for developers (not used by the pipeline);
//! - [`validate`](mod@validate): the template against Gröbner normal forms on fresh instances;
//! - [`build`]: the template of one action;
//! - `deflate`: a redundant basis deflated to a pencil on a basis of the solution count;
//! - `redundant`: a chosen template's basis grown past the solution count (redundant
//!   solving bases), when that makes it smaller, deflated where it can be;
//! - [`search`]: the search over actions and candidate degrees.

use crate::algebra::Monomial;

mod action;
pub mod build;
mod candidates;
mod deflate;
mod error;
mod exclude;
pub mod explore;
pub mod fold;
pub(crate) mod linalg;
mod newton_polytope;
mod options;
mod pools;
pub mod reduction;
mod redundant;
pub mod search;
pub mod select;
mod shape;
pub mod shift;
pub mod shrink;
pub mod sparse_order;
pub mod validate;
mod weight_sample;

pub use action::Action;
pub use candidates::ShrinkStep;
pub use error::TemplateError;
pub use fold::{fold_constant_rows, ConstantFold, EquationConstants};
pub use options::{ActionChoice, TemplateOptions};
pub use reduction::{EquationReduction, ReductionError};
pub use shape::ShapeError;
pub use shift::ColumnShift;
pub use sparse_order::{
    elimination_updates, order_for_sparse_elimination, SparseElimination, SPARSE_MIN_GAIN,
    SPARSE_MIN_PIVOTS, UNROLLED_MAX_UPDATES,
};

pub use build::BuiltTemplate;
pub use search::{best_template, PerAction};
pub use validate::{
    check_readoff, gb_action_matrix, template_action_matrix, validate, ValidationReport,
};

/// One template row: `multiplier * equations[equation]`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct TemplateRow {
    /// Index into the problem's (possibly eliminated) equation list, or, when the template
    /// has an [`EliminationTemplate::reduction`], into the reduced equations.
    pub equation: usize,
    /// Monomial in the unknowns that multiplies the equation.
    pub multiplier: Monomial,
}

/// An elimination template with its action monomial and quotient basis
/// (see the module documentation for the convention).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EliminationTemplate {
    /// Number of unknown scalars (variables of the monomials).
    pub nvars: usize,
    /// The template rows.
    pub rows: Vec<TemplateRow>,
    /// Column monomials, ordered `excess | reducible | basis`.
    pub columns: Vec<Monomial>,
    /// Number of excess columns (first block).
    pub n_excess: usize,
    /// Number of reducible columns (second block).
    pub n_reducible: usize,
    /// Number of dependent excess columns: the last `n_dependent` columns of the excess
    /// block are, on generic instances, linear combinations of the excess columns before
    /// them. Elimination leaves them out (after eliminating the other columns they are zero
    /// in every row that is not a pivot row), so only `rows >= pivot_columns()` is needed.
    pub n_dependent: usize,
    /// The quotient basis B (the last block of columns, same order); with
    /// [`EliminationTemplate::spurious_eigenvalues`], a redundant solving basis.
    pub basis: Vec<Monomial>,
    /// How many more monomials B has than the system has solutions (0: B is a quotient
    /// basis). A redundant B (see `redundant.rs`) spans the quotient without being
    /// independent in it: the action matrix has this many spurious eigenvalues besides the
    /// solutions', and the solver drops their read-outs by the residual of the equations
    /// ([`mingen_runtime::SPURIOUS_RESIDUAL`]).
    pub spurious_eigenvalues: usize,
    /// The basis indices, increasing, whose relation is taken the other way round: the
    /// rows reduce `b_j / action` rather than `action * b_j` (a pencil template, see the
    /// module documentation; monomial actions only). Empty for an ordinary template.
    pub flipped: Vec<usize>,
    /// Number of hidden variables (those of `nonzero`), the last `n_hidden` variables:
    /// part of the system, not read off the eigenvectors (B need not contain them).
    pub n_hidden: usize,
    /// The action (usually a single unknown, else a linear form in the unknowns): the
    /// columns `x_i * b` (coefficient of `x_i` non-zero) outside B are the reducible ones,
    /// and row j of the action matrix is `sum_i c_i` times the row of `x_i * b_j`.
    pub action: Action,
    /// The fixed-order sparse elimination of this template, when it pays (see
    /// [`order_for_sparse_elimination`], which also orders the rows and columns for it);
    /// `None`: the dense LU with partial pivoting.
    pub sparse: Option<SparseElimination>,
    /// The elimination in the template's own order along its structure, when `sparse` is
    /// `None` and it is small enough to be written out as straight-line code (see
    /// [`order_for_sparse_elimination`]): the dense LU's pivots and numbers, without its
    /// operations on entries that are zero for every instance. `None`: the dense LU.
    pub unrolled: Option<SparseElimination>,
    /// The row reduction of the equations on their data the rows refer to (see
    /// [`reduction`]); `None`: the rows are multiples of the equations as given.
    pub reduction: Option<EquationReduction>,
    /// The rows folded before the elimination (see [`fold`]): a block of numbers the
    /// generator inverted exactly (`fold.rows` rows), then rows with constant pivots in a
    /// triangle (`fold.pivot_inv.len()`); they are the first
    /// [`EliminationTemplate::folded_rows`] rows, and their pivot columns the first as
    /// many columns; the solver eliminates the Schur complement of the rest. `None`: the
    /// whole template is eliminated.
    pub fold: Option<ConstantFold>,
    /// The polynomial `σ` whose multiples the reducible and basis columns stand for (a
    /// template saturated by a polynomial, see [`shift`]): the column labelled `L m`, `L`
    /// the leading monomial of `σ`, holds the coordinate of `σ m`. `None`: every column is
    /// its monomial.
    pub shift: Option<ColumnShift>,
}

/// The unit of a basis: the greatest common divisor of its monomials, `1` for a quotient
/// basis (which contains 1), `s` for a basis `s B` shifted by a monomial `s` that is
/// non-zero on every solution (saturation inside the template, `search/saturated.rs`).
/// The eigenvector entry of the unit is the one every unknown is read relative to: with
/// `v ∝ (s b_k)(x)`, `v[s x_i] / v[s] = x_i`.
pub fn basis_unit(basis: &[Monomial]) -> Option<Monomial> {
    let first = basis.first()?;
    Some(basis.iter().fold(first.clone(), |g, b| g.gcd(b)))
}

/// The unknowns (the first `visible` variables) whose multiple by the basis's unit
/// ([`basis_unit`]) is not in `basis`, as those multiples, in variable order: read off the
/// eigenvectors through their reduced template rows (the linear read-out of the module
/// documentation), so they are reducible columns too.
pub fn unknowns_outside_basis(basis: &[Monomial], visible: usize) -> Vec<Monomial> {
    let Some(unit) = basis_unit(basis) else {
        return Vec::new();
    };
    (0..visible.min(unit.nvars()))
        .map(|v| Monomial::var(unit.nvars(), v).mul(&unit))
        .filter(|m| !basis.contains(m))
        .collect()
}

impl EliminationTemplate {
    /// The unknowns read off their reduced rows ([`unknowns_outside_basis`]).
    pub fn linear_readouts(&self) -> Vec<Monomial> {
        unknowns_outside_basis(&self.basis, self.visible_vars())
    }
    /// The basis's unit ([`basis_unit`]): `1`, or the monomial the basis is shifted by.
    pub fn unit(&self) -> Monomial {
        basis_unit(&self.basis).unwrap_or_else(|| Monomial::one(self.nvars))
    }
    /// The action's unknown `x` when the basis is its power basis `[x^(n-1), ..., x, 1]`
    /// in that order: the action matrix is then the companion matrix of the univariate
    /// polynomial of `x` the template's first reduced row holds (rows `1..n` shift the
    /// basis), its eigenvalues are the values of `x` at the solutions, and its eigenvectors
    /// the powers of each. The solvers take `x` from the eigenvalue then, not from
    /// eigenvector ratios, and the emitted ones solve the polynomial without building a
    /// general eigenproblem (`mingen_runtime::real_eigenpairs_companion`). `None` otherwise.
    pub fn companion_unknown(&self) -> Option<usize> {
        let x = self.action.single()?;
        let n = self.basis.len();
        let powers = self.basis.iter().enumerate().all(|(j, b)| {
            b.0.iter()
                .enumerate()
                .all(|(i, &e)| e as usize == if i == x { n - 1 - j } else { 0 })
        });
        (n > 0 && powers).then_some(x)
    }
    /// The relation of basis monomial `j`: the terms `(monomial, coefficient)` whose
    /// basis coordinates form row j of the relation matrix `R` (module documentation):
    /// `action * b_j`, or `b_j / action` when `j` is flipped.
    pub fn relation(&self, j: usize) -> Vec<(Monomial, i64)> {
        let b = &self.basis[j];
        if self.flipped.binary_search(&j).is_ok() {
            self.action
                .inverse_product(b)
                .map(|m| vec![(m, 1)])
                .unwrap_or_default()
        } else {
            self.action.products(b).collect()
        }
    }
    /// Number of variables read off the eigenvectors (all but the hidden ones).
    pub fn visible_vars(&self) -> usize {
        self.nvars - self.n_hidden.min(self.nvars)
    }
    /// Template size as (rows, columns), whole: every column, the dependent excess ones
    /// included, and before the fold of constant rows (see [`Self::eliminated_size`]).
    pub fn size(&self) -> (usize, usize) {
        (self.rows.len(), self.columns.len())
    }
    /// Size (equations, monomials) of the equations' coefficient matrix the solver
    /// row-reduces before filling the template, if it does ([`Self::reduction`]).
    pub fn reduction_size(&self) -> Option<(usize, usize)> {
        self.reduction
            .as_ref()
            .map(|r| (r.len(), r.monomials.len()))
    }
    /// Entries of every matrix the solver eliminates: the eliminated template's
    /// `rows x cols` plus, when the equations are row-reduced first, their coefficient
    /// matrix's. Templates are compared by it, so a reduction is chosen only when it pays
    /// for itself.
    pub fn elimination_area(&self) -> usize {
        let (r, c) = self.eliminated_size();
        r * c + self.reduction_size().map_or(0, |(n, m)| n * m)
    }
}
