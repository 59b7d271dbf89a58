//! `rspose demo`: one simulated scene at 2.5 rad/s with the paper's noise, every method.

use super::{CliError, Preset, ALL_METHODS};
use rspose::experiment::{level_simulation, run_methods, Sweep};
use rspose::simulate::simulate;

/// Options of `rspose demo`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// RANSAC/refinement settings.
    #[arg(long, value_enum, default_value_t = Preset::Default)]
    preset: Preset,
}

pub fn run(a: Args) -> Result<(), CliError> {
    // The hardest level of the paper's angular sweep: 2.5 rad/s, 1 px, 0.1 rad/s.
    let level = Sweep::Angular.levels()[4];
    let sim = level_simulation(&level, a.seed);
    let pair = simulate(&sim).map_err(|e| CliError::failed(e.to_string()))?;
    println!(
        "scene: {} matches, angular velocity {} rad/s, pixel noise {} px, gyro noise {} rad/s, seed {} ({:?} preset)",
        pair.matches.len(),
        level.angular,
        level.pixel_noise,
        level.gyro_noise,
        a.seed,
        a.preset
    );
    println!(
        "{:<10} {:>14} {:>17} {:>9} {:>10}",
        "method", "rotation (deg)", "translation (deg)", "inliers", "time (ms)"
    );
    let preset = a.preset;
    for o in run_methods(&pair, &ALL_METHODS, |m| preset.options(m, a.seed)) {
        let ms = o.seconds * 1e3;
        match (o.rotation_error_deg, o.translation_error_deg, o.inliers) {
            (Some(r), Some(t), Some(n)) => {
                println!("{:<10} {r:>14.4} {t:>17.4} {n:>9} {ms:>10.3}", o.method)
            }
            _ => println!(
                "{:<10} {:>14} {:>17} {:>9} {ms:>10.3}",
                o.method, "failed", "failed", "-"
            ),
        }
    }
    Ok(())
}
