//! The readout time of one pair, refined with its pose, for cameras whose readout time is
//! known only roughly.
//!
//! The views' row rotations `Ω(v)` depend on the readout time `T` through the time of row
//! `v`, `v T / H`. A wrong nominal `T` leaves every late row's bearing rotated by the
//! rate times the error, so the exact angular model's Sampson residuals
//! ([`PoseModel::ExactAngular`]) grow with the row. Given a pose and its inliers (from any
//! method run at the nominal readout, typically `rectified`), Levenberg-Marquardt refines
//! `(R, t)` and a common scale `k` of both views' readout times (the true `T` is `k` times
//! the nominal), minimising the Sampson error over the inliers with a Cauchy loss at the
//! pixel noise. `k` is parameterised by its logarithm and kept within
//! [`ReadoutOptions::scale_range`]. The Jacobian in `(R, t)` is the pose refinement's
//! analytic one ([`PoseProblem`]) at the current `k`; only its `ln k` column is by central
//! differences (the row rotations depend on `k` through the gyro track).
//!
//! `k` is observable only through the rolling-shutter rotations: with a still camera every
//! `k` fits, so the fit reports how far the cost fell and the caller may keep the nominal
//! readout when it did not fall (see [`ReadoutFit::cost_nominal`]). `rspose calibrate`
//! estimates the readout time (and the gyro's time offset) from many pairs at once instead.

use crate::estimation::refine::{
    levenberg_marquardt, LmOptions, LmProblem, Loss, Pose, PoseProblem,
};
use crate::model::camera::{Observation, View};
use crate::model::epipolar::{observe_matches, PointData, PoseModel, ResidualKind};
use crate::model::matches::Match;
use nalgebra::{Matrix3, SVector, Vector3};

/// Settings of [`refine_readout_scale`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReadoutOptions {
    /// The range the scale `k` (true readout over nominal) is kept in (default 0.25 to 4).
    pub scale_range: (f64, f64),
    /// Scale of the Cauchy loss, pixels (default 1: the simulator's and a typical matcher's
    /// noise).
    pub loss_px: f64,
    /// Levenberg-Marquardt settings (default: [`LmOptions::default`]).
    pub lm: LmOptions,
}

impl Default for ReadoutOptions {
    fn default() -> Self {
        ReadoutOptions {
            scale_range: (0.25, 4.0),
            loss_px: 1.0,
            lm: LmOptions::default(),
        }
    }
}

impl ReadoutOptions {
    /// The first invalid setting, named as in `EstimateOptions` (`readout.scale_range`,
    /// `readout.loss_px`), with what is wrong; `None` if all are valid.
    pub fn invalid(&self) -> Option<(&'static str, &'static str)> {
        let (lo, hi) = self.scale_range;
        if !(lo > 0.0 && lo <= 1.0 && hi >= 1.0 && hi.is_finite()) {
            return Some((
                "readout.scale_range",
                "must be (lo, hi) with 0 < lo <= 1 <= hi",
            ));
        }
        if !(self.loss_px.is_finite() && self.loss_px > 0.0) {
            return Some(("readout.loss_px", "must be finite and positive"));
        }
        None
    }
}

/// The result of [`refine_readout_scale`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReadoutFit {
    /// True readout time over the nominal one (both views).
    pub scale: f64,
    /// Refined rotation `R` (camera 1 to camera 2).
    pub rotation: Matrix3<f64>,
    /// Refined unit translation `t`.
    pub translation: Vector3<f64>,
    /// Robust cost (normalised units squared) at the start: the given pose, nominal readout.
    pub cost_nominal: f64,
    /// Robust cost at the fit.
    pub cost: f64,
    /// LM iterations.
    pub iterations: usize,
}

/// Views with both readout times scaled by `k`.
fn scaled(view: &View, k: f64) -> View {
    let mut v = view.clone();
    v.camera.readout *= k;
    v
}

/// Central-difference step in `ln k` for the Jacobian's last column.
const LN_K_STEP: f64 = 1e-6;

/// `(pose, ln k)` on the inlier matches.
struct ReadoutProblem<'a> {
    views: (&'a View, &'a View),
    /// The kept matches' bearings and line coordinates (independent of the readout time).
    observations: Vec<[Observation; 2]>,
    /// `0..matches.len()`, the indices the pose refinement's problem runs on.
    indices: Vec<usize>,
    loss: Loss,
    ln_range: (f64, f64),
}

impl ReadoutProblem<'_> {
    /// The pose refinement's problem on `d`: every kept match, the exact model's Sampson
    /// error (the residuals of this problem at fixed `k`).
    fn pose_problem<'b>(&'b self, d: &'b PointData) -> PoseProblem<'b> {
        PoseProblem {
            data: d,
            indices: &self.indices,
            model: PoseModel::ExactAngular,
            kind: ResidualKind::Sampson,
            loss: self.loss,
        }
    }

    fn data(&self, ln_k: f64) -> PointData {
        let k = ln_k.exp();
        PointData::from_observations(
            &scaled(self.views.0, k),
            &scaled(self.views.1, k),
            &self.observations,
        )
    }
}

impl LmProblem<6> for ReadoutProblem<'_> {
    type State = (Pose, f64);
    fn num_residuals(&self) -> usize {
        self.observations.len()
    }
    fn residuals(&self, (pose, ln_k): &(Pose, f64), out: &mut [f64]) {
        let d = self.data(*ln_k);
        self.pose_problem(&d).residuals(pose, out);
    }
    fn residuals_and_jacobian(
        &self,
        (pose, ln_k): &(Pose, f64),
        out: &mut [f64],
        jac: &mut [SVector<f64, 6>],
    ) -> bool {
        let n = self.observations.len();
        if out.len() != n || jac.len() != n {
            return false;
        }
        let d = self.data(*ln_k);
        let mut pose_jac = vec![SVector::<f64, 5>::zeros(); n];
        if !self
            .pose_problem(&d)
            .residuals_and_jacobian(pose, out, &mut pose_jac)
        {
            return false;
        }
        let (mut plus, mut minus) = (vec![0.0; n], vec![0.0; n]);
        self.residuals(&(*pose, ln_k + LN_K_STEP), &mut plus);
        self.residuals(&(*pose, ln_k - LN_K_STEP), &mut minus);
        for (i, row) in jac.iter_mut().enumerate() {
            row.fixed_rows_mut::<5>(0).copy_from(&pose_jac[i]);
            row[5] = (plus[i] - minus[i]) / (2.0 * LN_K_STEP);
        }
        true
    }
    fn retract(&self, (pose, ln_k): &(Pose, f64), delta: &SVector<f64, 6>) -> (Pose, f64) {
        (
            pose.retract(&delta.as_slice()[..5]),
            (ln_k + delta[5]).clamp(self.ln_range.0, self.ln_range.1),
        )
    }
    fn loss(&self) -> Loss {
        self.loss
    }
}

/// The observations (bearing and readout line in each image) of the matches flagged in
/// `inliers`, and the two cameras' mean focal length (pixels, to express a loss in pixels):
/// what a refinement of the pose with a rolling-shutter parameter works on. `None` with
/// fewer than 8 inliers or a pixel without a bearing.
pub(crate) fn inlier_observations(
    view1: &View,
    view2: &View,
    matches: &[Match],
    inliers: &[bool],
) -> Option<(Vec<[Observation; 2]>, f64)> {
    let kept: Vec<Match> = matches
        .iter()
        .zip(inliers)
        .filter_map(|(m, &i)| i.then_some(*m))
        .collect();
    if kept.len() < 8 {
        return None;
    }
    let observations = observe_matches(&view1.camera, &view2.camera, &kept).ok()?;
    let f = 0.5 * (view1.camera.mean_focal() + view2.camera.mean_focal());
    Some((observations, f))
}

/// Refines the pose `(rotation, translation)` of `view1`/`view2` (their cameras' readout
/// times nominal) together with a common scale of the readout times, over the matches
/// flagged in `inliers` (see the module documentation). `None` with fewer than 8 inliers,
/// an `inliers` mask of the wrong length, invalid options ([`ReadoutOptions::invalid`]) or
/// a non-finite result.
pub fn refine_readout_scale(
    view1: &View,
    view2: &View,
    matches: &[Match],
    inliers: &[bool],
    rotation: &Matrix3<f64>,
    translation: &Vector3<f64>,
    options: &ReadoutOptions,
) -> Option<ReadoutFit> {
    if inliers.len() != matches.len() || options.invalid().is_some() {
        return None;
    }
    let (lo, hi) = options.scale_range;
    let (observations, f) = inlier_observations(view1, view2, matches, inliers)?;
    let problem = ReadoutProblem {
        views: (view1, view2),
        indices: (0..observations.len()).collect(),
        observations,
        loss: Loss::Cauchy(options.loss_px / f),
        ln_range: (lo.ln(), hi.ln()),
    };
    let res = levenberg_marquardt(
        &problem,
        (Pose::new(rotation, translation), 0.0),
        &options.lm,
    );
    let (pose, ln_k) = res.state;
    let fit = ReadoutFit {
        scale: ln_k.exp(),
        rotation: pose.matrix(),
        translation: pose.translation,
        cost_nominal: res.initial_cost,
        cost: res.cost,
        iterations: res.iterations,
    };
    let finite = fit.scale.is_finite()
        && fit.rotation.iter().all(|x| x.is_finite())
        && fit.translation.iter().all(|x| x.is_finite());
    finite.then_some(fit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::model::geometry::{rotation_error_deg, translation_error_deg};

    #[test]
    fn recovers_the_readout_scale_and_the_pose_from_a_wrong_nominal_readout() {
        for (seed, nominal) in [(3, 1.3), (4, 0.7)] {
            let pair = simulate(&SimulationOptions {
                angular_velocity: 2.5,
                pixel_noise: 0.0,
                gyro_noise: 0.0,
                seed,
                ..Default::default()
            })
            .unwrap();
            let gt = pair.ground_truth.clone().unwrap();
            let (v1, v2) = pair.views().unwrap();
            let (w1, w2) = (scaled(&v1, nominal), scaled(&v2, nominal));
            // Start from the truth perturbed: the readout error is what must be found.
            let start = crate::estimation::refine::tests::perturbed(
                &gt.rotation_matrix(),
                &gt.translation_vector(),
            );
            let all = vec![true; pair.matches.len()];
            let fit = refine_readout_scale(
                &w1,
                &w2,
                &pair.matches,
                &all,
                &start.matrix(),
                &start.translation,
                &ReadoutOptions::default(),
            )
            .unwrap();
            assert!(
                (fit.scale * nominal - 1.0).abs() < 1e-6,
                "{nominal}: {}",
                fit.scale
            );
            assert!(rotation_error_deg(&gt.rotation_matrix(), &fit.rotation) < 1e-5);
            assert!(translation_error_deg(&gt.translation_vector(), &fit.translation) < 1e-4);
            assert!(fit.cost < fit.cost_nominal);
        }
    }

    #[test]
    fn rejects_bad_input() {
        let pair = simulate(&SimulationOptions {
            seed: 1,
            ..Default::default()
        })
        .unwrap();
        let (v1, v2) = pair.views().unwrap();
        let (r, t) = (Matrix3::identity(), Vector3::new(1.0, 0.0, 0.0));
        let n = pair.matches.len();
        let o = ReadoutOptions::default();
        let run = |mask: &[bool], o: &ReadoutOptions| {
            refine_readout_scale(&v1, &v2, &pair.matches, mask, &r, &t, o)
        };
        assert!(run(&vec![true; n - 1], &o).is_none());
        let mut few = vec![false; n];
        few[..7].iter_mut().for_each(|x| *x = true);
        assert!(run(&few, &o).is_none());
        let bad = ReadoutOptions {
            scale_range: (2.0, 4.0),
            ..ReadoutOptions::default()
        };
        assert!(run(&vec![true; n], &bad).is_none());
    }
}
