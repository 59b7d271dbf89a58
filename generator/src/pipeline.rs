//! The generator pipeline for one problem, end to end, and the one place that runs its
//! stages in order:
//!
//! 1. [`plan_file`]: problem file -> [`Problem`] (lexer, parser, checker, expansion);
//! 2. [`plan`]: options resolved, the linear elimination checked, `nonzero` expressions
//!    divided out, equations that are combinations of others dropped
//!    ([`crate::independent`]), then [`find_template`]:
//!    random instances mod p -> Gröbner basis, solution count and quotient basis
//!    ([`analyse_within`]) -> best elimination template on that same instance and Gröbner
//!    basis ([`best_template`](crate::template::best_template)) -> validation on fresh
//!    instances; then the polishing, unless the file or the command line chose it, by
//!    solving the template on random f64 instances ([`crate::polishing`]);
//! 3. [`emit_plan_from`]: traced instance -> Rust source of the solver.
//!
//! The resulting [`SolverPlan`] also serves `inspect` (sizes, basis, timings), the
//! interpreter and audit (f64 instances): all of them obtain the template's equations
//! through [`SolverPlan::equations`], so every consumer sees the same elimination. Writing
//! files is `crate::build`'s (and the `mingen` binary's).

use crate::action_accuracy::{self, ActionAccuracy};
use crate::algebra::{Monomial, Poly, Ring};
use crate::budget::{Deadline, Exhausted};
use crate::eliminate::{block_reduction, EliminateError};
use crate::emit::{
    emit_solver, CodeForm, EliminationSpec, EmitError, PolishSpec, SolverSpec, Tracer,
};
use crate::expand::EvalError;
use crate::instance::random_data_fp;
use crate::polishing::{self, AutoPolishing};
use crate::quotient::{analyse_within, InstanceRng, InstanceSource};
use crate::redundancy::{self, RedundantCheck};
use crate::rewrite;
use crate::system::{equation_supports, system, ProblemSource, System, SUPPORT_SEED};
use crate::template::search::best_template_within;
use crate::template::validate::validate_within;
use crate::template::{
    order_for_sparse_elimination, Action, ActionChoice, BuiltTemplate, TemplateError,
    TemplateOptions, ValidationReport,
};
use crate::{Problem, ProblemError};
use serde_json::{json, Value};
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::time::Instant;
use thiserror::Error;

/// Why a problem cannot be turned into a solver.
#[derive(Debug, Error)]
pub enum PipelineError {
    /// The problem file could not be read or parsed.
    #[error(transparent)]
    Problem(#[from] ProblemError),
    /// `eliminate` could not be carried out.
    #[error("{file}: eliminate {names}: {source}")]
    Eliminate {
        /// The problem file.
        file: String,
        /// The eliminated unknowns.
        names: String,
        /// What went wrong.
        source: EliminateError,
    },
    /// An option names something the problem does not have.
    #[error("{file}: {message}")]
    Option {
        /// The problem file.
        file: String,
        /// What is wrong.
        message: String,
    },
    /// The equations could not be expanded over Z_p within the budget, or a literal has
    /// no image there.
    #[error("{file}: {source}")]
    Expansion {
        /// The problem file.
        file: String,
        /// What went wrong.
        source: EvalError,
    },
    /// Gröbner basis, count or template construction failed (inconsistent or
    /// positive-dimensional systems end here).
    #[error("{file}: {source}")]
    Template {
        /// The problem file.
        file: String,
        /// What went wrong.
        source: TemplateError,
    },
    /// The solver could not be emitted.
    #[error("{file}: {source}")]
    Emit {
        /// The problem file.
        file: String,
        /// What went wrong.
        source: EmitError,
    },
}

impl PipelineError {
    /// The number of solutions, if the failure came after counting them.
    pub fn solution_count(&self) -> Option<usize> {
        match self {
            PipelineError::Template { source, .. } => source.solution_count(),
            PipelineError::Problem(_)
            | PipelineError::Eliminate { .. }
            | PipelineError::Option { .. }
            | PipelineError::Expansion { .. }
            | PipelineError::Emit { .. } => None,
        }
    }

    /// The budget that stopped planning, if a budget did.
    pub fn exhausted(&self) -> Option<Exhausted> {
        match self {
            PipelineError::Template { source, .. } => source.exhausted(),
            PipelineError::Expansion {
                source: EvalError::Budget(e),
                ..
            } => Some(*e),
            _ => None,
        }
    }
}

/// Everything needed to solve, audit or emit a problem.
pub struct SolverPlan {
    /// The parsed problem.
    pub problem: Problem,
    /// The problem file as given (for messages and the generated header).
    pub file: String,
    /// Count, basis, chosen template with its shrink history, per-action sizes, validation.
    pub generated: Generated,
    /// Wall-clock seconds of the whole plan (elimination check, Gröbner work, templates,
    /// validation, the polishing choice).
    pub seconds: f64,
    /// The monomials of each template equation on the problem's data family (generic
    /// instances mod p, rotations exact). A term outside vanishes identically there (e.g.
    /// a coefficient `(R Rᵀ)_12` of rotation data): [`SolverPlan::equations`] drops it, so
    /// the emitted solvers, with data as symbols, and the interpreter, with rounded
    /// rotations, fill exactly the template's columns.
    pub supports: Vec<Vec<Monomial>>,
    /// The polishing the plan chose by measuring its template, when neither the problem
    /// file nor the command line set `newton` (see [`AutoPolishing`]); the chosen steps
    /// are in `problem.layout.options.newton`, which the emitter and the audit read.
    /// `None` when they set it, or when the solver cannot polish.
    pub auto_polishing: Option<AutoPolishing>,
    /// When the search grew a redundant basis: whether the plan kept it, by measuring it
    /// against the quotient-basis template it grew from (see [`RedundantCheck`]).
    pub redundant_check: Option<RedundantCheck>,
    /// When the chosen template's solver failed too often on the plan's sample: the other
    /// actions' templates compared with it, and which was kept (see [`ActionAccuracy`]).
    pub action_accuracy: Option<ActionAccuracy>,
}

/// The share of a plan's wall-clock budget the template search may use (see [`plan`]).
const SEARCH_BUDGET_SHARE: f64 = 0.8;

/// The template options for `problem`: `options` with the problem file's `option` lines
/// applied, then `options.overrides` (the command line's) over them. An action name is an
/// unknown scalar of the system (after elimination); `random` is a random linear
/// combination of the unknowns; an extra degree is a hard bound (no adaptive raising).
pub fn resolve_options(problem: &Problem, options: &TemplateOptions) -> TemplateOptions {
    let file = &problem.layout.options;
    let o = &options.overrides;
    let action = o.action.as_ref().or(file.action.as_ref());
    let extra = o.extra_degree.or(file.extra_degree);
    let basis = o.basis.as_ref().or(file.basis.as_ref());
    let mut out = options.clone();
    if let Some(a) = action {
        let names = ProblemSource::new(problem).var_names();
        out.actions = named_action(a, &names).unwrap_or(ActionChoice::Random);
    }
    if let Some(d) = extra {
        out.max_extra_degree = d;
        out.adaptive_degree = false;
    }
    if let Some(b) = basis {
        out.basis_selection = b != "standard";
        out.alternative_bases = b != "standard";
    }
    if let Some(r) = o.reduce_equations.or(file.reduce_equations) {
        out.reduce_equations = r;
    }
    if let Some(r) = o.redundant_basis.or(file.redundant_basis) {
        out.redundant_bases = r;
    }
    if let Some(n) = o.weighted_orders.or(file.weighted_orders) {
        out.weighted_orders = n;
    }
    if let Some(s) = o.saturation.or(file.saturation) {
        out.polynomial_saturation = s;
    }
    out
}

/// The action an `--action` / `option action` value names among the unknowns `names`: an
/// unknown (`t1`) or its inverse (`1/t1`); `None` for anything else (`random`, a typo).
fn named_action(value: &str, names: &[String]) -> Option<ActionChoice> {
    let position = |n: &str| names.iter().position(|m| m == n);
    match value.strip_prefix("1/") {
        Some(inverse) => position(inverse.trim()).map(ActionChoice::Inverse),
        None => position(value).map(|v| ActionChoice::Unknowns(vec![v])),
    }
}

/// Parses and plans one problem file (the algebra of `inspect` and `generate`).
pub fn plan_file(path: &Path, options: &TemplateOptions) -> Result<SolverPlan, PipelineError> {
    let problem = Problem::from_file_within(path, options.budget)?;
    plan(problem, &path.display().to_string(), options)
}

/// [`plan_file`] of every file, on at most `threads` threads (each plan on one thread,
/// with its own `options.budget`), the plans in the files' order. A build script that
/// plans many problems uses this as `prost-build` compiles many files.
pub fn plan_files(
    paths: &[PathBuf],
    options: &TemplateOptions,
    threads: usize,
) -> Vec<Result<SolverPlan, PipelineError>> {
    crate::parallel::map_in_order(paths, threads, |path| plan_file(path, options))
}

/// Parses and plans a problem given as source text; `file` names it in messages and in
/// the header of the emitted solver.
pub fn plan_source(
    text: &str,
    file: &str,
    options: &TemplateOptions,
) -> Result<SolverPlan, PipelineError> {
    let problem = Problem::parse_within(text, file, options.budget).map_err(ProblemError::from)?;
    plan(problem, file, options)
}

/// Runs the algebra pipeline on `problem` (see the module documentation), with the
/// options of [`resolve_options`].
pub fn plan(
    mut problem: Problem,
    file: &str,
    options: &TemplateOptions,
) -> Result<SolverPlan, PipelineError> {
    let start = Instant::now();
    // One budget for the whole plan: the rewrites' counts, the template search and the
    // validation all draw on it.
    let deadline = options.budget.start();
    // Solution polishing is not part of the search: the command line's value replaces the
    // file's in the layout the emitter and the audit read.
    if let Some(n) = options.overrides.newton {
        problem.layout.options.newton = Some(n);
    }
    let options = &resolve_options(&problem, options);
    if let Some(a) = &options.overrides.action {
        let names = ProblemSource::new(&problem).var_names();
        if a != "random" && named_action(a, &names).is_none() {
            return Err(PipelineError::Option {
                file: file.to_string(),
                message: format!(
                    "--action {a}: not an unknown of the system (the unknowns: {}; their inverses, e.g. '1/NAME'; or 'random')",
                    names.join(", ")
                ),
            });
        }
    }
    // Every stage evaluates the equations on instances mod p; the first evaluation is
    // bounded by the budget, so that an expansion that blows up is refused here, and the
    // later ones, on other instances of the same equations, have its size.
    {
        let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(options.seed ^ 0xe5a9);
        let data = random_data_fp::<{ crate::algebra::P1 }>(&problem.layout, &mut rng);
        let evaluated = problem
            .check_constants::<crate::algebra::Fp<{ crate::algebra::P2 }>>()
            .and_then(|()| problem.try_evaluate_within(&data, Some(&deadline)));
        if let Err(source) = evaluated {
            return Err(PipelineError::Expansion {
                file: file.to_string(),
                source,
            });
        }
    }
    if !problem.layout.eliminate.is_empty() {
        // The block of equations linear in the eliminated unknowns is reduced by its data
        // where its minors would be wrong (see `crate::eliminate::block_reduction`).
        let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(options.seed ^ 0xb10c);
        let data = random_data_fp::<{ crate::algebra::P1 }>(&problem.layout, &mut rng);
        if let Some(mut reduction) =
            block_reduction(&problem.evaluate(&data), &problem.layout.eliminate)
        {
            // The reduced minors are solved through the equations' own row reduction,
            // which normalises their scale (`reduced_equations_only` below); without it
            // the block's rows are used as they are.
            if !options.reduce_equations {
                reduction.rest_pivots.clear();
            }
            problem = problem.with_block_reduction(reduction);
        }
        // Check the elimination once on an exact instance so that a structural problem is a
        // clear error here rather than an empty system later.
        let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(options.seed);
        let data = random_data_fp::<{ crate::algebra::P1 }>(&problem.layout, &mut rng);
        if let Err(source) = system(&problem, &data) {
            let el = problem.layout.names_of(&problem.layout.eliminate);
            // The library error numbers the unknowns; here they have their names.
            let source = match source {
                EliminateError::NotLinear { equation, .. } => EliminateError::NotLinear {
                    equation,
                    names: el.join(", "),
                },
                EliminateError::ConstraintOnEliminated { equation, .. } => {
                    EliminateError::ConstraintOnEliminated {
                        equation,
                        names: el.join(", "),
                    }
                }
                e => e,
            };
            return Err(PipelineError::Eliminate {
                file: file.to_string(),
                names: el.join(" "),
                source,
            });
        }
    }
    let problem = rewrite::eliminate_linear_unknowns(
        rewrite::substitute_affine_equations(problem, options, &deadline),
        options,
        &deadline,
    );
    let unfolded = rewrite::drop_dependent_equations(
        rewrite::divide_out_nonzero(problem, options, &deadline),
        options.seed,
    );
    let folded = rewrite::sign_fold_alternatives(unfolded.clone(), options, &deadline);
    // A sign fold halves the basis but not always the template: unless the file or the
    // command line asks for it, the system as written is searched too (on what is left
    // of the search's budget) and kept where its elimination is far smaller (below).
    let asked = options
        .overrides
        .sign_symmetry
        .or(unfolded.layout.options.sign_symmetry)
        .is_some();
    let compare = !folded.is_empty() && !asked;
    let search_deadline = deadline.portion(SEARCH_BUDGET_SHARE);
    // The equations' generic monomials serve the template search (its fold of constant
    // rows) and the sparse elimination order alike. The search stops with the best
    // template so far when its share of the budget runs out; the steps after it (the
    // fold, the sparse order, the polishing measurement) are not interruptible and keep
    // the rest.
    let search = |problem: Problem, actions: &ActionChoice, deadline: Deadline| {
        let supports = equation_supports(&problem, options.seed ^ SUPPORT_SEED);
        let options = &TemplateOptions {
            reduced_equations_only: problem
                .block_reduction()
                .is_some_and(|b| !b.rest_pivots.is_empty()),
            actions: actions.clone(),
            ..options.clone()
        };
        let generated = find_template_within(
            &ProblemSource::with_supports(&problem, &supports),
            options,
            deadline,
        );
        (problem, supports, generated)
    };
    let area = |g: &Result<Generated, TemplateError>| {
        g.as_ref().ok().map(|g| g.built.template.elimination_area())
    };
    // Each fold's pivot gives another system: every one is searched and the smallest
    // template kept (the first on a tie). The first has the whole budget, as a single
    // fold would (a large system's search takes it all, and a share of it might find no
    // template); the others, searched while time is left, an equal share of the rest.
    let systems = if folded.is_empty() {
        vec![unfolded.clone()]
    } else {
        folded
    };
    let (searched, mut chosen) = (systems.len(), None);
    for (i, system) in systems.into_iter().enumerate() {
        let parts = (searched - i + usize::from(compare)) as f64;
        let max_seconds = search_deadline.budget().max_seconds;
        let within = if i > 0 && max_seconds.is_finite() {
            let share = search_deadline.elapsed() + search_deadline.remaining() / parts;
            search_deadline.portion(share / max_seconds)
        } else {
            search_deadline
        };
        let result = search(system, &options.actions, within);
        chosen = match chosen {
            None => Some(result),
            Some(best) => match (area(&best.2), area(&result.2)) {
                (Some(b), Some(r)) if r < b => Some(result),
                (None, Some(_)) => Some(result),
                _ => Some(best),
            },
        };
    }
    let mut chosen = chosen.expect("at least one system is searched");
    if compare {
        let written = search(unfolded, &options.actions, search_deadline);
        // The folded eigenvalue problem is half the size: the folded template is kept up
        // to twice the area of the one as written.
        match (area(&chosen.2), area(&written.2)) {
            (Some(f), Some(w)) if 2 * w <= f => chosen = written,
            (None, Some(_)) => chosen = written,
            _ => {}
        }
    }
    let (problem, supports, generated) = chosen;
    let generated = generated.map_err(|source| PipelineError::Template {
        file: file.to_string(),
        // The problem's count, not the folded system's.
        source: match source {
            TemplateError::Counted { count, source } => TemplateError::Counted {
                count: count << problem.sign_folds().len(),
                source,
            },
            other => other,
        },
    })?;
    // Only an action the search chose itself is compared with the others.
    let unchosen = (options.actions == ActionChoice::Auto).then(|| problem.clone());
    let mut plan = complete_plan(problem, file, supports, generated);
    let first_seconds = start.elapsed().as_secs_f64();
    // Another action is searched only while the search's share of the budget has room for
    // a search as long as the first (`action_accuracy::choose`); without it, measuring the
    // first solver's failures (hundreds of solves, not bounded by the budget) is no use.
    let room = search_deadline.remaining() >= first_seconds;
    if let Some(problem) = unchosen.filter(|_| room && action_accuracy::needs_comparison(&plan)) {
        plan = action_accuracy::choose(
            plan,
            &search_deadline,
            &deadline,
            first_seconds,
            |v, area| {
                let (problem, supports, generated) = search(
                    problem.clone(),
                    &ActionChoice::Unknowns(vec![v]),
                    search_deadline,
                );
                let generated = generated.ok()?;
                let t = &generated.built.template;
                // Completing a plan measures it: not for a template that cannot be kept
                // (the completion never makes it smaller).
                if t.elimination_area() > area {
                    return Some(Err(t.eliminated_size()));
                }
                Some(Ok(complete_plan(problem, file, supports, generated)))
            },
        );
    }
    plan.seconds = start.elapsed().as_secs_f64();
    Ok(plan)
}

/// The plan of a searched template: the redundant basis measured against its quotient
/// basis ([`crate::redundancy`]), the sparse elimination order, and the polishing unless
/// the problem's layout sets it ([`crate::polishing`]).
fn complete_plan(
    problem: Problem,
    file: &str,
    supports: Vec<Vec<Monomial>>,
    generated: Generated,
) -> SolverPlan {
    let mut plan = SolverPlan {
        problem,
        file: file.to_string(),
        generated,
        seconds: 0.0,
        supports,
        auto_polishing: None,
        redundant_check: None,
        action_accuracy: None,
    };
    plan.redundant_check = redundancy::choose(&mut plan);
    let template = &mut plan.generated.built.template;
    let template_supports = match &template.reduction {
        Some(r) => r.reduced_supports(),
        None => plan.supports.clone(),
    };
    order_for_sparse_elimination(template, &template_supports);
    if plan.problem.layout.options.newton.is_none() {
        plan.auto_polishing = polishing::choose(&mut plan);
        if let Some(choice) = &plan.auto_polishing {
            plan.problem.layout.options.newton = Some(choice.steps);
        }
    }
    plan
}

impl SolverPlan {
    /// The template's equations (in [`SolverPlan::variable_names`] order) for one data
    /// instance over any ring, plus the elimination data if the problem eliminates unknowns.
    /// Terms outside the equation's support on the data family are dropped (see
    /// [`SolverPlan::supports`]).
    pub fn equations<C: Ring>(&self, data: &[C]) -> System<C> {
        let (equations, elimination) = system(&self.problem, data).unwrap_or_default();
        let equations = equations
            .into_iter()
            .enumerate()
            .map(|(k, e)| match self.supports.get(k) {
                Some(support) if !support.is_empty() => {
                    let support: HashSet<&Monomial> = support.iter().collect();
                    let kept = e
                        .terms()
                        .filter(|(m, _)| support.contains(m))
                        .map(|(m, c)| (m.clone(), c.clone()));
                    Poly::from_terms(e.nvars(), kept)
                }
                _ => e,
            })
            .collect();
        (equations, elimination)
    }

    /// The problem's original equations for one data instance, in all its unknowns, free
    /// of hidden unknowns (those of `nonzero`, whose equations `u * EXPR = 1` only define
    /// them): what solutions are checked and polished on, without hidden values.
    pub fn visible_equations<C: Ring>(&self, data: &[C]) -> Vec<Poly<C>> {
        let visible = self.visible_unknowns();
        self.problem
            .evaluate::<C>(data)
            .into_iter()
            .filter(|p| {
                p.terms()
                    .all(|(m, _)| m.0[visible..].iter().all(|&e| e == 0))
            })
            .collect()
    }

    /// The problem's number of solutions (real and complex): the template's count, times
    /// two per sign fold (`Generated::count` is the folded system's).
    pub fn solution_count(&self) -> usize {
        self.generated.count << self.problem.sign_folds().len()
    }

    /// The sign symmetry the plan folded, for people: `None` without one, else e.g.
    /// `"d1 d2 d3 (folded by d1: the system's d1 is d1^2, d2 is d2/d1, d3 is d3/d1)"`, one
    /// clause per fold joined by `"; "`.
    pub fn sign_symmetry_description(&self) -> Option<String> {
        let folds = self.problem.sign_folds();
        if folds.is_empty() {
            return None;
        }
        let names = self.variable_names();
        let name = |i: usize| names.get(i).cloned().unwrap_or_else(|| format!("x{i}"));
        let clauses: Vec<String> = folds
            .iter()
            .map(|f| {
                let vars: Vec<String> = f.variables().into_iter().map(name).collect();
                let p = name(f.pivot);
                let mut meaning = vec![format!("{p} is {p}^2")];
                meaning.extend(
                    f.scaled
                        .iter()
                        .map(|&j| format!("{} is {}/{p}", name(j), name(j))),
                );
                format!(
                    "{} (folded by {p}: the system's {})",
                    vars.join(" "),
                    meaning.join(", ")
                )
            })
            .collect();
        Some(clauses.join("; "))
    }

    /// Whether the solver polishes its poor solutions only: the plan chose its polishing
    /// ([`SolverPlan::auto_polishing`]), chose no steps for every solution, and the check
    /// is cheap beside the solve ([`crate::POOR_CHECK_MAX_SHARE`]), so a
    /// solution whose worst relative residual is above
    /// [`mingen_runtime::POOR_SOLUTION_RESIDUAL`] (a poorly conditioned instance) is given
    /// [`mingen_runtime::POOR_SOLUTION_STEPS`] Gauss-Newton steps and the others none.
    /// `false` where `option newton` (or `--newton`) set the steps, 0 included.
    pub fn polishes_poor_solutions_only(&self) -> bool {
        self.auto_polishing
            .as_ref()
            .is_some_and(|a| a.steps == 0 && a.polish_poor)
    }

    /// The number of declared (not hidden) unknowns: the first variables of every system.
    pub fn visible_unknowns(&self) -> usize {
        let layout = &self.problem.layout;
        layout.unknown_count() - layout.hidden_count()
    }

    /// The name of the emitted solver's module and file stem: the problem name lowercased,
    /// `p` prepended when it starts with a digit (`problem 8ptF` gives `p8ptf`).
    pub fn module_name(&self) -> String {
        self.problem.layout.module_name()
    }

    /// Names of the template's variables (the unknowns that were not eliminated).
    pub fn variable_names(&self) -> Vec<String> {
        ProblemSource::new(&self.problem).var_names()
    }

    /// Names of the eliminated unknowns.
    pub fn eliminated_names(&self) -> Vec<String> {
        self.problem.layout.names_of(&self.problem.layout.eliminate)
    }

    /// The `inspect --json` keys computed by the algebra (the `inspect --json` contract of docs/GENERATOR.md): `solutions`, `basis`,
    /// `action`, `template` `{rows, cols}` (as eliminated by the emitted solver),
    /// `eliminated`, `seconds`, plus `dependent_columns` (excess columns left out of the
    /// elimination), `equation_reduction` (`{rows, cols}` of the equations' coefficient
    /// matrix the solver row-reduces first, or null), `per_action` and `polishing`
    /// (`{"newton_steps", "poor_solutions_only", "chosen"}`, the second as
    /// [`SolverPlan::polishes_poor_solutions_only`], `chosen` null when the file or the command line set
    /// the steps, else `{"instances", "median_log10_residual", "p99_log10_residual",
    /// "failures"}`, what
    /// the plan measured, see [`AutoPolishing`]), `spurious_eigenvalues` (0 but for a
    /// redundant basis), `flipped_relations` (the basis monomials whose relation a pencil
    /// template takes the other way round, see `crate::template`; empty otherwise) and `redundant_basis` (null, or what the plan measured of a grown
    /// basis, see [`RedundantCheck`]: `kept`, `template`, `spurious_eigenvalues`,
    /// `instances`, `mean_real_solutions` and `failures` as `[redundant, quotient basis]`).
    pub fn summary_json(&self) -> Value {
        let names = self.variable_names();
        let t = &self.generated.built.template;
        let (rows, cols) = t.eliminated_size();
        json!({
            "solutions": self.solution_count(),
            "sign_symmetry": self.sign_symmetry_description(),
            "dependent_columns": t.n_dependent,
            "basis": t.basis.iter().map(|m| m.display_with(&names)).collect::<Vec<_>>(),
            "action": t.action.display_with(&names),
            "template": { "rows": rows, "cols": cols },
            "equation_reduction": t.reduction_size().map(|(r, c)| json!({"rows": r, "cols": c})),
            "eliminated": self.eliminated_names(),
            "seconds": self.seconds,
            "polishing": {
                "newton_steps": self.problem.layout.options.newton_steps(),
                "poor_solutions_only": self.polishes_poor_solutions_only(),
                "chosen": self.auto_polishing.as_ref().map(|a| json!({
                    "instances": a.instances,
                    "median_log10_residual": a.median_log10_residual,
                    "p99_log10_residual": a.p99_log10_residual,
                    "failures": a.failures,
                })),
            },
            "redundant_basis": self.redundant_check.as_ref().map(RedundantCheck::to_json),
            "action_accuracy": self.action_accuracy.as_ref().map(ActionAccuracy::to_json),
            "spurious_eigenvalues": t.spurious_eigenvalues,
            "flipped_relations": t.flipped.iter().map(|&j| t.basis[j].display_with(&names)).collect::<Vec<_>>(),
            "per_action": self.generated.per_action.iter().map(|(v, s)| json!({
                "action": v.display_with(&names),
                "template": s.map(|(r, c)| json!({"rows": r, "cols": c})),
            })).collect::<Vec<_>>(),
        })
    }
}

/// Everything the algebra core produces for one problem.
#[derive(Clone, Debug)]
pub struct Generated {
    /// Number of solutions.
    pub count: usize,
    /// Standard monomials of the Gröbner basis (descending grevlex). The template's own
    /// basis, `built.template.basis`, may differ (basis selection): emitters and `inspect`
    /// must use the template's.
    pub basis: Vec<Monomial>,
    /// The chosen template with its shrink history.
    pub built: BuiltTemplate,
    /// For each action tried: `(action, Some((rows, cols)) or None on failure)`.
    pub per_action: Vec<(Action, Option<(usize, usize)>)>,
    /// Validation on fresh instances (`None` if `opts.validate_instances == 0`).
    pub validation: Option<ValidationReport>,
    /// Wall-clock seconds: analysis (Gröbner bases), template search, validation.
    pub seconds: (f64, f64, f64),
}

/// The algebra of a problem given as an [`InstanceSource`]: count and basis (confirmed
/// across instances and primes), the best template over the action variables
/// ([`best_template`](crate::template::best_template), on the analysed instance mod P1
/// and its Gröbner basis), and validation against Gröbner normal forms on
/// `opts.validate_instances` fresh instances; all within `opts.budget`.
pub fn find_template<S: InstanceSource>(
    src: &S,
    opts: &TemplateOptions,
) -> Result<Generated, TemplateError> {
    find_template_within(src, opts, opts.budget.start())
}

/// [`find_template`] within a budget already running.
fn find_template_within<S: InstanceSource>(
    src: &S,
    opts: &TemplateOptions,
    deadline: Deadline,
) -> Result<Generated, TemplateError> {
    let t0 = Instant::now();
    let analysis = analyse_within(src, opts.seed, Some(deadline))?;
    let t1 = Instant::now();
    // Every template search builds `count x count` action matrices (and copies of them),
    // and a template has at least `count` columns: a count whose matrices alone would pass
    // the memory budget is refused before any is built.
    let count = analysis.count as u64;
    if let Err(exhausted) = deadline.check_memory(count.saturating_mul(count).saturating_mul(8)) {
        return Err(TemplateError::Counted {
            count: analysis.count,
            source: Box::new(TemplateError::Budget {
                step: format!("the action matrices of {count} solutions"),
                exhausted,
            }),
        });
    }
    let opts = &TemplateOptions {
        var_names: src.var_names(),
        hidden_vars: src.hidden_vars(),
        redundant_bases: opts.redundant_bases && src.residual_checkable(),
        ..opts.clone()
    };
    let counted = |source: TemplateError| TemplateError::Counted {
        count: analysis.count,
        source: Box::new(source),
    };
    let constants = src.equation_constants();
    let (built, all) =
        best_template_within(&analysis, opts, &deadline, &constants).map_err(counted)?;
    built
        .template
        .check_emittable(&opts.var_names)
        .map_err(|e| counted(e.into()))?;
    let t2 = Instant::now();
    let validation = if opts.validate_instances > 0 {
        Some(
            validate_within(
                &built.template,
                src,
                opts.validate_instances,
                opts.seed ^ 0x7A11_DA7E,
                Some(&deadline),
            )
            .map_err(counted)?,
        )
    } else {
        None
    };
    let t3 = Instant::now();
    Ok(Generated {
        count: analysis.count,
        basis: analysis.basis,
        built,
        per_action: all
            .into_iter()
            .map(|(v, r)| (v, r.ok().map(|b| b.template.eliminated_size())))
            .collect(),
        validation,
        seconds: (
            (t1 - t0).as_secs_f64(),
            (t2 - t1).as_secs_f64(),
            (t3 - t2).as_secs_f64(),
        ),
    })
}

/// Emits the solver source of a planned problem, its header naming the problem file
/// `problem_path`. The source is a self-contained module body for any crate that depends
/// on `mingen-runtime`: it names no `crate::` path and has no inner attributes, so it can
/// be a module file (`mod name;`) or `include!`d into `mod name { ... }`.
pub fn emit_plan_from(plan: &SolverPlan, problem_path: &str) -> Result<String, PipelineError> {
    emit_plan_in(plan, problem_path, CodeForm::Auto)
}

/// [`emit_plan_from`] with the coefficient code in the given form.
pub fn emit_plan_in(
    plan: &SolverPlan,
    problem_path: &str,
    code_form: CodeForm,
) -> Result<String, PipelineError> {
    let layout = &plan.problem.layout;
    let tracer = Tracer::new();
    let data = tracer.inputs(layout.data_slot_count());
    let (equations, elimination) = plan.equations(&data);
    let reject_spurious = plan.generated.built.template.spurious_eigenvalues > 0;
    let poor_only = plan.polishes_poor_solutions_only();
    let polish = match layout.options.newton_steps() {
        0 if !reject_spurious && !poor_only => None,
        steps => Some(PolishSpec {
            steps: if poor_only {
                mingen_runtime::POOR_SOLUTION_STEPS
            } else {
                steps as usize
            },
            poor_only,
            reject_spurious,
            equations: plan.visible_equations(&data),
            unknowns: plan.visible_unknowns(),
        }),
    };
    let spec = SolverSpec {
        layout: layout.clone(),
        template: plan.generated.built.template.clone(),
        equations,
        problem_path: problem_path.to_string(),
        elimination: elimination.map(|e| EliminationSpec {
            eliminated: e.eliminated,
            remaining: e.remaining,
            coefficient_matrix: e.coefficient_matrix,
            inhomogeneous: e.inhomogeneous,
        }),
        polish,
        code_form,
        sign_folds: plan.problem.sign_folds().to_vec(),
    };
    emit_solver(&spec).map_err(|source| PipelineError::Emit {
        file: plan.file.clone(),
        source,
    })
}
