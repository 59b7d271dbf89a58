//! Every method on a set of real pairs, against a rotation reference: the pair's ground
//! truth where it has one, else the relative rotation integrated from its gyro log
//! ([`PairFile::gyro_relative_rotation`]). On real recordings that reference is not
//! independent of the gyro methods (they read the same gyro, though only its rate within
//! each frame), and there is none for the translation.

use crate::data::pair_estimate::{estimate_pair, RowModel};
use crate::data::pair_file::PairFile;
use crate::methods::{EstimateOptions, Method};
use crate::model::geometry::rotation_error_deg;
use crate::stats::median;
use nalgebra::Matrix3;
use serde::Serialize;
use std::collections::BTreeMap;
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
    /// Pairs whose estimate raised a quality flag ([`crate::methods::Quality::flags`]): an
    /// answer the estimator cannot vouch for (random matches, collinear points, no
    /// baseline, ...).
    pub flagged: usize,
    /// How many estimates raised each flag, by flag name (sorted).
    pub flags: BTreeMap<String, usize>,
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

/// Runs `methods` on every pair with `options_for(method, pair)` and the row model `rows`
/// ([`estimate_pair`]). Pairs without a reference are
/// skipped by the caller ([`reference_rotation`]); here they count as failures.
pub fn run_real(
    pairs: &[PairFile],
    methods: &[Method],
    options_for: impl Fn(Method, &PairFile) -> EstimateOptions,
    rows: RowModel,
) -> Vec<RealRow> {
    methods
        .iter()
        .map(|&method| {
            let mut per_pair = Vec::with_capacity(pairs.len());
            let mut ratios = Vec::new();
            let mut seconds = Vec::new();
            let mut flagged = 0;
            let mut flags = BTreeMap::new();
            for pair in pairs {
                let result = (|| {
                    let reference = reference_rotation(pair)?;
                    let options = options_for(method, pair);
                    let start = Instant::now();
                    let est = estimate_pair(pair, &options, rows, None).ok()?;
                    seconds.push(start.elapsed().as_secs_f64());
                    ratios.push(est.num_inliers() as f64 / pair.matches.len().max(1) as f64);
                    let raised = est.quality.flags();
                    flagged += usize::from(!raised.is_empty());
                    for f in raised {
                        *flags.entry(f.to_string()).or_insert(0) += 1;
                    }
                    Some(rotation_error_deg(&reference, &est.rotation))
                })();
                per_pair.push(result.unwrap_or(f64::NAN));
            }
            let ok: Vec<f64> = per_pair.iter().copied().filter(|x| x.is_finite()).collect();
            let rot_max = ok.iter().copied().fold(f64::NAN, f64::max);
            RealRow {
                method: method.name().to_string(),
                pairs: pairs.len(),
                failures: pairs.len() - ok.len(),
                rot_median: median(&ok),
                rot_max,
                inlier_ratio_median: median(&ratios),
                seconds_median: median(&seconds),
                flagged,
                flags,
                per_pair_deg: per_pair,
            }
        })
        .collect()
}

/// A Markdown table of the rows (rotation in degrees, inliers in percent, time in ms;
/// "flagged" counts the estimates with a quality flag, naming the flags raised).
pub fn to_markdown(rows: &[RealRow]) -> String {
    let mut s = String::from(
        "| method | median / max rotation difference (deg) | median inliers | median time | failures | flagged |\n|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let flagged = if r.flags.is_empty() {
            "0".to_string()
        } else {
            let names: Vec<String> = r.flags.iter().map(|(f, n)| format!("{f} {n}")).collect();
            format!("{} ({})", r.flagged, names.join(", "))
        };
        s.push_str(&format!(
            "| `{}` | {:.3} / {:.3} | {:.1} % | {:.1} ms | {} of {} | {} |\n",
            r.method,
            r.rot_median,
            r.rot_max,
            100.0 * r.inlier_ratio_median,
            1e3 * r.seconds_median,
            r.failures,
            r.pairs,
            flagged
        ));
    }
    s
}
