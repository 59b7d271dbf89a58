//! `rspose compare`: every method on a set of pair files (e.g. from a real recording),
//! against each pair's rotation reference (ground truth, else the gyro-integrated rotation).

use super::estimate::r0_source;
use super::{preset_options, CliError, Preset, ALL_METHODS, PRESET_HELP};
use rspose::data::pair_estimate::{R0Choice, RowModel};
use rspose::data::pair_file::PairFile;
use rspose::estimation::gyro_bias::GyroBiasOptions;
use rspose::estimation::readout::ReadoutOptions;
use rspose::experiment::real::{reference_rotation, run_real, to_markdown};
use rspose::experiment::READOUT_REFINED_LABEL;
use rspose::methods::GrsrpModel;
use std::path::{Path, PathBuf};

/// The `compare` row of `rectified` with the gyro bias refined.
const BIAS_REFINED_LABEL: &str = "rectified+b";

/// Options of `rspose compare`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Pair files, or directories (every `pair*.json` in them).
    #[arg(required = true)]
    pairs: Vec<PathBuf>,
    #[arg(long, value_enum, default_value_t = Preset::Default, help = PRESET_HELP)]
    preset: Preset,
    /// Where grsrp/grsrp+ take R_0 from (default: the preset's).
    #[arg(long, value_enum)]
    r0: Option<R0Choice>,
    /// The model grsrp/grsrp+ score and refine with (default: the preset's).
    #[arg(long, value_enum)]
    grsrp_model: Option<GrsrpModel>,
    /// Row rotations for pairs with a gyro log.
    #[arg(long, value_enum, default_value_t = RowModel::Integrated)]
    rows: RowModel,
    /// RANSAC sampler seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Print JSON (one object per method, with per-pair figures) instead of a table.
    #[arg(long)]
    json: bool,
    /// Add a row `rectified+k`: `rectified` with the readout time's scale refined with
    /// each pair's pose (for a camera whose readout time is known only roughly).
    #[arg(long)]
    refine_readout: bool,
    /// Add a row `rectified+b`: `rectified` with a constant gyro bias shared by both views
    /// refined with each pair's pose (for an uncalibrated gyro).
    #[arg(long)]
    refine_gyro_bias: bool,
}

/// Pair files named on the command line: files as given, directories expanded to their
/// `pair*.json` files in name order.
pub fn pair_paths(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, CliError> {
    let mut out = Vec::new();
    for p in inputs {
        if p.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(p)
                .map_err(|e| CliError::input(format!("{}: {e}", p.display())))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| {
                    let name = f.file_name().map(|n| n.to_string_lossy().into_owned());
                    name.is_some_and(|n| n.starts_with("pair") && n.ends_with(".json"))
                })
                .collect();
            if found.is_empty() {
                return Err(CliError::input(format!(
                    "{}: no pair*.json files",
                    p.display()
                )));
            }
            found.sort();
            out.extend(found);
        } else {
            out.push(p.clone());
        }
    }
    Ok(out)
}

fn load(path: &Path) -> Result<PairFile, CliError> {
    let pair = super::load_pair(path)?;
    if reference_rotation(&pair).is_none() {
        return Err(CliError::input(format!(
            "{}: no rotation reference (neither ground_truth nor a gyro_log spanning both frames)",
            path.display()
        )));
    }
    Ok(pair)
}

pub fn run(a: Args) -> Result<(), CliError> {
    let paths = pair_paths(&a.pairs)?;
    let pairs = paths
        .iter()
        .map(|p| load(p))
        .collect::<Result<Vec<_>, _>>()?;
    let mut options = Vec::with_capacity(pairs.len());
    for (pair, path) in pairs.iter().zip(&paths) {
        let mut o = preset_options(a.preset, rspose::Method::GrsrpPlus, a.seed);
        if let Some(r0) = a.r0 {
            o.r0_source = r0_source(r0, pair, path)?;
        }
        if let Some(m) = a.grsrp_model {
            o.grsrp_model = m;
        }
        options.push(o);
    }
    // `grsrp-gravity` needs an accelerometer's gravity, which recordings often lack.
    let with_gravity = pairs.iter().all(|p| p.gravity.is_some());
    let methods: Vec<rspose::Method> = ALL_METHODS
        .into_iter()
        .filter(|&m| with_gravity || m != rspose::Method::GrsrpGravity)
        .collect();
    if !with_gravity {
        eprintln!("grsrp-gravity left out: not every pair has a `gravity` field");
    }
    let options_for = |method, pair: &PairFile| {
        let k = pairs
            .iter()
            .position(|p| std::ptr::eq(p, pair))
            .unwrap_or(0);
        rspose::EstimateOptions {
            method,
            ..options[k].clone()
        }
    };
    // A pair whose input every method refuses (too few or only identical matches) is bad
    // input, reported as `estimate` would; a pair some method can run is compared.
    for (pair, path) in pairs.iter().zip(&paths) {
        let at = |e: &dyn std::fmt::Display| CliError::input(format!("{}: {e}", path.display()));
        let (v1, v2) = a.rows.views(pair).map_err(|e| at(&e))?;
        let refusals: Vec<rspose::EstimateError> = methods
            .iter()
            .filter_map(|&m| {
                rspose::methods::validate_input(&v1, &v2, &pair.matches, &options_for(m, pair))
                    .err()
            })
            .collect();
        if refusals.len() == methods.len() {
            if let Some(e) = refusals.last() {
                return Err(at(e));
            }
        }
    }
    let mut rows = run_real(&pairs, &methods, options_for, a.rows);
    if a.refine_readout {
        let refined = |method, pair: &PairFile| rspose::EstimateOptions {
            readout: Some(ReadoutOptions::default()),
            ..options_for(method, pair)
        };
        let mut extra = run_real(&pairs, &[rspose::Method::Rectified], refined, a.rows);
        for r in &mut extra {
            r.method = READOUT_REFINED_LABEL.to_string();
        }
        rows.extend(extra);
    }
    if a.refine_gyro_bias {
        let refined = |method, pair: &PairFile| rspose::EstimateOptions {
            gyro_bias: Some(GyroBiasOptions::default()),
            ..options_for(method, pair)
        };
        let mut extra = run_real(&pairs, &[rspose::Method::Rectified], refined, a.rows);
        for r in &mut extra {
            r.method = BIAS_REFINED_LABEL.to_string();
        }
        rows.extend(extra);
    }
    if a.json {
        let v = serde_json::json!({
            "pairs": paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
            "methods": rows,
        });
        println!("{v}");
    } else {
        print!("{}", to_markdown(&rows));
    }
    // Valid pairs on which nothing could be estimated: an answer-less run, not a success.
    if rows.iter().all(|r| r.failures == r.pairs) {
        return Err(CliError::failed(format!(
            "no method estimated any of the {} pairs",
            pairs.len()
        )));
    }
    Ok(())
}
