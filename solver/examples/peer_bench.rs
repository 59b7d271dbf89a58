//! Same-data comparison with a peer library (PoseLib; `tools/peer/poselib/`).
//!
//! `peer_bench write DIR` writes the instances both sides run:
//! - `five_point.txt`: 64 minimal problems, one per line, 30 numbers: five unit bearings in
//!   image 1 then five in image 2 (random scenes, noise-free);
//! - `pairs.txt`: global-shutter pairs of the paper's protocol (150 matches, 1 px noise,
//!   30 % outliers; 50 unless `write DIR PAIRS` says otherwise), each a header line `N fx fy cx cy r00 .. r22 t0 t1 t2` (ground truth
//!   `x2 = R x1 + t`) and N lines `u1 v1 u2 v2`.
//!
//! `peer_bench time DIR [ROUNDS]` times ours on them: essential matrices from 5 bearings,
//! poses from 5 bearings (essential matrices, then the cheirality-checked decomposition of
//! each), and the estimator (`gsrp`: 200 RANSAC iterations, Sampson threshold 2 px, local
//! optimisation, final refinement), printing microseconds per call (median of rounds) and the
//! estimator's accuracy, in the same format as the peer driver.

use nalgebra::{Matrix3, Vector3};
use rspose::data::pair_file::{GroundTruth, Match};
use rspose::data::simulate::{simulate, SimulationOptions};
use rspose::experiment::evaluate::pose_errors;
use rspose::methods::Threshold;
use rspose::minimal::essential_5pt;
use rspose::model::camera::{Camera, View};
use rspose::model::geometry::pose_from_essential;
use rspose::{estimate_relative_pose, EstimateOptions, Method};
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

type Five = ([Vector3<f64>; 5], [Vector3<f64>; 5]);

struct Pair {
    camera: Camera,
    matches: Vec<Match>,
    truth: GroundTruth,
}

fn write(dir: &Path, num_pairs: u64) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    let mut five = String::new();
    for seed in 1..=64 {
        let p = simulate(&SimulationOptions {
            angular_velocity: 0.0,
            pixel_noise: 0.0,
            gyro_noise: 0.0,
            points: 5,
            seed,
            ..Default::default()
        })
        .map_err(|e| e.to_string())?;
        let cam = p.cameras[0];
        for k in 0..2 {
            for m in &p.matches {
                let b = cam
                    .undistort_bearing(m[k][0], m[k][1])
                    .map_err(|e| e.to_string())?
                    .normalize();
                let _ = write!(five, "{:e} {:e} {:e} ", b.x, b.y, b.z);
            }
        }
        five.push('\n');
    }
    std::fs::write(dir.join("five_point.txt"), five).map_err(|e| e.to_string())?;
    let mut pairs = String::new();
    for seed in 0..num_pairs {
        let p = simulate(&SimulationOptions {
            angular_velocity: 0.0,
            gyro_noise: 0.0,
            outlier_fraction: 0.3,
            seed: 1000 + seed,
            ..Default::default()
        })
        .map_err(|e| e.to_string())?;
        let gt = p.ground_truth.ok_or("no ground truth")?;
        let c = p.cameras[0];
        let _ = write!(
            pairs,
            "{} {} {} {} {}",
            p.matches.len(),
            c.fx,
            c.fy,
            c.cx,
            c.cy
        );
        for x in gt.rotation.iter().flatten().chain(&gt.translation) {
            let _ = write!(pairs, " {x:e}");
        }
        pairs.push('\n');
        for m in &p.matches {
            let _ = writeln!(
                pairs,
                "{:e} {:e} {:e} {:e}",
                m[0][0], m[0][1], m[1][0], m[1][1]
            );
        }
    }
    std::fs::write(dir.join("pairs.txt"), pairs).map_err(|e| e.to_string())
}

fn numbers(line: &str) -> Result<Vec<f64>, String> {
    line.split_whitespace()
        .map(|x| x.parse().map_err(|e| format!("`{x}`: {e}")))
        .collect()
}

fn read(dir: &Path) -> Result<(Vec<Five>, Vec<Pair>), String> {
    let load =
        |name: &str| std::fs::read_to_string(dir.join(name)).map_err(|e| format!("{name}: {e}"));
    let mut five = Vec::new();
    for l in load("five_point.txt")?.lines() {
        let v = numbers(l)?;
        if v.len() != 30 {
            return Err("five_point.txt: 30 numbers per line".into());
        }
        let b = |i: usize| Vector3::new(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        five.push((std::array::from_fn(b), std::array::from_fn(|i| b(i + 5))));
    }
    let text = load("pairs.txt")?;
    let mut lines = text.lines();
    let mut pairs = Vec::new();
    while let Some(h) = lines.next() {
        let h = numbers(h)?;
        if h.len() != 17 {
            return Err("pairs.txt: a header has 17 numbers".into());
        }
        let n = h[0] as usize;
        let camera = Camera::pinhole(h[1], h[2], h[3], h[4], 1920.0, 1080.0, 0.0);
        let mut matches: Vec<Match> = Vec::with_capacity(n);
        for _ in 0..n {
            let v = numbers(lines.next().ok_or("pairs.txt: truncated")?)?;
            if v.len() != 4 {
                return Err("pairs.txt: a match has 4 numbers".into());
            }
            matches.push([[v[0], v[1]], [v[2], v[3]]]);
        }
        pairs.push(Pair {
            camera,
            truth: GroundTruth {
                rotation: std::array::from_fn(|i| std::array::from_fn(|j| h[5 + 3 * i + j])),
                translation: [h[14], h[15], h[16]],
                omega: [[0.0; 3]; 2],
                velocity: [[0.0; 3]; 2],
                inliers: vec![true; n],
            },
            matches,
        });
    }
    Ok((five, pairs))
}

/// Median over `rounds` of the mean time per call of `f` over `calls` calls, in µs.
fn time(rounds: usize, calls: usize, mut f: impl FnMut(usize)) -> f64 {
    let mut t: Vec<f64> = (0..rounds.max(1))
        .map(|_| {
            let start = Instant::now();
            for k in 0..calls {
                f(k);
            }
            start.elapsed().as_secs_f64() * 1e6 / calls as f64
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn run(args: &[String]) -> Result<(), String> {
    let usage = "usage: peer_bench write DIR [PAIRS] | peer_bench time DIR [ROUNDS]";
    let (Some(cmd), Some(dir)) = (args.get(1), args.get(2)) else {
        return Err(usage.into());
    };
    let dir = Path::new(dir);
    match cmd.as_str() {
        "write" => {
            let num_pairs = match args.get(3) {
                Some(s) => s
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or(format!("PAIRS must be a positive integer, got `{s}`"))?,
                None => 50,
            };
            return write(dir, num_pairs);
        }
        "time" => {}
        _ => return Err(usage.into()),
    }
    let rounds: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(5);
    let (five, pairs) = read(dir)?;
    let mut es: Vec<Matrix3<f64>> = Vec::with_capacity(10);
    let e_us = time(rounds, 30_000, |k| {
        let (b1, b2) = &five[k % five.len()];
        es.clear();
        essential_5pt(black_box(b1), black_box(b2), &mut es);
        black_box(es.len());
    });
    let mut poses = Vec::with_capacity(10);
    let p_us = time(rounds, 30_000, |k| {
        let (b1, b2) = &five[k % five.len()];
        es.clear();
        essential_5pt(black_box(b1), black_box(b2), &mut es);
        poses.clear();
        poses.extend(es.iter().filter_map(|e| pose_from_essential(e, b1, b2)));
        black_box(poses.len());
    });
    let mut options = EstimateOptions::for_method(Method::Gsrp);
    options.robust.adaptive = false;
    options.robust.min_iterations = 200;
    options.robust.max_iterations = 200;
    options.robust.global_shutter_threshold = Threshold::SampsonPixels(2.0);
    let (mut rot, mut tra) = (Vec::new(), Vec::new());
    let est_us = time(rounds, pairs.len(), |k| {
        let p = &pairs[k];
        let v = View::new(p.camera, Vector3::zeros());
        if let Ok(e) = black_box(estimate_relative_pose(&v, &v, &p.matches, &options)) {
            if rot.len() < pairs.len() {
                let err = pose_errors(&e, &p.truth);
                rot.push(err.rotation_error_deg);
                tra.push(err.translation_error_deg);
            }
        }
    });
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    println!("ours essential_from_5_bearings_us {e_us:.3}");
    println!("ours poses_from_5_bearings_us {p_us:.3}");
    println!("ours estimator_200_iterations_us {est_us:.1}");
    println!(
        "ours estimator_mean_errors_deg rotation {:.4} translation {:.4} solved {}",
        mean(&rot),
        mean(&tra),
        rot.len()
    );
    Ok(())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Err(e) = run(&args) {
        eprintln!("peer_bench: {e}");
        std::process::exit(2);
    }
}
