//! Quotient-ring basis (standard monomials) and solution count, confirmed across instances
//! and primes.
//!
//! ## Public API
//! - [`standard_monomials`]`(&GroebnerBasis<P>) -> Result<Vec<Monomial>, GroebnerError>`:
//!   the monomials not divisible by any leading monomial, sorted by **descending grevlex**
//!   (so `1` is last); errors if the ideal is not zero-dimensional.
//! - [`InstanceSource`]: a problem that can draw random instances over any `Z_P`.
//! - [`analyse`]`(&source, seed) -> Result<Analysis<S>, AnalysisError>`: Gröbner basis and
//!   count on one instance mod [`P1`], confirmed on a second instance mod `P1` and on an
//!   instance mod [`P2`]; disagreement is an error, never a silent pick.
//!
//! Randomness: every random draw comes from `ChaCha8Rng::seed_from_u64(seed)` (instance 1
//! and 2 mod P1 in sequence), and `seed ^ 0x5EED_0002` for the P2 instance, so the result is
//! a function of the seed.

use crate::algebra::{Fp, Monomial, MonomialOrder, Poly, P1, P2};
use crate::budget::Deadline;
use crate::groebner::{
    groebner_with, GroebnerBasis, GroebnerError, GroebnerOptions, Mon, MAX_SOLUTIONS,
    MAX_TOTAL_DEGREE,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use thiserror::Error;

/// The random number generator handed to instance sources.
pub type InstanceRng = ChaCha8Rng;

/// A polynomial system family that can produce random instances over any prime field
/// `Z_P` (`P < 2^31`). Instances must be generic members of the family (random data of the
/// right kinds), so that the number of solutions of an instance is that of the family.
pub trait InstanceSource {
    /// Number of unknowns (variables of the polynomials).
    fn nvars(&self) -> usize;
    /// Names of the unknowns, used in error messages; defaults to `x0, x1, ...`.
    fn var_names(&self) -> Vec<String> {
        (0..self.nvars()).map(|i| format!("x{i}")).collect()
    }
    /// Number of hidden variables (the last ones; see
    /// [`crate::problem::UnknownSymbol::hidden`]); none by default.
    fn hidden_vars(&self) -> usize {
        0
    }
    /// Whether the solver of this family can check a solution by the residual of its
    /// original equations, which a redundant basis needs to drop its spurious eigenvalues
    /// (`crate::template::EliminationTemplate::spurious_eigenvalues`); no by default.
    fn residual_checkable(&self) -> bool {
        false
    }
    /// The equations of one random instance over `Z_P`, drawing from `rng`.
    fn instance<const P: u32>(&self, rng: &mut InstanceRng) -> Vec<Poly<Fp<P>>>;
    /// Each equation's terms with the exact coefficient where it is a number, the same on
    /// every instance (`None` where it depends on the data), for the fold of constant
    /// template blocks (`crate::template::fold`); none known by default.
    fn equation_constants(&self) -> Vec<crate::template::EquationConstants> {
        Vec::new()
    }
}

/// The standard monomials of a zero-dimensional Gröbner basis, descending grevlex.
pub fn standard_monomials<const P: u32>(
    gb: &GroebnerBasis<P>,
) -> Result<Vec<Monomial>, GroebnerError> {
    standard_monomials_named(gb, &[])
}

/// [`standard_monomials`] naming the variables in the error.
pub fn standard_monomials_named<const P: u32>(
    gb: &GroebnerBasis<P>,
    names: &[String],
) -> Result<Vec<Monomial>, GroebnerError> {
    let n = gb.nvars();
    let names: Vec<String> = (0..n)
        .map(|i| names.get(i).cloned().unwrap_or_else(|| format!("x{i}")))
        .collect();
    gb.check_zero_dimensional_named(&names)?;
    let lms = gb.leading_packed();
    if lms.iter().any(|m| m.degree() == 0) {
        return Err(GroebnerError::Inconsistent);
    }
    // Breadth-first over the order ideal: multiply standard monomials by each variable.
    let vars: Vec<Mon> = (0..n)
        .map(|v| {
            let mut e = vec![0u32; n];
            e[v] = 1;
            Mon::from_exps(&e)
        })
        .collect();
    let mut out: Vec<Mon> = vec![Mon::from_exps(&vec![0; n])];
    let mut frontier = out.clone();
    while !frontier.is_empty() {
        let mut next: Vec<Mon> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for m in &frontier {
            for x in &vars {
                // A monomial past the packing's bounds would wrap into its neighbours' fields
                // and escape the divisibility test.
                if !m.fits(n) {
                    return Err(GroebnerError::DegreeTooLarge(MAX_TOTAL_DEGREE));
                }
                let c = m.mul(x);
                if !c.fits(n) {
                    return Err(GroebnerError::DegreeTooLarge(MAX_TOTAL_DEGREE));
                }
                if !lms.iter().any(|l| l.divides(&c)) && seen.insert(c) {
                    next.push(c);
                }
            }
        }
        if out.len() + next.len() > MAX_SOLUTIONS {
            return Err(GroebnerError::TooManySolutions);
        }
        out.extend_from_slice(&next);
        frontier = next;
    }
    out.sort_by(|a, b| b.cmp(a));
    Ok(out.into_iter().map(|m| m.to_monomial(n)).collect())
}

/// Failures of [`analyse`].
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum AnalysisError {
    /// The Gröbner basis computation failed or the ideal is not zero-dimensional.
    #[error("{which}: {source}")]
    Groebner {
        /// Which instance (e.g. "instance 1 mod 2147483647").
        which: String,
        /// The underlying error.
        #[source]
        source: GroebnerError,
    },
    /// Two instances disagree on the number of solutions.
    #[error(
        "solution counts disagree: {count1} on instance 1 mod {P1}, {count2} on {which} \
         (an unlucky instance or prime, or data that is not generic)"
    )]
    CountMismatch {
        /// Count on the first instance mod P1.
        count1: usize,
        /// The disagreeing count.
        count2: usize,
        /// Which instance disagrees.
        which: String,
    },
    /// Same count but different standard monomials (the leading ideal is not generic).
    #[error("quotient bases disagree between instance 1 mod {P1} and {which}")]
    BasisMismatch {
        /// Which instance disagrees.
        which: String,
    },
}

/// The result of [`analyse`]: what the template builder needs.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// Number of unknowns.
    pub nvars: usize,
    /// Number of solutions (over the algebraic closure, with multiplicity) = `basis.len()`.
    pub count: usize,
    /// Standard monomials, descending grevlex (`1` last).
    pub basis: Vec<Monomial>,
    /// The equations of instance 1 mod P1 (the instance the template is built from).
    pub equations: Vec<Poly<Fp<P1>>>,
    /// Its reduced Gröbner basis.
    pub groebner: GroebnerBasis<P1>,
}

fn count_on<const P: u32>(
    nvars: usize,
    eqs: &[Poly<Fp<P>>],
    names: &[String],
    which: &str,
    opts: &GroebnerOptions,
) -> Result<(GroebnerBasis<P>, Vec<Monomial>), AnalysisError> {
    let wrap = |source| AnalysisError::Groebner {
        which: which.to_string(),
        source,
    };
    let gb = groebner_with(nvars, eqs, opts).map_err(wrap)?;
    let b = standard_monomials_named(&gb, names).map_err(wrap)?;
    Ok((gb, b))
}

/// Computes the quotient basis and the number of solutions of a system family on random
/// instances: instance 1 and 2 mod [`P1`], instance 3 mod [`P2`]; all three must agree on
/// the count and the standard monomials.
pub fn analyse<S: InstanceSource>(src: &S, seed: u64) -> Result<Analysis, AnalysisError> {
    analyse_within(src, seed, None)
}

/// [`analyse`] within a time and memory budget (the Gröbner bases stop with
/// [`GroebnerError::Budget`] when it runs out).
pub fn analyse_within<S: InstanceSource>(
    src: &S,
    seed: u64,
    deadline: Option<Deadline>,
) -> Result<Analysis, AnalysisError> {
    let opts = GroebnerOptions {
        deadline,
        ..GroebnerOptions::default()
    };
    let n = src.nvars();
    let names = src.var_names();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let eq1 = src.instance::<P1>(&mut rng);
    let (gb1, b1) = count_on(n, &eq1, &names, &format!("instance 1 mod {P1}"), &opts)?;
    let eq2 = src.instance::<P1>(&mut rng);
    let w2 = format!("instance 2 mod {P1}");
    let (_, b2) = count_on(n, &eq2, &names, &w2, &opts)?;
    let mut rng3 = ChaCha8Rng::seed_from_u64(seed ^ 0x5EED_0002);
    let eq3 = src.instance::<P2>(&mut rng3);
    let w3 = format!("instance 3 mod {P2}");
    let (_, b3) = count_on(n, &eq3, &names, &w3, &opts)?;
    for (b, which) in [(&b2, w2), (&b3, w3)] {
        if b.len() != b1.len() {
            return Err(AnalysisError::CountMismatch {
                count1: b1.len(),
                count2: b.len(),
                which,
            });
        }
        if *b != b1 {
            return Err(AnalysisError::BasisMismatch { which });
        }
    }
    debug_assert!(b1
        .windows(2)
        .all(|w| MonomialOrder::Grevlex.cmp(&w[0], &w[1]).is_gt()));
    Ok(Analysis {
        nvars: n,
        count: b1.len(),
        basis: b1,
        equations: eq1,
        groebner: gb1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::Ring;

    /// Intersection of a random circle and a random line: 2 solutions.
    struct CircleLine;
    impl InstanceSource for CircleLine {
        fn nvars(&self) -> usize {
            2
        }
        fn instance<const P: u32>(&self, rng: &mut InstanceRng) -> Vec<Poly<Fp<P>>> {
            use rand::Rng;
            let mut r = || Poly::constant(2, Fp::<P>::new(rng.gen_range(1..1000)));
            let (x, y) = (Poly::<Fp<P>>::var(2, 0), Poly::var(2, 1));
            let one = Poly::constant(2, Fp::<P>::one());
            vec![
                x.mul(&x).add(&y.mul(&y)).sub(&r()),
                x.mul(&r()).add(&y.mul(&r())).sub(&one),
            ]
        }
    }

    #[test]
    fn circle_line_has_two_solutions() {
        let a = analyse(&CircleLine, 1).unwrap();
        assert_eq!(a.count, 2);
        assert_eq!(a.basis, vec![Monomial(vec![0, 1]), Monomial(vec![0, 0])]);
    }
}
