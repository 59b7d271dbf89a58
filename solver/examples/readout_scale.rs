//! A wrong nominal readout time, and the pair's readout refined with its pose
//! (`rspose::estimation::readout`): `cargo run --release -p rspose --example readout_scale
//! [SCENES]`.
//!
//! Simulated pairs of the paper's protocol (1 px, 0.1 rad/s gyro noise, no linear
//! velocity) at 2.5 rad/s; both views are given a nominal readout time `factor` times the
//! true one. `rectified` (library defaults) runs with the nominal readout; its pose and
//! inliers then start the joint refinement of pose and readout scale. Printed per factor:
//! mean rotation / translation errors of both, the median and the 10th-90th percentile
//! range of the estimated readout over the true one, and the refinement's median time.

use rspose::estimation::readout::{refine_readout_scale, ReadoutOptions};
use rspose::model::geometry::{rotation_error_deg, translation_error_deg};
use rspose::{estimate_relative_pose, simulate, EstimateOptions, Method, SimulationOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scenes: u64 = match std::env::args().nth(1) {
        Some(s) => s
            .parse()
            .map_err(|_| format!("SCENES must be a positive integer, got `{s}`"))?,
        None => 40,
    };
    println!("{scenes} scenes a row, 2.5 rad/s, 1 px, 0.1 rad/s gyro noise");
    println!("| nominal / true readout | `rectified`: rotation / translation error (deg) | with the readout refined | estimated / true readout: median (10-90 %) | refinement time (median) |");
    println!("|---|---|---|---|---|");
    for factor in [0.7, 0.85, 1.0, 1.15, 1.3] {
        let (mut before, mut after) = ([0.0; 2], [0.0; 2]);
        let mut ratios = Vec::new();
        let mut times = Vec::new();
        let mut n = 0;
        for seed in 0..scenes {
            let pair = simulate(&SimulationOptions {
                angular_velocity: 2.5,
                seed,
                ..SimulationOptions::default()
            })?;
            let truth = pair.ground_truth.as_ref().ok_or("no ground truth")?;
            let (mut v1, mut v2) = pair.views()?;
            v1.camera.readout *= factor;
            v2.camera.readout *= factor;
            let mut options = EstimateOptions::for_method(Method::Rectified);
            options.robust.seed = seed;
            let Ok(est) = estimate_relative_pose(&v1, &v2, &pair.matches, &options) else {
                continue;
            };
            let start = std::time::Instant::now();
            let fitted = refine_readout_scale(
                &v1,
                &v2,
                &pair.matches,
                &est.inliers,
                &est.rotation,
                &est.translation,
                &ReadoutOptions::default(),
            );
            times.push(start.elapsed().as_secs_f64() * 1e3);
            let Some(fit) = fitted else {
                continue;
            };
            let (r, t) = (truth.rotation_matrix(), truth.translation_vector());
            before[0] += rotation_error_deg(&r, &est.rotation);
            before[1] += translation_error_deg(&t, &est.translation);
            after[0] += rotation_error_deg(&r, &fit.rotation);
            after[1] += translation_error_deg(&t, &fit.translation);
            ratios.push(fit.scale * factor);
            n += 1;
        }
        ratios.sort_by(f64::total_cmp);
        times.sort_by(f64::total_cmp);
        let q = |p: f64| ratios[((p * (ratios.len() - 1) as f64).round()) as usize];
        let m = n.max(1) as f64;
        println!(
            "| {factor} | {:.3} / {:.3} | {:.3} / {:.3} | {:.3} ({:.3}-{:.3}) | {:.1} ms |",
            before[0] / m,
            before[1] / m,
            after[0] / m,
            after[1] / m,
            q(0.5),
            q(0.1),
            q(0.9),
            times[times.len() / 2]
        );
    }
    Ok(())
}
