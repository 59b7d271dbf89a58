//! A constant gyro bias shared by the two frames, refined with their pose.
//!
//! The views' row rotations `Ω(v)` are integrated from the gyro's rate (ARCHITECTURE §4:
//! what a gyroscope reports, camera axes, rad/s). A constant bias `b` of that rate leaves
//! row `v`'s bearing rotated by about `v λ b`, so the exact angular model's Sampson residuals
//! ([`PoseModel::ExactAngular`]) grow with the row. Given a pose and its inliers (from any
//! gyro-aided method run with the rates as given), Levenberg-Marquardt refines `(R, t)` and
//! one bias `b` (camera axes, rad/s) common to both views, whose row rotations are
//! recomputed from `rate − b` (the constant rate, or each segment of an integrated gyro
//! track, [`RowTrack::with_bias`](crate::model::gyro_log::RowTrack::with_bias)). The two frames are a fraction of a second apart, so
//! one bias serves both; a per-frame rate error is not a bias and is not modelled.
//!
//! The cost is the Sampson error over the inliers with a Cauchy loss at the pixel noise;
//! `b` is kept within [`GyroBiasOptions::max_bias`]. The Jacobian in `(R, t)` is the pose
//! refinement's analytic one ([`PoseProblem`]) at the current `b`; the three bias columns
//! are central differences.
//!
//! `b` is observable only through the rolling-shutter rotations within each frame (the
//! rotation between the frames is the pose's), so it is weakly determined: the distortion
//! it causes is `f H λ |b|` pixels at the last row. A per-view rate noise comparable to the
//! bias is indistinguishable from it; the fit then returns the mean of bias and noise.

use crate::estimation::readout::inlier_observations;
use crate::estimation::refine::{
    levenberg_marquardt, LmOptions, LmProblem, Loss, Pose, PoseProblem,
};
use crate::model::camera::{Observation, View};
use crate::model::epipolar::{PointData, PoseModel, ResidualKind};
use crate::model::matches::Match;
use nalgebra::{Matrix3, SVector, Vector3};
use std::sync::Arc;

/// Settings of [`refine_gyro_bias`].
#[derive(Debug, Clone, PartialEq)]
pub struct GyroBiasOptions {
    /// The largest bias norm the fit may reach, rad/s (default 0.5: a MEMS gyroscope's
    /// uncalibrated bias is far below; the bound keeps a poorly conditioned fit in range).
    pub max_bias: f64,
    /// Scale of the Cauchy loss, pixels (default 1: the simulator's and a typical matcher's
    /// noise).
    pub loss_px: f64,
    /// Levenberg-Marquardt settings (default: [`LmOptions::default`]).
    pub lm: LmOptions,
}

impl Default for GyroBiasOptions {
    fn default() -> Self {
        GyroBiasOptions {
            max_bias: 0.5,
            loss_px: 1.0,
            lm: LmOptions::default(),
        }
    }
}

impl GyroBiasOptions {
    /// The first invalid setting, named as in `EstimateOptions` (`gyro_bias.max_bias`,
    /// `gyro_bias.loss_px`), with what is wrong; `None` if all are valid.
    pub fn invalid(&self) -> Option<(&'static str, &'static str)> {
        if !(self.max_bias.is_finite() && self.max_bias > 0.0) {
            return Some(("gyro_bias.max_bias", "must be finite and positive"));
        }
        if !(self.loss_px.is_finite() && self.loss_px > 0.0) {
            return Some(("gyro_bias.loss_px", "must be finite and positive"));
        }
        None
    }
}

/// The result of [`refine_gyro_bias`].
#[derive(Debug, Clone, PartialEq)]
pub struct GyroBiasFit {
    /// The bias of the views' rates, camera axes, rad/s: the true rate is the views' minus
    /// this (on top of any bias the pair file already removed).
    pub bias: Vector3<f64>,
    /// Refined rotation `R` (camera 1 to camera 2).
    pub rotation: Matrix3<f64>,
    /// Refined unit translation `t`.
    pub translation: Vector3<f64>,
    /// Robust cost (normalised units squared) at the start: the given pose, no bias.
    pub cost_initial: f64,
    /// Robust cost at the fit.
    pub cost: f64,
    /// LM iterations.
    pub iterations: usize,
    /// Standard deviation of each bias component, rad/s, from the Gauss-Newton covariance
    /// at the fit, `σ² (JᵀJ)⁻¹` with `σ²` the residuals' mean square over `n − 8` (the
    /// robust loss ignored): how well the pair determines the bias. Infinite when `JᵀJ` is
    /// singular.
    pub std: Vector3<f64>,
}

/// The bias reported in an [`crate::methods::Estimate`]: the value and its standard
/// deviation per axis ([`GyroBiasFit::bias`], [`GyroBiasFit::std`]), camera axes, rad/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EstimatedBias {
    /// The bias of the views' rates (true rate = the views' rate − this).
    pub bias: Vector3<f64>,
    /// Its standard deviation per axis.
    pub std: Vector3<f64>,
}

/// `view` with its rate, and its integrated track where it has one, less `bias` (camera
/// axes, rad/s).
pub fn unbiased_view(view: &View, bias: &Vector3<f64>) -> View {
    let mut v = view.clone();
    v.omega -= bias;
    if let Some(track) = &view.track {
        v.track = Some(Arc::new(track.with_bias(bias)));
    }
    v
}

/// Central-difference step of the bias columns, rad/s.
const BIAS_STEP: f64 = 1e-6;

/// `(pose, b)` on the inlier matches.
struct BiasProblem<'a> {
    views: (&'a View, &'a View),
    /// The kept matches' bearings and line coordinates (independent of the rates).
    observations: Vec<[Observation; 2]>,
    /// `0..observations.len()`, the indices the pose refinement's problem runs on.
    indices: Vec<usize>,
    loss: Loss,
    max_bias: f64,
}

impl BiasProblem<'_> {
    /// The pose refinement's problem on `d`: every kept match, the exact model's Sampson
    /// error (the residuals of this problem at fixed `b`).
    fn pose_problem<'b>(&'b self, d: &'b PointData) -> PoseProblem<'b> {
        PoseProblem {
            data: d,
            indices: &self.indices,
            model: PoseModel::ExactAngular,
            kind: ResidualKind::Sampson,
            loss: self.loss,
        }
    }

    fn data(&self, b: &Vector3<f64>) -> PointData {
        PointData::from_observations(
            &unbiased_view(self.views.0, b),
            &unbiased_view(self.views.1, b),
            &self.observations,
        )
    }
}

impl LmProblem<8> for BiasProblem<'_> {
    type State = (Pose, Vector3<f64>);
    fn num_residuals(&self) -> usize {
        self.observations.len()
    }
    fn residuals(&self, (pose, b): &(Pose, Vector3<f64>), out: &mut [f64]) {
        let d = self.data(b);
        self.pose_problem(&d).residuals(pose, out);
    }
    fn residuals_and_jacobian(
        &self,
        (pose, b): &(Pose, Vector3<f64>),
        out: &mut [f64],
        jac: &mut [SVector<f64, 8>],
    ) -> bool {
        let n = self.observations.len();
        if out.len() != n || jac.len() != n {
            return false;
        }
        let d = self.data(b);
        let mut pose_jac = vec![SVector::<f64, 5>::zeros(); n];
        if !self
            .pose_problem(&d)
            .residuals_and_jacobian(pose, out, &mut pose_jac)
        {
            return false;
        }
        for (i, row) in jac.iter_mut().enumerate() {
            row.fixed_rows_mut::<5>(0).copy_from(&pose_jac[i]);
        }
        let (mut plus, mut minus) = (vec![0.0; n], vec![0.0; n]);
        for axis in 0..3 {
            let mut step = Vector3::zeros();
            step[axis] = BIAS_STEP;
            self.residuals(&(*pose, b + step), &mut plus);
            self.residuals(&(*pose, b - step), &mut minus);
            for (i, row) in jac.iter_mut().enumerate() {
                row[5 + axis] = (plus[i] - minus[i]) / (2.0 * BIAS_STEP);
            }
        }
        true
    }
    fn retract(
        &self,
        (pose, b): &(Pose, Vector3<f64>),
        delta: &SVector<f64, 8>,
    ) -> (Pose, Vector3<f64>) {
        let mut next = b + Vector3::new(delta[5], delta[6], delta[7]);
        let norm = next.norm();
        if norm > self.max_bias {
            next *= self.max_bias / norm;
        }
        (pose.retract(&delta.as_slice()[..5]), next)
    }
    fn loss(&self) -> Loss {
        self.loss
    }
}

/// The bias's standard deviation at `state` (see [`GyroBiasFit::std`]).
fn bias_std(problem: &BiasProblem, state: &(Pose, Vector3<f64>)) -> Vector3<f64> {
    let n = problem.num_residuals();
    let mut r = vec![0.0; n];
    let mut jac = vec![SVector::<f64, 8>::zeros(); n];
    let unknown = Vector3::repeat(f64::INFINITY);
    if n <= 8 || !problem.residuals_and_jacobian(state, &mut r, &mut jac) {
        return unknown;
    }
    let mut h = nalgebra::SMatrix::<f64, 8, 8>::zeros();
    for j in &jac {
        h += j * j.transpose();
    }
    let sigma2 = r.iter().map(|x| x * x).sum::<f64>() / (n - 8) as f64;
    match h.try_inverse() {
        Some(cov) => Vector3::from_fn(|i, _| (sigma2 * cov[(5 + i, 5 + i)]).max(0.0).sqrt()),
        None => unknown,
    }
}

/// Refines the pose `(rotation, translation)` of `view1`/`view2` together with a gyro bias
/// common to both views (camera axes, rad/s), over the matches flagged in `inliers` (see the
/// module documentation). `None` with fewer than 8 inliers, an `inliers` mask of the wrong
/// length, invalid options ([`GyroBiasOptions::invalid`]), pixels without a bearing or a
/// non-finite result.
pub fn refine_gyro_bias(
    view1: &View,
    view2: &View,
    matches: &[Match],
    inliers: &[bool],
    rotation: &Matrix3<f64>,
    translation: &Vector3<f64>,
    options: &GyroBiasOptions,
) -> Option<GyroBiasFit> {
    if inliers.len() != matches.len() || options.invalid().is_some() {
        return None;
    }
    let (observations, f) = inlier_observations(view1, view2, matches, inliers)?;
    let problem = BiasProblem {
        views: (view1, view2),
        indices: (0..observations.len()).collect(),
        observations,
        loss: Loss::Cauchy(options.loss_px / f),
        max_bias: options.max_bias,
    };
    let res = levenberg_marquardt(
        &problem,
        (Pose::new(rotation, translation), Vector3::zeros()),
        &options.lm,
    );
    let (pose, bias) = res.state;
    let std = bias_std(&problem, &res.state);
    let fit = GyroBiasFit {
        bias,
        rotation: pose.matrix(),
        translation: pose.translation,
        cost_initial: res.initial_cost,
        cost: res.cost,
        iterations: res.iterations,
        std,
    };
    let finite = fit.bias.iter().all(|x| x.is_finite())
        && fit.rotation.iter().all(|x| x.is_finite())
        && fit.translation.iter().all(|x| x.is_finite());
    finite.then_some(fit)
}

#[cfg(test)]
mod tests;
