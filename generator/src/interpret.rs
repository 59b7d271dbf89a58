//! Interpreted f64 solving of an elimination template (no code generation): the reference
//! the emitted solvers are compared with, and the engine of `mingen audit`.
//!
//! It runs the numeric code of the emitted solvers, from `mingen-runtime`, at the
//! template's sizes: the template is filled with `multiplier * equations[equation]` (the
//! dependent excess columns left out, [`EliminationTemplate::eliminated_size`]), reduced
//! by [`mingen_runtime::lu_solve_template`] (or [`mingen_runtime::lu_solve_template_sparse`]
//! when the template has a sparse plan), the action matrix is assembled row by row,
//! its real eigenpairs come from [`mingen_runtime::real_eigenpairs_dyn`] (the back end an
//! emitted solver of that size calls), each unknown is read off by
//! [`mingen_runtime::read_unknowns`] through [`readout_pairs`], and eliminated unknowns
//! are recovered by [`mingen_runtime::null_vector3_rows`]. What differs from an emitted
//! solver is only how the coefficients are evaluated (from `Poly<f64>` here, from shared
//! intermediates there), so both agree to rounding.

use crate::algebra::{Monomial, Poly};
use crate::eliminate::has_data_only_columns;
use crate::template::shift::column_coordinates;
use crate::template::{EliminationTemplate, ShapeError};
use nalgebra::DMatrix;
use std::collections::HashMap;

/// Why a template could not be solved for one instance.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InterpretError {
    /// The template's fields are inconsistent with each other.
    #[error("malformed template: {0}")]
    Malformed(String),
    /// A template row names an equation that was not supplied.
    #[error("template row {row} uses equation {equation}, but only {count} equations were given")]
    MissingEquation {
        /// Template row.
        row: usize,
        /// Equation index of that row.
        equation: usize,
        /// Number of equations given.
        count: usize,
    },
    /// An equation has a different number of variables than the template.
    #[error("equation {equation} has {found} variables, the template {expected}")]
    VariableCount {
        /// Equation index.
        equation: usize,
        /// Its number of variables.
        found: usize,
        /// The template's number of variables.
        expected: usize,
    },
    /// `multiplier * equation` has a term whose monomial is not a template column.
    #[error(
        "template row {row} (equation {equation}) has the term {monomial}, which is not a column"
    )]
    TermOutsideColumns {
        /// Template row.
        row: usize,
        /// Equation index of that row.
        equation: usize,
        /// The offending monomial (`x0^2*x1` style).
        monomial: String,
    },
    /// A coefficient is NaN or infinite.
    #[error("template row {row} has a non-finite coefficient")]
    NonFinite {
        /// Template row.
        row: usize,
    },
    /// The equations cannot be row-reduced as the template's
    /// [`EliminationTemplate::reduction`] plans (degenerate data for the reduction).
    #[error("equation reduction: {0}")]
    Reduction(#[from] crate::template::ReductionError),
    /// The elimination found no pivot above [`mingen_runtime::PIVOT_TOL`] for some column:
    /// the template is singular on this instance (an emitted solver returns nothing).
    #[error("the elimination template is singular on this instance (no usable pivot)")]
    Singular,
    /// `action * b` is neither a basis monomial nor a reducible column.
    #[error("action * {basis} = {product} is neither in the basis nor a reducible column")]
    ActionNotCovered {
        /// The basis monomial b.
        basis: String,
        /// The product.
        product: String,
    },
    /// The basis lacks `1`, or a variable is neither in it nor a reducible column, so
    /// solutions cannot be read off.
    #[error("the basis lacks the monomial {0}, needed to read the solutions")]
    MissingReadout(String),
    /// The action matrix is larger than the runtime's dynamic eigen entry point accepts.
    #[error("the action matrix is {size} x {size}; the interpreter handles at most {max} x {max}")]
    ActionTooLarge {
        /// Basis size.
        size: usize,
        /// [`mingen_runtime::MAX_DYNAMIC_BASIS`].
        max: usize,
    },
}

/// The shared predicate [`EliminationTemplate::check_emittable`], in this module's errors.
fn check_template(t: &EliminationTemplate) -> Result<(), InterpretError> {
    t.check_emittable(&[]).map_err(|e| match e {
        ShapeError::BasisLacks(m) | ShapeError::ReadoutNotReducible(m) => {
            InterpretError::MissingReadout(m)
        }
        ShapeError::ActionNotCovered { basis, product } => {
            InterpretError::ActionNotCovered { basis, product }
        }
        e @ (ShapeError::Malformed(_) | ShapeError::TooFewRows { .. }) => {
            InterpretError::Malformed(e.to_string())
        }
    })
}

/// Fills the matrix an emitted solver eliminates (row-major,
/// [`EliminationTemplate::eliminated_size`]: the template without its dependent excess
/// columns, and the Schur complement of its constant rows when it has a
/// [`EliminationTemplate::fold`]) for these equations.
pub fn fill_template(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Result<Vec<f64>, InterpretError> {
    check_template(template)?;
    let reduced;
    let equations = match &template.reduction {
        Some(r) => {
            reduced = r.reduce_f64(equations)?;
            &reduced[..]
        }
        None => equations,
    };
    let col: HashMap<&Monomial, usize> = template
        .columns
        .iter()
        .enumerate()
        .map(|(i, m)| (m, i))
        .collect();
    let shift: Option<Vec<(Monomial, f64)>> = template.shift.as_ref().and_then(|s| s.terms_in());
    // The filled matrix; a fold then forms its Schur complement as the emitted solvers do.
    let (nr, nc) = template.filled_size();
    let mut m = vec![0.0; nr * nc];
    for (i, row) in template.rows.iter().enumerate() {
        let eq = equations
            .get(row.equation)
            .ok_or(InterpretError::MissingEquation {
                row: i,
                equation: row.equation,
                count: equations.len(),
            })?;
        if eq.nvars() != template.nvars {
            return Err(InterpretError::VariableCount {
                equation: row.equation,
                found: eq.nvars(),
                expected: template.nvars,
            });
        }
        let terms = column_coordinates(
            &row.multiplier,
            eq,
            shift.as_deref(),
            template.n_excess,
            |m| col.get(m).copied(),
        );
        for (prod, c) in terms {
            let j = *col
                .get(&prod)
                .ok_or_else(|| InterpretError::TermOutsideColumns {
                    row: i,
                    equation: row.equation,
                    monomial: format!("{prod:?}"),
                })?;
            if !c.is_finite() {
                return Err(InterpretError::NonFinite { row: i });
            }
            if let Some(j) = template.filled_column(j) {
                m[i * nc + j] += c;
            }
        }
    }
    let Some(f) = &template.fold else {
        return Ok(m);
    };
    let malformed = || InterpretError::Malformed("the fold does not match the template".into());
    let (er, ec) = template.eliminated_size();
    let kt = f.pivot_inv.len();
    if f.rows > 0 {
        let mut folded = vec![0.0; (er + kt) * (ec + kt)];
        let mut t = vec![0.0; f.rows];
        let plan = f.as_plan(template);
        if !mingen_runtime::fold_constant_rows(&m, &plan, &mut t, &mut folded) {
            return Err(malformed());
        }
        m = folded;
    }
    if kt > 0 {
        let mut folded = vec![0.0; er * ec];
        if !mingen_runtime::fold_triangular_rows(
            &mut m,
            &f.as_triangular_plan(template),
            &mut folded,
        ) {
            return Err(malformed());
        }
        m = folded;
    }
    Ok(m)
}

/// The action matrix (|B| x |B|) of the template on these equations, per the convention:
/// `M v = action(s) v` for `v = (b_0(s), ..., b_{n-1}(s))`. The filled template is reduced
/// as the emitted solvers reduce it: by [`mingen_runtime::lu_solve_template_sparse`] along
/// the template's sparse plan if it has one, otherwise by
/// [`mingen_runtime::lu_solve_template`] (both: partial pivoting, the same pivots, back
/// substitution of the reducible rows only).
pub fn action_matrix(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Result<DMatrix<f64>, InterpretError> {
    action_matrix_and_readouts(template, equations).map(|(a, _)| a)
}

/// [`action_matrix`] and the reduced row `T[x_i, :]` of every unknown outside the basis
/// (the linear read-out, [`mingen_runtime::read_linear`]), in variable order as
/// [`EliminationTemplate::linear_readouts`].
pub fn action_matrix_and_readouts(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Result<(DMatrix<f64>, Vec<Vec<f64>>), InterpretError> {
    let mut m = fill_template(template, equations)?;
    let (rows, cols) = template.eliminated_size();
    let pivots = template.pivot_columns();
    let first_row = template.first_reduced_row();
    let reduced = match &template.sparse {
        Some(s) => mingen_runtime::lu_solve_template_sparse(&mut m, &s.as_plan(template)),
        None => mingen_runtime::lu_solve_template(&mut m, rows, cols, pivots, first_row),
    };
    if !reduced {
        return Err(InterpretError::Singular);
    }
    let column: HashMap<&Monomial, usize> = template
        .columns
        .iter()
        .enumerate()
        .map(|(i, m)| (m, i))
        .collect();
    let n = template.basis.len();
    let mut a = DMatrix::zeros(n, n);
    for (j, b) in template.basis.iter().enumerate() {
        for (prod, coef) in template.relation(j) {
            let coef = coef as f64;
            let not_covered = || InterpretError::ActionNotCovered {
                basis: format!("{b:?}"),
                product: format!("{prod:?}"),
            };
            let c = column
                .get(&prod)
                .and_then(|&c| template.eliminated_column(c))
                .ok_or_else(not_covered)?;
            if c >= pivots {
                a[(j, c - pivots)] += coef;
            } else if c >= first_row {
                // Row c of the reduced template reads `col_c + sum_k T[c, k] b_k`.
                for k in 0..n {
                    a[(j, k)] -= coef * m[c * cols + pivots + k];
                }
            } else {
                return Err(not_covered());
            }
        }
    }
    if !template.flipped.is_empty() {
        a = pencil_action_matrix(&a, &template.flipped).ok_or(InterpretError::Singular)?;
    }
    let readouts = template
        .linear_readouts()
        .iter()
        .map(|x| {
            let c = column
                .get(x)
                .and_then(|&c| template.eliminated_column(c))
                .filter(|&c| c >= first_row && c < pivots)
                .ok_or_else(|| InterpretError::MissingReadout(format!("{x:?}")))?;
            Ok(m[c * cols + pivots..c * cols + pivots + n].to_vec())
        })
        .collect::<Result<Vec<_>, InterpretError>>()?;
    Ok((a, readouts))
}

/// The action matrix `M = T1^-1 T0` of a pencil template from its relation matrix `rel`
/// (see the template convention in [`crate::template`]): the flipped rows `F` solve
/// `rel_FF M_F = E_F - rel_FU rel_U` by Gauss-Jordan elimination with partial pivoting; `None` when `rel_FF` is
/// singular. The emitted solvers do the same ([`mingen_runtime::pencil_action_rows`]).
fn pencil_action_matrix(rel: &DMatrix<f64>, flipped: &[usize]) -> Option<DMatrix<f64>> {
    let n = rel.nrows();
    let mut out = rel.clone();
    let mut scratch = vec![0.0; flipped.len() * (flipped.len() + n)];
    mingen_runtime::pencil_action_rows(out.as_mut_slice(), n, flipped, &mut scratch).then_some(out)
}

/// The read-out pairs of every unknown (see [`mingen_runtime::read_unknowns`]): for each
/// variable `x_i` in the basis, all pairs `(j, k)` of basis indices with `basis[k] = x_i *
/// basis[j]`, the pair `(1, x_i)` first, then by increasing `j`; none for a variable
/// outside the basis (read off its reduced row instead) and none for the unknown of a
/// companion action ([`EliminationTemplate::companion_unknown`]), which is the
/// eigenvalue. Errors if the basis lacks `1`.
pub fn readout_pairs(
    template: &EliminationTemplate,
) -> Result<Vec<Vec<(usize, usize)>>, InterpretError> {
    let n = template.nvars;
    let find = |m: &Monomial| {
        template
            .basis
            .iter()
            .position(|b| b == m)
            .ok_or_else(|| InterpretError::MissingReadout(format!("{m:?}")))
    };
    let unit = template.unit();
    let one = find(&unit)?;
    let companion = template.companion_unknown();
    (0..template.visible_vars())
        .map(|i| {
            if Some(i) == companion {
                return Ok(Vec::new());
            }
            let x = Monomial::var(n, i);
            let Some(xk) = template.basis.iter().position(|b| *b == x.mul(&unit)) else {
                return Ok(Vec::new());
            };
            let mut pairs = vec![(one, xk)];
            for (j, b) in template.basis.iter().enumerate() {
                if j == one {
                    continue;
                }
                let xb = x.mul(b);
                if let Some(k) = template.basis.iter().position(|c| *c == xb) {
                    pairs.push((j, k));
                }
            }
            Ok(pairs)
        })
        .collect()
}

/// The real solutions of one instance, as an emitted solver computes them.
#[derive(Clone, Debug, PartialEq)]
pub struct TemplateSolutions {
    /// One solution per real eigenvector that could be read (template variables, in
    /// order).
    pub solutions: Vec<Vec<f64>>,
    /// Number of real eigenpairs of the action matrix: those beyond `solutions.len()` were
    /// rejected by the read-out (a zero denominator, a solution at infinity, or a
    /// non-finite unknown; a tiny denominator is read, see `mingen_runtime::MIN_UNIT_ENTRY`).
    pub eigenpairs: usize,
}

/// The real solutions of the system by the emitted solvers' numeric path (see the module
/// documentation). The basis must contain `1`; a variable outside it is read off its reduced row.
pub fn solve_template(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Result<TemplateSolutions, InterpretError> {
    check_template(template)?;
    let pairs = readout_pairs(template)?;
    let pairs: Vec<&[(usize, usize)]> = pairs.iter().map(Vec::as_slice).collect();
    let unit = template.unit();
    let one = template
        .basis
        .iter()
        .position(|b| *b == unit)
        .ok_or_else(|| InterpretError::MissingReadout("1".into()))?;
    let (a, readouts) = action_matrix_and_readouts(template, equations)?;
    let companion = template.companion_unknown();
    // The unknowns read off their reduced rows, in the order of `readouts`
    // ([`EliminationTemplate::linear_readouts`]), with those rows; a companion action's
    // unknown outside the basis (a basis of 1 alone) is its eigenvalue instead.
    let outside = template.linear_readouts();
    let linear: Vec<(usize, &Vec<f64>)> = (0..pairs.len())
        .filter(|&i| outside.contains(&Monomial::var(template.nvars, i).mul(&unit)))
        .zip(&readouts)
        .filter(|&(i, _)| Some(i) != companion)
        .collect();
    let n = a.nrows();
    let eigenpairs = mingen_runtime::real_eigenpairs_dyn(a.as_slice(), n).ok_or(
        InterpretError::ActionTooLarge {
            size: n,
            max: mingen_runtime::MAX_DYNAMIC_BASIS,
        },
    )?;
    let mut solutions = Vec::with_capacity(eigenpairs.len());
    let action = template.action.single();
    for (lambda, v) in &eigenpairs {
        let mut u = vec![0.0; pairs.len()];
        let action = action.map(|i| (i, *lambda));
        if !mingen_runtime::read_unknowns_with_eigenvalue(v, one, &pairs, action, &mut u) {
            continue;
        }
        if let Some(x) = companion {
            u[x] = *lambda;
        }
        let read = linear.iter().all(|&(i, row)| {
            mingen_runtime::read_linear(v, one, row)
                .map(|x| u[i] = x)
                .is_some()
        });
        if read {
            solutions.push(u);
        }
    }
    Ok(TemplateSolutions {
        solutions,
        eigenpairs: eigenpairs.len(),
    })
}

/// The real solutions of [`solve_template`]; like an emitted solver, none when the
/// instance cannot be solved (singular template, non-finite data): use [`solve_template`]
/// for the reason.
pub fn solve_template_real(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Vec<Vec<f64>> {
    solve_template(template, equations).map_or_else(|_| Vec::new(), |s| s.solutions)
}

/// Polishes `x` by up to `steps` Gauss-Newton steps on `equations` (polynomials in `x`'s
/// unknowns, possibly with more variables that do not occur) with [`mingen_runtime::newton_polish`], as an emitted solver of a problem
/// with `option newton = N` does. Returns the steps taken (0 if an exponent exceeds 255).
pub fn newton_polish_polys(equations: &[Poly<f64>], x: &mut [f64], steps: usize) -> usize {
    with_newton_terms(equations, x.len(), |terms, coefficients| {
        mingen_runtime::newton_polish(x, terms, coefficients, steps)
    })
    .unwrap_or(0)
}

/// Polishes `x` as a solver that polishes its poor solutions only does
/// ([`mingen_runtime::polish_poor_solution`], on `equations` as [`newton_polish_polys`]
/// takes them). Returns the steps taken (0 if an exponent exceeds 255).
pub fn polish_poor_solution_polys(equations: &[Poly<f64>], x: &mut [f64]) -> usize {
    with_newton_terms(equations, x.len(), |terms, coefficients| {
        mingen_runtime::polish_poor_solution(x, terms, coefficients)
    })
    .unwrap_or(0)
}

/// Whether `x`, read off a redundant basis, is a solution of `equations` (as
/// [`newton_polish_polys`] takes them), by [`mingen_runtime::screen_redundant_readout`] as
/// an emitted solver decides; a rescued `x` is left polished. `false` if an exponent
/// exceeds 255.
pub fn screen_redundant_readout_polys(equations: &[Poly<f64>], x: &mut [f64]) -> bool {
    with_newton_terms(equations, x.len(), |terms, coefficients| {
        mingen_runtime::screen_redundant_readout(x, terms, coefficients)
    })
    .unwrap_or(false)
}

/// Calls `f` with `equations` as the runtime's term tables in `n` unknowns: one
/// coefficient per term, numbered in order, and each term's exponents. `None` if an
/// exponent exceeds 255 or a variable beyond the first `n` occurs.
fn with_newton_terms<T>(
    equations: &[Poly<f64>],
    n: usize,
    f: impl FnOnce(&[&[mingen_runtime::NewtonTerm]], &[f64]) -> T,
) -> Option<T> {
    let mut coefficients = Vec::new();
    let mut exponents: Vec<Vec<(usize, Vec<u8>)>> = Vec::with_capacity(equations.len());
    for p in equations {
        let mut eq = Vec::new();
        for (m, &c) in p.terms() {
            // Variables beyond x's (hidden unknowns) must not occur.
            let (head, tail) = m.0.split_at(n.min(m.0.len()));
            let e = head
                .iter()
                .map(|&d| u8::try_from(d))
                .collect::<Result<Vec<u8>, _>>()
                .ok()?;
            if tail.iter().any(|&d| d != 0) {
                return None;
            }
            eq.push((coefficients.len(), e));
            coefficients.push(c);
        }
        exponents.push(eq);
    }
    let terms: Vec<Vec<mingen_runtime::NewtonTerm>> = exponents
        .iter()
        .map(|eq| eq.iter().map(|(c, e)| (*c, e.as_slice())).collect())
        .collect();
    let terms: Vec<&[mingen_runtime::NewtonTerm]> = terms.iter().map(Vec::as_slice).collect();
    Some(f(&terms, &coefficients))
}

/// Evaluates a real polynomial at a point.
pub fn eval(p: &Poly<f64>, x: &[f64]) -> f64 {
    p.terms().map(|(m, &c)| c * monomial_value(m, x)).sum()
}

/// `m(x)`.
fn monomial_value(m: &Monomial, x: &[f64]) -> f64 {
    m.0.iter()
        .zip(x)
        .map(|(&e, &xi)| xi.powi(i32::from(e)))
        .product()
}

/// Normalised residual `|p(x)| / sum_terms |c| |m(x)|` (0 if every term vanishes).
pub fn normalized_residual(p: &Poly<f64>, x: &[f64]) -> f64 {
    let mut acc = 0.0;
    let mut norm = 0.0;
    for (m, &c) in p.terms() {
        let t = c * monomial_value(m, x);
        acc += t;
        norm += t.abs();
    }
    if norm == 0.0 {
        0.0
    } else {
        acc.abs() / norm
    }
}

/// Recovers linearly eliminated unknowns as an emitted solver does: evaluates the
/// coefficient matrix (entries polynomials in the remaining unknowns, see
/// [`crate::eliminate::Eliminated::coefficient_matrix`]) at `remaining` and returns its
/// unit null vector (sign arbitrary), or, if `inhomogeneous` (the last column holds the
/// free terms), the null vector divided by its last entry. Three homogeneous columns go
/// through [`mingen_runtime::null_vector3_rows`], other widths through
/// [`mingen_runtime::null_vector_dyn`] and [`mingen_runtime::dehomogenize`]; inhomogeneous
/// equations whose eliminated unknowns have constant coefficients (data only) through
/// [`mingen_runtime::least_squares_dyn`] on `A n = -b`. `None` for
/// ragged or too few rows, a non-finite value, a rank below the width minus one, or a
/// solution at infinity.
pub fn recover_eliminated(
    coefficient_matrix: &[Vec<Poly<f64>>],
    remaining: &[f64],
    inhomogeneous: bool,
) -> Option<Vec<f64>> {
    let width = coefficient_matrix.first()?.len();
    if coefficient_matrix.iter().any(|r| r.len() != width) || width < 1 + usize::from(inhomogeneous)
    {
        return None;
    }
    let values: Vec<f64> = coefficient_matrix
        .iter()
        .flat_map(|row| row.iter().map(|p| eval(p, remaining)))
        .collect();
    let k = width - usize::from(inhomogeneous);
    if inhomogeneous && has_data_only_columns(coefficient_matrix, k) {
        // Data-only coefficients: least squares on `A n = -b`, as the emitted solver.
        let rows = coefficient_matrix.len();
        let (a, b): (Vec<f64>, Vec<f64>) = (
            values
                .chunks_exact(width)
                .flat_map(|r| r[..k].to_vec())
                .collect(),
            values.chunks_exact(width).map(|r| r[k]).collect(),
        );
        return mingen_runtime::least_squares_dyn(&a, rows, k, &b);
    }
    if width == 3 && !inhomogeneous {
        let rows: Vec<[f64; 3]> = values.chunks_exact(3).map(|r| [r[0], r[1], r[2]]).collect();
        return mingen_runtime::null_vector3_rows(&rows).map(|v| v.to_vec());
    }
    let v = mingen_runtime::null_vector_dyn(&values, coefficient_matrix.len(), width)?;
    if !inhomogeneous {
        return Some(v);
    }
    let mut out = vec![0.0; width - 1];
    mingen_runtime::dehomogenize(&v, &mut out).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::template::TemplateRow;

    fn mono(e: &[u16]) -> Monomial {
        Monomial(e.to_vec())
    }

    /// Points (1,1), (2,3), (3,-1): e0 = 3x^2 - 11x + 7 + y, e1 = (3xy - x - 7y + 5) + x*e0.
    fn three_points() -> (EliminationTemplate, Vec<Poly<f64>>) {
        let t = |e: &[u16], c: f64| (mono(e), c);
        let e0 = Poly::from_terms(
            2,
            [
                t(&[2, 0], 3.0),
                t(&[1, 0], -11.0),
                t(&[0, 0], 7.0),
                t(&[0, 1], 1.0),
            ],
        );
        let e1 = Poly::from_terms(
            2,
            [
                t(&[3, 0], 3.0),
                t(&[2, 0], -11.0),
                t(&[1, 1], 4.0),
                t(&[1, 0], 6.0),
                t(&[0, 1], -7.0),
                t(&[0, 0], 5.0),
            ],
        );
        let template = EliminationTemplate {
            nvars: 2,
            rows: vec![
                TemplateRow {
                    equation: 1,
                    multiplier: mono(&[0, 0]),
                },
                TemplateRow {
                    equation: 0,
                    multiplier: mono(&[1, 0]),
                },
                TemplateRow {
                    equation: 0,
                    multiplier: mono(&[0, 0]),
                },
            ],
            columns: vec![
                mono(&[3, 0]),
                mono(&[2, 0]),
                mono(&[1, 1]),
                mono(&[1, 0]),
                mono(&[0, 1]),
                mono(&[0, 0]),
            ],
            n_excess: 1,
            n_reducible: 2,
            n_dependent: 0,
            n_hidden: 0,
            basis: vec![mono(&[1, 0]), mono(&[0, 1]), mono(&[0, 0])],
            action: crate::template::Action::var(2, 0),
            sparse: None,
            unrolled: None,
            reduction: None,
            fold: None,
            shift: None,
            spurious_eigenvalues: 0,
            flipped: Vec::new(),
        };
        (template, vec![e0, e1])
    }

    #[test]
    fn three_known_points() {
        let (template, eqs) = three_points();
        let mut sols = solve_template_real(&template, &eqs);
        assert_eq!(sols.len(), 3);
        sols.sort_by(|a, b| a[0].total_cmp(&b[0]));
        let want = [[1.0, 1.0], [2.0, 3.0], [3.0, -1.0]];
        for (s, w) in sols.iter().zip(&want) {
            assert!(
                (s[0] - w[0]).abs() < 1e-12 && (s[1] - w[1]).abs() < 1e-12,
                "{s:?}"
            );
        }
        let all = solve_template(&template, &eqs).unwrap();
        assert_eq!(all.eigenpairs, 3);
        for s in &all.solutions {
            for e in &eqs {
                assert!(normalized_residual(e, s) < 1e-14);
            }
        }
    }

    #[test]
    fn errors_are_reported() {
        let (mut template, eqs) = three_points();
        assert!(matches!(
            solve_template(&template, &eqs[..1]),
            Err(InterpretError::MissingEquation { .. })
        ));
        let mut bad = eqs.clone();
        bad[0].add_term(mono(&[0, 2]), 1.0);
        assert!(matches!(
            solve_template(&template, &bad),
            Err(InterpretError::TermOutsideColumns { .. })
        ));
        let mut nan = eqs.clone();
        nan[0].add_term(mono(&[0, 0]), f64::NAN);
        assert!(solve_template(&template, &nan).is_err());
        assert!(solve_template_real(&template, &nan).is_empty());
        template.n_excess = 2;
        assert!(matches!(
            solve_template(&template, &eqs),
            Err(InterpretError::Malformed(_))
        ));
        template.n_excess = 1;
        template.columns[4] = mono(&[0, 2]);
        template.basis[1] = mono(&[0, 2]);
        assert!(matches!(
            solve_template(&template, &eqs),
            Err(InterpretError::MissingReadout(_))
        ));
    }

    #[test]
    fn readout_pairs_of_the_basis() {
        let (template, _) = three_points();
        // x: (1, x) only; y: (1, y) only (x*y, y^2 are not in the basis).
        assert_eq!(
            readout_pairs(&template).unwrap(),
            vec![vec![(2, 0)], vec![(2, 1)]]
        );
    }

    #[test]
    fn recover_null_vector() {
        // Rows linear in t with entries depending on one remaining unknown s: at s = 2 the
        // matrix [[s, -2, 0], [0, s, -2*s]] has null vector (2, s, s/2)/|.| = (2,2,1)/3.
        let x = |c: f64| Poly::from_terms(1, [(mono(&[1]), c)]);
        let k = |c: f64| Poly::constant(1, c);
        let m = vec![vec![x(1.0), k(-2.0), k(0.0)], vec![k(0.0), x(1.0), x(-2.0)]];
        let v = recover_eliminated(&m, &[2.0], false).unwrap();
        let sign = v[0].signum();
        for (z, w) in v.iter().zip([2.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0]) {
            assert!((z * sign - w).abs() < 1e-14);
        }
        assert!(recover_eliminated(&[], &[], false).is_none());
        assert!(recover_eliminated(&m[..1], &[2.0], false).is_none());
        // The same rows as [A b] with b the last column: t1 = -s/(-2) ... i.e. the affine
        // point of (2, s, s/2) is (4/s, 2) at s = 2: (2, 2).
        let t = recover_eliminated(&m, &[2.0], true).unwrap();
        assert!(
            (t[0] - 2.0).abs() < 1e-14 && (t[1] - 2.0).abs() < 1e-14,
            "{t:?}"
        );
        // Two columns (one eliminated unknown, homogeneous): the unit null vector.
        let two = vec![vec![x(1.0), k(-2.0)]];
        let v = recover_eliminated(&two, &[2.0], false).unwrap();
        assert!((v[0].abs() - v[1].abs()).abs() < 1e-15);
    }
}
