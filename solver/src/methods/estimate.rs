//! The result of [`estimate_relative_pose`](super::estimate_relative_pose)(super::estimate_relative_pose) and its JSON
//! report.

use super::method::Method;
use super::noise_fit::NoiseFit;
use super::quality::Quality;
use super::rectified_v::VelocityFit;
use crate::estimation::gyro_bias::EstimatedBias;
use nalgebra::{Matrix3, Vector3};

/// The result of [`estimate_relative_pose`](super::estimate_relative_pose).
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The method that produced it.
    pub method: Method,
    /// Relative rotation `R` (camera 1 row 0 to camera 2 row 0).
    pub rotation: Matrix3<f64>,
    /// Unit relative translation `t`.
    pub translation: Vector3<f64>,
    /// Inlier mask, one flag per match.
    pub inliers: Vec<bool>,
    /// RANSAC iterations of the final RANSAC stage.
    pub iterations: usize,
    /// MSAC score of the best RANSAC hypothesis: `Σ min(r², τ²)` over the matches, in the
    /// units of the method's threshold (squared).
    pub ransac_score: f64,
    /// Levenberg-Marquardt iterations of the final refinement (0 if none).
    pub refinement_iterations: usize,
    /// Final cost of the refinement (`None` without one), in the refinement's units.
    pub refinement_cost: Option<f64>,
    /// Inlier ratio, parallax, homography fit and the flags computed from them.
    pub quality: Quality,
    /// `nrsrp` only: estimated angular velocities ω1, ω2 (rad/s, camera frames).
    pub angular_velocity: Option<[Vector3<f64>; 2]>,
    /// `nrsrp` and `rectified+v` (unless it fell back to `rectified`): estimated linear
    /// velocities d1, d2 (baseline units per second, camera-1 row-0 frame).
    pub linear_velocity: Option<[Vector3<f64>; 2]>,
    /// `rectified+v` only: whether the velocities were estimated, regularised by their
    /// prior, or left out (the `rectified` pose returned), and why.
    pub velocity_fit: Option<VelocityFit>,
    /// The noise model the final inliers were classified with, when it was fitted to the
    /// pair ([`RobustOptions::fit_gyro_noise`](super::RobustOptions::fit_gyro_noise); `rectified`, `grsrp`, `grsrp+`,
    /// `grsrp-gravity`, and `rectified+v` when it falls back to `rectified`).
    pub noise_fit: Option<NoiseFit>,
    /// With [`EstimateOptions::readout`](super::EstimateOptions::readout): the readout time the pose was refined with, over
    /// the views' nominal one (`None` if the refinement could not run: fewer than 8
    /// inliers or a non-finite result; the method's pose is then kept).
    pub readout_scale: Option<f64>,
    /// With [`EstimateOptions::gyro_bias`](super::EstimateOptions::gyro_bias): the bias of the views' gyro rates the pose was
    /// refined with and its standard deviation, camera axes, rad/s (true rate = the views'
    /// rate − the bias; `None` if the refinement could not run: fewer than 8 inliers or a
    /// non-finite result; the method's pose is then kept).
    pub gyro_bias: Option<EstimatedBias>,
}

impl Estimate {
    /// A method's estimate before the shared stages: the pose, the inlier mask and the
    /// final RANSAC stage's figures; no refinement, the quality report still to be
    /// computed ([`Quality::default`]), no velocities, noise fit, readout scale or gyro bias.
    /// A method sets the fields it reports with `Estimate { field, ..Estimate::new(..) }`.
    pub fn new(
        method: Method,
        rotation: Matrix3<f64>,
        translation: Vector3<f64>,
        inliers: Vec<bool>,
        iterations: usize,
        ransac_score: f64,
    ) -> Self {
        Estimate {
            method,
            rotation,
            translation,
            inliers,
            iterations,
            ransac_score,
            refinement_iterations: 0,
            refinement_cost: None,
            quality: Quality::default(),
            angular_velocity: None,
            linear_velocity: None,
            velocity_fit: None,
            noise_fit: None,
            readout_scale: None,
            gyro_bias: None,
        }
    }

    /// Number of inliers.
    pub fn num_inliers(&self) -> usize {
        self.inliers.iter().filter(|&&b| b).count()
    }

    /// The estimate as the JSON object `rspose estimate --json` prints (without the
    /// command's own `seconds` and the pair file's reference errors): `method`, `rotation`
    /// (row-major rows), `translation`, `inliers` (the count), `iterations`, `inlier_ratio`,
    /// `ransac_score`, `refinement_iterations`, `refinement_cost`, `quality`, `flags`, and
    /// where present `linear_velocity`, `velocity_fit`, `noise_fit`, `readout_scale` and
    /// `gyro_bias` (`[bx, by, bz]`, camera axes, rad/s) with `gyro_bias_std` (its standard
    /// deviation per axis; `null` where infinite). The Python package's
    /// `Estimate.to_dict()` is this object.
    pub fn report_json(&self) -> serde_json::Value {
        let rows: Vec<[f64; 3]> = (0..3)
            .map(|i| std::array::from_fn(|j| self.rotation[(i, j)]))
            .collect();
        let t = self.translation;
        let mut obj = serde_json::json!({
            "method": self.method.name(),
            "rotation": rows,
            "translation": [t.x, t.y, t.z],
            "inliers": self.num_inliers(),
            "iterations": self.iterations,
            "inlier_ratio": self.quality.inlier_ratio,
            "ransac_score": self.ransac_score,
            "refinement_iterations": self.refinement_iterations,
            "refinement_cost": self.refinement_cost,
            "quality": self.quality,
            "flags": self.quality.flags(),
        });
        if let Some(d) = self.linear_velocity {
            obj["linear_velocity"] = serde_json::json!(d.map(|v| [v.x, v.y, v.z]));
        }
        if let Some(fit) = self.velocity_fit {
            obj["velocity_fit"] = serde_json::json!(fit);
        }
        if let Some(fit) = self.noise_fit {
            obj["noise_fit"] = serde_json::json!({
                "gyro_noise": fit.gyro_noise,
                "truncation": fit.truncation,
            });
        }
        if let Some(k) = self.readout_scale {
            obj["readout_scale"] = k.into();
        }
        if let Some(EstimatedBias { bias: b, std: s }) = self.gyro_bias {
            obj["gyro_bias"] = serde_json::json!([b.x, b.y, b.z]);
            obj["gyro_bias_std"] = serde_json::json!([s.x, s.y, s.z]);
        }
        obj
    }
}
