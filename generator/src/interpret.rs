//! Interpreted f64 solving of an elimination template (no code generation): the reference
//! the emitted solvers are compared with, and the engine of `mingen audit`.
//!
//! Follows the convention of [`crate::template`] exactly: the template is filled with
//! `multiplier * equations[equation]`, reduced by Gauss-Jordan elimination on the
//! `excess | reducible` columns, the action matrix is assembled row by row, and every
//! eigenvector `v` (complex ones included) gives a solution, each unknown read off by
//! [`readout_pairs`] / [`read_unknown`] (least squares over every pair `b, x_i b` of basis
//! monomials, not only `v[x_i] / v[1]`).

use crate::algebra::{Monomial, Poly};
use crate::template::{EliminationTemplate, ShapeError};
use nalgebra::{Complex, DMatrix, Schur};
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
    /// A reducible column has no usable pivot: the template is singular on this instance.
    #[error("reducible column {column} ({monomial}) has no pivot: the template is singular here")]
    Singular {
        /// Column index.
        column: usize,
        /// Its monomial.
        monomial: String,
    },
    /// `action * b` is neither a basis monomial nor a reducible column.
    #[error("action * {basis} = {product} is neither in the basis nor a reducible column")]
    ActionNotCovered {
        /// The basis monomial b.
        basis: String,
        /// The product.
        product: String,
    },
    /// The basis lacks `1` or a variable, so solutions cannot be read off.
    #[error("the basis lacks the monomial {0}, needed to read the solutions")]
    MissingReadout(String),
    /// The Schur iteration on the action matrix did not converge.
    #[error("the eigenvalue iteration on the action matrix did not converge")]
    NoConvergence,
}

/// Relative pivot tolerance of the interpreter's Gauss-Jordan elimination (rows are first
/// scaled to unit max-norm). An excess column without a pivot above it is skipped (it is
/// linearly dependent on earlier columns); a reducible column without one is an error.
pub const INTERPRET_PIVOT_TOL: f64 = 1e-12;

/// A solution is real for [`solve_template_real`] if every imaginary part is at most
/// `REAL_TOL * max(1, max_i |x_i|)`.
pub const REAL_TOL: f64 = 1e-8;

/// The shared predicate [`EliminationTemplate::check_emittable`], in this module's errors.
fn check_template(t: &EliminationTemplate) -> Result<(), InterpretError> {
    t.check_emittable(&[]).map_err(|e| match e {
        ShapeError::BasisLacks(m) => InterpretError::MissingReadout(m),
        ShapeError::ActionNotCovered { basis, product } => {
            InterpretError::ActionNotCovered { basis, product }
        }
        e @ (ShapeError::Malformed(_) | ShapeError::TooFewRows { .. }) => {
            InterpretError::Malformed(e.to_string())
        }
    })
}

/// Fills the template matrix (rows x columns, see the convention) for these equations.
pub fn fill_template(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Result<DMatrix<f64>, InterpretError> {
    check_template(template)?;
    let col: HashMap<&Monomial, usize> = template
        .columns
        .iter()
        .enumerate()
        .map(|(i, m)| (m, i))
        .collect();
    let (nr, nc) = template.size();
    let mut m = DMatrix::zeros(nr, nc);
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
        for (mon, &c) in eq.terms() {
            let prod = row.multiplier.mul(mon);
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
            m[(i, j)] += c;
        }
    }
    Ok(m)
}

/// Gauss-Jordan elimination of a filled template (partial pivoting, rows scaled to unit
/// max-norm first) on the `excess | reducible` columns, the dependent excess columns left
/// out as in the emitted solvers. Returns, for each reducible column
/// `n_excess + k`, the row that holds its reduced polynomial `r + sum_j T[r, j] b_j`.
pub fn reduce_template(
    m: &mut DMatrix<f64>,
    template: &EliminationTemplate,
) -> Result<Vec<usize>, InterpretError> {
    let (nr, nc) = m.shape();
    let npiv = template.n_excess + template.n_reducible;
    if nc != template.columns.len() || npiv > nc {
        return Err(InterpretError::Malformed("matrix shape".into()));
    }
    for i in 0..nr {
        let s = m.row(i).amax();
        if !s.is_finite() {
            return Err(InterpretError::NonFinite { row: i });
        }
        if s > 0.0 {
            m.row_mut(i).scale_mut(1.0 / s);
        }
    }
    let mut next = 0;
    let mut pivot_row = vec![usize::MAX; npiv];
    for (j, pr) in pivot_row.iter_mut().enumerate() {
        if template.eliminated_column(j).is_none() {
            continue;
        }
        let mut p = next;
        let mut best = 0.0;
        for i in next..nr {
            let a = m[(i, j)].abs();
            if a > best {
                best = a;
                p = i;
            }
        }
        if best <= INTERPRET_PIVOT_TOL {
            if j < template.n_excess {
                continue;
            }
            return Err(InterpretError::Singular {
                column: j,
                monomial: format!("{:?}", template.columns[j]),
            });
        }
        m.swap_rows(p, next);
        let inv = 1.0 / m[(next, j)];
        m.row_mut(next).scale_mut(inv);
        m[(next, j)] = 1.0;
        for i in 0..nr {
            if i == next {
                continue;
            }
            let f = m[(i, j)];
            if f != 0.0 {
                for k in j..nc {
                    let v = m[(next, k)];
                    m[(i, k)] -= f * v;
                }
                m[(i, j)] = 0.0;
            }
        }
        *pr = next;
        next += 1;
    }
    Ok(pivot_row[template.n_excess..].to_vec())
}

/// The action matrix (|B| x |B|) of the template on these equations, per the convention:
/// `M v = action(s) v` for `v = (b_0(s), ..., b_{n-1}(s))`.
pub fn action_matrix(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Result<DMatrix<f64>, InterpretError> {
    let mut m = fill_template(template, equations)?;
    let red_rows = reduce_template(&mut m, template)?;
    let npiv = template.n_excess + template.n_reducible;
    let n = template.basis.len();
    let basis_idx: HashMap<&Monomial, usize> = template
        .basis
        .iter()
        .enumerate()
        .map(|(i, b)| (b, i))
        .collect();
    let red_idx: HashMap<&Monomial, usize> = template.columns[template.n_excess..npiv]
        .iter()
        .enumerate()
        .map(|(k, r)| (r, k))
        .collect();
    let mut a = DMatrix::zeros(n, n);
    for (j, b) in template.basis.iter().enumerate() {
        let prod = template.action.mul(b);
        if let Some(&k) = basis_idx.get(&prod) {
            a[(j, k)] = 1.0;
        } else if let Some(&k) = red_idx.get(&prod) {
            let row = red_rows[k];
            for c in 0..n {
                a[(j, c)] = -m[(row, npiv + c)];
            }
        } else {
            return Err(InterpretError::ActionNotCovered {
                basis: format!("{b:?}"),
                product: format!("{prod:?}"),
            });
        }
    }
    Ok(a)
}

/// The read-out pairs of every unknown (see [`read_unknown`]): for each variable `x_i`, all
/// pairs `(j, k)` of basis indices with `basis[k] = x_i * basis[j]`, the pair `(1, x_i)`
/// first, then by increasing `j`. Errors if the basis lacks `1` or a variable.
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
    let one = find(&Monomial::one(n))?;
    (0..n)
        .map(|i| {
            let x = Monomial::var(n, i);
            let first = (one, find(&x)?);
            let mut pairs = vec![first];
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

/// Reads one unknown off an eigenvector `v` (`v ∝ (b_0(s), ..., b_{n-1}(s))`) through its
/// read-out pairs `(j, k)`, `b_k = x * b_j` (from [`readout_pairs`]): every pair gives
/// `x = v[k] / v[j]`, and the least-squares combination
/// `x = sum_p conj(v[j_p]) v[k_p] / sum_p |v[j_p]|^2` weights each by `|v[j]|^2`. With a
/// single pair it is the plain ratio `v[k] / v[j]` (usually `v[x] / v[1]`).
///
/// An eigenvector computed to absolute accuracy `e` gives `x` from one pair to about
/// `e / |v[j]|`: the plain read-out `v[x] / v[1]` loses all accuracy on solutions of large
/// magnitude, where `v[1]` is tiny next to the higher-degree monomials (grsrp: 56 of its
/// 59 audit failures in 10,000 instances were such solutions). The combination is
/// dominated by the largest denominators instead.
pub fn read_unknown(v: &[Complex<f64>], pairs: &[(usize, usize)]) -> Complex<f64> {
    if let [(j, k)] = pairs {
        return v[*k] / v[*j];
    }
    let mut num = Complex::new(0.0, 0.0);
    let mut den = 0.0;
    for &(j, k) in pairs {
        num += v[j].conj() * v[k];
        den += v[j].norm_sqr();
    }
    num / den
}

/// Unit right null vector (the right singular vector of the smallest singular value) of a
/// complex matrix; rows are padded with zeros if fewer than columns.
fn complex_null_vector(a: &DMatrix<Complex<f64>>) -> Option<Vec<Complex<f64>>> {
    let (r, c) = a.shape();
    if c == 0 || a.iter().any(|z| !(z.re.is_finite() && z.im.is_finite())) {
        return None;
    }
    let a = if r < c {
        let mut p = DMatrix::zeros(c, c);
        p.view_mut((0, 0), (r, c)).copy_from(a);
        p
    } else {
        a.clone()
    };
    let svd = a.try_svd(false, true, f64::EPSILON, 10_000)?;
    let vt = svd.v_t?;
    let k = svd.singular_values.imin();
    Some(vt.row(k).iter().map(|z| z.conj()).collect())
}

/// All solutions (real and complex) of the system, one per eigenvector of the action
/// matrix: unknown `x_i` is read off by [`read_unknown`] (the basis must contain `1` and
/// every variable).
///
/// Eigenvalues come from a real Schur decomposition (iteration-capped); the eigenvector
/// of each eigenvalue `lambda` is the null vector of `M - lambda I`, by a complex SVD.
/// A repeated eigenvalue therefore yields the same vector twice.
pub fn solve_template(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Result<Vec<Vec<Complex<f64>>>, InterpretError> {
    check_template(template)?;
    let pairs = readout_pairs(template)?;
    let a = action_matrix(template, equations)?;
    let n = a.nrows();
    let eigenvalues = eigenvalues_robust(&a).ok_or(InterpretError::NoConvergence)?;
    let ac: DMatrix<Complex<f64>> = a.map(|x| Complex::new(x, 0.0));
    let mut out = Vec::with_capacity(n);
    for &lam in eigenvalues.iter() {
        let mut shifted = ac.clone();
        for i in 0..n {
            shifted[(i, i)] -= lam;
        }
        let Some(v) = complex_null_vector(&shifted) else {
            continue;
        };
        out.push(pairs.iter().map(|p| read_unknown(&v, p)).collect());
    }
    Ok(out)
}

/// The real solutions (imaginary parts within [`REAL_TOL`]), for comparison with the
/// emitted solvers. Like an emitted solver, returns no solution when the instance cannot
/// be solved (singular template, non-finite data): use [`solve_template`] for the reason.
pub fn solve_template_real(
    template: &EliminationTemplate,
    equations: &[Poly<f64>],
) -> Vec<Vec<f64>> {
    let Ok(sols) = solve_template(template, equations) else {
        return Vec::new();
    };
    sols.into_iter()
        .filter(|s| {
            let big = s.iter().map(|z| z.norm()).fold(1.0, f64::max);
            s.iter()
                .all(|z| z.re.is_finite() && z.im.abs() <= REAL_TOL * big)
        })
        .map(|s| s.iter().map(|z| z.re).collect())
        .collect()
}

/// All eigenvalues of `a` by nalgebra's real Schur form, made robust: nalgebra's Francis
/// iteration has no exceptional shifts and stalls, at any iteration cap, on 20-30 % of the
/// action matrices of sign-symmetric problems (spectra in `±λ` pairs: grsrp, grsrp_gravity).
/// Each failure is retried on a similar matrix (same eigenvalues): shifted by `σI`, balanced
/// (diagonal similarity), and conjugated by a fixed Householder reflection, which breaks the
/// exact structure (unit rows, zeros) the stall comes from.
pub fn eigenvalues_robust(a: &DMatrix<f64>) -> Option<nalgebra::DVector<Complex<f64>>> {
    let n = a.nrows();
    let max_iter = 1000 + 100 * n;
    let scale = a.norm() / n.max(1) as f64;
    let u = nalgebra::DVector::from_fn(n, |i, _| {
        1.0 + 0.37 * i as f64 + ((i * 7919) % 13) as f64 * 0.11
    });
    let householder = DMatrix::<f64>::identity(n, n) - &u * u.transpose() * (2.0 / u.dot(&u));
    let w = nalgebra::DVector::from_fn(n, |i, _| ((i * 2654435761) % 1009) as f64 / 1009.0 - 0.43);
    let householder2 = DMatrix::<f64>::identity(n, n) - &w * w.transpose() * (2.0 / w.dot(&w));
    let balanced = balance(a);
    let candidates = [
        (a.clone(), 0.0),
        (
            a + DMatrix::<f64>::identity(n, n) * (0.618 * scale),
            0.618 * scale,
        ),
        (&householder * a * &householder, 0.0),
        (balanced.clone(), 0.0),
        (&householder * &balanced * &householder, 0.0),
        (&householder2 * a * &householder2, 0.0),
        (&householder2 * &balanced * &householder2, 0.0),
    ];
    for (m, sigma) in candidates {
        if let Some(s) = Schur::try_new(m, f64::EPSILON, max_iter) {
            return Some(s.complex_eigenvalues().map(|z| z - sigma));
        }
    }
    None
}

/// Diagonal similarity `D^-1 a D` equalising row and column norms (a few sweeps of the
/// classic balancing iteration).
fn balance(a: &DMatrix<f64>) -> DMatrix<f64> {
    let n = a.nrows();
    let mut d = a.clone();
    for _ in 0..10 {
        for i in 0..n {
            let c: f64 = (0..n).filter(|&j| j != i).map(|j| d[(j, i)].abs()).sum();
            let r: f64 = (0..n).filter(|&j| j != i).map(|j| d[(i, j)].abs()).sum();
            if c > 0.0 && r > 0.0 && c.is_finite() && r.is_finite() {
                let f = (r / c).sqrt();
                for j in 0..n {
                    d[(i, j)] /= f;
                    d[(j, i)] *= f;
                }
            }
        }
    }
    d
}

/// Evaluates a real polynomial at a complex point.
pub fn eval_complex(p: &Poly<f64>, x: &[Complex<f64>]) -> Complex<f64> {
    let mut acc = Complex::new(0.0, 0.0);
    for (m, &c) in p.terms() {
        let mut t = Complex::new(c, 0.0);
        for (xi, &e) in x.iter().zip(&m.0) {
            for _ in 0..e {
                t *= xi;
            }
        }
        acc += t;
    }
    acc
}

/// Normalised residual `|p(x)| / sum_terms |c| |m(x)|` (0 if every term vanishes).
pub fn normalized_residual(p: &Poly<f64>, x: &[Complex<f64>]) -> f64 {
    let mut acc = Complex::new(0.0, 0.0);
    let mut norm = 0.0;
    for (m, &c) in p.terms() {
        let mut t = Complex::new(c, 0.0);
        for (xi, &e) in x.iter().zip(&m.0) {
            for _ in 0..e {
                t *= xi;
            }
        }
        acc += t;
        norm += t.norm();
    }
    if norm == 0.0 {
        0.0
    } else {
        acc.norm() / norm
    }
}

/// Recovers linearly eliminated unknowns: evaluates the coefficient matrix (rows x k,
/// entries polynomials in the remaining unknowns) at `remaining` and returns its null
/// vector (complex SVD), scaled so that `sum_i v_i^2 = 1` — the bilinear norm, matching a
/// normalisation such as `t' * t = 1` also for complex solutions; for a real solution it
/// is the usual unit vector (sign arbitrary). If `sum v_i^2` vanishes, the Hermitian unit
/// vector is returned. `None` for an empty matrix, ragged rows or non-finite values.
pub fn recover_eliminated(
    coefficient_matrix: &[Vec<Poly<f64>>],
    remaining: &[Complex<f64>],
) -> Option<Vec<Complex<f64>>> {
    let r = coefficient_matrix.len();
    let k = coefficient_matrix.first()?.len();
    if coefficient_matrix.iter().any(|row| row.len() != k) {
        return None;
    }
    let a = DMatrix::from_fn(r, k, |i, j| {
        eval_complex(&coefficient_matrix[i][j], remaining)
    });
    let mut v = complex_null_vector(&a)?;
    let s: Complex<f64> = v.iter().map(|z| z * z).sum();
    if s.norm() > 1e-8 {
        let f = s.sqrt().inv();
        for z in &mut v {
            *z *= f;
        }
    }
    Some(v)
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
            basis: vec![mono(&[1, 0]), mono(&[0, 1]), mono(&[0, 0])],
            action: mono(&[1, 0]),
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
        for s in solve_template(&template, &eqs).unwrap() {
            for e in &eqs {
                assert!(normalized_residual(e, &s) < 1e-14);
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
    fn readout_uses_the_large_entries() {
        // Basis (x^2, x, 1) at x = 1e6, unit vector, entries perturbed by 1e-13 absolute:
        // v[x] / v[1] is off by ~10 %, the combination with v[x^2] / v[x] by ~1e-7.
        let x = 1e6;
        let n = (x * x * x * x + x * x + 1.0f64).sqrt();
        let v: Vec<Complex<f64>> = [x * x / n + 1e-13, x / n - 1e-13, 1.0 / n + 1e-13]
            .iter()
            .map(|&r| Complex::new(r, 0.0))
            .collect();
        let plain = read_unknown(&v, &[(2, 1)]);
        let both = read_unknown(&v, &[(2, 1), (1, 0)]);
        assert!((plain.re - x).abs() > 0.05 * x, "{plain}");
        assert!((both.re - x).abs() < 1e-6 * x, "{both}");
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
        let v = recover_eliminated(&m, &[Complex::new(2.0, 0.0)]).unwrap();
        let sign = v[0].re.signum();
        for (z, w) in v.iter().zip([2.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0]) {
            assert!((z * sign - Complex::new(w, 0.0)).norm() < 1e-14);
        }
        assert!(recover_eliminated(&[], &[]).is_none());
    }
}
