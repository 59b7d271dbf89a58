//! `rspose experiment SWEEP`: one of the paper's synthetic sweeps or one of this library's
//! (gravity noise, readout error), every method.

use super::{preset_options, CliError, Preset, ALL_METHODS, PRESET_HELP};
use indicatif::{ProgressBar, ProgressStyle};
use rspose::experiment::{
    render_svg, run_sweep, scene_trial, to_csv, trials_csv, write_output, ExperimentOptions, Sweep,
};
use std::io::IsTerminal;
use std::path::PathBuf;

/// Options of `rspose experiment`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// angular, angular-linear, gyro-noise, pixel-noise, gravity-noise or readout-error.
    sweep: String,
    /// Trials (scenes) per level.
    #[arg(long, default_value_t = 100)]
    trials: usize,
    /// Output directory for SWEEP.csv and SWEEP.svg (created if missing).
    #[arg(long, default_value = "results")]
    out: PathBuf,
    /// Master seed (results depend only on it, not on the thread count).
    #[arg(long, default_value_t = 2024)]
    seed: u64,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    // The paper's settings by default, to compare with its figures.
    #[arg(long, value_enum, default_value_t = Preset::Paper, help = PRESET_HELP)]
    preset: Preset,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let sweep: Sweep = a
        .sweep
        .parse()
        .map_err(|e: rspose::experiment::UnknownSweep| CliError::input(e.to_string()))?;
    if a.trials == 0 {
        return Err(CliError::input("--trials must be at least 1"));
    }
    std::fs::create_dir_all(&a.out).map_err(|e| {
        CliError::input(format!(
            "{}: cannot create output directory: {e}",
            a.out.display()
        ))
    })?;
    let mut options = ExperimentOptions {
        trials: a.trials,
        seed: a.seed,
        ..ExperimentOptions::default()
    };
    if let Some(t) = a.threads {
        options.threads = t.max(1);
    }
    let total = (sweep.levels().len() * a.trials) as u64;
    let bar = if std::io::stderr().is_terminal() {
        let b = ProgressBar::new(total);
        b.set_style(
            ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} scenes, eta {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b.set_message(sweep.name().to_string());
        Some(b)
    } else {
        None
    };
    let preset = a.preset;
    let result = run_sweep(
        sweep,
        &options,
        |level, seed| {
            scene_trial(level, seed, &ALL_METHODS, |m| {
                preset_options(preset, m, seed)
            })
        },
        |done, _| {
            if let Some(b) = &bar {
                b.set_position(done as u64);
            }
        },
    );
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let csv = to_csv(&result.rows);
    let svg = render_svg(sweep, &result.rows)
        .map_err(|e| CliError::failed(format!("plotting failed: {e}")))?;
    let csv_path = a.out.join(format!("{}.csv", sweep.name()));
    let svg_path = a.out.join(format!("{}.svg", sweep.name()));
    let trials_path = a.out.join(format!("{}-trials.csv", sweep.name()));
    write_output(&trials_path, trials_csv(&result).as_bytes(), &[])
        .map_err(|e| CliError::input(format!("{}: {e}", trials_path.display())))?;
    write_output(&csv_path, csv.as_bytes(), &[])
        .map_err(|e| CliError::input(format!("{}: {e}", csv_path.display())))?;
    write_output(&svg_path, svg.as_bytes(), &[])
        .map_err(|e| CliError::input(format!("{}: {e}", svg_path.display())))?;
    print!("{csv}");
    eprintln!("wrote {} and {}", csv_path.display(), svg_path.display());
    Ok(())
}
