//! Subcommands of the `rspose` binary (one file each) and their shared error type.

mod calibrate;
mod compare;
mod demo;
mod dump_instances;
mod estimate;
mod experiment;
mod make_pair;
mod simulate;

use clap::{Parser, Subcommand};
use rspose::{EstimateOptions, Method};
use std::path::PathBuf;

/// Gyro-aided relative pose of rolling-shutter cameras.
#[derive(Debug, Parser)]
#[command(name = "rspose", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Simulate one image pair with the paper's synthetic protocol (ground truth included).
    Simulate(simulate::Args),
    /// Estimate the relative pose of a pair file.
    Estimate(estimate::Args),
    /// Run one of the synthetic sweeps with every method; write CSV and SVG.
    Experiment(experiment::Args),
    /// Simulate one scene at 2.5 rad/s with the paper's noise and compare every method.
    Demo(demo::Args),
    /// Run every method on pair files (e.g. real ones) against their rotation reference.
    Compare(compare::Args),
    /// Estimate the readout time and camera-gyro time offset from pairs with gyro logs.
    Calibrate(calibrate::Args),
    /// Make a pair file from a real recording: gyro CSV, frame times, calibration, matches.
    MakePair(make_pair::Args),
    /// Write G-RSRP instances from simulated scenes for `mingen audit --instances-from`.
    DumpInstances(dump_instances::Args),
}

pub use rspose::methods::Preset;

/// The help of every `--preset` flag.
pub const PRESET_HELP: &str = "RANSAC/refinement settings: `default` (the library defaults: \
adaptive RANSAC, a 2.5 px Sampson threshold scaled per match by its row noise, local \
optimisation, final refinement) or `paper` (200 RANSAC iterations, threshold 0.01 on \
|m2' E m1|)";

/// The estimator options of `preset` for `method`, with a sampler seed.
pub fn preset_options(preset: Preset, method: Method, seed: u64) -> EstimateOptions {
    let mut o = preset.options(method);
    o.robust.seed = seed;
    o
}

/// Every method, in the order tables and plots list them.
pub const ALL_METHODS: [Method; Method::ALL.len()] = Method::ALL;

/// A failed command: the message and the exit code.
#[derive(Debug)]
pub struct CliError {
    /// One line for stderr.
    pub message: String,
    /// 2 for bad input, 1 for valid input without an answer.
    pub code: i32,
}

impl CliError {
    /// Bad input (exit code 2).
    pub fn input(message: impl Into<String>) -> Self {
        CliError {
            message: message.into(),
            code: 2,
        }
    }
    /// Valid input that produced no answer (exit code 1).
    pub fn failed(message: impl Into<String>) -> Self {
        CliError {
            message: message.into(),
            code: 1,
        }
    }
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Simulate(a) => simulate::run(a),
        Command::Estimate(a) => estimate::run(a),
        Command::Experiment(a) => experiment::run(a),
        Command::Demo(a) => demo::run(a),
        Command::MakePair(a) => make_pair::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Calibrate(a) => calibrate::run(a),
        Command::DumpInstances(a) => dump_instances::run(a),
    }
}

/// Checks that an output file's directory exists (so we fail before doing the work).
pub fn check_output_dir(path: &std::path::Path) -> Result<(), CliError> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map(PathBuf::from)
        .unwrap_or_else(|| ".".into());
    if dir.is_dir() {
        Ok(())
    } else {
        Err(CliError::input(format!(
            "{}: output directory does not exist",
            dir.display()
        )))
    }
}

/// Reads and validates a pair file for a command, every error as one line naming the file
/// (an invalid field's message names the field but not the file it is in).
pub fn load_pair(path: &std::path::Path) -> Result<rspose::PairFile, CliError> {
    use rspose::data::pair_file::PairFileError;
    rspose::PairFile::load(path).map_err(|e| match e {
        PairFileError::InvalidField { .. } => CliError::input(format!("{}: {e}", path.display())),
        e => CliError::input(e.to_string()),
    })
}

/// A clap error as the one line `rspose` prints for bad input: its message lines up to the
/// usage, joined, without clap's `error:` prefix and its tips.
pub fn usage_error_line(rendered: &str) -> String {
    rendered
        .lines()
        .map(str::trim)
        .take_while(|l| !l.starts_with("Usage:"))
        .filter(|l| !l.is_empty() && !l.starts_with("tip:"))
        .collect::<Vec<_>>()
        .join(" ")
        .trim_start_matches("error: ")
        .to_string()
        + " (see --help)"
}
