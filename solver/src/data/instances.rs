//! G-RSRP problem instances on simulated geometry, in the data-slot order of the
//! `grsrp10` / `grsrp` problem files (their data declarations are the same), for
//! `mingen audit FILE --instances-from DATA` (`rspose dump-instances`).
//!
//! Each instance is its own scene ([`crate::data::simulate::simulate`] with the given options
//! and a per-instance seed): five distinct true inliers drawn at random, their normalised
//! image points and rows, the gyro rates as the templates take them (`w = −λ ω`, see
//! [`crate::model::camera::View::paper_rate_per_row`]), and `R_0` = the true rotation perturbed
//! by a rotation of the given angle about a random axis (the estimator's `R_0` comes from
//! the gyro, a few degrees from the truth).

use crate::data::simulate::{gauss, simulate, SimulationError, SimulationOptions};
use crate::generated::grsrp10;
use crate::model::epipolar::PointData;
use crate::model::geometry::exp_so3;
use nalgebra::Vector3;
use rand::seq::index::sample;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use thiserror::Error;

/// Number of data slots of a G-RSRP instance.
pub const GRSRP_SLOTS: usize = 45;

/// Why instances could not be made.
#[derive(Debug, Error)]
pub enum InstancesError {
    /// The simulator rejected its options or could not make a scene.
    #[error("simulation: {0}")]
    Simulation(#[from] SimulationError),
    /// A simulated pair file was inconsistent (no ground truth or bad gyro data).
    #[error("simulated pair: {0}")]
    Pair(String),
    /// A scene had fewer than five true inliers.
    #[error("scene {scene}: only {inliers} true inliers, 5 needed")]
    TooFewInliers {
        /// Scene index.
        scene: usize,
        /// Its inliers.
        inliers: usize,
    },
    /// The perturbation of `R_0` is not a finite non-negative angle.
    #[error("the R0 perturbation must be a finite angle >= 0 degrees, not {0}")]
    Perturbation(f64),
}

/// Options of [`grsrp_instances`].
#[derive(Debug, Clone, PartialEq)]
pub struct InstanceOptions {
    /// The scenes (the seed of scene `k` is `simulation.seed + k`).
    pub simulation: SimulationOptions,
    /// Number of instances (one scene each).
    pub count: usize,
    /// Angle of the rotation between `R_0` and the true rotation, degrees.
    pub r0_perturbation_deg: f64,
}

impl Default for InstanceOptions {
    fn default() -> Self {
        InstanceOptions {
            simulation: SimulationOptions::default(),
            count: 1000,
            r0_perturbation_deg: 3.0,
        }
    }
}

/// `count` G-RSRP instances (see the module documentation), each `GRSRP_SLOTS` numbers in
/// the problem files' slot order.
pub fn grsrp_instances(
    options: &InstanceOptions,
) -> Result<Vec<[f64; GRSRP_SLOTS]>, InstancesError> {
    let deg = options.r0_perturbation_deg;
    if !(deg.is_finite() && deg >= 0.0) {
        return Err(InstancesError::Perturbation(deg));
    }
    let mut out = Vec::with_capacity(options.count);
    for scene in 0..options.count {
        let sim = SimulationOptions {
            seed: options.simulation.seed.wrapping_add(scene as u64),
            ..options.simulation.clone()
        };
        let pair = simulate(&sim)?;
        let truth = pair
            .ground_truth
            .as_ref()
            .ok_or_else(|| InstancesError::Pair("no ground truth".into()))?;
        let (view1, view2) = pair
            .views()
            .map_err(|e| InstancesError::Pair(e.to_string()))?;
        let inliers: Vec<usize> = (0..pair.matches.len())
            .filter(|&i| truth.inliers.get(i).copied().unwrap_or(false))
            .collect();
        if inliers.len() < 5 {
            return Err(InstancesError::TooFewInliers {
                scene,
                inliers: inliers.len(),
            });
        }
        // A separate stream from the simulator's, so the sample does not shift its scene.
        let mut rng = ChaCha8Rng::seed_from_u64(sim.seed ^ 0x9e37_79b9_7f4a_7c15);
        let picked: Vec<_> = sample(&mut rng, inliers.len(), 5)
            .iter()
            .map(|i| pair.matches[inliers[i]])
            .collect();
        let d = PointData::new(&view1, &view2, &picked)
            .map_err(|e| InstancesError::Pair(e.to_string()))?;
        let axis = loop {
            let v = Vector3::new(gauss(&mut rng), gauss(&mut rng), gauss(&mut rng));
            let n = v.norm();
            if n > 1e-6 {
                break v / n;
            }
        };
        let r0 = truth.rotation_matrix() * exp_so3(&(axis * deg.to_radians()));
        let data = grsrp10::Data {
            x1: std::array::from_fn(|k| [d.m1[k].x, d.m1[k].y]),
            x2: std::array::from_fn(|k| [d.m2[k].x, d.m2[k].y]),
            v1: std::array::from_fn(|k| d.v1[k]),
            v2: std::array::from_fn(|k| d.v2[k]),
            w1: d.w1.into(),
            w2: d.w2.into(),
            r0: std::array::from_fn(|i| std::array::from_fn(|j| r0[(i, j)])),
        };
        out.push(data.to_slots());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generated::grsrp;
    use crate::model::geometry::log_so3;
    use mingen_runtime::FlatValues;

    /// For each noise-free instance with these rates and `R_0` angle: the angle (degrees)
    /// between the truth and the nearest `grsrp10` solution. Checks the data layout on the
    /// way (orthonormal `R_0` at the requested angle, rows within the image, `grsrp` finds
    /// at least as many solutions).
    fn nearest_solution_errors(angular: f64, r0_deg: f64) -> Vec<f64> {
        let options = InstanceOptions {
            simulation: SimulationOptions {
                pixel_noise: 0.0,
                gyro_noise: 0.0,
                angular_velocity: angular,
                seed: 7,
                ..SimulationOptions::default()
            },
            count: 20,
            r0_perturbation_deg: r0_deg,
        };
        let all = grsrp_instances(&options).unwrap();
        assert_eq!(all.len(), 20);
        let mut errors = Vec::new();
        for (k, slots) in all.iter().enumerate() {
            let truth = simulate(&SimulationOptions {
                seed: 7 + k as u64,
                ..options.simulation.clone()
            })
            .unwrap()
            .ground_truth
            .unwrap();
            let r_true = truth.rotation_matrix();
            let data = grsrp10::Data::from_flat(slots).unwrap();
            let r0 = nalgebra::Matrix3::from_fn(|i, j| data.r0[i][j]);
            assert!((r0 * r0.transpose() - nalgebra::Matrix3::identity()).norm() < 1e-12);
            let angle = log_so3(&(r0.transpose() * r_true)).norm().to_degrees();
            assert!((angle - r0_deg).abs() < 1e-9, "{angle}");
            assert!(data
                .v1
                .iter()
                .chain(&data.v2)
                .all(|v| (0.0..1080.0).contains(v)));
            let ten = grsrp10::solve(&data);
            let twenty = grsrp::solve(&grsrp::Data::from_flat(slots).unwrap());
            assert!(twenty.len() >= ten.len());
            errors.push(
                ten.iter()
                    .map(|s| {
                        let r = r0 * exp_so3(&Vector3::from(s.a));
                        log_so3(&(r.transpose() * r_true)).norm().to_degrees()
                    })
                    .fold(f64::INFINITY, f64::min),
            );
        }
        errors.sort_by(f64::total_cmp);
        errors
    }

    /// Without rotation during readout and with `R_0` at the truth the model is exact: the
    /// truth is a solution (up to the conditioning of a random 5-point sample).
    #[test]
    fn exact_instances_have_the_truth_as_a_solution() {
        let errors = nearest_solution_errors(0.0, 0.0);
        assert!(errors[17] < 1e-6, "{errors:?}");
    }

    /// At the paper's 2.5 rad/s and `R_0` 2 degrees off, the linearised model (first order
    /// in `a` and in the row rotations) is within a few degrees of the truth on a typical
    /// 5-point sample.
    #[test]
    fn rolling_instances_have_a_solution_near_the_truth() {
        let errors = nearest_solution_errors(2.5, 2.0);
        assert!(errors[10] < 2.0, "{errors:?}");
    }

    #[test]
    fn rejects_bad_options() {
        let bad = InstanceOptions {
            r0_perturbation_deg: f64::NAN,
            ..InstanceOptions::default()
        };
        assert!(matches!(
            grsrp_instances(&bad),
            Err(InstancesError::Perturbation(_))
        ));
        let few = InstanceOptions {
            simulation: SimulationOptions {
                points: 4,
                ..SimulationOptions::default()
            },
            count: 1,
            ..InstanceOptions::default()
        };
        assert!(matches!(
            grsrp_instances(&few),
            Err(InstancesError::TooFewInliers { inliers: 4, .. })
        ));
    }
}
