//! Generic robust estimation: RANSAC with MSAC scoring and optional local optimisation,
//! structured like PoseLib's `ransac` (an estimator trait + options).
//!
//! Scoring (MSAC): for squared residuals `r_i²` and squared threshold `τ²` the score is
//! `Σ_i min(r_i², τ²)` (lower is better); inliers are the points with `r_i² < τ²`. The
//! residual's units are the estimator's (algebraic, Sampson in normalised image units, ...);
//! the threshold must be in the same units. Sampling is deterministic given the seed
//! (ChaCha8).
//!
//! Local optimisation (as in RansacLib and PoseLib): a minimal model that scores better
//! than every *minimal* model before it is refined once on its approximate inliers
//! (`r² < 5τ²`, [`LO_INLIER_FACTOR`]), and the refined model replaces the best if it scores
//! better. Comparing with the best minimal model, not the best refined one, matters: a
//! sample from the right basin rarely beats a refined model from a wrong one before its
//! own refinement, and would otherwise never be refined.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A model-fitting problem for [`ransac`].
pub trait RansacEstimator {
    /// The model type.
    type Model: Clone;
    /// Number of data points drawn per hypothesis (minimal sample size).
    fn sample_size(&self) -> usize;
    /// Number of data points.
    fn num_data(&self) -> usize;
    /// Append the models fitted to the sample (indices into the data) to `models`.
    fn generate_models(&mut self, sample: &[usize], models: &mut Vec<Self::Model>);
    /// Squared residual of data point `i` under `model` (non-finite counts as an outlier).
    fn residual_sq(&self, model: &Self::Model, i: usize) -> f64;
    /// Local optimisation of `model` on `inliers`, the indices of its approximate inliers
    /// (`r² < LO_INLIER_FACTOR · threshold_sq`): the cost should give no weight to points
    /// beyond the threshold, as MSAC does (e.g. a truncated quadratic, so that points can
    /// enter or leave as the model moves). Returns `None` if refinement is not possible
    /// (the caller keeps the unrefined model).
    fn refine(
        &self,
        model: &Self::Model,
        inliers: &[usize],
        threshold_sq: f64,
    ) -> Option<Self::Model>;
    /// Finish a model that scored better than the best so far, before local optimisation
    /// (e.g. decompose an essential matrix into a pose: scoring needs only the matrix, so
    /// only the few winners pay for it). `false` discards the model. Called right after
    /// [`generate_models`](Self::generate_models) for that sample. Default: nothing to do.
    fn complete(&mut self, _model: &mut Self::Model) -> bool {
        true
    }
    /// MSAC score and inlier count of `model` at squared threshold `threshold_sq`.
    fn score(&self, model: &Self::Model, threshold_sq: f64) -> Score {
        msac_score(self, model, threshold_sq)
    }
    /// Like [`score`](Self::score), but may stop early once the MSAC sum exceeds `bound`
    /// (the model cannot beat a model scoring `bound`); the returned score then has
    /// `msac > bound` and an incomplete inlier count. [`ransac`] calls this with the best
    /// score so far, so most hypotheses are rejected after a few points.
    fn score_bounded(&self, model: &Self::Model, threshold_sq: f64, bound: f64) -> Score {
        let mut msac = 0.0;
        let mut inliers = 0;
        for i in 0..self.num_data() {
            let r = self.residual_sq(model, i);
            if r < threshold_sq {
                msac += r;
                inliers += 1;
            } else {
                msac += threshold_sq;
            }
            if msac > bound {
                break;
            }
        }
        Score { msac, inliers }
    }
}

/// MSAC score (`Σ min(r², τ²)`, lower is better) and the number of inliers (`r² < τ²`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Score {
    /// Truncated quadratic cost.
    pub msac: f64,
    /// Number of points with squared residual below the threshold.
    pub inliers: usize,
}

impl Score {
    /// The worst possible score.
    pub fn worst() -> Self {
        Score {
            msac: f64::INFINITY,
            inliers: 0,
        }
    }

    fn better_than(&self, other: &Score) -> bool {
        self.msac < other.msac
    }
}

/// [`Score`] of `model` (see the module documentation).
pub fn msac_score<E: RansacEstimator + ?Sized>(
    est: &E,
    model: &E::Model,
    threshold_sq: f64,
) -> Score {
    let mut msac = 0.0;
    let mut inliers = 0;
    for i in 0..est.num_data() {
        let r = est.residual_sq(model, i);
        if r < threshold_sq {
            msac += r;
            inliers += 1;
        } else {
            msac += threshold_sq;
        }
    }
    Score { msac, inliers }
}

/// Indices `i` with `residual_sq(model, i) < threshold_sq`.
pub fn inlier_indices<E: RansacEstimator + ?Sized>(
    est: &E,
    model: &E::Model,
    threshold_sq: f64,
) -> Vec<usize> {
    (0..est.num_data())
        .filter(|&i| est.residual_sq(model, i) < threshold_sq)
        .collect()
}

/// Iteration control of [`ransac`].
#[derive(Debug, Clone, PartialEq)]
pub struct RansacOptions {
    /// Squared inlier threshold, in the estimator's residual units.
    pub threshold_sq: f64,
    /// Minimum number of iterations (adaptive mode).
    pub min_iterations: usize,
    /// Maximum number of iterations; with `adaptive = false` exactly this many are run.
    pub max_iterations: usize,
    /// Stop once `1 - (1 - w^s)^k >= success_probability` (`w` inlier ratio of the best
    /// model, `s` sample size, `k` iterations), within `[min, max]` iterations.
    pub adaptive: bool,
    /// Desired probability of drawing at least one all-inlier sample (adaptive mode).
    pub success_probability: f64,
    /// Run [`RansacEstimator::refine`] on each minimal model that beats every earlier
    /// minimal model (LO-RANSAC; see the module documentation) and keep the refined model
    /// if it scores better than the best.
    pub local_optimisation: bool,
    /// Seed of the sampler.
    pub seed: u64,
}

impl Default for RansacOptions {
    fn default() -> Self {
        RansacOptions {
            threshold_sq: 1.0,
            min_iterations: 50,
            max_iterations: 10_000,
            adaptive: true,
            success_probability: 0.9999,
            local_optimisation: true,
            seed: 0,
        }
    }
}

/// Result of [`ransac`].
#[derive(Debug, Clone)]
pub struct RansacResult<M> {
    /// The best model (`None` if no sample produced a model).
    pub model: Option<M>,
    /// Its score.
    pub score: Score,
    /// Iterations (samples drawn).
    pub iterations: usize,
    /// Inlier mask of the best model.
    pub inliers: Vec<bool>,
}

/// Local optimisation refines a model on the points within this multiple of the squared
/// threshold (PoseLib's choice): points just outside the threshold may join as it moves.
pub const LO_INLIER_FACTOR: f64 = 5.0;

/// Number of iterations needed to draw an all-inlier sample with probability `p` when the
/// inlier ratio is `w` and the sample size `s`.
pub fn required_iterations(w: f64, s: usize, p: f64) -> f64 {
    let ws = w.powi(s as i32);
    if ws <= 0.0 {
        return f64::INFINITY;
    }
    if ws >= 1.0 {
        return 0.0;
    }
    (1.0 - p).ln() / (1.0 - ws).ln()
}

/// Draw `k` distinct indices from `0..n` into `out` (rejection; `k` is small).
fn draw_sample(rng: &mut ChaCha8Rng, n: usize, k: usize, out: &mut Vec<usize>) {
    out.clear();
    while out.len() < k {
        let i = rng.gen_range(0..n);
        if !out.contains(&i) {
            out.push(i);
        }
    }
}

/// Run RANSAC/MSAC (with optional local optimisation). Fewer data than the sample size
/// gives no model.
pub fn ransac<E: RansacEstimator>(est: &mut E, options: &RansacOptions) -> RansacResult<E::Model> {
    let n = est.num_data();
    let s = est.sample_size();
    let mut result = RansacResult {
        model: None,
        score: Score::worst(),
        iterations: 0,
        inliers: vec![false; n],
    };
    if n < s || s == 0 || options.max_iterations == 0 {
        return result;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let mut sample = Vec::with_capacity(s);
    let mut models = Vec::new();
    let mut needed = options.max_iterations as f64;
    let mut best_minimal = Score::worst();
    let thr = options.threshold_sq;
    let mut iter = 0;
    while iter < options.max_iterations {
        if options.adaptive && iter >= options.min_iterations && (iter as f64) >= needed {
            break;
        }
        iter += 1;
        draw_sample(&mut rng, n, s, &mut sample);
        models.clear();
        est.generate_models(&sample, &mut models);
        for m in &models {
            // Only a model beating every minimal model so far can be refined into the best.
            let sc = est.score_bounded(m, thr, best_minimal.msac);
            if !sc.better_than(&best_minimal) {
                continue;
            }
            best_minimal = sc;
            let mut model = m.clone();
            if !est.complete(&mut model) {
                continue;
            }
            let mut score = sc;
            if options.local_optimisation {
                let near = inlier_indices(est, &model, LO_INLIER_FACTOR * thr);
                if near.len() >= s {
                    if let Some(r) = est.refine(&model, &near, thr) {
                        let rs = est.score_bounded(&r, thr, score.msac);
                        if rs.better_than(&score) {
                            model = r;
                            score = rs;
                        }
                    }
                }
            }
            if !score.better_than(&result.score) {
                continue;
            }
            result.model = Some(model);
            result.score = score;
            let w = score.inliers as f64 / n as f64;
            needed = required_iterations(w, s, options.success_probability);
        }
    }
    result.iterations = iter;
    if let Some(m) = &result.model {
        for i in 0..n {
            result.inliers[i] = est.residual_sq(m, i) < thr;
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fit a line `y = a x + b` to 2-D points.
    struct LineFit {
        pts: Vec<(f64, f64)>,
        refines: usize,
    }

    impl RansacEstimator for LineFit {
        type Model = (f64, f64);
        fn sample_size(&self) -> usize {
            2
        }
        fn num_data(&self) -> usize {
            self.pts.len()
        }
        fn generate_models(&mut self, sample: &[usize], models: &mut Vec<(f64, f64)>) {
            let (p, q) = (self.pts[sample[0]], self.pts[sample[1]]);
            if (q.0 - p.0).abs() > 1e-12 {
                let a = (q.1 - p.1) / (q.0 - p.0);
                models.push((a, p.1 - a * p.0));
            }
        }
        fn residual_sq(&self, m: &(f64, f64), i: usize) -> f64 {
            let (x, y) = self.pts[i];
            (m.0 * x + m.1 - y).powi(2)
        }
        fn refine(&self, m: &(f64, f64), inl: &[usize], thr_sq: f64) -> Option<(f64, f64)> {
            // Least squares line through the points within the threshold.
            let inl: Vec<usize> = inl
                .iter()
                .copied()
                .filter(|&i| self.residual_sq(m, i) < thr_sq)
                .collect();
            let n = inl.len() as f64;
            let (mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0);
            for &i in &inl {
                let (x, y) = self.pts[i];
                sx += x;
                sy += y;
                sxx += x * x;
                sxy += x * y;
            }
            let det = n * sxx - sx * sx;
            if det.abs() < 1e-12 {
                return None;
            }
            let a = (n * sxy - sx * sy) / det;
            Some((a, (sy - a * sx) / n))
        }
    }

    fn data(seed: u64) -> LineFit {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut pts = Vec::new();
        for i in 0..200 {
            let x = rng.gen_range(-10.0..10.0);
            if i % 5 < 2 {
                pts.push((x, rng.gen_range(-50.0..50.0))); // 40 % outliers
            } else {
                pts.push((x, 2.0 * x - 1.0 + rng.gen_range(-0.05..0.05)));
            }
        }
        LineFit { pts, refines: 0 }
    }

    #[test]
    fn fits_a_line_with_outliers() {
        let mut est = data(1);
        let opts = RansacOptions {
            threshold_sq: 0.1 * 0.1,
            ..Default::default()
        };
        let r = ransac(&mut est, &opts);
        let (a, b) = r.model.unwrap();
        assert!((a - 2.0).abs() < 0.01 && (b + 1.0).abs() < 0.02, "{a} {b}");
        assert!(r.score.inliers >= 118 && r.score.inliers <= 125);
        assert!(r.iterations >= 50 && r.iterations < 200, "{}", r.iterations);
        assert_eq!(r.inliers.iter().filter(|&&x| x).count(), r.score.inliers);
        // Deterministic.
        let r2 = ransac(&mut data(1), &opts);
        assert_eq!(r2.model, r.model);
        assert_eq!(r2.iterations, r.iterations);
        est.refines += 1;
    }

    #[test]
    fn fixed_iterations_and_degenerate_input() {
        let opts = RansacOptions {
            threshold_sq: 0.01,
            adaptive: false,
            max_iterations: 200,
            local_optimisation: false,
            ..Default::default()
        };
        let r = ransac(&mut data(2), &opts);
        assert_eq!(r.iterations, 200);
        assert!(r.model.is_some());
        let mut one = LineFit {
            pts: vec![(1.0, 1.0)],
            refines: 0,
        };
        assert!(ransac(&mut one, &opts).model.is_none());
        let mut same = LineFit {
            pts: vec![(1.0, 1.0); 10],
            refines: 0,
        };
        let r = ransac(&mut same, &opts);
        assert!(r.model.is_none());
        assert!(r.inliers.iter().all(|&x| !x));
    }

    #[test]
    fn iteration_formula() {
        assert!((required_iterations(0.5, 5, 0.99) - 145.05).abs() < 0.1);
        assert_eq!(required_iterations(1.0, 5, 0.99), 0.0);
        assert!(required_iterations(0.0, 5, 0.99).is_infinite());
    }
}
