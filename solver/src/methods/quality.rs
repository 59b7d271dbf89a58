//! The quality report of an estimate (in the spirit of PoseLib's `RansacStats`): how much of
//! the data the pose explains, and whether the geometry lets it be trusted.
//!
//! - **Too few inliers**: fewer than [`QualityOptions::min_inliers`].
//! - **Translation undetermined** (near-zero baseline, or a camera that only turned): the
//!   median parallax the best pure rotation leaves, `f · ∠(R_rot b1, b2)` in pixels, is
//!   below [`QualityOptions::min_parallax_ratio`] times the median epipolar residual of the
//!   estimate. Then a rotation explains the matches about as well as the pose, and the
//!   direction of `t` is noise.
//! - **Near-planar scene**: the best homography `x2 ~ H x1` leaves a median transfer error
//!   below [`QualityOptions::max_homography_ratio`] times the epipolar residual. A plane
//!   admits two essential matrices (and a homography fits every pure rotation too), so the
//!   pose may be the wrong one.
//!
//! - **Low inlier ratio**: fewer than [`QualityOptions::min_inlier_ratio`] of the matches
//!   are inliers. Random matches leave a few percent of chance inliers under any pose, so a
//!   pose resting on so few is not evidence of the scene.
//! - **Collinear**: the inliers' pixels in either image lie near one line (their spread
//!   across their main axis is below [`QualityOptions::min_spread_ratio`] times the image's
//!   smaller side). Points on a line do not determine the epipolar geometry: every pose
//!   whose epipolar planes contain the line fits them, so the reported one is arbitrary.
//! - **Gyro noise runaway**: the gyro-rate noise fitted to the pair (gyro-aided methods)
//!   exceeds [`MAX_PLAUSIBLE_GYRO_NOISE`]. A gyroscope that noisy carries no information;
//!   such a fit means the noise model absorbed residuals the pose does not explain, and the
//!   inliers classified with it are not trustworthy. Raised by the estimate after the fit
//!   ([`Quality::flag_gyro_noise`]).
//!
//! Both the parallax and homography flags compare with the epipolar residual, so they adapt to the matching noise. For `gsrp`
//! on strongly distorted rolling-shutter images that residual is inflated by the model's
//! error, which makes the flags more likely: a warning that the model does not explain the
//! data either.
//!
//! Bearings are the method's own: undistorted by the gyro row rotations for the gyro-aided
//! methods, by `nrsrp`'s estimated rotations for `nrsrp`, raw for `gsrp`.

use crate::estimation::refine::{refine_pose, LmOptions, Loss, Pose};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, PoseModel, ResidualKind};
use crate::model::matches::Match;
use crate::stats::upper_median;
use nalgebra::{Matrix3, SMatrix, SymmetricEigen, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Thresholds of the quality flags (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct QualityOptions {
    /// Fewer inliers raise `too_few_inliers` (default 15: three minimal samples).
    pub min_inliers: usize,
    /// The translation is undetermined when the parallax left by the best pure rotation is
    /// below this multiple of the epipolar residual (default 5: with pure noise the ratio
    /// is about 2-4, as the 2D rotation residual is compared with the 1D epipolar one).
    pub min_parallax_ratio: f64,
    /// The scene is near-planar when the best homography's transfer error is below this
    /// multiple of the epipolar residual (default 4: with pure noise the ratio is about
    /// 2.5-3.5, the transfer error adding both images' noise in 2D).
    pub max_homography_ratio: f64,
    /// Transfer error within which a match supports a homography hypothesis, pixels
    /// (default 2).
    pub homography_threshold_px: f64,
    /// A smaller fraction of inliers raises `low_inlier_ratio` (default 0.2: random matches
    /// keep well under a tenth as chance inliers, real pairs most of theirs).
    pub min_inlier_ratio: f64,
    /// Inlier pixels whose spread across their main axis (standard deviation, in either
    /// image) is below this fraction of the image's smaller side raise `collinear`
    /// (default 0.01).
    pub min_spread_ratio: f64,
}

/// A fitted gyro-rate noise above this (rad/s per axis) raises `gyro_noise_runaway`: far
/// beyond any real gyroscope's noise, and above which the gyro no longer constrains the
/// rows' rotations.
pub const MAX_PLAUSIBLE_GYRO_NOISE: f64 = 1.0;

impl Default for QualityOptions {
    fn default() -> Self {
        QualityOptions {
            min_inliers: 15,
            min_parallax_ratio: 5.0,
            max_homography_ratio: 4.0,
            homography_threshold_px: 2.0,
            min_inlier_ratio: 0.2,
            min_spread_ratio: 0.01,
        }
    }
}

/// Diagnostics of an estimate's inliers and geometry.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Quality {
    /// Inliers over matches.
    pub inlier_ratio: f64,
    /// Median parallax of the inliers left by the best pure rotation, pixels.
    pub parallax_px: f64,
    /// Median distance of the inliers from their epipolar planes under the estimate, pixels.
    pub epipolar_px: f64,
    /// Median transfer error of the inliers under the best homography, pixels.
    pub homography_px: f64,
    /// Fewer inliers than [`QualityOptions::min_inliers`].
    pub too_few_inliers: bool,
    /// The parallax is too small to determine the translation direction.
    pub translation_undetermined: bool,
    /// One homography explains nearly all inliers (planar scene or pure rotation).
    pub near_planar: bool,
    /// A smaller fraction of the matches than [`QualityOptions::min_inlier_ratio`] are
    /// inliers.
    pub low_inlier_ratio: bool,
    /// The inliers' pixels in one image lie near a line: the pose is not determined.
    pub collinear: bool,
    /// The fitted gyro-rate noise exceeds [`MAX_PLAUSIBLE_GYRO_NOISE`].
    pub gyro_noise_runaway: bool,
}

impl Quality {
    /// Names of the raised flags, e.g. `["near_planar"]`.
    pub fn flags(&self) -> Vec<&'static str> {
        [
            (self.too_few_inliers, "too_few_inliers"),
            (self.translation_undetermined, "translation_undetermined"),
            (self.near_planar, "near_planar"),
            (self.low_inlier_ratio, "low_inlier_ratio"),
            (self.collinear, "collinear"),
            (self.gyro_noise_runaway, "gyro_noise_runaway"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }

    /// Raises `gyro_noise_runaway` when the fitted gyro-rate noise `gyro_noise` (rad/s per
    /// axis) exceeds [`MAX_PLAUSIBLE_GYRO_NOISE`] or is not finite.
    pub fn flag_gyro_noise(&mut self, gyro_noise: f64) {
        self.gyro_noise_runaway = gyro_noise.is_nan() || gyro_noise > MAX_PLAUSIBLE_GYRO_NOISE;
    }
}

/// The standard deviation of `pixels` across their main axis (the smaller principal
/// standard deviation), pixels; 0 for fewer than two.
fn minor_spread(pixels: impl Iterator<Item = [f64; 2]>) -> f64 {
    let pts: Vec<[f64; 2]> = pixels.collect();
    if pts.len() < 2 {
        return 0.0;
    }
    let n = pts.len() as f64;
    let mean = pts
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in &pts {
        let (dx, dy) = (p[0] - mean[0], p[1] - mean[1]);
        sxx += dx * dx / n;
        sxy += dx * dy / n;
        syy += dy * dy / n;
    }
    // The smaller eigenvalue of the 2x2 covariance.
    let half_trace = 0.5 * (sxx + syy);
    let det = sxx * syy - sxy * sxy;
    (half_trace - (half_trace * half_trace - det).max(0.0).sqrt())
        .max(0.0)
        .sqrt()
}

/// At most this many inliers enter the homography search (a deterministic stride beyond).
const MAX_POINTS: usize = 2000;
/// Four-point homography hypotheses tried.
const HOMOGRAPHY_SAMPLES: usize = 64;

/// Assesses the pose `(rotation, translation)` over the inliers of `matches` (at most
/// 2000 of them, a deterministic stride beyond), with row-0 bearings from `view1`/`view2`'s
/// row rotations (constant zero-rate views for raw bearings). The noise level is the
/// median epipolar residual of the pose after a short Sampson refinement on those
/// bearings, so that it does not depend on how well the method's own model fits.
#[allow(clippy::too_many_arguments)]
pub fn assess(
    view1: &View,
    view2: &View,
    matches: &[Match],
    inliers: &[bool],
    rotation: &Matrix3<f64>,
    translation: &Vector3<f64>,
    options: &QualityOptions,
    seed: u64,
) -> Quality {
    let idx: Vec<usize> = (0..matches.len()).filter(|&i| inliers[i]).collect();
    let n = idx.len();
    let step = n.div_ceil(MAX_POINTS).max(1);
    let sub: Vec<Match> = idx.iter().step_by(step).map(|&i| matches[i]).collect();
    // Every match was observed when the input was validated.
    let Ok(data) = PointData::new(view1, view2, &sub) else {
        return Quality::default();
    };
    let all: Vec<usize> = (0..sub.len()).collect();
    let lm = LmOptions {
        max_iterations: 10,
        ..LmOptions::default()
    };
    let pose = if sub.len() >= 5 {
        refine_pose(
            &data,
            &all,
            PoseModel::ExactAngular,
            ResidualKind::Sampson,
            Loss::Trivial,
            Pose::new(rotation, translation),
            &lm,
        )
        .state
    } else {
        Pose::new(rotation, translation)
    };
    let (r, t) = (pose.matrix(), pose.translation);
    let pts: Vec<(Vector3<f64>, Vector3<f64>)> = data
        .b1
        .iter()
        .copied()
        .zip(data.b2.iter().copied())
        .collect();
    let f = 0.5 * (view1.camera.mean_focal() + view2.camera.mean_focal());
    // The parallax left by the best pure rotation (not the estimate's R, which absorbs
    // part of the translation when the baseline is tiny), against the epipolar residual.
    let r_only = best_rotation(&pts).unwrap_or(r);
    let parallax_px = f * median(pts.iter().map(|(b1, b2)| (r_only * b1).angle(b2)));
    let epipolar_px = f * median(pts.iter().map(|(b1, b2)| {
        let n = t.cross(&(r * b1));
        (b2.dot(&n) / (n.norm() * b2.norm())).abs().asin()
    }));
    let homography_px = f * homography_residual(&pts, options.homography_threshold_px / f, seed);
    let inlier_ratio = n as f64 / matches.len().max(1) as f64;
    let collinear = [view1, view2].into_iter().enumerate().any(|(k, view)| {
        let side = view.camera.width.min(view.camera.height);
        minor_spread(sub.iter().map(|m| m[k])) < options.min_spread_ratio * side
    });
    Quality {
        inlier_ratio,
        parallax_px,
        epipolar_px,
        homography_px,
        too_few_inliers: n < options.min_inliers,
        translation_undetermined: parallax_px < options.min_parallax_ratio * epipolar_px,
        near_planar: homography_px < options.max_homography_ratio * epipolar_px,
        low_inlier_ratio: inlier_ratio < options.min_inlier_ratio,
        collinear,
        gyro_noise_runaway: false,
    }
}

/// The quality figures' median: an observed residual, 0 without any.
fn median(v: impl Iterator<Item = f64>) -> f64 {
    upper_median(v).unwrap_or(0.0)
}

/// The rotation `R` maximising `Σ b2ᵀ R b1` over unit bearings (Wahba's problem, by SVD).
fn best_rotation(pts: &[(Vector3<f64>, Vector3<f64>)]) -> Option<Matrix3<f64>> {
    let mut b = Matrix3::zeros();
    for (b1, b2) in pts {
        b += b2.normalize() * b1.normalize().transpose();
    }
    let svd = b.svd(true, true);
    let (u, v_t) = (svd.u?, svd.v_t?);
    let d = (u * v_t).determinant().signum();
    let r = u * Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, d)) * v_t;
    r.iter().all(|x| x.is_finite()).then_some(r)
}

/// The best homography's median transfer error over `pts` (normalised image units): 4-point
/// hypotheses scored by the number of points within `thr`, the best refitted by least
/// squares on those points.
fn homography_residual(pts: &[(Vector3<f64>, Vector3<f64>)], thr: f64, seed: u64) -> f64 {
    let xs: Vec<(Vector3<f64>, Vector3<f64>)> = pts
        .iter()
        .filter(|(a, b)| a.z > 1e-9 && b.z > 1e-9)
        .map(|(a, b)| (a / a.z, b / b.z))
        .collect();
    if xs.len() < 5 {
        return f64::INFINITY;
    }
    let errors = |h: &Matrix3<f64>| -> Vec<f64> {
        xs.iter()
            .map(|(a, b)| {
                let p = h * a;
                if p.z.abs() > 1e-12 {
                    ((p.x / p.z - b.x).powi(2) + (p.y / p.z - b.y).powi(2)).sqrt()
                } else {
                    f64::INFINITY
                }
            })
            .collect()
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut best: Option<(usize, Matrix3<f64>)> = None;
    for _ in 0..HOMOGRAPHY_SAMPLES {
        let sample: [usize; 4] = std::array::from_fn(|_| rng.gen_range(0..xs.len()));
        let Some(h) = homography_from_4(&sample.map(|i| xs[i])) else {
            continue;
        };
        let count = errors(&h).iter().filter(|&&e| e < thr).count();
        if best.as_ref().map_or(true, |(c, _)| count > *c) {
            best = Some((count, h));
        }
    }
    let Some((_, h)) = best else {
        return f64::INFINITY;
    };
    let e = errors(&h);
    let refit = fit_homography(xs.iter().zip(&e).filter(|(_, &e)| e < thr).map(|(p, _)| p));
    let e2 = refit.map(|h| errors(&h)).unwrap_or_default();
    median(e.into_iter()).min(if e2.is_empty() {
        f64::INFINITY
    } else {
        median(e2.into_iter())
    })
}

/// The homography through four correspondences (points with z = 1), by mapping each
/// image's quadruple from the projective basis: `A = [p1 p2 p3] diag(λ)` with
/// `[p1 p2 p3] λ = p4` sends `e1, e2, e3, (1, 1, 1)` to the four points, so `H = B A⁻¹`.
/// `None` when three points of either image are collinear (the basis does not exist).
fn homography_from_4(pts: &[(Vector3<f64>, Vector3<f64>); 4]) -> Option<Matrix3<f64>> {
    let basis = |p: [&Vector3<f64>; 4]| -> Option<Matrix3<f64>> {
        let m = Matrix3::from_columns(&[*p[0], *p[1], *p[2]]);
        let l = m.lu().solve(p[3])?;
        if l.iter().any(|x| x.abs() < 1e-12 || !x.is_finite()) {
            return None;
        }
        Some(m * Matrix3::from_diagonal(&l))
    };
    let a = basis([&pts[0].0, &pts[1].0, &pts[2].0, &pts[3].0])?;
    let b = basis([&pts[0].1, &pts[1].1, &pts[2].1, &pts[3].1])?;
    let h = b * a.try_inverse()?;
    h.iter().all(|x| x.is_finite()).then_some(h)
}

/// Least-squares DLT homography `x2 ~ H x1` (points with z = 1), from the 9x9 normal
/// matrix's smallest eigenvector; `None` for fewer than 4 points or a non-finite result.
fn fit_homography<'a>(
    pts: impl Iterator<Item = &'a (Vector3<f64>, Vector3<f64>)>,
) -> Option<Matrix3<f64>> {
    let mut ata = SMatrix::<f64, 9, 9>::zeros();
    let mut n = 0;
    for (a, b) in pts {
        let r1 = SMatrix::<f64, 9, 1>::from_column_slice(&[
            a.x,
            a.y,
            1.0,
            0.0,
            0.0,
            0.0,
            -b.x * a.x,
            -b.x * a.y,
            -b.x,
        ]);
        let r2 = SMatrix::<f64, 9, 1>::from_column_slice(&[
            0.0,
            0.0,
            0.0,
            a.x,
            a.y,
            1.0,
            -b.y * a.x,
            -b.y * a.y,
            -b.y,
        ]);
        ata += r1 * r1.transpose() + r2 * r2.transpose();
        n += 1;
    }
    if n < 4 {
        return None;
    }
    let e = SymmetricEigen::new(ata);
    let h = e.eigenvectors.column(e.eigenvalues.imin());
    let m = Matrix3::new(h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8]);
    m.iter().all(|x| x.is_finite()).then_some(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apply(h: &Matrix3<f64>, p: &Vector3<f64>) -> Vector3<f64> {
        let q = h * p;
        q / q.z
    }

    #[test]
    fn four_point_homography_reproduces_a_known_one() {
        let h = Matrix3::new(1.1, 0.05, 0.2, -0.03, 0.95, -0.1, 0.02, 0.01, 1.0);
        let xs = [
            (0.1, 0.2),
            (-0.3, 0.25),
            (0.2, -0.4),
            (-0.15, -0.2),
            (0.05, 0.33),
        ]
        .map(|(x, y)| Vector3::new(x, y, 1.0));
        let pts: [(Vector3<f64>, Vector3<f64>); 4] =
            std::array::from_fn(|i| (xs[i], apply(&h, &xs[i])));
        let fit = homography_from_4(&pts).unwrap();
        for x in &xs {
            assert!((apply(&fit, x) - apply(&h, x)).norm() < 1e-12);
        }
        // Agrees with the least-squares fit on the same points.
        let ls = fit_homography(pts.iter()).unwrap();
        assert!((apply(&ls, &xs[4]) - apply(&h, &xs[4])).norm() < 1e-9);
        // Three collinear points: no homography.
        let mut bad = pts;
        bad[2].0 = Vector3::new(0.5 * (xs[0].x + xs[1].x), 0.5 * (xs[0].y + xs[1].y), 1.0);
        assert!(homography_from_4(&bad).is_none());
    }

    #[test]
    fn points_on_a_line_have_no_spread_across_it() {
        let line = (0..50).map(|i| [10.0 + 3.0 * i as f64, 20.0 + 2.0 * i as f64]);
        assert!(minor_spread(line) < 1e-9);
        let grid = (0..100).map(|i| [(i % 10) as f64 * 100.0, (i / 10) as f64 * 100.0]);
        assert!((minor_spread(grid) - 287.228).abs() < 1e-2);
    }

    #[test]
    fn a_runaway_gyro_noise_fit_is_flagged() {
        let mut q = Quality::default();
        q.flag_gyro_noise(0.05);
        assert!(q.flags().is_empty());
        for runaway in [MAX_PLAUSIBLE_GYRO_NOISE * 1.01, 9.5, f64::NAN] {
            q.flag_gyro_noise(runaway);
            assert_eq!(q.flags(), ["gyro_noise_runaway"]);
        }
    }
}
