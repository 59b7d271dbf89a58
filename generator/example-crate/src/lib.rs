//! # mingen-example — minimal solvers generated at build time
//!
//! How a crate uses `mingen` without checking generated code in: `build.rs` runs
//! `mingen::build::Config` on problem files, and each solver is `include!`d from
//! `$OUT_DIR`. The crate depends on `mingen-runtime` only (`mingen` is a
//! build-dependency).
//!
//! - [`gs5pt`]: the 5-point relative pose problem (`templates/gs5pt.mp`), 10 solutions.
//! - one module per problem of the classic corpus, `templates/classic/NAME.mp` (build.rs
//!   compiles the whole directory), e.g. [`relpose_6pt_focal`]: 6-point relative pose with
//!   a shared unknown focal length, 15 solutions.
//!
//! Each module has the emitted `Data`, `Solution`, `solve` and a `Solver` type that
//! implements [`mingen_runtime::MinimalSolver`].

/// The 5-point solver: `E = x E1 + y E2 + z E3 + E4` from a basis of the null space of the
/// five epipolar constraints.
pub mod gs5pt {
    include!(concat!(env!("OUT_DIR"), "/gs5pt.rs"));
}

include!(concat!(env!("OUT_DIR"), "/corpus.rs"));
