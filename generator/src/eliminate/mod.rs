//! Linear elimination of unknowns (the `eliminate` directive).
//!
//! Equations that are linear and homogeneous in the eliminated unknowns `t` read
//! `A(u) t = 0`, with `A` a matrix whose entries are polynomials in the remaining unknowns
//! `u`. A non-zero `t` exists exactly where every maximal minor of `A` vanishes, so those
//! minors replace the equations; the normalisation equation of `t` (one involving only the
//! eliminated unknowns, such as `t't = 1`) is dropped, and a solver recovers `t` as the unit
//! null vector of `A(u)` at each solution `u`. For G-RSRP this turns 6 unknowns and 20
//! solutions (the 10 with both signs of `t`) into 3 unknowns and 10 solutions.
//!
//! Equations that are linear but inhomogeneous in `t` (`A(u) t + b(u) = 0`, such as the
//! translation of an absolute pose) give the augmented matrix `[A b]`: a solution `t`
//! exists where `[A b]` has a null vector with a non-zero last entry, so the maximal minors
//! of `[A b]` (one column more) replace the equations, and `t` is that null vector divided
//! by its last entry ([`mingen_runtime::null_vector`], [`mingen_runtime::dehomogenize`]).
//! No equation is dropped as a normalisation then: one in `t` alone would constrain it.

use crate::algebra::{Monomial, Poly, Ring};
use std::collections::HashMap;
use thiserror::Error;

mod block;
pub use block::{block_reduction, reduce_block, BlockMode, BlockReduction, MAX_BLOCK_PIVOTS};

/// Why a set of unknowns cannot be eliminated linearly.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum EliminateError {
    /// An equation mixes the eliminated unknowns non-linearly with the others.
    #[error("equation {equation} is neither linear in the eliminated unknowns ({names}) nor free of the other unknowns, so it cannot be eliminated")]
    NotLinear {
        /// Index of the offending equation.
        equation: usize,
        /// The eliminated unknowns, comma separated.
        names: String,
    },
    /// Fewer linear equations than the matrix has columns: the minors do not constrain
    /// anything.
    #[error("only {rows} equations are linear in the {k} eliminated unknowns; at least {needed} are needed")]
    TooFewRows {
        /// Number of linear equations found.
        rows: usize,
        /// Number of eliminated unknowns.
        k: usize,
        /// Columns of the coefficient matrix (`k`, or `k + 1` if inhomogeneous).
        needed: usize,
    },
    /// The equations are inhomogeneous in the eliminated unknowns and another equation
    /// involves those unknowns alone: it constrains them and cannot be dropped.
    #[error("equation {equation} involves only the eliminated unknowns ({names}), whose other equations are inhomogeneous: it is not a normalisation and cannot be eliminated")]
    ConstraintOnEliminated {
        /// Index of the equation.
        equation: usize,
        /// The eliminated unknowns, comma separated.
        names: String,
    },
    /// No unknown is left after elimination.
    #[error("eliminating every unknown leaves nothing to solve for")]
    NothingLeft,
    /// A row of the block has a monomial with an eliminated unknown that the plan's
    /// coefficient matrix has no column for (the instance is not of the planned family).
    #[error("equation {equation} has a term in the eliminated unknowns outside the planned block reduction")]
    BlockColumn {
        /// Index of the equation.
        equation: usize,
    },
}

/// The result of eliminating unknowns from a system.
#[derive(Clone, Debug)]
pub struct Eliminated<C: Ring> {
    /// The new system in the remaining unknowns: equations free of the eliminated unknowns,
    /// followed by every maximal minor of [`Eliminated::coefficient_matrix`] (rows chosen
    /// in lexicographic order of their indices; zero ones included, so that the numbering
    /// is the same for every instance and ring).
    pub equations: Vec<Poly<C>>,
    /// Original flat indices of the remaining unknowns, in their new variable order.
    pub remaining: Vec<usize>,
    /// Original flat indices of the eliminated unknowns (column order of the matrix).
    pub eliminated: Vec<usize>,
    /// `A(u)`: one row per linear equation, one column per eliminated unknown, plus a last
    /// column `b(u)` (the terms free of them) if [`Eliminated::inhomogeneous`]; entries
    /// polynomials in the remaining unknowns. At a solution the eliminated unknowns are
    /// its unit null vector (homogeneous), or its null vector divided by the last entry.
    pub coefficient_matrix: Vec<Vec<Poly<C>>>,
    /// Whether some equation has terms free of the eliminated unknowns beside linear ones.
    pub inhomogeneous: bool,
    /// Original indices of the equations that were dropped as normalisations.
    pub dropped: Vec<usize>,
}

/// Whether the eliminated unknowns' columns of an elimination coefficient matrix (the first
/// `k` of each row; the free terms follow) are constant in the remaining unknowns: data
/// only, the same for every solution of an instance, so that a solver factors them once
/// (`mingen_runtime::LeastSquares`) instead of per solution. The emitter and the
/// interpreter decide with this one test.
pub fn has_data_only_columns<C: Ring>(matrix: &[Vec<Poly<C>>], k: usize) -> bool {
    matrix
        .iter()
        .all(|row| row.len() > k && row[..k].iter().all(|p| p.terms().all(|(m, _)| m.is_one())))
}

/// Eliminates the unknowns `eliminated` (flat indices) from `equations` (polynomials in
/// `nvars` unknowns). See the module documentation.
pub fn eliminate_linear<C: Ring>(
    equations: &[Poly<C>],
    nvars: usize,
    eliminated: &[usize],
) -> Result<Eliminated<C>, EliminateError> {
    eliminate_linear_selected(equations, nvars, eliminated, None)
}

/// [`eliminate_linear`] that computes only the equations `wanted` (indices into the full
/// list of [`Eliminated::equations`], increasing) and returns those, in that order; all of
/// them with `None`. The minors are the costly part, and most are often redundant (see
/// `crate::independent`).
pub fn eliminate_linear_selected<C: Ring>(
    equations: &[Poly<C>],
    nvars: usize,
    eliminated: &[usize],
    wanted: Option<&[usize]>,
) -> Result<Eliminated<C>, EliminateError> {
    let mut elim: Vec<usize> = eliminated.to_vec();
    elim.sort_unstable();
    elim.dedup();
    let remaining = remaining_unknowns(nvars, &elim)?;
    let k = elim.len();
    let nrem = remaining.len();
    // Maps a monomial in all unknowns to one in the remaining unknowns.
    let project = |m: &Monomial| Monomial(remaining.iter().map(|&i| m.0[i]).collect());
    let names = numbered(&elim);

    let mut kept = Vec::new();
    // Rows of [A b]: k columns for the eliminated unknowns, then the free terms.
    let mut matrix: Vec<Vec<Poly<C>>> = Vec::new();
    let mut only_eliminated = Vec::new();
    for (idx, eq) in equations.iter().enumerate() {
        let elim_degree = |m: &Monomial| elim.iter().map(|&i| m.0[i] as u32).sum::<u32>();
        let degrees: Vec<u32> = eq.terms().map(|(m, _)| elim_degree(m)).collect();
        let in_eliminated_only = eq
            .terms()
            .all(|(m, _)| remaining.iter().all(|&i| m.0[i] == 0));
        if degrees.iter().all(|&d| d == 0) {
            kept.push(Poly::from_terms(
                nrem,
                eq.terms().map(|(m, c)| (project(m), c.clone())),
            ));
        } else if degrees.iter().all(|&d| d <= 1) {
            // Linear: a row of [A b] (also `t3 = 1` alone, which fixes the scale).
            let mut row = vec![Poly::zero(nrem); k + 1];
            for (m, c) in eq.terms() {
                let j = elim.iter().position(|&i| m.0[i] == 1).unwrap_or(k);
                row[j].add_term(project(m), c.clone());
            }
            matrix.push(row);
        } else if in_eliminated_only {
            only_eliminated.push(idx);
        } else {
            return Err(EliminateError::NotLinear {
                equation: idx,
                names,
            });
        }
    }
    let inhomogeneous = matrix.iter().any(|row| !row[k].is_zero());
    if inhomogeneous {
        if let Some(&equation) = only_eliminated.first() {
            return Err(EliminateError::ConstraintOnEliminated { equation, names });
        }
    } else {
        for row in &mut matrix {
            row.pop();
        }
    }
    let cols = k + usize::from(inhomogeneous);
    if matrix.len() < cols {
        return Err(EliminateError::TooFewRows {
            rows: matrix.len(),
            k,
            needed: cols,
        });
    }
    let dropped = only_eliminated;
    let free = kept.len();
    let is_wanted = |i: usize| wanted.map_or(true, |w| w.binary_search(&i).is_ok());
    let mut equations_out: Vec<Poly<C>> = kept
        .into_iter()
        .enumerate()
        .filter(|(i, _)| is_wanted(*i))
        .map(|(_, e)| e)
        .collect();
    for (k, rows) in combinations(matrix.len(), cols).into_iter().enumerate() {
        // Every minor has its index, zero or not: equations are referred to by index, and a
        // minor that vanishes on the whole data family (e.g. three rows of one cross
        // product, of rank 2) is exactly zero mod p but rounding noise in f64, so dropping
        // the zero ones would number the equations differently over the two rings.
        if !is_wanted(free + k) {
            continue;
        }
        let sub: Vec<Vec<Poly<C>>> = rows.iter().map(|&r| matrix[r].clone()).collect();
        equations_out.push(determinant(&sub, nrem));
    }
    Ok(Eliminated {
        equations: equations_out,
        remaining,
        eliminated: elim,
        coefficient_matrix: matrix,
        inhomogeneous,
        dropped,
    })
}

/// The equations whose every term has total degree at most one in the unknowns, with at
/// least one of degree one: `A x + b = 0` with `A`, `b` free of unknowns (data and
/// numbers), as the epipolar constraints on the entries of an essential matrix.
pub fn affine_equations<C: Ring>(equations: &[Poly<C>]) -> Vec<usize> {
    equations
        .iter()
        .enumerate()
        .filter(|(_, e)| {
            e.terms().all(|(m, _)| m.degree() <= 1) && e.terms().any(|(m, _)| m.degree() == 1)
        })
        .map(|(i, _)| i)
        .collect()
}

/// Substitutes the unknowns `pivots` (flat indices, one per equation of `linear`) solved
/// from the independent affine equations `linear` (see [`affine_equations`]) into the
/// other equations except `implied` (affine equations that are combinations of
/// `linear`, see [`linear_pivots`]). With `A_p` the pivots' coefficient block (data only) and `r(u) = A_f u + b`
/// the rest, Cramer's rule gives `d x_p = g(u)` with `d = det A_p` and `g_i` the
/// determinant of `A_p` with column `i` replaced by `-r(u)`, polynomials in the remaining
/// unknowns `u` of degree at most one. An equation of degree `m` in the pivots becomes
/// `d^m f(g / d, u)`, computed without division (every ring, every instance alike). The
/// result is an [`Eliminated`] whose equations are the substituted ones (in their order),
/// whose coefficient matrix is `[A_p r(u)]` (one row per affine equation: at a solution
/// `u` the pivots are its null vector over the last entry) and which is inhomogeneous.
pub fn substitute_linear<C: Ring>(
    equations: &[Poly<C>],
    nvars: usize,
    pivots: &[usize],
    (linear, implied): (&[usize], &[usize]),
) -> Result<Eliminated<C>, EliminateError> {
    let k = pivots.len();
    if linear.len() != k || k == 0 {
        return Err(EliminateError::TooFewRows {
            rows: linear.len(),
            k,
            needed: k,
        });
    }
    let remaining = remaining_unknowns(nvars, pivots)?;
    let nrem = remaining.len();
    let project = |m: &Monomial| Monomial(remaining.iter().map(|&i| m.0[i]).collect());
    let mut matrix: Vec<Vec<Poly<C>>> = Vec::with_capacity(k);
    for &r in linear {
        let mut row = vec![Poly::zero(nrem); k + 1];
        for (m, c) in equations[r].terms() {
            match pivots.iter().position(|&p| m.0[p] > 0) {
                Some(j) => row[j].add_term(Monomial(vec![0; nrem]), c.clone()),
                None => row[k].add_term(project(m), c.clone()),
            }
        }
        matrix.push(row);
    }
    let block = |replace: Option<usize>| -> Vec<Vec<Poly<C>>> {
        matrix
            .iter()
            .map(|row| {
                (0..k)
                    .map(|j| match replace {
                        Some(i) if i == j => row[k].neg(),
                        _ => row[j].clone(),
                    })
                    .collect()
            })
            .collect()
    };
    let d = determinant(&block(None), nrem);
    let g: Vec<Poly<C>> = (0..k).map(|i| determinant(&block(Some(i)), nrem)).collect();
    let mut out = Vec::new();
    for (idx, eq) in equations.iter().enumerate() {
        // The affine equations are solved; those implied by them would be zero up to
        // rounding, so they are left out too.
        if linear.contains(&idx) || implied.contains(&idx) {
            continue;
        }
        let images: Vec<&Poly<C>> = g.iter().collect();
        let acc = substitute_quotients(eq, pivots, &images, &d, &remaining);
        out.push(acc);
    }
    Ok(Eliminated {
        equations: out,
        remaining,
        eliminated: pivots.to_vec(),
        coefficient_matrix: matrix,
        inhomogeneous: true,
        dropped: Vec::new(),
    })
}

/// Pivots for [`substitute_linear`] from the affine equations `linear`: a maximal
/// independent subset of them (on this instance) and one unknown each whose coefficient
/// block is nonsingular, chosen from the last unknown backwards (the first ones stay, in
/// their order). Returns `(pivots, used, implied)`: the pivot unknowns, the equations they
/// are solved from, and the affine equations that are combinations of those (satisfied
/// with them). `None` if no pivot is found or the pivots would leave no unknown.
pub fn linear_pivots<const P: u32>(
    equations: &[Poly<crate::algebra::Fp<P>>],
    nvars: usize,
    linear: &[usize],
) -> Option<(Vec<usize>, Vec<usize>, Vec<usize>)> {
    // Each affine equation's coefficients of x_0 .. x_{n-1}; the rows that enlarge the
    // basis are the independent ones, its pivot columns the pivot unknowns.
    let rows = linear.iter().map(|&r| {
        let mut row = vec![0u32; nvars];
        for (m, c) in equations[r].terms() {
            if let Some(j) = m.0.iter().position(|&e| e == 1) {
                row[j] = c.value();
            }
        }
        row
    });
    let (independent, pivots) = pivots_from_last::<P>(rows, nvars);
    let (mut used, mut implied) = (Vec::new(), Vec::new());
    for (&r, independent) in linear.iter().zip(independent) {
        if independent {
            used.push(r);
        } else {
            implied.push(r);
        }
    }
    if pivots.is_empty() || pivots.len() >= nvars {
        return None;
    }
    Some((pivots, used, implied))
}

/// Echelon pivots of `rows` (`ncols` entries mod P each, in order), preferring pivots on
/// the last columns: whether each row is independent of those before it, and the pivot
/// columns, increasing. Any nonsingular pivot block serves the callers; the last columns
/// keep the first unknowns (or monomials) out of it.
fn pivots_from_last<const P: u32>(
    rows: impl IntoIterator<Item = Vec<u32>>,
    ncols: usize,
) -> (Vec<bool>, Vec<usize>) {
    use crate::template::linalg::EchelonBasis;
    // Reversed columns, so that the echelon basis takes its pivots from the last one
    // backwards.
    let mut basis = EchelonBasis::<P>::new(ncols);
    let independent = rows
        .into_iter()
        .map(|mut row| {
            row.reverse();
            basis.insert(row)
        })
        .collect();
    let mut pivots: Vec<usize> = basis
        .pivot_columns()
        .into_iter()
        .map(|c| ncols - 1 - c)
        .collect();
    pivots.sort_unstable();
    (independent, pivots)
}

/// The unknowns among `candidates` (flat indices) that every equation has only in terms of
/// degree one: `c x` with `c` free of unknowns (data and numbers), as an absolute pose's
/// translation. Eliminating them ([`eliminate_linear`]) leaves the minors of a matrix
/// `[A b]` whose `A` involves no unknown, so the minors are combinations of the entries of
/// `b`: as many independent equations as rows beyond the unknowns, of `b`'s degree.
pub fn purely_linear_unknowns<C: Ring>(
    equations: &[Poly<C>],
    candidates: impl IntoIterator<Item = usize>,
) -> Vec<usize> {
    candidates
        .into_iter()
        .filter(|&x| {
            let mut appears = false;
            let only_linear = equations.iter().all(|e| {
                e.terms().all(|(m, _)| match m.0.get(x) {
                    Some(&k) if k > 0 => {
                        appears = true;
                        k == 1 && m.degree() == 1
                    }
                    _ => true,
                })
            });
            appears && only_linear
        })
        .collect()
}

/// The remaining unknowns (flat indices) when `eliminated` are eliminated from `nvars`;
/// an error if none is left.
fn remaining_unknowns(nvars: usize, eliminated: &[usize]) -> Result<Vec<usize>, EliminateError> {
    let remaining: Vec<usize> = (0..nvars).filter(|i| !eliminated.contains(i)).collect();
    if remaining.is_empty() {
        return Err(EliminateError::NothingLeft);
    }
    Ok(remaining)
}

/// The eliminated unknowns as the library's errors name them (`#i`, flat indices; the
/// command line puts their names in).
fn numbered(eliminated: &[usize]) -> String {
    eliminated
        .iter()
        .map(|i| format!("#{i}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `d^top f(g / d, u)` without division: `f` (`eq`, in all unknowns) with each unknown
/// `solved[i]` replaced by `images[i] / d`, multiplied through by `d` to the highest
/// degree `top` of `f` in them; a polynomial in the `remaining` unknowns.
fn substitute_quotients<C: Ring>(
    eq: &Poly<C>,
    solved: &[usize],
    images: &[&Poly<C>],
    d: &Poly<C>,
    remaining: &[usize],
) -> Poly<C> {
    let nrem = remaining.len();
    let project = |m: &Monomial| Monomial(remaining.iter().map(|&i| m.0[i]).collect());
    let degree = |m: &Monomial| solved.iter().map(|&p| u32::from(m.0[p])).sum::<u32>();
    let top = eq.terms().map(|(m, _)| degree(m)).max().unwrap_or(0);
    let mut acc = Poly::zero(nrem);
    for (m, c) in eq.terms() {
        let mut term = Poly::from_terms(nrem, [(project(m), c.clone())]);
        for (i, &p) in solved.iter().enumerate() {
            if m.0[p] > 0 {
                term = term.mul(&images[i].pow(u32::from(m.0[p])));
            }
        }
        let rest = top - degree(m);
        if rest > 0 {
            term = term.mul(&d.pow(rest));
        }
        acc = acc.add(&term);
    }
    acc
}

/// All `k`-subsets of `0..n` in lexicographic order.
fn combinations(n: usize, k: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut cur = Vec::with_capacity(k);
    fn rec(start: usize, n: usize, k: usize, cur: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        if cur.len() == k {
            out.push(cur.clone());
            return;
        }
        for i in start..n {
            cur.push(i);
            rec(i + 1, n, k, cur, out);
            cur.pop();
        }
    }
    rec(0, n, k, &mut cur, &mut out);
    out
}

/// Determinant of a square matrix of polynomials by Laplace expansion along the first row
/// (division-free, so it works over any ring), each minor of the lower rows computed once
/// (memoised by its column set: `2^n` minors instead of `n!` expansions, with the same
/// operations in the same order as the plain expansion).
fn determinant<C: Ring>(m: &[Vec<Poly<C>>], nvars: usize) -> Poly<C> {
    let n = m.len();
    if n == 0 {
        return Poly::constant(nvars, C::one());
    }
    let mut memo = HashMap::new();
    lower_minor(m, 0, &(0..n).collect::<Vec<_>>(), nvars, &mut memo)
}

/// The minor of rows `row..` and columns `columns` of `m` (see [`determinant`]).
fn lower_minor<C: Ring>(
    m: &[Vec<Poly<C>>],
    row: usize,
    columns: &[usize],
    nvars: usize,
    memo: &mut HashMap<Vec<usize>, Poly<C>>,
) -> Poly<C> {
    if columns.len() == 1 {
        return m[row][columns[0]].clone();
    }
    if let Some(p) = memo.get(columns) {
        return p.clone();
    }
    let mut acc = Poly::zero(nvars);
    for (j, &c) in columns.iter().enumerate() {
        if m[row][c].is_zero() {
            continue;
        }
        let rest: Vec<usize> = columns.iter().copied().filter(|&x| x != c).collect();
        let term = m[row][c].mul(&lower_minor(m, row + 1, &rest, nvars, memo));
        acc = if j % 2 == 0 {
            acc.add(&term)
        } else {
            acc.sub(&term)
        };
    }
    memo.insert(columns.to_vec(), acc.clone());
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Fp, P1};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    type F = Fp<P1>;

    /// Random system: rows linear in (t1, t2, t3) (vars 1..4) with coefficients linear in
    /// u (var 0), plus the normalisation t't = 1.
    fn system(rng: &mut ChaCha8Rng, rows: usize) -> Vec<Poly<F>> {
        let mut eqs = Vec::new();
        for _ in 0..rows {
            let mut p = Poly::zero(4);
            for j in 1..4 {
                let mut m0 = Monomial::var(4, j);
                p.add_term(m0.clone(), F::new(rng.gen_range(1..1000)));
                m0.0[0] = 1;
                p.add_term(m0, F::new(rng.gen_range(1..1000)));
            }
            eqs.push(p);
        }
        let mut n = Poly::constant(4, -F::one());
        for j in 1..4 {
            n = n.add(&Poly::var(4, j).mul(&Poly::var(4, j)));
        }
        eqs.push(n);
        eqs
    }

    /// The coefficient matrix evaluated at `u`.
    fn evaluated(e: &Eliminated<F>, u: F) -> Vec<Vec<F>> {
        e.coefficient_matrix
            .iter()
            .map(|r| r.iter().map(|p| p.eval(&[u])).collect())
            .collect()
    }
    /// The determinant of the rows `r` of a three-column matrix.
    fn det3(a: &[Vec<F>], r: [usize; 3]) -> F {
        let m = |i: usize, j: usize| a[r[i]][j];
        m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
            - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
            + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
    }

    #[test]
    fn minors_vanish_at_the_solutions_and_null_vector_solves() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let eqs = system(&mut rng, 4);
        let e = eliminate_linear(&eqs, 4, &[1, 2, 3]).unwrap();
        assert_eq!(e.remaining, vec![0]);
        assert_eq!(e.dropped, vec![4]);
        assert_eq!(e.coefficient_matrix.len(), 4);
        assert_eq!(e.equations.len(), 4); // C(4,3) minors, each cubic in u
        assert!(e.equations.iter().all(|p| p.degree() == Some(3)));
        // Each minor evaluated at u equals the determinant of the numeric 3x3 block.
        let u = F::new(12345);
        let a = evaluated(&e, u);
        assert_eq!(e.equations[0].eval(&[u]), det3(&a, [0, 1, 2]));
        assert_eq!(e.equations[3].eval(&[u]), det3(&a, [1, 2, 3]));
    }

    #[test]
    fn non_linear_mixing_is_an_error() {
        // u * t1^2 mixes the eliminated unknown quadratically with u.
        let mut p = Poly::<F>::zero(2);
        p.add_term(Monomial(vec![1, 2]), F::one());
        let err = eliminate_linear(&[p], 2, &[1]).unwrap_err();
        assert!(matches!(err, EliminateError::NotLinear { equation: 0, .. }));
        assert!(matches!(
            eliminate_linear::<F>(&[], 1, &[0]),
            Err(EliminateError::NothingLeft)
        ));
        let lin = Poly::<F>::var(2, 1);
        assert!(matches!(
            eliminate_linear(&[lin], 2, &[1]).map(|e| e.equations.len()),
            Ok(1)
        ));
    }

    #[test]
    fn inhomogeneous_rows_give_the_minors_of_the_augmented_matrix() {
        // Rows (u, 1) . t + (u + 2) = 0 style: t (two unknowns) linear with free terms.
        // Variables: u (0), t1 (1), t2 (2). With rows A(u) t + b(u) = 0, the 3x3 minors
        // of [A b] vanish exactly where a t exists.
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mut eqs = Vec::new();
        for _ in 0..3 {
            let mut p = Poly::<F>::zero(3);
            for j in 0..3 {
                let mut m = Monomial::one(3);
                if j > 0 {
                    m.0[j] = 1;
                }
                p.add_term(m.clone(), F::new(rng.gen_range(1..1000)));
                m.0[0] = 1;
                p.add_term(m, F::new(rng.gen_range(1..1000)));
            }
            eqs.push(p);
        }
        let e = eliminate_linear(&eqs, 3, &[1, 2]).unwrap();
        assert!(e.inhomogeneous);
        assert_eq!(e.coefficient_matrix[0].len(), 3);
        assert_eq!(e.equations.len(), 1); // C(3, 3)
        assert_eq!(e.equations[0].degree(), Some(3));
        // The minor equals det([A b]) at any u (it vanishes where (t1, t2, 1) solves the rows).
        let u = F::new(777);
        assert_eq!(
            e.equations[0].eval(&[u]),
            det3(&evaluated(&e, u), [0, 1, 2])
        );
        // The free terms sit in the last column: row 0's b(u) is eqs[0] at t = 0.
        assert_eq!(
            e.coefficient_matrix[0][2].eval(&[u]),
            eqs[0].eval(&[u, F::zero(), F::zero()])
        );
        // Too few rows for [A b], and an equation in t alone that is not linear.
        assert!(matches!(
            eliminate_linear(&eqs[..2], 3, &[1, 2]),
            Err(EliminateError::TooFewRows {
                rows: 2,
                k: 2,
                needed: 3
            })
        ));
        let mut norm = Poly::<F>::constant(3, -F::one());
        norm = norm.add(&Poly::var(3, 1).mul(&Poly::var(3, 1)));
        let mut with_norm = eqs.clone();
        with_norm.push(norm);
        assert!(matches!(
            eliminate_linear(&with_norm, 3, &[1, 2]),
            Err(EliminateError::ConstraintOnEliminated { equation: 3, .. })
        ));
    }
}
