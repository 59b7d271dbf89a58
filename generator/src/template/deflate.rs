//! Redundant bases deflated to pencils: a basis of the solution count, some relations
//! taken the other way round (see "Pencil templates" in the module documentation of
//! [`crate::template`]).
//!
//! In a redundant basis B (`|B| = count + k`) some monomials `e` have a trivial relation:
//! `action * e` is itself a basis monomial `p`. Dropping `k` of them (the set E) and
//! taking the relation of each `p = action * e` the other way round (`p / action = e`,
//! now a reducible column, while `action * p` need not be reduced any more) leaves a basis
//! `B0 = B \ E` of `count` monomials whose pencil `action T1 v = T0 v` has exactly the
//! solutions' eigenvalues: the k spurious eigenvalues (a Jordan block at 0 for a
//! Laurent action, which costs the solver accuracy) are gone, and so is the residual screen
//! of the read-outs. Martyushev, Bhayani and Pajdla's `unsynch_relpose` basis has this
//! shape (B = `z Q' ∪ z^2 {1, w, x, y}`, E = `z^2 {1, w, x, y}`); their solvers keep the
//! 20x20 pencil and drop its infinite eigenvalues instead.
//!
//! Whether the template's rows reduce the new reducible set is the usual test
//! ([`Blocks::reducible_by`]); whether B0 spans the quotient, the action matrix's
//! characteristic polynomial on the build instance, which the caller compares with the
//! quotient's. Where the rows cannot deflate the whole redundancy, the basis still loses
//! what they can: fewer spurious eigenvalues, shorter chains of them.

use super::candidates::{Blocks, Candidate};
use super::shrink::shrink_quick;
use super::Action;
use crate::algebra::Monomial;
use crate::budget::Deadline;
use std::collections::BTreeSet;

/// The bound on the summed `rows x columns` of the reducibility tests of one [`deflate`]:
/// the moves stop there, so that the result does not depend on the machine's speed (a
/// large redundant basis has many candidate moves, each an elimination of the rows).
const MAX_DEFLATE_WORK: u64 = 1 << 24;

/// Deflates a redundant basis `blocks` (relations all forward) with the rows `rows`
/// towards `count` monomials, greedily: one monomial `e` with a trivial relation
/// (`action * e = p` in the basis) leaves the basis at a time, chain starts (monomials no
/// basis monomial maps onto) first; when `p`'s own relation is not trivial, `p` is flipped
/// so that its relation reduces `e` (the row that reduced `action * p` is freed for it),
/// otherwise `e` just leaves (the rows must then prove it dependent). A move is kept when
/// the rows reduce the new reducible set ([`Blocks::reducible_by`]), and the moves stop at
/// `count` monomials, when none is left, or when the tests have used
/// [`MAX_DEFLATE_WORK`] (or the deadline passes, which only guards the budget). Returns the smaller basis's blocks and the rows
/// shrunk for them; `None` when the action is not a monomial one, the basis is not
/// redundant, or no move is possible.
pub(crate) fn deflate<const P: u32>(
    blocks: &Blocks,
    rows: &[Candidate],
    action: &Action,
    (visible, count): (usize, usize),
    deadline: Option<&Deadline>,
) -> Option<(Blocks, Vec<Candidate>)> {
    if blocks.basis.len() <= count || !action.is_monomial() || !blocks.flipped.is_empty() {
        return None;
    }
    let image = |b: &Monomial| action.products(b).next().map(|(m, _)| m);
    let refs: Vec<&Candidate> = rows.iter().collect();
    let mut basis = blocks.basis.clone();
    let mut flipped: BTreeSet<Monomial> = BTreeSet::new();
    let width = rows
        .iter()
        .flat_map(|c| c.terms.iter().map(|(m, _)| m))
        .collect::<BTreeSet<_>>()
        .len() as u64;
    let cost = rows.len() as u64 * width;
    let mut work = MAX_DEFLATE_WORK;
    'moves: while basis.len() > count {
        let in_basis: BTreeSet<&Monomial> = basis.iter().collect();
        let is_start = |e: &Monomial| {
            action
                .inverse_product(e)
                .map_or(true, |m| !in_basis.contains(&m) || flipped.contains(&m))
        };
        let mut moves: Vec<(bool, usize, Monomial)> = basis
            .iter()
            .enumerate()
            .filter(|(_, e)| !flipped.contains(*e))
            .filter_map(|(i, e)| {
                let p = image(e)?;
                (in_basis.contains(&p) && !flipped.contains(&p)).then(|| (!is_start(e), i, p))
            })
            .collect();
        moves.sort();
        let mut step = None;
        for (_, i, p) in moves {
            let kept: Vec<Monomial> = basis
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, b)| b.clone())
                .collect();
            let flip_p = image(&p).is_some_and(|q| !in_basis.contains(&q));
            let mut now = flipped.clone();
            if flip_p {
                now.insert(p);
            }
            let indices: Vec<usize> = (0..kept.len())
                .filter(|&j| now.contains(&kept[j]))
                .collect();
            let Some(pencil) = Blocks::try_with_flipped(&kept, action, &indices, visible) else {
                continue;
            };
            if cost > work || deadline.is_some_and(|d| d.check_time().is_err()) {
                break 'moves;
            }
            work -= cost;
            if pencil.reducible_by::<P>(&refs) {
                step = Some((kept, now));
                break;
            }
        }
        let Some((kept, now)) = step else {
            break;
        };
        basis = kept;
        flipped = now;
    }
    if basis.len() == blocks.basis.len() {
        return None;
    }
    let indices: Vec<usize> = (0..basis.len())
        .filter(|&j| flipped.contains(&basis[j]))
        .collect();
    let pencil = Blocks::try_with_flipped(&basis, action, &indices, visible)?;
    let shrunk = shrink_quick::<P>(&pencil, rows.to_vec());
    Some((pencil, shrunk))
}
