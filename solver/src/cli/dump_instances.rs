//! `rspose dump-instances`: G-RSRP instances on simulated geometry, one per line in the
//! data-slot order of `templates/grsrp10.mp` / `templates/grsrp.mp`, for
//! `mingen audit FILE --instances-from DATA`.

use super::{check_output_dir, CliError};
use clap::ValueEnum;
use rspose::data::atomic_file::write_output;
use rspose::data::instances::{grsrp_instances, InstanceOptions};
use rspose::data::simulate::SimulationOptions;
use std::fmt::Write as _;
use std::path::PathBuf;

/// The problem whose data the instances are (both G-RSRP files declare the same data).
#[derive(Debug, Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum Problem {
    /// `templates/grsrp10.mp` (`t` eliminated).
    Grsrp10,
    /// `templates/grsrp.mp` (6 unknowns).
    Grsrp,
}

/// Options of `rspose dump-instances` (scenes: the simulator's defaults, no outliers).
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The problem file the instances are for.
    #[arg(long, value_enum)]
    solver: Problem,
    /// Number of instances (one scene each).
    #[arg(long, default_value_t = 1000)]
    count: usize,
    /// Angular velocity magnitude of each camera (rad/s).
    #[arg(long, default_value_t = 2.5)]
    angular: f64,
    /// Pixel noise standard deviation (px).
    #[arg(long = "pixel-noise", default_value_t = 1.0)]
    pixel_noise: f64,
    /// Gyro noise standard deviation per axis (rad/s).
    #[arg(long = "gyro-noise", default_value_t = 0.1)]
    gyro_noise: f64,
    /// Angle between R0 and the true rotation (degrees, about a random axis).
    #[arg(long = "r0-deg", default_value_t = 3.0)]
    r0_deg: f64,
    /// Seed of the first scene (scene k uses seed + k).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Output file.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
}

pub fn run(a: Args) -> Result<(), CliError> {
    check_output_dir(&a.output)?;
    if a.count == 0 {
        return Err(CliError::input("--count must be at least 1"));
    }
    let options = InstanceOptions {
        simulation: SimulationOptions {
            angular_velocity: a.angular,
            pixel_noise: a.pixel_noise,
            gyro_noise: a.gyro_noise,
            seed: a.seed,
            ..SimulationOptions::default()
        },
        count: a.count,
        r0_perturbation_deg: a.r0_deg,
    };
    let instances = grsrp_instances(&options).map_err(|e| CliError::input(e.to_string()))?;
    let file = match a.solver {
        Problem::Grsrp10 => "templates/grsrp10.mp",
        Problem::Grsrp => "templates/grsrp.mp",
    };
    let mut text = format!(
        "# {} instances for {file} from `rspose dump-instances` ({} rad/s, {} px, {} rad/s gyro \
         noise, R0 {} deg from the truth, seed {}); one per line, the data slots in order: \
         x1[0..5].x/.y x2[0..5].x/.y v1[0..5] v2[0..5] w1.x/.y/.z w2.x/.y/.z R0 row-major\n",
        a.count, a.angular, a.pixel_noise, a.gyro_noise, a.r0_deg, a.seed
    );
    for inst in &instances {
        let line: Vec<String> = inst.iter().map(|x| format!("{x:?}")).collect();
        let _ = writeln!(text, "{}", line.join(" "));
    }
    write_output(&a.output, text.as_bytes(), &[])
        .map_err(|e| CliError::input(format!("{}: {e}", a.output.display())))?;
    eprintln!(
        "wrote {} ({} instances)",
        a.output.display(),
        instances.len()
    );
    Ok(())
}
