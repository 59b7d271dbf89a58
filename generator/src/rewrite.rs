//! Rewrites of a problem's system that planning chooses before the Gröbner work, each
//! kept only where it leaves the solutions as they were (`pipeline::plan` runs them in
//! this order):
//!
//! 1. [`substitute_affine_equations`]: unknowns solved from affine equations and
//!    substituted into the others;
//! 2. [`eliminate_linear_unknowns`]: unknowns that appear only as `data × x` eliminated
//!    by the maximal minors of their coefficient matrix;
//! 3. [`divide_out_nonzero`]: `nonzero` expressions divided out of the equations they
//!    divide exactly, and the saturation dropped where the count allows;
//! 4. [`drop_dependent_equations`]: equations that are combinations of others dropped;
//! 5. [`sign_fold_alternatives`]: a system whose solutions come in sign pairs folded to half
//!    of them (`crate::symmetry`), once for each pivot the fold can use.

use crate::algebra::{MonomialOrder, Poly};
use crate::budget::Deadline;
use crate::eliminate::{affine_equations, linear_pivots, purely_linear_unknowns};
use crate::groebner::{groebner_with, GroebnerError, GroebnerOptions};
use crate::instance::random_data_fp;
use crate::quotient::InstanceSource;
use crate::quotient::{analyse_within, InstanceRng};
use crate::symmetry::{sign_symmetries, SignFold};
use crate::system::{equation_supports, system, system_and_factors, ProblemSource};
use crate::template::TemplateOptions;
use crate::Problem;

/// `problem` with its purely linear unknowns eliminated as `eliminate` would
/// ([`purely_linear_unknowns`]: every term that has one is that unknown times data), when
/// the file eliminates nothing, allows it (`option auto_eliminate`), the elimination is
/// inhomogeneous (so each solution keeps its own values of them, recovered from the null
/// vector; a homogeneous one would identify solutions that differ in their scale) and the
/// solution count stays the same. Unchanged otherwise.
pub(crate) fn eliminate_linear_unknowns(
    problem: Problem,
    options: &TemplateOptions,
    deadline: &Deadline,
) -> Problem {
    const P: u32 = crate::algebra::P1;
    let layout = &problem.layout;
    if !auto_eliminate_allowed(&problem, options) {
        return problem;
    }
    let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(options.seed ^ 0xe11a);
    let data = random_data_fp::<P>(layout, &mut rng);
    let visible = layout.unknown_count() - layout.hidden_count();
    let linear = purely_linear_unknowns(&problem.evaluate(&data), 0..visible);
    if linear.is_empty() || linear.len() == visible {
        return problem;
    }
    let mut eliminated = problem.clone();
    eliminated.layout.eliminate = linear;
    match system(&eliminated, &data) {
        Ok((_, Some(e))) if e.inhomogeneous => {}
        _ => return problem,
    }
    same_count(eliminated, problem, options, deadline)
}

/// `problem` with the unknowns its affine equations determine substituted into its other
/// equations ([`crate::eliminate::substitute_linear`]: Cramer's rule on a pivot block of data only), when the
/// file eliminates nothing, allows it (`option auto_eliminate`), some equation is not
/// affine and the solution count stays the same: the linear constraints leave the
/// nonlinear ones in fewer unknowns, as the null-space parametrisation of the 5-point
/// problem's essential matrix does. Unchanged otherwise.
pub(crate) fn substitute_affine_equations(
    problem: Problem,
    options: &TemplateOptions,
    deadline: &Deadline,
) -> Problem {
    const P: u32 = crate::algebra::P1;
    let layout = &problem.layout;
    if !auto_eliminate_allowed(&problem, options) {
        return problem;
    }
    let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(options.seed ^ 0x5b57);
    let data = random_data_fp::<P>(layout, &mut rng);
    let equations = problem.evaluate(&data);
    let linear = affine_equations(&equations);
    if linear.is_empty() || linear.len() == equations.len() {
        return problem;
    }
    let Some((pivots, used, implied)) = linear_pivots(&equations, layout.unknown_count(), &linear)
    else {
        return problem;
    };
    // A `nonzero` stays as written (it saturates by a polynomial in the unknowns left):
    // none of its unknowns may be substituted.
    let n = layout.unknown_count();
    let visible = n - layout.hidden_count();
    let in_nonzero = |v: usize| {
        equations.iter().any(|f| {
            f.terms()
                .any(|(m, _)| m.0[visible..].iter().any(|&e| e > 0))
                && f.terms().any(|(m, _)| m.0[v] > 0)
        })
    };
    if pivots.iter().any(|&v| in_nonzero(v)) {
        return problem;
    }
    let substituted = problem.with_substitution(pivots, used, implied);
    if system(&substituted, &data).is_err() {
        return problem;
    }
    same_count(substituted, problem, options, deadline)
}

/// `candidate` if its solution count is that of `original` (both found within the
/// plan's budget), else `original`.
fn same_count(
    candidate: Problem,
    original: Problem,
    options: &TemplateOptions,
    deadline: &Deadline,
) -> Problem {
    let count = |p: &Problem| {
        analyse_within(&ProblemSource::new(p), options.seed, Some(*deadline))
            .ok()
            .map(|a| a.count)
    };
    match (count(&candidate), count(&original)) {
        (Some(a), Some(b)) if a == b => candidate,
        _ => original,
    }
}

/// Whether planning may eliminate unknowns on its own: the file eliminates nothing and
/// neither the command line nor the file's `option auto_eliminate` says no.
fn auto_eliminate_allowed(problem: &Problem, options: &TemplateOptions) -> bool {
    let layout = &problem.layout;
    layout.eliminate.is_empty()
        && options
            .overrides
            .auto_eliminate
            .or(layout.options.auto_eliminate)
            .unwrap_or(true)
}

/// `problem` keeping only a linearly independent subset of its system's equations that
/// spans the others (see [`crate::independent`]); unchanged when every equation is needed.
pub(crate) fn drop_dependent_equations(problem: Problem, seed: u64) -> Problem {
    const P: u32 = crate::algebra::P1;
    let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(seed ^ 0x1d9e);
    let mut instance = || {
        let data = random_data_fp::<P>(&problem.layout, &mut rng);
        system(&problem, &data).ok().map(|(equations, _)| equations)
    };
    let (Some(first), Some(second)) = (instance(), instance()) else {
        return problem;
    };
    match crate::independent::independent_subset(&first, &second) {
        Some(kept) => problem.with_independent(kept),
        None => problem,
    }
}

/// `problem` with its `nonzero` expressions divided out of the equations they divide
/// exactly (typically maximal minors after `eliminate`, which vanish wherever a rotation's
/// Cayley denominator does): lower degrees, the same solutions. If the divided system
/// without saturation has as many solutions as with it, saturation is dropped too (its
/// solutions include the saturated system's, so equal counts mean no others), which
/// removes the hidden unknowns from the template. Unchanged when nothing divides.
pub(crate) fn divide_out_nonzero(
    problem: Problem,
    options: &TemplateOptions,
    deadline: &Deadline,
) -> Problem {
    if problem.nonzero_count() == 0 {
        return problem;
    }
    let divisions = nonzero_divisions(&problem, options.seed);
    if divisions.is_empty() {
        return problem;
    }
    let saturated = problem.with_divisions(divisions);
    let plain = problem.without_saturation();
    let unsaturated = plain.with_divisions(nonzero_divisions(&plain, options.seed));
    same_count(unsaturated, saturated, options, deadline)
}

/// How many times each `nonzero` expression divides each equation of `problem`'s system
/// exactly, on the whole data family: the smaller count of two random instances mod p
/// (exact arithmetic; a division that is exact on random instances is exact as a
/// polynomial identity in the data but with probability about degree / p). An expression
/// must have the same leading term on both instances, with coefficient ±1 (its other
/// coefficients may depend on the data).
/// Empty when nothing divides.
fn nonzero_divisions(problem: &Problem, seed: u64) -> Vec<Vec<u32>> {
    type F = crate::algebra::Fp<{ crate::algebra::P1 }>;
    let plain = problem.with_divisions(Vec::new());
    let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(seed ^ 0xd1f1);
    let mut counts: Option<Vec<Vec<u32>>> = None;
    let mut first_factors: Option<Vec<Option<Poly<F>>>> = None;
    for _ in 0..2 {
        let data = random_data_fp::<{ crate::algebra::P1 }>(&plain.layout, &mut rng);
        let Ok(((equations, _), factors)) = system_and_factors(&plain, &data) else {
            return Vec::new();
        };
        // The leading term must be the same on both instances (±1 times one monomial);
        // the other coefficients may depend on the data.
        let leading = |f: &Option<Poly<F>>| {
            f.as_ref()
                .and_then(|f| f.leading(MonomialOrder::Grevlex))
                .map(|(m, c)| (m.clone(), *c))
        };
        let constant: Vec<Option<()>> = match &first_factors {
            None => factors.iter().map(|f| leading(f).map(|_| ())).collect(),
            Some(first) => first
                .iter()
                .zip(&factors)
                .map(|(a, b)| (leading(a).is_some() && leading(a) == leading(b)).then_some(()))
                .collect(),
        };
        let these: Vec<Vec<u32>> = equations
            .iter()
            .map(|eq| {
                factors
                    .iter()
                    .zip(&constant)
                    .map(|(f, c)| match (f, c) {
                        (Some(f), Some(_)) if f.degree().unwrap_or(0) > 0 => {
                            let mut p = eq.clone();
                            let mut k = 0;
                            while !p.is_zero() {
                                match p.divide(f) {
                                    Some((q, r)) if r.is_zero() => {
                                        p = q;
                                        k += 1;
                                    }
                                    _ => break,
                                }
                            }
                            k
                        }
                        _ => 0,
                    })
                    .collect()
            })
            .collect();
        counts = Some(match counts {
            None => these,
            Some(c) => c
                .iter()
                .zip(&these)
                .map(|(a, b)| a.iter().zip(b).map(|(x, y)| (*x).min(*y)).collect())
                .collect(),
        });
        first_factors.get_or_insert(factors);
    }
    let counts = counts.unwrap_or_default();
    if counts.iter().flatten().all(|&k| k == 0) {
        return Vec::new();
    }
    counts
}

/// The most sign folds [`sign_fold_alternatives`] applies (each halves the count).
const MAX_SIGN_FOLDS: u64 = 4;

/// The most first folds [`sign_fold_alternatives`] returns (one per pivot it can fold by).
const MAX_FOLD_ALTERNATIVES: usize = 4;

/// `problem` folded by its sign symmetries (`crate::symmetry`), one at a time while some
/// remain, when the command line and the file allow it (`option sign_symmetry`, default
/// yes): one folded system for each pivot the first fold can use (at most
/// [`MAX_FOLD_ALTERNATIVES`], the declared unknowns of each symmetry in order), each then
/// folded further by the first pivot that works. A fold is kept only when it halves the
/// solution count and no solution of the folded system has its pivot (the square) zero, so
/// that each of its solutions is exactly one pair of the original's. The pivot shapes the
/// folded system's monomials (`x_j / x_p` for the others), so its templates differ by
/// pivot, often severalfold: the caller searches each. Empty when there is no fold.
pub(crate) fn sign_fold_alternatives(
    problem: Problem,
    options: &TemplateOptions,
    deadline: &Deadline,
) -> Vec<Problem> {
    let allowed = options
        .overrides
        .sign_symmetry
        .or(problem.layout.options.sign_symmetry)
        .unwrap_or(true);
    if !allowed {
        return Vec::new();
    }
    let count = |p: &Problem| {
        analyse_within(&ProblemSource::new(p), options.seed, Some(*deadline))
            .ok()
            .map(|a| a.count)
    };
    // The sign symmetries of `problem` (bit masks of its variables) on the supports of the
    // fold's `round`.
    let symmetries = |problem: &Problem, round: u64| {
        let n = ProblemSource::new(problem).nvars();
        sign_symmetries(
            &equation_supports(problem, options.seed ^ 0x5167 ^ round),
            n,
        )
    };
    // The folds of `problem` (count `before`, symmetries `masks`) that halve it, at most
    // `max`.
    let folds = |problem: &Problem, masks: Vec<u32>, before: usize, max: usize| {
        let source = ProblemSource::new(problem);
        let n = source.nvars();
        let visible = n - source.hidden_vars().min(n);
        let mut out = Vec::new();
        for mask in masks {
            let vars: Vec<usize> = (0..n).filter(|&i| mask >> i & 1 == 1).collect();
            for &pivot in vars.iter().filter(|&&p| p < visible) {
                if out.len() == max || deadline.check_time().is_err() {
                    return out;
                }
                let fold = SignFold {
                    pivot,
                    scaled: vars.iter().copied().filter(|&j| j != pivot).collect(),
                };
                let candidate = problem.with_sign_fold(fold);
                if count(&candidate) == Some(before / 2)
                    && square_never_zero(&candidate, pivot, options.seed, deadline)
                {
                    out.push(candidate);
                }
            }
        }
        out
    };
    let first = symmetries(&problem, 0);
    if first.is_empty() {
        return Vec::new();
    }
    let Some(before) = count(&problem).filter(|c| c % 2 == 0) else {
        return Vec::new();
    };
    folds(&problem, first, before, MAX_FOLD_ALTERNATIVES)
        .into_iter()
        .map(|mut folded| {
            let mut total = before / 2;
            for round in 1..MAX_SIGN_FOLDS {
                if total % 2 != 0 {
                    break;
                }
                match folds(&folded, symmetries(&folded, round), total, 1).pop() {
                    Some(f) => {
                        folded = f;
                        total /= 2;
                    }
                    None => break,
                }
            }
            folded
        })
        .collect()
}

/// Whether the folded system of `problem` has no solution with variable `pivot` zero (its
/// equations and `pivot` generate the whole ring) on a random instance mod p.
fn square_never_zero(problem: &Problem, pivot: usize, seed: u64, deadline: &Deadline) -> bool {
    const P: u32 = crate::algebra::P1;
    let source = ProblemSource::new(problem);
    let n = source.nvars();
    let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(seed ^ 0x0f01d);
    let mut equations = source.instance::<P>(&mut rng);
    if equations.is_empty() {
        return false;
    }
    equations.push(Poly::var(n, pivot));
    let opts = GroebnerOptions {
        deadline: Some(*deadline),
        ..GroebnerOptions::default()
    };
    matches!(
        groebner_with(n, &equations, &opts),
        Err(GroebnerError::Inconsistent)
    )
}
