//! A gyro with a constant bias, and the bias refined with the pose
//! (`rspose::estimation::gyro_bias`, `EstimateOptions::gyro_bias`, `--refine-gyro-bias`):
//! `cargo run --release -p rspose --example gyro_bias [SCENES [POINTS [PIXEL_NOISE]]]`
//! (default 100 scenes, 1000 matches, 0.5 px).
//!
//! Simulated pairs of the paper's protocol (2.5 rad/s, no linear velocity) whose gyro
//! readings carry a bias of 0.03 rad/s per axis (camera axes, the same for both views), at
//! several per-view gyro noise levels. `rectified` (library defaults) runs once as it
//! stands and once with the bias refinement. Printed per noise level: the median and mean
//! rotation / translation errors of both, the median error of the estimated bias and its
//! 10th-90th percentile range, against the bias's norm, and the median of the standard
//! deviation the fit reports (the norm of its three components).

use nalgebra::Vector3;
use rspose::estimation::gyro_bias::GyroBiasOptions;
use rspose::model::geometry::{rotation_error_deg, translation_error_deg};
use rspose::stats::upper_median;
use rspose::{estimate_relative_pose, simulate, EstimateOptions, Method, SimulationOptions};

/// The bias added to every reading, rad/s, camera axes.
const BIAS: [f64; 3] = [0.03, -0.03, 0.03];

fn median(v: &[f64]) -> f64 {
    upper_median(v.iter().copied()).unwrap_or(f64::NAN)
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = |k: usize, name: &str, default: f64| -> Result<f64, String> {
        match std::env::args().nth(k) {
            Some(s) => s
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x >= 0.0)
                .ok_or_else(|| format!("{name} must be a non-negative number, got `{s}`")),
            None => Ok(default),
        }
    };
    let scenes = arg(1, "SCENES", 100.0)? as u64;
    let points = arg(2, "POINTS", 1000.0)? as usize;
    let pixel_noise = arg(3, "PIXEL_NOISE", 0.5)?;
    let bias = Vector3::from(BIAS);
    println!(
        "{scenes} scenes a row, 2.5 rad/s, {points} matches, {pixel_noise} px, gyro bias {BIAS:?} rad/s (norm {:.4})",
        bias.norm()
    );
    println!("| gyro noise (rad/s per axis) | `rectified` rotation / translation error, median (mean), deg | with the bias refined | bias error, median (10-90 %), rad/s | reported bias std (norm), median |");
    println!("|---|---|---|---|---|");
    for noise in [0.0, 0.002, 0.005, 0.01, 0.1] {
        let (mut rot, mut tra, mut rot_b, mut tra_b, mut err, mut stds) =
            (vec![], vec![], vec![], vec![], vec![], vec![]);
        for seed in 0..scenes {
            let mut pair = simulate(&SimulationOptions {
                angular_velocity: 2.5,
                gyro_noise: noise,
                points,
                pixel_noise,
                seed,
                ..SimulationOptions::default()
            })?;
            for w in pair.gyro.as_mut().ok_or("no gyro")?.iter_mut() {
                for (x, b) in w.iter_mut().zip(BIAS) {
                    *x += b;
                }
            }
            let truth = pair.ground_truth.as_ref().ok_or("no ground truth")?;
            let (r, t) = (truth.rotation_matrix(), truth.translation_vector());
            let (v1, v2) = pair.views()?;
            let mut plain = EstimateOptions::for_method(Method::Rectified);
            plain.robust.seed = seed;
            let refined = EstimateOptions {
                gyro_bias: Some(GyroBiasOptions::default()),
                ..plain.clone()
            };
            let (Ok(a), Ok(b)) = (
                estimate_relative_pose(&v1, &v2, &pair.matches, &plain),
                estimate_relative_pose(&v1, &v2, &pair.matches, &refined),
            ) else {
                continue;
            };
            let Some(fit) = b.gyro_bias else {
                continue;
            };
            let estimated = fit.bias;
            stds.push(fit.std.norm());
            rot.push(rotation_error_deg(&r, &a.rotation));
            tra.push(translation_error_deg(&t, &a.translation));
            rot_b.push(rotation_error_deg(&r, &b.rotation));
            tra_b.push(translation_error_deg(&t, &b.translation));
            err.push((estimated - bias).norm());
        }
        let (mr, mt, mrb, mtb) = (mean(&rot), mean(&tra), mean(&rot_b), mean(&tra_b));
        let n = err.len();
        let me = median(&err);
        let q = |p: f64| err[((p * (n.max(1) - 1) as f64).round()) as usize];
        println!(
            "| {noise} | {:.4} / {:.3} ({mr:.4} / {mt:.3}) | {:.4} / {:.3} ({mrb:.4} / {mtb:.3}) | {me:.4} ({:.4}-{:.4}) | {:.4} |",
            median(&rot),
            median(&tra),
            median(&rot_b),
            median(&tra_b),
            q(0.1),
            q(0.9),
            median(&stds),
        );
    }
    Ok(())
}
