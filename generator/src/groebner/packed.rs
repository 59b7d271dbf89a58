//! Packed monomials (see the module documentation of `crate::groebner`): two `u128`
//! words, exponents one per byte and a grevlex key, both additive under multiplication.

use super::*;

/// A packed monomial (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Mon {
    /// Weighted degree under the order's weights (the total degree when unweighted).
    wdeg: u32,
    key: u128,
    exps: u128,
}

const HIGH_BITS: u128 = 0x8080_8080_8080_8080_8080_8080_8080_8080;

impl Mon {
    pub(crate) fn from_exps(e: &[u32]) -> Mon {
        Mon::from_exps_weighted(e, &[])
    }
    /// The packed monomial of exponents `e` under the weights `weights` (empty: all 1).
    pub(crate) fn from_exps_weighted(e: &[u32], weights: &[u32]) -> Mon {
        let n = e.len();
        let mut exps = 0u128;
        for (i, &x) in e.iter().enumerate() {
            exps |= (x as u128) << (8 * i);
        }
        let deg: u32 = e.iter().sum();
        let mut key = (deg as u128) << 120;
        let mut s = 0u32;
        // Field j (j = 1..n-1) holds S_{n-j} = e_0 + ... + e_{n-j-1}.
        let mut prefix = vec![0u32; n + 1];
        for i in 0..n {
            s += e[i];
            prefix[i + 1] = s;
        }
        for j in 1..n {
            key |= (prefix[n - j] as u128) << (8 * (15 - j));
        }
        Mon {
            wdeg: weighted_degree(e, weights),
            key,
            exps,
        }
    }
    #[inline]
    pub(crate) fn exp(&self, i: usize) -> u32 {
        ((self.exps >> (8 * i)) & 0xff) as u32
    }
    #[inline]
    pub(crate) fn degree(&self) -> u32 {
        (self.key >> 120) as u32
    }
    /// The total degree summed from the exponents of the first `n` variables: exact where
    /// the key's 8-bit degree field would have wrapped (an lcm or product past
    /// [`MAX_TOTAL_DEGREE`]).
    #[inline]
    pub(crate) fn degree_of(&self, n: usize) -> u32 {
        (0..n).map(|i| self.exp(i)).sum()
    }
    /// Whether the exponents (of the first `n` variables) and the total degree stay within
    /// the packing's bounds.
    #[inline]
    pub(crate) fn fits(&self, n: usize) -> bool {
        (0..n).all(|i| self.exp(i) <= MAX_EXPONENT) && self.degree_of(n) <= MAX_TOTAL_DEGREE
    }
    #[inline]
    pub(crate) fn mul(&self, o: &Mon) -> Mon {
        Mon {
            wdeg: self.wdeg + o.wdeg,
            key: self.key + o.key,
            exps: self.exps + o.exps,
        }
    }
    /// Whether `self` divides `o`.
    #[inline]
    pub(crate) fn divides(&self, o: &Mon) -> bool {
        ((o.exps | HIGH_BITS) - self.exps) & HIGH_BITS == HIGH_BITS
    }
    /// `o / self`, assuming `self` divides `o`.
    #[inline]
    pub(crate) fn div_into(&self, o: &Mon) -> Mon {
        Mon {
            wdeg: o.wdeg - self.wdeg,
            key: o.key - self.key,
            exps: o.exps - self.exps,
        }
    }
    pub(crate) fn lcm(&self, o: &Mon, n: usize, weights: &[u32]) -> Mon {
        let e: Vec<u32> = (0..n).map(|i| self.exp(i).max(o.exp(i))).collect();
        Mon::from_exps_weighted(&e, weights)
    }
    #[inline]
    pub(crate) fn coprime(&self, o: &Mon, n: usize) -> bool {
        (0..n).all(|i| self.exp(i) == 0 || o.exp(i) == 0)
    }
    pub(crate) fn from_monomial_weighted(
        m: &Monomial,
        weights: &[u32],
    ) -> Result<Mon, GroebnerError> {
        let e: Vec<u32> = m.0.iter().map(|&x| x as u32).collect();
        if e.iter().any(|&x| x > MAX_EXPONENT) || e.iter().sum::<u32>() > MAX_TOTAL_DEGREE {
            return Err(GroebnerError::DegreeTooLarge(MAX_TOTAL_DEGREE));
        }
        Ok(Mon::from_exps_weighted(&e, weights))
    }
    pub(crate) fn to_monomial(self, n: usize) -> Monomial {
        Monomial((0..n).map(|i| self.exp(i) as u16).collect())
    }
}

impl PartialOrd for Mon {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Mon {
    /// Weighted degree, then grevlex (plain grevlex when unweighted).
    fn cmp(&self, other: &Self) -> Ordering {
        (self.wdeg, self.key).cmp(&(other.wdeg, other.key))
    }
}

/// Whether `weights` has one weight from 1 to [`MAX_WEIGHT`] for each of `nvars` variables.
pub fn weights_fit(weights: &[u32], nvars: usize) -> bool {
    weights.len() == nvars && weights.iter().all(|w| (1..=MAX_WEIGHT).contains(w))
}

/// `sum_i weights[i] * e[i]`; empty weights are all 1 (the total degree).
fn weighted_degree(e: &[u32], weights: &[u32]) -> u32 {
    if weights.is_empty() {
        e.iter().sum()
    } else {
        e.iter().zip(weights).map(|(&x, &w)| x * w).sum()
    }
}
