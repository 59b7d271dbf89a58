//! Rotation error of `nrsrp` and its `gsrp` initialisation with many outliers, on the paper's
//! simulated protocol (2.5 rad/s, 1 px, 0.1 rad/s, 150 matches, scene seeds `0..SCENES`):
//! `cargo run --release -p rspose --example outlier_robustness [SCENES]` (default 100).
//! Prints, per preset and outlier fraction (30 %, 45 %, 60 %), the mean and median rotation
//! error in degrees and the number of scenes whose rotation is more than 90° off (the
//! twisted pair of an essential matrix is 180° off).

use rspose::model::geometry::rotation_error_deg;
use rspose::{estimate_relative_pose, simulate, EstimateOptions, Method, SimulationOptions};

/// The options of a preset for a method.
type Preset = fn(Method) -> EstimateOptions;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scenes: u64 = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(100);
    println!("| preset | outliers | method | mean rotation (deg) | median | > 90° |");
    println!("|---|---|---|---|---|---|");
    let presets: [(&str, Preset); 2] = [
        ("paper", EstimateOptions::paper),
        ("default", EstimateOptions::for_method),
    ];
    for (name, preset) in presets {
        for fraction in [0.3, 0.45, 0.6] {
            for method in [Method::Nrsrp, Method::Gsrp] {
                let mut errors = Vec::new();
                for seed in 0..scenes {
                    let pair = simulate(&SimulationOptions {
                        outlier_fraction: fraction,
                        seed,
                        ..Default::default()
                    })?;
                    let (v1, v2) = pair.views()?;
                    let gt = pair.ground_truth.as_ref().ok_or("no ground truth")?;
                    if let Ok(e) = estimate_relative_pose(&v1, &v2, &pair.matches, &preset(method))
                    {
                        errors.push(rotation_error_deg(&gt.rotation_matrix(), &e.rotation));
                    }
                }
                errors.sort_by(f64::total_cmp);
                let mean = errors.iter().sum::<f64>() / errors.len().max(1) as f64;
                let median = errors.get(errors.len() / 2).copied().unwrap_or(f64::NAN);
                let off = errors.iter().filter(|&&x| x > 90.0).count();
                println!(
                    "| {name} | {:.0} % | {method} | {mean:.2} | {median:.2} | {off} |",
                    fraction * 100.0
                );
            }
        }
    }
    Ok(())
}
