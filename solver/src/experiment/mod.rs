//! The paper's synthetic experiments: sweeps over motion and noise levels, many trials per
//! level, every method on the same simulated scenes, summarised to CSV and plotted to SVG.
//!
//! Results depend only on the seed: trial `j` of level `i` simulates its scene from a seed
//! derived from `(seed, i, j)`, and trials are collected by index, so the number of worker
//! threads changes the wall time, never the numbers (except the timing columns).

pub mod evaluate;
#[cfg(feature = "plot")]
mod plot;
pub mod real;
mod sweep;

pub use crate::stats::{median, summarize};
#[cfg(feature = "plot")]
pub use plot::{render_svg, write_svg};
pub use sweep::{Level, Sweep, UnknownSweep, READOUT_REFINED_LABEL};

/// Output files are written whole or not at all (see [`crate::data::atomic_file`]).
pub use crate::data::atomic_file::write_output;

use crate::data::pair_file::PairFile;
use crate::data::simulate::{simulate, SimulationOptions};
use crate::estimation::readout::ReadoutOptions;
use crate::experiment::evaluate::pose_errors;
use crate::{estimate_relative_pose, EstimateOptions, Method};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// The outcome of one method on one simulated scene.
#[derive(Clone, Debug, PartialEq)]
pub struct MethodOutcome {
    /// The method's name (`gsrp`, `grsrp+`, ...).
    pub method: String,
    /// Rotation error in degrees, `None` if the method failed on this scene.
    pub rotation_error_deg: Option<f64>,
    /// Translation direction error in degrees, `None` if the method failed.
    pub translation_error_deg: Option<f64>,
    /// Wall time of the estimate in seconds.
    pub seconds: f64,
    /// Inliers of the estimate (`None` if the method failed).
    pub inliers: Option<usize>,
}

/// One row of a sweep's CSV: the statistics of one method at one level.
#[derive(Clone, Debug, PartialEq)]
pub struct SummaryRow {
    /// The level's x-axis value.
    pub level: f64,
    /// The method's name.
    pub method: String,
    /// Mean rotation error (degrees) over the successful trials.
    pub rot_mean: f64,
    /// Standard deviation of the rotation error (degrees).
    pub rot_std: f64,
    /// Median rotation error (degrees).
    pub rot_median: f64,
    /// Mean translation error (degrees).
    pub trans_mean: f64,
    /// Standard deviation of the translation error (degrees).
    pub trans_std: f64,
    /// Median translation error (degrees).
    pub trans_median: f64,
    /// Median wall time per estimate (seconds).
    pub seconds_median: f64,
    /// Trials in which the method returned no pose (excluded from the statistics above).
    pub failures: usize,
}

/// Settings of a sweep run.
#[derive(Clone, Debug)]
pub struct ExperimentOptions {
    /// Trials per level (the paper: 100).
    pub trials: usize,
    /// Master seed; every scene's seed derives from it.
    pub seed: u64,
    /// Worker threads (default: the available parallelism).
    pub threads: usize,
}

impl Default for ExperimentOptions {
    fn default() -> Self {
        ExperimentOptions {
            trials: 100,
            seed: 2024,
            threads: std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1),
        }
    }
}

/// The simulator settings of one scene at `level` (paper protocol otherwise).
pub fn level_simulation(level: &Level, seed: u64) -> SimulationOptions {
    SimulationOptions {
        angular_velocity: level.angular,
        linear_velocity: level.linear,
        pixel_noise: level.pixel_noise,
        gyro_noise: level.gyro_noise,
        gravity_noise_deg: level.gravity_noise_deg,
        outlier_fraction: level.outlier_fraction,
        seed,
        ..SimulationOptions::default()
    }
}

/// Simulates one scene at `level` from `seed`, gives the estimator the readout time
/// `level.readout_factor` times the true one, and runs each of `methods` on it (see
/// [`run_methods`]), then, if `level.compare_readout_refinement`, `rectified` with the
/// readout-scale refinement (labelled [`READOUT_REFINED_LABEL`]). A scene that cannot be
/// simulated counts as a failure of every method.
pub fn scene_trial(
    level: &Level,
    seed: u64,
    methods: &[Method],
    options_for: impl Fn(Method) -> EstimateOptions,
) -> Vec<MethodOutcome> {
    let refined = |m| EstimateOptions {
        readout: Some(ReadoutOptions::default()),
        ..options_for(m)
    };
    let label = |mut outcomes: Vec<MethodOutcome>| {
        for o in &mut outcomes {
            o.method = READOUT_REFINED_LABEL.to_string();
        }
        outcomes
    };
    let variant = [Method::Rectified];
    let variant = if level.compare_readout_refinement {
        &variant[..]
    } else {
        &[]
    };
    match simulate(&level_simulation(level, seed)) {
        Ok(mut pair) => {
            for camera in &mut pair.cameras {
                camera.readout *= level.readout_factor;
            }
            let mut out = run_methods(&pair, methods, &options_for);
            out.extend(label(run_methods(&pair, variant, refined)));
            out
        }
        Err(_) => {
            let failed = |ms: &[Method]| ms.iter().map(|&m| MethodOutcome::failed(m)).collect();
            let mut out: Vec<MethodOutcome> = failed(methods);
            out.extend(label(failed(variant)));
            out
        }
    }
}

impl MethodOutcome {
    /// The outcome of `method` when it returned no pose.
    pub fn failed(method: Method) -> Self {
        MethodOutcome {
            method: method.name().to_string(),
            rotation_error_deg: None,
            translation_error_deg: None,
            seconds: 0.0,
            inliers: None,
        }
    }
}

/// Runs each of `methods` on a simulated pair with the options `options_for(method)`, timing
/// each estimate and measuring its errors against the pair's ground truth. A method that
/// returns an error (or a pair without ground truth) is recorded as a failure.
pub fn run_methods(
    pair: &PairFile,
    methods: &[Method],
    options_for: impl Fn(Method) -> EstimateOptions,
) -> Vec<MethodOutcome> {
    methods
        .iter()
        .map(|&m| {
            let failed = MethodOutcome::failed(m);
            let Some(gt) = &pair.ground_truth else {
                return failed;
            };
            let Ok((v1, v2)) = pair.views() else {
                return failed;
            };
            let start = Instant::now();
            let est = estimate_relative_pose(&v1, &v2, &pair.matches, &options_for(m));
            let seconds = start.elapsed().as_secs_f64();
            match est {
                Ok(e) => {
                    let err = pose_errors(&e, gt);
                    MethodOutcome {
                        method: m.name().to_string(),
                        rotation_error_deg: Some(err.rotation_error_deg),
                        translation_error_deg: Some(err.translation_error_deg),
                        seconds,
                        inliers: Some(e.num_inliers()),
                    }
                }
                Err(_) => MethodOutcome { seconds, ..failed },
            }
        })
        .collect()
}

/// The seed of trial `trial` at level `level` (SplitMix64 mixing of the three numbers).
pub fn trial_seed(seed: u64, level: usize, trial: usize) -> u64 {
    let mut z = seed
        ^ (level as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (trial as u64).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Every trial's outcomes of a sweep and their summary.
#[derive(Debug, Clone)]
pub struct SweepResult {
    /// The sweep's levels.
    pub levels: Vec<Level>,
    /// Trials per level.
    pub trials: usize,
    /// Outcomes stored level-major: `outcomes[level * trials + trial]`.
    pub outcomes: Vec<Vec<MethodOutcome>>,
    /// Summary per level and method.
    pub rows: Vec<SummaryRow>,
}

/// Runs `trial(level, seed)` for every level of `sweep` and every trial index, on
/// `options.threads` threads, and summarises per level and method (in the order methods
/// appear in the first trial's outcomes). `progress(done, total)` is called after each trial.
pub fn run_sweep<T, P>(
    sweep: Sweep,
    options: &ExperimentOptions,
    trial: T,
    progress: P,
) -> SweepResult
where
    T: Fn(&Level, u64) -> Vec<MethodOutcome> + Sync,
    P: Fn(usize, usize) + Sync,
{
    let levels = sweep.levels();
    let total = levels.len() * options.trials;
    let results: Vec<Mutex<Option<Vec<MethodOutcome>>>> =
        (0..total).map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    std::thread::scope(|scope| {
        for _ in 0..options.threads.max(1) {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= total {
                    break;
                }
                let (li, ti) = (k / options.trials, k % options.trials);
                let outcome = trial(&levels[li], trial_seed(options.seed, li, ti));
                *results[k].lock().unwrap_or_else(|e| e.into_inner()) = Some(outcome);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            });
        }
    });
    let results: Vec<Vec<MethodOutcome>> = results
        .into_iter()
        .map(|m| {
            m.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .unwrap_or_default()
        })
        .collect();
    let rows = summarize_levels(&levels, options.trials, &results);
    SweepResult {
        levels,
        trials: options.trials,
        outcomes: results,
        rows,
    }
}

/// The header of the per-trial CSV ([`trials_csv`]).
pub const TRIALS_CSV_HEADER: &str = "level,trial,method,rot_err,trans_err,inliers";

/// One line per trial and method: the errors (degrees, empty for a failure) and inliers.
/// No timings, so the file depends only on the numerics and the seed.
pub fn trials_csv(result: &SweepResult) -> String {
    let mut s = String::from(TRIALS_CSV_HEADER);
    s.push('\n');
    for (k, outcomes) in result.outcomes.iter().enumerate() {
        let (li, ti) = (k / result.trials, k % result.trials);
        for o in outcomes {
            s.push_str(&trial_line(result.levels[li].value, ti, o));
        }
    }
    s
}

/// One line of [`trials_csv`].
pub fn trial_line(level: f64, trial: usize, o: &MethodOutcome) -> String {
    // Shortest round-trip form: the summary recomputed from the file is exact.
    let f = |x: Option<f64>| x.map(|v| format!("{v}")).unwrap_or_default();
    let n = o.inliers.map(|n| n.to_string()).unwrap_or_default();
    format!(
        "{level},{trial},{},{},{},{n}\n",
        o.method,
        f(o.rotation_error_deg),
        f(o.translation_error_deg)
    )
}

/// Summarises trial outcomes stored level-major (`results[level * trials + trial]`).
pub fn summarize_levels(
    levels: &[Level],
    trials: usize,
    results: &[Vec<MethodOutcome>],
) -> Vec<SummaryRow> {
    let mut methods: Vec<String> = Vec::new();
    for r in results {
        for o in r {
            if !methods.contains(&o.method) {
                methods.push(o.method.clone());
            }
        }
    }
    let mut rows = Vec::new();
    for (li, level) in levels.iter().enumerate() {
        let chunk = &results[li * trials..(li + 1) * trials];
        for m in &methods {
            let outcomes: Vec<&MethodOutcome> =
                chunk.iter().flatten().filter(|o| &o.method == m).collect();
            let ok: Vec<&&MethodOutcome> = outcomes
                .iter()
                .filter(|o| o.rotation_error_deg.is_some() && o.translation_error_deg.is_some())
                .collect();
            let rot: Vec<f64> = ok.iter().filter_map(|o| o.rotation_error_deg).collect();
            let trans: Vec<f64> = ok.iter().filter_map(|o| o.translation_error_deg).collect();
            let secs: Vec<f64> = outcomes.iter().map(|o| o.seconds).collect();
            let (rot_mean, rot_std, rot_median) =
                summarize(&rot).unwrap_or((f64::NAN, f64::NAN, f64::NAN));
            let (trans_mean, trans_std, trans_median) =
                summarize(&trans).unwrap_or((f64::NAN, f64::NAN, f64::NAN));
            rows.push(SummaryRow {
                level: level.value,
                method: m.clone(),
                rot_mean,
                rot_std,
                rot_median,
                trans_mean,
                trans_std,
                trans_median,
                seconds_median: median(&secs),
                failures: outcomes.len() - ok.len(),
            });
        }
    }
    rows
}

/// The CSV header (the columns `rspose experiment` documents, then `failures`).
pub const CSV_HEADER: &str =
    "level,method,rot_mean,rot_std,rot_median,trans_mean,trans_std,trans_median,seconds_median,failures";

/// Renders summary rows as CSV text.
pub fn to_csv(rows: &[SummaryRow]) -> String {
    let mut s = String::from(CSV_HEADER);
    s.push('\n');
    for r in rows {
        s.push_str(&format!(
            "{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.9},{}\n",
            r.level,
            r.method,
            r.rot_mean,
            r.rot_std,
            r.rot_median,
            r.trans_mean,
            r.trans_std,
            r.trans_median,
            r.seconds_median,
            r.failures
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fake_trial(level: &Level, seed: u64) -> Vec<MethodOutcome> {
        // A deterministic function of (level, seed) standing in for a simulated scene.
        let e = (seed % 1000) as f64 / 1000.0 * level.angular;
        vec![
            MethodOutcome {
                method: "a".into(),
                rotation_error_deg: Some(e),
                translation_error_deg: Some(2.0 * e),
                seconds: 0.0,
                inliers: Some(100),
            },
            MethodOutcome {
                method: "b".into(),
                rotation_error_deg: if seed % 7 == 0 { None } else { Some(e + 1.0) },
                translation_error_deg: Some(e),
                seconds: 0.0,
                inliers: None,
            },
        ]
    }

    #[test]
    fn results_do_not_depend_on_thread_count() {
        let run = |threads| {
            let opts = ExperimentOptions {
                trials: 23,
                seed: 9,
                threads,
            };
            run_sweep(Sweep::Angular, &opts, fake_trial, |_, _| {})
        };
        let result = run(1);
        let one = result.rows.clone();
        assert_eq!(one, run(2).rows);
        assert_eq!(one, run(5).rows);
        assert_eq!(trials_csv(&result), trials_csv(&run(2)));
        assert_eq!(trials_csv(&result).lines().count(), 1 + 5 * 23 * 2);
        assert_eq!(one.len(), 10);
        let csv = to_csv(&one);
        assert_eq!(csv.lines().count(), 11);
        assert!(csv.starts_with(CSV_HEADER));
        assert!(one.iter().any(|r| r.failures > 0));
    }
}
