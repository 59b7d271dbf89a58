//! The generalised epipolar (ray coplanarity) model of Dai, Li and Kneip (CVPR 2016) with
//! the row rotations known from the gyro: unknowns the relative pose `(R, t)` and each
//! camera's constant linear velocity (`rectified+v`).
//!
//! World frame: camera 1's row-0 frame (`R1 = I`, `C1 = 0`), so `R2 = R` and
//! `C2 = −R^T t` (`|t| = 1`: lengths in baselines). Camera `c` at row `v` has world-to-camera
//! rotation `Ω_c(v) R_c` ([`crate::model::camera::View::row_rotation`], from a constant gyro rate
//! or integrated gyro samples) and centre `C_c + v λ_c d_c` (`d_c` world frame). The match
//! `(m1 at row v1, m2 at row v2)` is two rays in the world frame,
//!
//! - origin `o1 = τ1 δ1`, direction `f1 = Ω1(v1)^T m1 = b1`,
//! - origin `o2 = −R^T t + τ2 δ2`, direction `f2 = R^T Ω2(v2)^T m2 = R^T b2`,
//!
//! with `τ_c = v_c λ_c / T` the row's time as a fraction of a reference duration `T` (the
//! longer frame readout, [`reference_duration`]) and `δ_c = T d_c` the displacement over
//! `T`, in baselines: the unknowns stay commensurate with the unit translation. The rays
//! meet iff
//!
//! `r = D · (f1 × f2) = 0`, `D = o2 − o1`.
//!
//! At `δ = 0`, `r = −b2^T [t]× R b1`: the exact angular model (`rectified`), which this model
//! nests. The Sampson-like residual divides `r` by the norm of its gradient with respect to
//! the normalised image points `(x1, y1, x2, y2)` with rows and row rotations held fixed,
//! `∂r/∂m1 = Ω1 (f2 × D)`, `∂r/∂m2 = Ω2 R (D × f1)` (first-order geometric error, normalised
//! image units), times the point's row-noise weight of the exact angular model
//! ([`PointData::weight`]).
//!
//! A prior `δ_c ~ N(0, σ_δ² I)` enters as six residuals `k δ` (`k = σ_r / σ_δ`, `σ_r` the
//! residuals' noise), exempt from the robust loss: it fixes the directions of `(δ1, δ2)` the
//! data do not determine (few points, a narrow field of view, rows read at the same time in
//! both images).

use crate::estimation::refine::{levenberg_marquardt, LmOptions, LmProblem, LmResult, Loss, Pose};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, PoseModel, ResidualKind};
use crate::model::geometry::tangent_basis;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

/// Tangent dimensions: rotation 3, unit translation 2, two displacements 6.
pub const DIM: usize = 11;

/// The reference duration `T` of the displacements: the longer of the two frames' readouts
/// (`lines × readout`), seconds; 0 for two global-shutter cameras (no velocity is
/// observable then).
pub fn reference_duration(view1: &View, view2: &View) -> f64 {
    let d = |v: &View| v.camera.frame_readout();
    d(view1).max(d(view2))
}

/// State of the model: the relative pose and each camera's displacement over the reference
/// duration, `δ_c = T d_c` (baselines, camera 1's row-0 frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityState {
    /// Relative pose `(R, t)`, `|t| = 1`.
    pub pose: Pose,
    /// `δ1`, `δ2`.
    pub delta: [Vector3<f64>; 2],
}

impl VelocityState {
    /// A pose with zero velocities.
    pub fn still(pose: Pose) -> Self {
        VelocityState {
            pose,
            delta: [Vector3::zeros(); 2],
        }
    }
}

/// The model evaluated for one state: the pose-dependent quantities shared by every point.
#[derive(Debug, Clone, Copy)]
pub struct VelocityModel {
    r: Matrix3<f64>,
    /// `R^T t`.
    p: Vector3<f64>,
    delta: [Vector3<f64>; 2],
    /// `λ_c / T`: `τ_c = v_c · row_time[c]`.
    row_time: [f64; 2],
}

/// One point's rays and residual: `(r, D, f1, f2, n = f1 × f2)`.
struct Rays {
    res: f64,
    d: Vector3<f64>,
    f1: Vector3<f64>,
    f2: Vector3<f64>,
    n: Vector3<f64>,
}

impl VelocityModel {
    /// The model of `state` for views whose rows take `λ_c / T` of the reference duration
    /// each (`row_time`; zero for a global-shutter view).
    pub fn new(state: &VelocityState, row_time: [f64; 2]) -> Self {
        let r = state.pose.matrix();
        VelocityModel {
            r,
            p: r.tr_mul(&state.pose.translation),
            delta: state.delta,
            row_time,
        }
    }

    fn tau(&self, data: &PointData, i: usize) -> (f64, f64) {
        (data.v1[i] * self.row_time[0], data.v2[i] * self.row_time[1])
    }

    fn rays(&self, data: &PointData, i: usize) -> Rays {
        self.rays_of(data, i, &data.b1[i], &data.b2[i])
    }

    /// The rays of point `i` with its row-0 bearings `b1`, `b2` replaced.
    fn rays_of(&self, data: &PointData, i: usize, b1: &Vector3<f64>, b2: &Vector3<f64>) -> Rays {
        let (t1, t2) = self.tau(data, i);
        let f1 = *b1;
        let f2 = self.r.tr_mul(b2);
        let d = -self.p + self.delta[1] * t2 - self.delta[0] * t1;
        let n = f1.cross(&f2);
        Rays {
            res: d.dot(&n),
            d,
            f1,
            f2,
            n,
        }
    }

    /// The image gradients `(∂r/∂m1, ∂r/∂m2)` of point `i`.
    fn gradients(&self, data: &PointData, i: usize, k: &Rays) -> (Vector3<f64>, Vector3<f64>) {
        (
            data.omega1[i] * k.f2.cross(&k.d),
            data.omega2[i] * (self.r * k.d.cross(&k.f1)),
        )
    }

    /// Residual of point `i`: algebraic `r`, or Sampson `w r / |∇r|` (see the module
    /// documentation); non-finite for a degenerate point.
    pub fn residual(&self, data: &PointData, kind: ResidualKind, i: usize) -> f64 {
        self.residual_of(data, kind, i, self.rays(data, i))
    }

    fn residual_of(&self, data: &PointData, kind: ResidualKind, i: usize, k: Rays) -> f64 {
        if kind == ResidualKind::Algebraic {
            return k.res;
        }
        let (g1, g2) = self.gradients(data, i, &k);
        let ss = g1.x * g1.x + g1.y * g1.y + g2.x * g2.x + g2.y * g2.y;
        if ss > 0.0 {
            data.weight(PoseModel::ExactAngular, i) * k.res / ss.sqrt()
        } else {
            f64::INFINITY
        }
    }

    /// Cheirality of the model over the points `indices`: the numbers of points whose two
    /// rays, from the moving centres `o1`, `o2` (see the module documentation), meet in front
    /// of both cameras, and behind both. The model is homogeneous in `(t, δ1, δ2)`: negating
    /// all three negates `D = o2 − o1` and with it both depths, so the second count is the
    /// first count of the mirrored state. The rigid test on the row-0 centres alone is not
    /// equivalent: when the cameras move a sizeable fraction of the baseline during the
    /// readout it can prefer the mirrored state.
    pub fn cheirality_counts(&self, data: &PointData, indices: &[usize]) -> (usize, usize) {
        let (mut front, mut behind) = (0, 0);
        for &i in indices {
            let k = self.rays(data, i);
            match crate::model::geometry::ray_depths(&k.f1, &k.f2, &k.d) {
                Some((a, b)) if a > 0.0 && b > 0.0 => front += 1,
                Some((a, b)) if a < 0.0 && b < 0.0 => behind += 1,
                _ => {}
            }
        }
        (front, behind)
    }

    /// `Σ_i min(r_i², τ²)` over every point (Sampson residuals; non-finite ones count `τ²`).
    pub fn truncated_cost(&self, data: &PointData, threshold_sq: f64) -> f64 {
        truncated(data.len(), threshold_sq, |i| {
            self.residual(data, ResidualKind::Sampson, i)
        })
    }
}

/// `Σ_i min(r_i², τ²)` over `n` residuals (non-finite ones count `τ²`).
fn truncated(n: usize, threshold_sq: f64, residual: impl Fn(usize) -> f64) -> f64 {
    (0..n)
        .map(|i| {
            let x = residual(i);
            let x = x * x;
            if x < threshold_sq {
                x
            } else {
                threshold_sq
            }
        })
        .sum()
}

/// The residuals of both problems: `residual(i)` for each point, then the prior's `k x`
/// for the two 3-vectors `pair`.
fn write_residuals(
    indices: &[usize],
    prior: f64,
    pair: &[Vector3<f64>; 2],
    out: &mut [f64],
    residual: impl Fn(usize) -> f64,
) {
    let (points, priors) = out.split_at_mut(indices.len());
    for (o, &i) in points.iter_mut().zip(indices) {
        *o = residual(i);
    }
    for (k, o) in priors.iter_mut().enumerate() {
        *o = prior * pair[k / 3][k % 3];
    }
}

/// The two 3-vectors of a state moved by tangent components 5..11.
fn retract_pair(pair: &[Vector3<f64>; 2], d: &SVector<f64, DIM>) -> [Vector3<f64>; 2] {
    let v = |k: usize| Vector3::new(d[k], d[k + 1], d[k + 2]);
    [pair[0] + v(5), pair[1] + v(8)]
}

/// Refinement of `(R, t, δ1, δ2)` over a set of points (the Sampson residuals of the module
/// documentation) with a robust loss, plus the velocity prior.
pub struct VelocityProblem<'a> {
    /// The points, with the views' row rotations.
    pub data: &'a PointData,
    /// Indices of the points used.
    pub indices: &'a [usize],
    /// `λ_c / T` of each view.
    pub row_time: [f64; 2],
    /// Loss of the point residuals.
    pub loss: Loss,
    /// Weight `k` of the prior residuals `k δ` (0: no prior).
    pub prior: f64,
}

impl LmProblem<DIM> for VelocityProblem<'_> {
    type State = VelocityState;
    fn num_residuals(&self) -> usize {
        self.indices.len() + 6
    }
    fn robust_residuals(&self) -> usize {
        self.indices.len()
    }
    fn residuals(&self, s: &VelocityState, out: &mut [f64]) {
        let model = VelocityModel::new(s, self.row_time);
        write_residuals(self.indices, self.prior, &s.delta, out, |i| {
            model.residual(self.data, ResidualKind::Sampson, i)
        });
    }
    fn retract(&self, s: &VelocityState, d: &SVector<f64, DIM>) -> VelocityState {
        VelocityState {
            pose: s.pose.retract(&d.as_slice()[0..5]),
            delta: retract_pair(&s.delta, d),
        }
    }
    fn loss(&self) -> Loss {
        self.loss
    }
    /// Analytic Jacobian. A tangent step moves `D`, `f2` and `R` by `dD`, `df2`, `dR`:
    /// rotation `θ_j` (`R ← R exp([θ]×)`): `dD = e_j × R^T t`, `df2 = f2 × e_j`,
    /// `dR a = R (e_j × a)`; translation `b_k`: `dD = −R^T b_k`; `δ1_j`: `dD = −τ1 e_j`;
    /// `δ2_j`: `dD = τ2 e_j`. Then `dr = dD · n + (D × f1) · df2`,
    /// `dg1 = Ω1 (df2 × D + f2 × dD)`, `dg2 = Ω2 (dR (D × f1) + R (dD × f1))`, and
    /// `∂(r/|g|) = dr/|g| − r (g · dg) / |g|³`.
    fn residuals_and_jacobian(
        &self,
        s: &VelocityState,
        out: &mut [f64],
        jac: &mut [SVector<f64, DIM>],
    ) -> bool {
        let model = VelocityModel::new(s, self.row_time);
        let d = self.data;
        let (tb1, tb2) = tangent_basis(&s.pose.translation);
        let dt = [-model.r.tr_mul(&tb1), -model.r.tr_mul(&tb2)];
        let e = [Vector3::x(), Vector3::y(), Vector3::z()];
        let n_pts = self.indices.len();
        for ((o, j), &i) in out.iter_mut().zip(jac.iter_mut()).zip(self.indices) {
            let k = model.rays(d, i);
            let (t1, t2) = model.tau(d, i);
            let (g1, g2) = model.gradients(d, i, &k);
            let dxf = k.d.cross(&k.f1);
            // (dD, df2, rotation axis) of each tangent direction.
            let step = |q: usize| -> (Vector3<f64>, Vector3<f64>, Option<Vector3<f64>>) {
                match q {
                    0..=2 => (e[q].cross(&model.p), k.f2.cross(&e[q]), Some(e[q])),
                    3 | 4 => (dt[q - 3], Vector3::zeros(), None),
                    5..=7 => (e[q - 5] * -t1, Vector3::zeros(), None),
                    _ => (e[q - 8] * t2, Vector3::zeros(), None),
                }
            };
            let ss = g1.x * g1.x + g1.y * g1.y + g2.x * g2.x + g2.y * g2.y;
            let sn = ss.sqrt();
            let wt = d.weight(PoseModel::ExactAngular, i);
            *o = if ss > 0.0 {
                wt * k.res / sn
            } else {
                f64::INFINITY
            };
            for q in 0..DIM {
                let (dd, df2, axis) = step(q);
                let dr = dd.dot(&k.n) + dxf.dot(&df2);
                let dg1 = d.omega1[i] * (df2.cross(&k.d) + k.f2.cross(&dd));
                let mut inner = dd.cross(&k.f1);
                if let Some(a) = axis {
                    inner += a.cross(&dxf);
                }
                let dg2 = d.omega2[i] * (model.r * inner);
                let dss = g1.x * dg1.x + g1.y * dg1.y + g2.x * dg2.x + g2.y * dg2.y;
                j[q] = wt * (dr / sn - k.res * dss / (ss * sn));
            }
        }
        for (k, j) in jac[n_pts..].iter_mut().enumerate() {
            *j = SVector::zeros();
            j[5 + k] = self.prior;
        }
        write_residuals(&[], self.prior, &s.delta, &mut out[n_pts..], |_| 0.0);
        true
    }
}

/// Refine `(R, t, δ1, δ2)` on the points `indices` from `start` (see [`VelocityProblem`]);
/// never worse in cost than the start.
pub fn refine_velocity(
    problem: &VelocityProblem<'_>,
    start: VelocityState,
    options: &LmOptions,
) -> LmResult<VelocityState> {
    levenberg_marquardt(problem, start, options)
}

/// The information the points alone carry about `(δ1, δ2)` once the pose is eliminated:
/// the Schur complement `H_δδ − H_δp H_pp⁻¹ H_pδ` of the loss-weighted Gauss-Newton matrix
/// `J^T W J` of the point residuals at `state` (prior excluded). Its eigenvalues below the
/// prior's `k²` are directions the prior, not the data, decides. `None` if the pose block is
/// singular.
pub fn velocity_information(
    problem: &VelocityProblem<'_>,
    state: &VelocityState,
) -> Option<SMatrix<f64, 6, 6>> {
    let n = problem.num_residuals();
    let mut r = vec![0.0; n];
    let mut jac = vec![SVector::<f64, DIM>::zeros(); n];
    problem.residuals_and_jacobian(state, &mut r, &mut jac);
    let mut h = SMatrix::<f64, DIM, DIM>::zeros();
    for (x, j) in r.iter().zip(&jac).take(problem.robust_residuals()) {
        let w = problem.loss.weight(x * x);
        if w.is_finite() && x.is_finite() && j.iter().all(|v| v.is_finite()) {
            h.syger(w, j, j, 1.0);
        }
    }
    h.fill_upper_triangle_with_lower_triangle();
    let hpp = h.fixed_view::<5, 5>(0, 0).into_owned();
    let hpd = h.fixed_view::<5, 6>(0, 5).into_owned();
    let hdd = h.fixed_view::<6, 6>(5, 5).into_owned();
    let x = hpp.cholesky()?.solve(&hpd);
    Some(hdd - hpd.transpose() * x)
}

/// The explanation `rectified+v` weighs its velocities against: still cameras whose gyro
/// rates are off by constant errors `δω_c`. With `ε_c = T δω_c` (rad over the reference
/// duration) the row-0 bearings become, to first order,
/// `b_c ← b_c + τ_c ε_c × b_c` (the row's extra rotation `exp(−[τ_c ε_c]×)`); the residual is
/// the module's at zero velocity on those bearings (image gradients through the gyro's
/// `Ω`, the correction's effect on them being second order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RateErrorState {
    /// Relative pose.
    pub pose: Pose,
    /// `ε1`, `ε2`, rad over the reference duration, camera axes.
    pub rate: [Vector3<f64>; 2],
}

/// Refinement of `(R, t, ε1, ε2)` over a set of points ([`RateErrorState`]) with a robust
/// loss and a zero-mean prior on the rate errors (residuals `k ε`, exempt from the loss);
/// its Jacobian is left to finite differences.
pub struct RateErrorProblem<'a> {
    /// The points.
    pub data: &'a PointData,
    /// Indices of the points used.
    pub indices: &'a [usize],
    /// `λ_c / T` of each view.
    pub row_time: [f64; 2],
    /// Loss of the point residuals.
    pub loss: Loss,
    /// Weight `k` of the prior residuals `k ε` (0: no prior).
    pub prior: f64,
}

impl RateErrorProblem<'_> {
    /// Sampson residual of point `i` under `state`.
    pub fn residual(&self, state: &RateErrorState, i: usize) -> f64 {
        let model = VelocityModel::new(&VelocityState::still(state.pose), self.row_time);
        let (t1, t2) = model.tau(self.data, i);
        let (b1, b2) = (self.data.b1[i], self.data.b2[i]);
        let b1 = b1 + (state.rate[0] * t1).cross(&b1);
        let b2 = b2 + (state.rate[1] * t2).cross(&b2);
        let rays = model.rays_of(self.data, i, &b1, &b2);
        model.residual_of(self.data, ResidualKind::Sampson, i, rays)
    }

    /// `Σ_i min(r_i², τ²)` over every point.
    pub fn truncated_cost(&self, state: &RateErrorState, threshold_sq: f64) -> f64 {
        truncated(self.data.len(), threshold_sq, |i| self.residual(state, i))
    }
}

impl LmProblem<DIM> for RateErrorProblem<'_> {
    type State = RateErrorState;
    fn num_residuals(&self) -> usize {
        self.indices.len() + 6
    }
    fn robust_residuals(&self) -> usize {
        self.indices.len()
    }
    fn residuals(&self, s: &RateErrorState, out: &mut [f64]) {
        write_residuals(self.indices, self.prior, &s.rate, out, |i| {
            self.residual(s, i)
        });
    }
    fn retract(&self, s: &RateErrorState, d: &SVector<f64, DIM>) -> RateErrorState {
        RateErrorState {
            pose: s.pose.retract(&d.as_slice()[0..5]),
            rate: retract_pair(&s.rate, d),
        }
    }
    fn loss(&self) -> Loss {
        self.loss
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::estimation::refine::tests::check_jacobian;
    use crate::model::geometry::{exp_so3, skew};

    fn scene(linear: f64, seed: u64) -> (crate::data::pair_file::PairFile, View, View, PointData) {
        let pair = simulate(&SimulationOptions {
            seed,
            points: 60,
            angular_velocity: 2.0,
            linear_velocity: linear,
            pixel_noise: 0.0,
            gyro_noise: 0.0,
            ..Default::default()
        })
        .unwrap();
        let (v1, v2) = pair.views().unwrap();
        let d = PointData::new(&v1, &v2, &pair.matches).unwrap();
        (pair, v1, v2, d)
    }

    fn row_time(v1: &View, v2: &View) -> [f64; 2] {
        let t = reference_duration(v1, v2);
        [v1.camera.readout / t, v2.camera.readout / t]
    }

    #[test]
    fn analytic_jacobian_matches_finite_differences() {
        let (pair, v1, v2, d) = scene(10.0, 31);
        let gt = pair.ground_truth.clone().unwrap();
        let idx: Vec<usize> = (0..d.len()).collect();
        let state = VelocityState {
            pose: Pose::new(
                &(gt.rotation_matrix() * exp_so3(&Vector3::new(0.02, -0.01, 0.015))),
                &(gt.translation_vector() + Vector3::new(0.05, -0.03, 0.02)),
            ),
            delta: [Vector3::new(0.1, -0.2, 0.05), Vector3::new(-0.1, 0.05, 0.3)],
        };
        let p = VelocityProblem {
            data: &d,
            indices: &idx,
            row_time: row_time(&v1, &v2),
            loss: Loss::Trivial,
            prior: 0.3,
        };
        check_jacobian(&p, &state, 1e-5);
    }

    /// With zero velocities the model is the exact angular one: the same Sampson residual
    /// (up to sign) as `rectified` scores with.
    #[test]
    fn zero_velocity_is_the_exact_angular_model() {
        let (pair, v1, v2, d) = scene(0.0, 32);
        let gt = pair.ground_truth.clone().unwrap();
        let r = gt.rotation_matrix() * exp_so3(&Vector3::new(0.01, 0.0, -0.02));
        let t = (gt.translation_vector() + Vector3::new(0.0, 0.1, 0.0)).normalize();
        let model = VelocityModel::new(&VelocityState::still(Pose::new(&r, &t)), {
            row_time(&v1, &v2)
        });
        let e = skew(&t) * r;
        for i in 0..d.len() {
            for kind in [ResidualKind::Algebraic, ResidualKind::Sampson] {
                let a = model.residual(&d, kind, i);
                let b = d.residual(PoseModel::ExactAngular, kind, i, &r, &t, &e);
                assert!((a + b).abs() <= 1e-12 * (1.0 + b.abs()), "{kind:?} {a} {b}");
            }
        }
    }

    /// Noise-free matches of cameras moving at 10 m/s satisfy the model exactly at the true
    /// pose and velocities, `δ_c = T d_c / |C2|`, and not at zero velocity. The simulator
    /// does not store the baseline `|C2|`; the algebraic residual is affine in `s = 1/|C2|`,
    /// so its least-squares value is solved for, and must zero every residual.
    #[test]
    fn true_velocities_zero_the_residuals() {
        let (pair, v1, v2, d) = scene(10.0, 33);
        let gt = pair.ground_truth.clone().unwrap();
        let tt = reference_duration(&v1, &v2);
        let residuals = |s: f64| -> Vec<f64> {
            let state = VelocityState {
                pose: Pose::new(&gt.rotation_matrix(), &gt.translation_vector()),
                delta: [0, 1].map(|c| Vector3::from(gt.velocity[c]) * tt * s),
            };
            let m = VelocityModel::new(&state, row_time(&v1, &v2));
            (0..d.len())
                .map(|i| m.residual(&d, ResidualKind::Algebraic, i))
                .collect()
        };
        let (a, b1) = (residuals(0.0), residuals(1.0));
        let b: Vec<f64> = b1.iter().zip(&a).map(|(y, x)| y - x).collect();
        let s = -a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>()
            / b.iter().map(|y| y * y).sum::<f64>();
        assert!(s > 0.0, "{s}");
        assert!(residuals(s).iter().all(|r| r.abs() < 1e-10));
        assert!(a.iter().any(|r| r.abs() > 1e-4), "the velocity must matter");
    }

    /// At the true pose and velocities every point meets in front of both moving cameras,
    /// and in the mirrored state `(−t, −δ1, −δ2)` behind both.
    #[test]
    fn cheirality_with_moving_centres() {
        let (pair, v1, v2, d) = scene(20.0, 34);
        let gt = pair.ground_truth.clone().unwrap();
        let tt = reference_duration(&v1, &v2);
        let idx: Vec<usize> = (0..d.len()).collect();
        // `δ_c = T d_c / |C2|` with the baseline solved for as in
        // `true_velocities_zero_the_residuals`.
        let state_at = |s: f64| VelocityState {
            pose: Pose::new(&gt.rotation_matrix(), &gt.translation_vector()),
            delta: [0, 1].map(|c| Vector3::from(gt.velocity[c]) * tt * s),
        };
        let residuals = |s: f64| -> Vec<f64> {
            let m = VelocityModel::new(&state_at(s), row_time(&v1, &v2));
            idx.iter()
                .map(|&i| m.residual(&d, ResidualKind::Algebraic, i))
                .collect()
        };
        let (a, b1) = (residuals(0.0), residuals(1.0));
        let b: Vec<f64> = b1.iter().zip(&a).map(|(y, x)| y - x).collect();
        let s = -a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>()
            / b.iter().map(|y| y * y).sum::<f64>();
        for sign in [1.0, -1.0] {
            let truth = state_at(s);
            let state = VelocityState {
                pose: Pose::new(&gt.rotation_matrix(), &(gt.translation_vector() * sign)),
                delta: truth.delta.map(|x| x * sign),
            };
            let (front, behind) =
                VelocityModel::new(&state, row_time(&v1, &v2)).cheirality_counts(&d, &idx);
            let expected = if sign > 0.0 {
                (d.len(), 0)
            } else {
                (0, d.len())
            };
            assert_eq!((front, behind), expected);
        }
    }
}
