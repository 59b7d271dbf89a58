//! A problem as a family of polynomial systems: the equations the template is built from
//! for one data instance over any ring, after the file's elimination, the division by the
//! `nonzero` expressions and the selection of independent equations. Planning
//! (`crate::pipeline`) and its rewrites (`crate::rewrite`) both evaluate problems through
//! here, so neither needs the other.

use crate::algebra::{Fp, Monomial, Poly, Ring};
use crate::eliminate::{
    eliminate_linear_selected, reduce_block, substitute_linear, EliminateError, Eliminated,
};
use crate::emit::traced::{TracedValue, Tracer};
use crate::instance::random_data_fp;
use crate::quotient::{InstanceRng, InstanceSource};
use crate::template::EquationConstants;
use crate::Problem;
use std::collections::HashSet;

/// A problem viewed as a family of polynomial systems (after elimination, if any).
pub struct ProblemSource<'a> {
    problem: &'a Problem,
    /// The equations' monomials for generic data ([`equation_supports`]), when the caller
    /// has them already.
    supports: Option<&'a [Vec<Monomial>]>,
}

impl<'a> ProblemSource<'a> {
    /// The family of `problem`'s instances.
    pub fn new(problem: &'a Problem) -> Self {
        ProblemSource {
            problem,
            supports: None,
        }
    }

    /// The family of `problem`'s instances, whose equations have the monomials `supports`
    /// for generic data (as [`equation_supports`] finds them).
    pub fn with_supports(problem: &'a Problem, supports: &'a [Vec<Monomial>]) -> Self {
        ProblemSource {
            problem,
            supports: Some(supports),
        }
    }
}

impl InstanceSource for ProblemSource<'_> {
    fn nvars(&self) -> usize {
        self.problem.layout.unknown_count() - self.problem.layout.eliminate.len()
    }
    fn var_names(&self) -> Vec<String> {
        let names = self.problem.unknown_names();
        (0..names.len())
            .filter(|i| !self.problem.layout.eliminate.contains(i))
            .map(|i| names[i].clone())
            .collect()
    }
    fn hidden_vars(&self) -> usize {
        self.problem.layout.hidden_count()
    }
    fn residual_checkable(&self) -> bool {
        // What the emitted residual check evaluates: every original equation (none
        // defines a hidden unknown), in at most as many unknowns as polishing takes.
        self.problem.layout.hidden_count() == 0
            && self.problem.layout.unknown_count() <= mingen_runtime::MAX_NEWTON_UNKNOWNS
    }
    fn instance<const P: u32>(&self, rng: &mut InstanceRng) -> Vec<Poly<Fp<P>>> {
        let data = random_data_fp::<P>(&self.problem.layout, rng);
        // Elimination was checked structurally by `plan`; an instance where it fails (a
        // coefficient vanishing by chance mod p) yields an empty system, which the
        // analysis reports as such instead of silently changing the family.
        system(self.problem, &data)
            .map(|(eqs, _)| eqs)
            .unwrap_or_default()
    }
    fn equation_constants(&self) -> Vec<EquationConstants> {
        match self.supports {
            Some(s) => equation_constants(self.problem, s),
            None => {
                equation_constants(self.problem, &equation_supports(self.problem, SUPPORT_SEED))
            }
        }
    }
}

/// The seed of [`equation_supports`]' instances when planning.
pub(crate) const SUPPORT_SEED: u64 = 0x5eed;

/// The monomials of each template equation for generic data: the union over two random
/// instances mod p (a coefficient vanishes by chance in both with probability about 1/p²).
pub(crate) fn equation_supports(problem: &Problem, seed: u64) -> Vec<Vec<Monomial>> {
    let mut rng = <InstanceRng as rand::SeedableRng>::seed_from_u64(seed);
    let mut sets: Vec<HashSet<Monomial>> = Vec::new();
    for _ in 0..2 {
        let data = random_data_fp::<{ crate::algebra::P1 }>(&problem.layout, &mut rng);
        let Ok((equations, _)) = system(problem, &data) else {
            continue;
        };
        sets.resize_with(equations.len(), HashSet::new);
        for (set, e) in sets.iter_mut().zip(&equations) {
            set.extend(e.terms().map(|(m, _)| m.clone()));
        }
    }
    sets.into_iter().map(|s| s.into_iter().collect()).collect()
}

/// The terms of each template equation, with the exact coefficient where it is a number
/// and `None` where it depends on the data. Coefficients are traced from the data symbols,
/// so a constant is exact; terms outside `supports` (vanishing on the data family) are
/// dropped.
pub(crate) fn equation_constants(
    problem: &Problem,
    supports: &[Vec<Monomial>],
) -> Vec<EquationConstants> {
    let tracer = Tracer::new();
    let Ok((equations, _)) = system(problem, &tracer.inputs(problem.layout.data_slot_count()))
    else {
        return Vec::new();
    };
    equations
        .iter()
        .enumerate()
        .map(|(k, e)| {
            let support: Option<HashSet<&Monomial>> = supports
                .get(k)
                .filter(|s| !s.is_empty())
                .map(|s| s.iter().collect());
            e.terms()
                .filter(|(m, _)| support.as_ref().map_or(true, |s| s.contains(m)))
                .map(|(m, c)| match c.value() {
                    TracedValue::Const(q) => (m.clone(), Some(q)),
                    TracedValue::Node { .. } => (m.clone(), None),
                })
                .collect()
        })
        .collect()
}

/// The template's equations for one data instance, and the elimination (with the
/// coefficient matrix that recovers the eliminated unknowns) if the problem has one.
pub type System<C> = (Vec<Poly<C>>, Option<Eliminated<C>>);

/// The template's equations for data `data` over any ring (see [`System`]).
pub(crate) fn system<C: Ring>(problem: &Problem, data: &[C]) -> Result<System<C>, EliminateError> {
    system_and_factors(problem, data).map(|(system, _)| system)
}

/// [`system`] and the `nonzero` expressions as polynomials in the system's variables (the
/// unknowns left after elimination, hidden ones included; `None` for one that involves an
/// eliminated unknown, which cannot divide the system's equations), from one evaluation of
/// the problem.
pub(crate) fn system_and_factors<C: Ring>(
    problem: &Problem,
    data: &[C],
) -> Result<(System<C>, Factors<C>), EliminateError> {
    let (equations, expressions) = if problem.nonzero_count() == 0 {
        (problem.evaluate(data), Vec::new())
    } else {
        problem
            .try_evaluate_with_nonzero(data)
            .unwrap_or_else(|e| panic!("evaluating problem {}: {e}", problem.layout.name))
    };
    // Only the kept equations are computed (the minors of an elimination are the costly
    // part).
    let kept = problem.independent();
    let (mut equations, mut elimination) = if problem.layout.eliminate.is_empty() {
        (select(equations, kept), None)
    } else {
        let (n, eliminate) = (problem.layout.unknown_count(), &problem.layout.eliminate);
        // The minors compute only the kept equations; the other forms select afterwards.
        let reduced = match (problem.block_reduction(), problem.substitution()) {
            (Some(reduction), _) => Some(reduce_block(&equations, n, eliminate, reduction)?),
            (None, Some(affine)) => Some(substitute_linear(&equations, n, eliminate, affine)?),
            (None, None) => None,
        };
        let e = match reduced {
            Some(mut e) => {
                e.equations = select(std::mem::take(&mut e.equations), kept);
                e
            }
            None => eliminate_linear_selected(&equations, n, eliminate, kept)?,
        };
        (e.equations.clone(), Some(e))
    };
    let factors = system_variables(problem, &expressions);
    if problem.divisions().iter().flatten().any(|&d| d > 0) {
        for (k, eq) in equations.iter_mut().enumerate() {
            // Divisions number the equations of the full system.
            let i = kept.map_or(k, |kept| kept[k]);
            let Some(counts) = problem.divisions().get(i) else {
                continue;
            };
            for (factor, &count) in factors.iter().zip(counts) {
                let Some(factor) = factor else { continue };
                for _ in 0..count {
                    if let Some((q, _)) = eq.divide(factor) {
                        *eq = q;
                    }
                }
            }
        }
        if let Some(e) = &mut elimination {
            e.equations.clone_from(&equations);
        }
    }
    // Sign folds come last: the eliminated unknowns' coefficient matrix stays in the
    // unfolded variables, which the solver recovers before it.
    if !problem.sign_folds().is_empty() {
        for fold in problem.sign_folds() {
            for eq in equations.iter_mut() {
                *eq = fold.fold_poly(eq);
            }
        }
        if let Some(e) = &mut elimination {
            e.equations.clone_from(&equations);
        }
    }
    Ok(((equations, elimination), factors))
}

/// The equations `kept` (increasing indices) of `equations`; all with `None`.
fn select<T>(equations: Vec<T>, kept: Option<&[usize]>) -> Vec<T> {
    match kept {
        None => equations,
        Some(kept) => equations
            .into_iter()
            .enumerate()
            .filter(|(i, _)| kept.binary_search(i).is_ok())
            .map(|(_, e)| e)
            .collect(),
    }
}

/// The `nonzero` expressions in a system's variables (see [`system_and_factors`]).
pub(crate) type Factors<C> = Vec<Option<Poly<C>>>;

/// Polynomials in the problem's declared unknowns renumbered into the system's variables
/// (the eliminated unknowns left out); `None` for one that involves an eliminated unknown.
fn system_variables<C: Ring>(problem: &Problem, polys: &[Poly<C>]) -> Factors<C> {
    let layout = &problem.layout;
    let kept: Vec<usize> = (0..layout.unknown_count())
        .filter(|i| !layout.eliminate.contains(i))
        .collect();
    let n = kept.len();
    polys
        .iter()
        .map(|e| {
            let mut out = Poly::zero(n);
            for (m, c) in e.terms() {
                let mut exps = vec![0; n];
                for (i, &x) in m.0.iter().enumerate() {
                    if x == 0 {
                        continue;
                    }
                    exps[kept.iter().position(|&k| k == i)?] = x;
                }
                out.add_term(Monomial(exps), c.clone());
            }
            Some(out)
        })
        .collect()
}
