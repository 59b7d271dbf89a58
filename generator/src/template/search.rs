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

use super::build::{build_template, BuiltTemplate, DegreeSearch};
use super::candidates::start_degree;
use super::linalg::is_squarefree;
use super::select::{basis_orders, BasisOrder};
use super::validate::nf_action_charpoly;
use super::{Action, ActionChoice, EquationReduction, TemplateError, TemplateOptions};
use crate::algebra::MonomialOrder;
use crate::algebra::{Fp, Monomial, Poly, P1};
use crate::budget::Deadline;
use crate::groebner::GroebnerBasis;
use crate::groebner::{groebner_with, GroebnerOptions};
use crate::quotient::{standard_monomials, Analysis};

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
    best_template_within(analysis, opts, &opts.budget.start())
}

/// [`best_template`] within a running budget.
pub(crate) fn best_template_within(
    analysis: &Analysis,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> Result<(BuiltTemplate, PerAction), TemplateError> {
    let (eqs, basis, gb) = (&analysis.equations, &analysis.basis, &analysis.groebner);
    let nvars = basis.first().map(|b| b.nvars()).unwrap_or(0);
    // Hidden variables (of `nonzero`) are not actions: they are not read out.
    let visible = nvars - opts.hidden_vars.min(nvars);
    let random = || {
        vec![Action::random(
            nvars,
            visible,
            opts.seed ^ RANDOM_ACTION_SEED,
        )]
    };
    let first: Vec<Action> = match &opts.actions {
        ActionChoice::Auto => (0..visible).map(|v| Action::var(nvars, v)).collect(),
        ActionChoice::Unknowns(vs) => vs.iter().map(|&v| Action::var(nvars, v)).collect(),
        ActionChoice::Random => random(),
    };
    // The equations as given, then (when it changes their monomials) their row reduction
    // on the instance's data: the same ideal, so the same bases and Gröbner basis.
    let reduction = opts
        .reduce_equations
        .then(|| EquationReduction::of(eqs))
        .flatten();
    let bases = if opts.alternative_bases {
        alternative_bases(eqs, basis, visible, deadline)
    } else {
        Vec::new()
    };
    let search_all = |eqs: &[Poly<Fp<P1>>]| {
        let mut all = search_actions(eqs, basis, gb, opts, deadline, &first);
        let has_distinct = all
            .iter()
            .any(|(_, r)| r.as_ref().is_ok_and(|b| b.distinct_eigenvalues));
        if opts.actions == ActionChoice::Auto && visible > 1 && !has_distinct {
            all.extend(search_actions(eqs, basis, gb, opts, deadline, &random()));
        }
        try_alternative_bases(eqs, &bases, visible, opts, deadline, &mut all);
        all
    };
    let mut all = search_all(eqs);
    let mut reduced_all: PerAction = Vec::new();
    if let Some((red, reduced)) = &reduction {
        reduced_all = search_all(reduced);
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
    if let Some(b) = choose(&all, opts) {
        finalists.push(refine(eqs, b, visible, opts, deadline));
    }
    if let (Some((red, reduced)), Some(b)) = (&reduction, choose(&reduced_all, opts)) {
        let mut r = refine(reduced, b, visible, opts, deadline);
        r.template.reduction = Some(red.clone());
        finalists.push(r);
    }
    merge_per_action(&mut all, reduced_all);
    let best = finalists
        .into_iter()
        .enumerate()
        .min_by_key(|(k, b)| (preference(b, opts), *k))
        .map(|(_, b)| b);
    match best {
        Some(b) => Ok((b, all)),
        None => Err(no_action(&all, opts)),
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
fn search_actions<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    gb: &GroebnerBasis<P>,
    opts: &TemplateOptions,
    deadline: &Deadline,
    monomials: &[Action],
) -> PerAction {
    // Basis selection costs most for actions that cannot be chosen anyway: with
    // `require_distinct_eigenvalues`, actions with a repeated eigenvalue get the standard
    // basis only, as long as some action has distinct eigenvalues.
    let distinct: Vec<bool> = monomials
        .iter()
        .map(|a| is_squarefree::<P>(&nf_action_charpoly::<P>(gb, basis, a)))
        .collect();
    let skip_selection = opts.require_distinct_eigenvalues && distinct.iter().any(|&d| d);
    let starts: Vec<u32> = monomials
        .iter()
        .map(|a| {
            let nvars = basis.first().map_or(0, Monomial::nvars);
            start_degree(eqs, basis, a, nvars - opts.hidden_vars.min(nvars))
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
            };
            let r = build_template(eqs, basis, STANDARD, v, &search, distinct[k], opts);
            (v.clone(), r)
        })
        .collect();
    if opts.adaptive_degree && all.iter().all(|(_, r)| r.is_err()) {
        raise_degree(
            eqs, basis, monomials, &starts, &distinct, opts, deadline, &mut all,
        );
    }
    all
}

/// The adaptive part of [`best_template_within`]: candidate degrees beyond every action's
/// first window, one degree at a time for all actions together, until one action reduces
/// (then every action that reduces at that degree is kept) or the budget runs out.
#[allow(clippy::too_many_arguments)]
fn raise_degree<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
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
            };
            let r = build_template(eqs, basis, STANDARD, a, &search, distinct[k], opts);
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

/// The standard bases of grevlex under the variable orders of
/// [`super::select::basis_orders`] other than the identity (the visible variables permuted,
/// hidden ones last), each from a Gröbner basis of the equations with the variables
/// renamed; bases equal to `basis` or to an earlier one, or of another size, are left out.
/// Stops when the budget runs out. Each comes with its description.
fn alternative_bases<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    visible: usize,
    deadline: &Deadline,
) -> Vec<(String, Vec<Monomial>)> {
    let nvars = basis.first().map_or(0, Monomial::nvars);
    let mut seen: Vec<Vec<Monomial>> = vec![sorted(basis.to_vec())];
    let mut out = Vec::new();
    for order in basis_orders(visible).into_iter().skip(1) {
        let BasisOrder::Grevlex(perm) = &order else {
            continue;
        };
        if deadline.check_time().is_err() {
            break;
        }
        // y_k = x_perm[k]: the k-th largest variable of the new order.
        let perm: Vec<usize> = perm.iter().copied().chain(visible..nvars).collect();
        let to_y = |m: &Monomial| Monomial(perm.iter().map(|&i| m.0[i]).collect());
        let permuted: Vec<Poly<Fp<P>>> = eqs
            .iter()
            .map(|f| Poly::from_terms(nvars, f.terms().map(|(m, c)| (to_y(m), *c))))
            .collect();
        let gopts = GroebnerOptions {
            deadline: Some(*deadline),
            ..GroebnerOptions::default()
        };
        let Ok(gb) = groebner_with(nvars, &permuted, &gopts) else {
            continue;
        };
        let Ok(b) = standard_monomials(&gb) else {
            continue;
        };
        let b: Vec<Monomial> = b
            .iter()
            .map(|y| {
                let mut e = vec![0; nvars];
                for (k, &i) in perm.iter().enumerate() {
                    e[i] = y.0[k];
                }
                Monomial(e)
            })
            .collect();
        let b = sorted(b);
        if b.len() != basis.len() || seen.contains(&b) {
            continue;
        }
        seen.push(b.clone());
        out.push((format!("standard monomials ({})", order.describe(&[])), b));
    }
    out
}

/// The size every choice minimises: [`super::EliminationTemplate::elimination_area`].
fn area(b: &BuiltTemplate) -> usize {
    b.template.elimination_area()
}

fn sorted(mut b: Vec<Monomial>) -> Vec<Monomial> {
    b.sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
    b
}

/// Replaces each action's template by the smallest one built on an alternative standard
/// basis, where that is smaller (actions without a template keep their error).
fn try_alternative_bases<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    bases: &[(String, Vec<Monomial>)],
    visible: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
    all: &mut PerAction,
) {
    for (label, b) in bases {
        for (action, result) in all.iter_mut() {
            let Ok(current) = result else { continue };
            if deadline.check_time().is_err() {
                return;
            }
            let start = start_degree(eqs, b, action, visible);
            let search = DegreeSearch {
                degrees: start..=start + opts.max_extra_degree,
                basis_selection: false,
                deadline: Some(deadline),
                exclude: false,
            };
            let distinct = current.distinct_eigenvalues;
            if let Ok(t) = build_template(eqs, b, label, action, &search, distinct, opts) {
                if area(&t) < area(current) {
                    *result = Ok(t);
                }
            }
        }
    }
}

/// The chosen template rebuilt on its basis with the greedy exclusion of
/// [`super::exclude`], when that is smaller; otherwise the template itself.
fn refine<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    best: BuiltTemplate,
    visible: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> BuiltTemplate {
    if !opts.exclude_monomials {
        return best;
    }
    let t = &best.template;
    let start = start_degree(eqs, &t.basis, &t.action, visible);
    let search = DegreeSearch {
        degrees: start..=start + opts.max_extra_degree,
        basis_selection: false,
        deadline: Some(deadline),
        exclude: true,
    };
    let label = best.basis_choice.clone();
    match build_template(
        eqs,
        &t.basis,
        &label,
        &t.action,
        &search,
        best.distinct_eigenvalues,
        opts,
    ) {
        Ok(r) if r.template.eliminated_size().0 < t.eliminated_size().0 => r,
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
    TemplateError::NoAction(
        reasons
            .iter()
            .map(|(r, names)| format!("action {}: {r}", names.join(", ")))
            .collect::<Vec<_>>()
            .join("; "),
    )
}
