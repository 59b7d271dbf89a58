//! Workspace-level integration tests live in `tests/tests/`. The library holds what they
//! share that must be generated at build time: a solver for every problem of the classic
//! corpus (`templates/classic/*.mp`, emitted by `build.rs`), e.g.
//! [`corpus::relpose_6pt_focal`], and three of them again in each form of the coefficient
//! code ([`inline`], [`table`]). Each module has the emitted `Data`, `Solution`, `solve`
//! and a `Solver` type that implements [`mingen_runtime::MinimalSolver`].

/// One module per problem of the classic corpus.
pub mod corpus {
    include!(concat!(env!("OUT_DIR"), "/corpus.rs"));
}

/// Three corpus solvers emitted in the inline form (`mingen::CodeForm::Inline`: straight-line
/// code in `solve`), whatever form `mingen` picks for them by default.
pub mod inline {
    /// `templates/classic/p35pf.mp` in inline form.
    pub mod p35pf {
        include!(concat!(env!("OUT_DIR"), "/inline/p35pf.rs"));
    }
    /// `templates/classic/relpose_5pt_entries.mp` in inline form.
    pub mod relpose_5pt_entries {
        include!(concat!(env!("OUT_DIR"), "/inline/relpose_5pt_entries.rs"));
    }
    /// `templates/classic/relpose_upright_3pt.mp` in inline form (its fold written out as
    /// code).
    pub mod relpose_upright_3pt {
        include!(concat!(env!("OUT_DIR"), "/inline/relpose_upright_3pt.rs"));
    }
}

/// The same three solvers in table form (`mingen::CodeForm::Table`: coefficient functions of
/// bounded size and a fill table), which must compute exactly what the inline form
/// computes.
pub mod table {
    /// `templates/classic/p35pf.mp` in table form.
    pub mod p35pf {
        include!(concat!(env!("OUT_DIR"), "/table/p35pf.rs"));
    }
    /// `templates/classic/relpose_5pt_entries.mp` in table form.
    pub mod relpose_5pt_entries {
        include!(concat!(env!("OUT_DIR"), "/table/relpose_5pt_entries.rs"));
    }
    /// `templates/classic/relpose_upright_3pt.mp` in table form (its fold by the runtime's
    /// plan).
    pub mod relpose_upright_3pt {
        include!(concat!(env!("OUT_DIR"), "/table/relpose_upright_3pt.rs"));
    }
}
