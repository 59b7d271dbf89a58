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
            // Sampson. The image gradients are g1 = P1 w and g2 = P2 u (x and y components).
            // With h1 = P1ᵀ [g1x, g1y, 0] and h2 = P2ᵀ [g2x, g2y, 0], half of ∂|g|² is
            // h1 · ∂w + h2 · ∂u, and by triple products h2 · ∂u/∂θ = c1 × (Mᵀ (h2 × t)),
            // h2 · ∂u/∂t_k = b_k · (y × h2), h1 · ∂w/∂θ = h1 × w and
            // h1 · ∂w/∂t_k = (M h1) · (c2 × b_k): no derivative vector is formed.
            let (g1, g2, h1, h2) = match model {
                PoseModel::GlobalShutter => {
                    let (g1, g2) = ([w.x, w.y], [u.x, u.y]);
                    (
                        g1,
                        g2,
                        Vector3::new(w.x, w.y, 0.0),
                        Vector3::new(u.x, u.y, 0.0),
                    )
                }
                PoseModel::ExactAngular => {
                    let (o1, o2) = (&d.omega1[i], &d.omega2[i]);
                    let row = |o: &Matrix3<f64>, r: usize, x: &Vector3<f64>| {
                        o[(r, 0)] * x.x + o[(r, 1)] * x.y + o[(r, 2)] * x.z
                    };
                    let g1 = [row(o1, 0, &w), row(o1, 1, &w)];
                    let g2 = [row(o2, 0, &u), row(o2, 1, &u)];
                    let back = |o: &Matrix3<f64>, g: [f64; 2]| {
                        Vector3::new(
                            o[(0, 0)] * g[0] + o[(1, 0)] * g[1],
                            o[(0, 1)] * g[0] + o[(1, 1)] * g[1],
                            o[(0, 2)] * g[0] + o[(1, 2)] * g[1],
                        )
                    };
                    (g1, g2, back(o1, g1), back(o2, g2))
                }
                PoseModel::PaperLinear => {
                    // P1 = I + [a1]×, P1ᵀ = I - [a1]×; P2 = I.
                    let a1 = d.w1 * d.v1[i];
                    let p1w = w + a1.cross(&w);
                    let g1 = [p1w.x, p1w.y];
                    let gh = Vector3::new(g1[0], g1[1], 0.0);
                    (
                        g1,
                        [u.x, u.y],
                        gh - a1.cross(&gh),
                        Vector3::new(u.x, u.y, 0.0),
                    )
                }
            };
            let ss = g1[0] * g1[0] + g1[1] * g1[1] + g2[0] * g2[0] + g2[1] * g2[1];
            let sn = ss.sqrt();
            let wt = d.weight(model, i);
            *o = if ss > 0.0 {
                wt * res / sn
            } else {
                f64::INFINITY
            };
            let k = res / (ss * sn);
            let rot_u = c1.cross(&m.tr_mul(&h2.cross(&t)));
            let rot_w = h1.cross(&w);
            let yh = y.cross(&h2);
            let mh = m * h1;
            let dss = [
                rot_u.x + rot_w.x,
                rot_u.y + rot_w.y,
                rot_u.z + rot_w.z,
                tb1.dot(&yh) + mh.dot(&c2.cross(&tb1)),
                tb2.dot(&yh) + mh.dot(&c2.cross(&tb2)),
            ];
            for q in 0..5 {
                j[q] = wt * (jr[q] / sn - k * dss[q]);
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
        let d = PointData::new(&v1, &v2, &pair.matches).unwrap();
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
        let d = PointData::new(&v1, &v2, &pair.matches).unwrap();
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
