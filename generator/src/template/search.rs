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

use super::build::assemble;
use super::build::{build_template, BuiltTemplate, DegreeSearch};
use super::candidates::{start_degree, Blocks, Candidate};
use super::fold::{fold_constant_rows, foldable_rows, EquationConstants};
use super::linalg::{charpoly_within, derivative, is_squarefree, poly_gcd};
use super::redundant::grow_basis;
use super::select::{basis_orders, BasisOrder};
use super::validate::{nf_action_charpoly, template_action_matrix};
use super::weight_sample::{narrow_weights, neighbours, ones_and_twos, sampled_weights};
use super::{
    Action, ActionChoice, EliminationTemplate, EquationReduction, TemplateError, TemplateOptions,
};
use crate::algebra::MonomialOrder;
use crate::algebra::{Fp, Monomial, Poly, P1};
use crate::budget::Deadline;
use crate::groebner::GroebnerBasis;
use crate::groebner::{groebner_with, weights_fit, GroebnerError, GroebnerOptions};
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
        let distinct_of = |a: &Action| {
            nf_action_charpoly::<P1>(gb, basis, a, Some(deadline))
                .is_ok_and(|c| is_squarefree::<P1>(&c))
        };
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
    let mut all = search_all(eqs, Some(constants));
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
    if let Some(b) = choose(&all, opts) {
        // The equations as given may have rows to fold (`fold.rs`): every template was
        // compared by its area after the fold, counted in Z_p; the chosen one is folded.
        let b = refine(eqs, Some(constants), b, visible, opts, deadline);
        let mut b = with_redundant_basis(
            eqs,
            Some(constants),
            b,
            visible,
            basis.len(),
            opts,
            deadline,
        );
        fold_constant_rows(&mut b.template, constants);
        if let Some(q) = &mut b.quotient_basis {
            fold_constant_rows(&mut q.template, constants);
        }
        finalists.push(b);
    }
    if let (Some((red, reduced)), Some(b)) = (&reduction, choose(&reduced_all, opts)) {
        let r = refine(reduced, None, b, visible, opts, deadline);
        let mut r = with_redundant_basis(reduced, None, r, visible, basis.len(), opts, deadline);
        r.template.reduction = Some(red.clone());
        if let Some(q) = &mut r.quotient_basis {
            q.template.reduction = Some(red.clone());
        }
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
    let distinct: Vec<bool> = monomials
        .iter()
        .map(|a| {
            nf_action_charpoly::<P>(gb, basis, a, Some(deadline))
                .is_ok_and(|c| is_squarefree::<P>(&c))
        })
        .collect();
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
            };
            let r = build_template(eqs, basis, STANDARD, v, &search, distinct[k], opts);
            (v.clone(), with_fold_count(r, constants))
        })
        .collect();
    if opts.adaptive_degree && all.iter().all(|(_, r)| r.is_err()) {
        raise_degree(
            eqs, constants, basis, monomials, &starts, &distinct, opts, deadline, &mut all,
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
    constants: Constants<'_>,
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
                weights: &[],
                max_pool: None,
            };
            let r = with_fold_count(
                build_template(eqs, basis, STANDARD, a, &search, distinct[k], opts),
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

/// A quotient basis other than the analysis's: the standard monomials of another
/// monomial order, with the grading its candidate pools use.
#[derive(Clone)]
struct AlternativeBasis {
    /// How it was obtained, for `inspect`.
    label: String,
    /// The standard monomials, descending grevlex.
    basis: Vec<Monomial>,
    /// The weights of its order (empty for grevlex under a variable order); its candidate
    /// pools are graded by the same weights.
    weights: Vec<u32>,
    /// The one unknown whose action it is tried for (the heaviest of `weights`), or none
    /// for every action.
    for_unknown: Option<usize>,
}

/// The standard bases of other monomial orders, each from a Gröbner basis of the
/// equations on the analysis instance: grevlex under the variable orders of
/// [`super::select::basis_orders`] other than the identity (the visible variables permuted,
/// hidden ones last), then the weighted orders: `opts.weights`, the grid of
/// [`ones_and_twos`] and the sample of [`sampled_weights`]. Bases equal to `basis` or to an
/// earlier one (except those of `opts.weights`), or of another size, are left out. Stops
/// when the budget runs out.
fn alternative_bases<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    visible: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> Vec<AlternativeBasis> {
    let nvars = basis.first().map_or(0, Monomial::nvars);
    let mut seen: Vec<Vec<Monomial>> = vec![sorted(basis.to_vec())];
    let mut out = Vec::new();
    let mut keep = |label: String, b: Vec<Monomial>, weights: Vec<u32>, always: bool| {
        let b = sorted(b);
        let new = b.len() == basis.len() && !seen.contains(&b);
        if new {
            seen.push(b.clone());
        }
        if new || (always && b.len() == basis.len()) {
            out.push(AlternativeBasis {
                label,
                basis: b,
                weights,
                for_unknown: None,
            });
        }
        new
    };
    // The orders the caller asked for first, each kept: their pools' grading is theirs.
    for weights in &opts.weights {
        if deadline.check_time().is_err() {
            return out;
        }
        if let Some(b) = weighted_basis(eqs, nvars, weights, deadline) {
            keep(weighted_label(weights), b, weights.clone(), true);
        }
    }
    for order in basis_orders(visible).into_iter().skip(1) {
        let BasisOrder::Grevlex(perm) = &order else {
            continue;
        };
        if deadline.check_time().is_err() {
            return out;
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
        keep(
            format!("standard monomials ({})", order.describe(&[])),
            b,
            Vec::new(),
            false,
        );
    }
    // The grid of 1s and 2s (small problems), then a sample; a Gröbner basis for each
    // until `opts.weighted_orders` bases beyond the grid's are new, most vectors falling in
    // cones already seen.
    let grid = ones_and_twos(nvars, opts.weighted_orders);
    let wanted = grid.len() + opts.weighted_orders;
    let draws = wanted.saturating_mul(DRAWS_PER_ORDER);
    let sample = sampled_weights(nvars, draws.saturating_sub(grid.len()), opts.seed);
    let sample: Vec<Vec<u32>> = sample.into_iter().filter(|w| !grid.contains(w)).collect();
    let mut kept = 0;
    for weights in grid.into_iter().chain(sample) {
        if deadline.check_time().is_err() || kept >= wanted {
            break;
        }
        if let Some(b) = weighted_basis(eqs, nvars, &weights, deadline) {
            kept += usize::from(keep(weighted_label(&weights), b, weights, false));
        }
    }
    out
}

/// The standard bases of weighted orders whose weights lie within a factor of four of
/// each other ([`narrow_weights`]), other than `basis` and those of `known`: up to
/// [`NARROW_BASES_PER_ORDER`] times `opts.weighted_orders` of them, in the order drawn.
/// Stops when the budget runs out.
fn narrow_bases<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    known: &[AlternativeBasis],
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> Vec<AlternativeBasis> {
    let nvars = basis.first().map_or(0, Monomial::nvars);
    let wanted = opts.weighted_orders.saturating_mul(NARROW_BASES_PER_ORDER);
    let mut seen: Vec<Vec<Monomial>> = std::iter::once(sorted(basis.to_vec()))
        .chain(known.iter().map(|b| b.basis.clone()))
        .collect();
    let mut out = Vec::new();
    let draws = wanted.saturating_mul(DRAWS_PER_ORDER);
    let visible = nvars - opts.hidden_vars.min(nvars);
    for (unknown, weights) in narrow_weights(nvars, visible, draws, opts.seed) {
        if out.len() >= wanted || deadline.check_time().is_err() {
            break;
        }
        let Some(b) = weighted_basis(eqs, nvars, &weights, deadline) else {
            continue;
        };
        if b.len() != basis.len() || seen.contains(&b) {
            continue;
        }
        seen.push(b.clone());
        out.push(AlternativeBasis {
            label: weighted_label(&weights),
            basis: b,
            weights,
            for_unknown: Some(unknown),
        });
    }
    out
}

/// How many bases of the narrow sample [`narrow_bases`] looks for, per weighted order of
/// `opts.weighted_orders`: the cones of such orders are many and small, the good ones rare.
const NARROW_BASES_PER_ORDER: usize = 4;

/// The share of the wall-clock budget the narrow sample's phase may use.
const NARROW_BUDGET_SHARE: f64 = 0.5;

/// The standard monomials (descending grevlex) of the weighted order `weights`, from a
/// Gröbner basis of `eqs` in that order; none when it fails or the budget runs out.
fn weighted_basis<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    nvars: usize,
    weights: &[u32],
    deadline: &Deadline,
) -> Option<Vec<Monomial>> {
    let gopts = GroebnerOptions {
        deadline: Some(*deadline),
        weights: weights.to_vec(),
        ..GroebnerOptions::default()
    };
    let gb = groebner_with(nvars, eqs, &gopts).ok()?;
    standard_monomials(&gb).ok().map(sorted)
}

/// How a basis of the weighted order `weights` is described.
fn weighted_label(weights: &[u32]) -> String {
    format!("standard monomials (weighted order, weights {weights:?})")
}

/// At most how many weight vectors [`alternative_bases`] computes a Gröbner basis for,
/// per new basis it looks for.
const DRAWS_PER_ORDER: usize = 8;

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

/// Replaces each action's template by the smallest one built on an alternative standard
/// basis, where that is smaller. An action without a template on the standard basis (an
/// unknown that basis cannot read off, say) is tried too, against the smallest template of
/// the other actions, and gets the first template found; `distinct_of` tells whether its
/// action matrix has distinct eigenvalues. Returns the [`CLIMB_STARTS`] smallest templates
/// built on weighted orders, with the index of their action in `all`, smallest first:
/// where [`climb_weights`] starts.
#[allow(clippy::too_many_arguments)]
fn try_alternative_bases<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Constants<'_>,
    bases: &[AlternativeBasis],
    visible: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
    distinct_of: &dyn Fn(&Action) -> bool,
    work: &mut u64,
    all: &mut PerAction,
) -> Vec<(usize, BuiltTemplate)> {
    let mut starts: Vec<(usize, BuiltTemplate)> = Vec::new();
    if bases.is_empty() {
        return starts;
    }
    let Some(smallest) = all
        .iter()
        .filter_map(|(_, r)| r.as_ref().ok())
        .min_by_key(|b| area(b))
        .cloned()
    else {
        return starts;
    };
    let distinct: Vec<bool> = all
        .iter()
        .map(|(a, r)| {
            r.as_ref()
                .map_or_else(|_| distinct_of(a), |b| b.distinct_eigenvalues)
        })
        .collect();
    'bases: for alt in bases {
        for (k, (action, result)) in all.iter_mut().enumerate() {
            if alt.for_unknown.is_some_and(|v| action.single() != Some(v)) {
                continue;
            }
            let current = result.as_ref().unwrap_or(&smallest);
            if deadline.check_time().is_err() {
                break 'bases;
            }
            if !alt.weights.is_empty() && !take_work(work, current) {
                continue;
            }
            let search = pool_capped(
                current,
                degree_window(
                    eqs,
                    &alt.basis,
                    action,
                    visible,
                    opts,
                    deadline,
                    &alt.weights,
                ),
            );
            let r = with_fold_count(
                build_template(
                    eqs,
                    &alt.basis,
                    &alt.label,
                    action,
                    &search,
                    distinct[k],
                    opts,
                ),
                constants,
            );
            if let Ok(t) = r {
                if !t.pool_weights.is_empty() {
                    remember_start(&mut starts, k, &t);
                }
                if result.as_ref().map_or(true, |c| area(&t) < area(c)) {
                    *result = Ok(t);
                }
            }
        }
    }
    starts
}

/// How many of the smallest weighted templates [`climb_weights`] climbs from.
const CLIMB_STARTS: usize = 3;

/// Keeps `t` among the [`CLIMB_STARTS`] smallest weighted templates of `starts` (ties to
/// the earlier), sorted by area.
fn remember_start(starts: &mut Vec<(usize, BuiltTemplate)>, action: usize, t: &BuiltTemplate) {
    let at = starts.partition_point(|(_, s)| area(s) <= area(t));
    if at < CLIMB_STARTS {
        starts.insert(at, (action, t.clone()));
        starts.truncate(CLIMB_STARTS);
    }
}

/// `search` with candidate pools capped at [`POOL_FACTOR`] times the rows of `current`,
/// the template to beat: a pool many times that rarely shrinks below it.
fn pool_capped<'a>(current: &BuiltTemplate, search: DegreeSearch<'a>) -> DegreeSearch<'a> {
    DegreeSearch {
        max_pool: Some((POOL_FACTOR * current.template.eliminated_size().0) as u64),
        ..search
    }
}

/// The work all templates on weighted orders of one equation set may take, in units of
/// the squared rows of the template each must beat (see [`take_work`]): a count, not a
/// time, so that the search stays deterministic, and small templates, cheap to build, get
/// many orders where large ones get few.
const WEIGHTED_WORK: u64 = 30_000_000;

/// Charges one template on a weighted order against `work`: the squared rows of `current`,
/// the template it must beat (its pools are bounded by [`POOL_FACTOR`] times those rows).
/// False, and nothing charged, when that would pass [`WEIGHTED_WORK`].
fn take_work(work: &mut u64, current: &BuiltTemplate) -> bool {
    let rows = current.template.eliminated_size().0 as u64;
    let cost = rows.saturating_mul(rows).max(1);
    if work.saturating_add(cost) > WEIGHTED_WORK {
        return false;
    }
    *work += cost;
    true
}

/// Most moves of [`climb_weights`].
const CLIMB_MOVES: usize = 6;

/// A local search around the weighted orders of the smallest weighted templates
/// (`starts`, from [`try_alternative_bases`]): from each, the weight vectors one step away
/// ([`neighbours`]) give other standard bases, and a move is kept when its template, for
/// the same action, is smaller; at most [`CLIMB_MOVES`] moves, each to the first smaller
/// neighbour. The end of a climb replaces its action's template when smaller. Sampling
/// finds the regions of good orders, the climbs the best cones near them; several starts,
/// because the cone of the best sampled order need not lead to the best one near.
#[allow(clippy::too_many_arguments)]
fn climb_weights<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Constants<'_>,
    basis: &[Monomial],
    bases: &[AlternativeBasis],
    starts: Vec<(usize, BuiltTemplate)>,
    visible: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
    work: &mut u64,
    all: &mut PerAction,
) {
    let nvars = basis.first().map_or(0, Monomial::nvars);
    let mut seen: Vec<Vec<Monomial>> = std::iter::once(sorted(basis.to_vec()))
        .chain(bases.iter().map(|b| b.basis.clone()))
        .collect();
    for (k, mut current) in starts {
        let action = all[k].0.clone();
        'moves: for _ in 0..CLIMB_MOVES {
            for weights in neighbours(&current.pool_weights) {
                if deadline.check_time().is_err() {
                    return;
                }
                let Some(b) = weighted_basis(eqs, nvars, &weights, deadline) else {
                    continue;
                };
                if b.len() != basis.len() || seen.contains(&b) {
                    continue;
                }
                seen.push(b.clone());
                if !take_work(work, &current) {
                    return;
                }
                let label = weighted_label(&weights);
                let search = pool_capped(
                    &current,
                    degree_window(eqs, &b, &action, visible, opts, deadline, &weights),
                );
                let distinct = current.distinct_eigenvalues;
                let r = build_template(eqs, &b, &label, &action, &search, distinct, opts);
                if let Ok(t) = with_fold_count(r, constants) {
                    if area(&t) < area(&current) {
                        current = t;
                        continue 'moves;
                    }
                }
            }
            break;
        }
        if let Ok(best) = &all[k].1 {
            if area(&current) < area(best) {
                all[k].1 = Ok(current);
            }
        }
    }
}

/// How many times the rows of the template to beat a candidate pool of an alternative basis
/// may have ([`pool_capped`]).
const POOL_FACTOR: usize = 6;

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

/// The chosen template with a redundant basis ([`super::redundant`]) when that is
/// smaller; otherwise the template itself.
fn with_redundant_basis<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Constants<'_>,
    best: BuiltTemplate,
    visible: usize,
    count: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> BuiltTemplate {
    if !opts.redundant_bases {
        return best;
    }
    let t = &best.template;
    let rows: Vec<Candidate> = t
        .rows
        .iter()
        .map(|r| {
            let f = &eqs[r.equation];
            let degree = f.degree().unwrap_or(0) + r.multiplier.degree();
            Candidate::multiple(r.equation, f, r.multiplier.clone(), degree)
        })
        .collect();
    let blocks = Blocks::new(&t.basis, &t.action, visible);
    let Some((grown, kept)) =
        grow_basis::<P>(&blocks, &rows, &t.action, visible, count, Some(deadline))
    else {
        return best;
    };
    let mut template = assemble::<P>(t.nvars, &grown, &kept, &t.action, t.n_hidden);
    template
        .basis
        .sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
    let nb = template.basis.len();
    template.spurious_eigenvalues = nb - count;
    let n = template.columns.len();
    template.columns[n - nb..].clone_from_slice(&template.basis);
    if template.check_emittable(&opts.var_names).is_err() {
        return best;
    }
    // A spurious eigenvalue equal to a solution's would make the eigenvectors of both
    // undefined: where the quotient's eigenvalues are distinct, no root of its
    // characteristic polynomial may be a repeated root of the template's (spurious ones
    // may repeat among themselves).
    if best.distinct_eigenvalues {
        let charpoly = |t: &EliminationTemplate| {
            template_action_matrix::<P>(t, eqs, &opts.var_names)
                .ok()
                .and_then(|m| charpoly_within::<P>(&m, Some(deadline)).ok())
        };
        let separate = match (charpoly(&template), charpoly(&best.template)) {
            (Some(grown), Some(quotient)) => {
                let repeated = poly_gcd::<P>(&grown, &derivative::<P>(&grown));
                poly_gcd::<P>(&repeated, &quotient).len() == 1
            }
            _ => false,
        };
        if !separate {
            return best;
        }
    }
    let mut history = best.history.clone();
    let (r, c) = template.size();
    history.push((
        format!("redundant basis: {nb} monomials for {count} solutions"),
        r,
        c,
    ));
    let grown = with_fold_count(
        Ok(BuiltTemplate {
            template,
            history,
            basis_choice: format!("{}, redundant basis", best.basis_choice),
            quotient_basis: Some(Box::new(best.clone())),
            ..best.clone()
        }),
        constants,
    );
    match grown {
        Ok(g) if area(&g) < area(&best) => g,
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
