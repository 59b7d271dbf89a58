//! The plan's check of a redundant basis (`crate::template`'s `redundant.rs`) against the
//! template with a quotient basis it was grown from.
//!
//! A redundant basis makes the template smaller, and its action matrix larger by its
//! spurious eigenvalues, which the solver drops by the residual of each read-out
//! ([`mingen_runtime::screen_redundant_readout`]). That screen can only be as good as the
//! read-outs are accurate: where a spurious eigenvalue comes close to a solution's, the
//! solution's read-out loses accuracy, and one the screen cannot tell from a spurious
//! read-out is lost. The algebra does not see this, so the plan measures it: both
//! templates solve the same [`REDUNDANT_CHECK_INSTANCES`] seeded uniform random instances
//! as the emitted solvers do (polished by [`AUTO_POLISH_STEPS`] unless the problem sets
//! `option newton`), and the redundant basis is kept only when it returns, on average, as
//! many real solutions as the other within [`REDUNDANT_REAL_TOLERANCE`] (fewer: solutions
//! lost; more: spurious read-outs kept) and fails on at most [`REDUNDANT_EXTRA_FAILURES`]
//! more instances. Where the quotient basis finds fewer than
//! [`REDUNDANT_MIN_REAL_SOLUTIONS`] real solutions in all, nothing is measured and the
//! redundant basis is dropped.

use crate::audit::{audit_plan, AuditOptions};
use crate::pipeline::SolverPlan;
use crate::polishing::AUTO_POLISH_STEPS;
use crate::template::BuiltTemplate;

/// Instances each template solves.
pub const REDUNDANT_CHECK_INSTANCES: usize = 200;
/// How far, relative to the quotient-basis template's, the redundant one's mean number of
/// real solutions may be: fewer is a solution lost, more a spurious read-out kept.
pub const REDUNDANT_REAL_TOLERANCE: f64 = 0.002;
/// The fewest real solutions the quotient-basis template must return over the instances
/// for the comparison to tell anything (uniform data of some problems has real solutions
/// rarely); with fewer, the redundant basis is dropped.
pub const REDUNDANT_MIN_REAL_SOLUTIONS: f64 = 200.0;
/// How many more failing instances the redundant basis may have.
pub const REDUNDANT_EXTRA_FAILURES: usize = 1;
/// Seed of the check's instances, apart from the audit's and the polishing choice's.
const REDUNDANT_CHECK_SEED: u64 = 0x5e1f_ba5e;

/// What the plan measured to keep or drop a redundant basis
/// ([`SolverPlan::redundant_check`]).
#[derive(Clone, Debug, PartialEq)]
pub struct RedundantCheck {
    /// Whether the redundant basis was kept.
    pub kept: bool,
    /// Instances solved by each template.
    pub instances: usize,
    /// Real solutions per solved instance: the redundant basis's, the quotient basis's.
    pub mean_real: (f64, f64),
    /// Failing instances (audit's definition, polished as in the module documentation):
    /// redundant, quotient basis.
    pub failures: (usize, usize),
    /// The redundant template's size (rows, columns), eliminated.
    pub redundant_size: (usize, usize),
    /// Its spurious eigenvalues (basis monomials beyond the solution count).
    pub spurious_eigenvalues: usize,
    /// Smaller templates with a redundant basis measured before it and dropped (rows,
    /// columns), smallest first.
    pub dropped_smaller: Vec<(usize, usize)>,
}

impl RedundantCheck {
    /// The check as JSON (`inspect --json` and `report --json` key `redundant_basis`):
    /// `kept`, `template` `{rows, cols}`, `spurious_eigenvalues`, `instances`, and
    /// `mean_real_solutions` and `failures` as `[redundant, quotient basis]`.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "kept": self.kept,
            "template": { "rows": self.redundant_size.0, "cols": self.redundant_size.1 },
            "spurious_eigenvalues": self.spurious_eigenvalues,
            "instances": self.instances,
            "mean_real_solutions": [self.mean_real.0, self.mean_real.1],
            "failures": [self.failures.0, self.failures.1],
            "dropped_smaller": self.dropped_smaller.iter().map(|(r, c)| [r, c]).collect::<Vec<_>>(),
        })
    }
}

/// Measures a plan whose template has a redundant basis against its quotient-basis
/// alternative and keeps the better (module documentation); nothing for other plans.
pub(crate) fn choose(plan: &mut SolverPlan) -> Option<RedundantCheck> {
    let t = &plan.generated.built.template;
    if t.spurious_eigenvalues == 0 && t.flipped.is_empty() {
        return None;
    }
    let alternative = *plan.generated.built.quotient_basis.take()?;
    let others = std::mem::take(&mut plan.generated.built.redundant_alternatives);
    let options = AuditOptions {
        instances: REDUNDANT_CHECK_INSTANCES,
        seed: REDUNDANT_CHECK_SEED,
        time_limit: None,
    };
    // Failures are compared as the solver would run, polished unless the problem file or
    // the command line sets the steps: the screen's decisions come before polishing, and
    // an unpolished residual that polishing repairs is no lost solution.
    let set_steps = plan.problem.layout.options.newton;
    if set_steps.is_none() {
        plan.problem.layout.options.newton = Some(AUTO_POLISH_STEPS);
    }
    let candidates: Vec<BuiltTemplate> =
        std::iter::once(std::mem::replace(&mut plan.generated.built, alternative))
            .chain(others)
            .collect();
    let quotient = audit_plan(plan, &options);
    let solved = |a: &crate::AuditReport| a.instances - a.solve_errors;
    let measurable =
        quotient.mean_real_solutions * solved(&quotient) as f64 >= REDUNDANT_MIN_REAL_SOLUTIONS;
    // Smallest first; the first that loses nothing is kept. The check reports it, or the
    // smallest when none is kept.
    let mut checks: Vec<RedundantCheck> = Vec::new();
    for grown in candidates {
        let redundant_size = grown.template.eliminated_size();
        let spurious_eigenvalues = grown.template.spurious_eigenvalues;
        let quotient_built = std::mem::replace(&mut plan.generated.built, grown);
        let redundant = audit_plan(plan, &options);
        let grown = std::mem::replace(&mut plan.generated.built, quotient_built);
        let kept = measurable
            && (redundant.mean_real_solutions - quotient.mean_real_solutions).abs()
                <= REDUNDANT_REAL_TOLERANCE * quotient.mean_real_solutions
            && redundant.failures <= quotient.failures + REDUNDANT_EXTRA_FAILURES;
        checks.push(RedundantCheck {
            kept,
            instances: REDUNDANT_CHECK_INSTANCES,
            mean_real: (redundant.mean_real_solutions, quotient.mean_real_solutions),
            failures: (redundant.failures, quotient.failures),
            redundant_size,
            spurious_eigenvalues,
            dropped_smaller: Vec::new(),
        });
        if kept {
            plan.generated.built = grown;
            break;
        }
    }
    let check = if checks.last().is_some_and(|c| c.kept) {
        let mut kept = checks.pop();
        if let Some(k) = &mut kept {
            k.dropped_smaller = checks.iter().map(|c| c.redundant_size).collect();
        }
        kept
    } else {
        checks.into_iter().next()
    };
    plan.problem.layout.options.newton = set_steps;
    check
}
