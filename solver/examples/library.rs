//! The README's "library in ten lines", runnable: `cargo run --release -p rspose --example library`.
//! The matches come from the simulator here; in an application they come from a matcher.

use nalgebra::Vector3;
use rspose::data::simulate::{simulate, SimulationOptions};
use rspose::model::camera::{Camera, View};
use rspose::{estimate_relative_pose, EstimateOptions, Method};

/// Pixel matches and the two views' gyroscope readings.
type Recording = (Vec<[[f64; 2]; 2]>, [[f64; 3]; 2]);

/// A simulated pair at 2.5 rad/s: its matches and the two gyroscope readings.
fn load() -> Result<Recording, Box<dyn std::error::Error>> {
    let pair = simulate(&SimulationOptions::default())?;
    Ok((pair.matches, pair.gyro.ok_or("no gyro")?))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // fx, fy, cx, cy, width, height (pixels), readout (s per row, read from the top);
    // distorted lenses: Camera::from_params(CameraModel::OpenCv, ...).
    let camera = Camera::pinhole(640.0, 640.0, 960.0, 540.0, 1920.0, 1080.0, 60e-6);
    let (matches, gyro) = load()?; // [[u1, v1], [u2, v2]] pixels; rad/s, camera axes
    let view1 = View::new(camera, Vector3::from(gyro[0])); // gyroscope reading of image 1
    let view2 = View::new(camera, Vector3::from(gyro[1])); // gyroscope reading of image 2
    let est = estimate_relative_pose(
        &view1,
        &view2,
        &matches,
        &EstimateOptions::for_method(Method::GrsrpPlus),
    )?;
    println!(
        "R = {}, t = {}, {} inliers",
        est.rotation,
        est.translation,
        est.num_inliers()
    );
    println!("flags: {:?}", est.quality.flags());
    Ok(())
}
