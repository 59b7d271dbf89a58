//! Coefficient rings: the prime fields Z_p, the rationals, and `f64`.

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive, Zero};
use std::fmt;

/// Exact rational numbers (arbitrary precision).
pub type Q = num_rational::BigRational;

/// A commutative ring with unity, as needed by the polynomial code.
///
/// Operations take references and return new values so that the trait also fits
/// heavy coefficient types (big rationals, polynomials, traced expressions).
pub trait Ring: Clone + fmt::Debug {
    /// The additive identity.
    fn zero() -> Self;
    /// The multiplicative identity.
    fn one() -> Self;
    /// Whether this is exactly the additive identity (structural zero for traced values).
    fn is_zero(&self) -> bool;
    /// `self + other`.
    fn add(&self, other: &Self) -> Self;
    /// `self - other`.
    fn sub(&self, other: &Self) -> Self;
    /// `self * other`.
    fn mul(&self, other: &Self) -> Self;
    /// `-self`.
    fn neg(&self) -> Self;
    /// The image of a rational number; `None` where it does not exist (a denominator
    /// divisible by p in Z_p).
    fn from_rational(q: &Q) -> Option<Self>;
    /// Whether this is exactly the multiplicative identity.
    fn is_one(&self) -> bool;
    /// The image of a small integer.
    fn from_i64(n: i64) -> Self {
        Self::from_rational(&Q::from_integer(BigInt::from(n)))
            .expect("integers map into every ring")
    }
}

/// A field: a ring where every non-zero element has an inverse.
pub trait Field: Ring + PartialEq {
    /// The multiplicative inverse; `None` for zero.
    fn inv(&self) -> Option<Self>;
}

/// The prime field Z_P for a prime `P < 2^31`, elements stored reduced in `0..P`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Fp<const P: u32>(pub u32);

/// The default prime for Gröbner work: 2^31 - 1 (a Mersenne prime).
pub const P1: u32 = 2_147_483_647;
/// The confirming prime: the largest prime below 2^31 - 1.
pub const P2: u32 = 2_147_483_629;

impl<const P: u32> Fp<P> {
    /// The element congruent to `n`.
    pub fn new(n: i64) -> Self {
        Fp(n.rem_euclid(P as i64) as u32)
    }
    /// The representative in `0..P`.
    pub fn value(self) -> u32 {
        self.0
    }
    /// The representative in `(-P/2, P/2]`, useful for printing small values.
    pub fn symmetric(self) -> i64 {
        let v = self.0 as i64;
        if v > (P as i64) / 2 {
            v - P as i64
        } else {
            v
        }
    }
    /// `self^e` by square and multiply.
    pub fn pow(self, mut e: u64) -> Self {
        let mut base = self;
        let mut acc = Fp(1 % P);
        while e > 0 {
            if e & 1 == 1 {
                acc = acc * base;
            }
            base = base * base;
            e >>= 1;
        }
        acc
    }
    /// The image of a big integer.
    pub fn from_bigint(n: &BigInt) -> Self {
        let r = n.mod_floor(&BigInt::from(P));
        Fp(r.to_u32().expect("reduced below P"))
    }
}

impl<const P: u32> fmt::Debug for Fp<P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.symmetric())
    }
}

impl<const P: u32> fmt::Display for Fp<P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

impl<const P: u32> std::ops::Add for Fp<P> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        let s = self.0 + o.0; // < 2^32 since both < 2^31
        Fp(if s >= P { s - P } else { s })
    }
}
impl<const P: u32> std::ops::Sub for Fp<P> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Fp(if self.0 >= o.0 {
            self.0 - o.0
        } else {
            self.0 + P - o.0
        })
    }
}
impl<const P: u32> std::ops::Mul for Fp<P> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Fp(((self.0 as u64 * o.0 as u64) % P as u64) as u32)
    }
}
impl<const P: u32> std::ops::Neg for Fp<P> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Fp(if self.0 == 0 { 0 } else { P - self.0 })
    }
}

impl<const P: u32> Ring for Fp<P> {
    fn zero() -> Self {
        Fp(0)
    }
    fn one() -> Self {
        Fp(1)
    }
    fn is_zero(&self) -> bool {
        self.0 == 0
    }
    fn is_one(&self) -> bool {
        self.0 == 1
    }
    fn add(&self, o: &Self) -> Self {
        *self + *o
    }
    fn sub(&self, o: &Self) -> Self {
        *self - *o
    }
    fn mul(&self, o: &Self) -> Self {
        *self * *o
    }
    fn neg(&self) -> Self {
        -*self
    }
    fn from_rational(q: &Q) -> Option<Self> {
        let d = Self::from_bigint(q.denom());
        d.inv().map(|di| Self::from_bigint(q.numer()) * di)
    }
    fn from_i64(n: i64) -> Self {
        Fp::new(n)
    }
}

impl<const P: u32> Field for Fp<P> {
    fn inv(&self) -> Option<Self> {
        // Extended Euclid on (a, P).
        if self.0 == 0 {
            return None;
        }
        let (mut r0, mut r1) = (P as i64, self.0 as i64);
        let (mut s0, mut s1) = (0i64, 1i64);
        while r1 != 0 {
            let q = r0 / r1;
            (r0, r1) = (r1, r0 - q * r1);
            (s0, s1) = (s1, s0 - q * s1);
        }
        debug_assert_eq!(r0, 1, "P must be prime");
        Some(Fp::new(s0))
    }
}

impl Ring for Q {
    fn zero() -> Self {
        Zero::zero()
    }
    fn one() -> Self {
        One::one()
    }
    fn is_zero(&self) -> bool {
        Zero::is_zero(self)
    }
    fn is_one(&self) -> bool {
        One::is_one(self)
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn neg(&self) -> Self {
        -self
    }
    fn from_rational(q: &Q) -> Option<Self> {
        Some(q.clone())
    }
}

impl Field for Q {
    fn inv(&self) -> Option<Self> {
        if Zero::is_zero(self) {
            None
        } else {
            Some(self.recip())
        }
    }
}

impl Ring for f64 {
    fn zero() -> Self {
        0.0
    }
    fn one() -> Self {
        1.0
    }
    fn is_zero(&self) -> bool {
        *self == 0.0
    }
    fn is_one(&self) -> bool {
        *self == 1.0
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn neg(&self) -> Self {
        -self
    }
    fn from_rational(q: &Q) -> Option<Self> {
        // Ratio of the two big integers, robust for values beyond f64 integer range.
        let n = q.numer().to_f64()?;
        let d = q.denom().to_f64()?;
        Some(n / d)
    }
}

impl Field for f64 {
    fn inv(&self) -> Option<Self> {
        if *self == 0.0 {
            None
        } else {
            Some(1.0 / self)
        }
    }
}
