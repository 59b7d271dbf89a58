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
//!   paper's `grsrp+` cost `m2^T [t]× (I + v2 [w2]×) R (I - v1 [w1]×) m1` (`w = −λω`) over inliers;
//! - [`refine_pose`] with [`PoseModel::ExactAngular`] + [`ResidualKind::Sampson`]: Sampson
//!   error of the exact angular model (`rectified`), or the global-shutter model (`gsrp`);
//! - [`refine_nrsrp`]: Dai et al.'s generalized epipolar constraint for the uniform RS model,
//!   unknowns `R, t, ω1, d1, ω2, d2`, Cauchy loss over all points;
//! - [`crate::velocity`]: the same constraint with the gyro's row rotations, unknowns
//!   `R, t, d1, d2` (`rectified+v`).

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
    /// Analytic Jacobian. Every model is `r = c2^T [t]× M c1` with `M = A2 R`:
    /// global shutter `c = m`, `A2 = I`; exact angular `c = Ω^T m`, `A2 = I`; the paper's
    /// model `c1 = (I - v1[w1]×) m1`, `c2 = m2`, `A2 = I + v2 [w2]×`. With `y = M c1`,
    /// `u = t × y` and `w = M^T (c2 × t)`: `r = c2 · u = c1 · w`,
    /// `∂r/∂θ = c1 × w`, `∂r/∂t_k = b_k · (y × c2)`. Sampson: the image gradients are
    /// `g2 = P2 u`, `g1 = P1 w` (`P = Ω` for the exact model, `P1 = I + v1[w1]×` for the
    /// paper's, else `I`; x and y components), with `∂u/∂θ_j = t × M (e_j × c1)`,
    /// `∂u/∂t_k = b_k × y`, `∂w/∂θ_j = w × e_j`, `∂w/∂t_k = M^T (c2 × b_k)`, and
    /// `∂(r/|g|) = ∂r/|g| - r ∂|g|² / (2|g|³)`.
    fn residuals_and_jacobian(
        &self,
        s: &Pose,
        out: &mut [f64],
        jac: &mut [SVector<f64, 5>],
    ) -> bool {
        let d = self.data;
        let rot = s.matrix();
        let t = s.translation;
        let (tb1, tb2) = tangent_basis(&t);
        let w2r = skew(&d.w2) * rot;
        for ((o, j), &i) in out.iter_mut().zip(jac.iter_mut()).zip(self.indices) {
            let (c1, c2, m) = match self.model {
                PoseModel::GlobalShutter => (d.m1[i], d.m2[i], rot),
                PoseModel::ExactAngular => (d.b1[i], d.b2[i], rot),
                PoseModel::PaperLinear => (d.l1[i], d.m2[i], rot + w2r * d.v2[i]),
            };
            let y = m * c1;
            let u = t.cross(&y);
            let w = m.tr_mul(&c2.cross(&t));
            let res = c2.dot(&u);
            let jth = c1.cross(&w);
            let yc = y.cross(&c2);
            let jr = [jth.x, jth.y, jth.z, tb1.dot(&yc), tb2.dot(&yc)];
            if self.kind == ResidualKind::Algebraic {
                *o = res;
                *j = SVector::<f64, 5>::from(jr);
                continue;
            }
            // Sampson.
            let ex = [
                Vector3::new(0.0, -c1.z, c1.y),
                Vector3::new(c1.z, 0.0, -c1.x),
                Vector3::new(-c1.y, c1.x, 0.0),
            ];
            let du = [
                t.cross(&(m * ex[0])),
                t.cross(&(m * ex[1])),
                t.cross(&(m * ex[2])),
                tb1.cross(&y),
                tb2.cross(&y),
            ];
            let dw = [
                Vector3::new(0.0, w.z, -w.y),
                Vector3::new(-w.z, 0.0, w.x),
                Vector3::new(w.y, -w.x, 0.0),
                m.tr_mul(&c2.cross(&tb1)),
                m.tr_mul(&c2.cross(&tb2)),
            ];
            let model = self.model;
            let (om1, om2) = (&d.omega1[i], &d.omega2[i]);
            let a1 = d.w1 * d.v1[i];
            let p1 = |x: &Vector3<f64>| match model {
                PoseModel::GlobalShutter => *x,
                PoseModel::ExactAngular => om1 * x,
                PoseModel::PaperLinear => x + a1.cross(x),
            };
            let p2 = |x: &Vector3<f64>| {
                if model == PoseModel::ExactAngular {
                    om2 * x
                } else {
                    *x
                }
            };
            let g1 = p1(&w);
            let g2 = p2(&u);
            let ss = g1.x * g1.x + g1.y * g1.y + g2.x * g2.x + g2.y * g2.y;
            let sn = ss.sqrt();
            let wt = d.weight(model, i);
            *o = if ss > 0.0 {
                wt * res / sn
            } else {
                f64::INFINITY
            };
            let k = res / (ss * sn);
            for q in 0..5 {
                let a = p1(&dw[q]);
                let b = p2(&du[q]);
                let dss = g1.x * a.x + g1.y * a.y + g2.x * b.x + g2.y * b.y; // half of ∂|g|²
                j[q] = wt * (jr[q] / sn - k * dss);
            }
        }
        true
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
/// accumulated over one full frame, `phi_c = −H λ ω_c` (rad, camera frame; `ω_c` the
/// physical angular velocity, so `exp([s phi]×)` is the row rotation at fraction `s`) and
/// `delta_c = H λ d_c` (units of the baseline |t| = 1, camera-1 frame), with `H` the image
/// height in rows. Scaling by the frame duration keeps the 17 unknowns commensurate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NrsrpState {
    /// Relative pose.
    pub pose: Pose,
    /// Per-frame rotation of camera 1 and 2 (`−H λ ω`).
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
            let f1 = SmallRotation::new(&(s.phi[0] * s1)).apply_transpose(&self.data.m1[i]);
            let h2 = SmallRotation::new(&(s.phi[1] * s2)).apply_transpose(&self.data.m2[i]);
            let f2 = r.tr_mul(&h2.normalize());
            let c1 = s.delta[0] * s1;
            let c2 = c2_0 + s.delta[1] * s2;
            *o = (c2 - c1).dot(&f1.normalize().cross(&f2));
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
    /// Analytic Jacobian. With unit rays `F1 = exp(s1 φ1)^T m1 / |m1|`,
    /// `H2 = exp(s2 φ2)^T m2 / |m2|`, `F2 = R^T H2`, `D = c2 - c1`, `N = F1 × F2`,
    /// `r = D · N`: `∂r/∂θ = (R^T t) × N - F2 × (D × F1)`, `∂r/∂t_k = -(R^T b_k) · N`,
    /// `∂r/∂φ1 = s1 J_r(s1 φ1)^T ((F2 × D) × F1)`,
    /// `∂r/∂φ2 = s2 J_r(s2 φ2)^T ((R (D × F1)) × H2)`, `∂r/∂δ1 = -s1 N`, `∂r/∂δ2 = s2 N`
    /// (`J_r` the right Jacobian of SO(3)).
    fn residuals_and_jacobian(
        &self,
        s: &NrsrpState,
        out: &mut [f64],
        jac: &mut [SVector<f64, 17>],
    ) -> bool {
        let r = s.pose.matrix();
        let t = s.pose.translation;
        let (tb1, tb2) = tangent_basis(&t);
        let rt = r.tr_mul(&t);
        let rb1 = r.tr_mul(&tb1);
        let rb2 = r.tr_mul(&tb2);
        let d = self.data;
        for (i, (o, j)) in out.iter_mut().zip(jac.iter_mut()).enumerate() {
            let s1 = d.v1[i] / self.height;
            let s2 = d.v2[i] / self.height;
            let q1 = SmallRotation::new(&(s.phi[0] * s1));
            let q2 = SmallRotation::new(&(s.phi[1] * s2));
            let f1 = q1.apply_transpose(&d.m1[i]).normalize();
            let h2 = q2.apply_transpose(&d.m2[i]).normalize();
            let f2 = r.tr_mul(&h2);
            let dd = -rt + s.delta[1] * s2 - s.delta[0] * s1;
            let n = f1.cross(&f2);
            *o = dd.dot(&n);
            let jth = rt.cross(&n) - f2.cross(&dd.cross(&f1));
            let jp1 = q1.right_jacobian_transpose(&f2.cross(&dd).cross(&f1)) * s1;
            let jp2 = q2.right_jacobian_transpose(&(r * dd.cross(&f1)).cross(&h2)) * s2;
            let jd1 = n * -s1;
            let jd2 = n * s2;
            j[0] = jth.x;
            j[1] = jth.y;
            j[2] = jth.z;
            j[3] = -rb1.dot(&n);
            j[4] = -rb2.dot(&n);
            for k in 0..3 {
                j[5 + k] = jp1[k];
                j[8 + k] = jp2[k];
                j[11 + k] = jd1[k];
                j[14 + k] = jd2[k];
            }
        }
        true
    }
}

/// `exp([φ]×)` kept as its Rodrigues coefficients, applied to vectors without forming the
/// matrix: `exp([φ]×) v = v + a φ × v + b φ × (φ × v)` with `a = sin θ / θ`,
/// `b = (1 - cos θ) / θ²`; the right Jacobian
/// `J_r = I - b [φ]× + c [φ]×²`, `c = (θ - sin θ) / θ³` (`exp(φ + δ) ≈ exp(φ) exp(J_r δ)`).
struct SmallRotation {
    phi: Vector3<f64>,
    a: f64,
    b: f64,
    c: f64,
}

impl SmallRotation {
    fn new(phi: &Vector3<f64>) -> Self {
        let th2 = phi.norm_squared();
        let (a, b, c) = if th2 < 1e-8 {
            (1.0 - th2 / 6.0, 0.5 - th2 / 24.0, 1.0 / 6.0 - th2 / 120.0)
        } else {
            let th = th2.sqrt();
            let (sn, cs) = th.sin_cos();
            (sn / th, (1.0 - cs) / th2, (th - sn) / (th2 * th))
        };
        SmallRotation { phi: *phi, a, b, c }
    }

    /// `exp([φ]×)^T v = exp([-φ]×) v`.
    fn apply_transpose(&self, v: &Vector3<f64>) -> Vector3<f64> {
        let pv = self.phi.cross(v);
        v - pv * self.a + self.phi.cross(&pv) * self.b
    }

    /// `J_r(φ)^T x = x + b φ × x + c φ × (φ × x)`.
    fn right_jacobian_transpose(&self, x: &Vector3<f64>) -> Vector3<f64> {
        let px = self.phi.cross(x);
        x + px * self.b + self.phi.cross(&px) * self.c
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
pub(crate) mod tests {
    use super::*;
    use crate::geometry::{exp_so3, rotation_error_deg, translation_error_deg};
    use crate::simulate::{simulate, SimulationOptions};

    fn perturbed(gt_r: &Matrix3<f64>, gt_t: &Vector3<f64>) -> Pose {
        Pose::new(
            &(gt_r * exp_so3(&Vector3::new(0.02, -0.015, 0.01))),
            &(gt_t + Vector3::new(0.05, -0.04, 0.03)),
        )
    }

    /// Analytic Jacobian of `p` at `state` against central finite differences.
    pub(crate) fn check_jacobian<const N: usize, P: LmProblem<N>>(
        p: &P,
        state: &P::State,
        tol: f64,
    ) {
        let n = p.num_residuals();
        let mut r = vec![0.0; n];
        let mut r0 = vec![0.0; n];
        let mut jac = vec![SVector::<f64, N>::zeros(); n];
        assert!(p.residuals_and_jacobian(state, &mut r, &mut jac));
        p.residuals(state, &mut r0);
        let (mut rp, mut rm) = (vec![0.0; n], vec![0.0; n]);
        let h = 1e-6;
        for k in 0..N {
            let mut d = SVector::<f64, N>::zeros();
            d[k] = h;
            p.residuals(&p.retract(state, &d), &mut rp);
            d[k] = -h;
            p.residuals(&p.retract(state, &d), &mut rm);
            for i in 0..n {
                let fd = (rp[i] - rm[i]) / (2.0 * h);
                let scale = jac[i].norm().max(1e-3);
                assert!(
                    (fd - jac[i][k]).abs() <= tol * scale,
                    "residual {i} param {k}: analytic {} fd {fd}",
                    jac[i][k]
                );
            }
        }
        for i in 0..n {
            assert!((r[i] - r0[i]).abs() <= 1e-12 * (1.0 + r0[i].abs()));
        }
    }

    #[test]
    fn analytic_jacobians_match_finite_differences() {
        let pair = simulate(&SimulationOptions {
            seed: 21,
            points: 40,
            angular_velocity: 2.0,
            ..Default::default()
        })
        .unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        let (v1, v2) = pair.views().unwrap();
        let d = PointData::new(&v1, &v2, &pair.matches);
        let idx: Vec<usize> = (0..d.len()).collect();
        let start = perturbed(&gt.rotation_matrix(), &gt.translation_vector());
        for model in [
            PoseModel::GlobalShutter,
            PoseModel::ExactAngular,
            PoseModel::PaperLinear,
        ] {
            for kind in [ResidualKind::Algebraic, ResidualKind::Sampson] {
                let p = PoseProblem {
                    data: &d,
                    indices: &idx,
                    model,
                    kind,
                    loss: Loss::Trivial,
                };
                check_jacobian(&p, &start, 1e-5);
            }
        }
        let p = NrsrpProblem {
            data: &d,
            height: v1.camera.height,
            cauchy_scale: 0.01,
        };
        let state = NrsrpState {
            pose: start,
            phi: [
                Vector3::new(0.1, -0.05, 0.08),
                Vector3::new(-0.07, 0.02, 0.1),
            ],
            delta: [
                Vector3::new(0.01, 0.02, -0.03),
                Vector3::new(-0.02, 0.0, 0.04),
            ],
        };
        check_jacobian(&p, &state, 1e-5);
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
        let (v1, v2) = pair.views().unwrap();
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
        let (v1, v2) = pair.views().unwrap();
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
        let phi_true = -Vector3::from(gt.omega[0]) * cam.height * cam.readout;
        assert!(
            (res.state.phi[0] - phi_true).norm() < 0.5 * phi_true.norm(),
            "{:?} {:?}",
            res.state.phi[0],
            phi_true
        );
    }
}
