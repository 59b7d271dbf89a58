//! One Gauss-Newton step of the polish ([`super`]): the equations' rows weighted by their
//! magnitudes, the least-squares step by a QR factorisation built with Givens rotations,
//! its halvings and its Levenberg-Marquardt fallback.

use super::AT_ROUNDING_LEVEL;

/// `f / magnitude`, the relative residual of an equation whose terms' magnitudes sum to
/// `magnitude`; `f` itself when that is zero (every term vanishes) or not finite.
#[inline(always)]
pub(super) fn relative(f: f64, magnitude: f64) -> f64 {
    if magnitude > 0.0 && magnitude.is_finite() {
        f / magnitude
    } else {
        f
    }
}

/// The equations evaluated at a trial point `y` of a step from `x`.
#[derive(Clone, Copy)]
pub(super) struct Trial {
    /// `Σ (f_i(y) / m_i(x))²`: the relative residuals with the magnitudes at `x`, the
    /// weights the step was solved with, so that a short enough step along it descends.
    pub(super) at_x: f64,
    /// `Σ (f_i(y) / m_i(y))²`: the baseline of the next step from `y`.
    pub(super) own: f64,
    /// Whether every equation is at rounding level at `y` ([`AT_ROUNDING_LEVEL`]).
    pub(super) converged: bool,
}

/// The [`Trial`] of each equation's `(f(y), m(y), m(x))`; `None` if one is `None` (a
/// malformed term) or a sum not finite.
#[inline(always)]
pub(super) fn trial(values: impl IntoIterator<Item = Option<(f64, f64, f64)>>) -> Option<Trial> {
    let (mut at_x, mut own) = (0.0, 0.0);
    let mut converged = true;
    for v in values {
        let (f, magnitude, magnitude_at_x) = v?;
        let (a, o) = (relative(f, magnitude_at_x), relative(f, magnitude));
        at_x += a * a;
        own += o * o;
        converged &= f.abs() <= AT_ROUNDING_LEVEL * magnitude;
    }
    (at_x.is_finite() && own.is_finite()).then_some(Trial {
        at_x,
        own,
        converged,
    })
}

/// Solves the least-squares problem accumulated in `r` (upper triangular, `n x n` leading
/// block) and `b` by back substitution, in place into `b`; `false` if it breaks down.
///
/// A direction whose diagonal entry is at most [`RANK_TOL`] times the largest is
/// rank-deficient (a root of higher multiplicity, a solution at infinity): its component of
/// the step is set to zero rather than divided by a rounding error.
#[allow(clippy::needless_range_loop)] // triangular index ranges read clearer than iterators
fn solve_triangular<const M: usize>(r: &[[f64; M]; M], b: &mut [f64], n: usize) -> bool {
    let scale = (0..n).map(|i| r[i][i].abs()).fold(0.0f64, f64::max);
    if !(scale.is_finite() && scale > 0.0) {
        return false;
    }
    for i in (0..n).rev() {
        if r[i][i].abs() <= RANK_TOL * scale {
            b[i] = 0.0;
            continue;
        }
        let mut s = b[i];
        for k in i + 1..n {
            s -= r[i][k] * b[k];
        }
        b[i] = s / r[i][i];
    }
    b[..n].iter().all(|v| v.is_finite())
}

/// Relative size of a diagonal entry of the step's triangular factor below which its
/// direction is treated as rank-deficient ([`solve_triangular`]).
const RANK_TOL: f64 = 1e-13;

/// The Levenberg-Marquardt ridge `λ` (rows `sqrt(λ) e_i` of the unknowns scaled to unit
/// Jacobian columns) of the step tried when the Gauss-Newton step and its halvings do not
/// lower the residual: an ill-conditioned direction of the Jacobian can give the full
/// step a length far beyond the root's neighbourhood, which the ridge shortens towards
/// the gradient's direction.
const RIDGE: f64 = 1e-14;

/// The weighted sum of squares below which a step that does not descend is not followed by
/// its Levenberg-Marquardt step: relative residuals near 1e-10 and below are a solution's
/// rounding noise, where no step descends, and the fallback would only cost evaluations.
const LEVENBERG_MIN_COST: f64 = 1e-20;

/// Adds an equation's value `f` and gradient `g`, divided by its magnitude `Σ_terms |c x^e|`
/// ([`relative`]), as a row `g δ = -f` of the step's least-squares problem, rotated into
/// the upper triangular `r` and right-hand side `b` by Givens rotations: a QR
/// factorisation of the Jacobian built one row at a time, whose step is as accurate as the
/// Jacobian's condition allows (the normal equations `JᵀJ` would square it, and lose the
/// step of a solution far from the origin). Divided by their magnitudes, the equations
/// weigh in the step as in the relative residual the polish is judged by: an
/// overdetermined system's equations with large terms (a solution far from the origin)
/// would otherwise hold the step while the others stay unsolved.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // the triangular index range reads clearer
pub(super) fn add_equation<const M: usize>(
    r: &mut [[f64; M]; M],
    b: &mut [f64; M],
    f: f64,
    magnitude: f64,
    grad: &[f64],
) {
    let n = grad.len();
    let w = relative(1.0, magnitude);
    let mut row = [0.0; M];
    for (v, g) in row.iter_mut().zip(grad) {
        *v = w * g;
    }
    let mut rhs = -w * f;
    for k in 0..n {
        let a = row[k];
        if a == 0.0 {
            continue;
        }
        let d = r[k][k];
        // `hypot` guards against overflow at a cost per rotation; the rows are relative
        // (divided by their magnitudes), so the plain square root overflows only on
        // entries beyond 1e150, where `hypot` takes over.
        let h = match (d * d + a * a).sqrt() {
            h if h.is_finite() && h > 0.0 => h,
            _ => d.hypot(a),
        };
        let (c, s) = (d / h, a / h);
        r[k][k] = h;
        for j in k + 1..n {
            let (u, v) = (r[k][j], row[j]);
            r[k][j] = c * u + s * v;
            row[j] = c * v - s * u;
        }
        let (u, v) = (b[k], rhs);
        b[k] = c * u + s * v;
        rhs = c * v - s * u;
    }
}

/// How many times a Gauss-Newton step that does not lower the sum of squares is halved
/// before polishing stops: far from a root (a solution read off a poorly conditioned
/// action matrix, far from the origin) the full step can overshoot where a shorter one
/// still descends.
pub const STEP_HALVINGS: usize = 4;

/// The steps both forms take from `x` (`x.len() <= M` unknowns). `evaluate(y, at, w)`
/// evaluates the equations at `y` ([`Trial`]: relative residuals weighted by the
/// magnitudes at the point `at` describes, or at `y` itself for `None`) and leaves in `w`
/// what describes `y` for the next step (the code form's magnitudes, the term form's
/// point); `least_squares(x, w, r, b)` adds every equation at `x` ([`add_equation`];
/// `false`: stop). A step solves the least-squares problem with unit columns (its
/// Levenberg-Marquardt step with [`RIDGE`] if the step and its halvings do not lower the
/// weighted sum).
#[inline(always)]
pub(super) fn gauss_newton<const M: usize, W: Copy>(
    x: &mut [f64],
    steps: usize,
    mut weights: W,
    evaluate: impl Fn(&[f64], Option<&W>, &mut W) -> Option<Trial>,
    least_squares: impl Fn(&[f64], &W, &mut [[f64; M]; M], &mut [f64; M]) -> bool,
) -> usize {
    let n = x.len();
    let Some(Trial {
        own: mut cost,
        mut converged,
        ..
    }) = evaluate(x, None, &mut weights)
    else {
        return 0;
    };
    let mut taken = 0;
    for _ in 0..steps {
        if cost == 0.0 || converged {
            break;
        }
        let mut r = [[0.0; M]; M];
        let mut rhs = [0.0; M];
        if !least_squares(x, &weights, &mut r, &mut rhs) {
            break;
        }
        // Columns scaled to unit norm (the columns of `r` have the Jacobian's norms): the
        // rank test and the ridge then compare directions, not the units of unknowns that
        // differ by orders of magnitude (a solution far from the origin).
        let mut norm = [1.0; M];
        for j in 0..n {
            let c = (0..=j).map(|i| r[i][j] * r[i][j]).sum::<f64>().sqrt();
            if c > 0.0 && c.is_finite() {
                norm[j] = c;
                (0..=j).for_each(|i| r[i][j] /= c);
            }
        }
        let mut accepted = false;
        for ridge in [None, Some(RIDGE)] {
            if ridge.is_some() && cost <= LEVENBERG_MIN_COST {
                break;
            }
            let (mut factor, mut step) = (r, rhs);
            if let Some(ridge) = ridge {
                // The Levenberg-Marquardt step: rows `sqrt(λ) e_i` of the scaled unknowns.
                let mut row = [0.0; M];
                for i in 0..n {
                    row[..n].iter_mut().for_each(|v| *v = 0.0);
                    row[i] = ridge.sqrt();
                    add_equation(&mut factor, &mut step, 0.0, 1.0, &row[..n]);
                }
            }
            if !solve_triangular(&factor, &mut step, n) {
                continue;
            }
            step.iter_mut().zip(&norm).for_each(|(d, c)| *d /= c);
            let mut next = [0.0; M];
            let mut t = 1.0;
            for _ in 0..=STEP_HALVINGS {
                for ((next, x), b) in next.iter_mut().zip(&*x).zip(&step) {
                    *next = x + t * b;
                }
                let mut at_next = weights;
                if let Some(t) = evaluate(&next[..n], Some(&weights), &mut at_next) {
                    if t.at_x < cost {
                        x.copy_from_slice(&next[..n]);
                        weights = at_next;
                        cost = t.own;
                        converged = t.converged;
                        taken += 1;
                        accepted = true;
                        break;
                    }
                }
                t *= 0.5;
            }
            if accepted {
                break;
            }
        }
        if !accepted {
            break;
        }
    }
    taken
}
