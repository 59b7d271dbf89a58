//! `rspose calibrate`: readout time and camera-gyro time offset from pairs with gyro logs.

use super::compare::pair_paths;
use super::CliError;
use rspose::estimation::calibrate::{calibrate, CalibrationOptions, Range};
use std::path::PathBuf;

/// Options of `rspose calibrate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Pair files with gyro logs, or directories (every `pair*.json` in them).
    #[arg(required = true)]
    pairs: Vec<PathBuf>,
    /// Frame readout times to search, milliseconds: MIN:MAX:STEP.
    #[arg(long = "readout-ms", default_value = "0:40:1")]
    readout_ms: String,
    /// Time offsets to search, milliseconds: MIN:MAX:STEP.
    #[arg(
        long = "offset-ms",
        default_value = "-15:15:1",
        allow_hyphen_values = true
    )]
    offset_ms: String,
    /// Scale of the Cauchy loss on the per-match distance, pixels.
    #[arg(long = "loss-scale", default_value_t = 1.0)]
    loss_scale: f64,
    /// Print one JSON object (best values and the whole cost grid) instead of text.
    #[arg(long)]
    json: bool,
}

fn range(flag: &str, s: &str) -> Result<Range, CliError> {
    let v: Vec<f64> = s
        .split(':')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| CliError::input(format!("{flag} `{s}`: expected MIN:MAX:STEP in ms")))?;
    match v[..] {
        [min, max, step] => Ok(Range {
            min: min * 1e-3,
            max: max * 1e-3,
            step: step * 1e-3,
        }),
        _ => Err(CliError::input(format!(
            "{flag} `{s}`: expected MIN:MAX:STEP in ms"
        ))),
    }
}

fn bar(cost: f64, lo: f64, hi: f64) -> String {
    let width = if hi > lo {
        ((cost - lo) / (hi - lo) * 40.0).round()
    } else {
        0.0
    };
    "#".repeat(width.clamp(0.0, 40.0) as usize)
}

pub fn run(a: Args) -> Result<(), CliError> {
    let options = CalibrationOptions {
        readout: range("--readout-ms", &a.readout_ms)?,
        offset: range("--offset-ms", &a.offset_ms)?,
        loss_scale_px: a.loss_scale,
        ..CalibrationOptions::default()
    };
    if !(a.loss_scale.is_finite() && a.loss_scale > 0.0) {
        return Err(CliError::input("--loss-scale must be finite and positive"));
    }
    let paths = pair_paths(&a.pairs)?;
    let pairs = paths
        .iter()
        .map(|p| super::load_pair(p))
        .collect::<Result<Vec<_>, _>>()?;
    let c = calibrate(&pairs, &options).map_err(|e| {
        let msg = match &e {
            rspose::estimation::calibrate::CalibrationError::NoGyroLog(i)
            | rspose::estimation::calibrate::CalibrationError::Log { pair: i, .. }
            | rspose::estimation::calibrate::CalibrationError::NotCovered { pair: i, .. } => {
                format!("{}: {e}", paths[*i].display())
            }
            _ => e.to_string(),
        };
        CliError::input(msg)
    })?;
    for d in &c.doubts {
        eprintln!("warning: {d}");
    }
    if a.json {
        println!("{}", serde_json::to_string(&c).unwrap_or_default());
        return Ok(());
    }
    for (title, profile) in [
        ("frame readout time (ms)", c.readout_profile()),
        ("time offset (ms)", c.offset_profile()),
    ] {
        let lo = profile.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        let hi = profile
            .iter()
            .map(|p| p.1)
            .fold(f64::NEG_INFINITY, f64::max);
        println!("cost (mean Cauchy loss per match, px^2) against {title}, best over the other:");
        for (x, cost) in profile {
            println!("{:>8.2}  {cost:>8.4}  {}", x * 1e3, bar(cost, lo, hi));
        }
        println!();
    }
    println!(
        "best: frame readout {:.2} ms ({:.4e} s/row), time offset {:+.2} ms, cost {:.4} px^2 ({} pairs)",
        c.readout * 1e3,
        c.readout_per_row,
        c.offset * 1e3,
        c.cost,
        pairs.len()
    );
    Ok(())
}
