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
use crate::algebra::{Fp, Monomial, Poly, Q};
use crate::budget::Deadline;
use crate::groebner::{groebner_with, weights_fit, GroebnerBasis, GroebnerOptions};
use crate::problem::PolynomialSaturation;
use crate::quotient::standard_monomials;
use crate::template::build::{build_template, BuiltTemplate, DegreeSearch};
use crate::template::candidates::start_degree;
use crate::template::weight_sample::ones_and_twos;
use crate::template::ColumnShift;
use crate::template::EquationConstants;
use crate::template::{Action, TemplateError, TemplateOptions};
use num_bigint::BigInt;

/// The largest power `k` of the shift `s^k` tried.
pub(crate) const MAX_SHIFT_POWER: u16 = 3;

/// The share of the template search's budget the saturated templates may take (where
/// they give none, the search with the hidden unknowns has the rest).
pub(crate) const SATURATED_BUDGET_SHARE: f64 = 0.5;

/// The most weight vectors of 1s and 2s tried for other bases of the saturated quotient.
const MAX_ALTERNATIVE_BASES: usize = 30;

/// The largest weight of the hidden unknowns tried for a basis free of them.
const MAX_HIDDEN_WEIGHT: u32 = 64;

/// The saturation of a system, where every hidden equation (those with a hidden unknown,
/// the last ones) is `c u s + d` for one hidden unknown `u`, a polynomial `s` in the
/// visible unknowns and non-zero numbers `c`, `d`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Saturation {
    /// How many equations come before the hidden ones.
    pub(crate) equations: usize,
    /// The product of the saturated polynomials `s`.
    pub(crate) shift: Saturating,
}

/// What a system is saturated by.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Saturating {
    /// A monomial: the basis is shifted by a monomial dividing a power of it.
    Monomial(Monomial),
    /// A polynomial with constant coefficients: the columns stand for multiples of a power
    /// of it ([`crate::template::shift`]).
    Polynomial(ColumnShift),
}

/// The saturation of `eqs` with `hidden` hidden unknowns (the last variables), `None` if
/// there is none, some hidden equation is not of that form, or (for a polynomial) some
/// coefficient of the product depends on the data, which the template's columns cannot
/// hold. `constants` (the equations' terms with their exact coefficients where those are
/// numbers, traced from the problem) decide that exactly; without them (equations
/// row-reduced on the data) a coefficient counts as a number when it is a small rational
/// ([`small_rational`]).
pub(crate) fn saturation<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    hidden: usize,
    constants: Constants<'_>,
) -> Option<Saturation> {
    let nvars = eqs.first()?.nvars();
    if hidden == 0 || hidden > nvars {
        return None;
    }
    let visible = nvars - hidden;
    let has_hidden = |m: &Monomial| m.0[visible..].iter().any(|&e| e > 0);
    let equations = eqs
        .iter()
        .position(|f| f.terms().any(|(m, _)| has_hidden(m)))?;
    if eqs[equations..].len() != hidden
        || !eqs[equations..]
            .iter()
            .all(|f| f.terms().any(|(m, _)| has_hidden(m)))
    {
        return None;
    }
    let mut product = Poly::constant(nvars, Fp::<P>::new(1));
    for f in &eqs[equations..] {
        // c u s + d: the terms with the hidden unknown share it, to the first power; the
        // one without is a non-zero number.
        let mut hidden_var = None;
        let mut s = Poly::zero(nvars);
        let mut constant = None;
        for (m, c) in f.terms() {
            let h = &m.0[visible..];
            if h.iter().all(|&e| e == 0) {
                if !m.is_one() || constant.is_some() {
                    return None;
                }
                constant = Some(*c);
                continue;
            }
            let v = h.iter().position(|&e| e > 0)?;
            if h[v] != 1 || h.iter().filter(|&&e| e > 0).count() != 1 {
                return None;
            }
            if hidden_var.is_some_and(|u| u != v) {
                return None;
            }
            hidden_var = Some(v);
            let mut t = m.clone();
            t.0[visible + v] = 0;
            s.add_term(t, *c);
        }
        let d = constant?;
        if s.is_zero() || s.terms().all(|(m, _)| m.is_one()) {
            return None;
        }
        // Normalised by -d (c u s = -d): only the zero set matters.
        product = product.mul(&s.scale(&(-d)));
    }
    let shift = if product.len() == 1 {
        let (m, _) = product.terms().next()?;
        Saturating::Monomial(m.clone())
    } else {
        let terms: Vec<(Monomial, Q)> = match constants {
            Some(c) => {
                let exact = exact_product(c.get(equations..)?, visible)?;
                // The instance's product has the same monomials (its coefficients are the
                // exact ones mod p, up to the normalisation).
                let same = exact.len() == product.len()
                    && exact
                        .iter()
                        .all(|(m, _)| product.terms().any(|(n, _)| n == m));
                same.then_some(exact)?
            }
            None => product
                .terms()
                .map(|(m, c)| small_rational(*c).map(|q| (m.clone(), q)))
                .collect::<Option<_>>()?,
        };
        Saturating::Polynomial(ColumnShift::new(terms)?)
    };
    Some(Saturation { equations, shift })
}

/// The product of the polynomials `s` of the hidden equations `c u s + d` from their exact
/// terms (`hidden`: each equation's, the hidden unknowns from variable `visible` on);
/// `None` if a coefficient of some `s` depends on the data.
fn exact_product(hidden: &[EquationConstants], visible: usize) -> Option<Vec<(Monomial, Q)>> {
    let nvars = hidden.first()?.first()?.0.nvars();
    let mut product = Poly::constant(nvars, Q::from_integer(BigInt::from(1)));
    for terms in hidden {
        let mut s = Poly::zero(nvars);
        for (m, c) in terms {
            if m.0[visible..].iter().all(|&e| e == 0) {
                continue;
            }
            let mut t = m.clone();
            t.0[visible..].iter_mut().for_each(|e| *e = 0);
            s.add_term(t, c.clone()?);
        }
        product = product.mul(&s);
    }
    Some(
        product
            .terms()
            .map(|(m, c)| (m.clone(), c.clone()))
            .collect(),
    )
}

/// The largest denominator and numerator [`small_rational`] recognises.
const SMALL_DENOMINATOR: i64 = 64;
const SMALL_NUMERATOR: i64 = 1 << 16;

/// The rational number `n / d` with `|n| <= 2^16`, `0 < d <= 64` congruent to `x`, if any:
/// the coefficients of a `nonzero` written with numbers are such, a coefficient made of
/// random data almost never (one chance in about 2^8 per coefficient).
fn small_rational<const P: u32>(x: Fp<P>) -> Option<Q> {
    (1..=SMALL_DENOMINATOR).find_map(|d| {
        let n = (x.0 as i64 * d) % P as i64;
        let n = if n > P as i64 / 2 { n - P as i64 } else { n };
        (n.abs() <= SMALL_NUMERATOR).then(|| Q::new(BigInt::from(n), BigInt::from(d)))
    })
}

/// One shift of the basis: the template reduces the reducible monomials times `unit`
/// onto the basis times `unit`, the columns standing for multiples of `columns` when set
/// (`unit` its leading monomial).
#[derive(Clone, Debug)]
struct Shift {
    unit: Monomial,
    columns: Option<ColumnShift>,
}

/// The shifts tried, in increasing degree. For a monomial `s`, any monomial `m` is sound
/// (a template that reduces `m R` onto `m B` proves `m (r - sum c_j b_j) ∈ I`, so the
/// relation holds in `I : m^∞ ⊆ I : s^∞` for `m` dividing a power of `s`, and `B` is a
/// basis of the latter), so smaller ones than `s` are tried too: `1`, each variable of `s`
/// to its power in `s`, then `s^k` for `k` up to [`MAX_SHIFT_POWER`]. For a polynomial
/// `s`, its powers `s^k`.
fn shifts(s: &Saturating) -> Vec<Shift> {
    match s {
        Saturating::Monomial(s) => monomial_shifts(s)
            .into_iter()
            .map(|unit| Shift {
                unit,
                columns: None,
            })
            .collect(),
        Saturating::Polynomial(sigma) => (1..=MAX_SHIFT_POWER)
            .filter_map(|k| sigma.pow(k))
            .map(|power| Shift {
                unit: power.leading().clone(),
                columns: Some(power),
            })
            .collect(),
    }
}

/// The monomial shifts of [`shifts`].
fn monomial_shifts(s: &Monomial) -> Vec<Monomial> {
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
    let sat = saturation(eqs, opts.hidden_vars, constants)?;
    if matches!(sat.shift, Saturating::Polynomial(_))
        && opts.polynomial_saturation == PolynomialSaturation::Unknown
    {
        return None;
    }
    let deadline = &deadline.portion(SATURATED_BUDGET_SHARE);
    let nvars = eqs.first()?.nvars();
    let visible = nvars - opts.hidden_vars;
    let (base, weights) = basis_without_hidden(eqs, basis, &vec![1; visible], deadline)?;
    let written = &eqs[..sat.equations];
    // A basis of the saturated quotient (of the order with `weights`) times the shift's
    // unit, and its description.
    let shifted = |base: &[Monomial], weights: &[u32], shift: &Shift| {
        let order = if weights.is_empty() {
            "grevlex".to_string()
        } else {
            format!("weighted order, weights {weights:?}")
        };
        let by = match &shift.columns {
            None => shift.unit.display_with(&opts.var_names),
            Some(sigma) => format!("the polynomial {}", sigma.display_with(&opts.var_names)),
        };
        let label = format!(
            "standard monomials ({order}) of the saturation, shifted by {by} (saturated inside the template)"
        );
        let b: Vec<Monomial> = base.iter().map(|b| b.mul(&shift.unit)).collect();
        (b, label)
    };
    let shifts = shifts(&sat.shift);
    // The template of `action` on the basis `b` within its window of candidate degrees,
    // pools graded by `grading` (empty: total degree).
    let build =
        |b: &[Monomial], label: &str, shift: &Shift, action: &Action, distinct, grading: &[u32]| {
            let search = DegreeSearch {
                shift: shift.columns.as_ref(),
                ..super::degree_window(written, b, action, visible, opts, deadline, grading)
            };
            let r = build_template(written, b, label, action, &search, distinct, opts);
            with_fold_count(r, constants)
        };
    let checks: Vec<Result<bool, TemplateError>> = actions
        .iter()
        .map(|a| super::quotient_action(gb, basis, a, opts, deadline))
        .collect();
    let distinct: Vec<bool> = checks.iter().map(|c| matches!(c, Ok(true))).collect();
    let mut all: PerAction = Vec::new();
    let mut chosen_shift: Vec<Option<Shift>> = Vec::new();
    for ((action, &distinct), check) in actions.iter().zip(&distinct).zip(&checks) {
        let mut best: Option<(Result<BuiltTemplate, TemplateError>, Shift)> = None;
        if let Err(e) = check {
            all.push((action.clone(), Err(e.clone())));
            chosen_shift.push(None);
            continue;
        }
        for shift in &shifts {
            let (b, label) = shifted(&base, &weights, shift);
            let r = build(&b, &label, shift, action, distinct, &[]);
            let better = match (&r, &best) {
                (Ok(new), Some((Ok(old), _))) => super::area(new) < super::area(old),
                (_, Some((Ok(_), _))) => false,
                _ => r.is_ok() || best.is_none(),
            };
            if better {
                best = Some((r, shift.clone()));
            }
            if deadline.check_time().is_err() {
                break;
            }
        }
        if let Some((r, shift)) = best {
            all.push((action.clone(), r));
            chosen_shift.push(Some(shift));
        }
    }
    // Other bases (weights 1 and 2 on the visible unknowns), for the best action and
    // shift only.
    let best = all
        .iter()
        .enumerate()
        .filter_map(|(k, (_, r))| r.as_ref().ok().map(|b| (k, b)))
        .min_by_key(|(k, b)| (super::area(b), *k))
        .and_then(|(k, _)| chosen_shift[k].clone().map(|s| (k, s)));
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
                let r = build(&b, &label, &shift, &actions[k], distinct[k], grading);
                if let (Ok(new), Ok(old)) = (&r, &all[k].1) {
                    if super::area(new) < super::area(old) {
                        all[k].1 = r;
                    }
                }
            }
        }
    }
    // No action reduces within its window: raise the degree, largest shift, all actions.
    if opts.adaptive_degree && all.iter().all(|(_, r)| r.is_err()) {
        let shift = shifts.last()?;
        let (b, label) = shifted(&base, &weights, shift);
        let starts: Vec<u32> = actions
            .iter()
            .map(|a| start_degree(written, &b, a, visible, &[]))
            .collect();
        super::raise_degree(
            written,
            constants,
            &b,
            &label,
            shift.columns.as_ref(),
            actions,
            &starts,
            &distinct,
            opts,
            deadline,
            &mut all,
        );
    }
    Some((all, written))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Ring, P1};

    fn poly(terms: &[(&[u16], u32)]) -> Poly<Fp<P1>> {
        Poly::from_terms(
            terms[0].0.len(),
            terms
                .iter()
                .map(|(e, c)| (Monomial(e.to_vec()), Fp::<P1>::new(*c as i64))),
        )
    }

    #[test]
    fn a_monomial_nonzero_shifts_the_basis_and_a_polynomial_one_the_columns() {
        // x^2 + y - 3, x y - 2, u x y - 1 (nonzero x*y).
        let f = poly(&[(&[2, 0, 0], 1), (&[0, 1, 0], 1), (&[0, 0, 0], P1 - 3)]);
        let g = poly(&[(&[1, 1, 0], 1), (&[0, 0, 0], P1 - 2)]);
        let sat = poly(&[(&[1, 1, 1], 1), (&[0, 0, 0], P1 - 1)]);
        let found = saturation(&[f.clone(), g.clone(), sat], 1, None);
        assert_eq!(
            found,
            Some(Saturation {
                equations: 2,
                shift: Saturating::Monomial(Monomial(vec![1, 1, 0])),
            })
        );
        // u (2 x + y) - 1 (nonzero 2 x + y): the columns shift by x + y / 2.
        let poly_sat = poly(&[(&[1, 0, 1], 2), (&[0, 1, 1], 1), (&[0, 0, 0], P1 - 1)]);
        let half = Q::new(BigInt::from(1), BigInt::from(2));
        let expected = ColumnShift::new([
            (Monomial(vec![1, 0, 0]), Q::from_integer(BigInt::from(1))),
            (Monomial(vec![0, 1, 0]), half),
        ]);
        assert_eq!(
            saturation(&[f.clone(), g.clone(), poly_sat], 1, None),
            Some(Saturation {
                equations: 2,
                shift: Saturating::Polynomial(expected.unwrap()),
            })
        );
        // A coefficient that is no small rational (data) is not taken for a number.
        let data_sat = poly(&[
            (&[1, 0, 1], 1_234_567_891),
            (&[0, 1, 1], 1),
            (&[0, 0, 0], P1 - 1),
        ]);
        assert_eq!(saturation(&[f.clone(), g.clone(), data_sat], 1, None), None);
        // No hidden unknown, nothing to saturate.
        assert_eq!(saturation(&[f.clone(), g.clone()], 0, None), None);
        // With the exact terms: a number that is no small rational (x + y / 100) is a
        // number, and a data coefficient is data whatever its value mod p.
        let hundredth = Q::new(BigInt::from(1), BigInt::from(100));
        let one = Q::from_integer(BigInt::from(1));
        let exact = |c: Option<Q>| -> Vec<EquationConstants> {
            vec![
                Vec::new(),
                Vec::new(),
                vec![
                    (Monomial(vec![1, 0, 1]), Some(one.clone())),
                    (Monomial(vec![0, 1, 1]), c),
                    (Monomial(vec![0, 0, 0]), Some(-one.clone())),
                ],
            ]
        };
        let p = Fp::<P1>::from_rational(&hundredth).unwrap();
        let sat = Poly::from_terms(
            3,
            [
                (Monomial(vec![1, 0, 1]), Fp::<P1>::new(1)),
                (Monomial(vec![0, 1, 1]), p),
                (Monomial(vec![0, 0, 0]), Fp::<P1>::new(-1)),
            ],
        );
        let eqs = [f, g, sat];
        assert_eq!(saturation(&eqs, 1, None), None);
        let found = saturation(&eqs, 1, Some(&exact(Some(hundredth.clone()))));
        let expected = ColumnShift::new([
            (Monomial(vec![1, 0, 0]), one.clone()),
            (Monomial(vec![0, 1, 0]), hundredth),
        ]);
        assert_eq!(
            found.map(|s| s.shift),
            Some(Saturating::Polynomial(expected.unwrap()))
        );
        assert_eq!(saturation(&eqs, 1, Some(&exact(None))), None);
    }
}
