//! Times each method on a simulated 150-match pair (paper preset: 200 RANSAC iterations,
//! algebraic threshold 0.01). Methods whose generated solver is not linked in yet are timed
//! with the 8-point stand-in essential solver where possible and otherwise skipped.

use criterion::{criterion_group, criterion_main, Criterion};
use rspose::minimal::{EssentialSolver, GENERATED_AVAILABLE};
use rspose::simulate::{simulate, SimulationOptions};
use rspose::{estimate_relative_pose, EstimateOptions, Method};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let pair = simulate(&SimulationOptions::default()).expect("simulation");
    let (v1, v2) = pair.views();
    let mut group = c.benchmark_group("estimator_150_matches_200_iterations");
    for method in Method::ALL {
        let mut opts = EstimateOptions::paper(method);
        if !GENERATED_AVAILABLE {
            if matches!(method, Method::Grsrp | Method::GrsrpPlus) {
                eprintln!("skipping {method}: generated solvers not available");
                continue;
            }
            opts.essential_solver = EssentialSolver::EightPoint;
        }
        group.bench_function(method.name(), |b| {
            b.iter(|| {
                let _ = black_box(estimate_relative_pose(
                    &v1,
                    &v2,
                    black_box(&pair.matches),
                    &opts,
                ));
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
