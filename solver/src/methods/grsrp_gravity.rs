//! `grsrp-gravity`: each view's gravity direction (an accelerometer's, [`View::gravity`])
//! fixes two of the relative rotation's three degrees of freedom, `R g1 ∥ g2`: with
//! `G_c g_c = e_y`, `R = G2^T Ry(yaw) G1` ([`crate::minimal::gravity_alignment`]).
//!
//! 1. **Consensus.** RANSAC draws 3-point samples for the generated known-gravity solver
//!    ([`crate::minimal::GravitySolver`]: `grsrp_gravity6` by default, the paper's G-RSRP
//!    row model with the gyro rates `w = −λ ω`, [`View::paper_rate_per_row`]; the sign of
//!    `t` by cheirality on the sample) and scores them with the exact angular model at the
//!    inlier threshold widened by the relative tilt the gravity errors cause,
//!    `τ² + 2 σ_g²` ([`super::RobustOptions::gravity_noise_deg`]). A gravity error of
//!    `σ_g` tilts every hypothesis by about `√2 σ_g` (1° moves points by some 15 px), so
//!    at the plain threshold even all-inlier samples gather biased fractions of the inliers
//!    and local optimisation from them stalls; at the widened one they gather nearly all.
//! 2. **Inner RANSAC** (LO-RANSAC's): 5-point samples from the consensus set, scored with
//!    the exact angular model at the plain threshold and locally optimised, free the two
//!    angles the gravity fixed. The consensus set is small and mostly inliers, so this is
//!    cheap.
//! 3. **Refinement**: `rectified`'s ([`super::rectified`]), on every match within the
//!    plain threshold of the inner RANSAC's pose: `(R, t)` by LM on the exact angular
//!    Sampson error, all three rotation angles free, so the accelerometer's error shapes
//!    the search but not the final pose.
//!
//! A 3-point sample is all inliers far more often than a 5-point one (at 50 % inliers
//! 1/8 against 1/32), so the consensus stage stops after about a quarter of the samples
//! `rectified` needs, and no `R_0` estimate is needed.

use super::pose_ransac::{indices, point_data, run, threshold, EssentialRansac, Hypothesis};
use super::{rectified, Estimate, EstimateError, EstimateOptions, Method, RobustOptions};
use crate::estimation::ransac::{RansacEstimator, RansacResult, Score};
use crate::minimal::{GravitySample, GravitySolver};
use crate::model::camera::View;
use crate::model::epipolar::PointData;
use crate::model::geometry::fix_translation_sign;
use crate::model::matches::Match;
use nalgebra::{Matrix3, Vector3};

/// Known-gravity RANSAC: hypotheses from the generated 3-point solver, scoring and local
/// optimisation delegated to the exact angular model (`rectified`'s estimator).
struct GravityRansac<'a> {
    exact: EssentialRansac<'a>,
    /// The views' gravity directions.
    gravity: [Vector3<f64>; 2],
    /// The views' numbers of lines per frame.
    rows: [f64; 2],
    solver: GravitySolver,
    sols: Vec<(Matrix3<f64>, Vector3<f64>)>,
}

impl RansacEstimator for GravityRansac<'_> {
    type Model = Hypothesis;
    fn sample_size(&self) -> usize {
        3
    }
    fn num_data(&self) -> usize {
        self.exact.scorer.data.len()
    }
    fn generate_models(&mut self, sample: &[usize], models: &mut Vec<Hypothesis>) {
        let d: &PointData = self.exact.scorer.data;
        let s = GravitySample::from_points(
            d,
            &std::array::from_fn(|k| sample[k]),
            self.gravity,
            self.rows,
        );
        let mut sols = std::mem::take(&mut self.sols);
        sols.clear();
        self.solver.solve(&s, &mut sols);
        let b1: [Vector3<f64>; 3] = std::array::from_fn(|k| d.b1[sample[k]]);
        let b2: [Vector3<f64>; 3] = std::array::from_fn(|k| d.b2[sample[k]]);
        let first = models.len();
        for (r, t) in &sols {
            // The solver returns each pose with both signs of t: keep one.
            let t = fix_translation_sign(r, t, &b1, &b2);
            let seen = models[first..]
                .iter()
                .any(|h| (h.r - r).norm() + (h.t - t).norm() < 1e-9);
            if !seen {
                models.push(Hypothesis::new(*r, t));
            }
        }
        self.sols = sols;
    }
    fn residual_sq(&self, m: &Hypothesis, i: usize) -> f64 {
        self.exact.residual_sq(m, i)
    }
    fn score_bounded(&self, m: &Hypothesis, thr_sq: f64, bound: f64) -> Score {
        self.exact.score_bounded(m, thr_sq, bound)
    }
    fn refine(&self, m: &Hypothesis, inliers: &[usize], thr_sq: f64) -> Option<Hypothesis> {
        self.exact.refine(m, inliers, thr_sq)
    }
}

/// Estimate with `grsrp-gravity`.
///
/// The input is not checked here: it must be what [`super::validate_input`] accepts with
/// `options.method` = `grsrp-gravity` (valid views, both with a gravity direction, finite pixels that have bearings, at
/// least [`super::Method::min_matches`] distinct matches, valid options); call that first, or
/// use [`super::estimate_relative_pose`], which checks the input and adds the subset of large
/// inputs, the optional readout and gyro-bias refinements and the quality report. Unchecked
/// input may give an error or a meaningless estimate.
pub fn estimate(
    view1: &View,
    view2: &View,
    matches: &[Match],
    options: &EstimateOptions,
) -> Result<Estimate, EstimateError> {
    let (Some(g1), Some(g2)) = (view1.gravity, view2.gravity) else {
        return Err(EstimateError::MissingGravity {
            view: if view1.gravity.is_none() { 1 } else { 2 },
        });
    };
    let data = point_data(view1, view2, matches, &options.robust)?;
    let (kind, thr_sq) = threshold(view1, view2, options.robust.threshold);
    let exact = |data| EssentialRansac::exact(data, kind, options);
    // Stage 1: the consensus set of the gravity hypotheses, with the threshold widened by
    // the relative tilt the gravity errors cause (both views': sqrt(2) σ_g per axis).
    let tilt = std::f64::consts::SQRT_2 * options.robust.gravity_noise_deg.to_radians();
    let mut est = GravityRansac {
        exact: exact(&data),
        gravity: [g1, g2],
        rows: [view1.camera.lines(), view2.camera.lines()],
        solver: options.gravity_solver,
        sols: Vec::new(),
    };
    let stage1 = EstimateOptions {
        robust: RobustOptions {
            local_optimisation: false,
            ..options.robust.clone()
        },
        ..options.clone()
    };
    let (_, consensus) = run(&mut est, &stage1, thr_sq + tilt * tilt)?;
    // Stage 2: 5-point samples from the consensus set free the two angles the gravity fixed.
    let idx = indices(&consensus.inliers);
    let sub = data.select(&idx);
    let (h, inner) = run(&mut exact(&sub), options, thr_sq)?;
    let full = exact(&data);
    let inliers: Vec<bool> = (0..data.len())
        .map(|i| full.residual_sq(&h, i) < thr_sq)
        .collect();
    let res = RansacResult {
        model: Some(h),
        score: full.score(&h, thr_sq),
        iterations: consensus.iterations + inner.iterations,
        inliers,
    };
    Ok(rectified::refine_exact(
        &data,
        (view1, view2),
        h,
        res,
        (kind, thr_sq),
        options,
        Method::GrsrpGravity,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::pair_file::PairFile;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::experiment::evaluate::pose_errors;
    use crate::{estimate_relative_pose, Method};

    fn run(p: &PairFile, o: &EstimateOptions) -> Result<Estimate, EstimateError> {
        let (v1, v2) = p.views().unwrap();
        estimate_relative_pose(&v1, &v2, &p.matches, o)
    }

    /// Exact gravity and noise-free matches at 2.5 rad/s: the pose is recovered exactly with
    /// either generated solver. With half the matches outliers every true inlier is kept and
    /// the pose is `rectified`'s to rounding: both end in the same least-squares refinement
    /// over the same inliers (an outlier that happens to lie within the threshold of its
    /// epipolar curve moves both alike).
    #[test]
    fn recovers_a_planted_pose() {
        for (seed, outliers) in [(1, 0.0), (2, 0.0), (1, 0.5), (2, 0.5)] {
            let p = simulate(&SimulationOptions {
                pixel_noise: 0.0,
                gyro_noise: 0.0,
                gravity_noise_deg: 0.0,
                outlier_fraction: outliers,
                seed,
                ..Default::default()
            })
            .unwrap();
            let gt = p.ground_truth.as_ref().unwrap();
            let rect = run(&p, &EstimateOptions::for_method(Method::Rectified)).unwrap();
            for solver in [GravitySolver::Six, GravitySolver::Twelve] {
                let o = EstimateOptions {
                    gravity_solver: solver,
                    ..EstimateOptions::for_method(Method::GrsrpGravity)
                };
                let e = run(&p, &o).unwrap();
                let err = pose_errors(&e, gt);
                if outliers == 0.0 {
                    assert!(err.rotation_error_deg < 1e-6, "{solver:?}: {err:?}");
                    assert!(err.translation_error_deg < 1e-6, "{solver:?}: {err:?}");
                }
                assert!((0..p.matches.len()).all(|i| !gt.inliers[i] || e.inliers[i]));
                assert_eq!(e.inliers, rect.inliers, "{solver:?}");
                assert!((e.rotation - rect.rotation).norm() < 1e-8, "{solver:?}");
                assert!(
                    (e.translation - rect.translation).norm() < 1e-8,
                    "{solver:?}"
                );
            }
        }
    }

    /// A gravity error tilts every hypothesis; the widened consensus and the inner 5-point
    /// RANSAC absorb it: with 1° (per axis) and 50 % outliers the pose is as accurate as
    /// `rectified`'s, in fewer samples.
    #[test]
    fn absorbs_a_gravity_error_with_half_the_matches_outliers() {
        let (mut ours, mut rect) = (0.0, 0.0);
        for seed in 0..8 {
            let p = simulate(&SimulationOptions {
                outlier_fraction: 0.5,
                gravity_noise_deg: 1.0,
                seed,
                ..Default::default()
            })
            .unwrap();
            let gt = p.ground_truth.as_ref().unwrap();
            let e = run(&p, &EstimateOptions::for_method(Method::GrsrpGravity)).unwrap();
            let r = run(&p, &EstimateOptions::for_method(Method::Rectified)).unwrap();
            ours += pose_errors(&e, gt).rotation_error_deg;
            rect += pose_errors(&r, gt).rotation_error_deg;
            assert!(pose_errors(&e, gt).rotation_error_deg < 1.5, "seed {seed}");
        }
        assert!(ours <= 1.25 * rect, "{ours} vs {rect}");
    }

    #[test]
    fn needs_gravity_on_both_views() {
        let p = simulate(&SimulationOptions::default()).unwrap();
        let (v1, v2) = p.views().unwrap();
        let o = EstimateOptions::for_method(Method::GrsrpGravity);
        let bare = View::new(v2.camera, v2.omega);
        assert_eq!(
            estimate_relative_pose(&v1, &bare, &p.matches, &o),
            Err(EstimateError::MissingGravity { view: 2 })
        );
        let mut bad = v1.clone();
        bad.gravity = Some(Vector3::new(f64::NAN, 1.0, 0.0));
        assert!(matches!(
            estimate_relative_pose(&bad, &v2, &p.matches, &o),
            Err(EstimateError::InvalidCamera { view: 1, .. })
        ));
    }
}
