//! Numerical-stability audit of an elimination template over many instances (`mingen
//! audit`; random ones, or read from a file by [`crate::instances_file`]),
//! through the interpreted solver of [`crate::interpret`], which runs the emitted solvers'
//! numeric code: the audit measures the real solutions a generated solver returns.

use crate::algebra::Poly;
use crate::instance::random_data_f64;
use crate::interpret::{
    newton_polish_polys, normalized_residual, polish_poor_solution_polys, recover_eliminated,
    screen_redundant_readout_polys, solve_template,
};
use crate::pipeline::SolverPlan;
use crate::template::EliminationTemplate;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::fmt;

/// An instance whose worst normalised residual exceeds this is a failure.
pub const FAILURE_RESIDUAL: f64 = 1e-6;
/// log10 residuals are clamped to `[LOG10_FLOOR, LOG10_CEIL]` (an exact zero residual
/// counts as `LOG10_FLOOR`; an instance that could not be solved at all as `LOG10_CEIL`).
pub const LOG10_FLOOR: f64 = -20.0;
/// See [`LOG10_FLOOR`].
pub const LOG10_CEIL: f64 = 20.0;

/// Audit settings.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AuditOptions {
    /// Number of random instances (default 1000; at most [`MAX_INSTANCES`], more are
    /// clamped to it).
    pub instances: usize,
    /// Seed of the `ChaCha8Rng` handed to the instance generator (default 1).
    pub seed: u64,
    /// Wall-clock limit of the instances (none by default): once it has passed, no
    /// further instance is started and the report says so ([`AuditReport::stopped`]).
    pub time_limit: Option<std::time::Duration>,
}

/// Estimated bytes an audit keeps per instance (two residual logs, the planted error).
pub const AUDIT_BYTES_PER_INSTANCE: u64 = 24;

/// The largest number of random instances an audit runs (its per-instance figures are
/// kept in memory).
pub const MAX_INSTANCES: usize = 10_000_000;

impl Default for AuditOptions {
    fn default() -> Self {
        AuditOptions {
            instances: 1000,
            seed: 1,
            time_limit: None,
        }
    }
}

/// Linearly eliminated unknowns of an instance (`eliminate`, templates/README.md).
#[derive(Clone, Debug)]
pub struct EliminatedUnknowns {
    /// Coefficient matrix (rows x k): entries are polynomials in the remaining unknowns
    /// (the template's variables); its null vector gives the eliminated unknowns, see
    /// [`recover_eliminated`] for the scaling.
    pub matrix: Vec<Vec<Poly<f64>>>,
    /// Positions of the k eliminated unknowns among the original unknowns, in order
    /// (`ProblemLayout::eliminate`). The remaining unknowns fill the other positions in
    /// order.
    pub positions: Vec<usize>,
    /// Whether the matrix's last column holds the free terms (the eliminated unknowns are
    /// then its null vector divided by the last entry, not a unit vector).
    pub inhomogeneous: bool,
}

/// One random instance for [`audit`].
#[derive(Clone, Debug)]
pub struct AuditInstance {
    /// The equations the template solves (after elimination, if any), in the template's
    /// variables.
    pub equations: Vec<Poly<f64>>,
    /// The original equations, in all original unknowns: residuals are measured on these.
    pub original: Vec<Poly<f64>>,
    /// The eliminated unknowns, if the problem eliminates some.
    pub eliminated: Option<EliminatedUnknowns>,
    /// Gauss-Newton steps polishing each solution on `original` (`option newton`).
    pub newton_steps: usize,
    /// Polish only a solution whose worst relative residual is above
    /// [`mingen_runtime::POOR_SOLUTION_RESIDUAL`], by
    /// [`mingen_runtime::POOR_SOLUTION_STEPS`] steps, as a solver whose plan chose not to
    /// polish every solution does ([`SolverPlan::polishes_poor_solutions_only`];
    /// `newton_steps` is then 0).
    pub poor_only: bool,
    /// A known solution of this instance (all original unknowns, in declaration order),
    /// e.g. the geometry a simulator planted: the audit then reports how accurately the
    /// closest returned solution recovers it ([`PlantedStats`]).
    pub planted: Option<Vec<f64>>,
    /// The unknowns declared `positive` (indices into the original unknowns): solutions
    /// where one is not positive are not returned (residuals are still measured on every
    /// real solution; [`AuditReport::mean_kept_solutions`] counts the others).
    pub positive: Vec<usize>,
    /// The sign folds of the template's system (`crate::symmetry`; empty: none): each
    /// solution of the template gives both signs before the eliminated unknowns are
    /// recovered.
    pub sign_folds: Vec<crate::symmetry::SignFold>,
}

/// Result of an audit (serialised by [`AuditReport::to_json`]).
#[derive(Clone, Debug, PartialEq)]
pub struct AuditReport {
    /// Number of instances run.
    pub instances: usize,
    /// Whether [`AuditOptions::time_limit`] stopped the audit before all the instances
    /// asked for were run.
    pub stopped: bool,
    /// Median over instances (those with a real solution, and the unsolved ones) of the
    /// log10 of the worst normalised residual of the real solutions.
    pub median_log10_residual: f64,
    /// 99th percentile (nearest rank) of the same.
    pub p99_log10_residual: f64,
    /// Instances with a residual above [`FAILURE_RESIDUAL`], a missed real solution, or
    /// not solved at all (singular template).
    pub failures: usize,
    /// Unit-width bins of log10 residual: `(lower_edge, count)`, contiguous from the lowest
    /// to the highest occupied bin.
    pub histogram: Vec<(f64, usize)>,
    /// Number of solutions (real and complex) of the problem.
    pub solutions_expected: usize,
    /// Instances where the interpreter returned an error (counted in `failures`).
    pub solve_errors: usize,
    /// Instances where a real eigenvector of the action matrix gave no solution (counted in
    /// `failures`).
    pub missed_solutions: usize,
    /// Solved instances without a real solution (not in the residual statistics).
    pub no_real_solutions: usize,
    /// Mean number of real solutions per solved instance.
    pub mean_real_solutions: f64,
    /// With unknowns declared `positive`: the mean number of real solutions where they
    /// are positive, the ones an emitted solver returns (`None` without a declaration).
    pub mean_kept_solutions: Option<f64>,
    /// Recovery of the planted solutions, if the instances came with them.
    pub planted: Option<PlantedStats>,
    /// The same figures with the other polishing: before polishing if the solver polishes
    /// (`newton_steps > 0`), else after [`COMPARISON_NEWTON_STEPS`] Gauss-Newton steps
    /// (what `option newton` would give). `None` when no instance was run.
    pub other_polishing: Option<PolishingStats>,
}

/// Gauss-Newton steps the audit of a solver that does not polish applies to a copy of each
/// solution, to show what `option newton` would give ([`AuditReport::other_polishing`]).
pub const COMPARISON_NEWTON_STEPS: usize = 2;

/// Residual figures of the same instances' solutions with other polishing than the
/// solver's ([`AuditReport::other_polishing`]), with the same definitions as
/// [`AuditReport`]'s.
#[derive(Clone, Debug, PartialEq)]
pub struct PolishingStats {
    /// Gauss-Newton steps applied (0: the solutions as read off the action matrix).
    pub newton_steps: usize,
    /// Median log10 of the worst normalised residual, see
    /// [`AuditReport::median_log10_residual`].
    pub median_log10_residual: f64,
    /// 99th percentile (nearest rank) of the same.
    pub p99_log10_residual: f64,
    /// Failures counted as [`AuditReport::failures`] are, on the unpolished residuals.
    pub failures: usize,
}

/// Recovery of planted solutions ([`AuditInstance::planted`]). The error of one instance is
/// the smallest, over the returned real solutions (polished as the solver polishes them),
/// of the largest per-unknown error `|x_i - p_i| / max(1, |p_i|)`; linearly eliminated
/// unknowns recovered as a unit null vector (homogeneous) are compared as unit vectors up
/// to sign, inhomogeneous ones as values.
/// An instance with no solution, or not solved, has an infinite error.
#[derive(Clone, Debug, PartialEq)]
pub struct PlantedStats {
    /// Instances with a planted solution.
    pub instances: usize,
    /// Those whose error is at most [`RECOVERY_TOLERANCE`].
    pub recovered: usize,
    /// Median log10 error (clamped to [`LOG10_FLOOR`], [`LOG10_CEIL`]).
    pub median_log10_error: f64,
    /// 99th percentile (nearest rank) of the same.
    pub p99_log10_error: f64,
}

/// A planted solution counts as recovered if its error ([`PlantedStats`]) is at most this.
pub const RECOVERY_TOLERANCE: f64 = 1e-6;

/// The recovery error of `planted` among `solutions` (see [`PlantedStats`]); `eliminated`
/// lists the positions of unknowns eliminated as a unit null vector (compared up to sign).
fn recovery_error(solutions: &[Vec<f64>], planted: &[f64], eliminated: &[usize]) -> f64 {
    let unit = |x: &[f64]| -> Vec<f64> {
        let v: Vec<f64> = eliminated
            .iter()
            .map(|&i| x.get(i).copied().unwrap_or(f64::NAN))
            .collect();
        let n = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        v.iter().map(|a| a / n).collect()
    };
    let p_unit = unit(planted);
    solutions
        .iter()
        .filter(|s| s.len() == planted.len())
        .map(|s| {
            let free = s
                .iter()
                .zip(planted)
                .enumerate()
                .filter(|(i, _)| !eliminated.contains(i))
                .map(|(_, (x, p))| (x - p).abs() / p.abs().max(1.0))
                .fold(0.0, f64::max);
            let s_unit = unit(s);
            let signed = |sign: f64| {
                s_unit
                    .iter()
                    .zip(&p_unit)
                    .map(|(a, b)| (sign * a - b).abs())
                    .fold(0.0, f64::max)
            };
            let e = free.max(signed(1.0).min(signed(-1.0)));
            if e.is_nan() {
                f64::INFINITY
            } else {
                e
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// `log10(x)` clamped to `[LOG10_FLOOR, LOG10_CEIL]`; an exact zero gives `LOG10_FLOOR`.
fn clamped_log10(x: f64) -> f64 {
    if x == 0.0 {
        LOG10_FLOOR
    } else {
        x.log10().clamp(LOG10_FLOOR, LOG10_CEIL)
    }
}

/// Worst normalised residual of a solution over the equations.
fn worst_residual(equations: &[Poly<f64>], s: &[f64]) -> f64 {
    equations
        .iter()
        .map(|e| normalized_residual(e, s))
        .fold(0.0, |a, r| {
            if r.is_nan() || a.is_nan() {
                f64::NAN
            } else {
                a.max(r)
            }
        })
}

/// Outcome of one solved instance.
struct Outcome {
    /// log10 of the worst residual over the real solutions (clamped), `None` without any.
    log10_residual: Option<f64>,
    /// The same with the other polishing ([`AuditReport::other_polishing`]).
    log10_other: Option<f64>,
    /// Real solutions found.
    real: usize,
    /// Of those, the ones whose `positive` unknowns are positive (returned).
    kept: usize,
    /// Real eigenpairs that gave no solution (rejected read-out or no eliminated unknowns).
    missed: usize,
    /// The planted solution's recovery error, if the instance has one.
    planted_error: Option<f64>,
}

/// Solves one instance; `None` if it could not be solved (an emitted solver returns
/// nothing).
fn run_instance(template: &EliminationTemplate, inst: &AuditInstance) -> Option<Outcome> {
    let solved = solve_template(template, &inst.equations).ok()?;
    let mut tally = Tally::default();
    // Eigenpairs that gave a solution, or a pair of complex ones (a negative square).
    let mut accounted = 0;
    let reject_spurious = template.spurious_eigenvalues > 0;
    for w in &solved.solutions {
        // A spurious read-out of a redundant basis, told apart on the template's own
        // equations before the eliminated unknowns are recovered (the emitted solver drops
        // it there, or by its residual on the original equations).
        if reject_spurious
            && worst_residual(&inst.equations, w)
                .partial_cmp(&mingen_runtime::SPURIOUS_RESCUE)
                .map_or(true, |o| o.is_gt())
        {
            tally.spurious += 1;
            accounted += 1;
            continue;
        }
        let signs = crate::symmetry::unfold_all(&inst.sign_folds, w);
        if signs.is_empty() && !inst.sign_folds.is_empty() {
            let negative = |f: &crate::symmetry::SignFold| w.get(f.pivot).is_some_and(|&s| s < 0.0);
            if inst.sign_folds.iter().any(negative) {
                accounted += 1;
            }
            continue;
        }
        let before = (tally.real, tally.spurious);
        for s in &signs {
            // A solution whose eliminated unknowns cannot be recovered is missed.
            let _ = tally.add(inst, s, reject_spurious);
        }
        if (tally.real, tally.spurious) != before {
            accounted += 1;
        }
    }
    // Only a homogeneous null vector is defined up to scale (compared up to sign).
    let projective = inst
        .eliminated
        .as_ref()
        .filter(|e| !e.inhomogeneous)
        .map_or(&[][..], |e| e.positions.as_slice());
    Some(Outcome {
        log10_residual: tally.worst.map(clamped_log10),
        log10_other: tally.worst_other.map(clamped_log10),
        real: tally.real,
        kept: tally.returned.len(),
        // A redundant basis's spurious eigenvectors may also give no read-out at all (the
        // entry of 1 zero): as many as its spurious eigenvalues are not missed solutions.
        missed: (solved.eigenpairs - accounted)
            .saturating_sub(template.spurious_eigenvalues.saturating_sub(tally.spurious)),
        planted_error: inst
            .planted
            .as_deref()
            .map(|p| recovery_error(&tally.returned, p, projective)),
    })
}

/// The real solutions of one instance as they are found (see [`run_instance`]).
#[derive(Default)]
struct Tally {
    /// Real solutions found.
    real: usize,
    /// The worst residual over them, as the emitted solver polishes.
    worst: Option<f64>,
    /// The same with the other polishing ([`AuditReport::other_polishing`]).
    worst_other: Option<f64>,
    /// Those whose `positive` unknowns are positive.
    returned: Vec<Vec<f64>>,
    /// Read-outs of a redundant basis dropped as spurious (residual above
    /// [`mingen_runtime::SPURIOUS_RESIDUAL`] before polishing, or a repeat of a solution
    /// kept before it), as the emitted solver does.
    spurious: usize,
    /// The solutions of a redundant basis kept so far, polished (the emitted solver's
    /// `mingen_runtime::DistinctSolutions`).
    distinct: Vec<Vec<f64>>,
}

impl Tally {
    /// `false` if `x` repeats a solution kept before ([`mingen_runtime::repeats`]);
    /// otherwise keeps it.
    fn distinct(&mut self, x: &[f64]) -> bool {
        let repeat = self.distinct.iter().any(|y| mingen_runtime::repeats(x, y));
        if !repeat {
            self.distinct.push(x.to_vec());
        }
        !repeat
    }

    /// Adds one real solution `s` of the template's variables (signs unfolded): the
    /// eliminated unknowns recovered, dropped as spurious when `reject_spurious` and its
    /// residual says so, polished as the emitted solver does, its residual on the original
    /// equations. `None` when the eliminated unknowns cannot be recovered.
    fn add(&mut self, inst: &AuditInstance, s: &[f64], reject_spurious: bool) -> Option<()> {
        let mut full = match &inst.eliminated {
            None => s.to_vec(),
            Some(el) => {
                let e = recover_eliminated(&el.matrix, s, el.inhomogeneous)?;
                let n = s.len() + e.len();
                let (mut si, mut ei) = (s.iter(), e.iter());
                let mut full = Vec::with_capacity(n);
                for pos in 0..n {
                    let next = if el.positions.contains(&pos) {
                        ei.next()
                    } else {
                        si.next()
                    };
                    full.push(*next?);
                }
                full
            }
        };
        let residual = |x: &[f64]| {
            let r = worst_residual(&inst.original, x);
            if r.is_nan() {
                f64::INFINITY
            } else {
                r
            }
        };
        let positive = |x: &[f64]| {
            inst.positive
                .iter()
                .all(|&i| x.get(i).is_some_and(|&v| v > 0.0))
        };
        if reject_spurious && !screen_redundant_readout_polys(&inst.original, &mut full) {
            self.spurious += 1;
            return Some(());
        }
        // As the emitted solver: a polished solution is returned if it was positive
        // before polishing too.
        let positive_before = positive(&full);
        let other = if inst.newton_steps > 0 {
            let r = residual(&full);
            newton_polish_polys(&inst.original, &mut full, inst.newton_steps);
            r
        } else {
            // The comparison polishes every solution of a solver that polishes its poor
            // ones only, too.
            let mut polished = full.clone();
            newton_polish_polys(&inst.original, &mut polished, COMPARISON_NEWTON_STEPS);
            if inst.poor_only {
                polish_poor_solution_polys(&inst.original, &mut full);
            }
            residual(&polished)
        };
        if reject_spurious && positive_before && !self.distinct(&full) {
            self.spurious += 1;
            return Some(());
        }
        self.worst_other = Some(self.worst_other.map_or(other, |w| w.max(other)));
        self.real += 1;
        let r = residual(&full);
        self.worst = Some(self.worst.map_or(r, |w| w.max(r)));
        if positive_before && positive(&full) {
            self.returned.push(full);
        }
        Some(())
    }
}

/// Runs `opts.instances` instances (at most [`MAX_INSTANCES`]) through the interpreted
/// template.
///
/// `make_instance` draws one instance from the shared generator (seeded with
/// `opts.seed`). Per real solution `s` (eliminated unknowns recovered and merged back into
/// the original order), the residual is the maximum over the original equations of
/// `|f(s)| / sum_terms |c| |m(s)|`; per instance, the log10 of the worst residual over its
/// real solutions (clamped, see [`LOG10_FLOOR`]). The median and p99 are over the instances
/// with a real solution plus the unsolved ones (at [`LOG10_CEIL`]). An instance fails if
/// that residual exceeds [`FAILURE_RESIDUAL`], if a real eigenvector of the action matrix
/// gave no solution (a missed solution), or if it could not be solved at all.
/// `expected_solutions` (real and complex) is reported only: an emitted solver returns the
/// real ones.
pub fn audit(
    template: &EliminationTemplate,
    expected_solutions: usize,
    opts: &AuditOptions,
    mut make_instance: impl FnMut(&mut ChaCha8Rng) -> AuditInstance,
) -> AuditReport {
    let mut rng = ChaCha8Rng::seed_from_u64(opts.seed);
    let instances = opts.instances.min(MAX_INSTANCES);
    let mut logs = Vec::with_capacity(instances);
    let mut other_logs = Vec::with_capacity(instances);
    let mut other_failures = 0;
    let mut other_steps = COMPARISON_NEWTON_STEPS;
    let (mut failures, mut solve_errors, mut missed, mut no_real) = (0, 0, 0, 0);
    let (mut real_total, mut kept_total, mut solved) = (0usize, 0usize, 0usize);
    let mut filtered = false;
    let mut planted_logs = Vec::new();
    let started = std::time::Instant::now();
    let mut run = 0;
    for _ in 0..instances {
        if opts
            .time_limit
            .is_some_and(|limit| started.elapsed() > limit)
        {
            break;
        }
        run += 1;
        let inst = make_instance(&mut rng);
        if inst.newton_steps > 0 {
            other_steps = 0;
        }
        let has_planted = inst.planted.is_some();
        filtered |= !inst.positive.is_empty();
        match run_instance(template, &inst) {
            None => {
                solve_errors += 1;
                failures += 1;
                other_failures += 1;
                logs.push(LOG10_CEIL);
                other_logs.push(LOG10_CEIL);
                if has_planted {
                    planted_logs.push(LOG10_CEIL);
                }
            }
            Some(o) => {
                if let Some(e) = o.planted_error {
                    planted_logs.push(clamped_log10(e));
                }
                solved += 1;
                real_total += o.real;
                kept_total += o.kept;
                let miss = o.missed > 0;
                if miss {
                    missed += 1;
                }
                let bad = |lg: Option<f64>| lg.is_some_and(|lg| lg > FAILURE_RESIDUAL.log10());
                if miss || bad(o.log10_residual) {
                    failures += 1;
                }
                if miss || bad(o.log10_other) {
                    other_failures += 1;
                }
                other_logs.extend(o.log10_other);
                match o.log10_residual {
                    Some(lg) => logs.push(lg),
                    None => no_real += 1,
                }
            }
        }
    }
    logs.sort_by(f64::total_cmp);
    other_logs.sort_by(f64::total_cmp);
    planted_logs.sort_by(f64::total_cmp);
    let planted = (!planted_logs.is_empty()).then(|| PlantedStats {
        instances: planted_logs.len(),
        recovered: planted_logs
            .iter()
            .filter(|&&e| e <= RECOVERY_TOLERANCE.log10())
            .count(),
        median_log10_error: median(&planted_logs),
        p99_log10_error: quantile(&planted_logs, 0.99),
    });
    AuditReport {
        instances: run,
        stopped: run < instances,
        median_log10_residual: median(&logs),
        p99_log10_residual: quantile(&logs, 0.99),
        failures,
        histogram: histogram(&logs),
        solutions_expected: expected_solutions,
        solve_errors,
        missed_solutions: missed,
        no_real_solutions: no_real,
        mean_real_solutions: if solved > 0 {
            real_total as f64 / solved as f64
        } else {
            0.0
        },
        mean_kept_solutions: filtered.then(|| {
            if solved > 0 {
                kept_total as f64 / solved as f64
            } else {
                0.0
            }
        }),
        planted,
        other_polishing: (run > 0).then(|| PolishingStats {
            newton_steps: other_steps,
            median_log10_residual: median(&other_logs),
            p99_log10_residual: quantile(&other_logs, 0.99),
            failures: other_failures,
        }),
    }
}

fn median(sorted: &[f64]) -> f64 {
    match sorted.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// Nearest-rank quantile.
fn quantile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let rank = (p * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

fn histogram(sorted: &[f64]) -> Vec<(f64, usize)> {
    let (Some(&lo), Some(&hi)) = (sorted.first(), sorted.last()) else {
        return Vec::new();
    };
    let (lo, hi) = (lo.floor(), hi.floor());
    let nbins = (hi - lo) as usize + 1;
    let mut counts = vec![0usize; nbins];
    for &x in sorted {
        let b = ((x.floor() - lo) as usize).min(nbins - 1);
        counts[b] += 1;
    }
    counts
        .into_iter()
        .enumerate()
        .map(|(i, c)| (lo + i as f64, c))
        .collect()
}

impl AuditReport {
    /// JSON with the keys `instances`, `median_log10_residual`,
    /// `p99_log10_residual`, `failures`, `histogram` (a list of
    /// `{"lower_edge": e, "count": n}` for the bins `[e, e + 1)` of log10 residual), plus
    /// `solutions_expected`, `solve_errors`, `missed_solutions`, `no_real_solutions`,
    /// `mean_real_solutions`, `mean_kept_solutions` (`null` without `positive`), `planted` (`null`, or `{"instances", "recovered",
    /// "median_log10_error", "p99_log10_error"}`, see [`PlantedStats`]) and
    /// `other_polishing` (`null`, or `{"newton_steps", "median_log10_residual",
    /// "p99_log10_residual", "failures"}`, see [`PolishingStats`]).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "instances": self.instances,
            "median_log10_residual": self.median_log10_residual,
            "p99_log10_residual": self.p99_log10_residual,
            "failures": self.failures,
            "histogram": self
                .histogram
                .iter()
                .map(|(e, c)| serde_json::json!({"lower_edge": e, "count": c}))
                .collect::<Vec<_>>(),
            "solutions_expected": self.solutions_expected,
            "solve_errors": self.solve_errors,
            "missed_solutions": self.missed_solutions,
            "no_real_solutions": self.no_real_solutions,
            "mean_real_solutions": self.mean_real_solutions,
            "mean_kept_solutions": self.mean_kept_solutions,
            "planted": self.planted.as_ref().map(|p| serde_json::json!({
                "instances": p.instances,
                "recovered": p.recovered,
                "median_log10_error": p.median_log10_error,
                "p99_log10_error": p.p99_log10_error,
            })),
            "other_polishing": self.other_polishing.as_ref().map(|u| serde_json::json!({
                "newton_steps": u.newton_steps,
                "median_log10_residual": u.median_log10_residual,
                "p99_log10_residual": u.p99_log10_residual,
                "failures": u.failures,
            })),
        })
    }

    /// Text histogram, one line per bin: `[-13, -12)  ########  523`.
    pub fn render_histogram(&self) -> String {
        const WIDTH: usize = 50;
        let max = self.histogram.iter().map(|b| b.1).max().unwrap_or(0).max(1);
        let mut s = String::new();
        for &(e, c) in &self.histogram {
            let bar = (c * WIDTH).div_ceil(max);
            let label = format!("[{}, {})", e, e + 1.0);
            s.push_str(&format!("{label:>10}  {:<WIDTH$}  {c}\n", "#".repeat(bar)));
        }
        s
    }
}

impl fmt::Display for AuditReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "instances:              {}", self.instances)?;
        writeln!(f, "solutions expected:     {}", self.solutions_expected)?;
        writeln!(f, "mean real solutions:    {:.2}", self.mean_real_solutions)?;
        if let Some(k) = self.mean_kept_solutions {
            writeln!(
                f,
                "  of them positive:     {k:.2} (declared `positive`; returned)"
            )?;
        }
        writeln!(f, "without real solution:  {}", self.no_real_solutions)?;
        writeln!(
            f,
            "median log10 residual:  {:.2}",
            self.median_log10_residual
        )?;
        writeln!(f, "p99 log10 residual:     {:.2}", self.p99_log10_residual)?;
        let pct = if self.instances > 0 {
            100.0 * self.failures as f64 / self.instances as f64
        } else {
            0.0
        };
        writeln!(
            f,
            "failures:               {} ({pct:.2} %; {} unsolved, {} with missed solutions)",
            self.failures, self.solve_errors, self.missed_solutions
        )?;
        if let Some(u) = &self.other_polishing {
            let label = match u.newton_steps {
                0 => "before polishing:".to_string(),
                n => format!("with newton = {n}:"),
            };
            writeln!(
                f,
                "{label:<24}median {:.2}, p99 {:.2}, {} failures",
                u.median_log10_residual, u.p99_log10_residual, u.failures
            )?;
        }
        if let Some(p) = &self.planted {
            writeln!(
                f,
                "planted solutions:      {} of {} recovered to {RECOVERY_TOLERANCE:e}; log10 error median {:.2}, p99 {:.2}",
                p.recovered, p.instances, p.median_log10_error, p.p99_log10_error
            )?;
        }
        writeln!(f, "log10 residual histogram:")?;
        write!(f, "{}", self.render_histogram())
    }
}

/// Audits a planned problem (`mingen audit FILE`): [`audit`] on `plan`'s template with
/// `options.instances` random f64 instances ([`crate::instance::random_data_f64`], drawn from
/// the audit's seeded generator). Each instance's template equations and elimination come
/// from [`SolverPlan::equations`], the residuals are measured on the original equations
/// (`plan.problem.evaluate`, all unknowns, eliminated ones recovered and merged back), and
/// `plan.solution_count()` solutions are expected per instance.
///
/// ```no_run
/// # use mingen::{audit_plan, plan_file, AuditOptions, TemplateOptions};
/// let plan = plan_file("templates/gs5pt.mp".as_ref(), &TemplateOptions::default()).unwrap();
/// println!("{}", audit_plan(&plan, &AuditOptions::default()));
/// ```
pub fn audit_plan(plan: &SolverPlan, options: &AuditOptions) -> AuditReport {
    let layout = &plan.problem.layout;
    audit(
        &plan.generated.built.template,
        plan.solution_count(),
        options,
        |rng| plan_instance(plan, &random_data_f64(layout, rng)),
    )
}

/// [`audit_plan`] on given instances (one data vector per instance, in the problem's slot
/// order, e.g. from [`crate::instances_file::read_instances`]) instead of random ones.
/// Panics if an instance does not have the problem's number of data slots.
pub fn audit_plan_on(plan: &SolverPlan, instances: &[Vec<f64>]) -> AuditReport {
    audit_plan_planted(plan, instances, None)
}

/// [`audit_plan_on`] with a planted solution per instance (`solutions[i]` solves
/// `instances[i]`: every visible unknown in declaration order, [`SolverPlan::visible_unknowns`]),
/// whose recovery the report gives ([`AuditReport::planted`]). Panics if an instance does
/// not have the problem's number of data slots, or the solutions are not one per instance
/// with one value per visible unknown.
pub fn audit_plan_planted(
    plan: &SolverPlan,
    instances: &[Vec<f64>],
    solutions: Option<&[Vec<f64>]>,
) -> AuditReport {
    let slots = plan.problem.layout.data_slot_count();
    assert!(
        instances.iter().all(|d| d.len() == slots),
        "every instance needs {slots} data values"
    );
    if let Some(s) = solutions {
        let n = plan.visible_unknowns();
        assert!(
            s.len() == instances.len() && s.iter().all(|x| x.len() == n),
            "one planted solution of {n} values per instance"
        );
    }
    let mut planted = solutions.map(|s| s.iter());
    let mut next = instances.iter();
    let options = AuditOptions {
        instances: instances.len(),
        seed: 0,
        time_limit: None,
    };
    audit(
        &plan.generated.built.template,
        plan.solution_count(),
        &options,
        |_| {
            let mut inst = plan_instance(plan, next.next().expect("one instance per draw"));
            inst.planted = planted.as_mut().and_then(|p| p.next().cloned());
            inst
        },
    )
}

/// The audit instance of one data vector.
fn plan_instance(plan: &SolverPlan, data: &[f64]) -> AuditInstance {
    let (equations, eliminated) = plan.equations::<f64>(data);
    AuditInstance {
        equations,
        original: plan.visible_equations(data),
        eliminated: eliminated.map(|e| EliminatedUnknowns {
            matrix: e.coefficient_matrix,
            positions: e.eliminated,
            inhomogeneous: e.inhomogeneous,
        }),
        newton_steps: plan.problem.layout.options.newton_steps() as usize,
        poor_only: plan.polishes_poor_solutions_only(),
        planted: None,
        positive: plan.problem.layout.positive.clone(),
        sign_folds: plan.problem.sign_folds().to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics() {
        let v = [-15.0, -14.2, -13.0, -12.5, 3.0];
        assert_eq!(median(&v), -13.0);
        assert_eq!(quantile(&v, 0.99), 3.0);
        assert_eq!(quantile(&v, 0.2), -15.0);
        let h = histogram(&v);
        assert_eq!(h.first(), Some(&(-15.0, 2)));
        assert_eq!(h.len(), 19);
        assert_eq!(h.last(), Some(&(3.0, 1)));
        assert_eq!(h.iter().map(|b| b.1).sum::<usize>(), 5);
    }
}
