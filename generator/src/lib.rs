//! # mingen — a minimal-solver generator
//!
//! Pipeline (one module per stage, in order):
//! `problem file -> lang (parse, check) -> expand -> eliminate -> instance (Z_p / f64 data)
//!  -> groebner -> quotient (basis, #solutions) -> template (build, shrink) -> emit`,
//! with `interpret` + `audit` solving the same template in f64 without compilation.
//!
//! All algebra is generic over [`algebra::Ring`], so one code path serves exact rationals,
//! the prime fields used for Gröbner bases, `f64`, and traced expressions for code emission.

pub mod algebra;
pub mod audit;
pub mod interpret;
pub mod problem;
pub mod template;
