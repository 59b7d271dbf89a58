//! Template shrinking: removal of rows and columns that reducibility does not need.
//!
//! Let S be the rows, E and R their excess and reducible column blocks. Every reducible
//! monomial is reducible iff `rank([E|R]_S) - rank(E_S) = |R|`. Two facts make greedy
//! removal cheap and exact:
//! 1. A row that is a linear combination of the others in the `[E|R]` block is one in the
//!    full template too (a combination supported on the basis block alone would be an
//!    ideal member supported on standard monomials, hence zero); removing it changes no
//!    rank. Removing linearly dependent rows greedily, highest priority for removal first,
//!    is the matroid greedy algorithm: insert rows into an echelon basis in the reverse
//!    order and keep the independent ones.
//! 2. For linearly independent rows, the test reads `|S| - rank(E_S) = |R|`, i.e. the left
//!    kernel of `E_S` has dimension |R|; a row can then be removed iff it lies outside the
//!    support of that left kernel, and all such rows can be removed at once (the kernel
//!    does not change). Afterwards no single row can be removed.
//!
//! An excess column touched by a single row forces that row out of the kernel support,
//! so step 2 also removes every "row + private excess column" pair.

use super::candidates::{Blocks, Candidate, ShrinkStep};
use super::linalg::{gauss_jordan_within, left_kernel_support, EchelonBasis};
use crate::algebra::MonomialOrder;
use crate::budget::Deadline;
use std::cmp::Ordering;

/// Removal priority: rows removed first come last in this order (higher total degree,
/// then higher multiplier degree, then later equation, then larger multiplier).
fn keep_order(a: &Candidate, b: &Candidate) -> Ordering {
    (a.degree, a.row.multiplier.degree(), a.row.equation)
        .cmp(&(b.degree, b.row.multiplier.degree(), b.row.equation))
        .then_with(|| MonomialOrder::Grevlex.cmp(&a.row.multiplier, &b.row.multiplier))
}

fn ncols(blocks: &Blocks, rows: &[Candidate]) -> usize {
    blocks.excess_of(rows.iter()).len() + blocks.reducible.len() + blocks.basis.len()
}

/// Whether the budget has run out (checked every 64 rows of an elimination).
fn out_of_time(deadline: Option<&Deadline>) -> bool {
    deadline.is_some_and(|d| d.check_time().is_err())
}

/// Drops linearly dependent rows, keeping rows early in `order` (matroid greedy); `None`
/// once `deadline` runs out.
fn independent_rows<const P: u32>(
    blocks: &Blocks,
    rows: Vec<Candidate>,
    deadline: Option<&Deadline>,
) -> Option<Vec<Candidate>> {
    let excess = blocks.excess_of(rows.iter());
    let refs: Vec<&Candidate> = rows.iter().collect();
    let dense = blocks.dense_er(&refs, &excess);
    let mut ech = EchelonBasis::<P>::new(excess.len() + blocks.reducible.len());
    let mut keep = Vec::with_capacity(dense.len());
    for (i, v) in dense.into_iter().enumerate() {
        if i % 64 == 63 && out_of_time(deadline) {
            return None;
        }
        keep.push(ech.insert(v));
    }
    Some(
        rows.into_iter()
            .zip(keep)
            .filter_map(|(r, k)| k.then_some(r))
            .collect(),
    )
}

/// Keeps only the rows in the support of the left kernel of the excess block; `None`
/// once `deadline` runs out.
fn kernel_rows<const P: u32>(
    blocks: &Blocks,
    rows: Vec<Candidate>,
    deadline: Option<&Deadline>,
) -> Option<Vec<Candidate>> {
    let excess = blocks.excess_of(rows.iter());
    let refs: Vec<&Candidate> = rows.iter().collect();
    let dense = blocks.dense_er(&refs, &excess);
    let supp = left_kernel_support::<P>(&dense, excess.len(), deadline)?;
    Some(
        rows.into_iter()
            .zip(supp)
            .filter_map(|(r, k)| k.then_some(r))
            .collect(),
    )
}

/// Rank of the excess block; `None` once `deadline` runs out.
fn excess_rank<const P: u32>(
    blocks: &Blocks,
    rows: &[Candidate],
    deadline: Option<&Deadline>,
) -> Option<usize> {
    let excess = blocks.excess_of(rows.iter());
    let refs: Vec<&Candidate> = rows.iter().collect();
    let mut dense = blocks.dense_er(&refs, &excess);
    gauss_jordan_within::<P>(&mut dense, excess.len(), false, deadline)
        .ok()
        .map(|p| p.len())
}

/// A removal-priority strategy: rows are kept preferentially in increasing key order.
#[derive(Clone, Copy, Debug)]
enum Strategy {
    /// Total degree, then multiplier degree, equation, multiplier.
    Degree,
    /// Total degree, then the number of excess monomials of the row.
    DegreeExcess,
    /// Number of excess monomials of the row, then total degree.
    Excess,
}

impl Strategy {
    fn name(self) -> &'static str {
        match self {
            Strategy::Degree => "highest degree first",
            Strategy::DegreeExcess => "highest degree, then most excess monomials, first",
            Strategy::Excess => "most excess monomials first",
        }
    }
}

fn order_rows(blocks: &Blocks, rows: &mut [Candidate], s: Strategy) {
    let n_exc = |c: &Candidate| {
        c.terms
            .iter()
            .filter(|(m, _)| !blocks.red_set.contains(m) && !blocks.basis_set.contains(m))
            .count()
    };
    match s {
        Strategy::Degree => rows.sort_by(keep_order),
        Strategy::DegreeExcess => rows.sort_by(|a, b| {
            (a.degree, n_exc(a))
                .cmp(&(b.degree, n_exc(b)))
                .then_with(|| keep_order(a, b))
        }),
        Strategy::Excess => rows.sort_by(|a, b| {
            (n_exc(a), a.degree)
                .cmp(&(n_exc(b), b.degree))
                .then_with(|| keep_order(a, b))
        }),
    }
}

/// Shrinks a reducing candidate set with each removal strategy and keeps the smallest
/// result (fewest rows * cols; ties to the earlier strategy); appends its history. Once
/// `deadline` has run out, the strategies not yet tried are skipped (the first always
/// runs to its end unless the budget runs out during it, and then there is no result:
/// `None`).
pub(crate) fn shrink<const P: u32>(
    blocks: &Blocks,
    cands: Vec<Candidate>,
    history: &mut Vec<ShrinkStep>,
    deadline: Option<&Deadline>,
) -> Option<Vec<Candidate>> {
    let strategies = [Strategy::Degree, Strategy::DegreeExcess, Strategy::Excess];
    let mut best: Option<(usize, Vec<Candidate>, Vec<ShrinkStep>, &str)> = None;
    for s in strategies {
        if best.is_some() && out_of_time(deadline) {
            break;
        }
        let mut rows = cands.clone();
        order_rows(blocks, &mut rows, s);
        let mut h = Vec::new();
        let Some(rows) = shrink_ordered::<P>(blocks, rows, &mut h, deadline) else {
            break;
        };
        let score = rows.len() * ncols(blocks, &rows);
        if best.as_ref().map_or(true, |b| score < b.0) {
            best = Some((score, rows, h, s.name()));
        }
    }
    let (_, rows, mut h, name) = best?;
    if let Some(first) = h.first_mut() {
        first.0 = format!("drop linearly dependent rows (removal order: {name})");
    }
    history.extend(h);
    Some(rows)
}

/// A cheaper [`shrink`] for screening: one removal strategy (highest degree first).
pub(crate) fn shrink_quick<const P: u32>(
    blocks: &Blocks,
    mut cands: Vec<Candidate>,
) -> Vec<Candidate> {
    order_rows(blocks, &mut cands, Strategy::Degree);
    shrink_ordered::<P>(blocks, cands, &mut Vec::new(), None).expect("no budget")
}

/// Shrinks with the rows already in keep-preference order; `None` once `deadline` runs
/// out.
pub(crate) fn shrink_ordered<const P: u32>(
    blocks: &Blocks,
    cands: Vec<Candidate>,
    history: &mut Vec<ShrinkStep>,
    deadline: Option<&Deadline>,
) -> Option<Vec<Candidate>> {
    let cols0 = ncols(blocks, &cands);
    let rows = independent_rows::<P>(blocks, cands, deadline)?;
    history.push((
        "drop linearly dependent rows (highest degree first)".into(),
        rows.len(),
        cols0,
    ));
    let cols1 = ncols(blocks, &rows);
    if cols1 != cols0 {
        history.push(("drop unused columns".into(), rows.len(), cols1));
    }
    let rows = kernel_rows::<P>(blocks, rows, deadline)?;
    history.push((
        "drop rows not needed to reduce (outside the excess left kernel)".into(),
        rows.len(),
        cols1,
    ));
    let cols2 = ncols(blocks, &rows);
    history.push(("drop unused columns".into(), rows.len(), cols2));
    let rank_e = excess_rank::<P>(blocks, &rows, deadline)?;
    let ne = blocks.excess_of(rows.iter()).len();
    if rank_e != ne {
        history.push((
            format!(
                "note: excess block rank {rank_e} < {ne} excess columns (left block not square)"
            ),
            rows.len(),
            cols2,
        ));
    }
    Some(rows)
}
