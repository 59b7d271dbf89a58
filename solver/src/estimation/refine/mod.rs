//! Nonlinear refinement: Levenberg-Marquardt on fixed-size nalgebra matrices (`lm`), the
//! relative-pose problem (`pose`) and Dai et al.'s uniform rolling-shutter model (`nrsrp`).
//!
//! Parameterisation: rotations are unit quaternions updated on the right by tangent steps,
//! `q ← q ⊗ exp(δθ)` (`R ← R exp([δθ]×)`, δθ ∈ so(3)); the unit translation is updated in the
//! 2-D tangent plane of the sphere, `t ← normalise(t + δ1 b1 + δ2 b2)` with `(b1, b2)` from
//! [`tangent_basis`]. Jacobians are central finite differences of the residual vector (step
//! [`LmOptions::fd_step`] in tangent coordinates) or analytic where a problem provides them,
//! assembled into `J^T W J` as an `N x N` fixed-size matrix. Robust losses use iteratively
//! reweighted normal equations; the cost minimised is `Σ ρ(r_i²)` with `ρ(s) = s` (trivial)
//! or `ρ(s) = c² ln(1 + s / c²)` (Cauchy with scale `c`). Damping is Marquardt's:
//! `(H + μ diag(H)) δ = -g`.
//!
//! The costs:
//! - [`refine_pose`] with [`PaperLinear`] + [`Algebraic`]: the paper's `grsrp+` cost
//!   `m2^T [t]× (I + v2 [w2]×) R (I - v1 [w1]×) m1` (`w = −λω`) over inliers;
//! - [`refine_pose`] with [`ExactAngular`] + [`Sampson`]: Sampson error of the exact angular
//!   model (`rectified`), or the global-shutter model (`gsrp`);
//! - [`refine_nrsrp`]: Dai et al.'s generalized epipolar constraint for the uniform RS model,
//!   unknowns `R, t, ω1, d1, ω2, d2`, Cauchy loss over all points;
//! - [`crate::estimation::velocity`]: the same constraint with the gyro's row rotations,
//!   unknowns `R, t, d1, d2` (`rectified+v`).
//!
//! [`tangent_basis`]: crate::model::geometry::tangent_basis
//! [`PaperLinear`]: crate::model::epipolar::PoseModel::PaperLinear
//! [`ExactAngular`]: crate::model::epipolar::PoseModel::ExactAngular
//! [`Algebraic`]: crate::model::epipolar::ResidualKind::Algebraic
//! [`Sampson`]: crate::model::epipolar::ResidualKind::Sampson

mod lm;
mod nrsrp;
mod pose;

pub use lm::{levenberg_marquardt, LmOptions, LmProblem, LmResult, Loss};
pub use nrsrp::{nrsrp_cheirality, nrsrp_residual, refine_nrsrp, NrsrpProblem, NrsrpState};
pub use pose::{refine_pose, Pose, PoseProblem};

#[cfg(test)]
pub(crate) mod tests {
    use super::lm::LmProblem;
    use super::Pose;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::model::epipolar::PointData;
    use crate::model::geometry::exp_so3;
    use nalgebra::{Matrix3, SVector, Vector3};

    /// The scene the analytic Jacobians are checked on: 40 matches at 2 rad/s, their image
    /// height, and a start pose perturbed from the truth.
    pub(crate) fn jacobian_scene() -> (PointData, f64, Pose) {
        let pair = simulate(&SimulationOptions {
            seed: 21,
            points: 40,
            angular_velocity: 2.0,
            ..Default::default()
        })
        .unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        let (v1, v2) = pair.views().unwrap();
        let data = PointData::new(&v1, &v2, &pair.matches).unwrap();
        let start = perturbed(&gt.rotation_matrix(), &gt.translation_vector());
        (data, v1.camera.height, start)
    }

    pub(crate) fn perturbed(gt_r: &Matrix3<f64>, gt_t: &Vector3<f64>) -> Pose {
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
}
