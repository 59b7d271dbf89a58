//! Dai et al.'s generalized epipolar constraint for the uniform rolling-shutter model
//! (`nrsrp`): unknowns `R, t, ω1, d1, ω2, d2`, Cauchy loss over the given points.

use super::lm::{levenberg_marquardt, LmOptions, LmProblem, LmResult, Loss};
use super::pose::Pose;
use crate::model::epipolar::{PointData, ResidualKind};
use crate::model::geometry::tangent_basis;
use nalgebra::{SVector, Vector3};

/// State of the NRSRP (Dai et al.) model, in the row-0 frame of camera 1 (world frame
/// `R1 = I, C1 = 0`): relative pose `(R, t)`, and per camera the rotation and displacement
/// accumulated over one full frame, `phi_c = −H λ ω_c` (rad, camera frame; `ω_c` the
/// physical angular velocity, so `exp([s phi]×)` is the row rotation at fraction `s`) and
/// `delta_c = H λ d_c` (units of the baseline |t| = 1, camera-1 frame), with `H` the lines per
/// frame (the image height for a row readout). Scaling by the frame duration keeps the 17 unknowns commensurate.
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
/// centres `c1 = s1 delta1`, `c2 = -R^T t + s2 delta2`, `s = v / H` (fraction of the frame; `v` the line coordinate, `H` the lines per frame).
/// This is the coplanarity of the two rays (zero iff they intersect).
pub struct NrsrpProblem<'a> {
    /// Bearings and rows.
    pub data: &'a PointData,
    /// The points refined on (indices into `data`).
    pub indices: &'a [usize],
    /// Lines per frame `H` of image 1 and image 2 ([`crate::model::camera::Camera::lines`]).
    pub lines: [f64; 2],
    /// Cauchy scale.
    pub cauchy_scale: f64,
}

impl LmProblem<17> for NrsrpProblem<'_> {
    type State = NrsrpState;
    fn num_residuals(&self) -> usize {
        self.indices.len()
    }
    fn residuals(&self, s: &NrsrpState, out: &mut [f64]) {
        let r = s.pose.matrix();
        let c2_0 = -(r.transpose() * s.pose.translation);
        for (o, &i) in out.iter_mut().zip(self.indices) {
            let s1 = self.data.v1[i] / self.lines[0];
            let s2 = self.data.v2[i] / self.lines[1];
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
        for ((o, j), &i) in out.iter_mut().zip(jac.iter_mut()).zip(self.indices) {
            let s1 = d.v1[i] / self.lines[0];
            let s2 = d.v2[i] / self.lines[1];
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

    /// `exp([φ]×) v`.
    fn apply(&self, v: &Vector3<f64>) -> Vector3<f64> {
        let pv = self.phi.cross(v);
        v + pv * self.a + self.phi.cross(&pv) * self.b
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

/// The rays of point `i` under `state` in camera 1's row-0 frame: unnormalised directions
/// `g1 = exp([s1 φ1]×)^T m1`, `g2 = R^T exp([s2 φ2]×)^T m2`, the vector between the centres
/// `D = c2 − c1`, and the row rotations `exp([s φ]×)` of both.
fn rays(
    data: &PointData,
    lines: [f64; 2],
    state: &NrsrpState,
    i: usize,
) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>, [SmallRotation; 2]) {
    let r = state.pose.matrix();
    let s1 = data.v1[i] / lines[0];
    let s2 = data.v2[i] / lines[1];
    let q1 = SmallRotation::new(&(state.phi[0] * s1));
    let q2 = SmallRotation::new(&(state.phi[1] * s2));
    let g1 = q1.apply_transpose(&data.m1[i]);
    let g2 = r.tr_mul(&q2.apply_transpose(&data.m2[i]));
    let d = -r.tr_mul(&state.pose.translation) + state.delta[1] * s2 - state.delta[0] * s1;
    (g1, g2, d, [q1, q2])
}

/// Residual of point `i` under `state` for an inlier test. Algebraic: `D · (g1 × g2)` with
/// the unnormalised rays of [`NrsrpProblem`] (at zero velocities `∓m2^T [t]× R m1`, the
/// global-shutter algebraic residual, so the same threshold applies). Sampson: that divided
/// by the norm of its gradient with respect to the normalised image points,
/// `∂r/∂m1 = Q1 (g2 × D)`, `∂r/∂m2 = Q2 R (D × g1)` (`Q` the row rotations; the first-order
/// distance in normalised image units). Non-finite for a degenerate point.
pub fn nrsrp_residual(
    data: &PointData,
    lines: [f64; 2],
    state: &NrsrpState,
    kind: ResidualKind,
    i: usize,
) -> f64 {
    let (g1, g2, d, [q1, q2]) = rays(data, lines, state, i);
    let res = d.dot(&g1.cross(&g2));
    if kind == ResidualKind::Algebraic {
        return res;
    }
    let grad1 = q1.apply(&g2.cross(&d));
    let grad2 = q2.apply(&(state.pose.matrix() * d.cross(&g1)));
    let ss = grad1.x * grad1.x + grad1.y * grad1.y + grad2.x * grad2.x + grad2.y * grad2.y;
    if ss > 0.0 {
        res / ss.sqrt()
    } else {
        f64::INFINITY
    }
}

/// Cheirality of `state` over the points `indices`: the numbers of points whose two rays,
/// from the moving centres `c1`, `c2`, meet in front of both cameras, and behind both. The
/// model is homogeneous in `(t, δ1, δ2)`: negating all three negates both depths, so the
/// second count is the first of the mirrored state.
pub fn nrsrp_cheirality(
    data: &PointData,
    lines: [f64; 2],
    state: &NrsrpState,
    indices: &[usize],
) -> (usize, usize) {
    let (mut front, mut behind) = (0, 0);
    for &i in indices {
        let (g1, g2, d, _) = rays(data, lines, state, i);
        match crate::model::geometry::ray_depths(&g1, &g2, &d) {
            Some((a, b)) if a > 0.0 && b > 0.0 => front += 1,
            Some((a, b)) if a < 0.0 && b < 0.0 => behind += 1,
            _ => {}
        }
    }
    (front, behind)
}

/// Refine the NRSRP model on the points `indices` with the Cauchy loss (see
/// [`NrsrpProblem`]).
pub fn refine_nrsrp(
    data: &PointData,
    indices: &[usize],
    lines: [f64; 2],
    cauchy_scale: f64,
    start: NrsrpState,
    options: &LmOptions,
) -> LmResult<NrsrpState> {
    let p = NrsrpProblem {
        data,
        indices,
        lines,
        cauchy_scale,
    };
    levenberg_marquardt(&p, start, options)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::estimation::refine::tests::{check_jacobian, jacobian_scene, perturbed};
    use crate::model::geometry::rotation_error_deg;

    #[test]
    fn nrsrp_analytic_jacobian_matches_finite_differences() {
        let (d, height, start) = jacobian_scene();
        let idx: Vec<usize> = (0..d.len()).collect();
        let p = NrsrpProblem {
            data: &d,
            indices: &idx,
            lines: [height; 2],
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
        let cam = pair.cameras[0];
        // NRSRP uses no gyro: bearings only.
        let still = crate::model::camera::View::new(cam, Vector3::zeros());
        let d = PointData::new(&still, &still, &pair.matches).unwrap();
        let (gr, gtt) = (gt.rotation_matrix(), gt.translation_vector());
        let start_pose = perturbed(&gr, &gtt);
        let start = NrsrpState {
            pose: start_pose,
            phi: [Vector3::zeros(); 2],
            delta: [Vector3::zeros(); 2],
        };
        let idx: Vec<usize> = (0..d.len()).collect();
        let res = refine_nrsrp(
            &d,
            &idx,
            [cam.height; 2],
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
