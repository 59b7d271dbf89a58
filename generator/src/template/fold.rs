//! The Schur complement of the template rows whose pivots are constants: a block the
//! generator inverts exactly, then rows pivoting in a triangle.
//!
//! A multiple of an equation with numeric coefficients on some monomials (`u² + v² + w² +
//! s² - 1` with data `s`, the entries of `R Rᵀ - I`) has the same entries there on every
//! instance. Let `k` rows and `k` independent excess columns form an invertible block
//! `M11` whose determinant is such a number: ordered first, the filled template is
//! `[M11 M12; M21 M22]`, and eliminating it reduces the rows of `M22 - M21 M11⁻¹ M12`
//! exactly as the whole template's elimination would (block elimination: the pivots of the
//! first `k` columns come from the folded rows), on every instance. This is the reduction
//! Martyushev, Vrablikova and Pajdla's solvers apply to the multiples of their
//! `schur_pols` before the elimination, and sizes are counted after it, like theirs.
//!
//! `M11` has two parts, `[[C, 0], [X, L]]`:
//! - `C`, a block whose entries are all numbers, inverted by the generator in rational
//!   arithmetic (`mingen_runtime::fold_constant_rows` forms its complement). Rows are taken
//!   greedily: a row joins when its entries in the chosen columns are constants and it has
//!   a constant entry in a new independent excess column where the rows already chosen
//!   are constant too, such that the block stays invertible; of several such columns the
//!   one with the largest pivot (the new Schur scalar) wins, the earliest on ties, so that
//!   the inverse stays small. The bordered inverse is updated exactly at each step.
//! - `L`, lower triangular with constant diagonal, and `X` anything (data included): each
//!   pivot row has a constant entry in a column that no row folded before it touches
//!   (`mingen_runtime::fold_triangular_rows` eliminates by forward substitution). For
//!   multiples `m f` of equations with a constant coefficient on a monomial `x`, taken by
//!   increasing `m x` in a monomial order and pivoting on `m x`, this is the triangle of
//!   leading terms; rows are taken greedily under several column orders (the template's,
//!   graded and lexicographic ones with each variable first), the most rows winning.
//!
//! `C` followed by pivot rows (none, or some), and pivot rows alone are tried; the most
//! rows folded win. That choice (which row order grows `C`, and whether `C` is kept) is
//! made in Z_p, where it costs little; only the chosen `C` is then grown again in rational
//! arithmetic, whose entries grow with the block (hundreds of rows take seconds each).

use super::EliminationTemplate;
use crate::algebra::{Field, Fp, Monomial, Ring, P1, Q};
use num_traits::Signed;
use std::collections::{BTreeMap, HashMap};

/// A template's fold: the constant block's inverse `C⁻¹` in the layout of
/// `mingen_runtime::ConstantFold` (see there; row `p` for the folded column `p`, its
/// column indices the folded rows'), then the pivot rows' inverse pivots
/// (`mingen_runtime::TriangularFold`).
#[derive(Clone, Debug, PartialEq)]
pub struct ConstantFold {
    /// The number of rows (and columns) of the constant block, `k`.
    pub rows: usize,
    /// Offsets into `inv_cols` and `inv_vals`, one per row of `M11⁻¹` plus the end.
    pub inv_start: Vec<u32>,
    /// The column of each non-zero of `M11⁻¹`.
    pub inv_cols: Vec<u16>,
    /// The non-zeros of `M11⁻¹` (the nearest doubles to the exact values).
    pub inv_vals: Vec<f64>,
    /// Offsets into `m12_cols`, one per folded row plus the end.
    pub m12_start: Vec<u32>,
    /// The eliminated matrix's columns where each folded row may be non-zero.
    pub m12_cols: Vec<u16>,
    /// Multiply-adds of forming the complement (a bound from the template's structure).
    pub updates: usize,
    /// The inverse pivots of the rows folded after the constant block, in order: row
    /// `rows + i` has the constant pivot `1 / pivot_inv[i]` in column `rows + i`, and no
    /// folded row before it has an entry there (see [`mingen_runtime::TriangularFold`]).
    pub pivot_inv: Vec<f64>,
}

impl Eq for ConstantFold {}

impl ConstantFold {
    /// The plan the runtime executes, for template `t` (the template it was computed for).
    pub fn as_plan<'a>(&'a self, t: &EliminationTemplate) -> mingen_runtime::ConstantFold<'a> {
        let (rows, cols) = t.filled_size();
        mingen_runtime::ConstantFold {
            rows: rows - self.rows,
            folded: self.rows,
            cols: cols - self.rows,
            inv_start: &self.inv_start,
            inv_cols: &self.inv_cols,
            inv_vals: &self.inv_vals,
            m12_start: &self.m12_start,
            m12_cols: &self.m12_cols,
        }
    }

    /// The plan of the pivot rows' fold, after the constant block's (see
    /// [`mingen_runtime::TriangularFold`]).
    pub fn as_triangular_plan<'a>(
        &'a self,
        t: &EliminationTemplate,
    ) -> mingen_runtime::TriangularFold<'a> {
        let (rows, cols) = t.eliminated_size();
        mingen_runtime::TriangularFold {
            rows,
            folded: self.pivot_inv.len(),
            cols,
            pivot_inv: &self.pivot_inv,
        }
    }
}

/// One template equation's terms: the exact coefficient where it is a number, `None` where
/// it depends on the data.
pub type EquationConstants = Vec<(Monomial, Option<Q>)>;

/// The largest constant block: beyond it the exact inverse's cost grows past what the fold
/// saves.
const MAX_FOLDED: usize = 512;

/// The most pivot rows folded after the constant block (the plan's 16-bit indices).
const MAX_PIVOT_ROWS: usize = 4096;

/// A row's entries by template column: the value where it is a number, `None` where it
/// depends on the data.
type Entries<F> = BTreeMap<usize, Option<F>>;

/// The constant block chosen greedily, rows taken in `order` (see the module
/// documentation): the rows with their entries by template column, the columns, and the
/// block's exact inverse (`inv[p][f]`: rows by chosen column, columns by chosen row).
/// `better(s, best)`: whether the Schur scalar `s` makes a better pivot than `best`.
fn choose_block<F: Field>(
    t: &EliminationTemplate,
    entries: &[Option<Entries<F>>],
    order: &[usize],
    better: fn(&F, &F) -> bool,
) -> Block<F> {
    let independent_excess = t.n_excess - t.n_dependent;
    let zero = F::zero();
    let mut rows: Vec<(usize, Entries<F>)> = Vec::new();
    let mut cols: Vec<usize> = Vec::new();
    let mut inv: Vec<Vec<F>> = Vec::new();
    for &i in order {
        if rows.len() >= MAX_FOLDED {
            break;
        }
        // A row with a term outside the template's columns is never folded.
        let Some(Some(entries)) = entries.get(i) else {
            continue;
        };
        // The row's entries in the chosen columns must be numbers.
        let a: Option<Vec<F>> = cols
            .iter()
            .map(|c| match entries.get(c) {
                None => Some(zero.clone()),
                Some(q) => q.clone(),
            })
            .collect();
        let Some(a) = a else {
            continue;
        };
        // a M11⁻¹ (1 x k), shared by every candidate column.
        let a_inv: Vec<F> = (0..rows.len())
            .map(|f| {
                a.iter()
                    .zip(&inv)
                    .fold(zero.clone(), |s, (x, r)| s.add(&x.mul(&r[f])))
            })
            .collect();
        let mut best: Option<(usize, F, Vec<F>)> = None;
        for (&c, d) in entries {
            let Some(d) = d else { continue };
            if c >= independent_excess || cols.contains(&c) || d.is_zero() {
                continue;
            }
            // The chosen rows' entries in column c must be numbers too.
            let b: Option<Vec<F>> = rows
                .iter()
                .map(|(_, e)| match e.get(&c) {
                    None => Some(zero.clone()),
                    Some(q) => q.clone(),
                })
                .collect();
            let Some(b) = b else { continue };
            let s = a_inv
                .iter()
                .zip(&b)
                .fold(d.clone(), |s, (x, y)| s.sub(&x.mul(y)));
            if s.is_zero() {
                continue;
            }
            if best.as_ref().map_or(true, |(_, bs, _)| better(&s, bs)) {
                best = Some((c, s, b));
            }
        }
        let Some((c, s, b)) = best else {
            continue;
        };
        // Bordered inverse: [[A⁻¹ + A⁻¹b s⁻¹ a A⁻¹, -A⁻¹b s⁻¹], [-s⁻¹ a A⁻¹, s⁻¹]].
        let inv_b: Vec<F> = inv
            .iter()
            .map(|r| {
                r.iter()
                    .zip(&b)
                    .fold(zero.clone(), |s, (x, y)| s.add(&x.mul(y)))
            })
            .collect();
        let Some(s_inv) = s.inv() else { continue };
        for (p, r) in inv.iter_mut().enumerate() {
            let u = inv_b[p].mul(&s_inv);
            for (f, x) in r.iter_mut().enumerate() {
                *x = x.add(&u.mul(&a_inv[f]));
            }
            r.push(u.neg());
        }
        let mut last: Vec<F> = a_inv.iter().map(|x| x.mul(&s_inv).neg()).collect();
        last.push(s_inv);
        inv.push(last);
        rows.push((i, entries.clone()));
        cols.push(c);
    }
    (rows, cols, inv)
}

/// See [`choose_block`].
type Block<F> = (Vec<(usize, Entries<F>)>, Vec<usize>, Vec<Vec<F>>);

/// A row after the constant block whose pivot is a constant in a column no earlier folded
/// row touches: the folded block stays lower triangular below the constant one.
#[derive(Clone, Debug)]
struct PivotRow<F> {
    row: usize,
    col: usize,
    pivot: F,
}

/// Each template row's entries by template column (`None`: the row has a term outside the
/// template's columns, which does not happen for a built template), in the field `F`
/// (a number without an image in `F` counts as data).
fn row_entries<F: Field>(
    t: &EliminationTemplate,
    equations: &[EquationConstants],
) -> Vec<Option<Entries<F>>> {
    let column_of: HashMap<&Monomial, usize> =
        t.columns.iter().enumerate().map(|(i, m)| (m, i)).collect();
    t.rows
        .iter()
        .map(|row| {
            equations
                .get(row.equation)?
                .iter()
                .map(|(m, q)| {
                    let c = *column_of.get(&row.multiplier.mul(m))?;
                    Some((c, q.as_ref().and_then(F::from_rational)))
                })
                .collect()
        })
        .collect()
}

/// Column rankings (lower ranks first) the pivot rows are chosen under: the template's
/// column order, its reverse, and per variable a graded order and a lexicographic one with
/// that variable first. Each is a monomial order's view of the columns, under which rows
/// processed by increasing leading column and pivoting on it form a triangle.
fn column_rankings(t: &EliminationTemplate) -> Vec<Vec<usize>> {
    let n = t.columns.len();
    let rank_of = |order: Vec<usize>| {
        let mut rank = vec![0; n];
        order.iter().enumerate().for_each(|(r, &c)| rank[c] = r);
        rank
    };
    let mut rankings = vec![rank_of((0..n).collect()), rank_of((0..n).rev().collect())];
    for v in 0..t.nvars {
        let exp = |c: usize| t.columns[c].0[v];
        let mut graded: Vec<usize> = (0..n).collect();
        graded.sort_by_key(|&c| {
            (
                std::cmp::Reverse(t.columns[c].degree()),
                std::cmp::Reverse(exp(c)),
                c,
            )
        });
        rankings.push(rank_of(graded));
        let mut lex: Vec<usize> = (0..n).collect();
        lex.sort_by_key(|&c| {
            (
                std::cmp::Reverse(exp(c)),
                std::cmp::Reverse(t.columns[c].degree()),
                c,
            )
        });
        rankings.push(rank_of(lex));
    }
    rankings
}

/// The pivot rows chosen greedily after `block` under `rank`: rows by decreasing rank of
/// their leading column (the earliest-ranked one they touch), each taking the
/// earliest-ranked independent excess column where its entry is a non-zero constant and
/// no row folded so far (the block's included) has an entry.
fn choose_pivot_rows<F: Field>(
    t: &EliminationTemplate,
    entries: &[Option<Entries<F>>],
    block: &Block<F>,
    rank: &[usize],
) -> Vec<PivotRow<F>> {
    let independent_excess = t.n_excess - t.n_dependent;
    let mut touched = vec![false; t.columns.len()];
    let mut used = vec![false; t.rows.len()];
    for (r, e) in &block.0 {
        used[*r] = true;
        e.keys().for_each(|&c| touched[c] = true);
    }
    block.1.iter().for_each(|&c| touched[c] = true);
    let mut order: Vec<(usize, usize)> = entries
        .iter()
        .enumerate()
        .filter(|(i, _)| !used[*i])
        .filter_map(|(i, e)| Some((e.as_ref()?.keys().map(|&c| rank[c]).min()?, i)))
        .collect();
    order.sort_by_key(|&(lead, i)| (std::cmp::Reverse(lead), i));
    let mut pivots = Vec::new();
    for (_, i) in order {
        if pivots.len() >= MAX_PIVOT_ROWS {
            break;
        }
        let Some(e) = &entries[i] else { continue };
        let best = e
            .iter()
            .filter(|(&c, q)| {
                c < independent_excess && !touched[c] && q.as_ref().is_some_and(|q| !q.is_zero())
            })
            .min_by_key(|(&c, _)| rank[c]);
        let Some((&col, Some(pivot))) = best else {
            continue;
        };
        pivots.push(PivotRow {
            row: i,
            col,
            pivot: pivot.clone(),
        });
        e.keys().for_each(|&c| touched[c] = true);
    }
    pivots
}

/// The row orders a constant block is grown under: the template's, its reverse, and by
/// multiplier degree (highest, then lowest first).
fn block_orders(t: &EliminationTemplate) -> [Vec<usize>; 4] {
    let n = t.rows.len();
    let by_degree = |high: bool| {
        let mut o: Vec<usize> = (0..n).collect();
        o.sort_by_key(|&i| {
            let d = t.rows[i].multiplier.degree();
            if high {
                std::cmp::Reverse(d)
            } else {
                std::cmp::Reverse(u32::MAX - d)
            }
        });
        o
    };
    [
        (0..n).collect::<Vec<_>>(),
        (0..n).rev().collect(),
        by_degree(true),
        by_degree(false),
    ]
}

/// The fold's structure, chosen in Z_p (see the module documentation): which row order of
/// [`block_orders`] grows the largest constant block (the earlier on ties), and whether
/// that block is kept (`Some(order)`) or the pivot rows alone fold more (`None`). Exact
/// arithmetic is then spent on the chosen block only: its rational inverse is what costs,
/// and a block of hundreds of rows takes many seconds in `Q`.
fn choose_structure(
    t: &EliminationTemplate,
    entries: &[Option<Entries<Fp<P1>>>],
) -> (Option<usize>, usize) {
    let (order, block) = block_orders(t)
        .iter()
        .map(|o| choose_block(t, entries, o, |_, _| false))
        .enumerate()
        .reduce(|best, b| {
            if b.1 .0.len() > best.1 .0.len() {
                b
            } else {
                best
            }
        })
        .unwrap_or_default();
    let with_block = block.0.len() + best_pivot_rows(t, entries, &block).len();
    let without = best_pivot_rows(t, entries, &Block::default()).len();
    // The block first on ties.
    if with_block >= without {
        (Some(order), with_block)
    } else {
        (None, without)
    }
}

/// The most pivot rows after `block` under any of [`column_rankings`] (the earlier
/// ranking on ties).
fn best_pivot_rows<F: Field>(
    t: &EliminationTemplate,
    entries: &[Option<Entries<F>>],
    block: &Block<F>,
) -> Vec<PivotRow<F>> {
    column_rankings(t)
        .iter()
        .map(|r| choose_pivot_rows(t, entries, block, r))
        .reduce(|best, p| if p.len() > best.len() { p } else { best })
        .unwrap_or_default()
}

/// How many rows [`fold_constant_rows`] would fold from `t`, counted in Z_p (no exact
/// inverse: cheap enough for every template of a search).
pub fn foldable_rows(t: &EliminationTemplate, equations: &[EquationConstants]) -> usize {
    if t.reduction.is_some() || t.shift.is_some() || equations.is_empty() {
        return 0;
    }
    choose_structure(t, &row_entries::<Fp<P1>>(t, equations)).1
}

/// Folds what `t` allows (see the module documentation): `equations[e]` are the terms of
/// template equation `e`. The template's rows and independent excess columns are reordered
/// (folded rows and their columns first: the constant block, then the pivot rows) and
/// `t.fold` set; `t` is left as it is when nothing folds, or when its rows are multiples
/// of equations row-reduced on the data.
pub fn fold_constant_rows(t: &mut EliminationTemplate, equations: &[EquationConstants]) {
    t.fold = None;
    // A shifted template's entries are combinations of its equations' coefficients, which
    // the constants below do not describe.
    if t.reduction.is_some() || t.shift.is_some() || equations.is_empty() {
        return;
    }
    let (order, _) = choose_structure(t, &row_entries::<Fp<P1>>(t, equations));
    let entries = row_entries::<Q>(t, equations);
    // The chosen block exactly, each row pivoting on its largest exact Schur scalar.
    let block = match order {
        Some(o) => choose_block(t, &entries, &block_orders(t)[o], |s, best| {
            s.abs() > best.abs()
        }),
        None => Block::default(),
    };
    let pivots = best_pivot_rows(t, &entries, &block);
    let (rows, cols, inv) = block;
    let k = rows.len();
    if k + pivots.len() == 0 {
        return;
    }
    let mut fold = ConstantFold {
        rows: k,
        inv_start: vec![0],
        inv_cols: Vec::new(),
        inv_vals: Vec::new(),
        m12_start: vec![0],
        m12_cols: Vec::new(),
        updates: 0,
        pivot_inv: Vec::new(),
    };
    for r in &inv {
        for (f, x) in r.iter().enumerate() {
            if Ring::is_zero(x) {
                continue;
            }
            let v = <f64 as Ring>::from_rational(x).unwrap_or(f64::NAN);
            if !v.is_finite() {
                return;
            }
            fold.inv_cols.push(f as u16);
            fold.inv_vals.push(v);
        }
        fold.inv_start.push(fold.inv_cols.len() as u32);
    }
    for p in &pivots {
        let v = <f64 as Ring>::from_rational(&(<Q as Ring>::one() / &p.pivot)).unwrap_or(f64::NAN);
        if !v.is_finite() || v == 0.0 {
            return;
        }
        fold.pivot_inv.push(v);
    }
    // Folded rows first (the block's, then the pivot rows, in the order chosen), then the
    // others; the folded columns first in the same order.
    let folded_rows: Vec<usize> = rows
        .iter()
        .map(|r| r.0)
        .chain(pivots.iter().map(|p| p.row))
        .collect();
    let folded_cols: Vec<usize> = cols
        .iter()
        .copied()
        .chain(pivots.iter().map(|p| p.col))
        .collect();
    let row_order = with_first(&folded_rows, t.rows.len());
    let col_order = with_first(&folded_cols, t.columns.len());
    t.rows = row_order.iter().map(|&r| t.rows[r].clone()).collect();
    t.columns = col_order.iter().map(|&c| t.columns[c].clone()).collect();
    t.sparse = None;
    t.unrolled = None;
    t.fold = Some(fold.clone());
    if t.eliminated_size().1 + pivots.len() > usize::from(u16::MAX) {
        t.fold = None;
        return;
    }
    // The filled columns of each row, and the multiply-adds: per other row,
    // `M21[i, :] M11⁻¹` over its non-zeros, then `t M12` over the folded rows' patterns.
    // `M12`'s columns are those of the constant block's complement (the pivot rows'
    // columns first).
    let column_of: HashMap<&Monomial, usize> =
        t.columns.iter().enumerate().map(|(i, m)| (m, i)).collect();
    let pattern = |i: usize| -> Vec<usize> {
        let row = &t.rows[i];
        let mut cs: Vec<usize> = equations
            .get(row.equation)
            .into_iter()
            .flatten()
            .filter_map(|(m, _)| column_of.get(&row.multiplier.mul(m)))
            .filter_map(|&c| t.filled_column(c))
            .collect();
        cs.sort_unstable();
        cs
    };
    for q in 0..k {
        fold.m12_cols.extend(
            pattern(q)
                .into_iter()
                .filter(|&c| c >= k)
                .map(|c| (c - k) as u16),
        );
        fold.m12_start.push(fold.m12_cols.len() as u32);
    }
    let m12_nnz = |q: usize| (fold.m12_start[q + 1] - fold.m12_start[q]) as usize;
    let m12_total: usize = (0..k).map(m12_nnz).sum();
    for i in k..t.rows.len() {
        let inv_nnz: usize = pattern(i)
            .into_iter()
            .filter(|&c| c < k)
            .map(|p| (fold.inv_start[p + 1] - fold.inv_start[p]) as usize)
            .sum();
        if inv_nnz > 0 {
            fold.updates += inv_nnz + m12_total;
        }
    }
    t.fold = Some(fold);
}

/// `first`, then `0..n` without them, in order.
fn with_first(first: &[usize], n: usize) -> Vec<usize> {
    let mut taken = vec![false; n];
    first.iter().for_each(|&i| taken[i] = true);
    first
        .iter()
        .copied()
        .chain((0..n).filter(|&i| !taken[i]))
        .collect()
}
