//! # mingen — a minimal-solver generator
//!
//! Pipeline (one module per stage, in order):
//! `problem file -> lang (parse, check) -> expand -> eliminate -> independent -> instance (Z_p / f64 data)
//!  -> groebner -> quotient (basis, #solutions) -> template (search, build, shrink,
//!  validate) -> emit`, with `interpret` + `audit` solving the same template in f64 without
//! compilation. [`pipeline`] is the one module that runs the stages in that order.
//!
//! [`build`] is the build-script API (problem files to solvers in `$OUT_DIR`); the emitted
//! code depends on the `mingen-runtime` crate only.
//!
//! All algebra is generic over [`algebra::Ring`], so one code path serves exact rationals,
//! the prime fields used for Gröbner bases, `f64`, and traced expressions for code emission.

pub mod algebra;
pub mod audit;
pub mod budget;
pub mod build;
pub mod eliminate;
pub mod emit;
pub mod groebner;
pub mod independent;
pub mod instances_file;
pub mod interpret;
pub mod problem;
pub mod quotient;
pub mod report;
mod rewrite;
pub mod template;

// Problem language and its symbolic expansion.
pub mod expand;
pub mod generate;
pub mod instance;
pub mod lang;
pub mod pipeline;

pub use expand::{Problem, ProblemError};
pub use lang::LangError;
