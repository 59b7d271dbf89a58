//! Basis selection (in the spirit of Larsson et al. 2018): instead of the standard
//! monomials of the Gröbner basis, choose the quotient basis B among the columns of a
//! candidate template by Gaussian elimination with a chosen column order.

use super::candidates::{Blocks, Candidate, ShrinkStep};
use super::linalg::gauss_jordan;
use super::pools::{pools, PoolFamily};
use super::shrink::{shrink, shrink_quick};
use super::Action;
use crate::algebra::{Fp, Monomial, MonomialOrder, Poly};
use crate::budget::Deadline;
use std::collections::{BTreeMap, BTreeSet};

/// A preference order for basis monomials: monomials with a larger key are eliminated
/// first (kept out of B).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BasisOrder {
    /// Grevlex with the variables permuted: `perm[k]` is the k-th largest variable.
    Grevlex(Vec<usize>),
    /// Total degree, then the degree in the variables `set` (larger first), then grevlex.
    DegreeThenSet(u64, bool),
    /// The degree in one variable first (larger first), then grevlex: the monomials of
    /// high degree in it are eliminated first, so that the basis is low in it.
    VariableFirst(usize),
}

fn key_cmp(o: &BasisOrder, a: &Monomial, b: &Monomial) -> std::cmp::Ordering {
    match o {
        BasisOrder::Grevlex(perm) => {
            let pa = Monomial(perm.iter().map(|&i| a.0[i]).collect());
            let pb = Monomial(perm.iter().map(|&i| b.0[i]).collect());
            MonomialOrder::Grevlex.cmp(&pa, &pb)
        }
        &BasisOrder::DegreeThenSet(mask, larger_first) => {
            let ds = |m: &Monomial| -> u32 {
                m.0.iter()
                    .enumerate()
                    .filter(|(i, _)| mask >> i & 1 == 1)
                    .map(|(_, &e)| e as u32)
                    .sum()
            };
            let c = a.degree().cmp(&b.degree());
            let c = c.then_with(|| {
                if larger_first {
                    ds(a).cmp(&ds(b))
                } else {
                    ds(b).cmp(&ds(a))
                }
            });
            c.then_with(|| MonomialOrder::Grevlex.cmp(a, b))
        }
        &BasisOrder::VariableFirst(v) => {
            let d = |m: &Monomial| m.0.get(v).copied().unwrap_or(0);
            d(a).cmp(&d(b))
                .then_with(|| MonomialOrder::Grevlex.cmp(a, b))
        }
    }
}

/// Chooses a basis of `count` monomials among the columns of `cands` whose product with
/// `action` is a column too, by Gaussian elimination with the columns ordered by `order`
/// (largest first, 1 and the variables last): the last `count` non-pivot columns.
pub(crate) fn select_basis<const P: u32>(
    cands: &[Candidate],
    nvars: usize,
    action: &Action,
    count: usize,
    order: &BasisOrder,
) -> Option<Vec<Monomial>> {
    let cols: BTreeSet<Monomial> = cands
        .iter()
        .flat_map(|c| c.terms.iter().map(|(m, _)| m.clone()))
        .collect();
    let forced: Vec<Monomial> = std::iter::once(Monomial::one(nvars))
        .chain((0..nvars).map(|i| Monomial::var(nvars, i)))
        .collect();
    let mut pool: Vec<Monomial> = cols
        .iter()
        .filter(|m| {
            action.applies_to(m)
                && action.products(m).all(|(p, _)| cols.contains(&p))
                && !forced.contains(m)
        })
        .cloned()
        .collect();
    pool.sort_by(|a, b| key_cmp(order, b, a));
    let pool_set: BTreeSet<&Monomial> = pool.iter().chain(forced.iter()).collect();
    let mut excess: Vec<Monomial> = cols
        .iter()
        .filter(|m| !pool_set.contains(m))
        .cloned()
        .collect();
    excess.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
    let ordered: Vec<Monomial> = excess
        .iter()
        .chain(pool.iter())
        .chain(forced.iter())
        .cloned()
        .collect();
    let idx: BTreeMap<&Monomial, usize> = ordered.iter().enumerate().map(|(i, m)| (m, i)).collect();
    let mut dense: Vec<Vec<u32>> = cands
        .iter()
        .map(|c| {
            let mut v = vec![0u32; ordered.len()];
            for (m, x) in &c.terms {
                v[idx[m]] = *x;
            }
            v
        })
        .collect();
    let piv = gauss_jordan::<P>(&mut dense, ordered.len(), false);
    let pivset: BTreeSet<usize> = piv.into_iter().collect();
    let nonpiv: Vec<usize> = (excess.len()..ordered.len())
        .filter(|c| !pivset.contains(c))
        .collect();
    if nonpiv.len() < count {
        return None;
    }
    let b: Vec<Monomial> = nonpiv[nonpiv.len() - count..]
        .iter()
        .map(|&c| ordered[c].clone())
        .collect();
    if forced.iter().any(|f| !b.contains(f)) {
        return None;
    }
    let mut b = b;
    b.sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
    Some(b)
}

/// The column orders tried by `best_selected`: grevlex under the cyclic rotations of
/// the variables and of their reversal (2n orders for n variables, the identity first),
/// without duplicates, then for each variable its degree first (a basis low in that
/// variable, as non-standard published bases often are: `{1, x, x^2, x^3} x {1, y}`).
pub fn basis_orders(nvars: usize) -> Vec<BasisOrder> {
    let mut out: Vec<BasisOrder> = Vec::new();
    for rev in [false, true] {
        for r in 0..nvars {
            let perm: Vec<usize> = (0..nvars)
                .map(|k| {
                    let v = (k + r) % nvars;
                    if rev {
                        nvars - 1 - v
                    } else {
                        v
                    }
                })
                .collect();
            let o = BasisOrder::Grevlex(perm);
            if !out.contains(&o) {
                out.push(o);
            }
        }
    }
    if nvars > 1 {
        out.extend((0..nvars).map(BasisOrder::VariableFirst));
    }
    out
}

impl BasisOrder {
    /// A human-readable description, the variables named by `names` (`x0, x1, ...` where
    /// a name is missing).
    pub fn describe(&self, names: &[String]) -> String {
        match self {
            BasisOrder::Grevlex(perm) => format!(
                "grevlex with {}",
                perm.iter()
                    .map(|&i| names.get(i).cloned().unwrap_or_else(|| format!("x{i}")))
                    .collect::<Vec<_>>()
                    .join(" > ")
            ),
            BasisOrder::DegreeThenSet(mask, larger_first) => format!(
                "degree, then {} degree in variables {mask:#b} first",
                if *larger_first { "larger" } else { "smaller" }
            ),
            BasisOrder::VariableFirst(v) => format!(
                "the degree in {} first, then grevlex",
                names.get(*v).cloned().unwrap_or_else(|| format!("x{v}"))
            ),
        }
    }
}

/// The best template found by basis selection.
pub(crate) struct SelectedTemplate {
    /// `rows * cols`.
    pub(crate) score: usize,
    /// Blocks for the selected basis.
    pub(crate) blocks: Blocks,
    /// Kept rows.
    pub(crate) kept: Vec<Candidate>,
    /// Construction and shrink history.
    pub(crate) history: Vec<ShrinkStep>,
    /// Description of the basis choice.
    pub(crate) label: String,
}

/// Basis selection for one action: for each candidate pool of [`pools`], and each of
/// [`basis_orders`], selects a basis ([`select_basis`]); each distinct basis that the
/// candidates reduce is screened with [`shrink_quick`], and the pool's best (fewest
/// rows * cols, ties to the earlier order) is shrunk with every strategy ([`shrink`]).
/// Pools come by partition of the unknowns (a total degree, a box, one unknown against
/// the others) and, within one, by increasing sum of caps; the pools of the first sum that
/// gives a basis end their partition's search. The smallest template over all is
/// returned. Deterministic. `None` also once `deadline` has run out (checked before each
/// pool and each order).
pub(crate) fn best_selected<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    nvars: usize,
    action: &Action,
    count: usize,
    maxeq: u32,
    names: &[String],
    deadline: Option<&Deadline>,
) -> Option<SelectedTemplate> {
    let orders = basis_orders(nvars);
    let out_of_budget = |bytes| deadline.is_some_and(|dl| dl.check(bytes).is_err());
    let mut best: Option<SelectedTemplate> = None;
    // Of each partition of the unknowns (the total degree is one), the pools of the first
    // cap sum that gives a basis end its search.
    let mut found: BTreeMap<PoolFamily, u32> = BTreeMap::new();
    for pool in pools(eqs, nvars, maxeq) {
        let (family, size) = pool.family_and_size();
        if found.get(&family).is_some_and(|&s| size > s) {
            continue;
        }
        if out_of_budget(pool.bytes(eqs)) {
            // A multidegree or a polytope over the memory budget leaves the total degrees
            // to try.
            if family != PoolFamily::TotalDegree
                && deadline.is_some_and(|dl| dl.check_time().is_ok())
            {
                continue;
            }
            return best;
        }
        let cands = pool.candidates(eqs);
        let refs: Vec<&Candidate> = cands.iter().collect();
        let mut seen: BTreeSet<Vec<Monomial>> = BTreeSet::new();
        let mut screened: Option<(usize, Blocks, &BasisOrder)> = None;
        for o in &orders {
            if out_of_budget(0) {
                return best;
            }
            let Some(b) = select_basis::<P>(&cands, nvars, action, count, o) else {
                continue;
            };
            if !seen.insert(b.clone()) {
                continue;
            }
            // Selected bases contain every variable (`forced`): no linear read-out.
            let blocks = Blocks::new(&b, action, nvars);
            if !blocks.reducible_by::<P>(&refs) {
                continue;
            }
            let kept = shrink_quick::<P>(&blocks, cands.clone());
            let score =
                kept.len() * (blocks.excess_of(kept.iter()).len() + blocks.reducible.len() + count);
            if screened.as_ref().map_or(true, |x| score < x.0) {
                screened = Some((score, blocks, o));
            }
        }
        let Some((_, blocks, o)) = screened else {
            continue;
        };
        found.insert(family, size);
        let ne = blocks.excess_of(cands.iter()).len();
        let label = pool.describe(names);
        let mut history = vec![(
            label.clone(),
            cands.len(),
            ne + blocks.reducible.len() + count,
        )];
        let Some(kept) = shrink::<P>(&blocks, cands, &mut history, deadline) else {
            return best;
        };
        let score =
            kept.len() * (blocks.excess_of(kept.iter()).len() + blocks.reducible.len() + count);
        if best.as_ref().map_or(true, |b| score < b.score) {
            best = Some(SelectedTemplate {
                score,
                blocks,
                kept,
                history,
                label: format!(
                    "selected by elimination of {label}, columns in {}",
                    o.describe(names)
                ),
            });
        }
    }
    best
}
