//! Exact and floating-point coefficient arithmetic and sparse multivariate polynomials.
//!
//! Everything the generator computes flows through the [`Ring`] trait: the same polynomial
//! code runs over the prime fields [`Fp`] (Gröbner work), the rationals [`Q`] (exact
//! symbolic coefficients), `f64` (interpreted solving) and polynomials themselves
//! (`Poly<Poly<Q>>`: polynomials in the unknowns whose coefficients are polynomials in the data).

mod field;
mod monomial;
mod poly;

pub use field::{Field, Fp, Ring, P1, P2, Q};
pub use monomial::{Exponent, Monomial, MonomialOrder};
pub use poly::Poly;
