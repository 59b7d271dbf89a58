//! Optional observation of an emitted solver's stages (benchmarks, diagnostics).

/// Called by an emitted `solve_staged` between its stages; each method returns whether to
/// go on (returning `false` makes the solver return no solutions at once). The unit type
/// observes nothing, and `solve` is `solve_staged(data, &mut ())`, which compiles to the
/// same code as a solver without observation points.
///
/// Timing `solve_staged` with an observer that stops after a stage gives the cumulative
/// cost up to that stage (coefficients, elimination, action matrix); see
/// `benches/stages.rs` of `rspose`.
pub trait Stages {
    /// The filled `rows x cols` template (row-major), before elimination.
    #[inline(always)]
    fn filled(&mut self, _template: &[f64]) -> bool {
        true
    }
    /// The template after elimination (only the rows the action matrix reads are reduced).
    #[inline(always)]
    fn eliminated(&mut self, _template: &[f64]) -> bool {
        true
    }
    /// The `n x n` action matrix (column-major), before the eigen decomposition.
    #[inline(always)]
    fn action(&mut self, _matrix: &[f64]) -> bool {
        true
    }
}

impl Stages for () {}
