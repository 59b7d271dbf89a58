//! Sparse multivariate polynomials generic over the coefficient ring.

use super::field::{Ring, Q};
use super::monomial::{Monomial, MonomialOrder};
use std::collections::BTreeMap;
use std::fmt;

/// A sparse polynomial in `nvars` variables with coefficients in `C`.
///
/// Terms are kept in a `BTreeMap` keyed by the exponent vector (storage order: lex), so
/// iteration order and therefore everything built from it is deterministic. No stored
/// coefficient is zero (as reported by [`Ring::is_zero`]).
#[derive(Clone)]
pub struct Poly<C> {
    nvars: usize,
    terms: BTreeMap<Monomial, C>,
}

#[allow(clippy::len_without_is_empty)] // `is_zero` is the ring's name for it
impl<C: Ring> Poly<C> {
    /// The zero polynomial in `nvars` variables.
    pub fn zero(nvars: usize) -> Self {
        Poly {
            nvars,
            terms: BTreeMap::new(),
        }
    }
    /// The constant polynomial `c`.
    pub fn constant(nvars: usize, c: C) -> Self {
        let mut p = Poly::zero(nvars);
        p.add_term(Monomial::one(nvars), c);
        p
    }
    /// The variable x_i.
    pub fn var(nvars: usize, i: usize) -> Self {
        let mut p = Poly::zero(nvars);
        p.add_term(Monomial::var(nvars, i), C::one());
        p
    }
    /// The single term `c * m`.
    pub fn term(m: Monomial, c: C) -> Self {
        let mut p = Poly::zero(m.nvars());
        p.add_term(m, c);
        p
    }
    /// Builds a polynomial from terms; repeated monomials are summed.
    pub fn from_terms(nvars: usize, terms: impl IntoIterator<Item = (Monomial, C)>) -> Self {
        let mut p = Poly::zero(nvars);
        for (m, c) in terms {
            p.add_term(m, c);
        }
        p
    }
    /// Number of variables of the ring.
    pub fn nvars(&self) -> usize {
        self.nvars
    }
    /// Number of non-zero terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }
    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }
    /// The terms in storage order (lex on exponent vectors, ascending).
    pub fn terms(&self) -> impl Iterator<Item = (&Monomial, &C)> {
        self.terms.iter()
    }
    /// The coefficient of `m` (zero if absent).
    pub fn coeff(&self, m: &Monomial) -> C {
        self.terms.get(m).cloned().unwrap_or_else(C::zero)
    }
    /// The monomials with non-zero coefficient, sorted descending in `order`.
    pub fn support(&self, order: MonomialOrder) -> Vec<Monomial> {
        let mut s: Vec<Monomial> = self.terms.keys().cloned().collect();
        s.sort_by(|a, b| order.cmp(b, a));
        s
    }
    /// Adds `c * m` in place.
    pub fn add_term(&mut self, m: Monomial, c: C) {
        debug_assert_eq!(m.nvars(), self.nvars);
        if c.is_zero() {
            return;
        }
        match self.terms.entry(m) {
            std::collections::btree_map::Entry::Vacant(v) => {
                v.insert(c);
            }
            std::collections::btree_map::Entry::Occupied(mut o) => {
                let s = o.get().add(&c);
                if s.is_zero() {
                    o.remove();
                } else {
                    *o.get_mut() = s;
                }
            }
        }
    }
    /// The total degree; `None` for the zero polynomial.
    pub fn degree(&self) -> Option<u32> {
        self.terms.keys().map(Monomial::degree).max()
    }
    /// The degree in variable `i`; `None` for the zero polynomial.
    pub fn degree_in(&self, i: usize) -> Option<u32> {
        self.terms.keys().map(|m| m.0[i] as u32).max()
    }
    /// The leading monomial and coefficient in `order`.
    pub fn leading(&self, order: MonomialOrder) -> Option<(&Monomial, &C)> {
        self.terms.iter().max_by(|a, b| order.cmp(a.0, b.0))
    }
    /// `self + other`.
    pub fn add(&self, other: &Self) -> Self {
        let mut r = self.clone();
        for (m, c) in &other.terms {
            r.add_term(m.clone(), c.clone());
        }
        r
    }
    /// `self - other`.
    pub fn sub(&self, other: &Self) -> Self {
        let mut r = self.clone();
        for (m, c) in &other.terms {
            r.add_term(m.clone(), c.neg());
        }
        r
    }
    /// `-self`.
    pub fn neg(&self) -> Self {
        Poly {
            nvars: self.nvars,
            terms: self
                .terms
                .iter()
                .map(|(m, c)| (m.clone(), c.neg()))
                .collect(),
        }
    }
    /// `self * other`.
    pub fn mul(&self, other: &Self) -> Self {
        debug_assert_eq!(self.nvars, other.nvars);
        let mut r = Poly::zero(self.nvars);
        for (ma, ca) in &self.terms {
            for (mb, cb) in &other.terms {
                r.add_term(ma.mul(mb), ca.mul(cb));
            }
        }
        r
    }
    /// `c * self`.
    pub fn scale(&self, c: &C) -> Self {
        let mut r = Poly::zero(self.nvars);
        for (m, a) in &self.terms {
            r.add_term(m.clone(), a.mul(c));
        }
        r
    }
    /// `c * m * self`.
    pub fn mul_term(&self, m: &Monomial, c: &C) -> Self {
        let mut r = Poly::zero(self.nvars);
        for (mm, a) in &self.terms {
            r.add_term(mm.mul(m), a.mul(c));
        }
        r
    }
    /// `self^e`.
    pub fn pow(&self, e: u32) -> Self {
        let mut r = Poly::constant(self.nvars, C::one());
        for _ in 0..e {
            r = r.mul(self);
        }
        r
    }
    /// Evaluates at a point (one value per variable) with Horner-free term summation.
    pub fn eval(&self, point: &[C]) -> C {
        debug_assert_eq!(point.len(), self.nvars);
        let mut acc = C::zero();
        for (m, c) in &self.terms {
            let mut t = c.clone();
            for (x, &e) in point.iter().zip(&m.0) {
                for _ in 0..e {
                    t = t.mul(x);
                }
            }
            acc = acc.add(&t);
        }
        acc
    }
    /// Maps every coefficient through `f` (zero images are dropped).
    pub fn map_coeffs<D: Ring>(&self, mut f: impl FnMut(&C) -> D) -> Poly<D> {
        let mut r = Poly::zero(self.nvars);
        for (m, c) in &self.terms {
            r.add_term(m.clone(), f(c));
        }
        r
    }
    /// Substitutes a polynomial (in `nvars_out` variables) for each variable.
    pub fn substitute(&self, images: &[Poly<C>], nvars_out: usize) -> Poly<C> {
        debug_assert_eq!(images.len(), self.nvars);
        let mut acc = Poly::zero(nvars_out);
        for (m, c) in &self.terms {
            let mut t = Poly::constant(nvars_out, c.clone());
            for (img, &e) in images.iter().zip(&m.0) {
                for _ in 0..e {
                    t = t.mul(img);
                }
            }
            acc = acc.add(&t);
        }
        acc
    }
    /// Renders with variable names and a coefficient printer, terms descending in `order`.
    pub fn display_with(&self, names: &[String], order: MonomialOrder) -> String
    where
        C: fmt::Display,
    {
        if self.is_zero() {
            return "0".into();
        }
        self.support(order)
            .iter()
            .map(|m| format!("({})*{}", self.terms[m], m.display_with(names)))
            .collect::<Vec<_>>()
            .join(" + ")
    }
}

impl<C: Ring> Ring for Poly<C> {
    /// Polynomials used as coefficients of other polynomials have a fixed variable count
    /// only once they are non-constant; `zero()` and `one()` produce 0-variable constants
    /// that combine with any variable count (see [`Poly::align`]).
    fn zero() -> Self {
        Poly::zero(0)
    }
    fn one() -> Self {
        Poly::constant(0, C::one())
    }
    fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }
    fn is_one(&self) -> bool {
        self.terms.len() == 1 && self.terms.iter().all(|(m, c)| m.is_one() && c.is_one())
    }
    fn add(&self, o: &Self) -> Self {
        let (a, b) = Poly::align(self, o);
        Poly::add(&a, &b)
    }
    fn sub(&self, o: &Self) -> Self {
        let (a, b) = Poly::align(self, o);
        Poly::sub(&a, &b)
    }
    fn mul(&self, o: &Self) -> Self {
        let (a, b) = Poly::align(self, o);
        Poly::mul(&a, &b)
    }
    fn neg(&self) -> Self {
        Poly::neg(self)
    }
    fn from_rational(q: &Q) -> Option<Self> {
        C::from_rational(q).map(|c| Poly::constant(0, c))
    }
}

impl<C: Ring> Poly<C> {
    /// Brings two polynomials to a common variable count: a constant polynomial with fewer
    /// variables (as made by `Ring::zero`/`one`/`from_rational`) is widened.
    pub fn align(a: &Self, b: &Self) -> (Self, Self) {
        if a.nvars == b.nvars {
            return (a.clone(), b.clone());
        }
        let n = a.nvars.max(b.nvars);
        (a.widen(n), b.widen(n))
    }
    /// The same polynomial in its first `n <= nvars` variables; `None` if a later variable
    /// occurs.
    pub fn narrow(&self, n: usize) -> Option<Self> {
        let mut r = Poly::zero(n);
        for (m, c) in &self.terms {
            if m.0.len() < n || m.0[n..].iter().any(|&e| e != 0) {
                return None;
            }
            r.add_term(Monomial(m.0[..n].to_vec()), c.clone());
        }
        Some(r)
    }
    /// Division by `d` in grevlex: `(q, r)` with `self = q d + r` and no term of `r`
    /// divisible by `d`'s leading monomial (the remainder is unique, so `r` is zero exactly
    /// when `d` divides `self`). `None` unless `d`'s leading coefficient is 1 or -1, so that
    /// the division needs no inverse and runs alike in every ring. The leading term of the
    /// running dividend is removed, not cancelled, so a ring without exact zero tests
    /// (traced coefficients) computes the same quotient.
    pub fn divide(&self, d: &Self) -> Option<(Self, Self)> {
        let (lm, lc) = d.leading(MonomialOrder::Grevlex)?;
        let sign = if lc.is_one() {
            C::one()
        } else if lc.neg().is_one() {
            C::one().neg()
        } else {
            return None;
        };
        let tail: Vec<(Monomial, C)> = d
            .terms
            .iter()
            .filter(|(m, _)| *m != lm)
            .map(|(m, c)| (m.clone(), c.clone()))
            .collect();
        let (mut p, mut q, mut r) = (self.clone(), Poly::zero(self.nvars), Poly::zero(self.nvars));
        while let Some(m) = p.leading(MonomialOrder::Grevlex).map(|(m, _)| m.clone()) {
            let c = p.terms.remove(&m).expect("the leading term is a term");
            match lm.divide_into(&m) {
                Some(s) => {
                    let f = c.mul(&sign);
                    for (tm, tc) in &tail {
                        p.add_term(tm.mul(&s), tc.mul(&f).neg());
                    }
                    q.add_term(s, f);
                }
                None => r.add_term(m, c),
            }
        }
        Some((q, r))
    }
    /// The same polynomial in `n >= nvars` variables (extra variables appended).
    pub fn widen(&self, n: usize) -> Self {
        assert!(n >= self.nvars, "cannot narrow a polynomial");
        let mut r = Poly::zero(n);
        for (m, c) in &self.terms {
            let mut e = m.0.clone();
            e.resize(n, 0);
            r.add_term(Monomial(e), c.clone());
        }
        r
    }
}

/// Equality of the polynomials as elements of the ring with the larger variable count
/// (a constant made by `Ring::one()` equals the same constant in any number of variables).
impl<C: Ring + PartialEq> PartialEq for Poly<C> {
    fn eq(&self, other: &Self) -> bool {
        if self.nvars == other.nvars {
            return self.terms == other.terms;
        }
        let (a, b) = Poly::align(self, other);
        a.terms == b.terms
    }
}

impl<C: Ring + fmt::Debug> fmt::Debug for Poly<C> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_zero() {
            return write!(f, "0");
        }
        let parts: Vec<String> = self
            .terms
            .iter()
            .rev()
            .map(|(m, c)| format!("{c:?}*{m:?}"))
            .collect();
        write!(f, "{}", parts.join(" + "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Fp, P1};
    use num_bigint::BigInt;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    type F = Fp<P1>;

    #[test]
    fn division_by_a_unit_leading_coefficient_is_exact_on_multiples() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let n = 3;
        let x = |i| Poly::<Q>::var(n, i);
        let one = Poly::constant(n, Q::from_integer(1.into()));
        // d = 1 + x0^2 + x1^2 + x2^2 (leading coefficient 1) and its negation.
        let d = (0..n).fold(one.clone(), |acc, i| acc.add(&x(i).mul(&x(i))));
        for d in [d.clone(), d.neg()] {
            for _ in 0..50 {
                let f = random_poly_q(&mut rng, n);
                let (q, r) = f.mul(&d).divide(&d).unwrap();
                assert!(r.is_zero());
                assert_eq!(q, f);
                // Plus a term no multiple of d has: a non-zero remainder.
                let g = f.mul(&d).add(&x(1));
                let (q, r) = g.divide(&d).unwrap();
                assert_eq!(q.mul(&d).add(&r), g);
                assert!(!r.is_zero());
            }
        }
        let two = Poly::constant(n, Q::from_integer(2.into()));
        assert!(x(0)
            .divide(&x(0).scale(&Q::from_integer(2.into())))
            .is_none());
        assert!(x(0).divide(&two).is_none(), "leading coefficient 2");
        assert!(x(0).divide(&Poly::zero(n)).is_none());
        assert_eq!(
            x(0).mul(&x(1)).narrow(2),
            Some(Poly::var(2, 0).mul(&Poly::var(2, 1)))
        );
        assert_eq!(x(2).narrow(2), None);
    }

    fn random_poly_q(rng: &mut ChaCha8Rng, nvars: usize) -> Poly<Q> {
        let nterms = rng.gen_range(0..6);
        Poly::from_terms(
            nvars,
            (0..nterms).map(|_| {
                let m = Monomial((0..nvars).map(|_| rng.gen_range(0..3)).collect());
                let c = Q::new(
                    BigInt::from(rng.gen_range(-20..=20)),
                    BigInt::from(rng.gen_range(1..=7)),
                );
                (m, c)
            }),
        )
    }

    fn reduce(p: &Poly<Q>) -> Poly<F> {
        p.map_coeffs(|c| F::from_rational(c).unwrap())
    }

    #[test]
    fn ring_laws_on_random_polynomials() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..300 {
            let (a, b, c) = (
                random_poly_q(&mut rng, 3),
                random_poly_q(&mut rng, 3),
                random_poly_q(&mut rng, 3),
            );
            assert_eq!(a.add(&b), b.add(&a));
            assert_eq!(a.mul(&b), b.mul(&a));
            assert_eq!(a.add(&b).add(&c), a.add(&b.add(&c)));
            assert_eq!(a.mul(&b).mul(&c), a.mul(&b.mul(&c)));
            assert_eq!(a.mul(&b.add(&c)), a.mul(&b).add(&a.mul(&c)));
            assert!(a.sub(&a).is_zero());
            assert_eq!(a.mul(&Poly::constant(3, Q::one())), a);
        }
    }

    #[test]
    fn reduction_mod_p_commutes_with_ring_operations() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _ in 0..300 {
            let (a, b) = (random_poly_q(&mut rng, 4), random_poly_q(&mut rng, 4));
            assert_eq!(reduce(&a.add(&b)), reduce(&a).add(&reduce(&b)));
            assert_eq!(reduce(&a.mul(&b)), reduce(&a).mul(&reduce(&b)));
            assert_eq!(reduce(&a.sub(&b)), reduce(&a).sub(&reduce(&b)));
        }
    }

    #[test]
    fn evaluation_is_a_ring_homomorphism() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..200 {
            let (a, b) = (random_poly_q(&mut rng, 3), random_poly_q(&mut rng, 3));
            let x: Vec<F> = (0..3)
                .map(|_| F::new(rng.gen_range(0..1_000_000)))
                .collect();
            let (ra, rb) = (reduce(&a), reduce(&b));
            assert_eq!(reduce(&a.mul(&b)).eval(&x), ra.eval(&x) * rb.eval(&x));
            assert_eq!(reduce(&a.add(&b)).eval(&x), ra.eval(&x) + rb.eval(&x));
        }
    }

    #[test]
    fn substitution_matches_composition() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for _ in 0..100 {
            let p = reduce(&random_poly_q(&mut rng, 2));
            let images = [
                reduce(&random_poly_q(&mut rng, 3)),
                reduce(&random_poly_q(&mut rng, 3)),
            ];
            let x: Vec<F> = (0..3)
                .map(|_| F::new(rng.gen_range(0..1_000_000)))
                .collect();
            let composed = p.substitute(&images, 3).eval(&x);
            let direct = p.eval(&[images[0].eval(&x), images[1].eval(&x)]);
            assert_eq!(composed, direct);
        }
    }

    #[test]
    fn nested_polynomials_multiply() {
        // (d0 * x0 + 1) * (d0 * x0 - 1) = d0^2 x0^2 - 1 with data coefficients in Poly<Q>.
        let d0: Poly<Q> = Poly::var(1, 0);
        let x = Poly::<Poly<Q>>::term(Monomial(vec![1]), d0.clone());
        let one = Poly::constant(1, <Poly<Q> as Ring>::one());
        let r = x.add(&one).mul(&x.sub(&one));
        assert_eq!(r.coeff(&Monomial(vec![2])), d0.mul(&d0));
        assert_eq!(r.coeff(&Monomial(vec![0])), Poly::constant(0, -Q::one()));
    }

    #[test]
    fn field_inverse() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..1000 {
            let a = F::new(rng.gen_range(1..P1 as i64));
            assert_eq!(a * crate::algebra::Field::inv(&a).unwrap(), F::one());
        }
        assert_eq!(
            F::from_rational(&Q::new(BigInt::from(1), BigInt::from(2))).unwrap() * F::new(2),
            F::one()
        );
    }
}
