//! How many true inliers the library defaults keep, and how many outliers they accept, on
//! the paper's simulated protocol (1 px, no linear velocity) at several gyro-noise levels and
//! outlier fractions:
//! `cargo run --release -p rspose --example inlier_retention [SCENES] [--no-fit] [--paper-model]`
//! (default 120 scenes a row; `--no-fit`: without the fit of the pair's gyro noise,
//! `RobustOptions::fit_gyro_noise`; `--paper-model`: `grsrp`/`grsrp+` score and refine with
//! the paper's linearised model, `EstimateOptions::grsrp_model`).
//!
//! Every scene is simulated with a known inlier mask (`GroundTruth::inliers`); a match is a
//! kept true inlier when the mask and the estimate's inlier flag are both true, an accepted
//! outlier when the estimate flags a simulated outlier as an inlier; the mean errors are
//! over the scenes with an estimate. The figures are
//! totals over all scenes of a row, so scenes with many matches do not count more.

use rspose::methods::GrsrpModel;
use rspose::model::geometry::{rotation_error_deg, translation_error_deg};
use rspose::{estimate_relative_pose, EstimateOptions, Method};
use rspose::{simulate, SimulationOptions};

/// One row of the table: the scenes' angular velocity, gyro noise and outlier fraction.
struct Setting {
    angular: f64,
    gyro_noise: f64,
    outliers: f64,
}

/// Kept true inliers and accepted outliers over a set of scenes.
#[derive(Default)]
struct Tally {
    inliers: usize,
    kept: usize,
    outliers: usize,
    accepted: usize,
    failures: usize,
    rotation_error_deg: f64,
    translation_error_deg: f64,
    estimates: usize,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str| args.iter().any(|a| a == name);
    let fit = !flag("--no-fit");
    let model = if flag("--paper-model") {
        GrsrpModel::Paper
    } else {
        GrsrpModel::Exact
    };
    let scenes: u64 = match args.iter().find(|a| !a.starts_with("--")) {
        Some(s) => s
            .parse()
            .map_err(|_| format!("SCENES must be a positive integer, got `{s}`"))?,
        None => 120,
    };
    let settings = [
        (0.5, 0.1, 0.0),
        (2.5, 0.1, 0.0),
        (0.5, 0.5, 0.0),
        (2.5, 0.5, 0.0),
        (2.5, 0.1, 0.3),
        (2.5, 0.1, 0.6),
        (0.5, 0.1, 0.3),
        (0.5, 0.1, 0.6),
    ]
    .map(|(angular, gyro_noise, outliers)| Setting {
        angular,
        gyro_noise,
        outliers,
    });
    let methods = [Method::Rectified, Method::Grsrp, Method::GrsrpPlus];
    println!(
        "{scenes} scenes a row, library defaults (EstimateOptions::for_method){}{}",
        if fit {
            ""
        } else {
            " without the gyro-noise fit"
        },
        if model == GrsrpModel::Paper {
            ", grsrp scored and refined with the paper's model"
        } else {
            ""
        }
    );
    println!("| rad/s | gyro noise | outliers | method | true inliers kept | outliers accepted | mean rotation / translation error (deg) | failures |");
    println!("|---|---|---|---|---|---|---|---|");
    for s in &settings {
        for m in methods {
            let mut tally = Tally::default();
            for seed in 0..scenes {
                let pair = simulate(&SimulationOptions {
                    angular_velocity: s.angular,
                    gyro_noise: s.gyro_noise,
                    outlier_fraction: s.outliers,
                    seed,
                    ..SimulationOptions::default()
                })?;
                let truth = pair
                    .ground_truth
                    .as_ref()
                    .ok_or("simulated without truth")?;
                let (view1, view2) = pair.views()?;
                let mut options = EstimateOptions::for_method(m);
                options.robust.seed = seed;
                options.robust.fit_gyro_noise = fit;
                options.grsrp_model = model;
                let flags = match estimate_relative_pose(&view1, &view2, &pair.matches, &options) {
                    Ok(est) => {
                        tally.rotation_error_deg +=
                            rotation_error_deg(&truth.rotation_matrix(), &est.rotation);
                        tally.translation_error_deg +=
                            translation_error_deg(&truth.translation_vector(), &est.translation);
                        tally.estimates += 1;
                        est.inliers
                    }
                    Err(_) => {
                        tally.failures += 1;
                        vec![false; pair.matches.len()]
                    }
                };
                for (&is_inlier, &flagged) in truth.inliers.iter().zip(&flags) {
                    if is_inlier {
                        tally.inliers += 1;
                        tally.kept += flagged as usize;
                    } else {
                        tally.outliers += 1;
                        tally.accepted += flagged as usize;
                    }
                }
            }
            let pct = |a: usize, b: usize| {
                if b == 0 {
                    "—".to_string()
                } else {
                    format!("{:.1} %", 100.0 * a as f64 / b as f64)
                }
            };
            let n = tally.estimates.max(1) as f64;
            println!(
                "| {} | {} | {:.0} % | {} | {} | {} | {:.3} / {:.3} | {} |",
                s.angular,
                s.gyro_noise,
                100.0 * s.outliers,
                m.name(),
                pct(tally.kept, tally.inliers),
                pct(tally.accepted, tally.outliers),
                tally.rotation_error_deg / n,
                tally.translation_error_deg / n,
                tally.failures
            );
        }
    }
    Ok(())
}
