//! Every method on a set of real pairs, against a rotation reference: the pair's ground
//! truth where it has one, else the relative rotation integrated from its gyro log
//! ([`PairFile::gyro_relative_rotation`]). On real recordings that reference is not
//! independent of the gyro methods (they read the same gyro, though only its rate within
//! each frame), and there is none for the translation.

use crate::data::pair_file::PairFile;
use crate::methods::{estimate_relative_pose, EstimateOptions, Method};
use crate::model::geometry::rotation_error_deg;
use nalgebra::Matrix3;
use serde::Serialize;
use std::time::Instant;

/// One method's figures over the pairs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RealRow {
    /// The method's name.
    pub method: String,
    /// Pairs estimated.
    pub pairs: usize,
    /// Pairs without an estimate.
    pub failures: usize,
    /// Median rotation difference to the reference, degrees.
    pub rot_median: f64,
    /// Largest rotation difference to the reference, degrees.
    pub rot_max: f64,
    /// Median inlier ratio.
    pub inlier_ratio_median: f64,
    /// Median time per estimate, seconds.
    pub seconds_median: f64,
    /// Per pair: rotation difference in degrees (NaN where the method failed).
    pub per_pair_deg: Vec<f64>,
}

/// The rotation reference of a pair: its ground truth, else the gyro-integrated rotation.
pub fn reference_rotation(pair: &PairFile) -> Option<Matrix3<f64>> {
    match &pair.ground_truth {
        Some(gt) => Some(gt.rotation_matrix()),
        None => pair.gyro_relative_rotation(),
    }
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Runs `methods` on every pair with `options_for(method, pair)`; `constant_rows` drops the
/// integrated gyro tracks (each frame's mean rate only). Pairs without a reference are
/// skipped by the caller ([`reference_rotation`]); here they count as failures.
pub fn run_real(
    pairs: &[PairFile],
    methods: &[Method],
    options_for: impl Fn(Method, &PairFile) -> EstimateOptions,
    constant_rows: bool,
) -> Vec<RealRow> {
    methods
        .iter()
        .map(|&method| {
            let mut per_pair = Vec::with_capacity(pairs.len());
            let mut ratios = Vec::new();
            let mut seconds = Vec::new();
            for pair in pairs {
                let result = (|| {
                    let reference = reference_rotation(pair)?;
                    let (mut v1, mut v2) = pair.views().ok()?;
                    if constant_rows {
                        (v1, v2) = (v1.constant_rate(), v2.constant_rate());
                    }
                    let options = options_for(method, pair);
                    let start = Instant::now();
                    let est = estimate_relative_pose(&v1, &v2, &pair.matches, &options).ok()?;
                    seconds.push(start.elapsed().as_secs_f64());
                    ratios.push(est.num_inliers() as f64 / pair.matches.len().max(1) as f64);
                    Some(rotation_error_deg(&reference, &est.rotation))
                })();
                per_pair.push(result.unwrap_or(f64::NAN));
            }
            let mut ok: Vec<f64> = per_pair.iter().copied().filter(|x| x.is_finite()).collect();
            let rot_max = ok.iter().copied().fold(f64::NAN, f64::max);
            RealRow {
                method: method.name().to_string(),
                pairs: pairs.len(),
                failures: pairs.len() - ok.len(),
                rot_median: median(&mut ok),
                rot_max,
                inlier_ratio_median: median(&mut ratios),
                seconds_median: median(&mut seconds),
                per_pair_deg: per_pair,
            }
        })
        .collect()
}

/// A Markdown table of the rows (rotation in degrees, inliers in percent, time in ms).
pub fn to_markdown(rows: &[RealRow]) -> String {
    let mut s = String::from(
        "| method | median / max rotation difference (deg) | median inliers | median time | failures |\n|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| `{}` | {:.3} / {:.3} | {:.1} % | {:.1} ms | {} of {} |\n",
            r.method,
            r.rot_median,
            r.rot_max,
            100.0 * r.inlier_ratio_median,
            1e3 * r.seconds_median,
            r.failures,
            r.pairs
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(&mut []).is_nan());
    }
}
