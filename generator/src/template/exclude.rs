//! Greedy exclusion of excess monomials: a local search over candidate sets that
//! [`super::shrink`] alone cannot do.
//!
//! Shrinking keeps, of one independent row set, exactly the support of the excess block's
//! left kernel; that set is the smallest template among subsets of those rows (see
//! `shrink.rs`), but which independent set the matroid greedy picks depends on the row
//! order, and a different one can need far fewer rows. This module moves between them:
//! for an excess monomial m of the current template, every candidate row that contains m
//! leaves the pool; the pool is shrunk again, and the move is kept when the pool still
//! reduces every reducible monomial and the template has no more rows than before (the
//! eliminated template is `rows x (rows + |basis|)`, its dependent excess columns left
//! out, so the row count is the size). Excluding a monomial is the removal of columns of
//! Martyushev, Vrablikova and Pajdla (CVPR 2022, "Optimizing elimination templates by
//! greedy parameter search"), applied to the candidate pool rather than to one template.
//!
//! Monomials are tried highest degree first (descending grevlex), each once per pass;
//! passes repeat while one shrinks the template. Deterministic; stops when the budget
//! runs out, keeping the best template found.

use super::candidates::{Blocks, Candidate, ShrinkStep};
use super::shrink::{shrink, shrink_quick};
use crate::algebra::{Monomial, MonomialOrder};
use crate::budget::Deadline;
use std::collections::BTreeSet;

/// Result of [`exclude_monomials`]: the pool the kept template came from, the template's
/// rows and the number of monomials excluded.
struct Excluded {
    /// The candidate rows left in the pool.
    pool: Vec<Candidate>,
    /// The shrunk rows of the best template.
    kept: Vec<Candidate>,
    /// How many moves were kept (an equation's top degree or an excess monomial excluded).
    excluded: usize,
}

/// The local search described in the module documentation, from the pool `pool` (which
/// reduces) and its shrunk template `kept`. Never returns a larger template than `kept`.
fn exclude_monomials<const P: u32>(
    blocks: &Blocks,
    pool: Vec<Candidate>,
    kept: Vec<Candidate>,
    deadline: Option<&Deadline>,
) -> Excluded {
    let mut best = Excluded {
        pool,
        kept,
        excluded: 0,
    };
    let mut work = 0u64;
    lower_equation_degrees::<P>(blocks, &mut best, &mut work);
    let mut tried: BTreeSet<Monomial> = BTreeSet::new();
    loop {
        let mut improved = false;
        let mut order = blocks.excess_of(best.kept.iter());
        order.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
        for m in order {
            if tried.contains(&m) || !best.kept.iter().any(|c| contains(c, &m)) {
                continue;
            }
            if deadline.is_some_and(|d| d.check_time().is_err()) {
                return best;
            }
            tried.insert(m.clone());
            // A deterministic bound on the work (entries of the pools eliminated), so that
            // the result does not depend on the machine's speed.
            let ncols = blocks.excess_of(best.pool.iter()).len() + blocks.reducible.len();
            work = work.saturating_add(best.pool.len() as u64 * ncols as u64);
            if work > MAX_WORK {
                return best;
            }
            let pool: Vec<Candidate> = best
                .pool
                .iter()
                .filter(|c| !contains(c, &m))
                .cloned()
                .collect();
            if pool.len() == best.pool.len() {
                continue;
            }
            let kept = shrink_quick::<P>(blocks, pool.clone());
            if kept.len() > best.kept.len()
                || !blocks.reducible_by::<P>(&kept.iter().collect::<Vec<_>>())
            {
                continue;
            }
            improved |= kept.len() < best.kept.len();
            best = Excluded {
                pool,
                kept,
                excluded: best.excluded + 1,
            };
        }
        if !improved {
            return best;
        }
        // A smaller template may make monomials tried before removable now.
        tried.clear();
    }
}

/// [`exclude_monomials`] from `pool` and its shrunk template `kept`, then the pool left is
/// shrunk with every strategy ([`shrink`]); the smaller of the two is returned, and a step
/// is appended to `history` when a move was kept.
pub(crate) fn exclude_and_shrink<const P: u32>(
    blocks: &Blocks,
    pool: Vec<Candidate>,
    kept: Vec<Candidate>,
    deadline: Option<&Deadline>,
    history: &mut Vec<ShrinkStep>,
) -> Vec<Candidate> {
    let ex = exclude_monomials::<P>(blocks, pool, kept, deadline);
    if ex.excluded == 0 {
        return ex.kept;
    }
    // Out of budget, the exclusion's own shrunk template is kept.
    let full = shrink::<P>(blocks, ex.pool, &mut Vec::new(), deadline);
    let kept = match full {
        Some(full) if full.len() <= ex.kept.len() => full,
        _ => ex.kept,
    };
    let cols = blocks.excess_of(kept.iter()).len() + blocks.reducible.len() + blocks.basis.len();
    history.push((
        format!(
            "greedy exclusion from the candidates ({} moves: equation degrees, excess monomials)",
            ex.excluded
        ),
        kept.len(),
        cols,
    ));
    kept
}

/// The first phase: per-equation candidate degrees (the multiplier sets of Martyushev et
/// al.). For each equation, last first, the multiples of its highest product degree in the
/// pool leave it while the template stays reducible and no larger.
fn lower_equation_degrees<const P: u32>(blocks: &Blocks, best: &mut Excluded, work: &mut u64) {
    let n_eq = best
        .pool
        .iter()
        .map(|c| c.row.equation + 1)
        .max()
        .unwrap_or(0);
    for eq in (0..n_eq).rev() {
        while let Some(top) = best
            .pool
            .iter()
            .filter(|c| c.row.equation == eq)
            .map(|c| c.degree)
            .max()
        {
            let ncols = blocks.excess_of(best.pool.iter()).len() + blocks.reducible.len();
            *work = work.saturating_add(best.pool.len() as u64 * ncols as u64);
            if *work > MAX_WORK {
                return;
            }
            let pool: Vec<Candidate> = best
                .pool
                .iter()
                .filter(|c| c.row.equation != eq || c.degree < top)
                .cloned()
                .collect();
            let kept = shrink_quick::<P>(blocks, pool.clone());
            if kept.len() > best.kept.len()
                || !blocks.reducible_by::<P>(&kept.iter().collect::<Vec<_>>())
            {
                break;
            }
            *best = Excluded {
                pool,
                kept,
                excluded: best.excluded + 1,
            };
        }
    }
}

/// The bound on the summed `rows x columns` of the pools shrunk by one search.
const MAX_WORK: u64 = 1 << 28;

fn contains(c: &Candidate, m: &Monomial) -> bool {
    c.terms.iter().any(|(t, _)| t == m)
}
