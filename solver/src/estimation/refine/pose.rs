//! The relative pose on `SO(3) x S²` and its refinement on the residuals of one of the
//! two-view models of [`crate::model::epipolar`].

use super::lm::{levenberg_marquardt, LmOptions, LmProblem, LmResult, Loss};
use crate::model::epipolar::{PointData, PoseModel, ResidualKind};
use crate::model::geometry::{skew, tangent_basis};
use nalgebra::{Matrix3, SVector, UnitQuaternion, Vector3};

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
        let r = crate::model::geometry::orthonormalize(r);
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
        // One loop per model, so that the per-point `match`es on it fold away.
        match self.model {
            PoseModel::GlobalShutter => self.fill_jacobian::<0>(s, out, jac),
            PoseModel::ExactAngular => self.fill_jacobian::<1>(s, out, jac),
            PoseModel::PaperLinear => self.fill_jacobian::<2>(s, out, jac),
        }
        true
    }
}

impl PoseProblem<'_> {
    /// [`LmProblem::residuals_and_jacobian`] for the model numbered `M` (0 global shutter, 1
    /// exact angular, 2 the paper's), which must be `self.model`.
    fn fill_jacobian<const M: u8>(&self, s: &Pose, out: &mut [f64], jac: &mut [SVector<f64, 5>]) {
        let model = match M {
            0 => PoseModel::GlobalShutter,
            1 => PoseModel::ExactAngular,
            _ => PoseModel::PaperLinear,
        };
        let d = self.data;
        let rot = s.matrix();
        let t = s.translation;
        let (tb1, tb2) = tangent_basis(&t);
        let w2r = skew(&d.w2) * rot;
        for ((o, j), &i) in out.iter_mut().zip(jac.iter_mut()).zip(self.indices) {
            let (c1, c2, m) = match model {
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
            // The projections of the image gradients, read only by the models using them.
            let (om1, om2, a1) = match model {
                PoseModel::GlobalShutter => (None, None, Vector3::zeros()),
                PoseModel::ExactAngular => {
                    (Some(&d.omega1[i]), Some(&d.omega2[i]), Vector3::zeros())
                }
                PoseModel::PaperLinear => (None, None, d.w1 * d.v1[i]),
            };
            let p1 = |x: &Vector3<f64>| match (model, om1) {
                (PoseModel::ExactAngular, Some(o)) => o * x,
                (PoseModel::PaperLinear, _) => x + a1.cross(x),
                _ => *x,
            };
            let p2 = |x: &Vector3<f64>| match om2 {
                Some(o) => o * x,
                None => *x,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::estimation::refine::tests::{check_jacobian, jacobian_scene, perturbed};
    use crate::model::geometry::{rotation_error_deg, translation_error_deg};

    #[test]
    fn pose_analytic_jacobians_match_finite_differences() {
        let (d, _, start) = jacobian_scene();
        let idx: Vec<usize> = (0..d.len()).collect();
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
}
