//! Saturation by a monomial inside the template.
//!
//! A `nonzero s` whose expression is a monomial (`nonzero x*y`, `nonzero w`; the divisions
//! of a Laurent equation) asks for the solutions of the saturation `I : s^∞`. Planning
//! states it with a hidden unknown `u` and `u s - 1 = 0`, which the template must then
//! carry as a variable. Here the template is built without it, in the declared unknowns
//! only: for a basis `B` of `C[x] / (I : s^∞)` and the reducible monomials `R` of the
//! action, the template reduces the shifted monomials `m R` onto `m B` with multiples of
//! the equations as written, for a monomial `m` dividing a power of `s` ([`shifts`]). A
//! relation `m (r - sum_j c_j b_j) ∈ I` puts `r - sum_j c_j b_j` in `I : m^∞ ⊆ I : s^∞`,
//! so the action matrix is the one of the saturated quotient, as in the saturated
//! templates of Larsson, Åström and Oskarsson (ICCV 2017) for a monomial, or the Laurent
//! templates of Martyushev et al. (arXiv 2307.00320) moved to polynomials by a common
//! monomial factor. The template's basis is `m B`, whose unit
//! ([`crate::template::basis_unit`]) is `m`: the solver reads every unknown relative to
//! that entry of the eigenvector.
//!
//! `B` must be free of the hidden unknowns: the standard monomials of an order in which
//! `u` is heavier than every monomial of its normal form (then `u` is a leading
//! monomial, and the standard monomials of `I + (u s - 1)` are those of `I : s^∞`).
//! Weighted orders with the hidden unknowns' weight doubled from 2 are tried until one
//! gives such a basis.

use super::{with_fold_count, Constants, PerAction};
use crate::algebra::{Fp, Monomial, Poly};
use crate::budget::Deadline;
use crate::groebner::{groebner_with, weights_fit, GroebnerBasis, GroebnerOptions};
use crate::quotient::standard_monomials;
use crate::template::build::{build_template, BuiltTemplate};
use crate::template::candidates::start_degree;
use crate::template::weight_sample::ones_and_twos;
use crate::template::{Action, TemplateError, TemplateOptions};

/// The largest power `k` of the shift `s^k` tried.
pub(crate) const MAX_SHIFT_POWER: u16 = 3;

/// The share of the template search's budget the saturated templates may take (where
/// they give none, the search with the hidden unknowns has the rest).
pub(crate) const SATURATED_BUDGET_SHARE: f64 = 0.5;

/// The most weight vectors of 1s and 2s tried for other bases of the saturated quotient.
const MAX_ALTERNATIVE_BASES: usize = 30;

/// The largest weight of the hidden unknowns tried for a basis free of them.
const MAX_HIDDEN_WEIGHT: u32 = 64;

/// The monomial saturation of a system, where every hidden equation (those with a hidden
/// unknown, the last ones) is `c u s + d` for one hidden unknown `u`, a monomial `s` in the
/// visible unknowns and non-zero numbers `c`, `d`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct MonomialSaturation {
    /// How many equations come before the hidden ones.
    pub(crate) equations: usize,
    /// The product of the saturated monomials `s`.
    pub(crate) shift: Monomial,
}

/// The monomial saturation of `eqs` with `hidden` hidden unknowns (the last variables),
/// `None` if there is none or some hidden equation is not of that form.
pub(crate) fn monomial_saturation<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    hidden: usize,
) -> Option<MonomialSaturation> {
    let nvars = eqs.first()?.nvars();
    if hidden == 0 || hidden > nvars {
        return None;
    }
    let visible = nvars - hidden;
    let has_hidden = |f: &Poly<Fp<P>>| {
        f.terms()
            .any(|(m, _)| m.0[visible..].iter().any(|&e| e > 0))
    };
    let equations = eqs.iter().position(has_hidden)?;
    if eqs[equations..].len() != hidden || !eqs[equations..].iter().all(has_hidden) {
        return None;
    }
    let mut shift = Monomial::one(nvars);
    for f in &eqs[equations..] {
        let terms: Vec<&Monomial> = f.terms().map(|(m, _)| m).collect();
        let [a, b] = terms[..] else {
            return None;
        };
        let (product, constant) = if a.is_one() { (b, a) } else { (a, b) };
        let hidden_part = &product.0[visible..];
        let single_hidden = hidden_part.iter().filter(|&&e| e == 1).count() == 1
            && hidden_part.iter().all(|&e| e <= 1);
        if !constant.is_one() || !single_hidden {
            return None;
        }
        let mut s = product.clone();
        s.0[visible..].iter_mut().for_each(|e| *e = 0);
        if s.is_one() {
            return None;
        }
        shift = shift.mul(&s);
    }
    Some(MonomialSaturation { equations, shift })
}

/// The shifts tried, in increasing degree: any monomial `m` is sound (a template that
/// reduces `m R` onto `m B` proves `m (r - sum c_j b_j) ∈ I`, so the relation holds in
/// `I : m^∞ ⊆ I : s^∞` for `m` dividing a power of `s`, and `B` is a basis of the
/// latter), so smaller ones than `s` are tried too: `1`, each variable of `s` to its
/// power in `s`, then `s^k` for `k` up to [`MAX_SHIFT_POWER`].
fn shifts(s: &Monomial) -> Vec<Monomial> {
    let n = s.nvars();
    let mut out = vec![Monomial::one(n)];
    for (v, &e) in s.0.iter().enumerate() {
        if e > 0 {
            let mut m = Monomial::one(n);
            m.0[v] = e;
            out.push(m);
        }
    }
    let mut power = Monomial::one(n);
    for _ in 0..MAX_SHIFT_POWER {
        power = power.mul(s);
        out.push(power.clone());
    }
    out.dedup();
    out
}

/// A basis of the saturated quotient free of the hidden unknowns, in descending grevlex
/// order, with the weights of its order: for `visible_weights` all 1, `basis` itself if it
/// is free; else the standard monomials of the first weighted order (`visible_weights` on
/// the visible unknowns, `w` on the hidden ones, `w` doubled from twice the largest
/// visible weight) that gives one. `None` if none does within [`MAX_HIDDEN_WEIGHT`] or the
/// budget.
fn basis_without_hidden<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    visible_weights: &[u32],
    deadline: &Deadline,
) -> Option<(Vec<Monomial>, Vec<u32>)> {
    let nvars = basis.first()?.nvars();
    let visible = visible_weights.len().min(nvars);
    let free = |b: &[Monomial]| b.iter().all(|m| m.0[visible..].iter().all(|&e| e == 0));
    if free(basis) && visible_weights.iter().all(|&w| w == 1) {
        return Some((basis.to_vec(), Vec::new()));
    }
    let mut w = 2 * visible_weights.iter().copied().max().unwrap_or(1);
    while w <= MAX_HIDDEN_WEIGHT {
        let weights: Vec<u32> = (0..nvars)
            .map(|v| visible_weights.get(v).copied().unwrap_or(w))
            .collect();
        if !weights_fit(&weights, nvars) || deadline.check_time().is_err() {
            return None;
        }
        let gopts = GroebnerOptions {
            deadline: Some(*deadline),
            weights: weights.clone(),
            ..GroebnerOptions::default()
        };
        let b = groebner_with(nvars, eqs, &gopts)
            .ok()
            .and_then(|gb| standard_monomials(&gb).ok())?;
        if b.len() == basis.len() && free(&b) {
            return Some((super::sorted(b), weights));
        }
        w *= 2;
    }
    None
}

/// The templates of `actions` with the saturation built in (see the module
/// documentation), each action's smallest over the shifts of [`shifts`], within
/// `opts.max_extra_degree` degrees of its start; where none reduces there, the degree is
/// raised for every action with the shift `s` until one does (with
/// `opts.adaptive_degree`), within [`SATURATED_BUDGET_SHARE`] of the budget. Returned
/// with the equations as written (the system's without the hidden ones), which the
/// templates' rows refer to. `None` where the system has no monomial saturation or no
/// basis free of the hidden unknowns is found. `basis` and `gb`: the analysis's, for the
/// actions' distinct eigenvalues (the saturated quotient's are the same).
#[allow(clippy::too_many_arguments)]
pub(super) fn saturated_templates<'a, const P: u32>(
    eqs: &'a [Poly<Fp<P>>],
    constants: Constants<'_>,
    basis: &[Monomial],
    gb: &GroebnerBasis<P>,
    opts: &TemplateOptions,
    deadline: &Deadline,
    actions: &[Action],
) -> Option<(PerAction, &'a [Poly<Fp<P>>])> {
    let sat = monomial_saturation(eqs, opts.hidden_vars)?;
    let deadline = &deadline.portion(SATURATED_BUDGET_SHARE);
    let nvars = sat.shift.nvars();
    let visible = nvars - opts.hidden_vars;
    let (base, weights) = basis_without_hidden(eqs, basis, &vec![1; visible], deadline)?;
    let written = &eqs[..sat.equations];
    // A basis of the saturated quotient (of the order with `weights`) times `shift`, and
    // its description.
    let shifted = |base: &[Monomial], weights: &[u32], shift: &Monomial| {
        let order = if weights.is_empty() {
            "grevlex".to_string()
        } else {
            format!("weighted order, weights {weights:?}")
        };
        let label = format!(
            "standard monomials ({order}) of the saturation, shifted by {} (saturated inside the template)",
            shift.display_with(&opts.var_names)
        );
        let b: Vec<Monomial> = base.iter().map(|b| b.mul(shift)).collect();
        (b, label)
    };
    let shifts = shifts(&sat.shift);
    // The template of `action` on the basis `b` within its window of candidate degrees,
    // pools graded by `grading` (empty: total degree).
    let build = |b: &[Monomial], label: &str, action: &Action, distinct, grading: &[u32]| {
        let search = super::degree_window(written, b, action, visible, opts, deadline, grading);
        let r = build_template(written, b, label, action, &search, distinct, opts);
        with_fold_count(r, constants)
    };
    let checks: Vec<Result<bool, TemplateError>> = actions
        .iter()
        .map(|a| super::quotient_action(gb, basis, a, opts, deadline))
        .collect();
    let distinct: Vec<bool> = checks.iter().map(|c| c.clone().unwrap_or(false)).collect();
    let mut all: PerAction = Vec::new();
    for ((action, &distinct), check) in actions.iter().zip(&distinct).zip(&checks) {
        let mut best: Option<Result<BuiltTemplate, TemplateError>> = None;
        if let Err(e) = check {
            all.push((action.clone(), Err(e.clone())));
            continue;
        }
        for shift in &shifts {
            let (b, label) = shifted(&base, &weights, shift);
            let r = build(&b, &label, action, distinct, &[]);
            let better = match (&r, &best) {
                (Ok(new), Some(Ok(old))) => super::area(new) < super::area(old),
                (_, Some(Ok(_))) => false,
                _ => r.is_ok() || best.is_none(),
            };
            if better {
                best = Some(r);
            }
            if deadline.check_time().is_err() {
                break;
            }
        }
        if let Some(r) = best {
            all.push((action.clone(), r));
        }
    }
    // Other bases (weights 1 and 2 on the visible unknowns), for the best action and
    // shift only.
    let best = all
        .iter()
        .enumerate()
        .filter_map(|(k, (_, r))| r.as_ref().ok().map(|b| (k, b)))
        .min_by_key(|(k, b)| (super::area(b), *k))
        .map(|(k, b)| (k, b.template.unit()));
    if let Some((k, shift)) = best {
        let mut seen = vec![base.clone()];
        for w in ones_and_twos(visible, MAX_ALTERNATIVE_BASES) {
            if deadline.check_time().is_err() {
                break;
            }
            let Some((other, weights)) = basis_without_hidden(eqs, basis, &w, deadline) else {
                continue;
            };
            if seen.contains(&other) {
                continue;
            }
            seen.push(other.clone());
            let (b, label) = shifted(&other, &weights, &shift);
            // Pools graded by total degree, then by the basis's own weights (its basis and
            // reducible monomials are low in that grading).
            for grading in [&[][..], &weights[..]] {
                let r = build(&b, &label, &actions[k], distinct[k], grading);
                if let (Ok(new), Ok(old)) = (&r, &all[k].1) {
                    if super::area(new) < super::area(old) {
                        all[k].1 = r;
                    }
                }
            }
        }
    }
    // No action reduces within its window: raise the degree, shift `s`, all actions.
    if opts.adaptive_degree && all.iter().all(|(_, r)| r.is_err()) {
        let (b, label) = shifted(&base, &weights, &sat.shift);
        let starts: Vec<u32> = actions
            .iter()
            .map(|a| start_degree(written, &b, a, visible, &[]))
            .collect();
        super::raise_degree(
            written, constants, &b, &label, actions, &starts, &distinct, opts, deadline, &mut all,
        );
    }
    Some((all, written))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::P1;

    fn poly(terms: &[(&[u16], u32)]) -> Poly<Fp<P1>> {
        Poly::from_terms(
            terms[0].0.len(),
            terms
                .iter()
                .map(|(e, c)| (Monomial(e.to_vec()), Fp::<P1>::new(*c as i64))),
        )
    }

    #[test]
    fn a_monomial_nonzero_is_found_and_a_polynomial_one_is_not() {
        // x^2 + y - 3, x y - 2, u x y - 1 (nonzero x*y).
        let f = poly(&[(&[2, 0, 0], 1), (&[0, 1, 0], 1), (&[0, 0, 0], P1 - 3)]);
        let g = poly(&[(&[1, 1, 0], 1), (&[0, 0, 0], P1 - 2)]);
        let sat = poly(&[(&[1, 1, 1], 1), (&[0, 0, 0], P1 - 1)]);
        let found = monomial_saturation(&[f.clone(), g.clone(), sat], 1);
        assert_eq!(
            found,
            Some(MonomialSaturation {
                equations: 2,
                shift: Monomial(vec![1, 1, 0]),
            })
        );
        // u (x + y) - 1 (nonzero x + y) is not a monomial saturation.
        let poly_sat = poly(&[(&[1, 0, 1], 1), (&[0, 1, 1], 1), (&[0, 0, 0], P1 - 1)]);
        assert_eq!(
            monomial_saturation(&[f.clone(), g.clone(), poly_sat], 1),
            None
        );
        // No hidden unknown, nothing to saturate.
        assert_eq!(monomial_saturation(&[f, g], 0), None);
    }
}
