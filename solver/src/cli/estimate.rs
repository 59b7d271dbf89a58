//! `rspose estimate`: relative pose of one pair file.

use super::{CliError, Preset};
use rspose::data::pair_file::PairFile;
use rspose::experiment::evaluate::pose_errors;
use rspose::methods::{GrsrpModel, R0Source};
use rspose::model::geometry::rotation_error_deg;
use rspose::{estimate_relative_pose, EstimateError, Method};
use std::path::PathBuf;
use std::time::Instant;

/// Options of `rspose estimate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The pair file (see `rspose::data::pair_file` for the schema).
    pair: PathBuf,
    /// Method: gsrp, nrsrp, grsrp, grsrp+, rectified, rectified+v.
    #[arg(long, default_value = "grsrp+")]
    method: String,
    /// RANSAC/refinement settings.
    #[arg(long, value_enum, default_value_t = Preset::Default)]
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
    grsrp_model: Option<GrsrpModelChoice>,
    /// Row rotations from a gyro log: `integrated` (exact, the default) or `constant` (the
    /// mean rate over each readout). Without a log the constant `gyro` rates are used.
    #[arg(long, value_enum, default_value_t = Rows::Integrated)]
    rows: Rows,
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

/// Source of `R_0` on the command line.
#[derive(Debug, Clone, Copy, clap::ValueEnum, PartialEq, Eq)]
pub enum R0Choice {
    /// The gsrp estimate.
    Gsrp,
    /// The rectified estimate.
    Rectified,
    /// Integrated from the pair's gyro log.
    Gyro,
}

/// The model `grsrp`/`grsrp+` score and refine with, on the command line.
#[derive(Debug, Clone, Copy, clap::ValueEnum, PartialEq, Eq)]
pub enum GrsrpModelChoice {
    /// The paper's linearised model.
    Paper,
    /// The exact angular model.
    Exact,
}

impl GrsrpModelChoice {
    /// The library's option value.
    pub fn model(self) -> GrsrpModel {
        match self {
            GrsrpModelChoice::Paper => GrsrpModel::Paper,
            GrsrpModelChoice::Exact => GrsrpModel::Exact,
        }
    }
}

/// Row-rotation model for pairs with a gyro log.
#[derive(Debug, Clone, Copy, clap::ValueEnum, PartialEq, Eq)]
pub enum Rows {
    /// Integrated from the samples over each readout.
    Integrated,
    /// Constant: each frame's mean rate.
    Constant,
}

/// The options for `method` with the command line's `--r0` applied.
pub fn apply_r0(
    options: &mut rspose::EstimateOptions,
    r0: Option<R0Choice>,
    pair: &PairFile,
    path: &std::path::Path,
) -> Result<(), CliError> {
    options.r0_source = match r0 {
        None => return Ok(()),
        Some(R0Choice::Gsrp) => R0Source::Gsrp,
        Some(R0Choice::Rectified) => R0Source::Rectified,
        Some(R0Choice::Gyro) => {
            R0Source::Given(pair.gyro_relative_rotation().ok_or_else(|| {
                CliError::input(format!(
                    "{}: --r0 gyro needs a gyro_log whose samples span both frames",
                    path.display()
                ))
            })?)
        }
    };
    Ok(())
}

pub fn run(a: Args) -> Result<(), CliError> {
    let method: Method = a
        .method
        .parse()
        .map_err(|e: rspose::methods::ParseMethodError| CliError::input(e.to_string()))?;
    let pair = PairFile::load(&a.pair).map_err(|e| CliError::input(e.to_string()))?;
    let (mut v1, mut v2) = pair
        .views()
        .map_err(|e| CliError::input(format!("{}: {e}", a.pair.display())))?;
    if a.rows == Rows::Constant {
        (v1, v2) = (v1.constant_rate(), v2.constant_rate());
    }
    let mut options = a.preset.options(method, a.seed);
    apply_r0(&mut options, a.r0, &pair, &a.pair)?;
    if let Some(m) = a.grsrp_model {
        options.grsrp_model = m.model();
    }
    if a.refine_readout {
        options.readout = Some(rspose::estimation::readout::ReadoutOptions::default());
    }
    if a.refine_gyro_bias {
        options.gyro_bias = Some(rspose::estimation::gyro_bias::GyroBiasOptions::default());
    }
    let start = Instant::now();
    let est = estimate_relative_pose(&v1, &v2, &pair.matches, &options).map_err(|e| match e {
        EstimateError::NoSolution => CliError::failed(format!("{}: {e}", a.pair.display())),
        other => CliError::input(format!("{}: {other}", a.pair.display())),
    })?;
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
            println!(
                "readout      {:.2} ms (nominal {:.2} ms, x{k:.3})",
                k * v1.camera.readout * v1.camera.lines() * 1e3,
                v1.camera.readout * v1.camera.lines() * 1e3
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
