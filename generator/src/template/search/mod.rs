//! The search over action variables and candidate degrees, on the instance the analysis
//! ([`crate::quotient::Analysis`]) computed its Gröbner basis for.
//!
//! ## Public API
//! - [`best_template`]: tries every unknown as action variable (within
//!   `opts.max_extra_degree` degrees of its start degree), keeps the best, and, when none
//!   works, raises the candidate degree for all of them together until one does or the
//!   budget runs out.
//!
//! [`crate::pipeline::find_template`] runs it between the analysis and the validation.

mod orders;
mod saturated;

use super::build::{build_template, BuiltTemplate, DegreeSearch};
use super::candidates::start_degree;
use super::fold::{fold_constant_rows, foldable_rows, EquationConstants};
use super::linalg::is_squarefree;
use super::redundant::{from_pools, with_redundant_basis, MAX_POOL_WORK};
use super::select::{basis_orders, BasisOrder};
use super::validate::nf_action_charpoly;
use super::weight_sample::{narrow_weights, neighbours, ones_and_twos, sampled_weights};
use super::{Action, ActionChoice, ColumnShift, EquationReduction, TemplateError, TemplateOptions};
use crate::algebra::MonomialOrder;
use crate::algebra::{Fp, Monomial, Poly, P1};
use crate::budget::Deadline;
use crate::groebner::GroebnerBasis;
use crate::groebner::{groebner_with, weights_fit, GroebnerError, GroebnerOptions};
use crate::problem::PolynomialSaturation;
use crate::quotient::{standard_monomials, Analysis};
use orders::{
    alternative_bases, climb_weights, narrow_bases, try_alternative_bases, AlternativeBasis,
    NARROW_BUDGET_SHARE,
};

/// Every action's result: `(action, template or why none)`.
pub type PerAction = Vec<(Action, Result<BuiltTemplate, TemplateError>)>;

/// How the grevlex standard basis of the analysis is described.
const STANDARD: &str = "standard monomials (grevlex)";

/// Appended to the description of a template built from the row-reduced equations.
const REDUCED: &str = ", equations row-reduced on the data";

/// Seed offset of the random linear-combination action.
const RANDOM_ACTION_SEED: u64 = 0xAC71_0000;

/// Tries each action of `opts.actions` on the analysed instance (its equations, standard
/// basis and Gröbner basis, all mod P1) and keeps the template with the fewest
/// `rows * cols`, among those whose action matrix has distinct eigenvalues when
/// `opts.require_distinct_eigenvalues` (falling back to all if none has); ties go to the
/// action tried first. With [`ActionChoice::Auto`], the unknowns are tried first and a
/// random linear combination of them only when none has distinct eigenvalues. Returns
/// the best and, for every action tried, its result.
///
/// Each action is first tried at candidate degrees up to `opts.max_extra_degree` above its
/// start degree; if none works and `opts.adaptive_degree`, the degree is raised for all
/// actions together, one degree at a time, until one works or `opts.budget` runs out.
pub fn best_template(
    analysis: &Analysis,
    opts: &TemplateOptions,
) -> Result<(BuiltTemplate, PerAction), TemplateError> {
    best_template_within(analysis, opts, &opts.budget.start(), &[])
}

/// [`best_template`] within a running budget.
pub(crate) fn best_template_within(
    analysis: &Analysis,
    opts: &TemplateOptions,
    deadline: &Deadline,
    constants: &[EquationConstants],
) -> Result<(BuiltTemplate, PerAction), TemplateError> {
    let (eqs, basis, gb) = (&analysis.equations, &analysis.basis, &analysis.groebner);
    let nvars = basis.first().map(|b| b.nvars()).unwrap_or(0);
    if let Some(w) = opts.weights.iter().find(|w| !weights_fit(w, nvars)) {
        return Err(GroebnerError::Weights {
            got: w.clone(),
            nvars,
        }
        .into());
    }
    // Hidden variables (of `nonzero`) are not actions: they are not read out.
    let visible = nvars - opts.hidden_vars.min(nvars);
    let random = || {
        vec![Action::random(
            nvars,
            visible,
            opts.seed ^ RANDOM_ACTION_SEED,
        )]
    };
    let mut first: Vec<Action> = match &opts.actions {
        ActionChoice::Auto => (0..visible).map(|v| Action::var(nvars, v)).collect(),
        ActionChoice::Unknowns(vs) => vs.iter().map(|&v| Action::var(nvars, v)).collect(),
        ActionChoice::Inverse(v) => vec![Action::inverse_of_var(nvars, *v)],
        ActionChoice::Random => random(),
    };
    // Laurent actions `1 / x_v` after the unknowns themselves (ties go to the unknown);
    // with a redundant basis requested too, which grows further from some of them.
    if opts.laurent_actions || opts.redundant_bases {
        let inverses: Vec<Action> = first
            .iter()
            .filter_map(|a| a.single().map(|v| Action::inverse_of_var(nvars, v)))
            .collect();
        first.extend(inverses);
    }
    // A `nonzero`: the saturation inside the template (`saturated.rs`), in the unknowns as
    // declared. Where a monomial's gives a template, the search with the hidden unknown
    // (one variable more in every pool and basis) is not run. A polynomial's template
    // cannot fold (its columns are not monomials), while the hidden unknown's equation
    // `u s - 1` has numeric coefficients and its multiples often fold away: both are
    // searched and the smaller kept. The saturated template's rows refer to the equations
    // before the hidden ones, which keep their indices in `eqs`.
    // The equations as given, then (when it changes their monomials) their row reduction
    // on the instance's data: the same ideal, so the same bases and Gröbner basis.
    let reduction = opts
        .reduce_equations
        .then(|| EquationReduction::of(eqs))
        .flatten();
    // Equations of very different scales are solved through their reduction only.
    let as_given = !(opts.reduced_equations_only && reduction.is_some());
    let saturated = as_given
        .then(|| {
            saturated::saturated_templates(eqs, Some(constants), basis, gb, opts, deadline, &first)
        })
        .flatten();
    let mut saturated_finalist = None;
    if let Some((b, written, saturated)) =
        saturated.and_then(|(all, written)| choose(&all, opts).map(|b| (b, written, all)))
    {
        let mut b = refine(written, Some(constants), b, visible, opts, deadline);
        fold_constant_rows(&mut b.template, constants);
        if b.template.shift.is_none()
            || opts.polynomial_saturation == PolynomialSaturation::Template
        {
            return Ok((b, saturated));
        }
        saturated_finalist = Some((b, saturated));
    }
    let bases = if opts.alternative_bases {
        alternative_bases(eqs, basis, visible, opts, deadline)
    } else {
        Vec::new()
    };
    // The narrow sample's phase may use part of the budget only: the refinement and the
    // validation after it keep theirs.
    let narrow_deadline = deadline.portion(NARROW_BUDGET_SHARE);
    let narrow = if opts.alternative_bases {
        narrow_bases(eqs, basis, &bases, opts, &narrow_deadline)
    } else {
        Vec::new()
    };
    // Every basis either sample found: the narrow sample's climbs skip them all.
    let both_samples: Vec<AlternativeBasis> = bases.iter().chain(&narrow).cloned().collect();
    let search_all = |eqs: &[Poly<Fp<P1>>], constants: Constants<'_>| {
        let mut all = search_actions(eqs, constants, basis, gb, opts, deadline, &first);
        let has_distinct = all
            .iter()
            .any(|(_, r)| r.as_ref().is_ok_and(|b| b.distinct_eigenvalues));
        if opts.actions == ActionChoice::Auto && visible > 1 && !has_distinct {
            all.extend(search_actions(
                eqs,
                constants,
                basis,
                gb,
                opts,
                deadline,
                &random(),
            ));
        }
        let mut work = 0u64;
        // An action whose check runs out of budget counts as not distinct: the search
        // after it stops on the same budget.
        let distinct_of =
            |a: &Action| quotient_action(gb, basis, a, opts, deadline).unwrap_or(false);
        let starts = try_alternative_bases(
            eqs,
            constants,
            &bases,
            visible,
            opts,
            deadline,
            &distinct_of,
            &mut work,
            &mut all,
        );
        climb_weights(
            eqs, constants, basis, &bases, starts, visible, opts, deadline, &mut work, &mut all,
        );
        // Then the narrow sample, on work of its own, and climbs from its best.
        let mut narrow_work = 0u64;
        let starts = try_alternative_bases(
            eqs,
            constants,
            &narrow,
            visible,
            opts,
            &narrow_deadline,
            &distinct_of,
            &mut narrow_work,
            &mut all,
        );
        climb_weights(
            eqs,
            constants,
            basis,
            &both_samples,
            starts,
            visible,
            opts,
            &narrow_deadline,
            &mut narrow_work,
            &mut all,
        );
        all
    };
    let mut all = if as_given {
        search_all(eqs, Some(constants))
    } else {
        Vec::new()
    };
    let mut reduced_all: PerAction = Vec::new();
    if let Some((red, reduced)) = &reduction {
        reduced_all = search_all(reduced, None);
        for (_, r) in &mut reduced_all {
            if let Ok(b) = r {
                b.template.reduction = Some(red.clone());
                b.basis_choice.push_str(REDUCED);
            }
        }
    }
    // The best of each equation set is refined, then the smaller kept (ties: the
    // equations as given): refinement can reorder them.
    let mut finalists = Vec::new();
    // The refined quotient template each equation set's pools start from (`from_pools`),
    // and whether it is the set row-reduced on the data.
    let mut pool_quotients: Vec<(BuiltTemplate, bool)> = Vec::new();
    for (k, b) in starts(&all, opts).into_iter().enumerate() {
        // The equations as given may have rows to fold (`fold.rs`): every template was
        // compared by its area after the fold, counted in Z_p; the chosen one is folded.
        let b = refine(eqs, Some(constants), b, visible, opts, deadline);
        if k == 0 && opts.redundant_bases {
            pool_quotients.push((b.clone(), false));
        }
        let mut b = with_redundant_basis(
            eqs,
            Some(constants),
            b,
            visible,
            basis.len(),
            opts,
            deadline,
        );
        fold_finalist(&mut b, constants);
        finalists.push(b);
    }
    if let Some((red, reduced)) = &reduction {
        for (k, b) in starts(&reduced_all, opts).into_iter().enumerate() {
            let r = refine(reduced, None, b, visible, opts, deadline);
            if k == 0 && opts.redundant_bases {
                pool_quotients.push((r.clone(), true));
            }
            let mut r =
                with_redundant_basis(reduced, None, r, visible, basis.len(), opts, deadline);
            set_reduction(&mut r, red);
            finalists.push(r);
        }
    }
    // Redundant templates from the candidate pools of every action (`redundant.rs`), last:
    // the quotient templates above are refined on the budget before them. The actions
    // qualify by their quotient's characteristic polynomial, the same for both equation
    // sets (one ideal).
    let qualified: Vec<(Action, Vec<u32>)> = if pool_quotients.is_empty() {
        Vec::new()
    } else {
        first
            .iter()
            .filter_map(|a| {
                let c = nf_action_charpoly::<P1>(gb, basis, a, Some(deadline)).ok()?;
                is_squarefree::<P1>(&c).then(|| (a.clone(), c))
            })
            .collect()
    };
    let mut work = MAX_POOL_WORK;
    for (quotient, on_reduced) in pool_quotients {
        let (system, system_constants) = match (&reduction, on_reduced) {
            (Some((_, reduced)), true) => (&reduced[..], None),
            _ => (&eqs[..], Some(constants)),
        };
        let dims = (visible, basis.len());
        let bounds = (&mut work, deadline);
        let pooled = from_pools(
            system,
            system_constants,
            &quotient,
            &qualified,
            dims,
            opts,
            bounds,
        );
        for mut p in pooled {
            match (&reduction, on_reduced) {
                (Some((red, _)), true) => set_reduction(&mut p, red),
                _ => fold_finalist(&mut p, constants),
            }
            finalists.push(p);
        }
    }
    merge_per_action(&mut all, reduced_all);
    if let Some((b, saturated)) = saturated_finalist {
        finalists.push(b);
        merge_per_action(&mut all, saturated);
    }
    match best_finalist(finalists, opts) {
        Some(b) => Ok((b, all)),
        None => Err(no_action(&all, opts)),
    }
}

/// Folds a finalist of the equations as given (`fold.rs`), with the quotient-basis
/// template and the redundant alternatives it carries.
fn fold_finalist(b: &mut BuiltTemplate, constants: &[EquationConstants]) {
    fold_constant_rows(&mut b.template, constants);
    if let Some(q) = &mut b.quotient_basis {
        fold_constant_rows(&mut q.template, constants);
    }
    for a in &mut b.redundant_alternatives {
        fold_constant_rows(&mut a.template, constants);
    }
}

/// Marks a finalist of the equations row-reduced on the data, with the templates it
/// carries, as solved through that reduction.
fn set_reduction(b: &mut BuiltTemplate, red: &EquationReduction) {
    b.template.reduction = Some(red.clone());
    if let Some(q) = &mut b.quotient_basis {
        q.template.reduction = Some(red.clone());
    }
    for a in &mut b.redundant_alternatives {
        a.template.reduction = Some(red.clone());
    }
}

/// The order templates are chosen in: those with distinct eigenvalues first when
/// `opts.require_distinct_eigenvalues`, then by [`area`].
fn preference(b: &BuiltTemplate, opts: &TemplateOptions) -> (bool, usize) {
    (
        opts.require_distinct_eigenvalues && !b.distinct_eigenvalues,
        area(b),
    )
}

/// The preferred template of a search (see [`preference`]; ties to the action tried
/// first).
fn choose(all: &PerAction, opts: &TemplateOptions) -> Option<BuiltTemplate> {
    all.iter()
        .enumerate()
        .filter_map(|(k, (_, r))| r.as_ref().ok().map(|b| (k, b)))
        .min_by_key(|(k, b)| (preference(b, opts), *k))
        .map(|(_, b)| b.clone())
}

/// The preferred of the finalists (ties: the earlier). A finalist with a redundant basis
/// stands for itself, its alternatives and the quotient-basis template it grew from; the
/// chosen one gets every redundant template smaller than the preferred quotient-basis
/// template, smallest first (itself, then its `redundant_alternatives`), and that template
/// as its `quotient_basis`: what the plan falls back on when it drops them all.
fn best_finalist(finalists: Vec<BuiltTemplate>, opts: &TemplateOptions) -> Option<BuiltTemplate> {
    let mut quotients = Vec::new();
    let mut redundant = Vec::new();
    for mut f in finalists {
        match f.quotient_basis.take() {
            Some(q) => {
                quotients.push(*q);
                redundant.append(&mut f.redundant_alternatives);
                redundant.push(f);
            }
            None => quotients.push(f),
        }
    }
    let quotient = quotients
        .into_iter()
        .enumerate()
        .min_by_key(|(k, b)| (preference(b, opts), *k))
        .map(|(_, b)| b)?;
    redundant.retain(|r| preference(r, opts) < preference(&quotient, opts));
    redundant.sort_by_key(BuiltTemplate::folded_area);
    redundant.dedup_by_key(|r| r.template.eliminated_size());
    if redundant.is_empty() {
        return Some(quotient);
    }
    let mut chosen = redundant.remove(0);
    chosen.quotient_basis = Some(Box::new(quotient));
    chosen.redundant_alternatives = redundant;
    Some(chosen)
}

/// The templates of a search that are refined and, with `opts.redundant_bases`, grown into
/// a redundant basis: the preferred one ([`choose`]), and with a redundant basis also the
/// preferred one among the Laurent actions when that is another action (on a quotient
/// basis the inverse's template is rarely smaller, but the basis grown on it can be).
fn starts(all: &PerAction, opts: &TemplateOptions) -> Vec<BuiltTemplate> {
    let mut out: Vec<BuiltTemplate> = choose(all, opts).into_iter().collect();
    if opts.redundant_bases {
        let laurent: PerAction = all
            .iter()
            .filter(|(a, _)| a.inverse_of().is_some())
            .cloned()
            .collect();
        if let Some(l) = choose(&laurent, opts) {
            if out.iter().all(|b| b.template.action != l.template.action) {
                out.push(l);
            }
        }
    }
    out
}

/// Each action of `more` keeps, in `all`, the smaller of its two templates (ties: the one
/// already there); actions new to `all` are appended.
fn merge_per_action(all: &mut PerAction, more: PerAction) {
    for (action, r) in more {
        match all.iter_mut().find(|(a, _)| *a == action) {
            Some((_, current)) => {
                let better = match (&r, &*current) {
                    (Ok(new), Ok(old)) => area(new) < area(old),
                    (Ok(_), Err(_)) => true,
                    _ => false,
                };
                if better {
                    *current = r;
                }
            }
            None => all.push((action, r)),
        }
    }
}

/// The templates of the actions `monomials`, each first within its window of
/// `opts.max_extra_degree`, then (see [`raise_degree`]) beyond.
#[allow(clippy::too_many_arguments)]
fn search_actions<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Constants<'_>,
    basis: &[Monomial],
    gb: &GroebnerBasis<P>,
    opts: &TemplateOptions,
    deadline: &Deadline,
    monomials: &[Action],
) -> PerAction {
    // Basis selection costs most for actions that cannot be chosen anyway: with
    // `require_distinct_eigenvalues`, actions with a repeated eigenvalue get the standard
    // basis only, as long as some action has distinct eigenvalues.
    let checks: Vec<Result<bool, TemplateError>> = monomials
        .iter()
        .map(|a| quotient_action(gb, basis, a, opts, deadline))
        .collect();
    let distinct: Vec<bool> = checks.iter().map(|c| matches!(c, Ok(true))).collect();
    let skip_selection = opts.require_distinct_eigenvalues && distinct.iter().any(|&d| d);
    let starts: Vec<u32> = monomials
        .iter()
        .map(|a| {
            let nvars = basis.first().map_or(0, Monomial::nvars);
            start_degree(eqs, basis, a, nvars - opts.hidden_vars.min(nvars), &[])
        })
        .collect();
    let mut all: PerAction = monomials
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let search = DegreeSearch {
                degrees: starts[k]..=starts[k] + opts.max_extra_degree,
                basis_selection: opts.basis_selection && (!skip_selection || distinct[k]),
                deadline: Some(deadline),
                exclude: false,
                weights: &[],
                max_pool: None,
                shift: None,
            };
            let r = checks[k].clone().and_then(|distinct| {
                build_template(eqs, basis, STANDARD, v, &search, distinct, opts)
            });
            (v.clone(), with_fold_count(r, constants))
        })
        .collect();
    if opts.adaptive_degree && all.iter().all(|(_, r)| r.is_err()) {
        raise_degree(
            eqs, constants, basis, STANDARD, None, monomials, &starts, &distinct, opts, deadline,
            &mut all,
        );
    }
    all
}

/// How `action` acts on the quotient (normal forms of `gb` on `basis`): whether its
/// matrix has distinct eigenvalues (a check that runs out of `deadline` counts as not
/// distinct), or `Err` for a Laurent action `1 / x` whose `x` is zero on a solution, so
/// that the search does not raise its degree for a template that cannot exist.
fn quotient_action<const P: u32>(
    gb: &GroebnerBasis<P>,
    basis: &[Monomial],
    action: &Action,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> Result<bool, TemplateError> {
    match nf_action_charpoly::<P>(gb, basis, action, Some(deadline)) {
        Ok(c) => Ok(is_squarefree::<P>(&c)),
        Err(TemplateError::Singular { .. }) if action.inverse_of().is_some() => {
            Err(TemplateError::NotInvertible {
                action: action.display_with(&opts.var_names),
            })
        }
        Err(_) => Ok(false),
    }
}

/// The adaptive part of [`best_template_within`]: candidate degrees beyond every action's
/// first window, one degree at a time for all actions together, until one action reduces
/// (then every action that reduces at that degree is kept) or the budget runs out.
/// `label` describes `basis` in the templates built.
#[allow(clippy::too_many_arguments)]
fn raise_degree<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Constants<'_>,
    basis: &[Monomial],
    label: &str,
    shift: Option<&ColumnShift>,
    monomials: &[Action],
    starts: &[u32],
    distinct: &[bool],
    opts: &TemplateOptions,
    deadline: &Deadline,
    all: &mut PerAction,
) {
    // Only actions that failed for want of degree can gain from more: a template that
    // was found but refused (a basis without an unknown, ...) stays refused.
    let raisable = |r: &Result<BuiltTemplate, TemplateError>| {
        matches!(
            r,
            Err(TemplateError::NotReducible {
                exhausted: None,
                ..
            })
        )
    };
    let mut live: Vec<bool> = all.iter().map(|(_, r)| raisable(r)).collect();
    let first = starts.iter().min().copied().unwrap_or(0) + opts.max_extra_degree + 1;
    for d in first.. {
        if !live.contains(&true) {
            return;
        }
        let mut any = false;
        for (k, a) in monomials.iter().enumerate() {
            if !live[k] || d <= starts[k] + opts.max_extra_degree {
                continue;
            }
            let search = DegreeSearch {
                degrees: d..=d,
                basis_selection: false,
                deadline: Some(deadline),
                exclude: false,
                weights: &[],
                max_pool: None,
                shift,
            };
            let r = with_fold_count(
                build_template(eqs, basis, label, a, &search, distinct[k], opts),
                constants,
            );
            let stop = matches!(
                &r,
                Err(TemplateError::NotReducible {
                    exhausted: Some(_),
                    ..
                })
            );
            any |= r.is_ok();
            live[k] = raisable(&r);
            all[k].1 = r;
            if stop {
                return;
            }
        }
        if any {
            return;
        }
    }
}

/// The size every choice minimises: [`super::EliminationTemplate::elimination_area`].
fn area(b: &BuiltTemplate) -> usize {
    b.folded_area()
}

/// The equations' constants where the search folds (the equations as given), `None` for
/// equations row-reduced on the data (never folded).
type Constants<'a> = Option<&'a [EquationConstants]>;

/// `r` with [`BuiltTemplate::foldable_rows`] counted for `constants`.
fn with_fold_count(
    r: Result<BuiltTemplate, TemplateError>,
    constants: Constants<'_>,
) -> Result<BuiltTemplate, TemplateError> {
    r.map(|mut b| {
        b.foldable_rows = constants.map_or(0, |c| foldable_rows(&b.template, c));
        b
    })
}

fn sorted(mut b: Vec<Monomial>) -> Vec<Monomial> {
    b.sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
    b
}

/// The candidate degrees an alternative basis (or a refinement) is built at: from the
/// start degree, `opts.max_extra_degree` degrees up (in a weighted grading, that many times
/// its largest weight), neither exclusion nor basis selection.
fn degree_window<'a, const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    action: &Action,
    visible: usize,
    opts: &TemplateOptions,
    deadline: &'a Deadline,
    weights: &'a [u32],
) -> DegreeSearch<'a> {
    let start = start_degree(eqs, basis, action, visible, weights);
    let step = weights.iter().copied().max().unwrap_or(1);
    DegreeSearch {
        degrees: start..=start + opts.max_extra_degree * step,
        basis_selection: false,
        deadline: Some(deadline),
        exclude: false,
        weights,
        max_pool: None,
        shift: None,
    }
}

/// The chosen template rebuilt on its basis with the greedy exclusion of
/// [`super::exclude`], when that is smaller; otherwise the template itself.
fn refine<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Constants<'_>,
    best: BuiltTemplate,
    visible: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> BuiltTemplate {
    if !opts.exclude_monomials {
        return best;
    }
    let t = &best.template;
    let weights = best.pool_weights.clone();
    let search = DegreeSearch {
        exclude: true,
        shift: t.shift.as_ref(),
        ..degree_window(eqs, &t.basis, &t.action, visible, opts, deadline, &weights)
    };
    let label = best.basis_choice.clone();
    let r = build_template(
        eqs,
        &t.basis,
        &label,
        &t.action,
        &search,
        best.distinct_eigenvalues,
        opts,
    );
    match with_fold_count(r, constants) {
        Ok(r) if area(&r) < area(&best) => r,
        _ => best,
    }
}

/// The error of a search in which no action worked: one clause per distinct reason,
/// naming the actions that failed for it.
fn no_action(all: &PerAction, opts: &TemplateOptions) -> TemplateError {
    let mut reasons: Vec<(String, Vec<String>)> = Vec::new();
    for (v, r) in all {
        let Err(e) = r else { continue };
        let name = v.display_with(&opts.var_names);
        let reason = e.to_string();
        match reasons.iter_mut().find(|(r, _)| *r == reason) {
            Some((_, names)) => names.push(name),
            None => reasons.push((reason, vec![name])),
        }
    }
    TemplateError::NoAction {
        reasons: reasons
            .iter()
            .map(|(r, names)| format!("action {}: {r}", names.join(", ")))
            .collect::<Vec<_>>()
            .join("; "),
        exhausted: all
            .iter()
            .find_map(|(_, r)| r.as_ref().err().and_then(TemplateError::exhausted)),
    }
}
