//! Per-point epipolar residuals of the three two-view models used by the estimator.
//!
//! All bearings are undistorted normalised coordinates `m = (x, y, 1)` (`K^-1 [u, v, 1]^T`
//! for a pinhole), and `v` is a pixel's line coordinate (its row for a top-to-bottom
//! readout; [`crate::model::camera::Camera::observe`]). `Ω(v)` is a view's line rotation ([`View::row_rotation`]: `exp(−[v λ ω]×)` for a constant gyro
//! rate `ω`, or integrated from gyro samples), and `w = −λ ω` (rad/row) the paper's per-row
//! rate ([`View::paper_rate_per_row`]). For a relative pose `(R, t)` (`|t| = 1`,
//! `E = [t]× R`):
//!
//! - [`PoseModel::GlobalShutter`]: `r = m2^T E m1`.
//! - [`PoseModel::ExactAngular`]: `r = (Ω2(v2)^T m2)^T E (Ω1(v1)^T m1)`.
//! - [`PoseModel::PaperLinear`]: the paper's G-RSRP model
//!   `r = m2^T [t]× (I + v2 [w2]×) R (I - v1 [w1]×) m1`.
//!
//! [`ResidualKind::Algebraic`] uses `r` itself (the paper's `|m2^T E m1|` threshold);
//! [`ResidualKind::Sampson`] divides by the norm of the gradient of `r` with respect to the
//! two normalised image points `(x1, y1, x2, y2)` (row rotations held fixed), i.e. the
//! first-order geometric error in normalised image units (multiply by the focal length for
//! pixels).

use crate::model::camera::{Camera, CameraError, Observation, View};
use crate::model::geometry::skew;
use crate::model::matches::Match;
use crate::model::sampson_kernel::{msac_sampson, BearingColumns};
use nalgebra::{Matrix3, Vector3};
use std::sync::OnceLock;
use thiserror::Error;

/// Which two-view model a residual follows (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoseModel {
    /// Global shutter: no row rotation.
    GlobalShutter,
    /// Exact angular rolling-shutter model (gyro row rotations, bearings undistorted).
    ExactAngular,
    /// The paper's linearised G-RSRP model, `[t]×` outside the row rotation.
    PaperLinear,
}

/// Algebraic or Sampson residual (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ResidualKind {
    /// `r` itself.
    Algebraic,
    /// `r / |∇r|`, normalised image units.
    Sampson,
}

/// A match with a pixel that has no bearing in its camera ([`CameraError::NotInvertible`],
/// [`CameraError::NotConverged`]).
#[derive(Debug, Clone, PartialEq, Error)]
#[error("match {index}, image {image}: {source}")]
pub struct UnobservableMatch {
    /// Index of the match.
    pub index: usize,
    /// 1 or 2.
    pub image: usize,
    /// Why the pixel has no bearing.
    pub source: CameraError,
}

/// Each match's two pixels observed by their cameras ([`crate::model::camera::Camera::observe`]):
/// bearing and line coordinate. Errors name the first match with a pixel that has no
/// bearing.
pub fn observe_matches(
    camera1: &Camera,
    camera2: &Camera,
    matches: &[Match],
) -> Result<Vec<[Observation; 2]>, UnobservableMatch> {
    matches
        .iter()
        .enumerate()
        .map(|(index, m)| {
            let observe = |camera: &Camera, k: usize| {
                camera.observe(m[k]).map_err(|source| UnobservableMatch {
                    index,
                    image: k + 1,
                    source,
                })
            };
            Ok([observe(camera1, 0)?, observe(camera2, 1)?])
        })
        .collect()
}

/// Matches converted to bearings, with the per-point line quantities every model needs.
///
/// Built by [`PointData::new`] or [`PointData::select`]; the fields are public for reading
/// and must not be changed afterwards (the scores read a copy of `m1` and `m2` by
/// coordinate).
#[derive(Debug, Clone)]
pub struct PointData {
    /// Bearings in image 1, undistorted normalised coordinates (`K^-1 [u1, v1, 1]` for a
    /// pinhole).
    pub m1: Vec<Vector3<f64>>,
    /// Bearings in image 2.
    pub m2: Vec<Vector3<f64>>,
    /// Line coordinates in image 1 (pixels; the row for a top-to-bottom readout).
    pub v1: Vec<f64>,
    /// Line coordinates in image 2 (pixels).
    pub v2: Vec<f64>,
    /// `w1 = −λ ω1`, rad/row (the paper's sign).
    pub w1: Vector3<f64>,
    /// `w2 = −λ ω2`, rad/row.
    pub w2: Vector3<f64>,
    /// Row rotations `Ω1(v1)`.
    pub omega1: Vec<Matrix3<f64>>,
    /// Row rotations `Ω2(v2)`.
    pub omega2: Vec<Matrix3<f64>>,
    /// Undistorted bearings `Ω1(v1)^T m1` (row-0 frame of camera 1).
    pub b1: Vec<Vector3<f64>>,
    /// Undistorted bearings `Ω2(v2)^T m2`.
    pub b2: Vec<Vector3<f64>>,
    /// Linearised undistortion `(I - v1 [w1]×) m1` of the paper's model.
    pub l1: Vec<Vector3<f64>>,
    /// Per-point weights `σ_px / σ_i` of the Sampson residuals of the rolling-shutter models
    /// (`[exact angular, paper]`; empty: all 1), from [`RowNoise`] (see
    /// [`PointData::set_row_noise`]).
    pub scale: [Vec<f64>; 2],
    /// `m1`, `m2` by coordinate for the global-shutter Sampson score, built on its first
    /// use (the gyro-aided models never need it).
    columns: OnceLock<BearingColumns>,
}

/// The noise of a match's epipolar residual, growing with its rows: pixel noise `σ_px`
/// plus the displacement a gyro-rate error `σ_ω` causes at row `v`, `f λ v σ_ω`, in each
/// image; for the paper's linearised model also its truncation error, `f (v λ |ω|)² / 2`.
/// All in normalised image units (pixels over the focal length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowNoise {
    /// Pixel noise, normalised units.
    pub pixel: f64,
    /// Gyro-rate noise times the readout of a row, `λ σ_ω` (rad/row).
    pub rate_per_row: f64,
    /// Scale of the paper model's truncation term (1: its bound `(v |w|)² / 2` taken as a
    /// standard deviation; the truncation error is systematic and usually smaller).
    pub truncation: f64,
}

impl PointData {
    /// Build from two views and pixel matches (inputs assumed validated and finite): each
    /// pixel's bearing and line coordinate from its camera ([`Camera::observe`]). Errors
    /// name the first match with a pixel that has no bearing (outside the region where its
    /// camera's distortion is invertible).
    ///
    /// [`Camera::observe`]: crate::model::camera::Camera::observe
    pub fn new(view1: &View, view2: &View, matches: &[Match]) -> Result<Self, UnobservableMatch> {
        let obs = observe_matches(&view1.camera, &view2.camera, matches)?;
        Ok(Self::from_observations(view1, view2, &obs))
    }

    /// Build from two views and their matches' observations ([`observe_matches`]).
    pub fn from_observations(view1: &View, view2: &View, obs: &[[Observation; 2]]) -> Self {
        let n = obs.len();
        let mut d = PointData {
            m1: Vec::with_capacity(n),
            m2: Vec::with_capacity(n),
            v1: Vec::with_capacity(n),
            v2: Vec::with_capacity(n),
            w1: view1.paper_rate_per_row(),
            w2: view2.paper_rate_per_row(),
            omega1: Vec::with_capacity(n),
            omega2: Vec::with_capacity(n),
            b1: Vec::with_capacity(n),
            b2: Vec::with_capacity(n),
            l1: Vec::with_capacity(n),
            scale: [Vec::new(), Vec::new()],
            columns: OnceLock::new(),
        };
        for [p1, p2] in obs {
            let (m1, m2) = (p1.bearing, p2.bearing);
            let o1 = view1.row_rotation(p1.line);
            let o2 = view2.row_rotation(p2.line);
            d.b1.push(o1.transpose() * m1);
            d.b2.push(o2.transpose() * m2);
            d.l1.push(m1 - (d.w1 * p1.line).cross(&m1));
            d.omega1.push(o1);
            d.omega2.push(o2);
            d.m1.push(m1);
            d.m2.push(m2);
            d.v1.push(p1.line);
            d.v2.push(p2.line);
        }
        d
    }

    /// Weights the Sampson residuals of the rolling-shutter models by `σ_px / σ_i`, with
    /// `σ_i² = σ_px² + (λ σ_ω)² (v1² + v2²)` (plus, for the paper's model, the squared
    /// truncation error `((v1 |w1|)⁴ + (v2 |w2|)⁴) / 4`), so that a single threshold in
    /// pixels keeps rows read late, which a gyro error moves further, as well as row 0.
    pub fn set_row_noise(&mut self, noise: RowNoise) {
        let px2 = noise.pixel * noise.pixel;
        if px2.is_nan() || px2 <= 0.0 {
            self.scale = [Vec::new(), Vec::new()];
            return;
        }
        let weights = |model| {
            (0..self.len())
                .map(|i| (px2 / self.noise_variance(noise, model, i)).sqrt())
                .collect()
        };
        self.scale = [
            weights(PoseModel::ExactAngular),
            weights(PoseModel::PaperLinear),
        ];
    }

    /// `σ_i²`, the variance of point `i`'s Sampson residual under `noise` (normalised units
    /// squared): `σ_px² + (λ σ_ω)² (v1² + v2²)`, plus for the paper's model its squared
    /// truncation error `((v1 |w1|)⁴ + (v2 |w2|)⁴) / 4` times `truncation²`; `σ_px²` alone for the
    /// global-shutter model, which has no gyro.
    pub fn noise_variance(&self, noise: RowNoise, model: PoseModel, i: usize) -> f64 {
        let px2 = noise.pixel * noise.pixel;
        let (v1, v2) = (self.v1[i] * self.v1[i], self.v2[i] * self.v2[i]);
        let gyro = noise.rate_per_row * noise.rate_per_row * (v1 + v2);
        match model {
            PoseModel::GlobalShutter => px2,
            PoseModel::ExactAngular => px2 + gyro,
            PoseModel::PaperLinear => {
                let (a1, a2) = (self.w1.norm_squared(), self.w2.norm_squared());
                let lin = 0.25 * (a1 * a1 * v1 * v1 + a2 * a2 * v2 * v2);
                px2 + gyro + noise.truncation * noise.truncation * lin
            }
        }
    }

    /// The Sampson residual `r / |∇r|` of point `i` under `model` without its weight
    /// (normalised image units; infinite where the gradient vanishes).
    #[inline]
    pub fn sampson_unweighted(
        &self,
        model: PoseModel,
        i: usize,
        r: &Matrix3<f64>,
        t: &Vector3<f64>,
        e: &Matrix3<f64>,
    ) -> f64 {
        let (res, g) = self.residual_and_gradient(model, i, r, t, e);
        if g > 0.0 {
            res / g.sqrt()
        } else {
            f64::INFINITY
        }
    }

    /// The weight of point `i`'s Sampson residual under `model` (1 without a noise model).
    #[inline(always)]
    pub fn weight(&self, model: PoseModel, i: usize) -> f64 {
        let s = match model {
            PoseModel::GlobalShutter => return 1.0,
            PoseModel::ExactAngular => &self.scale[0],
            PoseModel::PaperLinear => &self.scale[1],
        };
        s.get(i).copied().unwrap_or(1.0)
    }

    /// The points `indices` (in that order), with their weights.
    pub fn select(&self, indices: &[usize]) -> PointData {
        let pick3 = |v: &[Vector3<f64>]| indices.iter().map(|&i| v[i]).collect();
        let pick = |v: &[f64]| indices.iter().map(|&i| v[i]).collect();
        let pick_m = |v: &[Matrix3<f64>]| indices.iter().map(|&i| v[i]).collect();
        PointData {
            m1: pick3(&self.m1),
            m2: pick3(&self.m2),
            v1: pick(&self.v1),
            v2: pick(&self.v2),
            w1: self.w1,
            w2: self.w2,
            omega1: pick_m(&self.omega1),
            omega2: pick_m(&self.omega2),
            b1: pick3(&self.b1),
            b2: pick3(&self.b2),
            l1: pick3(&self.l1),
            scale: self
                .scale
                .clone()
                .map(|w| if w.is_empty() { w } else { pick(&w) }),
            columns: OnceLock::new(),
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.m1.len()
    }

    /// True if there are no points.
    pub fn is_empty(&self) -> bool {
        self.m1.is_empty()
    }

    /// `(r, |∇r|²)` of point `i` under `model` for pose `(R, t)`; `e` must be `[t]× R`.
    #[inline]
    pub fn residual_and_gradient(
        &self,
        model: PoseModel,
        i: usize,
        r: &Matrix3<f64>,
        t: &Vector3<f64>,
        e: &Matrix3<f64>,
    ) -> (f64, f64) {
        let (res, g1, g2) = match model {
            PoseModel::GlobalShutter => {
                let (m1, m2) = (&self.m1[i], &self.m2[i]);
                let g2 = e * m1;
                (m2.dot(&g2), e.tr_mul(m2), g2)
            }
            PoseModel::ExactAngular => {
                let eb1 = e * self.b1[i];
                let res = self.b2[i].dot(&eb1);
                let g2 = self.omega2[i] * eb1;
                let g1 = self.omega1[i] * e.tr_mul(&self.b2[i]);
                (res, g1, g2)
            }
            PoseModel::PaperLinear => {
                let (m2, v1, v2) = (&self.m2[i], self.v1[i], self.v2[i]);
                let y = r * self.l1[i];
                let z = y + (self.w2 * v2).cross(&y);
                let g2 = t.cross(&z);
                let p = m2.cross(t);
                let q = p - (self.w2 * v2).cross(&p);
                let s = r.tr_mul(&q);
                let g1 = s + (self.w1 * v1).cross(&s);
                (m2.dot(&g2), g1, g2)
            }
        };
        (res, g1.x * g1.x + g1.y * g1.y + g2.x * g2.x + g2.y * g2.y)
    }

    /// Truncated-quadratic (MSAC) score of the pose `(R, t)` (`e = [t]× R`) under
    /// `model`/`kind`: `(Σ_i min(r_i², τ²), #{i : r_i² < τ²})` with `τ² = thr_sq` and `r_i`
    /// as in [`residual`](Self::residual) (non-finite residuals count as outliers). Stops
    /// early, returning a partial sum above `bound`, as soon as the sum exceeds `bound`
    /// (the hypothesis cannot beat a model scoring `bound`). Each (model, kind) pair has its
    /// own loop with the pose-dependent matrices precomputed: no per-point branching and
    /// no allocation.
    #[allow(clippy::too_many_arguments)]
    pub fn msac(
        &self,
        model: PoseModel,
        kind: ResidualKind,
        r: &Matrix3<f64>,
        t: &Vector3<f64>,
        e: &Matrix3<f64>,
        thr_sq: f64,
        bound: f64,
    ) -> (f64, usize) {
        let sq2 = |g1: &Vector3<f64>, g2: &Vector3<f64>| {
            g1.x * g1.x + g1.y * g1.y + g2.x * g2.x + g2.y * g2.y
        };
        match (model, kind) {
            (PoseModel::GlobalShutter, ResidualKind::Algebraic) => msac_of(
                thr_sq,
                bound,
                self.m1.iter().zip(&self.m2).map(|(m1, m2)| {
                    let x = m2.dot(&(e * m1));
                    (x * x, 1.0)
                }),
            ),
            (PoseModel::GlobalShutter, ResidualKind::Sampson) => {
                let columns = self
                    .columns
                    .get_or_init(|| BearingColumns::new(&self.m1, &self.m2));
                msac_sampson(columns, e, thr_sq, bound)
            }
            (PoseModel::ExactAngular, ResidualKind::Algebraic) => msac_of(
                thr_sq,
                bound,
                self.b1.iter().zip(&self.b2).map(|(b1, b2)| {
                    let x = b2.dot(&(e * b1));
                    (x * x, 1.0)
                }),
            ),
            (PoseModel::ExactAngular, ResidualKind::Sampson) => {
                let rows = self.omega1.iter().zip(&self.omega2);
                let w = weights(&self.scale[0]);
                msac_of(
                    thr_sq,
                    bound,
                    self.b1.iter().zip(&self.b2).zip(rows).zip(w).map(
                        |(((b1, b2), (o1, o2)), w)| {
                            let u = e * b1;
                            let x = b2.dot(&u);
                            let g2 = o2 * u;
                            let g1 = o1 * e.tr_mul(b2);
                            (w * w * x * x, sq2(&g1, &g2))
                        },
                    ),
                )
            }
            (PoseModel::PaperLinear, _) => {
                // [t]× (I + v2 [w2]×) R = E + v2 F with F = [t]× [w2]× R.
                let f = skew(t) * skew(&self.w2) * r;
                let rows = self.v1.iter().zip(&self.v2);
                let points = self.l1.iter().zip(&self.m2).zip(rows);
                if kind == ResidualKind::Algebraic {
                    msac_of(
                        thr_sq,
                        bound,
                        points.map(|((l1, m2), (_, &v2))| {
                            let g2 = e * l1 + (f * l1) * v2;
                            let x = m2.dot(&g2);
                            (x * x, 1.0)
                        }),
                    )
                } else {
                    let w = weights(&self.scale[1]);
                    msac_of(
                        thr_sq,
                        bound,
                        points.zip(w).map(|(((l1, m2), (&v1, &v2)), w)| {
                            let g2 = e * l1 + (f * l1) * v2;
                            let h = e.tr_mul(m2) + f.tr_mul(m2) * v2;
                            let g1 = h + (self.w1 * v1).cross(&h);
                            let x = m2.dot(&g2);
                            (w * w * x * x, sq2(&g1, &g2))
                        }),
                    )
                }
            }
        }
    }

    /// Signed residual of point `i` (algebraic `r`, or Sampson `r / |∇r|` times the point's
    /// [`weight`](Self::weight)).
    #[inline]
    pub fn residual(
        &self,
        model: PoseModel,
        kind: ResidualKind,
        i: usize,
        r: &Matrix3<f64>,
        t: &Vector3<f64>,
        e: &Matrix3<f64>,
    ) -> f64 {
        match kind {
            ResidualKind::Algebraic => self.residual_and_gradient(model, i, r, t, e).0,
            ResidualKind::Sampson => {
                self.weight(model, i) * self.sampson_unweighted(model, i, r, t, e)
            }
        }
    }
}

/// The MSAC sum and inlier count of squared residuals given as `(numerator, denominator)`
/// (`r² = n / d`), stopping once the sum exceeds `bound`. A pair failing `n < τ² d`
/// (including a zero or non-finite denominator) is an outlier and adds `τ²`.
#[inline(always)]
fn msac_of(thr_sq: f64, bound: f64, residuals: impl Iterator<Item = (f64, f64)>) -> (f64, usize) {
    let mut sum = 0.0;
    let mut inliers = 0;
    for (n, d) in residuals {
        // Branch-free (whether a point is an inlier is as good as random to the branch
        // predictor): `min` also maps a non-finite ratio (zero denominator) to τ².
        sum += (n / d).min(thr_sq);
        inliers += usize::from(n < thr_sq * d);
        if sum > bound {
            break;
        }
    }
    (sum, inliers)
}

/// Per-point weights, 1 where none are set.
fn weights(w: &[f64]) -> impl Iterator<Item = f64> + '_ {
    w.iter().copied().chain(std::iter::repeat(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::simulate::{simulate, SimulationOptions};
    use crate::model::camera::Camera;
    use crate::model::geometry::{exp_so3, skew};

    #[test]
    fn models_agree_where_they_should() {
        let pair = simulate(&SimulationOptions {
            pixel_noise: 0.0,
            gyro_noise: 0.0,
            angular_velocity: 1.0,
            seed: 11,
            ..Default::default()
        })
        .unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        let (v1, v2) = pair.views().unwrap();
        let d = PointData::new(&v1, &v2, &pair.matches).unwrap();
        let (r, t) = (gt.rotation_matrix(), gt.translation_vector());
        let e = skew(&t) * r;
        for i in 0..d.len() {
            // The paper's linear undistortion (I - v [w]×) m is the first-order expansion of
            // the exact Ω(v)^T m: its error is second order, far below the first-order
            // correction itself (a flipped sign of w would double the correction instead).
            let first_order = (d.b1[i] - d.m1[i]).norm();
            assert!(
                (d.l1[i] - d.b1[i]).norm() <= 0.1 * first_order + 1e-12,
                "point {i}: paper undistortion disagrees with the exact one"
            );
            let exact = d.residual(
                PoseModel::ExactAngular,
                ResidualKind::Sampson,
                i,
                &r,
                &t,
                &e,
            );
            assert!(exact.abs() < 1e-10);
            let lin = d.residual(
                PoseModel::PaperLinear,
                ResidualKind::Algebraic,
                i,
                &r,
                &t,
                &e,
            );
            let gs = d.residual(
                PoseModel::GlobalShutter,
                ResidualKind::Algebraic,
                i,
                &r,
                &t,
                &e,
            );
            assert!(lin.abs() < 0.02 && lin.abs().is_finite(), "{lin} vs {gs}");
        }
        // With zero angular velocity all three coincide.
        let still = View::new(Camera::paper(), Vector3::zeros());
        let d0 = PointData::new(&still, &still, &pair.matches).unwrap();
        let r = exp_so3(&Vector3::new(0.1, 0.2, -0.1));
        for i in 0..10 {
            let a = d0.residual(
                PoseModel::GlobalShutter,
                ResidualKind::Sampson,
                i,
                &r,
                &t,
                &e,
            );
            let b = d0.residual(
                PoseModel::ExactAngular,
                ResidualKind::Sampson,
                i,
                &r,
                &t,
                &e,
            );
            let c = d0.residual(
                PoseModel::PaperLinear,
                ResidualKind::Sampson,
                i,
                &r,
                &t,
                &(skew(&t) * r),
            );
            let a2 = d0.residual(
                PoseModel::GlobalShutter,
                ResidualKind::Sampson,
                i,
                &r,
                &t,
                &(skew(&t) * r),
            );
            assert!((a - b).abs() < 1e-12);
            assert!((c - a2).abs() < 1e-12);
        }
    }

    #[test]
    fn msac_matches_per_point_residuals() {
        let pair = simulate(&SimulationOptions {
            seed: 12,
            outlier_fraction: 0.2,
            ..Default::default()
        })
        .unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        let (v1, v2) = pair.views().unwrap();
        let d = PointData::new(&v1, &v2, &pair.matches).unwrap();
        let r = gt.rotation_matrix() * exp_so3(&Vector3::new(0.003, -0.002, 0.001));
        let t = gt.translation_vector();
        let e = skew(&t) * r;
        for model in [
            PoseModel::GlobalShutter,
            PoseModel::ExactAngular,
            PoseModel::PaperLinear,
        ] {
            for (kind, thr) in [
                (ResidualKind::Algebraic, 0.01f64),
                (ResidualKind::Sampson, 2.0 / 640.0),
            ] {
                let thr_sq = thr * thr;
                let (mut sum, mut inl) = (0.0, 0);
                for i in 0..d.len() {
                    let x = d.residual(model, kind, i, &r, &t, &e);
                    if x * x < thr_sq {
                        sum += x * x;
                        inl += 1;
                    } else {
                        sum += thr_sq;
                    }
                }
                let (s, k) = d.msac(model, kind, &r, &t, &e, thr_sq, f64::INFINITY);
                assert_eq!(k, inl, "{model:?} {kind:?}");
                assert!(
                    (s - sum).abs() <= 1e-9 * sum,
                    "{model:?} {kind:?} {s} {sum}"
                );
                let (s2, _) = d.msac(model, kind, &r, &t, &e, thr_sq, 0.5 * sum);
                assert!(s2 > 0.5 * sum && s2 <= sum * (1.0 + 1e-9), "{s2} {sum}");
            }
        }
    }

    #[test]
    fn sampson_gradient_matches_finite_differences() {
        let cam = Camera::paper();
        let v1 = View::new(cam, Vector3::new(1.0, -2.0, 0.5));
        let v2 = View::new(cam, Vector3::new(-0.5, 1.5, 2.0));
        let r = exp_so3(&Vector3::new(0.1, -0.2, 0.05));
        let t = Vector3::new(0.3, 0.1, 0.9).normalize();
        let e = skew(&t) * r;
        let base: Match = [[700.0, 300.0], [900.0, 500.0]];
        // Gradient w.r.t. x1 of the linear model with the rows held fixed: perturb u1 only
        // (u changes x but not the row).
        let d = PointData::new(&v1, &v2, &[base]).unwrap();
        let h = 1e-3;
        let mut plus = base;
        plus[0][0] += h;
        let mut minus = base;
        minus[0][0] -= h;
        for model in [
            PoseModel::GlobalShutter,
            PoseModel::ExactAngular,
            PoseModel::PaperLinear,
        ] {
            let dp = PointData::new(&v1, &v2, &[plus]).unwrap();
            let dm = PointData::new(&v1, &v2, &[minus]).unwrap();
            let fd = (dp.residual(model, ResidualKind::Algebraic, 0, &r, &t, &e)
                - dm.residual(model, ResidualKind::Algebraic, 0, &r, &t, &e))
                / (2.0 * h / cam.fx);
            let (_, gsq) = d.residual_and_gradient(model, 0, &r, &t, &e);
            assert!(fd.abs() <= gsq.sqrt() + 1e-9, "{model:?}");
            assert!(gsq > 0.0);
        }
    }
}
