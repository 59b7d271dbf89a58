//! `rectified+v`: `rectified`'s RANSAC and pose, then a refinement of the pose and both
//! cameras' constant linear velocities `d1`, `d2` on the generalised epipolar model with
//! the gyro's row rotations ([`crate::estimation::velocity`]: each row's rotation from the gyro, each
//! row's centre `C + v λ d`), Sampson-normalised residuals, Cauchy loss, a zero-mean prior on
//! the velocities. The inliers are re-classified with the refined model (the angular model's
//! inliers miss the matches the linear motion moved furthest) and the refinement repeated
//! until they settle ([`VelocityOptions::rounds`]).
//!
//! **Weak observability.** The velocities are determined by how the residuals change with
//! the row; with few points, a narrow field of view or matches read at the same time in
//! both images, some directions of `(d1, d2)` are not. Two safeguards, reported in
//! [`super::Estimate::velocity_fit`]:
//! - the prior `δ ~ N(0, σ_δ²)` on the displacement over a frame (in baselines,
//!   [`VelocityOptions::prior_std`]) pulls undetermined directions to zero
//!   ([`VelocityFit::Regularised`] counts the directions where the prior outweighs the
//!   data);
//! - two tests on the truncated squared Sampson error over every match, `C = Σ min(r², τ²)`
//!   (`τ` = [`VelocityOptions::loss_px`]), in pixel-noise variances. The velocities must
//!   lower `C` below `rectified`'s by more than [`VelocityOptions::significance`] (a χ²
//!   quantile with 6 degrees of freedom: what six free parameters gain on pure noise;
//!   [`VelocityFit::NotSignificant`] otherwise), and by [`VelocityOptions::rate_margin`] more
//!   than the competing explanation with as many parameters does: still cameras whose gyro rates are off by a constant
//!   error of plausible size ([`crate::estimation::velocity::RateErrorProblem`], prior
//!   [`VelocityOptions::rate_error_std`]). A gyro-rate error also grows with the
//!   row, and velocities fitted to it move the translation further than the error itself
//!   did ([`VelocityFit::GyroErrorExplains`] otherwise). Either way, and for global-shutter
//!   views or too few inliers, `rectified`'s estimate is returned with no velocities.

use super::pose_ransac::{indices, point_data, threshold};
use super::{rectified, Estimate, EstimateError, EstimateOptions, Method};
use crate::estimation::refine::{levenberg_marquardt, LmOptions, Loss, Pose};
use crate::estimation::velocity::{
    reference_duration, refine_velocity, velocity_information, RateErrorProblem, RateErrorState,
    VelocityModel, VelocityProblem, VelocityState,
};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, ResidualKind};
use crate::model::matches::Match;
use nalgebra::Vector3;
use serde::Serialize;

/// Settings of the velocity stage of `rectified+v` (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct VelocityOptions {
    /// Prior standard deviation of each camera's displacement over a frame's readout, per
    /// axis, in baselines (default 1: a camera moving a baseline per frame is extreme;
    /// `f64::INFINITY`: no prior). Its weight against the matches is set by
    /// [`super::RobustOptions::pixel_noise`].
    pub prior_std: f64,
    /// Cauchy scale of the refinement and truncation `τ` of the significance test, pixels of
    /// the (row-noise-weighted) Sampson error (default 2.5, the default inlier threshold).
    pub loss_px: f64,
    /// Significance of the velocities: the decrease of the truncated squared error below
    /// `rectified`'s they must bring, in pixel-noise variances (default 22.46, the 99.9 %
    /// quantile of χ² with 6 degrees of freedom).
    pub significance: f64,
    /// Prior standard deviation per axis of the gyro-rate error in the competing
    /// explanation, rad/s (default 0.1, like [`super::RobustOptions::gyro_noise`], which the
    /// paper preset zeroes because its threshold is unweighted; `f64::INFINITY`: unbounded).
    /// Without a bound a large rate error mimics any row-dependent misfit, such as that of a
    /// badly wrong starting pose.
    pub rate_error_std: f64,
    /// How much more than the gyro-rate error the velocities must lower the truncated squared
    /// error, pixel-noise variances (default 12.59, the 95 % quantile of χ² with 6 degrees
    /// of freedom: the two explanations have as many parameters, and when they explain
    /// nearly as much the velocities are as likely fitted to a gyro error).
    pub rate_margin: f64,
    /// Fewer inliers than this: fall back to `rectified` (default 30).
    pub min_inliers: usize,
    /// Refine / re-classify rounds at most (default 4).
    pub rounds: usize,
}

impl Default for VelocityOptions {
    fn default() -> Self {
        VelocityOptions {
            prior_std: 1.0,
            loss_px: 2.5,
            significance: 22.46,
            rate_error_std: 0.1,
            rate_margin: 12.59,
            min_inliers: 30,
            rounds: 4,
        }
    }
}

impl VelocityOptions {
    pub(crate) fn validate(&self) -> Result<(), EstimateError> {
        let bad = |option, reason: &str| {
            Err(EstimateError::InvalidOption {
                option,
                reason: reason.into(),
            })
        };
        for (name, x) in [
            ("velocity.prior_std", self.prior_std),
            ("velocity.rate_error_std", self.rate_error_std),
        ] {
            if x.is_nan() || x <= 0.0 {
                return bad(name, "must be positive (infinity: no prior)");
            }
        }
        if !(self.loss_px.is_finite() && self.loss_px > 0.0) {
            return bad("velocity.loss_px", "must be finite and positive");
        }
        for (name, x) in [
            ("velocity.significance", self.significance),
            ("velocity.rate_margin", self.rate_margin),
        ] {
            if !(x.is_finite() && x >= 0.0) {
                return bad(name, "must be finite and non-negative");
            }
        }
        if self.rounds == 0 {
            return bad("velocity.rounds", "must be at least 1");
        }
        Ok(())
    }
}

/// What the velocity stage of `rectified+v` did. `statistic` is the decrease of the
/// truncated squared Sampson error below `rectified`'s that the velocities bring,
/// `rate_statistic` the decrease a constant gyro-rate error per camera brings instead, both
/// in pixel-noise variances.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "outcome", rename_all = "snake_case")]
pub enum VelocityFit {
    /// Velocities estimated; the data determine every direction of `(d1, d2)`.
    Estimated {
        /// Decrease by the velocities.
        statistic: f64,
        /// Decrease by a gyro-rate error.
        rate_statistic: f64,
    },
    /// Velocities estimated, but in `prior_dominated` of the six directions of `(d1, d2)`
    /// the prior outweighs the data (those stay near zero).
    Regularised {
        /// Decrease by the velocities.
        statistic: f64,
        /// Decrease by a gyro-rate error.
        rate_statistic: f64,
        /// Directions decided by the prior.
        prior_dominated: usize,
    },
    /// Fallback to `rectified`: both views are global-shutter (readout 0).
    NoReadout,
    /// Fallback to `rectified`: fewer inliers than [`VelocityOptions::min_inliers`].
    TooFewInliers {
        /// Inliers.
        inliers: usize,
    },
    /// Fallback to `rectified`: the velocities do not explain the data significantly
    /// better ([`VelocityOptions::significance`]).
    NotSignificant {
        /// Decrease by the velocities.
        statistic: f64,
    },
    /// Fallback to `rectified`: a camera's fitted displacement over the reference duration
    /// exceeds 4 prior standard deviations ([`VelocityOptions::prior_std`]): the refinement
    /// left the starting pose's basin.
    Implausible {
        /// The larger displacement, baselines.
        displacement: f64,
    },
    /// Fallback to `rectified`: a constant gyro-rate error explains the data nearly as well
    /// as the velocities, or better ([`VelocityOptions::rate_margin`]).
    GyroErrorExplains {
        /// Decrease by the velocities.
        statistic: f64,
        /// Decrease by a gyro-rate error.
        rate_statistic: f64,
    },
}

impl VelocityFit {
    /// True if `rectified`'s estimate was returned (no velocities).
    pub fn fell_back(&self) -> bool {
        !matches!(
            self,
            VelocityFit::Estimated { .. } | VelocityFit::Regularised { .. }
        )
    }

    /// A one-line description, e.g. `regularised: 2 of 6 directions by the prior`.
    pub fn describe(&self) -> String {
        let tests = |v: &f64, g: &f64| format!("velocities {v:.1}, gyro-rate error {g:.1}");
        match self {
            VelocityFit::Estimated {
                statistic,
                rate_statistic,
            } => format!("estimated ({})", tests(statistic, rate_statistic)),
            VelocityFit::Regularised {
                statistic,
                rate_statistic,
                prior_dominated,
            } => format!(
                "regularised: {prior_dominated} of 6 directions by the prior ({})",
                tests(statistic, rate_statistic)
            ),
            VelocityFit::NoReadout => "fallback to rectified: global-shutter views".into(),
            VelocityFit::TooFewInliers { inliers } => {
                format!("fallback to rectified: {inliers} inliers")
            }
            VelocityFit::NotSignificant { statistic } => {
                format!("fallback to rectified: velocities not significant ({statistic:.1})")
            }
            VelocityFit::Implausible { displacement } => format!(
                "fallback to rectified: implausible displacement ({displacement:.2} baselines per frame)"
            ),
            VelocityFit::GyroErrorExplains {
                statistic,
                rate_statistic,
            } => format!(
                "fallback to rectified: a gyro-rate error explains as much ({})",
                tests(statistic, rate_statistic)
            ),
        }
    }
}

/// Largest displacement over the reference duration, in [`VelocityOptions::prior_std`]s,
/// that the velocity stage accepts. The prior is per axis, so the norm of a displacement it
/// supports exceeds 4 of them with probability about 0.1 %; beyond that the refinement has
/// left the basin of the starting pose (it can turn `t` around and fit the misfit with
/// velocities several baselines per frame), which cheirality cannot detect: that state is
/// self-consistent.
const IMPLAUSIBLE_DISPLACEMENT: f64 = 4.0;

/// `λ_c / T` of each view ([`crate::estimation::velocity::VelocityModel::new`]); `None` for two
/// global-shutter views.
pub(crate) fn row_times(view1: &View, view2: &View) -> Option<[f64; 2]> {
    let t = reference_duration(view1, view2);
    (t > 0.0).then(|| [view1.camera.readout / t, view2.camera.readout / t])
}

/// The velocity stage's fixed inputs.
struct Stage<'a> {
    data: &'a PointData,
    row_time: [f64; 2],
    loss: Loss,
    prior: f64,
    /// Inlier test of the method's threshold.
    kind: ResidualKind,
    thr_sq: f64,
    lm: LmOptions,
}

impl Stage<'_> {
    fn problem<'b>(&'b self, idx: &'b [usize]) -> VelocityProblem<'b> {
        VelocityProblem {
            data: self.data,
            indices: idx,
            row_time: self.row_time,
            loss: self.loss,
            prior: self.prior,
        }
    }

    /// Indices of the points within the threshold under `state`.
    fn classify(&self, state: &VelocityState) -> Vec<usize> {
        let model = VelocityModel::new(state, self.row_time);
        (0..self.data.len())
            .filter(|&i| {
                let x = model.residual(self.data, self.kind, i);
                x * x < self.thr_sq
            })
            .collect()
    }

    /// Directions of `(δ1, δ2)` where the data's information is below the prior's (without
    /// a prior: numerically zero).
    fn prior_dominated(&self, idx: &[usize], state: &VelocityState) -> usize {
        velocity_information(&self.problem(idx), state).map_or(6, |info| {
            let eig = info.symmetric_eigenvalues();
            let floor = (self.prior * self.prior).max(1e-12 * eig.amax());
            eig.iter().filter(|&&x| x <= floor).count()
        })
    }
}

/// Estimate with `rectified+v`.
///
/// The input is not checked here: it must be what [`super::validate_input`] accepts with
/// `options.method` = `rectified+v` (valid views, finite pixels that have bearings, at
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
    let data = point_data(view1, view2, matches, &options.robust)?;
    let base = Estimate {
        method: Method::RectifiedV,
        ..rectified::run_on(&data, view1, view2, options)?
    };
    let fallback = |fit| {
        Ok(Estimate {
            velocity_fit: Some(fit),
            ..base.clone()
        })
    };
    let Some(row_time) = row_times(view1, view2) else {
        return fallback(VelocityFit::NoReadout);
    };
    let vo = &options.velocity;
    let f = 0.5 * (view1.camera.mean_focal() + view2.camera.mean_focal());
    let sigma = options.robust.pixel_noise / f;
    let (kind, thr_sq) = threshold(view1, view2, options.robust.threshold);
    let stage = Stage {
        data: &data,
        row_time,
        loss: Loss::Cauchy(vo.loss_px / f),
        prior: sigma / vo.prior_std,
        kind,
        thr_sq,
        lm: LmOptions {
            max_iterations: options.refinement.max_iterations.max(100),
            ..options.refinement.clone()
        },
    };
    let start = VelocityState::still(Pose::new(&base.rotation, &base.translation));
    let mut state = start;
    let mut idx = indices(&base.inliers);
    let (mut iterations, mut cost) = (0, 0.0);
    for _ in 0..vo.rounds {
        if idx.len() < vo.min_inliers {
            break;
        }
        let r = refine_velocity(&stage.problem(&idx), state, &stage.lm);
        (state, iterations, cost) = (r.state, iterations + r.iterations, r.cost);
        let next = stage.classify(&state);
        if next == idx {
            break;
        }
        idx = next;
    }
    if idx.len() < vo.min_inliers {
        return fallback(VelocityFit::TooFewInliers { inliers: idx.len() });
    }
    // The tests, in pixel-noise variances.
    let tau_sq = (vo.loss_px / f).powi(2);
    let null = VelocityModel::new(&start, row_time).truncated_cost(&data, tau_sq);
    let with_velocity = VelocityModel::new(&state, row_time).truncated_cost(&data, tau_sq);
    let statistic = (null - with_velocity) / (sigma * sigma);
    if statistic.is_nan() || statistic <= vo.significance {
        return fallback(VelocityFit::NotSignificant { statistic });
    }
    let rates = RateErrorProblem {
        data: &data,
        indices: &idx,
        row_time,
        loss: stage.loss,
        prior: sigma / (vo.rate_error_std * reference_duration(view1, view2)),
    };
    let still = RateErrorState {
        pose: start.pose,
        rate: [Vector3::zeros(); 2],
    };
    let fitted = levenberg_marquardt(&rates, still, &stage.lm).state;
    let rate_statistic = (null - rates.truncated_cost(&fitted, tau_sq)) / (sigma * sigma);
    if statistic <= rate_statistic + vo.rate_margin {
        return fallback(VelocityFit::GyroErrorExplains {
            statistic,
            rate_statistic,
        });
    }
    let displacement = state.delta[0].norm().max(state.delta[1].norm());
    if displacement > IMPLAUSIBLE_DISPLACEMENT * vo.prior_std {
        return fallback(VelocityFit::Implausible { displacement });
    }
    let fit = match stage.prior_dominated(&idx, &state) {
        0 => VelocityFit::Estimated {
            statistic,
            rate_statistic,
        },
        prior_dominated => VelocityFit::Regularised {
            statistic,
            rate_statistic,
            prior_dominated,
        },
    };
    let r = state.pose.matrix();
    // The model is homogeneous in (t, δ1, δ2), so the refinement cannot decide their common
    // sign: cheirality does, with the rays from the moving centres the velocities give.
    let (front, behind) = VelocityModel::new(&state, row_time).cheirality_counts(&data, &idx);
    let sign = if behind > front { -1.0 } else { 1.0 };
    let t = state.pose.translation * sign;
    let duration = reference_duration(view1, view2);
    let mut inliers = vec![false; data.len()];
    for &i in &idx {
        inliers[i] = true;
    }
    Ok(Estimate {
        rotation: r,
        translation: t,
        inliers,
        refinement_iterations: base.refinement_iterations + iterations,
        refinement_cost: Some(cost),
        linear_velocity: Some(state.delta.map(|d| d * (sign / duration))),
        velocity_fit: Some(fit),
        noise_fit: None,
        ..base
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::pair_file::PairFile;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::experiment::evaluate::pose_errors;
    use crate::model::camera::Camera;
    use crate::{estimate_relative_pose, Method};

    fn run(p: &PairFile, o: &EstimateOptions) -> Estimate {
        let (v1, v2) = p.views().unwrap();
        estimate_relative_pose(&v1, &v2, &p.matches, o).unwrap()
    }

    /// `[d1; d2]` estimated (baselines/s) against the truth (m/s): the estimate must be the
    /// truth divided by the baseline. Returns the relative misfit after the best positive
    /// scale.
    fn velocity_misfit(est: &[Vector3<f64>; 2], truth: &[[f64; 3]; 2]) -> f64 {
        let g: Vec<f64> = truth.iter().flatten().copied().collect();
        let e: Vec<f64> = est.iter().flat_map(|v| v.iter().copied()).collect();
        let s = g.iter().zip(&e).map(|(a, b)| a * b).sum::<f64>()
            / g.iter().map(|a| a * a).sum::<f64>();
        assert!(s > 0.0, "velocity scale {s}");
        let r: f64 = g
            .iter()
            .zip(&e)
            .map(|(a, b)| (b - s * a).powi(2))
            .sum::<f64>()
            .sqrt();
        r / e.iter().map(|b| b * b).sum::<f64>().sqrt()
    }

    /// Noise-free matches of cameras turning at 2.5 rad/s and moving at 20 m/s: without a
    /// prior the model recovers the pose and both velocities exactly, with the default
    /// prior nearly so, where `rectified` (no linear motion) is off by degrees.
    #[test]
    fn recovers_pose_and_velocities_on_noise_free_data() {
        for seed in [1, 2, 3] {
            let p = simulate(&SimulationOptions {
                pixel_noise: 0.0,
                gyro_noise: 0.0,
                linear_velocity: 20.0,
                seed,
                ..Default::default()
            })
            .unwrap();
            let gt = p.ground_truth.as_ref().unwrap();
            let rect = pose_errors(
                &run(&p, &EstimateOptions::for_method(Method::Rectified)),
                gt,
            );
            assert!(rect.translation_error_deg > 3.0, "{rect:?}");
            let mut o = EstimateOptions::for_method(Method::RectifiedV);
            o.velocity.prior_std = f64::INFINITY;
            let e = run(&p, &o);
            assert!(matches!(
                e.velocity_fit,
                Some(VelocityFit::Estimated { .. })
            ));
            let err = pose_errors(&e, gt);
            assert!(err.rotation_error_deg < 1e-6, "{err:?}");
            assert!(err.translation_error_deg < 1e-6, "{err:?}");
            let misfit = velocity_misfit(&e.linear_velocity.unwrap(), &gt.velocity);
            assert!(misfit < 1e-6, "{misfit}");
            assert_eq!(e.num_inliers(), p.matches.len());
            let e = run(&p, &EstimateOptions::for_method(Method::RectifiedV));
            assert!(!e.velocity_fit.unwrap().fell_back());
            let err = pose_errors(&e, gt);
            assert!(err.rotation_error_deg < 0.01, "{err:?}");
            assert!(err.translation_error_deg < 0.1, "{err:?}");
            assert!(velocity_misfit(&e.linear_velocity.unwrap(), &gt.velocity) < 0.5);
        }
    }

    /// Without linear motion the velocities fit only noise and the gyro's error: the test
    /// rejects them and `rectified`'s estimate is returned unchanged.
    #[test]
    fn falls_back_to_rectified_without_linear_velocity() {
        for seed in [1, 2, 3] {
            let p = simulate(&SimulationOptions {
                seed,
                ..Default::default()
            })
            .unwrap();
            for o in [EstimateOptions::for_method, EstimateOptions::paper] {
                let rect = run(&p, &o(Method::Rectified));
                let e = run(&p, &o(Method::RectifiedV));
                let fit = e.velocity_fit.unwrap();
                assert!(fit.fell_back(), "seed {seed}: {}", fit.describe());
                assert_eq!(e.linear_velocity, None);
                assert_eq!(
                    (e.rotation, e.translation),
                    (rect.rotation, rect.translation)
                );
                assert_eq!(e.inliers, rect.inliers);
            }
        }
    }

    #[test]
    fn few_inliers_and_global_shutter_views_fall_back() {
        let p = simulate(&SimulationOptions {
            points: 25,
            linear_velocity: 20.0,
            seed: 4,
            ..Default::default()
        })
        .unwrap();
        let fit = run(&p, &EstimateOptions::for_method(Method::RectifiedV)).velocity_fit;
        assert!(matches!(fit, Some(VelocityFit::TooFewInliers { inliers }) if inliers < 30));
        let p = simulate(&SimulationOptions {
            camera: Camera {
                readout: 0.0,
                ..Camera::paper()
            },
            linear_velocity: 20.0,
            seed: 4,
            ..Default::default()
        })
        .unwrap();
        let fit = run(&p, &EstimateOptions::for_method(Method::RectifiedV)).velocity_fit;
        assert_eq!(fit, Some(VelocityFit::NoReadout));
    }

    /// Above `max_points` the velocities come from a subset and every match is classified
    /// with them: the linear motion that moved late rows' matches off the angular model must
    /// not make them outliers.
    #[test]
    fn large_inputs_are_classified_with_the_velocities() {
        let p = simulate(&SimulationOptions {
            points: 1500,
            outlier_fraction: 0.3,
            linear_velocity: 12.0,
            angular_velocity: 1.5,
            seed: 6,
            ..Default::default()
        })
        .unwrap();
        let gt = p.ground_truth.as_ref().unwrap();
        let mut o = EstimateOptions::for_method(Method::RectifiedV);
        o.robust.max_points = 300;
        let e = run(&p, &o);
        assert!(!e.velocity_fit.unwrap().fell_back());
        assert_eq!(e.inliers.len(), p.matches.len());
        let count = |want: bool| {
            (0..p.matches.len())
                .filter(|&i| gt.inliers[i] == want && e.inliers[i])
                .count()
        };
        let rect = run(
            &p,
            &EstimateOptions {
                method: Method::Rectified,
                ..o.clone()
            },
        );
        let rect_kept = (0..p.matches.len())
            .filter(|&i| gt.inliers[i] && rect.inliers[i])
            .count();
        assert!(count(true) > 1000, "{} true inliers kept", count(true));
        assert!(count(true) > rect_kept, "{} vs {rect_kept}", count(true));
        assert!(count(false) < 30, "{} outliers accepted", count(false));
    }

    /// A narrow field of view (f = 4000 px: 27° across) leaves the velocities nearly
    /// indistinguishable from a gyro-rate error and from the translation: fewer directions
    /// of them are determined (more are the prior's, or the method falls back), and what is
    /// returned is on average no worse than `rectified`.
    #[test]
    fn a_narrow_field_of_view_is_reported() {
        let (mut weak, mut total, mut err_v, mut err_r) = ([0; 2], [0; 2], 0.0, 0.0);
        for (k, f) in [640.0, 4000.0].into_iter().enumerate() {
            for seed in 0..8 {
                let Ok(p) = simulate(&SimulationOptions {
                    camera: Camera {
                        fx: f,
                        fy: f,
                        ..Camera::paper()
                    },
                    points: 60,
                    linear_velocity: 20.0,
                    seed,
                    ..Default::default()
                }) else {
                    continue;
                };
                let gt = p.ground_truth.as_ref().unwrap();
                let rect = run(&p, &EstimateOptions::for_method(Method::Rectified));
                let e = run(&p, &EstimateOptions::for_method(Method::RectifiedV));
                let fit = e.velocity_fit.unwrap();
                total[k] += 6;
                weak[k] += match fit {
                    VelocityFit::Estimated { .. } => 0,
                    VelocityFit::Regularised {
                        prior_dominated, ..
                    } => prior_dominated,
                    _ => 6,
                };
                if k == 1 {
                    err_v += pose_errors(&e, gt).translation_error_deg;
                    err_r += pose_errors(&rect, gt).translation_error_deg;
                }
            }
        }
        let share = |k: usize| weak[k] as f64 / total[k].max(1) as f64;
        assert!(total[1] >= 18, "{total:?}");
        assert!(share(1) > 2.0 * share(0), "{weak:?} of {total:?}");
        assert!(err_v <= err_r, "{err_v} vs {err_r}");
    }
}
