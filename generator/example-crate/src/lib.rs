//! # mingen-example — minimal solvers generated at build time
//!
//! How a crate uses `mingen` without checking generated code in: `build.rs` runs
//! `mingen::build::Config` on problem files, and each solver is `include!`d from
//! `$OUT_DIR`. The crate depends on `mingen-runtime` only (`mingen` is a
//! build-dependency).
//!
//! - [`gs5pt`]: the 5-point relative pose problem (`templates/gs5pt.mp`), 10 solutions.
//! - [`inline`], [`table`]: two corpus solvers again in each form of the coefficient code
//!   (`mingen::emit::CodeForm`).
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

/// Two corpus solvers emitted in the inline form (`mingen::emit::CodeForm::Inline`:
/// straight-line code in `solve`), whatever form `mingen` picks for them by default.
pub mod inline {
    /// `templates/classic/p35pf.mp` in inline form.
    pub mod p35pf {
        include!(concat!(env!("OUT_DIR"), "/inline/p35pf.rs"));
    }
    /// `templates/classic/relpose_5pt_entries.mp` in inline form.
    pub mod relpose_5pt_entries {
        include!(concat!(env!("OUT_DIR"), "/inline/relpose_5pt_entries.rs"));
    }
}

/// The same two solvers in table form (`mingen::emit::CodeForm::Table`: coefficient
/// functions of bounded size and a fill table), which must compute exactly what the
/// inline form computes.
pub mod table {
    /// `templates/classic/p35pf.mp` in table form.
    pub mod p35pf {
        include!(concat!(env!("OUT_DIR"), "/table/p35pf.rs"));
    }
    /// `templates/classic/relpose_5pt_entries.mp` in table form.
    pub mod relpose_5pt_entries {
        include!(concat!(env!("OUT_DIR"), "/table/relpose_5pt_entries.rs"));
    }
}
