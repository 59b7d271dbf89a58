//! Templates saturated by a polynomial: columns that stand for shifted polynomials.
//!
//! A `nonzero s` whose `s` is a polynomial with constant coefficients (`nonzero 1 + b^2 +
//! c^2 + d^2` for a quaternion's norm, `p11^2 + p12^2 + p13^2` for a row of a scaled
//! rotation) asks for the solutions of the saturation `I : s^∞`. A monomial `s` is built
//! into the template by shifting its basis (`search/saturated.rs`); for a polynomial, the
//! template reduces the polynomials `σ r` onto `σ B` (`σ = s^k`, `r` reducible, `B` a basis
//! of the saturated quotient) with multiples of the equations as written, as in the
//! saturated templates of Larsson, Åström and Oskarsson (ICCV 2017): a relation
//! `σ (r - sum_j c_j b_j) ∈ I` puts `r - sum_j c_j b_j` in `I : s^∞`.
//!
//! The template's columns change coordinates for it. With `L` the leading monomial of
//! `σ` (grevlex), each column `L m` of the reducible and basis blocks stands for the
//! polynomial `σ m`, every other column for its monomial. The polynomials `σ m` and the
//! other monomials are a basis of the polynomials (triangular against the monomials, as
//! `σ m = L m + lower terms`), and a row's coordinates in it are found by walking its
//! monomials from the highest down ([`shifted_coordinates`]). Every matrix of such a
//! template (the search's mod p, the validation's, the interpreter's, the emitted
//! solver's) holds these coordinates; the labels are the monomials `L m`, so everything
//! after the fill sees a template shifted by the monomial `L`, whose unit `L` reads the
//! unknowns (`σ x_i / σ = x_i` on every solution).

use crate::algebra::{Monomial, MonomialOrder, Poly, Ring, Q};
use std::cmp::Ordering;
use std::collections::BTreeMap;

/// The polynomial `σ` whose multiples the reducible and basis columns of a template stand
/// for (see the module documentation): terms with constant coefficients, the grevlex
/// leading one first with coefficient 1.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ColumnShift {
    /// The terms of `σ`, descending grevlex, the first one's coefficient 1.
    pub terms: Vec<(Monomial, Q)>,
}

impl ColumnShift {
    /// `σ / lc(σ)` for a non-zero polynomial given by its terms; `None` for zero.
    pub fn new(terms: impl IntoIterator<Item = (Monomial, Q)>) -> Option<ColumnShift> {
        let mut terms: Vec<(Monomial, Q)> = terms
            .into_iter()
            .filter(|(_, c)| c != &Q::from_integer(0.into()))
            .collect();
        terms.sort_by(|a, b| MonomialOrder::Grevlex.cmp(&b.0, &a.0));
        let lead = terms.first()?.1.clone();
        for (_, c) in &mut terms {
            *c = &*c / &lead;
        }
        Some(ColumnShift { terms })
    }
    /// The leading monomial `L`: the column `L m` stands for `σ m`.
    pub fn leading(&self) -> &Monomial {
        &self.terms[0].0
    }
    /// `σ^k` (`None` for `k = 0`).
    pub fn pow(&self, k: u16) -> Option<ColumnShift> {
        let nvars = self.leading().nvars();
        let sigma = Poly::from_terms(nvars, self.terms.iter().cloned());
        let mut power = sigma.clone();
        for _ in 1..k {
            power = power.mul(&sigma);
        }
        (k > 0).then(|| ColumnShift::new(power.terms().map(|(m, c)| (m.clone(), c.clone()))))?
    }
    /// `σ` written with the unknowns' names.
    pub fn display_with(&self, names: &[String]) -> String {
        Poly::from_terms(self.leading().nvars(), self.terms.iter().cloned())
            .display_with(names, MonomialOrder::Grevlex)
    }
    /// The terms in a ring (`None` where a denominator vanishes in it).
    pub fn terms_in<C: Ring>(&self) -> Option<Vec<(Monomial, C)>> {
        self.terms
            .iter()
            .map(|(m, c)| C::from_rational(c).map(|c| (m.clone(), c)))
            .collect()
    }
}

/// A coefficient known only as structurally zero or possibly non-zero: the ring in which
/// [`shifted_coordinates`] gives a row's pattern for every instance at once (sums and
/// products of possibly non-zero values are possibly non-zero; no cancellation is assumed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Structural(pub bool);

impl Ring for Structural {
    fn zero() -> Self {
        Structural(false)
    }
    fn one() -> Self {
        Structural(true)
    }
    fn is_zero(&self) -> bool {
        !self.0
    }
    fn add(&self, other: &Self) -> Self {
        Structural(self.0 || other.0)
    }
    fn sub(&self, other: &Self) -> Self {
        Structural(self.0 || other.0)
    }
    fn mul(&self, other: &Self) -> Self {
        Structural(self.0 && other.0)
    }
    fn neg(&self) -> Self {
        *self
    }
    fn from_rational(q: &Q) -> Option<Self> {
        Some(Structural(q != &Q::from_integer(0.into())))
    }
    fn is_one(&self) -> bool {
        false
    }
}

/// A monomial ordered by grevlex.
#[derive(Clone, PartialEq, Eq)]
struct Grevlex(Monomial);

impl Ord for Grevlex {
    fn cmp(&self, other: &Self) -> Ordering {
        MonomialOrder::Grevlex.cmp(&self.0, &other.0)
    }
}

impl PartialOrd for Grevlex {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The coordinates of the polynomial with terms `poly` when every monomial `L m` for
/// which `shifted(L m)` holds stands for `σ m` (`shift`: the terms of `σ`, leading first
/// with coefficient 1, as [`ColumnShift::terms_in`]) and every other monomial for itself.
/// Walks the monomials from the highest (grevlex) down: the coordinate of `σ m` is what is
/// left on `L m`, and its other terms, all lower, are taken off. Zero coordinates are
/// left out.
pub fn shifted_coordinates<C: Ring>(
    poly: impl IntoIterator<Item = (Monomial, C)>,
    shift: &[(Monomial, C)],
    shifted: impl Fn(&Monomial) -> bool,
) -> Vec<(Monomial, C)> {
    let mut v: BTreeMap<Grevlex, C> = BTreeMap::new();
    for (m, c) in poly {
        let e = v.entry(Grevlex(m)).or_insert_with(C::zero);
        *e = e.add(&c);
    }
    let Some((lead, rest)) = shift.split_first() else {
        return v.into_iter().map(|(m, c)| (m.0, c)).collect();
    };
    let mut cursor: Option<Grevlex> = None;
    loop {
        let next = match &cursor {
            None => v.iter().next_back(),
            Some(c) => v.range(..c.clone()).next_back(),
        };
        let Some((key, a)) = next else { break };
        let (key, a) = (key.clone(), a.clone());
        cursor = Some(key.clone());
        if a.is_zero() || !shifted(&key.0) {
            continue;
        }
        let Some(m) = lead.0.divide_into(&key.0) else {
            continue;
        };
        for (tau, c) in rest {
            let e = v.entry(Grevlex(tau.mul(&m))).or_insert_with(C::zero);
            *e = e.sub(&a.mul(c));
        }
    }
    v.into_iter()
        .filter(|(_, c)| !c.is_zero())
        .map(|(m, c)| (m.0, c))
        .collect()
}

/// The terms of the template row `multiplier * eq` in the template's column coordinates:
/// its products' monomials, or with `shift` (the template's [`ColumnShift::terms_in`]) their
/// [`shifted_coordinates`], where `column` gives a monomial's column and the reducible and
/// basis columns (from `n_excess` on) stand for multiples of the shift.
pub(crate) fn row_coordinates<C: Ring>(
    multiplier: &Monomial,
    eq: &Poly<C>,
    shift: Option<&[(Monomial, C)]>,
    n_excess: usize,
    column: impl Fn(&Monomial) -> Option<usize>,
) -> Vec<(Monomial, C)> {
    let product = eq.terms().map(|(m, c)| (multiplier.mul(m), c.clone()));
    match shift {
        Some(s) => shifted_coordinates(product, s, |l| column(l).is_some_and(|k| k >= n_excess)),
        None => product.collect(),
    }
}

/// [`row_coordinates`] as the solvers fill them: for a shifted template, coordinates
/// outside the columns are left out (zero mod p by construction; in floating point, what
/// rounding left, and in a traced or structural ring, cancellations it does not see).
/// Without a shift every product is returned, so that one outside the columns still shows.
pub(crate) fn column_coordinates<C: Ring>(
    multiplier: &Monomial,
    eq: &Poly<C>,
    shift: Option<&[(Monomial, C)]>,
    n_excess: usize,
    column: impl Fn(&Monomial) -> Option<usize>,
) -> Vec<(Monomial, C)> {
    let mut terms = row_coordinates(multiplier, eq, shift, n_excess, &column);
    if shift.is_some() {
        terms.retain(|(m, _)| column(m).is_some());
    }
    terms
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Fp, P1};

    type F = Fp<P1>;

    fn m(e: &[u16]) -> Monomial {
        Monomial(e.to_vec())
    }

    /// The sum of the monomials with exponents `terms`, normalised.
    fn sigma(terms: &[&[u16]]) -> ColumnShift {
        ColumnShift::new(terms.iter().map(|e| (m(e), Q::from_integer(1.into())))).unwrap()
    }

    #[test]
    fn a_multiple_of_the_shift_has_one_coordinate() {
        // σ = x^2 + y + 1 (grevlex leading x^2); σ * x y = x^3 y + x y^2 + x y.
        let sigma = sigma(&[&[0, 1], &[2, 0], &[0, 0]]);
        assert_eq!(sigma.leading(), &m(&[2, 0]));
        let s: Vec<(Monomial, F)> = sigma.terms_in().unwrap();
        let poly = [
            (m(&[3, 1]), F::one()),
            (m(&[1, 2]), F::one()),
            (m(&[1, 1]), F::one()),
        ];
        let c = shifted_coordinates(poly.clone(), &s, |l| l == &m(&[3, 1]));
        assert_eq!(c, vec![(m(&[3, 1]), F::one())]);
        // Where `x^3 y` is not shifted, the coordinates are the monomials.
        let c = shifted_coordinates(poly, &s, |_| false);
        assert_eq!(c.len(), 3);
    }

    #[test]
    fn coordinates_walk_down_through_shifted_terms() {
        // σ = x + 1; x^2 = σ x - x = σ x - σ + 1 when both x^2 and x stand for σ-multiples.
        let sigma = sigma(&[&[1], &[0]]);
        let s: Vec<(Monomial, F)> = sigma.terms_in().unwrap();
        let c = shifted_coordinates([(m(&[2]), F::one())], &s, |l| l.0[0] >= 1);
        assert_eq!(
            c,
            vec![
                (m(&[0]), F::one()),
                (m(&[1]), F::one().neg()),
                (m(&[2]), F::one())
            ]
        );
    }

    #[test]
    fn the_structural_coordinates_bound_every_instance() {
        // σ = x^2 + x y + y + 1; rows of random coefficients on random supports, every
        // monomial of degree at least 2 shifted: the coordinates over Z_p lie within those
        // in the ring of structural zeros, which the sparse elimination's pattern reads.
        let sigma = sigma(&[&[2, 0], &[1, 1], &[0, 1], &[0, 0]]);
        let numeric: Vec<(Monomial, F)> = sigma.terms_in().unwrap();
        let structural: Vec<(Monomial, Structural)> = sigma.terms_in().unwrap();
        let shifted = |l: &Monomial| l.0[0] + l.0[1] >= 2;
        let mut state = 17u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            state >> 33
        };
        for _ in 0..200 {
            let support: Vec<Monomial> = (0..6)
                .map(|_| m(&[(next() % 4) as u16, (next() % 4) as u16]))
                .collect();
            let poly = support
                .iter()
                .map(|mono| (mono.clone(), F::new((next() % 7) as i64)));
            let got = shifted_coordinates(poly, &numeric, shifted);
            let bound = shifted_coordinates(
                support.iter().map(|mono| (mono.clone(), Structural(true))),
                &structural,
                shifted,
            );
            for (mono, _) in &got {
                assert!(bound.iter().any(|(b, _)| b == mono), "{mono:?} {bound:?}");
            }
        }
    }
}
