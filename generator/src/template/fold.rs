//! The Schur complement of the template rows whose pivot block is constant, taken with an
//! inverse the generator computes exactly.
//!
//! A multiple of an equation with numeric coefficients on some monomials (`u² + v² + w² +
//! s² - 1` with data `s`, the entries of `R Rᵀ - I`) has the same entries there on every
//! instance. Let `k` such rows and `k` independent excess columns form a constant,
//! invertible block `M11`: ordered first, the filled template is `[M11 M12; M21 M22]`, and
//! eliminating it reduces the rows of `M22 - M21 M11⁻¹ M12` exactly as the whole
//! template's elimination would (block elimination: the pivots of the first `k` columns
//! come from the folded rows). The generator computes `M11⁻¹` in rational arithmetic; the
//! solver fills the template, forms the complement (`mingen_runtime::fold_constant_rows`)
//! and eliminates a matrix `k` rows and columns smaller. This is the reduction
//! Martyushev, Vrablikova and Pajdla's solvers apply to the multiples of their
//! `schur_pols` before the elimination.
//!
//! Rows are taken greedily in template order: a row joins when its entries in the chosen
//! columns are constants and it has a constant entry in a new independent excess column
//! where the rows already chosen are constant too, such that the block stays invertible;
//! of several such columns the one with the largest pivot (the new Schur scalar) wins, the
//! earliest on ties, so that the inverse stays small. The bordered inverse is updated
//! exactly at each step.

use super::EliminationTemplate;
use crate::algebra::{Monomial, Ring, Q};
use num_traits::Signed;
use std::collections::{BTreeMap, HashMap};

/// The constant inverse `M11⁻¹` of a template's folded block in the layout of
/// `mingen_runtime::ConstantFold` (see there): row `p` for the folded column `p`, its
/// column indices the folded rows'.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstantFold {
    /// The number of rows (and columns) folded, `k`.
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
}

impl Eq for ConstantFold {}

impl ConstantFold {
    /// The plan the runtime executes, for template `t` (the template it was computed for).
    pub fn as_plan<'a>(&'a self, t: &EliminationTemplate) -> mingen_runtime::ConstantFold<'a> {
        let (rows, cols) = t.eliminated_size();
        mingen_runtime::ConstantFold {
            rows,
            folded: self.rows,
            cols,
            inv_start: &self.inv_start,
            inv_cols: &self.inv_cols,
            inv_vals: &self.inv_vals,
            m12_start: &self.m12_start,
            m12_cols: &self.m12_cols,
        }
    }
}

/// One template equation's terms: the exact coefficient where it is a number, `None` where
/// it depends on the data.
pub type EquationConstants = Vec<(Monomial, Option<Q>)>;

/// The largest fold: beyond it the exact inverse's cost grows past what the fold saves.
const MAX_FOLDED: usize = 512;

/// The constant block chosen greedily, rows taken in `order` (see the module
/// documentation): the rows with their entries by template column, the columns, and the
/// block's exact inverse (`inv[p][f]`: rows by chosen column, columns by chosen row).
fn choose_block(
    t: &EliminationTemplate,
    equations: &[EquationConstants],
    order: &[usize],
) -> Block {
    let independent_excess = t.n_excess - t.n_dependent;
    let column_of: HashMap<&Monomial, usize> =
        t.columns.iter().enumerate().map(|(i, m)| (m, i)).collect();
    let zero = <Q as Ring>::zero();
    // Chosen rows (their entries by column), chosen columns, the block's exact inverse
    // (`inv[p][f]`: rows by chosen column, columns by chosen row).
    let mut rows: Vec<(usize, BTreeMap<usize, Option<Q>>)> = Vec::new();
    let mut cols: Vec<usize> = Vec::new();
    let mut inv: Vec<Vec<Q>> = Vec::new();
    for &i in order {
        let row = &t.rows[i];
        if rows.len() >= MAX_FOLDED {
            break;
        }
        let Some(terms) = equations.get(row.equation) else {
            continue;
        };
        let mut entries: BTreeMap<usize, Option<Q>> = BTreeMap::new();
        let mut outside = false;
        for (m, q) in terms {
            match column_of.get(&row.multiplier.mul(m)) {
                Some(&c) => {
                    entries.insert(c, q.clone());
                }
                None => outside = true,
            }
        }
        // The row's entries in the chosen columns must be numbers.
        let a: Option<Vec<Q>> = cols
            .iter()
            .map(|c| match entries.get(c) {
                None => Some(zero.clone()),
                Some(q) => q.clone(),
            })
            .collect();
        let (false, Some(a)) = (outside, a) else {
            continue;
        };
        // a M11⁻¹ (1 x k), shared by every candidate column.
        let a_inv: Vec<Q> = (0..rows.len())
            .map(|f| {
                a.iter()
                    .zip(&inv)
                    .fold(zero.clone(), |s, (x, r)| &s + &(x * &r[f]))
            })
            .collect();
        let mut best: Option<(usize, Q, Vec<Q>, Vec<Q>)> = None;
        for (&c, d) in &entries {
            let Some(d) = d else { continue };
            if c >= independent_excess || cols.contains(&c) || Ring::is_zero(d) {
                continue;
            }
            // The chosen rows' entries in column c must be numbers too.
            let b: Option<Vec<Q>> = rows
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
                .fold(d.clone(), |s, (x, y)| &s - &(x * y));
            if Ring::is_zero(&s) {
                continue;
            }
            if best
                .as_ref()
                .map_or(true, |(_, bs, _, _)| s.abs() > bs.abs())
            {
                best = Some((c, s, b, a.clone()));
            }
        }
        let Some((c, s, b, _)) = best else {
            continue;
        };
        // Bordered inverse: [[A⁻¹ + A⁻¹b s⁻¹ a A⁻¹, -A⁻¹b s⁻¹], [-s⁻¹ a A⁻¹, s⁻¹]].
        let inv_b: Vec<Q> = inv
            .iter()
            .map(|r| {
                r.iter()
                    .zip(&b)
                    .fold(zero.clone(), |s, (x, y)| &s + &(x * y))
            })
            .collect();
        let s_inv = <Q as Ring>::one() / &s;
        for (p, r) in inv.iter_mut().enumerate() {
            let u = &inv_b[p] * &s_inv;
            for (f, x) in r.iter_mut().enumerate() {
                *x = &*x + &(&u * &a_inv[f]);
            }
            r.push(-u);
        }
        let mut last: Vec<Q> = a_inv.iter().map(|x| -(x * &s_inv)).collect();
        last.push(s_inv);
        inv.push(last);
        rows.push((i, entries));
        cols.push(c);
    }
    (rows, cols, inv)
}

/// See [`choose_block`].
type Block = (
    Vec<(usize, BTreeMap<usize, Option<Q>>)>,
    Vec<usize>,
    Vec<Vec<Q>>,
);

/// Folds what `t` allows (see the module documentation): `equations[e]` are the terms of
/// template equation `e`. The template's rows and independent excess columns are reordered
/// (folded rows and their columns first) and `t.fold` set; `t` is left as it is when
/// nothing folds, or when its rows are multiples of equations row-reduced on the data.
pub fn fold_constant_rows(t: &mut EliminationTemplate, equations: &[EquationConstants]) {
    t.fold = None;
    if t.reduction.is_some() || equations.is_empty() {
        return;
    }
    // Row orders tried: the template's, its reverse, and by multiplier degree (highest,
    // then lowest first); the largest block wins, the earlier order on ties.
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
    let orders = [
        (0..n).collect::<Vec<_>>(),
        (0..n).rev().collect(),
        by_degree(true),
        by_degree(false),
    ];
    let Some((rows, cols, inv)) = orders
        .iter()
        .map(|o| choose_block(t, equations, o))
        .reduce(|best, b| if b.0.len() > best.0.len() { b } else { best })
    else {
        return;
    };
    let k = rows.len();
    if k == 0 {
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
    // Folded rows first (in the order chosen), then the others; the folded columns first.
    let folded_rows: Vec<usize> = rows.iter().map(|r| r.0).collect();
    let row_order = with_first(&folded_rows, t.rows.len());
    let col_order = with_first(&cols, t.columns.len());
    t.rows = row_order.iter().map(|&r| t.rows[r].clone()).collect();
    t.columns = col_order.iter().map(|&c| t.columns[c].clone()).collect();
    t.sparse = None;
    t.fold = Some(ConstantFold {
        rows: k,
        ..fold.clone()
    });
    if t.eliminated_size().1 > usize::from(u16::MAX) {
        t.fold = None;
        return;
    }
    // The filled columns of each row, and the multiply-adds: per other row,
    // `M21[i, :] M11⁻¹` over its non-zeros, then `t M12` over the folded rows' patterns.
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
