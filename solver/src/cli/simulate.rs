//! `rspose simulate`: one pair from the paper's synthetic protocol.

use super::{check_output_dir, CliError};
use rspose::data::simulate::{simulate, SimulationOptions};
use rspose::model::camera::Camera;
use std::path::PathBuf;

/// Options of `rspose simulate` (defaults: 2.5 rad/s, 0 m/s, 1 px, 0.1 rad/s, 1° gravity
/// noise, 150 points).
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Angular velocity magnitude of each camera (rad/s).
    #[arg(long, default_value_t = 2.5)]
    angular: f64,
    /// Linear velocity magnitude of each camera (m/s).
    #[arg(long, default_value_t = 0.0)]
    linear: f64,
    /// Pixel noise standard deviation (px).
    #[arg(long = "pixel-noise", default_value_t = 1.0)]
    pixel_noise: f64,
    /// Gyro noise standard deviation per axis (rad/s).
    #[arg(long = "gyro-noise", default_value_t = 0.1)]
    gyro_noise: f64,
    /// Gravity noise standard deviation per axis of each view's gravity direction (deg).
    #[arg(long = "gravity-noise", default_value_t = 1.0)]
    gravity_noise: f64,
    /// Number of matches (at most 2,000,000).
    #[arg(long, default_value_t = 150)]
    points: usize,
    /// Fraction of matches replaced by outliers, in [0, 1).
    #[arg(long, default_value_t = 0.0)]
    outliers: f64,
    /// Random seed.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Planar scene: every point on the plane at this depth (m) in front of camera 1.
    #[arg(long)]
    plane: Option<f64>,
    /// Standard deviation of camera 2's centre per axis (m); the baseline.
    #[arg(long = "translation-std", default_value_t = 2.0)]
    translation_std: f64,
    /// Camera to image the scene with: a JSON file holding one camera object in the pair
    /// file's form (a COLMAP model with `params` and a readout direction, or the pinhole
    /// short form); default: the paper's 1920x1080 pinhole, 60 µs per row.
    #[arg(long)]
    camera: Option<PathBuf>,
    /// Image 2's camera, if it differs from image 1's (a JSON file as for `--camera`; the
    /// pair file then has `cameras`).
    #[arg(long)]
    camera2: Option<PathBuf>,
    /// Output pair file (JSON).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
}

/// One camera object (the pair file's form) from a JSON file, checked.
fn read_camera(path: &std::path::Path) -> Result<Camera, CliError> {
    let bad = |e: String| CliError::input(format!("{}: {e}", path.display()));
    let text = std::fs::read_to_string(path).map_err(|e| bad(e.to_string()))?;
    let camera: Camera = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
    camera.validate().map_err(|e| bad(e.to_string()))?;
    Ok(camera)
}

pub fn run(a: Args) -> Result<(), CliError> {
    check_output_dir(&a.output)?;
    let camera = match &a.camera {
        Some(path) => read_camera(path)?,
        None => Camera::paper(),
    };
    let camera2 = a.camera2.as_deref().map(read_camera).transpose()?;
    let options = SimulationOptions {
        camera,
        camera2,
        angular_velocity: a.angular,
        linear_velocity: a.linear,
        pixel_noise: a.pixel_noise,
        gyro_noise: a.gyro_noise,
        gravity_noise_deg: a.gravity_noise,
        points: a.points,
        outlier_fraction: a.outliers,
        seed: a.seed,
        plane_depth: a.plane,
        translation_std: a.translation_std,
        ..SimulationOptions::default()
    };
    let pair = simulate(&options).map_err(|e| CliError::input(e.to_string()))?;
    pair.save_atomic(&a.output)
        .map_err(|e| CliError::input(e.to_string()))?;
    eprintln!(
        "wrote {} ({} matches)",
        a.output.display(),
        pair.matches.len()
    );
    Ok(())
}
