//! The search over monomial orders: the standard bases of other orders (grevlex under
//! variable permutations, weighted orders from a grid and samples), each action's template
//! on them, and local climbs around the best weighted orders.

use super::*;

/// A quotient basis other than the analysis's: the standard monomials of another
/// monomial order, with the grading its candidate pools use.
#[derive(Clone)]
pub(super) struct AlternativeBasis {
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
pub(super) fn alternative_bases<const P: u32>(
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
pub(super) fn narrow_bases<const P: u32>(
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
pub(super) const NARROW_BUDGET_SHARE: f64 = 0.5;

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

/// Replaces each action's template by the smallest one built on an alternative standard
/// basis, where that is smaller. An action without a template on the standard basis (an
/// unknown that basis cannot read off, say) is tried too, against the smallest template of
/// the other actions, and gets the first template found; `distinct_of` tells whether its
/// action matrix has distinct eigenvalues. Returns the [`CLIMB_STARTS`] smallest templates
/// built on weighted orders, with the index of their action in `all`, smallest first:
/// where [`climb_weights`] starts.
#[allow(clippy::too_many_arguments)]
pub(super) fn try_alternative_bases<const P: u32>(
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
pub(super) fn climb_weights<const P: u32>(
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
