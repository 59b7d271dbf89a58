//! The plan's choice of solution polishing when neither the problem file (`option newton`)
//! nor the command line (`--newton`) makes it.
//!
//! An elimination template loses accuracy by its conditioning, which the algebra does not
//! see: two templates of one problem can differ by orders of magnitude in the residual of
//! their solutions. So the plan measures its own template: [`AUTO_POLISH_INSTANCES`]
//! uniform random instances solved as the emitted solver solves them ([`crate::audit`],
//! unpolished). If the median log10 of the worst normalised residual per instance is above
//! [`AUTO_POLISH_MEDIAN`], or the 99th percentile above [`AUTO_POLISH_TAIL`] (with this many
//! instances: any instance), the solver polishes every solution with
//! [`AUTO_POLISH_STEPS`] Gauss-Newton steps on the original equations; otherwise it does
//! not, since polishing costs a few evaluations of the equations and their gradients per
//! solution, several times a small template's solve. The instances are seeded, so the
//! choice, like the template, is the same on every run.

use crate::audit::{audit_plan, AuditOptions};
use crate::instance::random_data_f64;
use crate::pipeline::SolverPlan;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Instances the plan solves to decide on polishing.
pub const AUTO_POLISH_INSTANCES: usize = 48;
/// Polishing is chosen when the median log10 residual is above this.
pub const AUTO_POLISH_MEDIAN: f64 = -11.0;
/// Polishing is chosen when the 99th percentile of the log10 residual is above this.
pub const AUTO_POLISH_TAIL: f64 = -8.0;
/// The Gauss-Newton steps chosen (polishing converges in one or two from an eliminated
/// solution; a step that does not lower the residual is not kept).
pub const AUTO_POLISH_STEPS: u32 = 2;
/// Seed of the choice's instances, apart from `mingen audit`'s default ones.
const AUTO_POLISH_SEED: u64 = 0x9011_5A17;

/// What the plan measured to choose its polishing ([`SolverPlan::auto_polishing`]).
#[derive(Clone, Debug, PartialEq)]
pub struct AutoPolishing {
    /// The Gauss-Newton steps chosen: 0 or [`AUTO_POLISH_STEPS`].
    pub steps: u32,
    /// Instances solved.
    pub instances: usize,
    /// Their median log10 residual, unpolished.
    pub median_log10_residual: f64,
    /// Their 99th percentile log10 residual, unpolished.
    pub p99_log10_residual: f64,
}

/// Measures `plan`'s template unpolished and chooses the steps (see the module
/// documentation). `None` when the solver cannot polish: more unknowns than
/// `mingen_runtime::MAX_NEWTON_UNKNOWNS`, fewer equations than unknowns, or an exponent
/// above 255 (what `option newton` refuses).
pub(crate) fn choose(plan: &SolverPlan) -> Option<AutoPolishing> {
    if !can_polish(plan) {
        return None;
    }
    let report = audit_plan(
        plan,
        &AuditOptions {
            instances: AUTO_POLISH_INSTANCES,
            seed: AUTO_POLISH_SEED,
            time_limit: None,
        },
    );
    let poor = report.median_log10_residual > AUTO_POLISH_MEDIAN
        || report.p99_log10_residual > AUTO_POLISH_TAIL;
    Some(AutoPolishing {
        steps: if poor { AUTO_POLISH_STEPS } else { 0 },
        instances: report.instances,
        median_log10_residual: report.median_log10_residual,
        p99_log10_residual: report.p99_log10_residual,
    })
}

/// Whether the emitted solver can polish `plan`'s solutions (the conditions of
/// `option newton`), read off the original equations of one instance.
fn can_polish(plan: &SolverPlan) -> bool {
    let unknowns = plan.visible_unknowns();
    let mut rng = ChaCha8Rng::seed_from_u64(AUTO_POLISH_SEED);
    let equations = plan.visible_equations(&random_data_f64(&plan.problem.layout, &mut rng));
    unknowns <= mingen_runtime::MAX_NEWTON_UNKNOWNS
        && equations.len() >= unknowns
        && equations.iter().all(|e| {
            e.terms()
                .all(|(m, _)| m.0[..unknowns].iter().all(|&d| d <= u8::MAX as _))
        })
}
