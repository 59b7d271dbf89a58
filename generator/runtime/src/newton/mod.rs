//! Polishing a solution by Gauss-Newton steps on the problem's polynomial equations
//! (`option newton = N` of a problem file).
//!
//! An equation is a list of terms `c · x^e`: the index of the coefficient `c` in a
//! coefficient slice and the exponents `e` of the unknowns. Each step evaluates every
//! equation `f_i` and its gradient `g_i` at `x`, divides both by the equation's magnitude
//! `m_i = Σ_terms |c x^e|` (the relative residual the audit measures), solves the
//! least-squares problem `min |J δ + f|` of those rows by a QR factorisation built one row
//! at a time with Givens rotations (columns scaled to unit norm; directions whose
//! diagonal is below 1e-13 of the largest get no step) and takes `x + δ` only if it lowers
//! `Σ (f_i / m_i)²` (the magnitudes at `x`), else the
//! first of `x + δ/2`, `x + δ/4`, ... ([`STEP_HALVINGS`]) that does; otherwise polishing
//! stops. Near a simple root each step roughly squares the error, so the one or
//! two steps a solution from an inaccurate action matrix needs bring it to rounding level;
//! a solution already at rounding level ([`AT_ROUNDING_LEVEL`]) takes no step.
//! No heap allocation: at most [`MAX_NEWTON_UNKNOWNS`] unknowns.

mod step;

pub use step::STEP_HALVINGS;
use step::{add_equation, gauss_newton, trial};

/// One term of an equation: the index of its coefficient and the exponent of each unknown.
pub type NewtonTerm<'a> = (usize, &'a [u8]);

/// Most unknowns [`newton_polish`] accepts.
pub const MAX_NEWTON_UNKNOWNS: usize = 24;

/// Highest power of an unknown taken from the table of [`Powers`]; higher exponents use
/// `powi`. The emitted solvers' written-out equations form their powers the same way, so
/// that both forms compute the same bits.
pub const MAX_TABULATED_POWER: usize = 15;

/// The powers `x_j^0 ..= x_j^MAX_TABULATED_POWER` of every unknown, so that a term costs a
/// few multiplications instead of a `powi` per factor. `M` is the capacity (at least
/// `x.len()`): the working arrays of a polish are sized by it, so a small problem does not
/// fill and clear arrays for [`MAX_NEWTON_UNKNOWNS`] unknowns at every evaluation.
struct Powers<'x, const M: usize> {
    x: &'x [f64],
    table: [[f64; MAX_TABULATED_POWER + 1]; M],
}

impl<'x, const M: usize> Powers<'x, M> {
    fn new(x: &'x [f64]) -> Self {
        let mut table = [[1.0; MAX_TABULATED_POWER + 1]; M];
        for (row, &xi) in table.iter_mut().zip(x) {
            for p in 1..=MAX_TABULATED_POWER {
                row[p] = row[p - 1] * xi;
            }
        }
        Powers { x, table }
    }
    /// `x_j^e`.
    fn pow(&self, j: usize, e: u8) -> f64 {
        match self.table[j].get(usize::from(e)) {
            Some(&v) => v,
            None => self.x[j].powi(i32::from(e)),
        }
    }
}

/// The coefficient of a term and its factors `x_j^e_j` (into `factors[..n]`), or `None` if
/// the term is malformed.
fn term_factors<const M: usize>(
    (c, e): NewtonTerm<'_>,
    coefficients: &[f64],
    powers: &Powers<'_, M>,
    factors: &mut [f64; M],
) -> Option<f64> {
    let n = powers.x.len();
    if e.len() != n {
        return None;
    }
    for (j, (f, &ej)) in factors.iter_mut().zip(e).enumerate() {
        *f = powers.pow(j, ej);
    }
    coefficients.get(c).copied()
}

/// Value of `Σ_terms c x^e` and its magnitude `Σ_terms |c x^e|`.
fn value<const M: usize>(
    terms: &[NewtonTerm<'_>],
    coefficients: &[f64],
    powers: &Powers<'_, M>,
) -> Option<(f64, f64)> {
    let n = powers.x.len();
    let mut factors = [0.0; M];
    let (mut value, mut magnitude) = (0.0, 0.0);
    for &term in terms {
        let c = term_factors(term, coefficients, powers, &mut factors)?;
        let t = c * factors[..n].iter().product::<f64>();
        value += t;
        magnitude += t.abs();
    }
    Some((value, magnitude))
}

/// Value, magnitude `Σ_terms |c x^e|` and gradient of `Σ_terms c x^e` (gradient into
/// `grad[..n]`): per term, the
/// products of the factors before and after each unknown (prefix and suffix products), so
/// the gradient costs O(n) per term.
fn value_and_gradient<const M: usize>(
    terms: &[NewtonTerm<'_>],
    coefficients: &[f64],
    powers: &Powers<'_, M>,
    grad: &mut [f64],
) -> Option<(f64, f64)> {
    let n = powers.x.len();
    if n == 0 {
        return None;
    }
    grad[..n].iter_mut().for_each(|g| *g = 0.0);
    let mut factors = [0.0; M];
    // after[j]: the product of the factors after unknown j.
    let mut after = [1.0; M];
    let (mut value, mut magnitude) = (0.0, 0.0);
    for &term in terms {
        let c = term_factors(term, coefficients, powers, &mut factors)?;
        let e = term.1;
        after[n - 1] = 1.0;
        for j in (0..n - 1).rev() {
            after[j] = factors[j + 1] * after[j + 1];
        }
        let t = c * (factors[0] * after[0]);
        value += t;
        magnitude += t.abs();
        let mut prefix = c;
        for k in 0..n {
            if e[k] != 0 {
                // ∂/∂x_k of x^e: e_k x_k^(e_k - 1) times the other factors.
                grad[k] += prefix * f64::from(e[k]) * powers.pow(k, e[k] - 1) * after[k];
            }
            prefix *= factors[k];
        }
    }
    Some((value, magnitude))
}

/// A solution whose every equation has `|f_i| <= AT_ROUNDING_LEVEL * Σ_terms |c x^e|` is
/// at the rounding level of evaluating the equations in f64: no step can make it more
/// accurate, so polishing stops there.
pub const AT_ROUNDING_LEVEL: f64 = 16.0 * f64::EPSILON;

/// The largest `|f| / magnitude` over each equation's `(f, magnitude)` (those of zero
/// magnitude left out); `None` if one is `None` or not finite.
#[inline(always)]
fn worst_of(values: impl IntoIterator<Item = Option<(f64, f64)>>) -> Option<f64> {
    let mut worst = 0.0f64;
    for v in values {
        let (f, magnitude) = v?;
        if !(f.is_finite() && magnitude.is_finite()) {
            return None;
        }
        if magnitude > 0.0 {
            worst = worst.max(f.abs() / magnitude);
        }
    }
    Some(worst)
}

/// The largest relative residual ([`worst_relative_residual`]) at which a read-out of a
/// redundant basis is a solution as it is: the action matrix of a redundant basis (more
/// monomials than solutions) has eigenvalues that are no solution. A solution's residual
/// is near the rounding level scaled by the template's conditioning; a spurious
/// read-out's is mostly of the order of the equations' terms themselves.
pub const SPURIOUS_RESIDUAL: f64 = 1e-4;

/// Up to this relative residual, a read-out above [`SPURIOUS_RESIDUAL`] is given
/// [`SPURIOUS_RESCUE_STEPS`] Gauss-Newton steps, and kept (polished) if they bring it to
/// [`RESCUED_RESIDUAL`]: a poorly conditioned solution does, a spurious read-out does not.
pub const SPURIOUS_RESCUE: f64 = 1e-2;

/// Gauss-Newton steps of [`SPURIOUS_RESCUE`].
pub const SPURIOUS_RESCUE_STEPS: usize = 3;

/// The relative residual a rescued read-out must reach ([`SPURIOUS_RESCUE`]).
pub const RESCUED_RESIDUAL: f64 = 1e-9;

/// Whether a read-out `x` of a redundant basis is a solution ([`SPURIOUS_RESIDUAL`],
/// [`SPURIOUS_RESCUE`]); a rescued one is left polished in `x`.
pub fn screen_redundant_readout(
    x: &mut [f64],
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
) -> bool {
    screen(
        x,
        |x| worst_relative_residual(x, equations, coefficients),
        |x| {
            newton_polish(x, equations, coefficients, SPURIOUS_RESCUE_STEPS);
        },
    )
}

/// [`screen_redundant_readout`] on equations given as code, as [`newton_polish_with`]
/// takes them: the same test and the same bits.
pub fn screen_redundant_readout_with<const N: usize, const E: usize>(
    x: &mut [f64; N],
    values: impl Fn(&[f64; N], &mut [f64; E], &mut [f64; E]),
    jacobian: impl Fn(&[f64; N], &mut [f64; E], &mut [[f64; N]; E]),
) -> bool {
    let worst = |x: &[f64]| worst_of(evaluate(&values, x.try_into().ok()?));
    screen(x, worst, |x| {
        if let Ok(x) = <&mut [f64; N]>::try_from(x) {
            newton_polish_with(x, SPURIOUS_RESCUE_STEPS, &values, &jacobian);
        }
    })
}

/// The screen of both forms: `worst(x)` is the worst relative residual, `polish(x)` the
/// rescue's steps.
fn screen(
    x: &mut [f64],
    worst: impl Fn(&[f64]) -> Option<f64>,
    polish: impl Fn(&mut [f64]),
) -> bool {
    match worst(x) {
        Some(r) if r <= SPURIOUS_RESIDUAL => true,
        Some(r) if r <= SPURIOUS_RESCUE => {
            let mut polished = [0.0; MAX_NEWTON_UNKNOWNS];
            let Some(polished) = polished.get_mut(..x.len()) else {
                return false;
            };
            polished.copy_from_slice(x);
            polish(polished);
            let rescued = worst(polished).is_some_and(|r| r <= RESCUED_RESIDUAL);
            if rescued {
                x.copy_from_slice(polished);
            }
            rescued
        }
        _ => false,
    }
}

/// The worst relative residual above which a solution is poor: a solver whose solutions
/// are not all polished (the plan found its template accurate, `option newton` not given)
/// still gives a poor one [`POOR_SOLUTION_STEPS`] Gauss-Newton steps
/// ([`polish_poor_solution`]). A solution from a well-conditioned elimination is near the
/// rounding level, orders of magnitude below; a poorly conditioned instance (a near-
/// degenerate configuration, a solution far from the origin) gives one that is accurate
/// to a few digits only, which one or two steps bring to rounding level. Checking costs
/// one evaluation of the equations per solution.
pub const POOR_SOLUTION_RESIDUAL: f64 = 1e-10;

/// Gauss-Newton steps of [`polish_poor_solution`].
pub const POOR_SOLUTION_STEPS: usize = 2;

/// Polishes `x` by up to [`POOR_SOLUTION_STEPS`] Gauss-Newton steps ([`newton_polish`])
/// if its worst relative residual ([`worst_relative_residual`]) is above
/// [`POOR_SOLUTION_RESIDUAL`] (or cannot be evaluated; more than [`MAX_NEWTON_UNKNOWNS`]
/// unknowns: nothing is done); returns the steps taken. Never
/// makes `x` worse, never panics, never allocates.
pub fn polish_poor_solution(
    x: &mut [f64],
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
) -> usize {
    match worst_relative_residual(x, equations, coefficients) {
        Some(r) if r <= POOR_SOLUTION_RESIDUAL => 0,
        _ => newton_polish(x, equations, coefficients, POOR_SOLUTION_STEPS),
    }
}

/// [`polish_poor_solution`] on equations given as code, as [`newton_polish_with`] takes
/// them: the same test and the same bits.
pub fn polish_poor_solution_with<const N: usize, const E: usize>(
    x: &mut [f64; N],
    values: impl Fn(&[f64; N], &mut [f64; E], &mut [f64; E]),
    jacobian: impl Fn(&[f64; N], &mut [f64; E], &mut [[f64; N]; E]),
) -> usize {
    match worst_of(evaluate(&values, x)) {
        Some(r) if r <= POOR_SOLUTION_RESIDUAL => 0,
        _ => newton_polish_with(x, POOR_SOLUTION_STEPS, values, jacobian),
    }
}

/// The worst relative residual `|f_i(x)| / Σ_terms |c x^e|` over the equations (0 for an
/// equation whose terms all vanish at `x`), as the audit measures solutions; `None` for a
/// malformed term, too many unknowns ([`MAX_NEWTON_UNKNOWNS`]) or a non-finite value.
pub fn worst_relative_residual(
    x: &[f64],
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
) -> Option<f64> {
    match x.len() {
        0..=3 => worst_relative::<3>(x, equations, coefficients),
        4..=6 => worst_relative::<6>(x, equations, coefficients),
        7..=12 => worst_relative::<12>(x, equations, coefficients),
        13..=MAX_NEWTON_UNKNOWNS => {
            worst_relative::<MAX_NEWTON_UNKNOWNS>(x, equations, coefficients)
        }
        _ => None,
    }
}

/// [`worst_relative_residual`] with working arrays for `M >= x.len()` unknowns.
fn worst_relative<const M: usize>(
    x: &[f64],
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
) -> Option<f64> {
    let powers = Powers::<M>::new(x);
    worst_of(equations.iter().map(|eq| value(eq, coefficients, &powers)))
}

/// Up to `steps` Gauss-Newton steps on `equations` (terms indexing `coefficients`) from
/// `x`, each kept only if it lowers the sum of squared residuals (see the module
/// documentation). Returns the number of steps taken; `x` is never made worse. Nothing
/// is done for more than [`MAX_NEWTON_UNKNOWNS`] unknowns, fewer equations than
/// unknowns, a malformed term or non-finite values.
pub fn newton_polish(
    x: &mut [f64],
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
    steps: usize,
) -> usize {
    let n = x.len();
    if n == 0 || n > MAX_NEWTON_UNKNOWNS || equations.len() < n {
        return 0;
    }
    match n {
        1..=3 => polish::<3>(x, equations, coefficients, steps),
        4..=6 => polish::<6>(x, equations, coefficients, steps),
        7..=12 => polish::<12>(x, equations, coefficients, steps),
        _ => polish::<MAX_NEWTON_UNKNOWNS>(x, equations, coefficients, steps),
    }
}

/// [`newton_polish`] with working arrays for `M >= x.len()` unknowns.
fn polish<const M: usize>(
    x: &mut [f64],
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
    steps: usize,
) -> usize {
    gauss_newton::<M, _>(
        x,
        steps,
        [0.0; M],
        |y, at, point| {
            point[..y.len()].copy_from_slice(y);
            let powers = Powers::<M>::new(y);
            let at = at.map(|x| Powers::<M>::new(&x[..y.len()]));
            trial(equations.iter().map(|eq| {
                let (f, m) = value(eq, coefficients, &powers)?;
                let m_at = match &at {
                    Some(p) => value(eq, coefficients, p)?.1,
                    None => m,
                };
                Some((f, m, m_at))
            }))
        },
        |x, _, r, b| {
            let mut grad = [0.0; M];
            let powers = Powers::<M>::new(x);
            for eq in equations {
                let Some((f, magnitude)) = value_and_gradient(eq, coefficients, &powers, &mut grad)
                else {
                    return false;
                };
                add_equation(r, b, f, magnitude, &grad[..x.len()]);
            }
            true
        },
    )
}

/// Each equation's `(value, magnitude)` from the code form's `values`.
#[inline(always)]
fn evaluate<const N: usize, const E: usize>(
    values: impl Fn(&[f64; N], &mut [f64; E], &mut [f64; E]),
    x: &[f64; N],
) -> impl Iterator<Item = Option<(f64, f64)>> {
    let (mut f, mut magnitude) = ([0.0; E], [0.0; E]);
    values(x, &mut f, &mut magnitude);
    f.into_iter().zip(magnitude).map(Some)
}

/// [`newton_polish`] on equations given as code rather than as a term table: the same
/// steps, acceptance test and stopping rule, and the same bits when the code evaluates the
/// terms as [`newton_polish`] does (emitted solvers write their equations out so, without
/// a table to walk per term).
///
/// `values(x, f, magnitudes)` writes each equation's value `f_i(x)` and its magnitude
/// `Σ_terms |c x^e|` ([`AT_ROUNDING_LEVEL`]); `jacobian(x, f, j)` writes the values and
/// the gradients, `j[i][k] = ∂f_i/∂x_k`. Returns the number of steps taken; none if there
/// are no unknowns, more than [`MAX_NEWTON_UNKNOWNS`], fewer equations than unknowns, or
/// a value is not finite. Never panics, never allocates.
pub fn newton_polish_with<const N: usize, const E: usize>(
    x: &mut [f64; N],
    steps: usize,
    values: impl Fn(&[f64; N], &mut [f64; E], &mut [f64; E]),
    jacobian: impl Fn(&[f64; N], &mut [f64; E], &mut [[f64; N]; E]),
) -> usize {
    if N == 0 || N > MAX_NEWTON_UNKNOWNS || E < N {
        return 0;
    }
    gauss_newton::<N, _>(
        x,
        steps,
        [0.0; E],
        |y, at, magnitudes| {
            let (mut f, mut m) = ([0.0; E], [0.0; E]);
            values(y.try_into().ok()?, &mut f, &mut m);
            *magnitudes = m;
            let at = at.unwrap_or(&m);
            trial((0..E).map(|i| Some((f[i], m[i], at[i]))))
        },
        |x, magnitudes, r, b| {
            let Ok(x) = <&[f64; N]>::try_from(x) else {
                return false;
            };
            let (mut f, mut jac) = ([0.0; E], [[0.0; N]; E]);
            jacobian(x, &mut f, &mut jac);
            for ((&f, grad), &magnitude) in f.iter().zip(&jac).zip(magnitudes) {
                add_equation(r, b, f, magnitude, grad);
            }
            true
        },
    )
}

#[cfg(test)]
mod tests;
