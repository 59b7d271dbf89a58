//! Levenberg-Marquardt on fixed-size nalgebra matrices, with robust losses by iteratively
//! reweighted normal equations and Marquardt's damping (ARCHITECTURE §3).

use nalgebra::{SMatrix, SVector};

/// Loss applied to squared residuals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Loss {
    /// `ρ(s) = s`.
    Trivial,
    /// `ρ(s) = c² ln(1 + s/c²)` with scale `c` (residual units).
    Cauchy(f64),
    /// `ρ(s) = min(s, c²)` with threshold `c` (residual units): MSAC's truncated quadratic,
    /// so points beyond `c` carry no weight (their set is re-decided every iteration).
    Truncated(f64),
}

impl Loss {
    /// `ρ(s)` of a squared residual `s`.
    pub fn rho(&self, s: f64) -> f64 {
        match *self {
            Loss::Trivial => s,
            Loss::Cauchy(c) => c * c * (s / (c * c)).ln_1p(),
            Loss::Truncated(c) => s.min(c * c),
        }
    }
    /// The IRLS weight `ρ'(s)` of a squared residual `s`.
    pub fn weight(&self, s: f64) -> f64 {
        match *self {
            Loss::Trivial => 1.0,
            Loss::Cauchy(c) => 1.0 / (1.0 + s / (c * c)),
            Loss::Truncated(c) => {
                if s < c * c {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}

/// Levenberg-Marquardt options.
#[derive(Debug, Clone, PartialEq)]
pub struct LmOptions {
    /// Maximum number of LM iterations (default 50).
    pub max_iterations: usize,
    /// Initial damping μ (default 1e-3).
    pub initial_damping: f64,
    /// Stop when the relative cost decrease falls below this (default 1e-12).
    pub cost_tolerance: f64,
    /// Stop when the step norm falls below this (default 1e-12).
    pub step_tolerance: f64,
    /// Finite-difference step in tangent coordinates (default 1e-6).
    pub fd_step: f64,
}

impl Default for LmOptions {
    fn default() -> Self {
        LmOptions {
            max_iterations: 50,
            initial_damping: 1e-3,
            cost_tolerance: 1e-12,
            step_tolerance: 1e-12,
            fd_step: 1e-6,
        }
    }
}

/// A least-squares problem in `N` tangent dimensions.
pub trait LmProblem<const N: usize> {
    /// The state on its manifold.
    type State: Clone;
    /// Number of residuals.
    fn num_residuals(&self) -> usize;
    /// Write the residuals of `state` into `out` (length [`num_residuals`](Self::num_residuals)).
    fn residuals(&self, state: &Self::State, out: &mut [f64]);
    /// Move `state` by the tangent step `delta`.
    fn retract(&self, state: &Self::State, delta: &SVector<f64, N>) -> Self::State;
    /// The robust loss.
    fn loss(&self) -> Loss;
    /// The loss applies to residuals `0..robust_residuals()`; the rest are plain squares
    /// (prior terms, which a robust loss must not discount). Default: all residuals.
    fn robust_residuals(&self) -> usize {
        self.num_residuals()
    }
    /// Residuals of `state` into `out` and their analytic Jacobian into `jac` (`jac[i]` is
    /// the gradient of residual `i` with respect to the tangent step `δ` at `δ = 0`, i.e.
    /// of `residuals(retract(state, δ))`). Return `false` (the default) to have
    /// [`levenberg_marquardt`] use central finite differences instead.
    fn residuals_and_jacobian(
        &self,
        _state: &Self::State,
        _out: &mut [f64],
        _jac: &mut [SVector<f64, N>],
    ) -> bool {
        false
    }
}

/// Result of [`levenberg_marquardt`].
#[derive(Debug, Clone)]
pub struct LmResult<S> {
    /// Final state.
    pub state: S,
    /// Initial robust cost.
    pub initial_cost: f64,
    /// Final robust cost.
    pub cost: f64,
    /// Iterations performed.
    pub iterations: usize,
}

fn robust_cost(loss: Loss, robust: usize, r: &[f64]) -> f64 {
    let (a, b) = r.split_at(robust.min(r.len()));
    a.iter().map(|x| loss.rho(x * x)).sum::<f64>() + b.iter().map(|x| x * x).sum::<f64>()
}

/// Minimise `Σ ρ(r_i²)` from `state` (see the module documentation). Never returns a state
/// with a higher or non-finite cost than the initial one.
pub fn levenberg_marquardt<const N: usize, P: LmProblem<N>>(
    problem: &P,
    state: P::State,
    options: &LmOptions,
) -> LmResult<P::State> {
    let n = problem.num_residuals();
    let loss = problem.loss();
    let robust = problem.robust_residuals();
    let mut r = vec![0.0; n];
    let mut rp = vec![0.0; n];
    let mut rm = vec![0.0; n];
    let mut jac = vec![SVector::<f64, N>::zeros(); n];
    problem.residuals(&state, &mut r);
    let mut cost = robust_cost(loss, robust, &r);
    let mut result = LmResult {
        state,
        initial_cost: cost,
        cost,
        iterations: 0,
    };
    if !cost.is_finite() || n == 0 {
        return result;
    }
    let mut mu = options.initial_damping;
    let h = options.fd_step;
    let mut need_jacobian = true;
    let mut hess = SMatrix::<f64, N, N>::zeros();
    let mut grad = SVector::<f64, N>::zeros();
    while result.iterations < options.max_iterations {
        result.iterations += 1;
        if need_jacobian && !problem.residuals_and_jacobian(&result.state, &mut r, &mut jac) {
            for k in 0..N {
                let mut d = SVector::<f64, N>::zeros();
                d[k] = h;
                problem.residuals(&problem.retract(&result.state, &d), &mut rp);
                d[k] = -h;
                problem.residuals(&problem.retract(&result.state, &d), &mut rm);
                for i in 0..n {
                    jac[i][k] = (rp[i] - rm[i]) / (2.0 * h);
                }
            }
        }
        if need_jacobian {
            hess.fill(0.0);
            grad.fill(0.0);
            for i in 0..n {
                let w = if i < robust {
                    loss.weight(r[i] * r[i])
                } else {
                    1.0
                };
                if !(w.is_finite() && jac[i].iter().all(|x| x.is_finite()) && r[i].is_finite()) {
                    continue;
                }
                hess.syger(w, &jac[i], &jac[i], 1.0);
                grad.axpy(w * r[i], &jac[i], 1.0);
            }
            hess.fill_upper_triangle_with_lower_triangle();
            need_jacobian = false;
        }
        let mut damped = hess;
        for k in 0..N {
            damped[(k, k)] += mu * hess[(k, k)].max(1e-12);
        }
        let Some(step) = damped.cholesky().map(|c| c.solve(&(-grad))) else {
            mu *= 10.0;
            if mu > 1e12 {
                break;
            }
            continue;
        };
        if !step.iter().all(|x| x.is_finite()) {
            break;
        }
        let candidate = problem.retract(&result.state, &step);
        problem.residuals(&candidate, &mut rp);
        let new_cost = robust_cost(loss, robust, &rp);
        if new_cost.is_finite() && new_cost < cost {
            let decrease = (cost - new_cost) / cost.max(1e-300);
            result.state = candidate;
            std::mem::swap(&mut r, &mut rp);
            cost = new_cost;
            mu = (mu * 0.1).max(1e-12);
            need_jacobian = true;
            if decrease < options.cost_tolerance || step.norm() < options.step_tolerance {
                break;
            }
        } else {
            mu *= 10.0;
            if mu > 1e12 || step.norm() < options.step_tolerance {
                break;
            }
        }
    }
    result.cost = cost;
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lm_minimises_a_quadratic() {
        struct Q;
        impl LmProblem<2> for Q {
            type State = SVector<f64, 2>;
            fn num_residuals(&self) -> usize {
                3
            }
            fn residuals(&self, s: &Self::State, out: &mut [f64]) {
                out[0] = s[0] - 1.0;
                out[1] = 10.0 * (s[1] - s[0] * s[0]);
                out[2] = 0.0;
            }
            fn retract(&self, s: &Self::State, d: &SVector<f64, 2>) -> Self::State {
                s + d
            }
            fn loss(&self) -> Loss {
                Loss::Trivial
            }
        }
        let opts = LmOptions {
            max_iterations: 200,
            ..Default::default()
        };
        let r = levenberg_marquardt(&Q, SVector::<f64, 2>::new(-1.2, 1.0), &opts);
        assert!(
            (r.state - SVector::<f64, 2>::new(1.0, 1.0)).norm() < 1e-6,
            "{:?} {} {} {}",
            r.state,
            r.iterations,
            r.cost,
            r.initial_cost
        );
    }
}
