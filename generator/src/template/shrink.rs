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

use super::build::{Blocks, Candidate, ShrinkStep};
use super::linalg::{gauss_jordan, left_kernel_support, EchelonBasis};
use crate::algebra::MonomialOrder;
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

/// Drops linearly dependent rows, keeping rows early in `order` (matroid greedy).
fn independent_rows<const P: u32>(blocks: &Blocks, mut rows: Vec<Candidate>) -> Vec<Candidate> {
    rows.sort_by(keep_order);
    let excess = blocks.excess_of(rows.iter());
    let refs: Vec<&Candidate> = rows.iter().collect();
    let dense = blocks.dense_er(&refs, &excess);
    let mut ech = EchelonBasis::<P>::new(excess.len() + blocks.reducible.len());
    let keep: Vec<bool> = dense.into_iter().map(|v| ech.insert(v)).collect();
    rows.into_iter()
        .zip(keep)
        .filter_map(|(r, k)| k.then_some(r))
        .collect()
}

/// Keeps only the rows in the support of the left kernel of the excess block.
fn kernel_rows<const P: u32>(blocks: &Blocks, rows: Vec<Candidate>) -> Vec<Candidate> {
    let excess = blocks.excess_of(rows.iter());
    let refs: Vec<&Candidate> = rows.iter().collect();
    let dense = blocks.dense_er(&refs, &excess);
    let supp = left_kernel_support::<P>(&dense, excess.len());
    rows.into_iter()
        .zip(supp)
        .filter_map(|(r, k)| k.then_some(r))
        .collect()
}

/// Rank of the excess block.
fn excess_rank<const P: u32>(blocks: &Blocks, rows: &[Candidate]) -> usize {
    let excess = blocks.excess_of(rows.iter());
    let refs: Vec<&Candidate> = rows.iter().collect();
    let mut dense = blocks.dense_er(&refs, &excess);
    gauss_jordan::<P>(&mut dense, excess.len(), false).len()
}

/// Shrinks a reducing candidate set; appends one history entry per step.
pub(crate) fn shrink<const P: u32>(
    blocks: &Blocks,
    cands: Vec<Candidate>,
    history: &mut Vec<ShrinkStep>,
) -> Vec<Candidate> {
    let cols0 = ncols(blocks, &cands);
    let rows = independent_rows::<P>(blocks, cands);
    history.push((
        "drop linearly dependent rows (highest degree first)".into(),
        rows.len(),
        cols0,
    ));
    let cols1 = ncols(blocks, &rows);
    if cols1 != cols0 {
        history.push(("drop unused columns".into(), rows.len(), cols1));
    }
    let rows = kernel_rows::<P>(blocks, rows);
    history.push((
        "drop rows not needed to reduce (outside the excess left kernel)".into(),
        rows.len(),
        cols1,
    ));
    let cols2 = ncols(blocks, &rows);
    history.push(("drop unused columns".into(), rows.len(), cols2));
    let rank_e = excess_rank::<P>(blocks, &rows);
    let ne = blocks.excess_of(rows.iter()).len();
    if rank_e != ne {
        history.push((
            format!("note: excess block rank {rank_e} < {ne} excess columns (left block not square)"),
            rows.len(),
            cols2,
        ));
    }
    rows
}
