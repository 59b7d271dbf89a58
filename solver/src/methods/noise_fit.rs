//! The gyro-rate noise of a pair, fitted to the residuals of its final pose, and the final
//! inlier classification with it.
//!
//! A gyro-rate error `δω` rotates row `v` by about `vλ δω`, so a match's Sampson residual has
//! the variance `σ_i² = σ_px² + (λ σ_ω)² (v1² + v2²)` (`epipolar::PointData::noise_variance`).
//! The options' `gyro_noise` is a prior guess of `σ_ω`; a real gyro, or one pair of frames,
//! may be several times better or worse, and a threshold sized by a wrong guess either drops
//! the late rows of every true match or accepts outliers there. Given the final pose, the
//! residuals of all matches follow a mixture of the inliers' zero-mean normal with variance
//! `σ_i²(σ_ω)` and the outliers' uniform density over the image; expectation-maximisation
//! on that mixture (Dempster, Laird and Rubin 1977) yields `σ_ω` and the inlier fraction,
//! and the matches are then classified with the fitted `σ_ω` at the options' threshold in
//! standard deviations.

use super::pose_ransac::{indices, row_noise, Hypothesis};
use super::{EstimateOptions, RobustOptions};
use crate::estimation::refine::{refine_pose, Loss};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, PoseModel, ResidualKind, RowNoise};

/// Smallest and largest gyro-rate noise the fit considers, rad/s per axis (a hundredth of
/// a good MEMS gyro's noise to far beyond the rates the library accepts as plausible).
const RATE_RANGE: (f64, f64) = (1e-4, 20.0);

/// Smallest and largest scale of the paper model's truncation term.
const TRUNCATION_RANGE: (f64, f64) = (1e-3, 1.0);

/// Expectation-maximisation rounds (the fit has at most two parameters and converges in a
/// few).
const EM_ROUNDS: usize = 30;

/// Golden-section steps of each maximisation over a logarithm (resolution below 1e-6 of the
/// log range).
const GOLDEN_STEPS: usize = 40;

/// The noise model fitted to a pair's residuals under its final pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseFit {
    /// Gyro-rate noise, rad/s per axis, that explains the residuals the final pose leaves
    /// (the part of a frame's rate error the pose absorbs does not show in them).
    pub gyro_noise: f64,
    /// Scale of the paper model's truncation term (`grsrp`, `grsrp+`; 1 for the exact
    /// model, which has none): the bound `(v |w|)² / 2` times this is its standard deviation.
    pub truncation: f64,
}

impl NoiseFit {
    /// The per-match noise model, with pixel noise `pixel_noise` (px).
    pub(crate) fn row_noise(&self, view1: &View, view2: &View, pixel_noise: f64) -> RowNoise {
        RowNoise {
            truncation: self.truncation,
            ..row_noise(view1, view2, pixel_noise, self.gyro_noise)
        }
    }
}

/// The noise model of a pair fitted to `sq`, the squared unweighted Sampson residuals of its
/// matches under its final pose and `model` (normalised units; non-finite ones are left
/// out), with pixel noise `pixel` (normalised units, kept) and starting from the gyro-rate
/// noise `gyro_noise` (rad/s): the gyro-rate noise, and for the paper's model also the
/// scale of its truncation term. `None` when the rows carry no gyro noise (zero readout: a
/// global-shutter camera) or fewer than ten residuals are finite.
pub(crate) fn fit_noise(
    data: &PointData,
    (view1, view2): (&View, &View),
    model: PoseModel,
    sq: &[f64],
    (pixel, gyro_noise): (f64, f64),
) -> Option<NoiseFit> {
    let readout = view1.camera.readout.max(view2.camera.readout);
    if readout <= 0.0 || pixel <= 0.0 || model == PoseModel::GlobalShutter {
        return None;
    }
    let (finite, sq): (Vec<usize>, Vec<f64>) = sq
        .iter()
        .enumerate()
        .filter(|(_, x2)| x2.is_finite())
        .unzip();
    if sq.len() < 10 {
        return None;
    }
    // Outliers' residuals spread over about the image: uniform on [-B, B], B the half
    // diagonal in normalised units.
    let f = 0.5 * (view1.camera.mean_focal() + view2.camera.mean_focal());
    let half_diagonal = 0.5 * view1.camera.width.hypot(view1.camera.height) / f;
    let outlier_density = 1.0 / (2.0 * half_diagonal);
    // σ_i² is linear in σ_px², (λσ_ω)² and the truncation scale squared: split it once into
    // its three per-match terms so that the search costs a few multiplications a match.
    let term = |pixel, rate_per_row, truncation, i| {
        let noise = RowNoise {
            pixel,
            rate_per_row,
            truncation,
        };
        data.noise_variance(noise, model, i)
    };
    let terms: Vec<[f64; 3]> = finite
        .iter()
        .map(|&i| {
            [
                term(pixel, 0.0, 0.0, i),
                term(0.0, 1.0, 0.0, i),
                term(0.0, 0.0, 1.0, i),
            ]
        })
        .collect();
    let variance = |fit: NoiseFit, k: usize| {
        let [p2, rows, truncation] = terms[k];
        let rate = fit.gyro_noise * readout;
        p2 + rate * rate * rows + fit.truncation * fit.truncation * truncation
    };
    let log_normal = |x2: f64, var: f64| -0.5 * (x2 / var + var.ln() + std::f64::consts::TAU.ln());
    let mut fit = NoiseFit {
        gyro_noise: gyro_noise.clamp(RATE_RANGE.0, RATE_RANGE.1),
        truncation: 1.0,
    };
    let fit_truncation = model == PoseModel::PaperLinear;
    let mut inlier_fraction = 0.5;
    let mut posterior = vec![0.0; sq.len()];
    for _ in 0..EM_ROUNDS {
        // Expectation: each residual's probability of being an inlier.
        for (k, &x2) in sq.iter().enumerate() {
            let p_in = inlier_fraction * log_normal(x2, variance(fit, k)).exp();
            let p_out = (1.0 - inlier_fraction) * outlier_density;
            posterior[k] = if p_in + p_out > 0.0 {
                p_in / (p_in + p_out)
            } else {
                0.0
            };
        }
        let total: f64 = posterior.iter().sum();
        inlier_fraction = (total / sq.len() as f64).clamp(1e-3, 1.0 - 1e-9);
        // Maximisation: the posterior-weighted normal log-likelihood, one parameter at a
        // time by golden-section search on its logarithm (each variance term grows with its
        // parameter, so each one-dimensional objective is unimodal in practice).
        let likelihood = |fit: NoiseFit| {
            sq.iter()
                .zip(&posterior)
                .enumerate()
                .map(|(k, (&x2, &w))| w * log_normal(x2, variance(fit, k)))
                .sum::<f64>()
        };
        let mut next = fit;
        next.gyro_noise = golden_section_max(
            |ln| {
                likelihood(NoiseFit {
                    gyro_noise: ln.exp(),
                    ..next
                })
            },
            RATE_RANGE.0.ln(),
            RATE_RANGE.1.ln(),
        )
        .exp();
        if fit_truncation {
            next.truncation = golden_section_max(
                |ln| {
                    likelihood(NoiseFit {
                        truncation: ln.exp(),
                        ..next
                    })
                },
                TRUNCATION_RANGE.0.ln(),
                TRUNCATION_RANGE.1.ln(),
            )
            .exp();
        }
        let converged = (next.gyro_noise / fit.gyro_noise - 1.0).abs() < 1e-4
            && (next.truncation / fit.truncation - 1.0).abs() < 1e-4;
        fit = next;
        if converged {
            break;
        }
    }
    Some(fit)
}

/// The final inlier mask of the pose `h` under `model` with the squared threshold `thr_sq`
/// of residual kind `kind`, and the noise model it was classified with. With a pixel
/// (Sampson) threshold and [`RobustOptions::fit_gyro_noise`], the noise is fitted to the
/// pair ([`fit_noise`]) and each match's residual weighted by it; otherwise the weights of
/// `data` (the options' noise model) are used and no fit is reported.
pub(crate) fn final_inliers(
    data: &PointData,
    (view1, view2): (&View, &View),
    model: PoseModel,
    (kind, thr_sq): (ResidualKind, f64),
    h: &Hypothesis,
    robust: &RobustOptions,
) -> (Vec<bool>, Option<NoiseFit>) {
    let fitted = match kind {
        ResidualKind::Sampson if robust.fit_gyro_noise => {
            // One pass over the matches: the fit and the classification share the residuals.
            let sq: Vec<f64> = (0..data.len())
                .map(|i| data.sampson_unweighted(model, i, &h.r, &h.t, &h.e).powi(2))
                .collect();
            let pixel = row_noise(view1, view2, robust.pixel_noise, 0.0).pixel;
            fit_noise(data, (view1, view2), model, &sq, (pixel, robust.gyro_noise))
                .map(|fit| (fit, sq))
        }
        _ => None,
    };
    let inliers = match &fitted {
        Some((fit, sq)) => {
            let noise = fit.row_noise(view1, view2, robust.pixel_noise);
            let px2 = noise.pixel * noise.pixel;
            sq.iter()
                .enumerate()
                .map(|(i, x2)| x2 * px2 / data.noise_variance(noise, model, i) < thr_sq)
                .collect()
        }
        None => (0..data.len())
            .map(|i| {
                let x = data.residual(model, kind, i, &h.r, &h.t, &h.e);
                x * x < thr_sq
            })
            .collect(),
    };
    let fitted = fitted.map(|(fit, _)| fit);
    (inliers, fitted)
}

/// A refined pose with its final inliers.
pub(crate) struct Refined {
    /// The refined pose.
    pub h: Hypothesis,
    /// The final inlier mask.
    pub inliers: Vec<bool>,
    /// The noise model fitted to the pair, if any.
    pub noise_fit: Option<NoiseFit>,
    /// Levenberg-Marquardt iterations, all rounds.
    pub iterations: usize,
    /// Final refinement cost.
    pub cost: f64,
}

/// Refine `h0` by LM on `refine_kind` residuals of `model` over `inliers`, then classify
/// every match ([`final_inliers`]); when the fitted gyro noise exceeds the prior, refine
/// once more on the new inliers, each weighted by the fitted noise, and classify again.
pub(crate) fn refine_and_classify(
    data: &PointData,
    views: (&View, &View),
    (model, refine_kind): (PoseModel, ResidualKind),
    threshold: (ResidualKind, f64),
    (h0, inliers): (&Hypothesis, &[bool]),
    options: &EstimateOptions,
) -> Refined {
    let refine = |data: &PointData, inliers: &[bool], h: &Hypothesis| {
        refine_pose(
            data,
            &indices(inliers),
            model,
            refine_kind,
            Loss::Trivial,
            h.pose(),
            &options.refinement,
        )
    };
    let classify =
        |h: &Hypothesis| final_inliers(data, views, model, threshold, h, &options.robust);
    let r = refine(data, inliers, h0);
    let h = Hypothesis::from_pose(&r.state);
    let (inliers, noise_fit) = classify(&h);
    // A second round only when the pair is noisier than the prior said: RANSAC's inliers
    // then miss late rows, which the fitted noise admits. A quieter pair keeps the pose
    // refined with the prior's weights (sharper weights on late rows let the systematic
    // part of a rate error pull the rotation) and only its classification tightens.
    let noisier = |fit: &NoiseFit| fit.gyro_noise > options.robust.gyro_noise;
    let Some(fit) = noise_fit.filter(noisier) else {
        return Refined {
            h,
            inliers,
            noise_fit,
            iterations: r.iterations,
            cost: r.cost,
        };
    };
    let mut fitted = data.clone();
    fitted.set_row_noise(fit.row_noise(views.0, views.1, options.robust.pixel_noise));
    let again = refine(&fitted, &inliers, &h);
    let h = Hypothesis::from_pose(&again.state);
    let (inliers, noise_fit) = classify(&h);
    Refined {
        h,
        inliers,
        noise_fit,
        iterations: r.iterations + again.iterations,
        cost: again.cost,
    }
}

/// The maximiser of a unimodal `f` on `[lo, hi]` by golden-section search.
fn golden_section_max(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let mut a = hi - g * (hi - lo);
    let mut b = lo + g * (hi - lo);
    let (mut fa, mut fb) = (f(a), f(b));
    for _ in 0..GOLDEN_STEPS {
        if fa < fb {
            lo = a;
            a = b;
            fa = fb;
            b = lo + g * (hi - lo);
            fb = f(b);
        } else {
            hi = b;
            b = a;
            fb = fa;
            a = hi - g * (hi - lo);
            fa = f(a);
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::model::geometry::skew;
    use nalgebra::{Matrix3, Vector3};

    /// Squared unweighted Sampson residuals of every match under `(r, t)`.
    fn squared_residuals(data: &PointData, r: &Matrix3<f64>, t: &Vector3<f64>) -> Vec<f64> {
        let e = skew(t) * r;
        (0..data.len())
            .map(|i| {
                data.sampson_unweighted(PoseModel::ExactAngular, i, r, t, &e)
                    .powi(2)
            })
            .collect()
    }

    /// The fit recovers the simulator's gyro noise within a factor of two whatever the
    /// prior, with and without outliers.
    #[test]
    fn the_fitted_gyro_noise_follows_the_simulated_one() {
        for (sigma, outliers) in [(0.05, 0.0), (0.5, 0.0), (0.5, 0.4), (0.1, 0.4)] {
            let mut fitted = Vec::new();
            for seed in 0..8 {
                let pair = simulate(&SimulationOptions {
                    gyro_noise: sigma,
                    outlier_fraction: outliers,
                    points: 400,
                    seed,
                    ..SimulationOptions::default()
                })
                .unwrap();
                let (v1, v2) = pair.views().unwrap();
                let gt = pair.ground_truth.as_ref().unwrap();
                let (r, t) = (gt.rotation_matrix(), gt.translation_vector());
                let data = PointData::new(&v1, &v2, &pair.matches).unwrap();
                let s = fit_noise(
                    &data,
                    (&v1, &v2),
                    PoseModel::ExactAngular,
                    &squared_residuals(&data, &r, &t),
                    (1.0 / v1.camera.mean_focal(), 0.1),
                )
                .unwrap();
                fitted.push(s.gyro_noise);
            }
            fitted.sort_by(f64::total_cmp);
            let median = 0.5 * (fitted[3] + fitted[4]);
            assert!(
                median > 0.5 * sigma && median < 2.0 * sigma,
                "σ_ω {sigma}, outliers {outliers}: fitted {fitted:?}"
            );
        }
    }

    #[test]
    fn a_global_shutter_camera_has_no_gyro_noise_to_fit() {
        let pair = simulate(&SimulationOptions::default()).unwrap();
        let (mut v1, mut v2) = pair.views().unwrap();
        v1.camera.readout = 0.0;
        v2.camera.readout = 0.0;
        let data = PointData::new(&v1, &v2, &pair.matches).unwrap();
        let (r, t) = (Matrix3::identity(), Vector3::x());
        let fit = fit_noise(
            &data,
            (&v1, &v2),
            PoseModel::ExactAngular,
            &squared_residuals(&data, &r, &t),
            (1e-3, 0.1),
        );
        assert_eq!(fit, None);
    }
}
