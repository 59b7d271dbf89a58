use super::*;
use crate::data::pair_file::PairFile;
use crate::data::simulate::{simulate, SimulationOptions};
use crate::estimation::readout::ReadoutOptions;
use crate::experiment::evaluate::pose_errors;
use crate::minimal::{EssentialSolver, GrsrpSolver};
use crate::model::camera::{Camera, View};
use crate::model::matches::Match;
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn pair(opts: SimulationOptions) -> PairFile {
    simulate(&opts).unwrap()
}

fn run(p: &PairFile, o: &EstimateOptions) -> Result<Estimate, EstimateError> {
    let (v1, v2) = p.views().unwrap();
    estimate_relative_pose(&v1, &v2, &p.matches, o)
}

fn eight_point(method: Method) -> EstimateOptions {
    EstimateOptions {
        essential_solver: EssentialSolver::EightPoint,
        ..EstimateOptions::for_method(method)
    }
}

#[test]
fn method_names_roundtrip() {
    for m in Method::ALL {
        assert_eq!(m.to_string().parse::<Method>().unwrap(), m);
    }
    assert_eq!("grsrp+".parse::<Method>().unwrap(), Method::GrsrpPlus);
    assert!("foo".parse::<Method>().is_err());
}

#[test]
fn input_errors_are_typed() {
    let p = pair(SimulationOptions {
        points: 30,
        ..Default::default()
    });
    let (v1, v2) = p.views().unwrap();
    let o = EstimateOptions::for_method(Method::Gsrp);
    let mut m = p.matches.clone();
    m[3][1][0] = f64::NAN;
    assert_eq!(
        estimate_relative_pose(&v1, &v2, &m, &o),
        Err(EstimateError::NonFinitePixel { index: 3, image: 2 })
    );
    let mut m = p.matches.clone();
    m[2][0][0] -= 1e6;
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &m, &o),
        Err(EstimateError::PixelOutsideImage {
            index: 2,
            image: 1,
            ..
        })
    ));
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &p.matches[..4], &o),
        Err(EstimateError::TooFewMatches {
            needed: 5,
            got: 4,
            ..
        })
    ));
    let nr = EstimateOptions::for_method(Method::Nrsrp);
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &p.matches[..16], &nr),
        Err(EstimateError::TooFewMatches { needed: 17, .. })
    ));
    let dup = vec![p.matches[0]; 40];
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &dup, &o),
        Err(EstimateError::Degenerate { distinct: 1, .. })
    ));
    let mut bad = v1.clone();
    bad.camera.fy = -3.0;
    assert!(matches!(
        estimate_relative_pose(&bad, &v2, &p.matches, &o),
        Err(EstimateError::InvalidCamera { view: 1, .. })
    ));
    let mut bad = v2.clone();
    bad.omega.x = f64::INFINITY;
    assert!(matches!(
        estimate_relative_pose(&v1, &bad, &p.matches, &o),
        Err(EstimateError::InvalidCamera { view: 2, .. })
    ));
    let mut o2 = o.clone();
    o2.robust.threshold = Threshold::SampsonPixels(-1.0);
    assert!(matches!(
        estimate_relative_pose(&v1, &v2, &p.matches, &o2),
        Err(EstimateError::InvalidOption { .. })
    ));
}

#[test]
fn garbage_input_never_panics() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let specials = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e300,
        -1e300,
        0.0,
        1e-300,
        5.0,
    ];
    let cam = Camera::paper();
    for trial in 0..60 {
        let n = rng.gen_range(0..40);
        let mut matches: Vec<Match> = (0..n)
            .map(|_| {
                let mut g = || {
                    if rng.gen_bool(0.15) {
                        specials[rng.gen_range(0..specials.len())]
                    } else {
                        rng.gen_range(-3000.0..3000.0)
                    }
                };
                [[g(), g()], [g(), g()]]
            })
            .collect();
        if trial % 3 == 0 && !matches.is_empty() {
            // Mostly duplicates / finite garbage.
            let m0 = [[1e300, -1e300], [1e-300, 7.0]];
            for (i, m) in matches.iter_mut().enumerate() {
                *m = if i % 2 == 0 {
                    m0
                } else {
                    [[3.0, 3.0], [3.0, 3.0]]
                };
            }
        }
        let w = Vector3::new(
            specials[rng.gen_range(0..specials.len())],
            rng.gen_range(-10.0..10.0),
            0.0,
        );
        let g = Vector3::new(0.1, rng.gen_range(-10.0..10.0), 0.2);
        let views = [
            View::new(cam, Vector3::new(0.5, 0.1, -0.3)).with_gravity(g),
            View::new(cam, w).with_gravity(g),
        ];
        for method in Method::ALL {
            for solver in [EssentialSolver::FivePoint, EssentialSolver::EightPoint] {
                let o = EstimateOptions {
                    essential_solver: solver,
                    ..EstimateOptions::paper(method)
                };
                if let Ok(e) = estimate_relative_pose(&views[0], &views[1], &matches, &o) {
                    assert!(e.rotation.iter().all(|x| x.is_finite()));
                    assert!((e.translation.norm() - 1.0).abs() < 1e-6);
                    assert_eq!(e.inliers.len(), matches.len());
                }
            }
        }
    }
}

#[test]
fn degenerate_geometry_gives_no_nan() {
    // All points on one ray pair: rank-deficient; must be an error or a finite pose.
    let cam = Camera::paper();
    let v = View::new(cam, Vector3::zeros()).with_gravity(Vector3::y());
    let matches: Vec<Match> = (0..20)
        .map(|k| {
            [
                [100.0 + k as f64 * 1e-9, 200.0],
                [100.0, 200.0 + k as f64 * 1e-9],
            ]
        })
        .collect();
    for method in Method::ALL {
        let o = eight_point(method);
        match estimate_relative_pose(&v, &v, &matches, &o) {
            Ok(e) => assert!(e
                .rotation
                .iter()
                .chain(e.translation.iter())
                .all(|x| x.is_finite())),
            Err(e) => assert!(matches!(e, EstimateError::NoSolution)),
        }
    }
}

mod accuracy;
mod cameras;
mod robustness;
