//! The search over action variables and candidate degrees, and the whole algebra
//! pipeline of one problem.
//!
//! ## Public API
//! - [`best_template`]: tries every unknown as action variable (within
//!   `opts.max_extra_degree` degrees of its start degree), keeps the best, and, when none
//!   works, raises the candidate degree for all of them together until one does or the
//!   budget runs out.
//! - [`generate`]`(&source, &opts)`: [`crate::quotient::analyse_within`] (count and basis,
//!   confirmed), [`best_template`], [`super::validate::validate`]; returns a [`Generated`].

use super::build::{build_in_range, BuiltTemplate, DegreeSearch};
use super::candidates::start_degree;
use super::linalg::is_squarefree;
use super::validate::{nf_action_charpoly, validate_within, ValidationReport};
use super::{Action, ActionChoice, TemplateError, TemplateOptions};
use crate::algebra::{Fp, Monomial, Poly, P1};
use crate::budget::Deadline;
use crate::groebner::{groebner, GroebnerBasis};
use crate::quotient::{analyse_within, InstanceSource};
use std::time::Instant;

/// Every action's result: `(action, template or why none)`.
pub type PerAction = Vec<(Action, Result<BuiltTemplate, TemplateError>)>;

/// Seed offset of the random linear-combination action.
const RANDOM_ACTION_SEED: u64 = 0xAC71_0000;

/// Tries each action of `opts.actions` and keeps the template with the fewest
/// `rows * cols`, among those whose action matrix has distinct eigenvalues when
/// `opts.require_distinct_eigenvalues` (falling back to all if none has); ties go to the
/// action tried first. With [`ActionChoice::Auto`], the unknowns are tried first and a
/// random linear combination of them only when none has distinct eigenvalues. Returns
/// the best and, for every action tried, its result.
///
/// Each action is first tried at candidate degrees up to `opts.max_extra_degree` above its
/// start degree; if none works and `opts.adaptive_degree`, the degree is raised for all
/// actions together, one degree at a time, until one works or `opts.budget` runs out.
pub fn best_template<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    opts: &TemplateOptions,
) -> Result<(BuiltTemplate, PerAction), TemplateError> {
    let nvars = basis.first().map(|b| b.nvars()).unwrap_or(0);
    let gb = groebner(nvars, eqs).ok();
    best_template_within(eqs, basis, gb.as_ref(), opts, &opts.budget.start())
}

/// [`best_template`] with the instance's Gröbner basis (if known) and a running budget.
pub(crate) fn best_template_within<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    gb: Option<&GroebnerBasis<P>>,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> Result<(BuiltTemplate, PerAction), TemplateError> {
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
    let mut all = search_actions(eqs, basis, gb, opts, deadline, &first);
    let has_distinct = all
        .iter()
        .any(|(_, r)| r.as_ref().is_ok_and(|b| b.distinct_eigenvalues));
    if opts.actions == ActionChoice::Auto && visible > 1 && !has_distinct {
        all.extend(search_actions(eqs, basis, gb, opts, deadline, &random()));
    }
    let score = |b: &BuiltTemplate| {
        let (r, c) = b.template.eliminated_size();
        r * c
    };
    let pick = |need_distinct: bool| {
        all.iter()
            .enumerate()
            .filter_map(|(k, (_, r))| r.as_ref().ok().map(|b| (k, b)))
            .filter(|(_, b)| !need_distinct || b.distinct_eigenvalues)
            .min_by_key(|(k, b)| (score(b), *k))
            .map(|(_, b)| b.clone())
    };
    let best = if opts.require_distinct_eigenvalues {
        pick(true).or_else(|| pick(false))
    } else {
        pick(false)
    };
    match best {
        Some(b) => Ok((b, all)),
        None => Err(no_action(&all, opts)),
    }
}

/// The templates of the actions `monomials`, each first within its window of
/// `opts.max_extra_degree`, then (see [`raise_degree`]) beyond.
fn search_actions<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    gb: Option<&GroebnerBasis<P>>,
    opts: &TemplateOptions,
    deadline: &Deadline,
    monomials: &[Action],
) -> PerAction {
    // Basis selection costs most for actions that cannot be chosen anyway: with
    // `require_distinct_eigenvalues`, actions with a repeated eigenvalue get the standard
    // basis only, as long as some action has distinct eigenvalues.
    let distinct: Vec<bool> = match gb {
        Some(gb) => monomials
            .iter()
            .map(|a| is_squarefree::<P>(&nf_action_charpoly::<P>(gb, basis, a)))
            .collect(),
        None => vec![false; monomials.len()],
    };
    let skip_selection = opts.require_distinct_eigenvalues && distinct.iter().any(|&d| d);
    let starts: Vec<u32> = monomials
        .iter()
        .map(|a| start_degree(eqs, basis, a))
        .collect();
    let mut all: PerAction = monomials
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let search = DegreeSearch {
                degrees: starts[k]..=starts[k] + opts.max_extra_degree,
                basis_selection: opts.basis_selection && (!skip_selection || distinct[k]),
                deadline: Some(deadline),
            };
            let r = build_in_range(eqs, basis, v, &search, distinct[k], opts);
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
            };
            let r = build_in_range(eqs, basis, a, &search, distinct[k], opts);
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

/// The whole algebra pipeline for a problem given as an [`InstanceSource`]: count and basis
/// (confirmed across instances and primes), the best template over the action variables
/// ([`best_template`], built on the analysed instance mod P1), and validation against
/// Gröbner normal forms on `opts.validate_instances` fresh instances; all within
/// `opts.budget`.
pub fn generate<S: InstanceSource>(
    src: &S,
    opts: &TemplateOptions,
) -> Result<Generated, TemplateError> {
    let deadline = opts.budget.start();
    let t0 = Instant::now();
    let analysis = analyse_within(src, opts.seed, Some(deadline))?;
    let t1 = Instant::now();
    let opts = &TemplateOptions {
        var_names: src.var_names(),
        hidden_vars: src.hidden_vars(),
        ..opts.clone()
    };
    let counted = |source: TemplateError| TemplateError::Counted {
        count: analysis.count,
        source: Box::new(source),
    };
    let (built, all) = best_template_within::<P1>(
        &analysis.equations,
        &analysis.basis,
        Some(&analysis.groebner),
        opts,
        &deadline,
    )
    .map_err(counted)?;
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
