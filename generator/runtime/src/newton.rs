//! Polishing a solution by Gauss-Newton steps on the problem's polynomial equations
//! (`option newton = N` of a problem file).
//!
//! An equation is a list of terms `c · x^e`: the index of the coefficient `c` in a
//! coefficient slice and the exponents `e` of the unknowns. Each step evaluates every
//! equation `f_i` and its gradient `g_i` at `x`, solves the normal equations
//! `(Σ g_i g_iᵀ) δ = −Σ f_i g_i` (Cholesky, with a relative ridge of 1e-14 on the diagonal
//! for rank-deficient directions) and takes `x + δ` only if it lowers `Σ f_i²`, else the
//! first of `x + δ/2`, `x + δ/4`, ... ([`STEP_HALVINGS`]) that does; otherwise polishing
//! stops. Near a simple root each step roughly squares the error, so the one or
//! two steps a solution from an inaccurate action matrix needs bring it to rounding level;
//! a solution already at rounding level ([`AT_ROUNDING_LEVEL`]) takes no step.
//! No heap allocation: at most [`MAX_NEWTON_UNKNOWNS`] unknowns.

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

/// Value and gradient of `Σ_terms c x^e` (gradient into `grad[..n]`): per term, the
/// products of the factors before and after each unknown (prefix and suffix products), so
/// the gradient costs O(n) per term.
fn value_and_gradient<const M: usize>(
    terms: &[NewtonTerm<'_>],
    coefficients: &[f64],
    powers: &Powers<'_, M>,
    grad: &mut [f64],
) -> Option<f64> {
    let n = powers.x.len();
    if n == 0 {
        return None;
    }
    grad[..n].iter_mut().for_each(|g| *g = 0.0);
    let mut factors = [0.0; M];
    // after[j]: the product of the factors after unknown j.
    let mut after = [1.0; M];
    let mut value = 0.0;
    for &term in terms {
        let c = term_factors(term, coefficients, powers, &mut factors)?;
        let e = term.1;
        after[n - 1] = 1.0;
        for j in (0..n - 1).rev() {
            after[j] = factors[j + 1] * after[j + 1];
        }
        value += c * (factors[0] * after[0]);
        let mut prefix = c;
        for k in 0..n {
            if e[k] != 0 {
                // ∂/∂x_k of x^e: e_k x_k^(e_k - 1) times the other factors.
                grad[k] += prefix * f64::from(e[k]) * powers.pow(k, e[k] - 1) * after[k];
            }
            prefix *= factors[k];
        }
    }
    Some(value)
}

/// A solution whose every equation has `|f_i| <= AT_ROUNDING_LEVEL * Σ_terms |c x^e|` is
/// at the rounding level of evaluating the equations in f64: no step can make it more
/// accurate, so polishing stops there.
pub const AT_ROUNDING_LEVEL: f64 = 16.0 * f64::EPSILON;

/// The sum of squares `Σ_i f_i(x)²` and whether every equation is at rounding level
/// ([`AT_ROUNDING_LEVEL`]); `None` if an equation is malformed or a value not finite.
fn squared_residual<const M: usize>(
    equations: &[&[NewtonTerm<'_>]],
    coefficients: &[f64],
    x: &[f64],
) -> Option<(f64, bool)> {
    let powers = Powers::<M>::new(x);
    sum_of_squares(equations.iter().map(|eq| value(eq, coefficients, &powers)))
}

/// `Σ f²` and whether every `|f| <= AT_ROUNDING_LEVEL · magnitude`, over each equation's
/// `(f, magnitude)`; `None` if one is `None` (a malformed term) or the sum not finite.
#[inline(always)]
fn sum_of_squares(values: impl IntoIterator<Item = Option<(f64, f64)>>) -> Option<(f64, bool)> {
    let mut sum = 0.0;
    let mut converged = true;
    for v in values {
        let (f, magnitude) = v?;
        sum += f * f;
        converged &= f.abs() <= AT_ROUNDING_LEVEL * magnitude;
    }
    sum.is_finite().then_some((sum, converged))
}

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

/// Solves `h δ = b` for the symmetric positive semi-definite `n x n` leading block of `h`
/// (Cholesky with a relative ridge), in place into `b`; `false` if it breaks down.
#[allow(clippy::needless_range_loop)] // triangular index ranges read clearer than iterators
fn solve_normal<const M: usize>(h: &mut [[f64; M]; M], b: &mut [f64], n: usize) -> bool {
    let scale = (0..n).map(|i| h[i][i]).fold(0.0f64, f64::max);
    if !(scale.is_finite() && scale > 0.0) {
        return false;
    }
    for i in 0..n {
        h[i][i] += 1e-14 * scale;
    }
    for j in 0..n {
        let mut d = h[j][j];
        for k in 0..j {
            d -= h[j][k] * h[j][k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        h[j][j] = d;
        for i in j + 1..n {
            let mut s = h[i][j];
            for k in 0..j {
                s -= h[i][k] * h[j][k];
            }
            h[i][j] = s / d;
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= h[i][k] * b[k];
        }
        b[i] = s / h[i][i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= h[k][i] * b[k];
        }
        b[i] = s / h[i][i];
    }
    b[..n].iter().all(|v| v.is_finite())
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
    gauss_newton::<M>(
        x,
        steps,
        |x| squared_residual::<M>(equations, coefficients, x),
        |x, h, b| {
            let mut grad = [0.0; M];
            let powers = Powers::<M>::new(x);
            for eq in equations {
                let Some(f) = value_and_gradient(eq, coefficients, &powers, &mut grad) else {
                    return false;
                };
                add_equation(h, b, f, &grad[..x.len()]);
            }
            true
        },
    )
}

/// Adds an equation's value `f` and gradient to the normal equations `h δ = b` (the lower
/// triangle of `h = Σ g gᵀ`, `b = -Σ f g`).
#[inline(always)]
#[allow(clippy::needless_range_loop)] // the triangular index range reads clearer
fn add_equation<const M: usize>(h: &mut [[f64; M]; M], b: &mut [f64; M], f: f64, grad: &[f64]) {
    for i in 0..grad.len() {
        b[i] -= f * grad[i];
        for j in 0..=i {
            h[i][j] += grad[i] * grad[j];
        }
    }
}

/// How many times a Gauss-Newton step that does not lower the sum of squares is halved
/// before polishing stops: far from a root (a solution read off a poorly conditioned
/// action matrix, far from the origin) the full step can overshoot where a shorter one
/// still descends.
pub const STEP_HALVINGS: usize = 4;

/// The steps both forms take from `x` (`x.len() <= M` unknowns): `squared(x)` is the sum
/// of squares and whether every equation is at rounding level, `normal_equations(x, h, b)`
/// adds every equation ([`add_equation`]; `false`: stop).
#[inline(always)]
fn gauss_newton<const M: usize>(
    x: &mut [f64],
    steps: usize,
    squared: impl Fn(&[f64]) -> Option<(f64, bool)>,
    normal_equations: impl Fn(&[f64], &mut [[f64; M]; M], &mut [f64; M]) -> bool,
) -> usize {
    let n = x.len();
    let Some((mut cost, mut converged)) = squared(x) else {
        return 0;
    };
    let mut taken = 0;
    for _ in 0..steps {
        if cost == 0.0 || converged {
            break;
        }
        let mut h = [[0.0; M]; M];
        let mut b = [0.0; M];
        if !normal_equations(x, &mut h, &mut b) || !solve_normal(&mut h, &mut b, n) {
            break;
        }
        let mut next = [0.0; M];
        let mut accepted = false;
        let mut t = 1.0;
        for _ in 0..=STEP_HALVINGS {
            for ((next, x), b) in next.iter_mut().zip(&*x).zip(&b) {
                *next = x + t * b;
            }
            if let Some((c, at_rounding_level)) = squared(&next[..n]) {
                if c < cost {
                    x.copy_from_slice(&next[..n]);
                    cost = c;
                    converged = at_rounding_level;
                    taken += 1;
                    accepted = true;
                    break;
                }
            }
            t *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    taken
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
    gauss_newton::<N>(
        x,
        steps,
        |x| sum_of_squares(evaluate(&values, x.try_into().ok()?)),
        |x, h, b| {
            let Ok(x) = <&[f64; N]>::try_from(x) else {
                return false;
            };
            let (mut f, mut jac) = ([0.0; E], [[0.0; N]; E]);
            jacobian(x, &mut f, &mut jac);
            for (&f, grad) in f.iter().zip(&jac) {
                add_equation(h, b, f, grad);
            }
            true
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x² + y² − 2 = 0, x − y = 0, x y − 1 = 0 (overdetermined; root (1, 1)).
    fn system() -> (Vec<Vec<NewtonTerm<'static>>>, Vec<f64>) {
        const X2: [u8; 2] = [2, 0];
        const Y2: [u8; 2] = [0, 2];
        const ONE: [u8; 2] = [0, 0];
        const X: [u8; 2] = [1, 0];
        const Y: [u8; 2] = [0, 1];
        const XY: [u8; 2] = [1, 1];
        let eqs = vec![
            vec![(0, &X2[..]), (1, &Y2[..]), (2, &ONE[..])],
            vec![(1, &X[..]), (3, &Y[..])],
            vec![(1, &XY[..]), (3, &ONE[..])],
        ];
        (eqs, vec![1.0, 1.0, -2.0, -1.0])
    }

    #[test]
    fn value_and_gradient_match_the_direct_formula() {
        // 0.5 x^3 y^17 z - 2 y^2 z^4 + 3, exponents past the power table included.
        const A: [u8; 3] = [3, 17, 1];
        const B: [u8; 3] = [0, 2, 4];
        const ONE: [u8; 3] = [0, 0, 0];
        let terms = [(0, &A[..]), (1, &B[..]), (2, &ONE[..])];
        let c = [0.5, -2.0, 3.0];
        let x: [f64; 3] = [1.1, -0.9, 0.7];
        let (a, b, z) = (x[0], x[1], x[2]);
        let f = 0.5 * a.powi(3) * b.powi(17) * z - 2.0 * b * b * z.powi(4) + 3.0;
        let g = [
            1.5 * a * a * b.powi(17) * z,
            8.5 * a.powi(3) * b.powi(16) * z - 4.0 * b * z.powi(4),
            0.5 * a.powi(3) * b.powi(17) - 8.0 * b * b * z.powi(3),
        ];
        let powers = Powers::<3>::new(&x);
        let mut grad = [0.0; 3];
        let v = value_and_gradient(&terms, &c, &powers, &mut grad).unwrap();
        let close = |p: f64, q: f64| (p - q).abs() <= 1e-14 * q.abs().max(1.0);
        assert!(close(v, f), "{v} {f}");
        assert!(close(value(&terms, &c, &powers).unwrap().0, f));
        for k in 0..3 {
            assert!(close(grad[k], g[k]), "{k}: {} {}", grad[k], g[k]);
        }
    }

    #[test]
    fn converges_quadratically_to_a_root() {
        let (eqs, c) = system();
        let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
        let mut x = [1.0 + 1e-5, 1.0 - 3e-6];
        let steps = newton_polish(&mut x, &eqs, &c, 3);
        assert!(steps >= 1);
        assert!(
            (x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14,
            "{x:?}"
        );
    }

    /// The system of [`system`] written out as the emitted solvers write it: the same
    /// steps and the same bits as the table form.
    #[test]
    fn code_form_takes_the_same_steps_as_the_table() {
        let (eqs, c) = system();
        let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
        let values = |x: &[f64; 2], f: &mut [f64; 3], m: &mut [f64; 3]| {
            let t = [
                [c[0] * (x[0] * x[0]), c[1] * (x[1] * x[1]), c[2]],
                [c[1] * x[0], c[3] * x[1], 0.0],
                [c[1] * (x[0] * x[1]), c[3], 0.0],
            ];
            for i in 0..3 {
                f[i] = t[i].iter().sum();
                m[i] = t[i].iter().map(|t| t.abs()).sum();
            }
        };
        let jacobian = |x: &[f64; 2], f: &mut [f64; 3], j: &mut [[f64; 2]; 3]| {
            let mut m = [0.0; 3];
            values(x, f, &mut m);
            *j = [
                [c[0] * 2.0 * x[0], c[1] * 2.0 * x[1]],
                [c[1], c[3]],
                [c[1] * x[1], c[1] * x[0]],
            ];
        };
        for start in [
            [1.3, 0.8],
            [1.0 + 1e-5, 1.0 - 3e-6],
            [3.0, -2.0],
            [1.0, 1.0],
        ] {
            let (mut a, mut b) = (start, start);
            let steps = newton_polish(&mut a, &eqs, &c, 4);
            assert_eq!(newton_polish_with(&mut b, 4, values, jacobian), steps);
            assert_eq!(a, b, "from {start:?}");
        }
        let mut x = [f64::NAN, 1.0];
        assert_eq!(newton_polish_with(&mut x, 4, values, jacobian), 0);
        // The redundant basis's screen: kept as is, rescued by polishing, dropped.
        for start in [
            [1.0, 1.0],
            [1.0 + 1e-3, 1.0 - 2e-3],
            [1.3, 0.8],
            [3.0, -2.0],
        ] {
            let (mut a, mut b) = (start, start);
            let kept = screen_redundant_readout(&mut a, &eqs, &c);
            assert_eq!(
                screen_redundant_readout_with(&mut b, values, jacobian),
                kept
            );
            assert_eq!(a, b, "from {start:?}");
        }
        // Polishing of poor solutions only: the same test and steps.
        for start in [
            [1.0 + 1e-12, 1.0],
            [1.0 + 1e-6, 1.0 - 1e-6],
            [1.3, 0.8],
            [f64::NAN, 1.0],
        ] {
            let (mut a, mut b) = (start, start);
            let steps = polish_poor_solution(&mut a, &eqs, &c);
            assert_eq!(polish_poor_solution_with(&mut b, values, jacobian), steps);
            assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "from {start:?}");
        }
    }

    #[test]
    fn never_makes_a_solution_worse_and_rejects_bad_input() {
        let (eqs, c) = system();
        let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
        // An exact root: nothing to do.
        let mut x = [1.0, 1.0];
        assert_eq!(newton_polish(&mut x, &eqs, &c, 3), 0);
        assert_eq!(x, [1.0, 1.0]);
        // Non-finite start, coefficient out of range, too few equations: untouched.
        let mut x = [f64::NAN, 1.0];
        assert_eq!(newton_polish(&mut x, &eqs, &c, 3), 0);
        let mut x = [1.1, 0.9];
        assert_eq!(newton_polish(&mut x, &eqs, &c[..2], 3), 0);
        assert_eq!(x, [1.1, 0.9]);
        assert_eq!(newton_polish(&mut x, &eqs[..1], &c, 3), 0);
        // Far from a root the cost still only goes down.
        let before = squared_residual::<3>(&eqs, &c, &[3.0, -2.0]).unwrap().0;
        let mut x = [3.0, -2.0];
        newton_polish(&mut x, &eqs, &c, 8);
        assert!(squared_residual::<3>(&eqs, &c, &x).unwrap().0 <= before);
    }

    #[test]
    fn relative_residuals_tell_roots_from_other_points() {
        let (eqs, c) = system();
        let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
        assert_eq!(worst_relative_residual(&[1.0, 1.0], &eqs, &c), Some(0.0));
        // At (2, 1): x^2 + y^2 - 2 = 3 of terms 4 + 1 + 2; x - y = 1 of 2 + 1; xy - 1 = 1
        // of 2 + 1.
        let r = worst_relative_residual(&[2.0, 1.0], &eqs, &c).unwrap();
        assert!((r - 3.0 / 7.0).abs() < 1e-15, "{r}");
        assert!(r > SPURIOUS_RESIDUAL);
        assert!(worst_relative_residual(&[1.0 + 1e-9, 1.0], &eqs, &c).unwrap() < SPURIOUS_RESIDUAL);
        assert_eq!(worst_relative_residual(&[f64::NAN, 1.0], &eqs, &c), None);
        assert_eq!(worst_relative_residual(&[1.0, 1.0], &eqs, &c[..2]), None);
        assert_eq!(worst_relative_residual(&[0.5; 25], &eqs, &c), None);
        // Screening: a close read-out is kept as it is, a poorer one is rescued by
        // polishing, a far one dropped.
        let mut x = [1.0 + 1e-9, 1.0];
        assert!(screen_redundant_readout(&mut x, &eqs, &c));
        assert_eq!(x, [1.0 + 1e-9, 1.0]);
        let mut x = [1.0 + 2e-3, 1.0 - 1e-3];
        assert!(worst_relative_residual(&x, &eqs, &c).unwrap() > SPURIOUS_RESIDUAL);
        assert!(screen_redundant_readout(&mut x, &eqs, &c));
        assert!(
            (x[0] - 1.0).abs() < 1e-9 && (x[1] - 1.0).abs() < 1e-9,
            "{x:?}"
        );
        let mut x = [2.0, 1.0];
        assert!(!screen_redundant_readout(&mut x, &eqs, &c));
        assert_eq!(x, [2.0, 1.0]);
    }

    /// x^3 - 2x + 2 = 0 from x = 1: the Newton step goes back to 0, where the residual is
    /// larger (the classic 0 <-> 1 cycle); a shorter step still descends.
    #[test]
    fn an_overshooting_step_is_halved() {
        const X3: [u8; 1] = [3];
        const X: [u8; 1] = [1];
        const ONE: [u8; 1] = [0];
        let eq: Vec<NewtonTerm> = vec![(0, &X3[..]), (1, &X[..]), (2, &ONE[..])];
        let eqs = [eq.as_slice()];
        let c = [1.0, -2.0, 2.0];
        let f = |x: f64| x * x * x - 2.0 * x + 2.0;
        let mut x = [1.0];
        assert_eq!(newton_polish(&mut x, &eqs, &c, 1), 1);
        assert!(f(x[0]).abs() < f(1.0).abs(), "{x:?}");
        // x = 0 and 0.5 do not lower the residual; 0.75, a quarter of the step, does.
        assert!((x[0] - 0.75).abs() < 1e-12, "{x:?}");
        // Enough steps reach the real root near -1.7693 and stop there.
        let mut x = [1.0];
        newton_polish(&mut x, &eqs, &c, 8);
        assert!(f(x[0]).abs() < f(1.0).abs(), "{x:?}");
    }

    #[test]
    fn polishes_poor_solutions_only() {
        let (eqs, c) = system();
        let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
        // Off by 1e-12: a relative residual near 1e-12, not poor; left as it is although
        // not at rounding level (where `newton_polish` would step).
        let good = [1.0 + 1e-12, 1.0];
        let r = worst_relative_residual(&good, &eqs, &c).unwrap();
        assert!(
            r > 10.0 * AT_ROUNDING_LEVEL && r < POOR_SOLUTION_RESIDUAL,
            "{r}"
        );
        let mut x = good;
        assert_eq!(polish_poor_solution(&mut x, &eqs, &c), 0);
        assert_eq!(x, good);
        // Off by 1e-6: poor; polished to the root within its steps.
        let mut x = [1.0 + 1e-6, 1.0 - 1e-6];
        assert!(worst_relative_residual(&x, &eqs, &c).unwrap() > POOR_SOLUTION_RESIDUAL);
        let steps = polish_poor_solution(&mut x, &eqs, &c);
        assert!((1..=POOR_SOLUTION_STEPS).contains(&steps), "{steps}");
        assert!(
            worst_relative_residual(&x, &eqs, &c).unwrap() < 1e-14,
            "{x:?}"
        );
        // Non-finite input and too many unknowns: untouched.
        let mut x = [f64::NAN, 1.0];
        assert_eq!(polish_poor_solution(&mut x, &eqs, &c), 0);
        let mut x = [0.5; 25];
        assert_eq!(polish_poor_solution(&mut x, &eqs, &c), 0);
        assert_eq!(x, [0.5; 25]);
    }

    #[test]
    fn stops_at_rounding_level() {
        let (eqs, c) = system();
        let eqs: Vec<&[NewtonTerm]> = eqs.iter().map(Vec::as_slice).collect();
        // One ulp off the root: the residual (about 4e-16 against terms of size 1) is at
        // rounding level, so no step is taken even with steps to spare.
        let mut x = [1.0 + f64::EPSILON, 1.0];
        assert!(squared_residual::<3>(&eqs, &c, &x).unwrap().1);
        assert_eq!(newton_polish(&mut x, &eqs, &c, 8), 0);
        assert_eq!(x, [1.0 + f64::EPSILON, 1.0]);
        // A millionth off: not at rounding level; polishing takes steps and then stops
        // before its budget, once the residual is at rounding level.
        let mut x = [1.0 + 1e-6, 1.0 - 1e-6];
        assert!(!squared_residual::<3>(&eqs, &c, &x).unwrap().1);
        let steps = newton_polish(&mut x, &eqs, &c, 8);
        assert!((1..8).contains(&steps), "{steps}");
        assert!(squared_residual::<3>(&eqs, &c, &x).unwrap().1, "{x:?}");
    }
}
