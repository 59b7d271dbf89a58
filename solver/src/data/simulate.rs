//! The paper's synthetic protocol ("Experiments on Synthetic Data") as a library function.
//!
//! Scene: camera 1 at the world origin with identity orientation at row 0
//! (`R1 = I, C1 = 0`); camera 2 with orientation `R2 = exp([r]×)`, `r ~ N(0, σ_R²)` per axis
//! (σ_R = 10° by default) and centre `C2 ~ N(0, σ_t²)` per axis (σ_t = 2 m). Relative pose
//! (ARCHITECTURE §4): `R = R2 R1^T = R2`, `t = R2 (C1 - C2) / |.|`.
//! Each camera gets an angular velocity of magnitude `angular_velocity` (rad/s, camera frame)
//! and a linear velocity of magnitude `linear_velocity` (m/s, world frame), each in an
//! independent uniformly random direction. Points are drawn along random pixels of image 1 at
//! depths uniform in `[min_depth, max_depth]`, kept if within `max_depth` of both camera
//! centres and if their rolling-shutter projections ([`project_rs`], fixed point over the
//! line coordinate of the raw distorted pixel, with the camera's model and readout
//! direction) fall inside both images. Pixels get Gaussian noise (`pixel_noise` px per coordinate); the gyro
//! readings stored in the file are the true ω plus Gaussian noise (`gyro_noise` rad/s per
//! axis), while the true ω generated the images. A fraction `outlier_fraction` of the matches
//! has its image-2 pixel replaced by a uniformly random pixel (flagged as outliers in the
//! ground truth). Each view also gets the direction of gravity in its row-0 camera axes, an
//! accelerometer's reading: a world "down" drawn uniformly on the sphere, rotated into each
//! camera, then tilted by a Gaussian angle per tangent axis (`gravity_noise_deg`; the
//! tilt's magnitude averages 1.25 times that). Everything is deterministic given `seed`
//! (ChaCha8); the gravity is drawn after everything else, so it leaves the rest of a scene
//! as it was without it.

use crate::data::pair_file::{rows_of_matrix, GroundTruth, Match, PairFile};
use crate::model::camera::Camera;
use crate::model::geometry::{exp_so3, tangent_basis};
use crate::model::rolling_shutter::{project_rs, RsPose};
use nalgebra::{Matrix3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use thiserror::Error;

/// Options of [`simulate`]. Defaults: the paper's setting at its hardest noise experiment
/// level, with zero linear velocity.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationOptions {
    /// Camera (default [`Camera::paper`]: 1920x1080, f = 640 px, centred, 60 µs/row): any
    /// model and readout direction. Points are drawn along the bearings of random pixels
    /// (undistorted; pixels without one skipped) and projected through the distortion,
    /// each at the time of its raw pixel's line ([`project_rs`]); points outside the
    /// distortion's invertible region are not visible.
    pub camera: Camera,
    /// Image 2's camera, if it differs from image 1's (default `None`: `camera` for both;
    /// the pair file then has `cameras`).
    pub camera2: Option<Camera>,
    /// Number of matches visible in both images (default 150).
    pub points: usize,
    /// Nearest point depth in camera 1, m (default 1).
    pub min_depth: f64,
    /// Farthest point, m: depth in camera 1 and distance to both centres (default 60).
    pub max_depth: f64,
    /// Standard deviation of the relative rotation per axis, degrees (default 10).
    pub rotation_std_deg: f64,
    /// Standard deviation of camera 2's centre per axis, m (default 2).
    pub translation_std: f64,
    /// Angular velocity magnitude of each camera, rad/s (default 2.5).
    pub angular_velocity: f64,
    /// Linear velocity magnitude of each camera, m/s (default 0).
    pub linear_velocity: f64,
    /// Pixel noise standard deviation per coordinate, px (default 1).
    pub pixel_noise: f64,
    /// Gyro noise standard deviation per axis, rad/s (default 0.1).
    pub gyro_noise: f64,
    /// Fraction of matches replaced by random pixels in image 2, in `[0, 1)` (default 0).
    pub outlier_fraction: f64,
    /// Gravity noise per tangent axis of each view's gravity direction, degrees (default 1).
    pub gravity_noise_deg: f64,
    /// Random seed (default 0).
    pub seed: u64,
    /// A planar scene: every point on the plane `z = plane_depth` (m) of camera 1's row-0
    /// frame, instead of depths uniform in `[min_depth, max_depth]` (default `None`).
    pub plane_depth: Option<f64>,
}

/// The largest number of points [`simulate`] makes (a pair file of this size is a few
/// hundred MB).
pub const MAX_POINTS: usize = 2_000_000;

impl Default for SimulationOptions {
    fn default() -> Self {
        SimulationOptions {
            camera: Camera::paper(),
            camera2: None,
            points: 150,
            min_depth: 1.0,
            max_depth: 60.0,
            rotation_std_deg: 10.0,
            translation_std: 2.0,
            angular_velocity: 2.5,
            linear_velocity: 0.0,
            pixel_noise: 1.0,
            gyro_noise: 0.1,
            outlier_fraction: 0.0,
            gravity_noise_deg: 1.0,
            seed: 0,
            plane_depth: None,
        }
    }
}

/// Why a simulation could not be produced.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SimulationError {
    /// An option is out of range; names the option.
    #[error("invalid simulation option `{option}`: {reason}")]
    InvalidOption {
        /// Option name.
        option: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Not enough points were visible in both images after many attempts.
    #[error("only {found} of {wanted} points visible in both images")]
    TooFewVisiblePoints {
        /// Points found.
        found: usize,
        /// Points requested.
        wanted: usize,
    },
}

/// Standard normal sample (Box-Muller).
pub(crate) fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = 1.0 - rng.gen::<f64>(); // (0, 1]
    let u2: f64 = rng.gen::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

fn gauss3(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    Vector3::new(gauss(rng), gauss(rng), gauss(rng))
}

fn random_direction(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    loop {
        let v = gauss3(rng);
        let n = v.norm();
        if n > 1e-6 {
            return v / n;
        }
    }
}

fn check(options: &SimulationOptions) -> Result<(), SimulationError> {
    let bad = |option, reason: &str| {
        Err(SimulationError::InvalidOption {
            option,
            reason: reason.into(),
        })
    };
    if let Err(e) = options.camera.validate() {
        return bad("camera", &e.to_string());
    }
    if let Some(Err(e)) = options.camera2.map(|c| c.validate()) {
        return bad("camera2", &e.to_string());
    }
    if options.points == 0 || options.points > MAX_POINTS {
        return bad("points", &format!("must be between 1 and {MAX_POINTS}"));
    }
    if let Some(d) = options.plane_depth {
        if !(d.is_finite() && d > 0.0) {
            return bad("plane_depth", "must be finite and positive");
        }
    }
    let nonneg = [
        ("rotation_std_deg", options.rotation_std_deg),
        ("translation_std", options.translation_std),
        ("angular_velocity", options.angular_velocity),
        ("linear_velocity", options.linear_velocity),
        ("pixel_noise", options.pixel_noise),
        ("gyro_noise", options.gyro_noise),
        ("gravity_noise_deg", options.gravity_noise_deg),
    ];
    for (name, v) in nonneg {
        if !(v.is_finite() && v >= 0.0) {
            return bad(name, "must be finite and non-negative");
        }
    }
    if !(options.min_depth.is_finite()
        && options.min_depth > 0.0
        && options.max_depth.is_finite()
        && options.max_depth > options.min_depth)
    {
        return bad("min_depth/max_depth", "need 0 < min_depth < max_depth");
    }
    if !(options.outlier_fraction.is_finite() && (0.0..1.0).contains(&options.outlier_fraction)) {
        return bad("outlier_fraction", "must be in [0, 1)");
    }
    if options.translation_std == 0.0 {
        return bad("translation_std", "must be positive (zero baseline)");
    }
    Ok(())
}

/// Simulate one image pair following the paper's protocol (see the module documentation).
pub fn simulate(options: &SimulationOptions) -> Result<PairFile, SimulationError> {
    check(options)?;
    let cam = options.camera;
    let cam2 = options.camera2.unwrap_or(cam);
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let r2 = exp_so3(&(gauss3(&mut rng) * options.rotation_std_deg.to_radians()));
    let c2 = loop {
        let c = gauss3(&mut rng) * options.translation_std;
        if c.norm() > 1e-3 * options.translation_std.max(1e-9) {
            break c;
        }
    };
    let omega = [
        random_direction(&mut rng) * options.angular_velocity,
        random_direction(&mut rng) * options.angular_velocity,
    ];
    let velocity = [
        random_direction(&mut rng) * options.linear_velocity,
        random_direction(&mut rng) * options.linear_velocity,
    ];
    let poses = [
        RsPose {
            rotation: Matrix3::identity(),
            centre: Vector3::zeros(),
            velocity: velocity[0],
            omega: omega[0],
        },
        RsPose {
            rotation: r2,
            centre: c2,
            velocity: velocity[1],
            omega: omega[1],
        },
    ];
    let inside = |p: &nalgebra::Vector2<f64>, cam: &Camera| {
        p.x >= 0.0 && p.x < cam.width && p.y >= 0.0 && p.y < cam.height
    };
    let mut matches: Vec<Match> = Vec::with_capacity(options.points);
    let max_attempts = 2000 * options.points + 10_000;
    let mut attempts = 0;
    while matches.len() < options.points && attempts < max_attempts {
        attempts += 1;
        let u = rng.gen_range(0.0..cam.width);
        let v = rng.gen_range(0.0..cam.height);
        let depth = match options.plane_depth {
            Some(d) => d,
            None => rng.gen_range(options.min_depth..options.max_depth),
        };
        let Ok(bearing) = cam.undistort_bearing(u, v) else {
            continue;
        };
        let x = bearing * depth;
        if x.norm() > options.max_depth || (x - c2).norm() > options.max_depth {
            continue;
        }
        let (Ok(p1), Ok(p2)) = (
            project_rs(&cam, &poses[0], &x),
            project_rs(&cam2, &poses[1], &x),
        ) else {
            continue;
        };
        if !(inside(&p1, &cam) && inside(&p2, &cam2)) {
            continue;
        }
        matches.push([[p1.x, p1.y], [p2.x, p2.y]]);
    }
    if matches.len() < options.points {
        return Err(SimulationError::TooFewVisiblePoints {
            found: matches.len(),
            wanted: options.points,
        });
    }
    for m in &mut matches {
        for p in m.iter_mut() {
            p[0] += options.pixel_noise * gauss(&mut rng);
            p[1] += options.pixel_noise * gauss(&mut rng);
        }
    }
    let mut inliers = vec![true; matches.len()];
    let n_out = (options.outlier_fraction * matches.len() as f64).round() as usize;
    let mut chosen = 0;
    while chosen < n_out {
        let i = rng.gen_range(0..matches.len());
        if inliers[i] {
            inliers[i] = false;
            // A random pixel that has a bearing (every pixel of a pinhole does; the
            // principal point always has one).
            let mut pixel = [cam2.cx, cam2.cy];
            for _ in 0..10_000 {
                let p = [
                    rng.gen_range(0.0..cam2.width),
                    rng.gen_range(0.0..cam2.height),
                ];
                if cam2.observe(p).is_ok() {
                    pixel = p;
                    break;
                }
            }
            matches[i][1] = pixel;
            chosen += 1;
        }
    }
    let gyro = [
        omega[0] + gauss3(&mut rng) * options.gyro_noise,
        omega[1] + gauss3(&mut rng) * options.gyro_noise,
    ];
    let down = random_direction(&mut rng);
    let sigma = options.gravity_noise_deg.to_radians();
    let gravity = [Matrix3::identity(), r2].map(|r| {
        let g = r * down;
        let (b1, b2) = tangent_basis(&g);
        let tilt = (b1 * gauss(&mut rng) + b2 * gauss(&mut rng)) * sigma;
        (exp_so3(&tilt) * g).into()
    });
    let t = (-r2 * c2).normalize();
    Ok(PairFile {
        cameras: [cam, cam2],
        gyro: Some([gyro[0].into(), gyro[1].into()]),
        gyro_bias: None,
        gyro_log: None,
        gravity: Some(gravity),
        matches,
        ground_truth: Some(GroundTruth {
            rotation: rows_of_matrix(&r2),
            translation: t.into(),
            omega: [omega[0].into(), omega[1].into()],
            velocity: [velocity[0].into(), velocity[1].into()],
            inliers,
        }),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::skew;
    use crate::model::rolling_shutter::undistort_bearing;

    #[test]
    fn deterministic_and_valid() {
        let opts = SimulationOptions {
            outlier_fraction: 0.2,
            seed: 7,
            ..Default::default()
        };
        let a = simulate(&opts).unwrap();
        let b = simulate(&opts).unwrap();
        assert_eq!(a, b);
        a.validate().unwrap();
        assert_eq!(a.matches.len(), 150);
        let gt = a.ground_truth.as_ref().unwrap();
        assert_eq!(gt.inliers.iter().filter(|&&x| !x).count(), 30);
        let c = simulate(&SimulationOptions { seed: 8, ..opts }).unwrap();
        assert_ne!(a, c);
        for m in &a.matches {
            for p in m {
                assert!(p[0] > -10.0 && p[0] < 1930.0 && p[1] > -10.0 && p[1] < 1090.0);
            }
        }
    }

    #[test]
    fn noise_free_angular_pairs_satisfy_the_exact_model() {
        let opts = SimulationOptions {
            pixel_noise: 0.0,
            gyro_noise: 0.0,
            angular_velocity: 3.0,
            seed: 3,
            ..Default::default()
        };
        let pair = simulate(&opts).unwrap();
        let gt = pair.ground_truth.clone().unwrap();
        assert_eq!(pair.gyro, Some(gt.omega));
        let (v1, v2) = pair.views().unwrap();
        let e = skew(&gt.translation_vector()) * gt.rotation_matrix();
        let mut max_plain: f64 = 0.0;
        for m in &pair.matches {
            let b1 = undistort_bearing(&v1, m[0][0], m[0][1])
                .unwrap()
                .normalize();
            let b2 = undistort_bearing(&v2, m[1][0], m[1][1])
                .unwrap()
                .normalize();
            assert!((b2.transpose() * e * b1)[0].abs() < 1e-9);
            let p1 = v1
                .camera
                .undistort_bearing(m[0][0], m[0][1])
                .unwrap()
                .normalize();
            let p2 = v2
                .camera
                .undistort_bearing(m[1][0], m[1][1])
                .unwrap()
                .normalize();
            max_plain = max_plain.max((p2.transpose() * e * p1)[0].abs());
        }
        // The global-shutter model is visibly violated.
        assert!(max_plain > 1e-3);
    }

    /// The gravity of each view is the same world direction in its camera axes (`R g1 = g2`
    /// exactly without noise), tilted by about the requested angle with noise.
    #[test]
    fn gravity_is_one_world_direction_with_the_requested_noise() {
        let exact = simulate(&SimulationOptions {
            gravity_noise_deg: 0.0,
            seed: 9,
            ..Default::default()
        })
        .unwrap();
        let gt = exact.ground_truth.as_ref().unwrap();
        let [g1, g2] = exact.gravity.unwrap().map(Vector3::from);
        assert!((gt.rotation_matrix() * g1 - g2).norm() < 1e-12);
        assert!((g1.norm() - 1.0).abs() < 1e-12);
        let mut sum = 0.0;
        for seed in 0..200 {
            let noisy = simulate(&SimulationOptions {
                gravity_noise_deg: 2.0,
                seed,
                points: 10,
                ..Default::default()
            })
            .unwrap();
            let clean = simulate(&SimulationOptions {
                gravity_noise_deg: 0.0,
                seed,
                points: 10,
                ..Default::default()
            })
            .unwrap();
            // The rest of the scene does not depend on the gravity noise.
            assert_eq!(noisy.matches, clean.matches);
            for (a, b) in noisy.gravity.unwrap().iter().zip(clean.gravity.unwrap()) {
                sum += Vector3::from(*a).angle(&Vector3::from(b)).to_degrees();
            }
        }
        // Rayleigh mean sqrt(pi/2) sigma = 2.51 deg.
        let mean = sum / 400.0;
        assert!((mean - 2.51).abs() < 0.2, "{mean}");
    }

    #[test]
    fn invalid_options_are_named() {
        let err = simulate(&SimulationOptions {
            outlier_fraction: 1.5,
            ..Default::default()
        })
        .unwrap_err();
        assert!(err.to_string().contains("outlier_fraction"));
        let err = simulate(&SimulationOptions {
            pixel_noise: f64::NAN,
            ..Default::default()
        })
        .unwrap_err();
        assert!(err.to_string().contains("pixel_noise"));
    }
}
