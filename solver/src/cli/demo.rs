//! `rspose demo`: one simulated scene at 2.5 rad/s with the paper's noise, every method;
//! optionally with linear velocity (`--linear`) and outliers (`--outliers`).

use super::{preset_options, CliError, Preset, ALL_METHODS, PRESET_HELP};
use rspose::data::simulate::simulate;
use rspose::experiment::{level_simulation, run_methods, Level, Sweep};

/// Options of `rspose demo`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    #[arg(long, value_enum, default_value_t = Preset::Default, help = PRESET_HELP)]
    preset: Preset,
    /// Linear velocity of each camera (m/s); 20 is the angular-linear sweep's hardest level,
    /// where `rectified+v` differs from `rectified`.
    #[arg(long, default_value_t = 0.0)]
    linear: f64,
    /// Fraction of outlier matches, in [0, 1); at 0.5 `grsrp-gravity`'s 3-point samples
    /// pay most.
    #[arg(long, default_value_t = 0.0)]
    outliers: f64,
}

pub fn run(a: Args) -> Result<(), CliError> {
    // The hardest level of the paper's angular sweep: 2.5 rad/s, 1 px, 0.1 rad/s.
    let level = Level {
        linear: a.linear,
        outlier_fraction: a.outliers,
        ..Sweep::Angular.levels()[4]
    };
    let sim = level_simulation(&level, a.seed);
    let pair = simulate(&sim).map_err(|e| CliError::input(e.to_string()))?;
    println!(
        "scene: {} matches ({} % outliers), angular velocity {} rad/s, linear velocity {} m/s, pixel noise {} px, gyro noise {} rad/s, gravity noise {} deg, seed {} ({:?} preset)",
        pair.matches.len(),
        100.0 * level.outlier_fraction,
        level.angular,
        level.linear,
        level.pixel_noise,
        level.gyro_noise,
        level.gravity_noise_deg,
        a.seed,
        a.preset
    );
    println!(
        "{:<13} {:>14} {:>17} {:>9} {:>10}",
        "method", "rotation (deg)", "translation (deg)", "inliers", "time (ms)"
    );
    let preset = a.preset;
    for o in run_methods(&pair, &ALL_METHODS, |m| preset_options(preset, m, a.seed)) {
        let ms = o.seconds * 1e3;
        match (o.rotation_error_deg, o.translation_error_deg, o.inliers) {
            (Some(r), Some(t), Some(n)) => {
                println!("{:<13} {r:>14.4} {t:>17.4} {n:>9} {ms:>10.3}", o.method)
            }
            _ => println!(
                "{:<13} {:>14} {:>17} {:>9} {ms:>10.3}",
                o.method, "failed", "failed", "-"
            ),
        }
    }
    Ok(())
}
