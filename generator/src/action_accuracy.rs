//! The plan's choice among equally small templates by their accuracy.
//!
//! The search picks the action (the unknown whose multiplication matrix is the solver's
//! eigenproblem) by template area alone. Templates of different actions can be of one size
//! and still fail at very different rates: the action decides which monomial multiples the
//! template eliminates, hence which pivot blocks become nearly singular on which
//! instances, and how far apart the eigenvalues are. So when the solver of the chosen
//! template fails at least [`AUTO_POLISH_FAILURE_RATE`] of the plan's own sample (as
//! returned, polished as chosen; [`crate::polishing`]), the plan searches a template for
//! every other unknown as the action and completes each as it completed the chosen one
//! (its own polishing chosen by its own measurement). The chosen template and those of
//! at most its elimination area are then solved on [`ACCURACY_INSTANCES`] further seeded
//! instances, each polished as it chose, and the one that fails the fewest is kept (ties:
//! the chosen template, then the unknowns in order): the polishing sample is a screen,
//! and rates of one or two percent are told apart on the larger one.
//!
//! The budget: an action is searched only while the search's share of the budget has at
//! least as much time left as the first plan took (an action whose search runs out is not
//! a candidate), and the comparison's solves stop when the whole budget runs out (the
//! rates are then of the instances solved). Where the file or the command line names the
//! action, nothing is compared.

use crate::audit::{audit_plan, AuditOptions};
use crate::budget::Deadline;
use crate::pipeline::SolverPlan;
use crate::polishing::failure_rate;
use crate::AUTO_POLISH_FAILURE_RATE;
use serde_json::{json, Value};

/// Instances each compared template's solver solves.
pub const ACCURACY_INSTANCES: usize = 500;
/// Seed of the comparison's instances, apart from the polishing sample's and the audit's.
const ACCURACY_SEED: u64 = 0xACC0_4A7E;

/// The failure rate of `plan`'s solver, polished as its layout says, on the comparison's
/// instances solved before `deadline` runs out (`None`: none was).
fn measured_failure_rate(plan: &SolverPlan, deadline: &Deadline) -> Option<f64> {
    let report = audit_plan(
        plan,
        &AuditOptions {
            instances: ACCURACY_INSTANCES,
            seed: ACCURACY_SEED,
            // An unbounded budget is no limit.
            time_limit: std::time::Duration::try_from_secs_f64(deadline.remaining()).ok(),
        },
    );
    (report.instances > 0).then(|| report.failures as f64 / report.instances as f64)
}

/// One action the plan compared ([`ActionAccuracy`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ActionTrial {
    /// The action, as `inspect` names it.
    pub action: String,
    /// The template's eliminated size (`None`: no template within the budget).
    pub size: Option<(usize, usize)>,
    /// The failure rate of its solver on the comparison's instances (`None`: not
    /// measured: its template is larger than the chosen one or there is none, or, for the
    /// chosen one, no other was of at most its area).
    pub failure_rate: Option<f64>,
}

/// What the plan measured to choose its action by accuracy ([`SolverPlan::action_accuracy`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ActionAccuracy {
    /// The template the search chose first, then every other unknown's.
    pub tried: Vec<ActionTrial>,
    /// The index in `tried` of the kept template.
    pub kept: usize,
}

impl ActionAccuracy {
    /// JSON object `{"tried": [{"action", "rows", "cols", "failure_rate"}], "kept"}`.
    pub fn to_json(&self) -> Value {
        json!({
            "tried": self.tried.iter().map(|t| json!({
                "action": t.action,
                "rows": t.size.map(|s| s.0),
                "cols": t.size.map(|s| s.1),
                "failure_rate": t.failure_rate,
            })).collect::<Vec<_>>(),
            "kept": self.kept,
        })
    }
}

/// Whether `plan`'s solver fails often enough on its polishing sample for the other
/// actions to be compared ([`AUTO_POLISH_FAILURE_RATE`]).
pub(crate) fn needs_comparison(plan: &SolverPlan) -> bool {
    failure_rate(plan) >= AUTO_POLISH_FAILURE_RATE
}

/// The plan to keep among `plan` and the plans `plan_with(v, area)` of the other visible
/// unknowns `v` as the action (see the module documentation), with what was compared in
/// its [`SolverPlan::action_accuracy`]. `plan_with` searches on `search`, the search's
/// share of the budget, and completes the plan only when its template's elimination area
/// is at most `area` (`Err(size)` otherwise: it is not compared); `deadline` is the whole
/// budget, `first_seconds` what `plan` took.
pub(crate) fn choose(
    plan: SolverPlan,
    search: &Deadline,
    deadline: &Deadline,
    first_seconds: f64,
    mut plan_with: impl FnMut(usize, usize) -> Option<Result<SolverPlan, (usize, usize)>>,
) -> SolverPlan {
    let template = &plan.generated.built.template;
    let names = plan.variable_names();
    let area = template.elimination_area();
    let chosen_action = template.action.single();
    // The chosen template is solved only once another one is to be compared with it.
    let mut rate: Option<Option<f64>> = None;
    let mut tried = vec![ActionTrial {
        action: template.action.display_with(&names),
        size: Some(template.eliminated_size()),
        failure_rate: None,
    }];
    let mut best: Option<(f64, usize, SolverPlan)> = None;
    for v in (0..template.visible_vars()).filter(|&v| Some(v) != chosen_action) {
        let action = names.get(v).cloned().unwrap_or_else(|| format!("x{v}"));
        let other = (search.remaining() >= first_seconds)
            .then(|| plan_with(v, area))
            .flatten();
        let (size, other, other_rate) = match other {
            None => (None, None, None),
            Some(Err(size)) => (Some(size), None, None),
            Some(Ok(other)) if other.generated.built.template.elimination_area() > area => (
                Some(other.generated.built.template.eliminated_size()),
                None,
                None,
            ),
            Some(Ok(other)) => {
                let first = *rate.get_or_insert_with(|| measured_failure_rate(&plan, deadline));
                tried[0].failure_rate = first;
                let r = measured_failure_rate(&other, deadline);
                (
                    Some(other.generated.built.template.eliminated_size()),
                    Some(other),
                    r,
                )
            }
        };
        tried.push(ActionTrial {
            action,
            size,
            failure_rate: other_rate,
        });
        let to_beat = best.as_ref().map(|b| b.0).or(rate.flatten());
        if let (Some(r), Some(b), Some(other)) = (other_rate, to_beat, other) {
            if r < b {
                best = Some((r, tried.len() - 1, other));
            }
        }
    }
    let (mut kept_plan, kept) = match best {
        Some((_, k, other)) => (other, k),
        None => (plan, 0),
    };
    kept_plan.action_accuracy = Some(ActionAccuracy { tried, kept });
    kept_plan
}
