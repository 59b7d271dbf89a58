//! Elimination through the data row reduction of the block of equations linear in the
//! eliminated unknowns: what the worksheets of Martyushev et al. do with a numeric
//! `ReducedRowEchelonForm` of the block's coefficient matrix before substituting.
//!
//! Write the block (the equations of degree one in the eliminated unknowns `t`) as
//! `C y + D m(u) = 0`, where `y` are the block's monomials that contain an eliminated
//! unknown (`t_i` times a monomial in the remaining unknowns `u`), `m(u)` the others, and
//! `C`, `D` numbers (functions of the data). When `C` has dependent rows, or the
//! eliminated unknowns enter other equations non-linearly, the maximal minors of the
//! block's `[A(u) b(u)]` (`super::eliminate_linear`) are the wrong equations: the former
//! multiplies every `t`-free combination of rows by minors of `A` (a component of
//! spurious solutions where they vanish), the latter is not linear at all. Both are
//! handled from one nonsingular pivot block `C_PQ` (rows `P`, columns `Q`, chosen on an
//! instance mod p by [`block_reduction`]), without division, so that every ring and
//! every instance computes the same polynomials:
//!
//! - each row `i` outside `P` gives the `t`-free equation `det [[C_PQ, D_P m]; [C_iQ,
//!   D_i m]]` (the combination of rows that cancels `C`);
//! - [`BlockMode::Minors`] (`C` of rank `r` below its column count): the maximal minors
//!   of `[A b]` on the rows `P` only, the equations the worksheet gets by solving rows for
//!   `t` and substituting into another (`numer` of the result). As in the worksheet, whose
//!   reduced row echelon form clears the `t`-free rows' pivot monomials from the rows it
//!   then solves, the rows `P` are first reduced by the `t`-free combinations (their
//!   `b` loses those monomials; a multiple of `t`-free equations, so the minors change by
//!   members of the ideal only): the minors have far fewer terms;
//! - [`BlockMode::Substitute`] (`C` of full column rank, every `t_i` a column of its
//!   own): Cramer's rule `d y_j = g_j(u)` with `d = det C_PQ` solves every column, the
//!   columns `t_i` give `t_i = g_i / d`, which is substituted into the other equations
//!   (multiplied through by `d`'s power), and a column `t_i m'(u)` gives `m' g_i - g_j = 0`.
//!
//! The solver recovers `t` as before, from the null vector of the block's `[A(u) b(u)]`.

use super::{
    combinations, determinant, numbered, pivots_from_last, remaining_unknowns,
    substitute_quotients, EliminateError, Eliminated,
};
use crate::algebra::{Fp, Monomial, MonomialOrder, Poly, Ring};

/// How the block of equations linear in the eliminated unknowns is reduced (see the module
/// documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockMode {
    /// The `t`-free row combinations and the maximal minors of `[A b]` on the pivot rows.
    Minors,
    /// The `t`-free row combinations and Cramer's rule on the whole coefficient matrix,
    /// the eliminated unknowns substituted into the other equations.
    Substitute,
}

/// The plan of a block reduction, chosen on one instance mod p ([`block_reduction`]) and
/// applied alike over every ring ([`reduce_block`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlockReduction {
    /// The columns of `C`: the block's monomials (in all unknowns) that contain an
    /// eliminated unknown, in increasing order.
    pub columns: Vec<Monomial>,
    /// The pivot rows `P`, indices among the block's rows (the equations linear in the
    /// eliminated unknowns, in equation order).
    pub pivot_rows: Vec<usize>,
    /// The pivot columns `Q`, indices into [`BlockReduction::columns`].
    pub pivot_columns: Vec<usize>,
    /// Minors or substitution.
    pub mode: BlockMode,
    /// [`BlockMode::Minors`]: the pivot monomial of each `t`-free combination of rows (in
    /// the order they are produced, a monomial in the remaining unknowns; `None` for one
    /// that is a combination of those before it) in their fraction-free echelon form, by
    /// which the pivot rows' `t`-free parts are reduced before their minors are taken
    /// (see [`reduce_pivot_rows`]). Empty: the minors of the rows as they are.
    pub rest_pivots: Vec<Option<Monomial>>,
}

/// How each equation meets the eliminated unknowns.
enum Role {
    /// Free of them.
    Free,
    /// Of degree exactly one in them (a row of the block).
    Block,
    /// Of higher degree in them, and in other unknowns too.
    Other,
    /// In them alone (a normalisation such as `t't = 1`, or a constraint on them).
    OnlyEliminated,
}

fn role<C: Ring>(eq: &Poly<C>, elim: &[usize]) -> Role {
    let degree = |m: &Monomial| elim.iter().map(|&i| u32::from(m.0[i])).sum::<u32>();
    let top = eq.terms().map(|(m, _)| degree(m)).max().unwrap_or(0);
    let only_eliminated = eq.terms().all(|(m, _)| {
        m.0.iter()
            .enumerate()
            .all(|(i, &e)| e == 0 || elim.contains(&i))
    });
    match top {
        0 => Role::Free,
        _ if only_eliminated => Role::OnlyEliminated,
        1 => Role::Block,
        _ => Role::Other,
    }
}

/// Largest pivot block a block reduction takes: its determinants are expanded by Laplace
/// over every column subset (`2^r` minors), so a larger block falls back to the minors.
pub const MAX_BLOCK_PIVOTS: usize = 12;

/// Chooses the block reduction for eliminating `eliminated` (flat indices, increasing)
/// from `equations` (one instance mod p), or `None` where the maximal minors of the block
/// (`super::eliminate_linear`) are the right equations: the block's `C` has independent
/// rows or independent columns, and no other equation involves the eliminated unknowns;
/// also where the pivot block would exceed [`MAX_BLOCK_PIVOTS`].
pub fn block_reduction<const P: u32>(
    equations: &[Poly<Fp<P>>],
    eliminated: &[usize],
) -> Option<BlockReduction> {
    let block: Vec<&Poly<Fp<P>>> = equations
        .iter()
        .filter(|e| matches!(role(e, eliminated), Role::Block))
        .collect();
    let others = equations
        .iter()
        .any(|e| matches!(role(e, eliminated), Role::Other | Role::OnlyEliminated));
    let has_eliminated = |m: &Monomial| eliminated.iter().any(|&i| m.0[i] > 0);
    let mut columns: Vec<Monomial> = block
        .iter()
        .flat_map(|e| e.terms().map(|(m, _)| m.clone()))
        .filter(|m| has_eliminated(m))
        .collect();
    columns.sort();
    columns.dedup();
    let c = columns.len();
    let rows = block.iter().map(|e| {
        columns
            .iter()
            .map(|m| e.coeff(m).value())
            .collect::<Vec<u32>>()
    });
    let (independent, pivot_columns) = pivots_from_last::<P>(rows, c);
    let pivot_rows: Vec<usize> = (0..block.len()).filter(|&r| independent[r]).collect();
    let rank = pivot_rows.len();
    if rank > MAX_BLOCK_PIVOTS {
        return None;
    }
    let inhomogeneous = block
        .iter()
        .any(|e| e.terms().any(|(m, _)| !has_eliminated(m)));
    let pure = |i: usize| columns.iter().any(|m| m.degree() == 1 && m.0[i] == 1);
    let mode = if others {
        // Only substitution takes equations of higher degree in the eliminated unknowns.
        if rank == c && inhomogeneous && eliminated.iter().all(|&i| pure(i)) {
            BlockMode::Substitute
        } else {
            return None;
        }
    } else if rank < block.len() && rank < c {
        BlockMode::Minors
    } else {
        return None;
    };
    let mut plan = BlockReduction {
        columns,
        pivot_rows,
        pivot_columns,
        mode,
        rest_pivots: Vec::new(),
    };
    if mode == BlockMode::Minors {
        let nvars = block.first().map_or(0, |e| e.nvars());
        let t_free = reduce_block(equations, nvars, eliminated, &plan)
            .ok()
            .map(|e| t_free_rows(&e, equations, eliminated, &plan))
            .unwrap_or_default();
        plan.rest_pivots = choose_rest_pivots(&t_free);
    }
    Some(plan)
}

/// The `t`-free combinations of rows among the equations `e` produced (after the
/// equations free of the eliminated unknowns, see [`reduce_block`]).
fn t_free_rows<C: Ring>(
    e: &Eliminated<C>,
    equations: &[Poly<C>],
    eliminated: &[usize],
    plan: &BlockReduction,
) -> Vec<Poly<C>> {
    let free = equations
        .iter()
        .filter(|q| matches!(role(q, eliminated), Role::Free))
        .count();
    let block = equations
        .iter()
        .filter(|q| matches!(role(q, eliminated), Role::Block))
        .count();
    let n = block.saturating_sub(plan.pivot_rows.len());
    e.equations.iter().skip(free).take(n).cloned().collect()
}

/// The pivots of the fraction-free echelon form of `rows` ([`echelon_form`]): each row's
/// largest monomial (grevlex) once the pivots before it are eliminated, `None` for a row
/// that vanishes.
fn choose_rest_pivots<const P: u32>(rows: &[Poly<Fp<P>>]) -> Vec<Option<Monomial>> {
    echelon_form(rows, |_, t| {
        t.leading(MonomialOrder::Grevlex).map(|(m, _)| m.clone())
    })
    .into_iter()
    .map(|(_, p)| p)
    .collect()
}

/// The fraction-free echelon form of `rows`: each row reduced by the rows before it on
/// their pivots ([`echelon_step`]), then given its own pivot by `pivot(i, reduced row)`.
fn echelon_form<C: Ring>(
    rows: &[Poly<C>],
    mut pivot: impl FnMut(usize, &Poly<C>) -> Option<Monomial>,
) -> Vec<(Poly<C>, Option<Monomial>)> {
    let mut reduced: Vec<(Poly<C>, Option<Monomial>)> = Vec::with_capacity(rows.len());
    for (i, r) in rows.iter().enumerate() {
        let mut t = r.clone();
        for (prev, m) in &reduced {
            if let Some(m) = m {
                t = echelon_step(&t, prev, m);
            }
        }
        let p = pivot(i, &t);
        reduced.push((t, p));
    }
    reduced
}

/// One fraction-free elimination step: `p` times `by`'s coefficient on `m`, minus `by`
/// times `p`'s coefficient on `m`, with the term on `m` removed (its coefficient is zero;
/// removed explicitly so that a ring that does not see the cancellation, such as the
/// emitter's traced expressions, has the support the plan has).
fn echelon_step<C: Ring>(p: &Poly<C>, by: &Poly<C>, m: &Monomial) -> Poly<C> {
    let reduced = p.scale(&by.coeff(m)).sub(&by.scale(&p.coeff(m)));
    Poly::from_terms(
        reduced.nvars(),
        reduced
            .terms()
            .filter(|(t, _)| *t != m)
            .map(|(t, c)| (t.clone(), c.clone())),
    )
}

/// `m` with `n` exponents: unknowns added at the end with exponent 0, or removed from the
/// end where their exponents are 0 (`None` otherwise).
fn fit_monomial(m: &Monomial, n: usize) -> Option<Monomial> {
    let mut e = m.0.clone();
    if e.len() > n && e[n..].iter().any(|&x| x != 0) {
        return None;
    }
    e.resize(n, 0);
    Some(Monomial(e))
}

/// The pivot rows of `[A b]` with their `t`-free parts `b` reduced by the `t`-free
/// combinations `t_free` (brought to echelon form on the pivots `pivots` first): each
/// pivot monomial is eliminated from the column `b` fraction-free. Every step scales the
/// whole column by one number (the pivot's coefficient) and subtracts multiples of a
/// `t`-free equation, and a determinant is linear in a column: the minors become a
/// number times the minors before, minus multiples of `t`-free equations. `A` is left as
/// it is (scaling the rows instead would multiply the minors by the cube of it).
fn reduce_pivot_rows<C: Ring>(
    mut rows: Vec<Vec<Poly<C>>>,
    t_free: &[Poly<C>],
    pivots: &[Option<Monomial>],
) -> Vec<Vec<Poly<C>>> {
    let echelon = echelon_form(t_free, |i, _| pivots.get(i).cloned().flatten());
    for row in &mut rows {
        let Some(b) = row.last_mut() else { continue };
        for (by, m) in &echelon {
            if let Some(m) = m {
                *b = echelon_step(b, by, m);
            }
        }
    }
    rows
}

/// Eliminates the unknowns `eliminated` (flat indices) from `equations` (polynomials in
/// `nvars` unknowns) by the block reduction `plan` (see the module documentation). The
/// equations are, in order: those free of the eliminated unknowns, the others substituted
/// ([`BlockMode::Substitute`]), the `t`-free combinations of the rows outside the pivot
/// rows, then the minors of the pivot rows ([`BlockMode::Minors`]) or the columns'
/// consistency equations ([`BlockMode::Substitute`]).
pub fn reduce_block<C: Ring>(
    equations: &[Poly<C>],
    nvars: usize,
    eliminated: &[usize],
    plan: &BlockReduction,
) -> Result<Eliminated<C>, EliminateError> {
    let mut elim: Vec<usize> = eliminated.to_vec();
    elim.sort_unstable();
    elim.dedup();
    let remaining = remaining_unknowns(nvars, &elim)?;
    let k = elim.len();
    let nrem = remaining.len();
    let project = |m: &Monomial| Monomial(remaining.iter().map(|&i| m.0[i]).collect());
    let names = || numbered(&elim);
    let constant = |c: C| Poly::constant(nrem, c);

    let mut free = Vec::new();
    let mut others = Vec::new();
    let mut only_eliminated = Vec::new();
    // Per block row: its entries of C, its t-free part D m(u), and its row of [A b].
    let mut coefficients: Vec<Vec<C>> = Vec::new();
    let mut rests: Vec<Poly<C>> = Vec::new();
    let mut matrix: Vec<Vec<Poly<C>>> = Vec::new();
    for (idx, eq) in equations.iter().enumerate() {
        match role(eq, &elim) {
            Role::Free => free.push(Poly::from_terms(
                nrem,
                eq.terms().map(|(m, c)| (project(m), c.clone())),
            )),
            Role::Other | Role::OnlyEliminated if plan.mode == BlockMode::Substitute => {
                others.push(eq)
            }
            Role::OnlyEliminated => only_eliminated.push(idx),
            Role::Other => {
                return Err(EliminateError::NotLinear {
                    equation: idx,
                    names: names(),
                })
            }
            Role::Block => {
                let mut row = vec![Poly::zero(nrem); k + 1];
                for (m, c) in eq.terms() {
                    let j = elim.iter().position(|&i| m.0[i] == 1).unwrap_or(k);
                    row[j].add_term(project(m), c.clone());
                    if j < k && plan.columns.binary_search(m).is_err() {
                        return Err(EliminateError::BlockColumn { equation: idx });
                    }
                }
                coefficients.push(plan.columns.iter().map(|m| eq.coeff(m)).collect());
                rests.push(row[k].clone());
                matrix.push(row);
            }
        }
    }
    let rank = plan.pivot_rows.len();
    if plan.pivot_rows.iter().any(|&r| r >= matrix.len())
        || plan.pivot_columns.len() != rank
        || plan.pivot_columns.iter().any(|&j| j >= plan.columns.len())
    {
        return Err(EliminateError::TooFewRows {
            rows: matrix.len(),
            k,
            needed: rank,
        });
    }
    let inhomogeneous = matrix.iter().any(|row| !row[k].is_zero());
    if inhomogeneous {
        if let Some(&equation) = only_eliminated.first() {
            return Err(EliminateError::ConstraintOnEliminated {
                equation,
                names: names(),
            });
        }
    }
    // The pivot block C_PQ bordered by row `extra`, with a last column of t-free parts.
    let bordered = |extra: usize| -> Vec<Vec<Poly<C>>> {
        plan.pivot_rows
            .iter()
            .chain([&extra])
            .map(|&r| {
                let mut row: Vec<Poly<C>> = plan
                    .pivot_columns
                    .iter()
                    .map(|&j| constant(coefficients[r][j].clone()))
                    .collect();
                row.push(rests[r].clone());
                row
            })
            .collect()
    };
    let t_free: Vec<Poly<C>> = (0..matrix.len())
        .filter(|r| !plan.pivot_rows.contains(r))
        .map(|r| determinant(&bordered(r), nrem))
        .collect();
    let mut out = free;
    let mut tail = Vec::new();
    match plan.mode {
        BlockMode::Minors => {
            let cols = k + usize::from(inhomogeneous);
            if rank < cols {
                return Err(EliminateError::TooFewRows {
                    rows: rank,
                    k,
                    needed: cols,
                });
            }
            let pivot_rows: Vec<Vec<Poly<C>>> = plan
                .pivot_rows
                .iter()
                .map(|&r| matrix[r][..cols].to_vec())
                .collect();
            // The pivots in this system's remaining unknowns: a `nonzero`'s hidden unknowns,
            // when the plan was made without them or they are dropped, come last.
            let rest_pivots: Option<Vec<Option<Monomial>>> = plan
                .rest_pivots
                .iter()
                .map(|p| match p {
                    None => Some(None),
                    Some(m) => fit_monomial(m, nrem).map(Some),
                })
                .collect();
            // Without a `t`-free part there is nothing to reduce.
            let pivot_rows = match rest_pivots {
                Some(pivots) if inhomogeneous && pivots.len() == t_free.len() => {
                    reduce_pivot_rows(pivot_rows, &t_free, &pivots)
                }
                _ => pivot_rows,
            };
            for rows in combinations(rank, cols) {
                let sub: Vec<Vec<Poly<C>>> = rows.iter().map(|&r| pivot_rows[r].clone()).collect();
                tail.push(determinant(&sub, nrem));
            }
        }
        BlockMode::Substitute => {
            if !inhomogeneous || rank != plan.columns.len() {
                return Err(EliminateError::TooFewRows {
                    rows: rank,
                    k,
                    needed: plan.columns.len(),
                });
            }
            // Cramer's rule on C_PQ y = -D_P m: d y_j = g_j.
            let square = |replace: Option<usize>| -> Vec<Vec<Poly<C>>> {
                plan.pivot_rows
                    .iter()
                    .map(|&r| {
                        plan.pivot_columns
                            .iter()
                            .map(|&j| match replace {
                                Some(q) if q == j => rests[r].neg(),
                                _ => constant(coefficients[r][j].clone()),
                            })
                            .collect()
                    })
                    .collect()
            };
            let d = determinant(&square(None), nrem);
            let g: Vec<Poly<C>> = (0..plan.columns.len())
                .map(|j| determinant(&square(Some(j)), nrem))
                .collect();
            // The column of each eliminated unknown alone.
            let mut solved = Vec::with_capacity(k);
            for &t in &elim {
                let Some(j) = plan
                    .columns
                    .iter()
                    .position(|m| m.degree() == 1 && m.0[t] == 1)
                else {
                    return Err(EliminateError::NotLinear {
                        equation: 0,
                        names: names(),
                    });
                };
                solved.push(j);
            }
            let images: Vec<&Poly<C>> = solved.iter().map(|&j| &g[j]).collect();
            for eq in others {
                out.push(substitute_quotients(eq, &elim, &images, &d, &remaining));
            }
            for (j, m) in plan.columns.iter().enumerate() {
                if solved.contains(&j) {
                    continue;
                }
                let i = elim
                    .iter()
                    .position(|&t| m.0[t] == 1)
                    .expect("a column has an eliminated unknown");
                let cofactor = Poly::from_terms(nrem, [(project(m), C::one())]);
                tail.push(cofactor.mul(&g[solved[i]]).sub(&g[j]));
            }
        }
    }
    out.extend(t_free);
    out.extend(tail);
    if !inhomogeneous {
        for row in &mut matrix {
            row.pop();
        }
    }
    Ok(Eliminated {
        equations: out,
        remaining,
        eliminated: elim,
        coefficient_matrix: matrix,
        inhomogeneous,
        dropped: only_eliminated,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::P1;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    type F = Fp<P1>;

    fn random(rng: &mut ChaCha8Rng) -> F {
        F::new(rng.gen_range(1..1_000_000))
    }

    /// A random polynomial in `nvars` unknowns with the given monomials.
    fn poly(rng: &mut ChaCha8Rng, nvars: usize, monomials: &[Vec<u16>]) -> Poly<F> {
        Poly::from_terms(
            nvars,
            monomials.iter().map(|m| (Monomial(m.clone()), random(rng))),
        )
    }

    /// `p - p(point)`: vanishes at `point`.
    fn through(p: Poly<F>, point: &[F]) -> Poly<F> {
        let at = p.eval(point);
        p.sub(&Poly::constant(p.nvars(), at))
    }

    /// Unknowns (v, w, x, y): four rows `sum_j X_kj g_j(v, w, x, y) + h_k(x, y)`, with
    /// three polynomials `g_j` linear in (v, w), so that the block's coefficient matrix has
    /// rank three; every row vanishes at `point`.
    fn dependent_rows(rng: &mut ChaCha8Rng, point: &[F]) -> Vec<Poly<F>> {
        let linear = [
            vec![1, 0, 0, 0],
            vec![1, 0, 1, 0],
            vec![0, 1, 0, 1],
            vec![0, 1, 1, 1],
        ];
        let g: Vec<Poly<F>> = (0..3).map(|_| poly(rng, 4, &linear)).collect();
        let quadratic = [
            vec![0, 0, 2, 0],
            vec![0, 0, 1, 1],
            vec![0, 0, 0, 1],
            vec![0, 0, 0, 0],
        ];
        (0..4)
            .map(|_| {
                let mut row = poly(rng, 4, &quadratic);
                for gj in &g {
                    row = row.add(&gj.scale(&random(rng)));
                }
                through(row, point)
            })
            .collect()
    }

    #[test]
    fn dependent_rows_give_equations_free_of_the_eliminated_unknowns() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let point: Vec<F> = (0..4).map(|_| random(&mut rng)).collect();
        let eqs = dependent_rows(&mut rng, &point);
        let plan = block_reduction(&eqs, &[0, 1]).expect("rank three of four rows");
        assert_eq!(plan.mode, BlockMode::Minors);
        assert_eq!((plan.columns.len(), plan.pivot_rows.len()), (4, 3));
        let e = reduce_block(&eqs, 4, &[0, 1], &plan).unwrap();
        // One combination of rows free of (v, w), one minor of the three pivot rows.
        assert_eq!(e.equations.len(), 2);
        assert_eq!(e.remaining, vec![2, 3]);
        for eq in &e.equations {
            assert_eq!(eq.nvars(), 2);
            assert!(!eq.is_zero());
            assert!(eq.eval(&point[2..]).is_zero());
        }
        // The solver's null vector: [A b] at (x, y) annihilates (v, w, 1).
        for row in &e.coefficient_matrix {
            let at: Vec<F> = row.iter().map(|p| p.eval(&point[2..])).collect();
            assert!((at[0] * point[0] + at[1] * point[1] + at[2]).is_zero());
        }
        // Independent rows: the block's minors are the right equations, no reduction.
        assert!(block_reduction(&eqs[..2], &[0, 1]).is_none());
    }

    #[test]
    fn pivot_rows_lose_the_t_free_pivot_monomials_and_keep_the_solution() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let point: Vec<F> = (0..4).map(|_| random(&mut rng)).collect();
        let eqs = dependent_rows(&mut rng, &point);
        let plan = block_reduction(&eqs, &[0, 1]).expect("rank three of four rows");
        assert_eq!(plan.rest_pivots.len(), 1);
        let pivot = plan.rest_pivots[0].clone().expect("a non-zero t-free row");
        let e = reduce_block(&eqs, 4, &[0, 1], &plan).unwrap();
        let rows: Vec<Vec<Poly<F>>> = plan
            .pivot_rows
            .iter()
            .map(|&r| e.coefficient_matrix[r].clone())
            .collect();
        let reduced = reduce_pivot_rows(rows.clone(), &e.equations[..1], &plan.rest_pivots);
        for (before, after) in rows.iter().zip(&reduced) {
            assert!(!before[2].coeff(&pivot).is_zero());
            assert!(after[2].coeff(&pivot).is_zero());
            assert_eq!(before[..2], after[..2]);
        }
        // The minor of the reduced rows is the equation the plan gives, and vanishes at
        // the solution.
        let minor = determinant(&reduced, 2);
        assert_eq!(e.equations[1], minor);
        assert!(minor.eval(&point[2..]).is_zero());
        let plain = BlockReduction {
            rest_pivots: Vec::new(),
            ..plan.clone()
        };
        let unreduced = reduce_block(&eqs, 4, &[0, 1], &plain).unwrap();
        assert_ne!(unreduced.equations[1], minor);
        assert!(unreduced.equations[1].eval(&point[2..]).is_zero());
    }

    #[test]
    fn substitution_solves_the_columns_and_substitutes_into_the_others() {
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        // Unknowns (t, x, y): rows in the columns t x, t; an equation quadratic in t.
        let point: Vec<F> = (0..3).map(|_| random(&mut rng)).collect();
        let columns = [
            vec![1, 1, 0],
            vec![1, 0, 0],
            vec![0, 2, 0],
            vec![0, 0, 1],
            vec![0, 0, 0],
        ];
        let mut eqs: Vec<Poly<F>> = (0..2)
            .map(|_| through(poly(&mut rng, 3, &columns), &point))
            .collect();
        let outer = [vec![2, 0, 0], vec![1, 1, 1], vec![0, 1, 1], vec![0, 0, 0]];
        eqs.push(through(poly(&mut rng, 3, &outer), &point));
        assert!(crate::eliminate::eliminate_linear(&eqs, 3, &[0]).is_err());
        let plan = block_reduction(&eqs, &[0]).expect("substitution");
        assert_eq!(plan.mode, BlockMode::Substitute);
        let e = reduce_block(&eqs, 3, &[0], &plan).unwrap();
        // The outer equation substituted and the consistency of the column t x.
        assert_eq!(e.equations.len(), 2);
        for eq in &e.equations {
            assert!(!eq.is_zero());
            assert!(eq.eval(&point[1..]).is_zero());
        }
        // t itself is the null vector of the block's [A b] at (x, y), over its last entry.
        for row in &e.coefficient_matrix {
            let at: Vec<F> = row.iter().map(|p| p.eval(&point[1..])).collect();
            assert!((at[0] * point[0] + at[1]).is_zero());
        }
    }
}
