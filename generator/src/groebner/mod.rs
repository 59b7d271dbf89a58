//! Gröbner bases over the prime fields Z_p (grevlex), by Buchberger's algorithm with the
//! Gebauer–Möller criteria and the sugar selection strategy.
//!
//! ## Public API
//! - [`groebner`]`(nvars, &[Poly<Fp<P>>]) -> Result<GroebnerBasis<P>, GroebnerError>`: the
//!   reduced, monic Gröbner basis in grevlex with `x_0 > x_1 > ...` (the
//!   [`crate::algebra::MonomialOrder::Grevlex`] convention of [`crate::algebra`]). An inconsistent system
//!   (the basis is `{1}`) is the error [`GroebnerError::Inconsistent`].
//! - [`GroebnerBasis::normal_form`]: the remainder of any polynomial on division by the basis
//!   (the unique representative supported on standard monomials).
//! - [`GroebnerBasis::check_zero_dimensional`]: [`GroebnerError::PositiveDimensional`] naming
//!   the variables that have no pure power among the leading monomials.
//!
//! ## Internal representation
//! Monomials are packed into two `u128` words (at most [`MAX_VARS`] variables, exponents at
//! most [`MAX_EXPONENT`]): `exps` holds one exponent per byte (divisibility by a SWAR test)
//! and `key` holds `(degree, e_0+..+e_{n-2}, e_0+..+e_{n-3}, ..., e_0)` one per byte from the
//! top, so that integer comparison of keys is grevlex and both words are additive under
//! multiplication. Polynomials are vectors of `(monomial, coefficient < P)` sorted by
//! decreasing key.

use crate::algebra::{Fp, Monomial, Poly};
use crate::budget::{Deadline, Exhausted};
use std::cmp::Ordering;
use thiserror::Error;

/// Largest number of variables the packed representation supports.
pub const MAX_VARS: usize = 15;

/// The largest weight of a weighted order ([`GroebnerOptions::weights`]): weighted degrees
/// stay small integers.
pub const MAX_WEIGHT: u32 = 64;
/// Largest exponent the packed representation supports.
pub const MAX_EXPONENT: u32 = 127;
/// Largest total degree the packed representation supports (products of two monomials
/// must still fit the 8-bit fields of the key).
pub const MAX_TOTAL_DEGREE: u32 = 250;

/// The most standard monomials (solutions) the quotient basis is enumerated to: the
/// enumeration's memory is linear in it, and every later stage at least quadratic (the
/// action matrix alone is `count x count`), so planning refuses far earlier by its memory
/// estimate; this bound only keeps the enumeration itself finite and small.
pub const MAX_SOLUTIONS: usize = 1 << 20;

/// Failures of Gröbner basis computations.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum GroebnerError {
    /// The equations have no common solution: the reduced Gröbner basis is `{1}`.
    #[error(
        "inconsistent system: the Gröbner basis is {{1}}, the equations have no common solution"
    )]
    Inconsistent,
    /// The ideal is not zero-dimensional (infinitely many solutions).
    #[error(
        "positive-dimensional ideal (infinitely many solutions): no pure power of {} among the leading monomials",
        .missing.join(", ")
    )]
    PositiveDimensional {
        /// Names of the variables without a pure power among the leading monomials.
        missing: Vec<String>,
    },
    /// More variables than the packed monomials hold.
    #[error("{0} variables: at most {MAX_VARS} are supported")]
    TooManyVariables(usize),
    /// An exponent or degree outgrew the packed monomials (or the configured bound).
    #[error(
        "degree bound exceeded: a polynomial of degree above {0} (packed monomials hold \
         exponents up to {MAX_EXPONENT} and total degrees up to {MAX_TOTAL_DEGREE})"
    )]
    DegreeTooLarge(u32),
    /// The resource budget ran out before the basis was complete.
    #[error(
        "Gröbner basis not finished (degree {degree} reached in {:.1} s): {exhausted}",
        *.millis as f64 / 1000.0
    )]
    Budget {
        /// Which limit ran out.
        exhausted: Exhausted,
        /// The largest sugar degree reached.
        degree: u32,
        /// Milliseconds spent on this basis.
        millis: u64,
    },
    /// The weights of a weighted order are not one weight from 1 to [`MAX_WEIGHT`] per
    /// variable.
    #[error(
        "weights {got:?} for {nvars} variables: one weight from 1 to {MAX_WEIGHT} per variable"
    )]
    Weights {
        /// The weights given.
        got: Vec<u32>,
        /// The number of variables.
        nvars: usize,
    },
    /// The quotient ring has more standard monomials than [`MAX_SOLUTIONS`] (the problem
    /// has at least that many solutions).
    #[error(
        "more than {MAX_SOLUTIONS} solutions (standard monomials): far beyond any minimal solver"
    )]
    TooManySolutions,
    /// A polynomial has a different number of variables than announced.
    #[error("polynomial {index} has {got} variables, expected {expected}")]
    VariableCount {
        /// Index of the offending input polynomial.
        index: usize,
        /// Its variable count.
        got: usize,
        /// The announced variable count.
        expected: usize,
    },
}

mod packed;

pub use packed::weights_fit;
pub(crate) use packed::Mon;

// ---------------------------------------------------------------------------------------
// Modular arithmetic and sparse polynomials
// ---------------------------------------------------------------------------------------

#[inline]
fn mulmod<const P: u32>(a: u32, b: u32) -> u32 {
    ((a as u64 * b as u64) % P as u64) as u32
}
#[inline]
fn submod<const P: u32>(a: u32, b: u32) -> u32 {
    if a >= b {
        a - b
    } else {
        a + P - b
    }
}
fn invmod<const P: u32>(a: u32) -> u32 {
    debug_assert!(a != 0);
    Fp::<P>(a).pow(P as u64 - 2).0
}

/// A polynomial as terms sorted by decreasing grevlex, coefficients in `1..P`.
pub(crate) type SPoly = Vec<(Mon, u32)>;

pub(crate) fn to_spoly<const P: u32>(
    p: &Poly<Fp<P>>,
    weights: &[u32],
) -> Result<SPoly, GroebnerError> {
    let mut v: SPoly = Vec::with_capacity(p.len());
    for (m, c) in p.terms() {
        v.push((Mon::from_monomial_weighted(m, weights)?, c.0));
    }
    v.sort_by_key(|t| std::cmp::Reverse(t.0));
    Ok(v)
}

pub(crate) fn from_spoly<const P: u32>(p: &SPoly, n: usize) -> Poly<Fp<P>> {
    Poly::from_terms(n, p.iter().map(|(m, c)| (m.to_monomial(n), Fp::<P>(*c))))
}

/// `a - c * m * b` (merge of two sorted term lists).
fn sub_mul<const P: u32>(a: &[(Mon, u32)], c: u32, m: &Mon, b: &[(Mon, u32)], out: &mut SPoly) {
    out.clear();
    out.reserve(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let bm = m.mul(&b[j].0);
        match a[i].0.cmp(&bm) {
            Ordering::Greater => {
                out.push(a[i]);
                i += 1;
            }
            Ordering::Less => {
                out.push((bm, submod::<P>(0, mulmod::<P>(c, b[j].1))));
                j += 1;
            }
            Ordering::Equal => {
                let v = submod::<P>(a[i].1, mulmod::<P>(c, b[j].1));
                if v != 0 {
                    out.push((bm, v));
                }
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    for t in &b[j..] {
        out.push((m.mul(&t.0), submod::<P>(0, mulmod::<P>(c, t.1))));
    }
}

fn make_monic<const P: u32>(p: &mut SPoly) {
    if let Some(&(_, c)) = p.first() {
        if c != 1 {
            let ci = invmod::<P>(c);
            for t in p.iter_mut() {
                t.1 = mulmod::<P>(t.1, ci);
            }
        }
    }
}

/// Full reduction of `p` by the monic polynomials `g[k]`, `k in active`; returns the
/// (monic unless zero) remainder and its sugar.
fn reduce_full<const P: u32>(
    mut p: SPoly,
    mut sugar: u32,
    g: &[SPoly],
    g_sugar: &[u32],
    active: &[usize],
) -> (SPoly, u32) {
    let mut rem: SPoly = Vec::new();
    let mut tmp: SPoly = Vec::new();
    // `p[start..]` is the part still to reduce.
    let mut start = 0;
    while start < p.len() {
        let (lm, lc) = p[start];
        let reducer = active.iter().copied().find(|&k| g[k][0].0.divides(&lm));
        match reducer {
            None => {
                rem.push((lm, lc));
                start += 1;
            }
            Some(k) => {
                let q = g[k][0].0.div_into(&lm);
                sugar = sugar.max(q.degree() + g_sugar[k]);
                // p[start] - lc * q * g[k]: the leading terms cancel.
                sub_mul::<P>(&p[start + 1..], lc, &q, &g[k][1..], &mut tmp);
                std::mem::swap(&mut p, &mut tmp);
                start = 0;
            }
        }
    }
    make_monic::<P>(&mut rem);
    (rem, sugar)
}

// ---------------------------------------------------------------------------------------
// Buchberger
// ---------------------------------------------------------------------------------------

#[derive(Clone, Copy, Debug)]
struct Pair {
    i: usize,
    j: usize,
    lcm: Mon,
    sugar: u32,
}

/// A reduced, monic Gröbner basis of an ideal of `Z_P[x_0..x_{n-1}]` in grevlex.
#[derive(Clone, Debug)]
pub struct GroebnerBasis<const P: u32> {
    nvars: usize,
    /// The weights of the order (empty: grevlex).
    weights: Vec<u32>,
    /// Internal form, sorted by increasing leading monomial.
    polys: Vec<SPoly>,
}

/// Options bounding a Gröbner basis computation.
#[derive(Clone, Debug)]
pub struct GroebnerOptions {
    /// Largest sugar degree of a pair before giving up with [`GroebnerError::DegreeTooLarge`];
    /// by default the packing limit [`MAX_TOTAL_DEGREE`], so that only the budget stops a
    /// computation.
    pub max_degree: u32,
    /// Time and memory budget ([`GroebnerError::Budget`] when it runs out); none by default.
    pub deadline: Option<Deadline>,
    /// Positive weights of the variables for a weighted order: monomials compared by
    /// `sum_i w_i e_i` first, ties by grevlex. Empty (the default): grevlex.
    pub weights: Vec<u32>,
}

impl Default for GroebnerOptions {
    fn default() -> Self {
        GroebnerOptions {
            max_degree: MAX_TOTAL_DEGREE,
            deadline: None,
            weights: Vec::new(),
        }
    }
}

/// Estimated bytes of one stored term (packed monomial and coefficient, aligned).
const TERM_BYTES: u64 = 48;
/// Estimated bytes of one pending pair.
const PAIR_BYTES: u64 = 64;

/// The reduced grevlex Gröbner basis of the ideal generated by `polys` (all in `nvars`
/// variables), with default [`GroebnerOptions`].
///
/// Errors: [`GroebnerError::Inconsistent`] if the ideal is the whole ring; size limits.
/// The zero ideal gives an empty basis.
pub fn groebner<const P: u32>(
    nvars: usize,
    polys: &[Poly<Fp<P>>],
) -> Result<GroebnerBasis<P>, GroebnerError> {
    groebner_with(nvars, polys, &GroebnerOptions::default())
}

/// [`groebner`] with explicit options.
pub fn groebner_with<const P: u32>(
    nvars: usize,
    polys: &[Poly<Fp<P>>],
    opts: &GroebnerOptions,
) -> Result<GroebnerBasis<P>, GroebnerError> {
    if nvars > MAX_VARS {
        return Err(GroebnerError::TooManyVariables(nvars));
    }
    let weights: &[u32] = if opts.weights.iter().all(|&w| w == 1) {
        &[]
    } else {
        &opts.weights
    };
    if !weights.is_empty() && !weights_fit(weights, nvars) {
        return Err(GroebnerError::Weights {
            got: weights.to_vec(),
            nvars,
        });
    }
    let mut input: Vec<(SPoly, u32)> = Vec::new();
    for (index, p) in polys.iter().enumerate() {
        if p.nvars() != nvars && !p.is_zero() {
            return Err(GroebnerError::VariableCount {
                index,
                got: p.nvars(),
                expected: nvars,
            });
        }
        let mut s = to_spoly::<P>(p, weights)?;
        if s.is_empty() {
            continue;
        }
        make_monic::<P>(&mut s);
        let d = s.iter().map(|t| t.0.degree()).max().unwrap_or(0);
        input.push((s, d));
    }
    // Process inputs by increasing leading monomial (deterministic, usually efficient).
    input.sort_by(|a, b| a.0[0].0.cmp(&b.0[0].0));

    let mut g: Vec<SPoly> = Vec::new();
    let mut g_sugar: Vec<u32> = Vec::new();
    let mut active: Vec<usize> = Vec::new();
    let mut pairs: Vec<Pair> = Vec::new();
    let started = std::time::Instant::now();
    let mut top_degree = 0u32;
    let mut steps = 0u64;

    let add = |h: SPoly,
               sugar: u32,
               g: &mut Vec<SPoly>,
               g_sugar: &mut Vec<u32>,
               active: &mut Vec<usize>,
               pairs: &mut Vec<Pair>|
     -> Result<(), GroebnerError> {
        if h[0].0.degree() == 0 {
            return Err(GroebnerError::Inconsistent);
        }
        // A remainder's terms stay below its leading monomial in degree, but one exponent
        // may still pass the 7 bits the divisibility test allows.
        if h.iter().any(|t| !t.0.fits(nvars)) {
            return Err(GroebnerError::DegreeTooLarge(
                opts.max_degree.min(MAX_TOTAL_DEGREE),
            ));
        }
        let hi = g.len();
        let hlm = h[0].0;
        let hdeg = hlm.degree();
        g.push(h);
        g_sugar.push(sugar);
        // Gebauer–Möller update.
        let cand: Vec<Pair> = active
            .iter()
            .map(|&k| {
                let lcm = g[k][0].0.lcm(&hlm, nvars, weights);
                let s = (g_sugar[k] - g[k][0].0.degree()).max(sugar - hdeg) + lcm.degree();
                Pair {
                    i: k,
                    j: hi,
                    lcm,
                    sugar: s,
                }
            })
            .collect();
        let mut keep = vec![true; cand.len()];
        // Chain criterion among the new pairs: drop (k,h) if some other new pair's lcm
        // properly divides it, or equals it with a smaller index (keep one per lcm).
        for a in 0..cand.len() {
            let coprime_a = g[cand[a].i][0].0.coprime(&hlm, nvars);
            if coprime_a {
                continue;
            }
            for b in 0..cand.len() {
                if a == b || !keep[b] {
                    continue;
                }
                if cand[b].lcm.divides(&cand[a].lcm)
                    && (cand[b].lcm != cand[a].lcm
                        || b < a
                        || g[cand[b].i][0].0.coprime(&hlm, nvars))
                {
                    keep[a] = false;
                    break;
                }
            }
        }
        // Product criterion: a pair with coprime leading monomials reduces to zero; if it
        // shares its lcm with other pairs, those are dropped too (handled above).
        for (a, c) in cand.iter().enumerate() {
            if keep[a] && g[c.i][0].0.coprime(&hlm, nvars) {
                keep[a] = false;
            }
        }
        // Old pairs: drop (i,j) if lm(h) divides lcm(i,j) strictly on both sides.
        pairs.retain(|p| {
            !(hlm.divides(&p.lcm)
                && g[p.i][0].0.lcm(&hlm, nvars, weights) != p.lcm
                && g[p.j][0].0.lcm(&hlm, nvars, weights) != p.lcm)
        });
        for (a, c) in cand.into_iter().enumerate() {
            if keep[a] {
                pairs.push(c);
            }
        }
        active.retain(|&k| !hlm.divides(&g[k][0].0));
        active.push(hi);
        Ok(())
    };

    for (p, s) in input {
        let (h, sugar) = reduce_full::<P>(p, s, &g, &g_sugar, &active);
        if !h.is_empty() {
            add(h, sugar, &mut g, &mut g_sugar, &mut active, &mut pairs)?;
        }
    }

    while !pairs.is_empty() {
        // Sugar strategy: smallest sugar, then smallest lcm, then oldest.
        let (best, _) = pairs
            .iter()
            .enumerate()
            .min_by(|a, b| {
                (a.1.sugar, a.1.lcm, a.1.j, a.1.i).cmp(&(b.1.sugar, b.1.lcm, b.1.j, b.1.i))
            })
            .expect("non-empty");
        let pr = pairs.swap_remove(best);
        if pr.sugar > opts.max_degree || !pr.lcm.fits(nvars) {
            return Err(GroebnerError::DegreeTooLarge(
                opts.max_degree.min(MAX_TOTAL_DEGREE),
            ));
        }
        top_degree = top_degree.max(pr.sugar);
        steps += 1;
        if let Some(d) = &opts.deadline {
            if steps % 16 == 0 {
                let terms: u64 = g.iter().map(|p| p.len() as u64).sum();
                let bytes = terms * TERM_BYTES + pairs.len() as u64 * PAIR_BYTES;
                if let Err(exhausted) = d.check(bytes) {
                    return Err(GroebnerError::Budget {
                        exhausted,
                        degree: top_degree,
                        millis: started.elapsed().as_millis() as u64,
                    });
                }
            }
        }
        let (fi, fj) = (&g[pr.i], &g[pr.j]);
        let qi = fi[0].0.div_into(&pr.lcm);
        let qj = fj[0].0.div_into(&pr.lcm);
        // S = qi*fi - qj*fj (both monic).
        let a: SPoly = fi[1..].iter().map(|t| (qi.mul(&t.0), t.1)).collect();
        let mut s = Vec::new();
        sub_mul::<P>(&a, 1, &qj, &fj[1..], &mut s);
        if s.is_empty() {
            continue;
        }
        if s.iter().any(|t| !t.0.fits(nvars)) {
            return Err(GroebnerError::DegreeTooLarge(
                opts.max_degree.min(MAX_TOTAL_DEGREE),
            ));
        }
        let (h, sugar) = reduce_full::<P>(s, pr.sugar, &g, &g_sugar, &active);
        if !h.is_empty() {
            add(h, sugar, &mut g, &mut g_sugar, &mut active, &mut pairs)?;
        }
    }

    // Minimal basis: the active set; then inter-reduce.
    let mut basis: Vec<SPoly> = active.iter().map(|&k| g[k].clone()).collect();
    basis.sort_by(|a, b| a[0].0.cmp(&b[0].0));
    // Inter-reduction: leading monomials of a minimal basis are irredundant, so only the
    // tails change.
    for k in 0..basis.len() {
        let others: Vec<usize> = (0..basis.len()).filter(|&o| o != k).collect();
        let p = std::mem::take(&mut basis[k]);
        let mut full = vec![p[0]];
        full.extend(normal_form_raw::<P>(p[1..].to_vec(), &basis, &others));
        basis[k] = full;
    }
    Ok(GroebnerBasis {
        nvars,
        weights: weights.to_vec(),
        polys: basis,
    })
}

/// Remainder of `p` on division by `basis[k]`, `k in idx` (not normalised).
fn normal_form_raw<const P: u32>(mut p: SPoly, basis: &[SPoly], idx: &[usize]) -> SPoly {
    let mut rem: SPoly = Vec::new();
    let mut tmp: SPoly = Vec::new();
    let mut start = 0;
    while start < p.len() {
        let (lm, lc) = p[start];
        match idx.iter().copied().find(|&k| basis[k][0].0.divides(&lm)) {
            None => {
                rem.push((lm, lc));
                start += 1;
            }
            Some(k) => {
                let q = basis[k][0].0.div_into(&lm);
                sub_mul::<P>(&p[start + 1..], lc, &q, &basis[k][1..], &mut tmp);
                std::mem::swap(&mut p, &mut tmp);
                start = 0;
            }
        }
    }
    rem
}

impl<const P: u32> GroebnerBasis<P> {
    /// Number of variables.
    pub fn nvars(&self) -> usize {
        self.nvars
    }
    /// Number of basis polynomials.
    pub fn len(&self) -> usize {
        self.polys.len()
    }
    /// Whether the basis is empty (the zero ideal).
    pub fn is_empty(&self) -> bool {
        self.polys.is_empty()
    }
    /// The basis polynomials (monic, sorted by increasing grevlex leading monomial).
    pub fn polys(&self) -> Vec<Poly<Fp<P>>> {
        self.polys
            .iter()
            .map(|p| from_spoly::<P>(p, self.nvars))
            .collect()
    }
    /// The leading monomials (grevlex), increasing.
    pub fn leading_monomials(&self) -> Vec<Monomial> {
        self.polys
            .iter()
            .map(|p| p[0].0.to_monomial(self.nvars))
            .collect()
    }
    pub(crate) fn leading_packed(&self) -> Vec<Mon> {
        self.polys.iter().map(|p| p[0].0).collect()
    }
    /// The normal form (remainder on division by the basis) of `p`; it is supported on
    /// standard monomials and is zero exactly when `p` is in the ideal.
    ///
    /// [`GroebnerError::DegreeTooLarge`] if a term of `p` exceeds the packed degree bounds,
    /// [`GroebnerError::VariableCount`] if `p` has another variable count.
    pub fn normal_form(&self, p: &Poly<Fp<P>>) -> Result<Poly<Fp<P>>, GroebnerError> {
        if p.nvars() != self.nvars && !p.is_zero() {
            return Err(GroebnerError::VariableCount {
                index: 0,
                got: p.nvars(),
                expected: self.nvars,
            });
        }
        let s = to_spoly::<P>(p, &self.weights)?;
        let idx: Vec<usize> = (0..self.polys.len()).collect();
        let r = normal_form_raw::<P>(s, &self.polys, &idx);
        Ok(from_spoly::<P>(&r, self.nvars))
    }
    /// Whether `p` lies in the ideal (as [`Self::normal_form`], whose errors it passes on).
    pub fn contains(&self, p: &Poly<Fp<P>>) -> Result<bool, GroebnerError> {
        Ok(self.normal_form(p)?.is_zero())
    }
    /// Checks that the ideal is zero-dimensional (every variable has a pure power among the
    /// leading monomials), naming the variables `x0, x1, ...` in the error.
    pub fn check_zero_dimensional(&self) -> Result<(), GroebnerError> {
        let names: Vec<String> = (0..self.nvars).map(|i| format!("x{i}")).collect();
        self.check_zero_dimensional_named(&names)
    }
    /// [`Self::check_zero_dimensional`] with the given variable names in the error.
    pub fn check_zero_dimensional_named(&self, names: &[String]) -> Result<(), GroebnerError> {
        let lms = self.leading_packed();
        let missing: Vec<String> = (0..self.nvars)
            .filter(|&v| {
                !lms.iter()
                    .any(|m| m.exp(v) > 0 && (0..self.nvars).all(|w| w == v || m.exp(w) == 0))
            })
            .map(|v| names.get(v).cloned().unwrap_or_else(|| format!("x{v}")))
            .collect();
        if missing.is_empty() {
            Ok(())
        } else {
            Err(GroebnerError::PositiveDimensional { missing })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{MonomialOrder, P1};
    type F = Fp<P1>;

    fn var(n: usize, i: usize) -> Poly<F> {
        Poly::var(n, i)
    }
    fn c(n: usize, v: i64) -> Poly<F> {
        Poly::constant(n, F::new(v))
    }

    #[test]
    fn packed_order_is_grevlex() {
        let all = Monomial::all_up_to_degree(4, 4, MonomialOrder::Grevlex);
        for a in &all {
            for b in &all {
                let (pa, pb) = (
                    Mon::from_monomial_weighted(a, &[]).unwrap(),
                    Mon::from_monomial_weighted(b, &[]).unwrap(),
                );
                assert_eq!(pa.cmp(&pb), MonomialOrder::Grevlex.cmp(a, b));
                assert_eq!(pa.divides(&pb), a.divides(b));
                assert_eq!(pa.mul(&pb).to_monomial(4), a.mul(b));
                assert_eq!(pa.lcm(&pb, 4, &[]).to_monomial(4), a.lcm(b));
            }
        }
    }

    #[test]
    fn circle_and_line() {
        // x^2 + y^2 - 1, x - y: two solutions.
        let n = 2;
        let (x, y) = (var(n, 0), var(n, 1));
        let f1 = x.mul(&x).add(&y.mul(&y)).sub(&c(n, 1));
        let f2 = x.sub(&y);
        let gb = groebner(n, &[f1.clone(), f2.clone()]).unwrap();
        assert_eq!(gb.len(), 2);
        gb.check_zero_dimensional().unwrap();
        assert!(gb.contains(&f1).unwrap() && gb.contains(&f2).unwrap());
        assert!(!gb.contains(&x).unwrap());
        // Leading monomials: x and y^2.
        assert_eq!(
            gb.leading_monomials(),
            vec![Monomial(vec![1, 0]), Monomial(vec![0, 2])]
        );
    }

    #[test]
    fn inconsistent_and_positive_dimensional() {
        let n = 2;
        let x = var(n, 0);
        let e = groebner(n, &[x.clone(), x.sub(&c(n, 1))]).unwrap_err();
        assert_eq!(e, GroebnerError::Inconsistent);
        let gb = groebner(n, &[x.mul(&var(n, 1))]).unwrap();
        let e = gb
            .check_zero_dimensional_named(&["u".into(), "v".into()])
            .unwrap_err();
        assert_eq!(
            e,
            GroebnerError::PositiveDimensional {
                missing: vec!["u".into(), "v".into()]
            }
        );
        assert!(e.to_string().contains("no pure power of u, v"));
    }

    #[test]
    fn cyclic4_is_positive_free_and_ideal_members_reduce_to_zero() {
        // Katsura-3: a zero-dimensional system with 8 solutions.
        let n = 4;
        let x: Vec<Poly<F>> = (0..n).map(|i| var(n, i)).collect();
        let two = c(n, 2);
        let f1 = x[0]
            .add(&two.mul(&x[1]))
            .add(&two.mul(&x[2]))
            .add(&two.mul(&x[3]))
            .sub(&c(n, 1));
        let f2 = x[0]
            .mul(&x[0])
            .add(&two.mul(&x[1].mul(&x[1])))
            .add(&two.mul(&x[2].mul(&x[2])))
            .add(&two.mul(&x[3].mul(&x[3])))
            .sub(&x[0]);
        let f3 = two
            .mul(&x[0].mul(&x[1]))
            .add(&two.mul(&x[1].mul(&x[2])))
            .add(&two.mul(&x[2].mul(&x[3])))
            .sub(&x[1]);
        let f4 = two
            .mul(&x[0].mul(&x[2]))
            .add(&x[1].mul(&x[1]))
            .add(&two.mul(&x[1].mul(&x[3])))
            .sub(&x[2]);
        let fs = [f1, f2, f3, f4];
        let gb = groebner(n, &fs).unwrap();
        gb.check_zero_dimensional().unwrap();
        for f in &fs {
            assert!(gb.contains(f).unwrap());
            assert!(gb.contains(&f.mul(&x[2]).add(&f.mul(&x[0]))).unwrap());
        }
        // Reducedness: no term of any element is divisible by another leading monomial.
        let lms = gb.leading_monomials();
        for (k, p) in gb.polys().iter().enumerate() {
            for (m, _) in p.terms() {
                for (o, l) in lms.iter().enumerate() {
                    if o != k {
                        assert!(!l.divides(m));
                    }
                }
            }
        }
    }

    #[test]
    fn weighted_order_changes_leading_monomials_not_the_ideal() {
        // y - x^2 and x^3 - 2: under grevlex the leading monomials are x^2 and x*y (3
        // solutions, standard monomials 1, x, y); with weights (1, 3), y outweighs x^2, so y
        // leads the first and the basis is 1, x, x^2.
        let n = 2;
        let (x, y) = (var(n, 0), var(n, 1));
        let f1 = y.sub(&x.mul(&x));
        let f2 = x.mul(&x).mul(&x).sub(&c(n, 2));
        let opts = GroebnerOptions {
            weights: vec![1, 3],
            ..GroebnerOptions::default()
        };
        let weighted = groebner_with(n, &[f1.clone(), f2.clone()], &opts).unwrap();
        let plain = groebner(n, &[f1.clone(), f2.clone()]).unwrap();
        let standard = |gb: &GroebnerBasis<P1>| {
            let mut b = crate::quotient::standard_monomials(gb).unwrap();
            b.sort();
            b
        };
        assert_eq!(
            standard(&weighted),
            vec![
                Monomial(vec![0, 0]),
                Monomial(vec![1, 0]),
                Monomial(vec![2, 0])
            ]
        );
        assert_eq!(standard(&plain).len(), 3);
        assert_ne!(standard(&plain), standard(&weighted));
        for f in [&f1, &f2] {
            assert!(weighted.contains(f).unwrap() && plain.contains(f).unwrap());
        }
        // The normal form is taken in the weighted order: y reduces to x^2.
        assert_eq!(weighted.normal_form(&y).unwrap(), x.mul(&x));
        // All-one weights are grevlex; a zero weight or a wrong length is refused.
        let ones = GroebnerOptions {
            weights: vec![1, 1],
            ..GroebnerOptions::default()
        };
        let g1 = groebner_with(n, &[f1.clone(), f2.clone()], &ones).unwrap();
        assert_eq!(g1.leading_monomials(), plain.leading_monomials());
        for bad in [vec![1, 0], vec![1, 2, 3]] {
            let o = GroebnerOptions {
                weights: bad,
                ..GroebnerOptions::default()
            };
            let e = groebner_with(n, &[f1.clone(), f2.clone()], &o).unwrap_err();
            assert!(matches!(e, GroebnerError::Weights { .. }), "{e}");
        }
    }
}
