//! Fill-reducing order of a template for sparse elimination.
//!
//! Template rows are monomial multiples of the equations, so a large template is mostly
//! zeros at positions fixed by the problem. [`order_for_sparse_elimination`] permutes the
//! rows and, within their blocks, the excess and the reducible columns so that step `k`
//! eliminates column `k` (excess columns first, so that only the reducible rows are
//! back-substituted), in a Markowitz-style order. The runtime pivots partially among each
//! step's candidate rows, so the structure recorded ([`SparseElimination`],
//! `mingen_runtime::SparseLuPlan`) is a bound over all pivot choices: after step `k`
//! every candidate holds the union of the candidates' patterns. The numbers are then those
//! of the dense LU with partial pivoting; the plan is kept for templates of at least
//! [`SPARSE_MIN_PIVOTS`] pivot columns whose operation count beats the dense LU's by
//! [`SPARSE_MIN_GAIN`]. Large steps (a pattern over half the remaining columns) run as
//! contiguous row operations at run time. A template left in its order gets the plan of
//! that order instead (`EliminationTemplate::unrolled`) when it has at most
//! [`UNROLLED_MAX_UPDATES`] multiply-adds: the solver writes it out as straight-line code,
//! whose pivots and numbers are the dense LU's (rows outside a step's candidates are zero
//! in its column), without the dense LU's operations on entries that are zero for every
//! instance, its index arithmetic or its loops.

use super::shift::{column_coordinates, Structural};
use super::{EliminationTemplate, TemplateRow};
use crate::algebra::{Monomial, Poly};
use std::collections::HashMap;

/// The sparse elimination is used only when the dense LU needs at least this many times
/// its multiply-adds (its indexed updates cost more per operation than the dense rows).
pub const SPARSE_MIN_GAIN: usize = 3;

/// Templates with fewer pivot columns keep the dense LU: it is already cheap there, and
/// the per-step bookkeeping of the sparse one would not pay.
pub const SPARSE_MIN_PIVOTS: usize = 32;

/// Templates whose elimination in their own order takes at most this many multiply-adds
/// are eliminated by straight-line code: it stays a few thousand statements, which
/// rustc compiles quickly in any profile.
pub const UNROLLED_MAX_UPDATES: usize = 3000;

/// The structure of a template's elimination in its (permuted) natural order: the
/// owned form of `mingen_runtime::SparseLuPlan` (see there for the fields' meaning).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparseElimination {
    /// Offsets into `pattern`, one per pivot step plus the end.
    pub pattern_start: Vec<u32>,
    /// Pivot columns `c > k` where a candidate row of step `k` may be non-zero.
    pub pattern: Vec<u16>,
    /// Offsets into `targets`, one per pivot step plus the end.
    pub target_start: Vec<u32>,
    /// Rows `i > k` that may be non-zero in column `k` at step `k`.
    pub targets: Vec<u16>,
    /// Multiply-adds of the sparse elimination (forward and back substitution).
    pub sparse_updates: usize,
    /// Multiply-adds of the dense LU on the same template (an upper bound).
    pub dense_updates: usize,
    /// The entries (row-major indices into the eliminated matrix) that may be non-zero
    /// before the elimination, ascending: recorded for a plan in the template's own order
    /// (`EliminationTemplate::unrolled`), whose code reads the pivot tolerances off them;
    /// empty otherwise.
    pub filled: Vec<u32>,
}

impl SparseElimination {
    /// The plan the runtime executes, for template `t` (the template it was computed for).
    pub fn as_plan<'a>(&'a self, t: &EliminationTemplate) -> mingen_runtime::SparseLuPlan<'a> {
        let (rows, cols) = t.eliminated_size();
        mingen_runtime::SparseLuPlan {
            rows,
            cols,
            pivot_cols: t.pivot_columns(),
            first_row: t.first_reduced_row(),
            pattern_start: &self.pattern_start,
            pattern: &self.pattern,
            target_start: &self.target_start,
            targets: &self.targets,
        }
    }
}

/// Row-wise bit sets over the columns of the eliminated matrix.
#[derive(Clone)]
struct Bits {
    words: usize,
    data: Vec<u64>,
}

impl Bits {
    fn new(rows: usize, cols: usize) -> Bits {
        let words = cols.div_ceil(64);
        Bits {
            words,
            data: vec![0; rows * words],
        }
    }
    fn row(&self, r: usize) -> &[u64] {
        &self.data[r * self.words..(r + 1) * self.words]
    }
    fn get(&self, r: usize, c: usize) -> bool {
        self.data[r * self.words + c / 64] >> (c % 64) & 1 == 1
    }
    fn set(&mut self, r: usize, c: usize, on: bool) {
        let w = &mut self.data[r * self.words + c / 64];
        if on {
            *w |= 1 << (c % 64);
        } else {
            *w &= !(1 << (c % 64));
        }
    }
    fn count(&self, r: usize) -> usize {
        self.row(r).iter().map(|w| w.count_ones() as usize).sum()
    }
    /// The set columns of row `r` in `lo..hi`, ascending.
    fn ones(&self, r: usize, lo: usize, hi: usize) -> impl Iterator<Item = usize> + '_ {
        self.row(r).iter().enumerate().flat_map(move |(wi, &w)| {
            let mut w = w;
            std::iter::from_fn(move || {
                if w == 0 {
                    return None;
                }
                let b = w.trailing_zeros() as usize;
                w &= w - 1;
                Some(wi * 64 + b)
            })
            .filter(move |&c| c >= lo && c < hi)
        })
    }
}

/// The structural non-zeros of `t` (eliminated matrix: dependent excess columns left out)
/// when equation `e` has the monomials `supports[e]`: a fold's constant block reaches
/// through `M11⁻¹` into `M12`, and each pivot row of a triangular fold spreads its pattern
/// to the rows it updates.
fn structure(t: &EliminationTemplate, supports: &[Vec<Monomial>]) -> Option<Bits> {
    let (rows, cols) = t.eliminated_size();
    let k = t.fold.as_ref().map_or(0, |f| f.rows);
    let kt = t.fold.as_ref().map_or(0, |f| f.pivot_inv.len());
    let column: HashMap<&Monomial, usize> =
        t.columns.iter().enumerate().map(|(i, m)| (m, i)).collect();
    // Each row's entries are its coordinates as the fill computes them, for every instance
    // at once: on the equations' generic supports, in the ring of structural zeros.
    let shift: Option<Vec<(Monomial, Structural)>> = match &t.shift {
        Some(s) => Some(s.terms_in()?),
        None => None,
    };
    let generic: Vec<Poly<Structural>> = supports
        .iter()
        .map(|s| Poly::from_terms(t.nvars, s.iter().map(|m| (m.clone(), Structural(true)))))
        .collect();
    // The constant block's complement: the pivot rows and columns first.
    let mut bits = Bits::new(rows + kt, cols + kt);
    for (i, row) in t.rows.iter().enumerate().skip(k) {
        let entries = column_coordinates(
            &row.multiplier,
            generic.get(row.equation)?,
            shift.as_deref(),
            t.n_excess,
            |m| column.get(m).copied(),
        );
        for (mono, _) in &entries {
            let c = *column.get(mono)?;
            match (t.filled_column(c), &t.fold) {
                // A folded column: the complement's row gains `M11⁻¹`'s reach into `M12`.
                (Some(p), Some(f)) if p < k => {
                    let inv = f.inv_start[p] as usize..f.inv_start[p + 1] as usize;
                    for &q in &f.inv_cols[inv] {
                        let q = usize::from(q);
                        let m12 = f.m12_start[q] as usize..f.m12_start[q + 1] as usize;
                        for &c in &f.m12_cols[m12] {
                            bits.set(i - k, usize::from(c), true);
                        }
                    }
                }
                (Some(c), _) => bits.set(i - k, c - k, true),
                (None, _) => {}
            }
        }
    }
    if kt == 0 {
        return Some(bits);
    }
    for p in 0..kt {
        let pivot: Vec<usize> = bits.ones(p, p + 1, cols + kt).collect();
        for r in p + 1..rows + kt {
            if bits.get(r, p) {
                pivot.iter().for_each(|&c| bits.set(r, c, true));
            }
        }
    }
    let mut out = Bits::new(rows, cols);
    for r in 0..rows {
        for c in bits.ones(r + kt, kt, cols + kt) {
            out.set(r, c - kt, true);
        }
    }
    Some(out)
}

/// Multiply-adds of eliminating `t` as its solver does: along its sparse plan or its
/// written-out one if it has one, else the dense LU's (an upper bound); a fold's are not
/// included.
pub fn elimination_updates(t: &EliminationTemplate) -> usize {
    match t.sparse.as_ref().or(t.unrolled.as_ref()) {
        Some(s) => s.sparse_updates,
        None => {
            let (rows, cols) = t.eliminated_size();
            dense_updates(rows, cols, t.pivot_columns(), t.first_reduced_row())
        }
    }
}

/// Multiply-adds of the dense LU with partial pivoting (forward elimination of every row
/// below the pivot, back substitution of the reducible rows over the right-hand side).
fn dense_updates(rows: usize, cols: usize, pivots: usize, first_row: usize) -> usize {
    let forward: usize = (0..pivots).map(|j| (rows - j - 1) * (cols - j - 1)).sum();
    let back = (first_row..pivots)
        .map(|k| (pivots - k - 1) * (cols - pivots))
        .sum::<usize>();
    forward + back
}

/// Columns whose cost is evaluated exactly at each step, among those with the fewest
/// candidate rows, when the block has more remaining columns than this.
const COST_CANDIDATES: usize = 32;

/// The order of steps, `(row, column)` each, excess columns (`< first`) first: at every
/// step the column whose elimination costs the least multiply-adds under the union rule
/// (`(candidates - 1) * (union pattern - 1)`), its row the candidate with the fewest
/// non-zeros. `None` if some column has no candidate row (structurally singular).
fn markowitz(
    mut bits: Bits,
    rows: usize,
    first: usize,
    pivots: usize,
) -> Option<Vec<(usize, usize)>> {
    // Transposed structure of the pivot columns over the active rows.
    let mut by_col = Bits::new(pivots, rows);
    for r in 0..rows {
        for c in bits.ones(r, 0, pivots) {
            by_col.set(c, r, true);
        }
    }
    let mut done = vec![false; pivots];
    let mut order = Vec::with_capacity(pivots);
    let mut union = vec![0u64; bits.words];
    for step in 0..pivots {
        let (lo, hi) = if step < first {
            (0, first)
        } else {
            (first, pivots)
        };
        let mut open: Vec<(usize, usize)> = (lo..hi)
            .filter(|&c| !done[c])
            .map(|c| (by_col.count(c), c))
            .collect();
        if open.len() > COST_CANDIDATES {
            open.sort_unstable();
            open.truncate(COST_CANDIDATES);
        }
        let mut best: Option<(usize, usize)> = None;
        for &(n, c) in &open {
            if n == 0 {
                return None;
            }
            union.iter_mut().for_each(|w| *w = 0);
            for r in by_col.ones(c, 0, rows) {
                union.iter_mut().zip(bits.row(r)).for_each(|(u, w)| *u |= w);
            }
            let width: usize = union.iter().map(|w| w.count_ones() as usize).sum();
            let cost = (n - 1) * (width - 1);
            if best.map_or(true, |b| cost < b.0) {
                best = Some((cost, c));
            }
        }
        let (_, pc) = best?;
        let candidates: Vec<usize> = by_col.ones(pc, 0, rows).collect();
        let pr = *candidates.iter().min_by_key(|&&r| (bits.count(r), r))?;
        union.iter_mut().for_each(|w| *w = 0);
        for &r in &candidates {
            union.iter_mut().zip(bits.row(r)).for_each(|(u, w)| *u |= w);
        }
        for c in bits.ones(pr, 0, pivots) {
            by_col.set(c, pr, false);
        }
        for &r in candidates.iter().filter(|&&r| r != pr) {
            bits.data[r * bits.words..(r + 1) * bits.words].copy_from_slice(&union);
            bits.set(r, pc, false);
            for c in bits.ones(r, 0, pivots) {
                by_col.set(c, r, true);
            }
        }
        by_col.data[pc * by_col.words..(pc + 1) * by_col.words].fill(0);
        done[pc] = true;
        order.push((pr, pc));
    }
    Some(order)
}

/// The plan of eliminating `bits` (already in step order) in its natural order under the
/// union rule (see `mingen_runtime::SparseLuPlan`).
fn plan(
    mut bits: Bits,
    rows: usize,
    cols: usize,
    pivots: usize,
    first: usize,
) -> SparseElimination {
    let rhs = cols - pivots;
    let mut e = SparseElimination {
        pattern_start: vec![0],
        pattern: Vec::new(),
        target_start: vec![0],
        targets: Vec::new(),
        sparse_updates: 0,
        dense_updates: 0,
        filled: Vec::new(),
    };
    let mut union = vec![0u64; bits.words];
    for k in 0..pivots {
        let targets: Vec<usize> = (k + 1..rows).filter(|&i| bits.get(i, k)).collect();
        union.copy_from_slice(bits.row(k));
        for &i in &targets {
            union.iter_mut().zip(bits.row(i)).for_each(|(u, w)| *u |= w);
        }
        for &i in &targets {
            bits.data[i * bits.words..(i + 1) * bits.words].copy_from_slice(&union);
            bits.set(i, k, false);
        }
        bits.data[k * bits.words..(k + 1) * bits.words].copy_from_slice(&union);
        let pattern: Vec<usize> = bits.ones(k, k + 1, pivots).collect();
        e.sparse_updates += targets.len() * (pattern.len() + rhs);
        if k >= first {
            e.sparse_updates += pattern.len() * rhs;
        }
        e.pattern.extend(pattern.iter().map(|&c| c as u16));
        e.targets.extend(targets.iter().map(|&i| i as u16));
        e.pattern_start.push(e.pattern.len() as u32);
        e.target_start.push(e.targets.len() as u32);
    }
    e
}

/// Orders `t` for sparse elimination and records the plan in `t.sparse` when it pays (see
/// the module documentation); `supports[e]` are the monomials of equation `e` for generic
/// data. Leaves the order of `t` unchanged (and `t.sparse` empty) when the template is
/// small ([`SPARSE_MIN_PIVOTS`]) or the dense LU is about as cheap, when the supports do
/// not cover the template, or when the template has more rows than the plan's 16-bit
/// indices hold; `t.unrolled` is then the plan of its own order if that is small
/// ([`UNROLLED_MAX_UPDATES`]) and needs no more multiply-adds than the dense LU.
pub fn order_for_sparse_elimination(t: &mut EliminationTemplate, supports: &[Vec<Monomial>]) {
    t.unrolled = None;
    if !order_by_markowitz(t, supports) {
        t.unrolled = plan_in_own_order(t, supports);
    }
}

/// The plan of `t` in its own order, when it is small and needs no more multiply-adds than
/// the dense LU (a dense template too: its code has no loops or index arithmetic).
fn plan_in_own_order(
    t: &EliminationTemplate,
    supports: &[Vec<Monomial>],
) -> Option<SparseElimination> {
    let (rows, cols) = t.eliminated_size();
    let pivots = t.pivot_columns();
    let first = t.first_reduced_row();
    if pivots == 0 || pivots > rows || rows > usize::from(u16::MAX) || rows * cols > 1 << 31 {
        return None;
    }
    let bits = structure(t, supports)?;
    let filled: Vec<u32> = (0..rows)
        .flat_map(|r| bits.ones(r, 0, cols).map(move |c| (r * cols + c) as u32))
        .collect();
    let mut e = plan(bits, rows, cols, pivots, first);
    e.dense_updates = dense_updates(rows, cols, pivots, first);
    e.filled = filled;
    (e.sparse_updates <= UNROLLED_MAX_UPDATES && e.sparse_updates <= e.dense_updates).then_some(e)
}

/// [`order_for_sparse_elimination`]'s reordering: true if `t` was ordered and given its
/// plan in `t.sparse`.
fn order_by_markowitz(t: &mut EliminationTemplate, supports: &[Vec<Monomial>]) -> bool {
    t.sparse = None;
    // A fold's rows and columns stay first; the plan permutes those of the complement.
    let k = t.folded_rows();
    let (rows, cols) = t.eliminated_size();
    let pivots = t.pivot_columns();
    let first = t.first_reduced_row();
    if pivots < SPARSE_MIN_PIVOTS || pivots > rows || rows > usize::from(u16::MAX) {
        return false;
    }
    let Some(bits) = structure(t, supports) else {
        return false;
    };
    let Some(order) = markowitz(bits.clone(), rows, first, pivots) else {
        return false;
    };
    // Rows: pivot rows in step order, then the others in their order.
    let mut row_order: Vec<usize> = order.iter().map(|&(r, _)| r).collect();
    let mut used = vec![false; rows];
    row_order.iter().for_each(|&r| used[r] = true);
    row_order.extend((0..rows).filter(|&r| !used[r]));
    // Eliminated columns: pivot columns in step order, the right-hand side unchanged.
    let col_order: Vec<usize> = order.iter().map(|&(_, c)| c).chain(pivots..cols).collect();
    let mut permuted = Bits::new(rows, cols);
    for (new_r, &r) in row_order.iter().enumerate() {
        for (new_c, &c) in col_order.iter().enumerate() {
            if bits.get(r, c) {
                permuted.set(new_r, new_c, true);
            }
        }
    }
    let mut e = plan(permuted, rows, cols, pivots, first);
    e.dense_updates = dense_updates(rows, cols, pivots, first);
    if e.sparse_updates.saturating_mul(SPARSE_MIN_GAIN) > e.dense_updates {
        return false;
    }
    // Template columns: eliminated column c is template column c + k below the dependent
    // block, c + k + n_dependent after it (k folded columns first).
    let template_col = |c: usize| {
        if c < first {
            c + k
        } else {
            c + k + t.n_dependent
        }
    };
    let mut columns: Vec<Monomial> = Vec::with_capacity(t.columns.len());
    columns.extend_from_slice(&t.columns[..k]);
    columns.extend(
        order[..first]
            .iter()
            .map(|&(_, c)| t.columns[template_col(c)].clone()),
    );
    columns.extend_from_slice(&t.columns[k + first..t.n_excess]);
    columns.extend(
        order[first..]
            .iter()
            .map(|&(_, c)| t.columns[template_col(c)].clone()),
    );
    columns.extend_from_slice(&t.columns[t.n_excess + t.n_reducible..]);
    let mut rows_new: Vec<TemplateRow> = t.rows[..k].to_vec();
    rows_new.extend(row_order.iter().map(|&r| t.rows[r + k].clone()));
    // The fold's `M12` patterns name the constant block's complement columns: the pivot
    // rows' columns, which stay, then the eliminated matrix's, which move.
    if let Some(f) = &mut t.fold {
        let kt = f.pivot_inv.len();
        let mut new_of_old = vec![0u16; cols];
        for (new_c, &c) in col_order.iter().enumerate() {
            new_of_old[c] = new_c as u16;
        }
        for c in f.m12_cols.iter_mut() {
            if usize::from(*c) >= kt {
                *c = new_of_old[usize::from(*c) - kt] + kt as u16;
            }
        }
    }
    t.rows = rows_new;
    t.columns = columns;
    t.sparse = Some(e);
    true
}
