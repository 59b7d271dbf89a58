//! Times each method on a simulated 150-match pair (paper preset: 200 RANSAC iterations,
//! algebraic threshold 0.01), with the generated minimal solvers.

use criterion::{criterion_group, criterion_main, Criterion};
use rspose::data::simulate::{simulate, SimulationOptions};
use rspose::{estimate_relative_pose, EstimateOptions, Method};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let pair = simulate(&SimulationOptions::default()).expect("simulation");
    let (v1, v2) = pair.views().unwrap();
    let mut group = c.benchmark_group("estimator_150_matches_200_iterations");
    for method in Method::ALL {
        let opts = EstimateOptions::paper(method);
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
