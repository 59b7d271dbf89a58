//! The plan's choice of solution polishing when neither the problem file (`option newton`)
//! nor the command line (`--newton`) makes it.
//!
//! An elimination template loses accuracy by its conditioning, which the algebra does not
//! see: two templates of one problem can differ by orders of magnitude in the residual of
//! their solutions. So the plan measures its own template: [`AUTO_POLISH_INSTANCES`]
//! uniform random instances solved as the emitted solver solves them ([`crate::audit`],
//! unpolished). The solver polishes every solution with [`AUTO_POLISH_STEPS`] Gauss-Newton
//! steps on the original equations if the median log10 of the worst normalised residual per
//! instance is above [`AUTO_POLISH_MEDIAN`], or if at least [`AUTO_POLISH_FAILURE_RATE`] of
//! the instances fail (a residual above `audit::FAILURE_RESIDUAL`, a missed real solution,
//! or no solve at all): at least 2 of the first 100, or, after exactly one, at least 3 of
//! 500 once [`AUTO_POLISH_MORE_INSTANCES`] more are solved (a rate this low is not told
//! apart from zero by 100 instances). The rate is half the audit's target of 1 %, a margin
//! for the estimate. It polishes too when the 99th percentile is above [`AUTO_POLISH_P99`],
//! within two orders of magnitude of the failure residual: the sample's worst instances
//! are that close to failing, so failures at a rate it cannot resolve are to be expected.
//! Otherwise it does not polish, since polishing costs a few evaluations of the equations
//! and their gradients per solution, up to several times a small template's solve; the
//! solver then still gives a poor solution (worst relative residual above
//! `mingen_runtime::POOR_SOLUTION_RESIDUAL`) two steps, where checking each solution's
//! residual is cheap beside the solve ([`POOR_CHECK_MAX_SHARE`]).
//! Where it polishes, the same instances are measured polished (two steps on a copy of
//! each solution of the same solves, four and eight solved again): if two steps leave
//! the sample failing by the same tests (the failure rate or the 99th percentile), four
//! and then eight are tried ([`AUTO_POLISH_STEP_CHOICES`]; a solution at rounding level
//! takes no step, so only the poor ones pay for them), and the fewest steps that pass, or
//! else that fail the fewest instances, are chosen. Steps that pass with at most one
//! failure in the first 100 are confirmed on [`AUTO_POLISH_MORE_INSTANCES`] more: the
//! solutions polishing cannot bring in are a template's stragglers, a rate near the
//! threshold that 100 instances do not resolve. The instances are seeded, so the
//! choice, like the template, is the same on every run.

use crate::algebra::Poly;
use crate::audit::{audit_plan, AuditOptions, COMPARISON_NEWTON_STEPS};
use crate::emit::polish::check_polishable;
use crate::instance::random_data_f64;
use crate::pipeline::SolverPlan;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Instances the plan solves to decide on polishing.
pub const AUTO_POLISH_INSTANCES: usize = 100;
/// Instances solved besides when the first ones gave one failure.
pub const AUTO_POLISH_MORE_INSTANCES: usize = 400;
/// The failure rate from which the plan polishes.
pub const AUTO_POLISH_FAILURE_RATE: f64 = 0.005;
/// Polishing is chosen when the median log10 residual is above this.
pub const AUTO_POLISH_MEDIAN: f64 = -11.0;
/// Polishing is chosen when the 99th percentile of the log10 residual (of the first
/// [`AUTO_POLISH_INSTANCES`]) is above this.
pub const AUTO_POLISH_P99: f64 = -8.0;
/// The Gauss-Newton steps chosen first (polishing converges in one or two from an
/// eliminated solution; a step that does not lower the residual is not kept).
pub const AUTO_POLISH_STEPS: u32 = 2;

/// The steps tried in turn while the polished sample still fails (see the module
/// documentation).
pub const AUTO_POLISH_STEP_CHOICES: [u32; 3] = [AUTO_POLISH_STEPS, 4, 8];
/// Seed of the choice's instances, apart from `mingen audit`'s default ones.
const AUTO_POLISH_SEED: u64 = 0x9011_5A17;

/// What the plan measured to choose its polishing ([`SolverPlan::auto_polishing`]).
#[derive(Clone, Debug, PartialEq)]
pub struct AutoPolishing {
    /// The Gauss-Newton steps chosen: 0 or one of [`AUTO_POLISH_STEP_CHOICES`].
    pub steps: u32,
    /// Instances solved.
    pub instances: usize,
    /// The median log10 residual of the first [`AUTO_POLISH_INSTANCES`], unpolished.
    pub median_log10_residual: f64,
    /// Their 99th percentile log10 residual, unpolished.
    pub p99_log10_residual: f64,
    /// The failing instances among all `instances`, unpolished.
    pub failures: usize,
    /// Instances solved with the chosen steps (`instances` when none are chosen): the
    /// sample's further instances are drawn for each polishing on its own rule.
    pub chosen_instances: usize,
    /// The failing instances among `chosen_instances`, polished by the chosen steps.
    pub chosen_failures: usize,
    /// With no steps chosen: whether the solver still polishes its poor solutions
    /// ([`crate::SolverPlan::polishes_poor_solutions_only`]), which it does where the
    /// check is cheap beside the solve ([`POOR_CHECK_MAX_SHARE`]).
    pub polish_poor: bool,
}

/// The solver of a plan that polishes no solution checks each one's residual (and polishes
/// the poor ones, `mingen_runtime::POOR_SOLUTION_RESIDUAL`) when the check is cheap beside
/// the solve: the terms it evaluates (the original equations' terms times the solution
/// count) at most this share of the solve's estimated operations (the entries of the
/// matrices it eliminates, [`crate::template::EliminationTemplate::elimination_area`],
/// plus the eigenproblem's `10 n^3` for a basis of `n`, `n^2` for a companion action's
/// polynomial). A closed form or a template of a few entries, whose solve costs about as
/// much as evaluating the equations at every solution, does without it.
pub const POOR_CHECK_MAX_SHARE: f64 = 0.3;

impl AutoPolishing {
    /// The failure rate of the plan's sample as its solver returns it (polished by the
    /// chosen steps).
    pub fn chosen_failure_rate(&self) -> f64 {
        self.chosen_failures as f64 / self.chosen_instances.max(1) as f64
    }
}

/// Measures `plan`'s template unpolished and chooses the steps (see the module
/// documentation); `plan`'s own polishing is as it was on return. `None` when the solver
/// cannot polish (what `option newton` refuses).
pub(crate) fn choose(plan: &mut SolverPlan) -> Option<AutoPolishing> {
    if !can_polish(plan) {
        return None;
    }
    let given = plan.problem.layout.options.newton;
    plan.problem.layout.options.newton = Some(0);
    let (unpolished, two_steps) = measure(plan, true);
    let mut steps = 0;
    let mut chosen = (unpolished.failures, unpolished.instances);
    if unpolished.needs_polishing() {
        // The fewest steps that pass, else those that fail the fewest instances.
        let mut best: Option<(usize, u32, usize)> = None;
        let mut two_steps = two_steps;
        for k in AUTO_POLISH_STEP_CHOICES {
            plan.problem.layout.options.newton = Some(k);
            let polished = match two_steps.take() {
                Some(s) if k as usize == COMPARISON_NEWTON_STEPS => s,
                _ => measure(plan, true).0,
            };
            let passes = !polished.fails();
            if passes || best.map_or(true, |(f, _, _)| polished.failures < f) {
                best = Some((polished.failures, k, polished.instances));
            }
            if passes {
                break;
            }
        }
        if let Some((failures, k, instances)) = best {
            steps = k;
            chosen = (failures, instances);
        }
    }
    plan.problem.layout.options.newton = given;
    let polish_poor = steps == 0 && poor_check_is_cheap(plan);
    Some(AutoPolishing {
        polish_poor,
        steps,
        instances: unpolished.instances,
        median_log10_residual: unpolished.median_log10_residual,
        p99_log10_residual: unpolished.p99_log10_residual,
        failures: unpolished.failures,
        chosen_instances: chosen.1,
        chosen_failures: chosen.0,
    })
}

/// The failure rate of `plan`'s solver on the plan's sample, polished as its layout says:
/// read off [`SolverPlan::auto_polishing`] where the plan chose its polishing, measured
/// otherwise (the file or the command line set it).
pub(crate) fn failure_rate(plan: &SolverPlan) -> f64 {
    match &plan.auto_polishing {
        Some(a) => a.chosen_failure_rate(),
        None => {
            let sample = measure(plan, false).0;
            sample.failures as f64 / sample.instances.max(1) as f64
        }
    }
}

/// The plan's sample as its solver solves it (polished as its layout says).
struct Sample {
    instances: usize,
    median_log10_residual: f64,
    p99_log10_residual: f64,
    failures: usize,
}

impl Sample {
    /// Whether a solver that solves as this sample says is to polish: its median, or
    /// [`Sample::fails`].
    fn needs_polishing(&self) -> bool {
        self.median_log10_residual > AUTO_POLISH_MEDIAN || self.fails()
    }
    /// The tests beside the median: the 99th percentile, the failure rate.
    fn fails(&self) -> bool {
        self.p99_log10_residual > AUTO_POLISH_P99
            || self.failures as f64 >= AUTO_POLISH_FAILURE_RATE * self.instances as f64
    }
}

/// Solves the plan's [`AUTO_POLISH_INSTANCES`] seeded instances, and
/// [`AUTO_POLISH_MORE_INSTANCES`] more when exactly one fails (one failure in 100 tells a
/// rate above the threshold from one below it no better than none does) or, when
/// `confirm` (the choice of polishing), when polishing is what makes the sample pass with
/// at most one failure: the choice then rests on 500 instances (polishing rescues a
/// failing template only where its solutions are near enough to converge, and 100
/// instances do not show a straggler rate near the threshold).
///
/// Solved unpolished, the same solves give the sample polished by
/// [`COMPARISON_NEWTON_STEPS`] too (the audit's comparison polishes a copy of each
/// solution, as the solver would): returned second, with its own rule for the further
/// instances, so that the template is solved once for both. Not for a redundant basis,
/// whose spurious read-outs are told apart after polishing.
fn measure(plan: &SolverPlan, confirm: bool) -> (Sample, Option<Sample>) {
    let run = |instances, seed| {
        audit_plan(
            plan,
            &AuditOptions {
                instances,
                seed,
                time_limit: None,
            },
        )
    };
    let report = run(AUTO_POLISH_INSTANCES, AUTO_POLISH_SEED);
    let comparable = plan.problem.layout.options.newton == Some(0)
        && plan.generated.built.template.spurious_eigenvalues == 0;
    let polished = report
        .other_polishing
        .as_ref()
        .filter(|o| comparable && o.newton_steps == COMPARISON_NEWTON_STEPS);
    let first = Sample {
        instances: report.instances,
        median_log10_residual: report.median_log10_residual,
        p99_log10_residual: report.p99_log10_residual,
        failures: report.failures,
    };
    let polishing = plan.problem.layout.options.newton.is_some_and(|k| k > 0);
    let rescued = |failures: usize| confirm && failures <= 1;
    let more = (report.failures == 1
        || (polishing && rescued(report.failures))
        || polished.is_some_and(|o| rescued(o.failures) && first.needs_polishing()))
    .then(|| run(AUTO_POLISH_MORE_INSTANCES, AUTO_POLISH_SEED + 1));
    // The further instances count for an unpolished sample after exactly one failure of
    // the first, for a polished one after at most one.
    let sample = |failures: usize, median, p99, more: Option<(usize, usize)>, polished: bool| {
        let counts = failures == 1 || (polished && failures == 0);
        let (extra_instances, extra_failures) = more.filter(|_| counts).unwrap_or((0, 0));
        Sample {
            instances: report.instances + extra_instances,
            median_log10_residual: median,
            p99_log10_residual: p99,
            failures: failures + extra_failures,
        }
    };
    let unpolished = sample(
        report.failures,
        report.median_log10_residual,
        report.p99_log10_residual,
        more.as_ref().map(|m| (m.instances, m.failures)),
        polishing,
    );
    let polished = polished.map(|o| {
        let more = more
            .as_ref()
            .and_then(|m| Some((m.instances, m.other_polishing.as_ref()?.failures)));
        sample(
            o.failures,
            o.median_log10_residual,
            o.p99_log10_residual,
            more,
            true,
        )
    });
    (unpolished, polished)
}

/// Whether checking every solution's residual costs little beside `plan`'s solve
/// ([`POOR_CHECK_MAX_SHARE`]); the terms are counted on one seeded instance.
fn poor_check_is_cheap(plan: &SolverPlan) -> bool {
    let terms: usize = sample_equations(plan)
        .iter()
        .map(|e| e.terms().count())
        .sum();
    let template = &plan.generated.built.template;
    let n = template.basis.len();
    let eigen = match template.companion_unknown() {
        Some(_) => n * n,
        None => EIGEN_OPERATIONS_PER_CUBE * n * n * n,
    };
    let solve = template.elimination_area() + eigen;
    (terms * plan.solution_count()) as f64 <= POOR_CHECK_MAX_SHARE * solve as f64
}

/// Operations of a real eigenproblem of size `n` per `n^3` (the Hessenberg reduction and
/// the QR sweeps, about `10 n^3`), in the estimate of [`POOR_CHECK_MAX_SHARE`].
const EIGEN_OPERATIONS_PER_CUBE: usize = 10;

/// Whether the emitted solver can polish `plan`'s solutions (what `option newton` needs,
/// `emit::polish::check_polishable`), read off the original equations of one instance.
fn can_polish(plan: &SolverPlan) -> bool {
    check_polishable(plan.visible_unknowns(), &sample_equations(plan)).is_ok()
}

/// The original equations the solver polishes on, for one seeded instance.
fn sample_equations(plan: &SolverPlan) -> Vec<Poly<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(AUTO_POLISH_SEED);
    plan.visible_equations(&random_data_f64(&plan.problem.layout, &mut rng))
}
