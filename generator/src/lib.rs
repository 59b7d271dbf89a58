//! # mingen — a minimal-solver generator
//!
//! A problem file (`.mp`, the language of `templates/README.md`) becomes a Rust solver
//! whose only dependency is the `mingen-runtime` crate.
//!
//! - In a build script, [`build::Config`] turns a crate's problem files into solvers in
//!   `$OUT_DIR`, in the manner of `prost-build`.
//! - Otherwise, [`plan_file`] (or [`plan_source`], or [`plan`] on a parsed [`Problem`])
//!   runs the algebra once and returns a [`SolverPlan`]; [`emit_plan_in`] writes its solver
//!   in either [`CodeForm`], and [`audit_plan`] solves its template numerically on random
//!   instances ([`AuditReport`]); [`report()`] tabulates a set of problem files.
//! - [`TemplateOptions`] steers planning (budget, actions, bases, the problem file's
//!   `option` lines overridden through [`ProblemOptions`]).
//!
//! The stages behind them (language, expansion, Gröbner bases, template search, emission,
//! the interpreter) are private: `ARCHITECTURE.md` §2 describes them.

mod action_accuracy;
mod algebra;
mod audit;
mod budget;
pub mod build;
mod eliminate;
mod emit;
mod expand;
mod groebner;
mod independent;
mod instance;
mod instances_file;
mod interpret;
mod lang;
mod parallel;
mod pipeline;
mod polishing;
mod problem;
mod quotient;
mod redundancy;
mod report;
mod rewrite;
mod symmetry;
mod system;
mod template;

pub use action_accuracy::{ActionAccuracy, ActionTrial, ACCURACY_INSTANCES};
pub use audit::{
    audit_plan, audit_plan_on, audit_plan_planted, AuditOptions, AuditReport, PlantedStats,
    PolishingStats, MAX_INSTANCES,
};
pub use budget::{Budget, Exhausted};
pub use emit::{CodeForm, EmitError};
pub use expand::{EvalError, Problem, ProblemError, MAX_PROBLEM_FILE_BYTES};
pub use lang::LangError;
pub use pipeline::{
    emit_plan_from, emit_plan_in, plan, plan_file, plan_files, plan_source, PipelineError,
    SolverPlan,
};
pub use polishing::{
    AutoPolishing, AUTO_POLISH_FAILURE_RATE, AUTO_POLISH_INSTANCES, AUTO_POLISH_MEDIAN,
    AUTO_POLISH_MORE_INSTANCES, AUTO_POLISH_P99, AUTO_POLISH_STEPS, AUTO_POLISH_STEP_CHOICES,
    POOR_CHECK_MAX_SHARE,
};
pub use problem::{PolynomialSaturation, ProblemOptions};
pub use redundancy::{
    RedundantCheck, REDUNDANT_CHECK_INSTANCES, REDUNDANT_EXTRA_FAILURES,
    REDUNDANT_MIN_REAL_SOLUTIONS, REDUNDANT_REAL_TOLERANCE,
};
pub use report::{
    report, report_with, to_json, to_markdown, PublishedSizes, ReportError, ReportRow,
};
pub use symmetry::SignFold;
pub use template::{ActionChoice, TemplateOptions};

/// The stages, for this package's binary, tests and examples and for the workspace's
/// tests, which check them one by one. Not part of the API: anything here may change.
#[doc(hidden)]
pub mod __internal {
    /// Polynomials and the rings they are generic over.
    pub mod algebra {
        pub use crate::algebra::*;
    }
    /// Numerical audit of a template.
    pub mod audit {
        pub use crate::audit::*;
    }
    /// Wall-clock and memory bounds of planning.
    pub mod budget {
        pub use crate::budget::*;
    }
    /// Linear elimination of unknowns.
    pub mod eliminate {
        pub use crate::eliminate::*;
    }
    /// Code emission.
    pub mod emit {
        pub use crate::emit::*;
    }
    /// Gröbner bases over Z_p.
    pub mod groebner {
        pub use crate::groebner::*;
    }
    /// Random instances of a problem's data.
    pub mod instance {
        pub use crate::instance::*;
    }
    /// Instance and solution files of `mingen audit`.
    pub mod instances_file {
        pub use crate::instances_file::*;
    }
    /// The template solved numerically without compiling.
    pub mod interpret {
        pub use crate::interpret::*;
    }
    /// The problem language.
    pub mod lang {
        pub use crate::lang::*;
    }
    /// Planning and emission of one problem.
    pub mod pipeline {
        pub use crate::pipeline::*;
    }
    /// A problem's declared symbols and options.
    pub mod problem {
        pub use crate::problem::*;
    }
    /// Quotient basis and solution count.
    pub mod quotient {
        pub use crate::quotient::*;
    }
    /// Sign symmetry: folding and unfolding.
    pub mod symmetry {
        pub use crate::symmetry::*;
    }
    /// A problem as a family of polynomial systems.
    pub mod system {
        pub use crate::system::*;
    }
    /// Elimination templates.
    pub mod template {
        pub use crate::template::*;
    }
}
