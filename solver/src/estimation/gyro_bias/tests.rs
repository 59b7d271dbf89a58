use super::*;
use crate::data::pair_file::PairFile;
use crate::data::simulate::{simulate, SimulationOptions};
use crate::estimation::refine::tests::{check_jacobian, perturbed};
use crate::experiment::median;
use crate::methods::{estimate_relative_pose, EstimateOptions, Method};
use crate::model::epipolar::observe_matches;
use crate::model::geometry::{rotation_error_deg, translation_error_deg};

/// The bias the tests add to the simulated gyro readings: 0.03 rad/s per axis.
const BIAS: [f64; 3] = [0.03, -0.03, 0.03];

/// A simulated pair of 150 matches whose `gyro` readings carry [`BIAS`] (camera axes).
fn biased_pair(seed: u64, pixel_noise: f64, gyro_noise: f64) -> PairFile {
    biased_pair_of(seed, 150, pixel_noise, gyro_noise)
}

/// [`biased_pair`] with `points` matches.
fn biased_pair_of(seed: u64, points: usize, pixel_noise: f64, gyro_noise: f64) -> PairFile {
    let mut pair = simulate(&SimulationOptions {
        points,
        pixel_noise,
        gyro_noise,
        seed,
        ..Default::default()
    })
    .unwrap();
    let g = pair.gyro.as_mut().unwrap();
    for w in g.iter_mut() {
        for (x, b) in w.iter_mut().zip(BIAS) {
            *x += b;
        }
    }
    pair
}

#[test]
fn recovers_the_bias_and_the_pose_without_noise() {
    for seed in [3, 4] {
        let pair = biased_pair(seed, 0.0, 0.0);
        let gt = pair.ground_truth.clone().unwrap();
        let (v1, v2) = pair.views().unwrap();
        let start = perturbed(&gt.rotation_matrix(), &gt.translation_vector());
        let all = vec![true; pair.matches.len()];
        let fit = refine_gyro_bias(
            &v1,
            &v2,
            &pair.matches,
            &all,
            &start.matrix(),
            &start.translation,
            &GyroBiasOptions::default(),
        )
        .unwrap();
        assert!(
            (fit.bias - Vector3::from(BIAS)).norm() < 1e-6,
            "seed {seed}: {}",
            fit.bias
        );
        assert!(rotation_error_deg(&gt.rotation_matrix(), &fit.rotation) < 1e-5);
        assert!(translation_error_deg(&gt.translation_vector(), &fit.translation) < 1e-4);
        assert!(fit.cost < fit.cost_initial);
    }
}

#[test]
fn bias_columns_match_finite_differences_of_the_whole_problem() {
    let pair = biased_pair(21, 1.0, 0.01);
    let gt = pair.ground_truth.clone().unwrap();
    let (v1, v2) = pair.views().unwrap();
    let observations = observe_matches(&v1.camera, &v2.camera, &pair.matches).unwrap();
    let p = BiasProblem {
        views: (&v1, &v2),
        indices: (0..observations.len()).collect(),
        observations,
        loss: Loss::Trivial,
        max_bias: 0.5,
    };
    let start = perturbed(&gt.rotation_matrix(), &gt.translation_vector());
    check_jacobian(&p, &(start, Vector3::new(0.01, 0.02, -0.01)), 1e-5);
}

#[test]
fn the_bias_is_clamped_and_bad_input_refused() {
    let pair = biased_pair(1, 1.0, 0.01);
    let (v1, v2) = pair.views().unwrap();
    let (r, t) = (Matrix3::identity(), Vector3::new(1.0, 0.0, 0.0));
    let n = pair.matches.len();
    let run = |mask: &[bool], o: &GyroBiasOptions| {
        refine_gyro_bias(&v1, &v2, &pair.matches, mask, &r, &t, o)
    };
    let o = GyroBiasOptions::default();
    assert!(run(&vec![true; n - 1], &o).is_none());
    let mut few = vec![false; n];
    few[..7].iter_mut().for_each(|x| *x = true);
    assert!(run(&few, &o).is_none());
    for bad in [
        GyroBiasOptions {
            max_bias: 0.0,
            ..GyroBiasOptions::default()
        },
        GyroBiasOptions {
            loss_px: f64::NAN,
            ..GyroBiasOptions::default()
        },
    ] {
        assert!(bad.invalid().is_some());
        assert!(run(&vec![true; n], &bad).is_none());
    }
    let tight = GyroBiasOptions {
        max_bias: 0.01,
        ..GyroBiasOptions::default()
    };
    let fit = run(&vec![true; n], &tight).unwrap();
    assert!(fit.bias.norm() <= 0.01 + 1e-12, "{}", fit.bias);
}

/// Pose and bias errors of `rectified` with and without the bias refinement on a biased
/// pair: (rotation error without, with, bias error, reported bias std), degrees and rad/s
/// (norms of the bias vectors).
fn errors(pair: &PairFile) -> (f64, f64, f64, f64) {
    let gt = pair.ground_truth.clone().unwrap();
    let (v1, v2) = pair.views().unwrap();
    let plain = EstimateOptions::for_method(Method::Rectified);
    let refined = EstimateOptions {
        gyro_bias: Some(GyroBiasOptions::default()),
        ..plain.clone()
    };
    let a = estimate_relative_pose(&v1, &v2, &pair.matches, &plain).unwrap();
    let b = estimate_relative_pose(&v1, &v2, &pair.matches, &refined).unwrap();
    assert_eq!(a.gyro_bias, None);
    let fit = b.gyro_bias.unwrap();
    let bias = fit.bias;
    let json = b.report_json();
    assert_eq!(
        json["gyro_bias"],
        serde_json::json!([bias.x, bias.y, bias.z])
    );
    (
        rotation_error_deg(&gt.rotation_matrix(), &a.rotation),
        rotation_error_deg(&gt.rotation_matrix(), &b.rotation),
        (bias - Vector3::from(BIAS)).norm(),
        fit.std.norm(),
    )
}

#[test]
fn on_seeded_scenes_the_refined_bias_and_pose_beat_the_biased_ones() {
    // The bias is weakly observable (module documentation): 1000 matches at 0.5 px, and a
    // per-view rate error of 0.002 rad/s per axis, well below the bias.
    let (mut without, mut with, mut bias_err, mut stds) = (vec![], vec![], vec![], vec![]);
    for seed in 0..12 {
        let (a, b, e, s) = errors(&biased_pair_of(100 + seed, 1000, 0.5, 0.002));
        without.push(a);
        with.push(b);
        bias_err.push(e);
        stds.push(s);
    }
    let norm = Vector3::from(BIAS).norm();
    let (a, b, e) = (median(&without), median(&with), median(&bias_err));
    eprintln!("median rotation error {a:.4}° without, {b:.4}° with; bias error {e:.4} rad/s");
    assert!(e < 0.5 * norm, "median bias error {e} rad/s, bias {norm}");
    assert!(b < a, "median rotation error {b}° with, {a}° without");
    // The reported standard deviation matches the errors' size (within a factor of 2).
    let s = median(&stds);
    assert!(
        (0.5 * e..2.0 * e).contains(&s),
        "std {s} rad/s, error {e} rad/s"
    );
}

#[test]
fn estimate_options_refuse_the_bias_for_methods_without_the_gyro() {
    let pair = biased_pair(2, 1.0, 0.01);
    let (v1, v2) = pair.views().unwrap();
    let o = EstimateOptions {
        gyro_bias: Some(GyroBiasOptions::default()),
        ..EstimateOptions::for_method(Method::Gsrp)
    };
    let e = estimate_relative_pose(&v1, &v2, &pair.matches, &o).unwrap_err();
    assert!(e.to_string().contains("gyro_bias"), "{e}");
}
