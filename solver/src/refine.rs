//! Nonlinear refinement: Levenberg-Marquardt on fixed-size nalgebra matrices.
//!
//! Parameterisation: rotations are unit quaternions updated on the right by tangent steps,
//! `q ← q ⊗ exp(δθ)` (`R ← R exp([δθ]×)`, δθ ∈ so(3)); the unit translation is updated in the
//! 2-D tangent plane of the sphere, `t ← normalise(t + δ1 b1 + δ2 b2)` with `(b1, b2)` from
//! [`tangent_basis`]. Jacobians are central finite differences of the residual vector
//! (step [`LmOptions::fd_step`] in tangent coordinates), assembled into `J^T W J` as an
//! `N x N` fixed-size matrix. Robust losses use iteratively reweighted normal equations; the
//! cost minimised is `Σ ρ(r_i²)` with `ρ(s) = s` (trivial) or `ρ(s) = c² ln(1 + s / c²)`
//! (Cauchy with scale `c`). Damping is Marquardt's: `(H + μ diag(H)) δ = -g`.
//!
//! Three costs:
//! - [`refine_pose`] with [`PoseModel::PaperLinear`] + [`ResidualKind::Algebraic`]: the
//!   paper's `grsrp+` cost `m2^T [t]× (I + v2[λω2]×) R (I - v1[λω1]×) m1` over inliers;
//! - [`refine_pose`] with [`PoseModel::ExactAngular`] + [`ResidualKind::Sampson`]: Sampson
//!   error of the exact angular model (`rectified`), or the global-shutter model (`gsrp`);
//! - [`refine_nrsrp`]: Dai et al.'s generalized epipolar constraint for the uniform RS model,
//!   unknowns `R, t, ω1, d1, ω2, d2`, Cauchy loss over all points.

use crate::epipolar::{PointData, PoseModel, ResidualKind};
use crate::geometry::{skew, tangent_basis};
use nalgebra::{Matrix3, SMatrix, SVector, UnitQuaternion, Vector3};

/// Loss applied to squared residuals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Loss {
    /// `ρ(s) = s`.
    Trivial,
    /// `ρ(s) = c² ln(1 + s/c²)` with scale `c` (residual units).
    Cauchy(f64),
}

impl Loss {
    fn rho(&self, s: f64) -> f64 {
        match *self {
            Loss::Trivial => s,
            Loss::Cauchy(c) => c * c * (s / (c * c)).ln_1p(),
        }
    }
    fn weight(&self, s: f64) -> f64 {
        match *self {
            Loss::Trivial => 1.0,
            Loss::Cauchy(c) => 1.0 / (1.0 + s / (c * c)),
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

fn robust_cost(loss: Loss, r: &[f64]) -> f64 {
    r.iter().map(|x| loss.rho(x * x)).sum()
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
    let mut r = vec![0.0; n];
    let mut rp = vec![0.0; n];
    let mut rm = vec![0.0; n];
    let mut jac = vec![SVector::<f64, N>::zeros(); n];
    problem.residuals(&state, &mut r);
    let mut cost = robust_cost(loss, &r);
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
        if need_jacobian {
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
            hess.fill(0.0);
            grad.fill(0.0);
            for i in 0..n {
                let w = loss.weight(r[i] * r[i]);
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
        let new_cost = robust_cost(loss, &rp);
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

/// A relative pose on `SO(3) x S²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Rotation `R` (camera 1 to camera 2).
    pub rotation: UnitQuaternion<f64>,
    /// Unit translation `t`.
    pub translation: Vector3<f64>,
}

impl Pose {
    /// From a rotation matrix (re-orthonormalised) and a translation (normalised).
    pub fn new(r: &Matrix3<f64>, t: &Vector3<f64>) -> Self {
        // Closed-form conversion of the orthonormalised matrix (nalgebra's iterative
        // `from_matrix` can fail to terminate on non-finite input).
        let r = crate::geometry::orthonormalize(r);
        Pose {
            rotation: UnitQuaternion::from_rotation_matrix(
                &nalgebra::Rotation3::from_matrix_unchecked(r),
            ),
            translation: t.normalize(),
        }
    }

    /// Rotation matrix.
    pub fn matrix(&self) -> Matrix3<f64> {
        *self.rotation.to_rotation_matrix().matrix()
    }

    /// Retraction by `δ = (δθ, δt)`: `R exp([δθ]×)`, `normalise(t + δt1 b1 + δt2 b2)`.
    pub fn retract(&self, d: &[f64]) -> Pose {
        let (b1, b2) = tangent_basis(&self.translation);
        Pose {
            rotation: self.rotation
                * UnitQuaternion::from_scaled_axis(Vector3::new(d[0], d[1], d[2])),
            translation: (self.translation + b1 * d[3] + b2 * d[4]).normalize(),
        }
    }
}

/// Pose refinement over a subset of points.
pub struct PoseProblem<'a> {
    /// The points.
    pub data: &'a PointData,
    /// Indices of the points used (inliers).
    pub indices: &'a [usize],
    /// Two-view model.
    pub model: PoseModel,
    /// Residual kind.
    pub kind: ResidualKind,
    /// Loss.
    pub loss: Loss,
}

impl LmProblem<5> for PoseProblem<'_> {
    type State = Pose;
    fn num_residuals(&self) -> usize {
        self.indices.len()
    }
    fn residuals(&self, s: &Pose, out: &mut [f64]) {
        let r = s.matrix();
        let t = s.translation;
        let e = skew(&t) * r;
        for (o, &i) in out.iter_mut().zip(self.indices) {
            *o = self.data.residual(self.model, self.kind, i, &r, &t, &e);
        }
    }
    fn retract(&self, s: &Pose, d: &SVector<f64, 5>) -> Pose {
        s.retract(d.as_slice())
    }
    fn loss(&self) -> Loss {
        self.loss
    }
}

/// Refine `(R, t)` on the points `indices` under `model`/`kind` (see the module
/// documentation). Returns the refined pose (never worse in cost than the input).
pub fn refine_pose(
    data: &PointData,
    indices: &[usize],
    model: PoseModel,
    kind: ResidualKind,
    loss: Loss,
    start: Pose,
    options: &LmOptions,
) -> LmResult<Pose> {
    let p = PoseProblem {
        data,
        indices,
        model,
        kind,
        loss,
    };
    levenberg_marquardt(&p, start, options)
}

/// State of the NRSRP (Dai et al.) model, in the row-0 frame of camera 1 (world frame
/// `R1 = I, C1 = 0`): relative pose `(R, t)`, and per camera the rotation and displacement
/// accumulated over one full frame, `phi_c = H λ ω_c` (rad, camera frame) and
/// `delta_c = H λ d_c` (units of the baseline |t| = 1, camera-1 frame), with `H` the image
/// height in rows. Scaling by the frame duration keeps the 17 unknowns commensurate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NrsrpState {
    /// Relative pose.
    pub pose: Pose,
    /// Per-frame rotation of camera 1 and 2 (`H λ ω`).
    pub phi: [Vector3<f64>; 2],
    /// Per-frame displacement of camera 1 and 2 (`H λ d`).
    pub delta: [Vector3<f64>; 2],
}

/// The NRSRP problem: generalized epipolar residual per point
/// `r = (c2(v2) - c1(v1)) · (f1 × f2)` with unit ray directions in camera-1 row-0 frame
/// `f1 = normalise(exp([s1 phi1]×)^T m1)`, `f2 = normalise(R^T exp([s2 phi2]×)^T m2)`,
/// centres `c1 = s1 delta1`, `c2 = -R^T t + s2 delta2`, `s = v / H` (fraction of the frame).
/// This is the coplanarity of the two rays (zero iff they intersect).
pub struct NrsrpProblem<'a> {
    /// Bearings and rows.
    pub data: &'a PointData,
    /// Image height `H` in rows.
    pub height: f64,
    /// Cauchy scale.
    pub cauchy_scale: f64,
}

impl LmProblem<17> for NrsrpProblem<'_> {
    type State = NrsrpState;
    fn num_residuals(&self) -> usize {
        self.data.len()
    }
    fn residuals(&self, s: &NrsrpState, out: &mut [f64]) {
        let r = s.pose.matrix();
        let c2_0 = -(r.transpose() * s.pose.translation);
        for (i, o) in out.iter_mut().enumerate() {
            let s1 = self.data.v1[i] / self.height;
            let s2 = self.data.v2[i] / self.height;
            let f1 = crate::geometry::exp_so3(&(s.phi[0] * s1)).tr_mul(&self.data.m1[i]);
            let f2 = r.tr_mul(&crate::geometry::exp_so3(&(s.phi[1] * s2)).tr_mul(&self.data.m2[i]));
            let c1 = s.delta[0] * s1;
            let c2 = c2_0 + s.delta[1] * s2;
            *o = (c2 - c1).dot(&f1.normalize().cross(&f2.normalize()));
        }
    }
    fn retract(&self, s: &NrsrpState, d: &SVector<f64, 17>) -> NrsrpState {
        let v = |k: usize| Vector3::new(d[k], d[k + 1], d[k + 2]);
        NrsrpState {
            pose: s.pose.retract(&d.as_slice()[0..5]),
            phi: [s.phi[0] + v(5), s.phi[1] + v(8)],
            delta: [s.delta[0] + v(11), s.delta[1] + v(14)],
        }
    }
    fn loss(&self) -> Loss {
        Loss::Cauchy(self.cauchy_scale)
    }
}

/// Refine the NRSRP model on all points with the Cauchy loss (see [`NrsrpProblem`]).
pub fn refine_nrsrp(
    data: &PointData,
    height: f64,
    cauchy_scale: f64,
    start: NrsrpState,
    options: &LmOptions,
) -> LmResult<NrsrpState> {
    let p = NrsrpProblem {
        data,
        height,
        cauchy_scale,
    };
    levenberg_marquardt(&p, start, options)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{exp_so3, rotation_error_deg, translation_error_deg};
    use crate::simulate::{simulate, SimulationOptions};

    fn perturbed(gt_r: &Matrix3<f64>, gt_t: &Vector3<f64>) -> Pose {
        Pose::new(
            &(gt_r * exp_so3(&Vector3::new(0.02, -0.015, 0.01))),
            &(gt_t + Vector3::new(0.05, -0.04, 0.03)),
        )
    }

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

    #[test]
    fn exact_angular_sampson_refinement_recovers_ground_truth() {
        let pair = simulate(&SimulationOptions {
            pixel_noise: 0.0,
            gyro_noise: 0.0,
            seed: 5,
            ..Default::default()
        })
        .unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        let (v1, v2) = pair.views();
        let d = PointData::new(&v1, &v2, &pair.matches);
        let idx: Vec<usize> = (0..d.len()).collect();
        let (gr, gtt) = (gt.rotation_matrix(), gt.translation_vector());
        let res = refine_pose(
            &d,
            &idx,
            PoseModel::ExactAngular,
            ResidualKind::Sampson,
            Loss::Trivial,
            perturbed(&gr, &gtt),
            &LmOptions::default(),
        );
        assert!(rotation_error_deg(&gr, &res.state.matrix()) < 1e-6);
        assert!(translation_error_deg(&gtt, &res.state.translation) < 1e-5);
    }

    #[test]
    fn paper_algebraic_refinement_is_close_under_noise() {
        let pair = simulate(&SimulationOptions {
            seed: 6,
            ..Default::default()
        })
        .unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        let (v1, v2) = pair.views();
        let d = PointData::new(&v1, &v2, &pair.matches);
        let idx: Vec<usize> = (0..d.len()).collect();
        let (gr, gtt) = (gt.rotation_matrix(), gt.translation_vector());
        let start = perturbed(&gr, &gtt);
        let res = refine_pose(
            &d,
            &idx,
            PoseModel::PaperLinear,
            ResidualKind::Algebraic,
            Loss::Trivial,
            start,
            &LmOptions::default(),
        );
        assert!(res.cost < res.initial_cost);
        assert!(rotation_error_deg(&gr, &res.state.matrix()) < 1.0);
        assert!(translation_error_deg(&gtt, &res.state.translation) < 5.0);
    }

    #[test]
    fn nrsrp_refinement_reduces_cost_and_error() {
        let pair = simulate(&SimulationOptions {
            seed: 9,
            angular_velocity: 2.0,
            linear_velocity: 4.0,
            pixel_noise: 0.5,
            ..Default::default()
        })
        .unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        let cam = pair.camera;
        // NRSRP uses no gyro: bearings only.
        let still = crate::camera::View::new(cam, Vector3::zeros());
        let d = PointData::new(&still, &still, &pair.matches);
        let (gr, gtt) = (gt.rotation_matrix(), gt.translation_vector());
        let start_pose = perturbed(&gr, &gtt);
        let start = NrsrpState {
            pose: start_pose,
            phi: [Vector3::zeros(); 2],
            delta: [Vector3::zeros(); 2],
        };
        let res = refine_nrsrp(
            &d,
            cam.height,
            2.0 / cam.fx,
            start,
            &LmOptions {
                max_iterations: 100,
                ..Default::default()
            },
        );
        assert!(res.cost < 0.5 * res.initial_cost);
        let r0 = rotation_error_deg(&gr, &start_pose.matrix());
        let r1 = rotation_error_deg(&gr, &res.state.pose.matrix());
        assert!(r1 < r0, "{r1} vs {r0}");
        // The recovered per-frame rotation of camera 1 approximates the truth.
        let phi_true = Vector3::from(gt.omega[0]) * cam.height * cam.readout;
        assert!(
            (res.state.phi[0] - phi_true).norm() < 0.5 * phi_true.norm(),
            "{:?} {:?}",
            res.state.phi[0],
            phi_true
        );
    }
}
