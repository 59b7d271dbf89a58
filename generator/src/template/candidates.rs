//! Candidate rows and column blocks: what every template stage (shrink, basis selection,
//! build) works on.
//!
//! Candidate rows are monomial multiples of the equations (Macaulay-style, by increasing
//! total degree). The reducibility test used everywhere: with the template's columns
//! ordered `excess | reducible | basis`, Gauss-Jordan elimination makes every reducible
//! column a pivot column iff `rank([E | R]) - rank(E) = |R|` (E, R: the excess and
//! reducible column blocks); the basis block does not enter the test.

use super::linalg::gauss_jordan_within;
use super::{Action, TemplateRow};
use crate::algebra::{Field, Fp, Monomial, MonomialOrder, Poly};
use crate::budget::{Deadline, Exhausted};
use std::collections::{BTreeMap, BTreeSet};

/// One shrinking step: `(description, rows, cols)` after the step.
pub type ShrinkStep = (String, usize, usize);

/// The candidate rows and their monomials, as used by build and shrink.
#[derive(Clone, Debug)]
pub(crate) struct Candidate {
    pub(crate) row: TemplateRow,
    /// Degree of `multiplier * equation` in the pool's grading ([`weighted_degree`]; the
    /// total degree when unweighted).
    pub(crate) degree: u32,
    /// Terms of the product (monomial, raw residue).
    pub(crate) terms: Vec<(Monomial, u32)>,
}

/// Classification of monomials into the reducible and basis blocks.
pub(crate) struct Blocks {
    pub(crate) reducible: Vec<Monomial>,
    pub(crate) basis: Vec<Monomial>,
    pub(crate) red_set: BTreeSet<Monomial>,
    pub(crate) basis_set: BTreeSet<Monomial>,
    /// The basis indices whose relation is `b / action` (a pencil template, see
    /// [`super::EliminationTemplate::flipped`]); increasing.
    pub(crate) flipped: Vec<usize>,
}

impl Blocks {
    /// The blocks of `basis` under `action`: the reducible monomials are the products
    /// `action * b` outside the basis and the unknowns among the first `visible` variables
    /// outside it ([`super::unknowns_outside_basis`]).
    pub(crate) fn new(basis: &[Monomial], action: &Action, visible: usize) -> Blocks {
        Blocks::with_flipped(basis, action, &[], visible)
    }
    /// [`Blocks::new`] with the relations of the basis indices `flipped` (increasing) taken
    /// the other way round: `b / action` ([`Action::inverse_product`]) is reducible rather
    /// than `action * b`. `None` when a flipped `b / action` is not a polynomial monomial.
    pub(crate) fn try_with_flipped(
        basis: &[Monomial],
        action: &Action,
        flipped: &[usize],
        visible: usize,
    ) -> Option<Blocks> {
        let flipped_ok = flipped
            .iter()
            .all(|&j| action.inverse_product(&basis[j]).is_some());
        flipped_ok.then(|| Blocks::with_flipped(basis, action, flipped, visible))
    }
    fn with_flipped(
        basis: &[Monomial],
        action: &Action,
        flipped: &[usize],
        visible: usize,
    ) -> Blocks {
        let basis_set: BTreeSet<Monomial> = basis.iter().cloned().collect();
        let red_set: BTreeSet<Monomial> = basis
            .iter()
            .enumerate()
            .flat_map(|(j, b)| {
                if flipped.contains(&j) {
                    action.inverse_product(b).into_iter().collect::<Vec<_>>()
                } else {
                    action.products(b).map(|(m, _)| m).collect::<Vec<_>>()
                }
            })
            .chain(super::unknowns_outside_basis(basis, visible))
            .filter(|m| !basis_set.contains(m))
            .collect();
        let mut reducible: Vec<Monomial> = red_set.iter().cloned().collect();
        reducible.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
        Blocks {
            reducible,
            basis: basis.to_vec(),
            red_set,
            basis_set,
            flipped: flipped.to_vec(),
        }
    }
    /// The excess monomials of a set of rows, descending grevlex.
    pub(crate) fn excess_of<'a>(&self, rows: impl Iterator<Item = &'a Candidate>) -> Vec<Monomial> {
        let mut s: BTreeSet<Monomial> = BTreeSet::new();
        for c in rows {
            for (m, _) in &c.terms {
                if !self.red_set.contains(m) && !self.basis_set.contains(m) {
                    s.insert(m.clone());
                }
            }
        }
        let mut v: Vec<Monomial> = s.into_iter().collect();
        v.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
        v
    }
    /// Dense `[E | R]` rows (raw residues) of the candidates, with the given excess order.
    pub(crate) fn dense_er(&self, rows: &[&Candidate], excess: &[Monomial]) -> Vec<Vec<u32>> {
        let idx: BTreeMap<&Monomial, usize> = excess
            .iter()
            .chain(self.reducible.iter())
            .enumerate()
            .map(|(i, m)| (m, i))
            .collect();
        let n = excess.len() + self.reducible.len();
        rows.iter()
            .map(|c| {
                let mut v = vec![0u32; n];
                for (m, x) in &c.terms {
                    if let Some(&k) = idx.get(m) {
                        v[k] = *x;
                    }
                }
                v
            })
            .collect()
    }
    /// The reducibility test `rank([E|R]) - rank(E) == |R|` for a row set.
    pub(crate) fn reducible_by<const P: u32>(&self, rows: &[&Candidate]) -> bool {
        self.reducible_within::<P>(rows, None)
            .expect("no budget, never exhausted")
    }
    /// [`Self::reducible_by`] within a budget.
    pub(crate) fn reducible_within<const P: u32>(
        &self,
        rows: &[&Candidate],
        deadline: Option<&Deadline>,
    ) -> Result<bool, Exhausted> {
        let excess = self.excess_of(rows.iter().copied());
        let mut m = self.dense_er(rows, &excess);
        let piv =
            gauss_jordan_within::<P>(&mut m, excess.len() + self.reducible.len(), false, deadline)?;
        Ok(piv.iter().filter(|&&c| c >= excess.len()).count() == self.reducible.len())
    }
}

/// `sum_i weights[i] * e_i`, the grading of weighted candidate pools; empty weights are all
/// 1 (the total degree).
pub(crate) fn weighted_degree(m: &Monomial, weights: &[u32]) -> u32 {
    if weights.is_empty() {
        m.degree()
    } else {
        m.0.iter().zip(weights).map(|(&e, &w)| e as u32 * w).sum()
    }
}

/// The largest [`weighted_degree`] of a term of `f` (`None` for zero).
pub(crate) fn poly_weighted_degree<F: Field>(f: &Poly<F>, weights: &[u32]) -> Option<u32> {
    f.terms().map(|(m, _)| weighted_degree(m, weights)).max()
}

/// The monomials of weighted degree at most `d`, descending (weighted degree, then
/// grevlex): with empty weights, every monomial of total degree at most `d`, descending
/// grevlex.
fn multipliers(nvars: usize, d: u32, weights: &[u32]) -> Vec<Monomial> {
    if weights.is_empty() {
        return Monomial::all_up_to_degree(nvars, d, MonomialOrder::Grevlex);
    }
    fn rec(i: usize, left: u32, w: &[u32], cur: &mut Vec<u16>, out: &mut Vec<Monomial>) {
        if i == w.len() {
            out.push(Monomial(cur.clone()));
            return;
        }
        for e in 0..=left / w[i] {
            cur.push(e as u16);
            rec(i + 1, left - e * w[i], w, cur, out);
            cur.pop();
        }
    }
    let mut out = Vec::new();
    rec(0, d, weights, &mut Vec::with_capacity(nvars), &mut out);
    out.sort_by(|a, b| {
        weighted_degree(b, weights)
            .cmp(&weighted_degree(a, weights))
            .then_with(|| MonomialOrder::Grevlex.cmp(b, a))
    });
    out
}

/// `C(n, k)`, saturating (it bounds sizes).
pub(crate) fn binomial(n: u64, k: u64) -> u64 {
    (1..=k).fold(1u64, |acc, i| acc.saturating_mul(n + 1 - i) / i)
}

impl Candidate {
    /// The row `m * f`, `f` the equation `equation`, of the given pool degree.
    pub(crate) fn multiple<const P: u32>(
        equation: usize,
        f: &Poly<Fp<P>>,
        m: Monomial,
        degree: u32,
    ) -> Candidate {
        Candidate {
            degree,
            terms: f.terms().map(|(t, c)| (t.mul(&m), c.0)).collect(),
            row: TemplateRow {
                equation,
                multiplier: m,
            },
        }
    }
}

/// All multiples `m * f_i` with `wdeg(m * f_i) <= d` ([`weighted_degree`] under `weights`;
/// the total degree when empty).
pub(crate) fn candidates<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    d: u32,
    weights: &[u32],
) -> Vec<Candidate> {
    let mut out = Vec::new();
    for (i, f) in eqs.iter().enumerate() {
        let Some(df) = poly_weighted_degree(f, weights) else {
            continue;
        };
        if df > d {
            continue;
        }
        let n = f.nvars();
        for m in multipliers(n, d - df, weights) {
            let degree = df + weighted_degree(&m, weights);
            out.push(Candidate::multiple(i, f, m, degree));
        }
    }
    out
}

/// The smallest candidate degree worth trying for `action` (in the grading of `weights`):
/// the largest degree among the equations and the reducible monomials.
pub(crate) fn start_degree<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    action: &Action,
    visible: usize,
    weights: &[u32],
) -> u32 {
    let blocks = Blocks::new(&action.basis_for(basis), action, visible);
    eqs.iter()
        .filter_map(|f| poly_weighted_degree(f, weights))
        .chain(blocks.reducible.iter().map(|m| weighted_degree(m, weights)))
        .max()
        .unwrap_or(0)
}

/// Number of monomials in `weights.len()` variables of weighted degree at most `d`.
fn count_up_to(d: u32, weights: &[u32]) -> u64 {
    // ways[k]: monomials in the variables so far of weighted degree exactly k.
    let mut ways = vec![0u64; d as usize + 1];
    ways[0] = 1;
    for &w in weights {
        for k in w as usize..=d as usize {
            ways[k] = ways[k].saturating_add(ways[k - w as usize]);
        }
    }
    ways.iter().fold(0u64, |a, &b| a.saturating_add(b))
}

/// Number of candidate rows of [`candidates`]`(eqs, d, weights)`.
pub(crate) fn pool_size<F: Field>(eqs: &[Poly<F>], d: u32, weights: &[u32]) -> u64 {
    let n = eqs.first().map_or(0, |f| f.nvars());
    let ones = vec![1; n];
    let w = if weights.is_empty() {
        &ones[..]
    } else {
        weights
    };
    eqs.iter()
        .filter_map(|f| poly_weighted_degree(f, weights))
        .filter(|&df| df <= d)
        .fold(0u64, |a, df| a.saturating_add(count_up_to(d - df, w)))
}

/// Estimated bytes of the candidate rows of degree `d` and of their dense `[E|R]` matrix.
pub(crate) fn candidate_bytes<const P: u32>(eqs: &[Poly<Fp<P>>], d: u32, weights: &[u32]) -> u64 {
    let n = eqs.first().map_or(0, |f| f.nvars()) as u64;
    if !weights.is_empty() {
        let cols = count_up_to(d, weights);
        let (mut rows, mut terms) = (0u64, 0u64);
        for f in eqs {
            let Some(df) = poly_weighted_degree(f, weights) else {
                continue;
            };
            if df <= d {
                let r = count_up_to(d - df, weights);
                rows = rows.saturating_add(r);
                terms = terms.saturating_add(r.saturating_mul(f.len() as u64));
            }
        }
        return rows
            .saturating_mul(cols)
            .saturating_mul(4)
            .saturating_add(terms.saturating_mul(48 + 2 * n));
    }
    let cols = binomial(n + d as u64, n);
    let (mut rows, mut terms) = (0u64, 0u64);
    for f in eqs {
        let Some(df) = f.degree() else { continue };
        if df <= d {
            let r = binomial(n + (d - df) as u64, n);
            rows = rows.saturating_add(r);
            terms = terms.saturating_add(r.saturating_mul(f.len() as u64));
        }
    }
    rows.saturating_mul(cols)
        .saturating_mul(4)
        .saturating_add(terms.saturating_mul(48 + 2 * n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::P1;

    #[test]
    fn weighted_pools_hold_exactly_the_multiples_within_the_weighted_degree() {
        // f = x^2 + y in (x, y), weights (1, 3): wdeg f = 3.
        let n = 2;
        let f: Poly<Fp<P1>> = Poly::var(n, 0).mul(&Poly::var(n, 0)).add(&Poly::var(n, 1));
        let w = [1, 3];
        assert_eq!(poly_weighted_degree(&f, &w), Some(3));
        for d in 0..12 {
            let pool = candidates(std::slice::from_ref(&f), d, &w);
            assert_eq!(
                pool.len() as u64,
                pool_size(std::slice::from_ref(&f), d, &w)
            );
            for c in &pool {
                assert!(c.degree <= d);
                assert_eq!(c.degree, 3 + weighted_degree(&c.row.multiplier, &w));
            }
            // Every multiplier of weighted degree d - 3 at most, each once.
            let expect = (0..=d)
                .flat_map(|a| (0..=d).map(move |b| (a, b)))
                .filter(|&(a, b)| d >= 3 && a + 3 * b <= d - 3)
                .count();
            assert_eq!(pool.len(), expect, "degree {d}");
        }
        // Unweighted pools are the total-degree ones: multipliers of degree 3 at most.
        let plain = candidates(std::slice::from_ref(&f), 5, &[]);
        assert_eq!(plain.len(), 10);
        assert_eq!(pool_size(&[f], 5, &[]), 10);
    }
}
