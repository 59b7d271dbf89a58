//! `rspose estimate`: relative pose of one pair file.

use super::{CliError, Preset};
use rspose::evaluate::pose_errors;
use rspose::pair_file::PairFile;
use rspose::{estimate_relative_pose, EstimateError, Method};
use std::path::PathBuf;
use std::time::Instant;

/// Options of `rspose estimate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The pair file (see `rspose::pair_file` for the schema).
    pair: PathBuf,
    /// Method: gsrp, nrsrp, grsrp, grsrp+, rectified.
    #[arg(long, default_value = "grsrp+")]
    method: String,
    /// RANSAC/refinement settings.
    #[arg(long, value_enum, default_value_t = Preset::Default)]
    preset: Preset,
    /// RANSAC sampler seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let method: Method = a
        .method
        .parse()
        .map_err(|e: rspose::methods::ParseMethodError| CliError::input(e.to_string()))?;
    let pair = PairFile::load(&a.pair).map_err(|e| CliError::input(e.to_string()))?;
    let (v1, v2) = pair.views();
    let options = a.preset.options(method, a.seed);
    let start = Instant::now();
    let est = estimate_relative_pose(&v1, &v2, &pair.matches, &options).map_err(|e| match e {
        EstimateError::NoSolution => CliError::failed(format!("{}: {e}", a.pair.display())),
        other => CliError::input(format!("{}: {other}", a.pair.display())),
    })?;
    let seconds = start.elapsed().as_secs_f64();
    let errors = pair.ground_truth.as_ref().map(|gt| pose_errors(&est, gt));
    let rows: Vec<[f64; 3]> = (0..3)
        .map(|i| {
            [
                est.rotation[(i, 0)],
                est.rotation[(i, 1)],
                est.rotation[(i, 2)],
            ]
        })
        .collect();
    if a.json {
        let mut obj = serde_json::json!({
            "method": method.name(),
            "rotation": rows,
            "translation": [est.translation.x, est.translation.y, est.translation.z],
            "inliers": est.num_inliers(),
            "iterations": est.iterations,
            "seconds": seconds,
        });
        if let Some(e) = errors {
            obj["rotation_error_deg"] = e.rotation_error_deg.into();
            obj["translation_error_deg"] = e.translation_error_deg.into();
        }
        println!("{obj}");
    } else {
        println!("method       {}", method.name());
        for (i, r) in rows.iter().enumerate() {
            let label = if i == 0 { "rotation" } else { "" };
            println!("{label:<12} [{:>10.6} {:>10.6} {:>10.6}]", r[0], r[1], r[2]);
        }
        let t = est.translation;
        println!("translation  [{:>10.6} {:>10.6} {:>10.6}]", t.x, t.y, t.z);
        println!(
            "inliers      {} / {}",
            est.num_inliers(),
            pair.matches.len()
        );
        println!("iterations   {}", est.iterations);
        println!("seconds      {seconds:.6}");
        if let Some(e) = errors {
            println!("rotation error     {:.4} deg", e.rotation_error_deg);
            println!("translation error  {:.4} deg", e.translation_error_deg);
        }
    }
    Ok(())
}
