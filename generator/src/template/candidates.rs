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
use crate::algebra::{Fp, Monomial, MonomialOrder, Poly};
use crate::budget::{Deadline, Exhausted};
use std::collections::{BTreeMap, BTreeSet};

/// One shrinking step: `(description, rows, cols)` after the step.
pub type ShrinkStep = (String, usize, usize);

/// The candidate rows and their monomials, as used by build and shrink.
#[derive(Clone, Debug)]
pub(crate) struct Candidate {
    pub(crate) row: TemplateRow,
    /// Total degree of `multiplier * equation`.
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
}

impl Blocks {
    /// The blocks of `basis` under `action`: the reducible monomials are the products
    /// `action * b` outside the basis and the unknowns among the first `visible` variables
    /// outside it ([`super::unknowns_outside_basis`]).
    pub(crate) fn new(basis: &[Monomial], action: &Action, visible: usize) -> Blocks {
        let basis_set: BTreeSet<Monomial> = basis.iter().cloned().collect();
        let red_set: BTreeSet<Monomial> = basis
            .iter()
            .flat_map(|b| action.products(b).map(|(m, _)| m).collect::<Vec<_>>())
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

/// All multiples `m * f_i` with `deg(m * f_i) <= d`.
pub(crate) fn candidates<const P: u32>(eqs: &[Poly<Fp<P>>], d: u32) -> Vec<Candidate> {
    let mut out = Vec::new();
    for (i, f) in eqs.iter().enumerate() {
        let Some(df) = f.degree() else { continue };
        if df > d {
            continue;
        }
        let n = f.nvars();
        for m in Monomial::all_up_to_degree(n, d - df, MonomialOrder::Grevlex) {
            let terms = f.terms().map(|(t, c)| (t.mul(&m), c.0)).collect();
            out.push(Candidate {
                row: TemplateRow {
                    equation: i,
                    multiplier: m.clone(),
                },
                degree: df + m.degree(),
                terms,
            });
        }
    }
    out
}

/// The smallest candidate degree worth trying for `action`: the largest degree among the
/// equations and the reducible monomials.
pub(crate) fn start_degree<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    action: &Action,
    visible: usize,
) -> u32 {
    let blocks = Blocks::new(basis, action, visible);
    eqs.iter()
        .filter_map(|f| f.degree())
        .chain(blocks.reducible.iter().map(|m| m.degree()))
        .max()
        .unwrap_or(0)
}

/// Estimated bytes of the candidate rows of degree `d` and of their dense `[E|R]` matrix.
pub(crate) fn candidate_bytes<const P: u32>(eqs: &[Poly<Fp<P>>], d: u32) -> u64 {
    let n = eqs.first().map_or(0, |f| f.nvars()) as u64;
    let binom =
        |a: u64, b: u64| -> u64 { (1..=b).fold(1u64, |acc, i| acc.saturating_mul(a + 1 - i) / i) };
    let cols = binom(n + d as u64, n);
    let (mut rows, mut terms) = (0u64, 0u64);
    for f in eqs {
        let Some(df) = f.degree() else { continue };
        if df <= d {
            let r = binom(n + (d - df) as u64, n);
            rows = rows.saturating_add(r);
            terms = terms.saturating_add(r.saturating_mul(f.len() as u64));
        }
    }
    rows.saturating_mul(cols)
        .saturating_mul(4)
        .saturating_add(terms.saturating_mul(48 + 2 * n))
}
