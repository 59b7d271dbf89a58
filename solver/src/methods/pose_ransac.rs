//! RANSAC estimators shared by the methods: essential-matrix hypotheses (from plain or
//! gyro-undistorted bearings) and G-RSRP hypotheses, both scored with a per-point epipolar
//! residual ([`crate::model::epipolar`]).

use super::{EstimateError, EstimateOptions, RobustOptions, Threshold};
use crate::estimation::ransac::{ransac, RansacEstimator, RansacOptions, RansacResult, Score};
use crate::estimation::refine::{refine_pose, LmOptions, Loss, Pose};
use crate::minimal::{EssentialSolver, GrsrpSample, GrsrpSolver};
use crate::model::camera::View;
use crate::model::epipolar::{PointData, PoseModel, ResidualKind, RowNoise};
use crate::model::geometry::{fix_translation_sign, pose_from_essential, skew};
use nalgebra::{Matrix3, Vector3};

/// A pose hypothesis with its essential matrix `E = [t]× R`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hypothesis {
    pub r: Matrix3<f64>,
    pub t: Vector3<f64>,
    pub e: Matrix3<f64>,
}

impl Hypothesis {
    /// An essential matrix not yet decomposed (`r`, `t` zero), scaled to `‖E‖_F = √2`, the
    /// norm of `[t]× R` with a unit `t`, so that algebraic residuals match the pose's.
    /// [`EssentialRansac`] decomposes it in [`RansacEstimator::complete`].
    fn essential(e: &Matrix3<f64>) -> Self {
        Hypothesis {
            r: Matrix3::zeros(),
            t: Vector3::zeros(),
            e: e * (std::f64::consts::SQRT_2 / e.norm()),
        }
    }

    pub fn new(r: Matrix3<f64>, t: Vector3<f64>) -> Self {
        Hypothesis {
            r,
            t,
            e: skew(&t) * r,
        }
    }
    pub fn from_pose(p: &Pose) -> Self {
        Self::new(p.matrix(), p.translation)
    }
    pub fn pose(&self) -> Pose {
        Pose::new(&self.r, &self.t)
    }
}

/// Residual kind and squared threshold for the given views.
pub(crate) fn threshold(view1: &View, view2: &View, t: Threshold) -> (ResidualKind, f64) {
    match t {
        Threshold::Algebraic(x) => (ResidualKind::Algebraic, x * x),
        Threshold::SampsonPixels(px) => {
            let f = 0.5 * (view1.camera.mean_focal() + view2.camera.mean_focal());
            (ResidualKind::Sampson, (px / f).powi(2))
        }
    }
}

/// Residual kind and squared threshold of the global-shutter model:
/// [`RobustOptions::global_shutter_threshold`] widened by the rolling-shutter allowance.
pub(crate) fn gs_threshold(view1: &View, view2: &View, o: &RobustOptions) -> (ResidualKind, f64) {
    match o.global_shutter_threshold {
        Threshold::SampsonPixels(px) => {
            let rs = |v: &View| {
                v.camera.mean_focal() * v.camera.readout * v.camera.lines() * v.omega.norm()
            };
            let px = px + o.rolling_shutter_allowance * rs(view1).max(rs(view2));
            threshold(view1, view2, Threshold::SampsonPixels(px))
        }
        t => threshold(view1, view2, t),
    }
}

/// Bearings and row data of the matches, with the per-point noise model of the options
/// (only for pixel thresholds: the paper's algebraic threshold is unweighted).
pub(crate) fn point_data(
    view1: &View,
    view2: &View,
    matches: &[crate::model::matches::Match],
    o: &RobustOptions,
) -> Result<PointData, crate::model::epipolar::UnobservableMatch> {
    let mut data = PointData::new(view1, view2, matches)?;
    if matches!(o.threshold, Threshold::SampsonPixels(_)) {
        data.set_row_noise(row_noise(view1, view2, o.pixel_noise, o.gyro_noise));
    }
    Ok(data)
}

/// The per-match noise model of pixel noise `pixel_noise` (px) and gyro-rate noise
/// `gyro_noise` (rad/s per axis), in normalised units of the two views' mean focal length.
pub(crate) fn row_noise(view1: &View, view2: &View, pixel_noise: f64, gyro_noise: f64) -> RowNoise {
    let f = 0.5 * (view1.camera.mean_focal() + view2.camera.mean_focal());
    RowNoise {
        pixel: pixel_noise / f,
        rate_per_row: gyro_noise * view1.camera.readout.max(view2.camera.readout),
        truncation: 1.0,
    }
}

pub(crate) fn ransac_options(r: &RobustOptions, thr_sq: f64) -> RansacOptions {
    RansacOptions {
        threshold_sq: thr_sq,
        min_iterations: r.min_iterations.min(r.max_iterations),
        max_iterations: r.max_iterations,
        adaptive: r.adaptive,
        success_probability: r.success_probability,
        local_optimisation: r.local_optimisation,
        seed: r.seed,
    }
}

/// LM settings for local optimisation (a few iterations, with a truncated quadratic at the
/// inlier threshold: the MSAC cost).
fn lo_options(base: &LmOptions) -> LmOptions {
    LmOptions {
        max_iterations: base.max_iterations.min(10),
        ..base.clone()
    }
}

/// How both RANSACs judge and polish a pose hypothesis: its residuals under `model` and
/// `kind`, their MSAC score, and local optimisation by a few LM iterations on the truncated
/// quadratic at the threshold.
pub(crate) struct PoseScorer<'a> {
    pub data: &'a PointData,
    pub model: PoseModel,
    pub kind: ResidualKind,
    pub lm: LmOptions,
}

impl PoseScorer<'_> {
    /// Squared residual of match `i` (infinite where it is not finite).
    fn residual_sq(&self, m: &Hypothesis, i: usize) -> f64 {
        let r = self
            .data
            .residual(self.model, self.kind, i, &m.r, &m.t, &m.e);
        if r.is_finite() {
            r * r
        } else {
            f64::INFINITY
        }
    }

    /// MSAC score, abandoned once it exceeds `bound`.
    fn score_bounded(&self, m: &Hypothesis, thr_sq: f64, bound: f64) -> Score {
        let (msac, inliers) = self
            .data
            .msac(self.model, self.kind, &m.r, &m.t, &m.e, thr_sq, bound);
        Score { msac, inliers }
    }

    /// Local optimisation of `m` on `inliers`.
    fn refine(&self, m: &Hypothesis, inliers: &[usize], thr_sq: f64) -> Option<Hypothesis> {
        let res = refine_pose(
            self.data,
            inliers,
            self.model,
            self.kind,
            Loss::Truncated(thr_sq.sqrt()),
            m.pose(),
            &lo_options(&self.lm),
        );
        Some(Hypothesis::from_pose(&res.state))
    }
}

/// Essential-matrix RANSAC on bearings `b` (plain `m` or gyro-undistorted), scored with
/// `scorer`.
pub(crate) struct EssentialRansac<'a> {
    pub scorer: PoseScorer<'a>,
    pub undistorted: bool,
    pub solver: EssentialSolver,
    pub es: Vec<Matrix3<f64>>,
    /// The current sample's bearings (for the cheirality test of [`RansacEstimator::complete`]).
    pub sample: ([Vector3<f64>; 8], [Vector3<f64>; 8], usize),
}

impl<'a> EssentialRansac<'a> {
    /// Essential-matrix RANSAC on bearings `m` (`undistorted = false`) or the
    /// gyro-undistorted `b`, scored with `model` and `kind`.
    pub fn new(
        data: &'a PointData,
        undistorted: bool,
        model: PoseModel,
        kind: ResidualKind,
        options: &EstimateOptions,
    ) -> Self {
        EssentialRansac {
            scorer: PoseScorer {
                data,
                model,
                kind,
                lm: options.refinement.clone(),
            },
            undistorted,
            solver: options.essential_solver,
            es: Vec::new(),
            sample: ([Vector3::zeros(); 8], [Vector3::zeros(); 8], 0),
        }
    }

    /// Essential-matrix RANSAC on gyro-undistorted bearings scored with the exact angular
    /// model (`rectified`'s), with the options' solver and LM settings.
    pub fn exact(data: &'a PointData, kind: ResidualKind, options: &EstimateOptions) -> Self {
        Self::new(data, true, PoseModel::ExactAngular, kind, options)
    }
}

impl RansacEstimator for EssentialRansac<'_> {
    type Model = Hypothesis;
    fn sample_size(&self) -> usize {
        self.solver.sample_size()
    }
    fn num_data(&self) -> usize {
        self.scorer.data.len()
    }
    fn generate_models(&mut self, sample: &[usize], models: &mut Vec<Hypothesis>) {
        let data = self.scorer.data;
        let (b1, b2) = if self.undistorted {
            (&data.b1, &data.b2)
        } else {
            (&data.m1, &data.m2)
        };
        let (buf1, buf2, k) = &mut self.sample;
        *k = sample.len().min(8);
        for (j, &i) in sample.iter().take(*k).enumerate() {
            buf1[j] = b1[i];
            buf2[j] = b2[i];
        }
        let mut es = std::mem::take(&mut self.es);
        es.clear();
        self.solver.solve(&buf1[..*k], &buf2[..*k], &mut es);
        // Scoring needs only E; the pose is extracted for the winners (`complete`).
        models.extend(
            es.iter()
                .filter(|e| e.norm() > 0.0 && e.iter().all(|x| x.is_finite()))
                .map(Hypothesis::essential),
        );
        self.es = es;
    }
    fn complete(&mut self, m: &mut Hypothesis) -> bool {
        let (s1, s2, k) = &self.sample;
        match pose_from_essential(&m.e, &s1[..*k], &s2[..*k]) {
            Some((r, t)) => {
                *m = Hypothesis::new(r, t);
                true
            }
            None => false,
        }
    }
    fn residual_sq(&self, m: &Hypothesis, i: usize) -> f64 {
        self.scorer.residual_sq(m, i)
    }
    fn score_bounded(&self, m: &Hypothesis, thr_sq: f64, bound: f64) -> Score {
        self.scorer.score_bounded(m, thr_sq, bound)
    }
    fn refine(&self, m: &Hypothesis, inliers: &[usize], thr_sq: f64) -> Option<Hypothesis> {
        self.scorer.refine(m, inliers, thr_sq)
    }
}

/// G-RSRP RANSAC: the generated solver with a fixed `R_0`, scored (and locally optimised)
/// by `scorer`: the paper's linearised model or the exact angular one.
pub(crate) struct GrsrpRansac<'a> {
    pub scorer: PoseScorer<'a>,
    pub solver: GrsrpSolver,
    pub r0: Matrix3<f64>,
    pub sols: Vec<(Matrix3<f64>, Vector3<f64>)>,
}

impl RansacEstimator for GrsrpRansac<'_> {
    type Model = Hypothesis;
    fn sample_size(&self) -> usize {
        5
    }
    fn num_data(&self) -> usize {
        self.scorer.data.len()
    }
    fn generate_models(&mut self, sample: &[usize], models: &mut Vec<Hypothesis>) {
        let d = self.scorer.data;
        let s = GrsrpSample::from_points(d, &std::array::from_fn(|k| sample[k]), self.r0);
        let mut sols = std::mem::take(&mut self.sols);
        sols.clear();
        self.solver.solve(&s, &mut sols);
        let b1: [Vector3<f64>; 5] = std::array::from_fn(|k| d.b1[sample[k]]);
        let b2: [Vector3<f64>; 5] = std::array::from_fn(|k| d.b2[sample[k]]);
        for (r, t) in &sols {
            let t = fix_translation_sign(r, t, &b1, &b2);
            models.push(Hypothesis::new(*r, t));
        }
        self.sols = sols;
    }
    fn residual_sq(&self, m: &Hypothesis, i: usize) -> f64 {
        self.scorer.residual_sq(m, i)
    }
    fn score_bounded(&self, m: &Hypothesis, thr_sq: f64, bound: f64) -> Score {
        self.scorer.score_bounded(m, thr_sq, bound)
    }
    fn refine(&self, m: &Hypothesis, inliers: &[usize], thr_sq: f64) -> Option<Hypothesis> {
        self.scorer.refine(m, inliers, thr_sq)
    }
}

/// Run RANSAC and return the best hypothesis, or `NoSolution`.
pub(crate) fn run<E: RansacEstimator<Model = Hypothesis>>(
    est: &mut E,
    options: &EstimateOptions,
    thr_sq: f64,
) -> Result<(Hypothesis, RansacResult<Hypothesis>), EstimateError> {
    let res = ransac(est, &ransac_options(&options.robust, thr_sq));
    match res.model {
        Some(h) if res.score.inliers > 0 => Ok((h, res)),
        _ => Err(EstimateError::NoSolution),
    }
}

/// Indices of the `true` entries of a mask.
pub(crate) fn indices(mask: &[bool]) -> Vec<usize> {
    mask.iter()
        .enumerate()
        .filter_map(|(i, &b)| b.then_some(i))
        .collect()
}

/// The pose of `h`'s essential matrix `[t]× R` that the most inliers triangulate in front of
/// both cameras, on bearings `b1`, `b2`: of its four decompositions, the twisted pair (the
/// rotation turned 180° about `t`) included, not only the sign of `t`. RANSAC scores an
/// essential matrix, which both rotations of the pair share, and picks between them by
/// cheirality on its minimal sample alone; with a few noisy or mismatched points there, the
/// pair's wrong rotation can win. If `E` cannot be decomposed, `h`'s rotation with the sign
/// of `t` by cheirality.
pub(crate) fn decompose_on_inliers(
    h: &Hypothesis,
    b1: &[Vector3<f64>],
    b2: &[Vector3<f64>],
    inliers: &[usize],
) -> (Matrix3<f64>, Vector3<f64>) {
    let s1: Vec<Vector3<f64>> = inliers.iter().map(|&i| b1[i]).collect();
    let s2: Vec<Vector3<f64>> = inliers.iter().map(|&i| b2[i]).collect();
    pose_from_essential(&(skew(&h.t) * h.r), &s1, &s2)
        .unwrap_or_else(|| (h.r, fix_translation_sign(&h.r, &h.t, &s1, &s2)))
}

/// Fix the sign of `t` by cheirality over the inliers, using bearings `b1`, `b2`.
pub(crate) fn orient(
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    b1: &[Vector3<f64>],
    b2: &[Vector3<f64>],
    inliers: &[usize],
) -> Vector3<f64> {
    let s1: Vec<Vector3<f64>> = inliers.iter().map(|&i| b1[i]).collect();
    let s2: Vec<Vector3<f64>> = inliers.iter().map(|&i| b2[i]).collect();
    fix_translation_sign(r, t, &s1, &s2)
}
