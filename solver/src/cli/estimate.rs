//! `rspose estimate`: relative pose of one pair file.

use super::{preset_options, CliError, Preset, PRESET_HELP};
use rspose::data::pair_estimate::{estimate_pair, PairEstimateError, R0Choice, RowModel};
use rspose::data::pair_file::PairFile;
use rspose::experiment::evaluate::pose_errors;
use rspose::methods::{GrsrpModel, R0Source};
use rspose::model::geometry::rotation_error_deg;
use rspose::{EstimateError, Method};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `rspose estimate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The pair file (see `rspose::data::pair_file` for the schema).
    pair: PathBuf,
    /// Method: gsrp, nrsrp, grsrp, grsrp+, rectified, rectified+v or grsrp-gravity.
    #[arg(long, default_value = "grsrp+")]
    method: String,
    #[arg(long, value_enum, default_value_t = Preset::Default, help = PRESET_HELP)]
    preset: Preset,
    /// RANSAC sampler seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Where grsrp/grsrp+ take R_0 from: the preset's choice (paper: gsrp, default:
    /// rectified), or `gyro` (integrated from the pair's gyro log between the frames).
    #[arg(long, value_enum)]
    r0: Option<R0Choice>,
    /// The model grsrp/grsrp+ score and refine with: the preset's choice (paper: `paper`,
    /// default: `exact`).
    #[arg(long, value_enum)]
    grsrp_model: Option<GrsrpModel>,
    /// Row rotations from a gyro log: `integrated` (exact, the default) or `constant` (the
    /// mean rate over each readout). Without a log the constant `gyro` rates are used.
    #[arg(long, value_enum, default_value_t = RowModel::Integrated)]
    rows: RowModel,
    /// Refine the readout time with the pose (a common scale of both views' nominal
    /// readout; gyro-aided methods only) and print it.
    #[arg(long)]
    refine_readout: bool,
    /// Refine a constant gyro bias shared by both views with the pose (gyro-aided methods
    /// only) and print it (camera axes, rad/s; JSON `gyro_bias`).
    #[arg(long)]
    refine_gyro_bias: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// The message of a failed pair-file estimate: exit code 1 for a valid pair without an
/// answer, 2 for bad input; `path` prefixes the message as every subcommand names the file.
pub fn pair_error(e: PairEstimateError, path: &Path) -> CliError {
    let path = path.display();
    match e {
        PairEstimateError::Estimate(e @ EstimateError::NoSolution) => {
            CliError::failed(format!("{path}: {e}"))
        }
        PairEstimateError::NoGyroRotation(_) => CliError::input(format!(
            "{path}: --r0 gyro needs a gyro_log whose samples span both frames"
        )),
        other => CliError::input(format!("{path}: {other}")),
    }
}

/// The `R_0` source `r0` names for `pair`, checked before any estimate.
pub fn r0_source(r0: R0Choice, pair: &PairFile, path: &Path) -> Result<R0Source, CliError> {
    r0.source(pair)
        .map_err(|e| pair_error(PairEstimateError::NoGyroRotation(e), path))
}

pub fn run(a: Args) -> Result<(), CliError> {
    let method: Method = a
        .method
        .parse()
        .map_err(|e: rspose::methods::ParseMethodError| CliError::input(e.to_string()))?;
    let pair = super::load_pair(&a.pair)?;
    let mut options = preset_options(a.preset, method, a.seed);
    if let Some(m) = a.grsrp_model {
        options.grsrp_model = m;
    }
    if a.refine_readout {
        options.readout = Some(rspose::estimation::readout::ReadoutOptions::default());
    }
    if a.refine_gyro_bias {
        options.gyro_bias = Some(rspose::estimation::gyro_bias::GyroBiasOptions::default());
    }
    let start = Instant::now();
    let est = estimate_pair(&pair, &options, a.rows, a.r0).map_err(|e| pair_error(e, &a.pair))?;
    let seconds = start.elapsed().as_secs_f64();
    let errors = pair.ground_truth.as_ref().map(|gt| pose_errors(&est, gt));
    let gyro_difference = pair
        .gyro_relative_rotation()
        .map(|r| rotation_error_deg(&r, &est.rotation));
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
        let mut obj = est.report_json();
        obj["seconds"] = seconds.into();
        if let Some(e) = errors {
            obj["rotation_error_deg"] = e.rotation_error_deg.into();
            obj["translation_error_deg"] = e.translation_error_deg.into();
        }
        if let Some(d) = gyro_difference {
            obj["gyro_rotation_difference_deg"] = d.into();
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
        println!(
            "quality      inlier ratio {:.3}, parallax {:.2} px, epipolar {:.2} px, homography {:.2} px",
            est.quality.inlier_ratio,
            est.quality.parallax_px,
            est.quality.epipolar_px,
            est.quality.homography_px
        );
        let flags = est.quality.flags();
        if !flags.is_empty() {
            println!("flags        {}", flags.join(", "));
        }
        if let Some(fit) = est.velocity_fit {
            println!("velocities   {}", fit.describe());
        }
        if let Some(fit) = est.noise_fit {
            println!(
                "noise fit    gyro {:.4} rad/s per axis{}",
                fit.gyro_noise,
                if fit.truncation < 1.0 {
                    format!(", paper-model truncation x{:.3}", fit.truncation)
                } else {
                    String::new()
                }
            );
        }
        if let Some(k) = est.readout_scale {
            let camera = &pair.cameras[0];
            println!(
                "readout      {:.2} ms (nominal {:.2} ms, x{k:.3})",
                k * camera.readout * camera.lines() * 1e3,
                camera.readout * camera.lines() * 1e3
            );
        }
        if let Some(rspose::estimation::gyro_bias::EstimatedBias { bias: b, std: s }) =
            est.gyro_bias
        {
            println!(
                "gyro bias    [{:.5} {:.5} {:.5}] ± [{:.5} {:.5} {:.5}] rad/s (camera axes, subtracted from the rates)",
                b.x, b.y, b.z, s.x, s.y, s.z
            );
        }
        if let Some([d1, d2]) = est.linear_velocity {
            println!(
                "linear vel.  [{:.4} {:.4} {:.4}] [{:.4} {:.4} {:.4}] baselines/s (camera-1 frame)",
                d1.x, d1.y, d1.z, d2.x, d2.y, d2.z
            );
        }
        println!("seconds      {seconds:.6}");
        if let Some(e) = errors {
            println!("rotation error     {:.4} deg", e.rotation_error_deg);
            println!("translation error  {:.4} deg", e.translation_error_deg);
        }
        if let Some(d) = gyro_difference {
            println!("rotation vs gyro   {d:.4} deg (gyro-integrated reference)");
        }
    }
    Ok(())
}
