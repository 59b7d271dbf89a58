//! µs per call of every generated solver on fixed random instances (seeded; realistic data:
//! the nullspace basis of five random correspondences for `gs5pt`, random points, rows,
//! small gyro rates and rotations for `grsrp*`). Each iteration solves the next instance of
//! a pool of 64, so that data-dependent branches (number of real roots) are averaged. The
//! last entry times the whole 5-point solver from bearings (`minimal::essential_5pt`).
//!
//! `cargo bench -p rspose --bench solvers -- --warm-up-time 1 --measurement-time 3`
//!
//! The per-stage breakdown (coefficients, elimination, eigen) on the same instances:
//! `cargo bench -p rspose --bench stages`.

#[path = "../tests/planted/mod.rs"]
mod planted;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mingen_runtime::FlatValues;
use mingen_runtime::MinimalSolver;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rspose::generated::{grsrp, grsrp10, grsrp_gravity, grsrp_gravity6, gs5pt};
use rspose::minimal::essential_5pt;

const POOL: usize = 64;

fn bench_solvers(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let g5_instances: Vec<planted::Gs5pt> = (0..POOL)
        .map(|_| planted::gs5pt_instance(&mut rng))
        .collect();
    let g5: Vec<gs5pt::Data> = g5_instances.iter().map(|i| i.data).collect();
    let rs: Vec<planted::Grsrp> = (0..POOL)
        .map(|_| planted::grsrp_instance(&mut rng))
        .collect();
    let r10: Vec<grsrp10::Data> = rs.iter().map(|i| i.data10()).collect();
    let r20: Vec<grsrp::Data> = rs.iter().map(|i| i.data20()).collect();
    let gr: Vec<grsrp_gravity::Data> = (0..POOL)
        .map(|_| planted::gravity_instance(&mut rng).data)
        .collect();

    bench::<gs5pt::Solver>(c, &g5);
    bench::<grsrp10::Solver>(c, &r10);
    bench::<grsrp_gravity::Solver>(c, &gr);
    // The same instances for the t-eliminated problem (identical data slots).
    let gr6: Vec<grsrp_gravity6::Data> = gr
        .iter()
        .filter_map(|d| grsrp_gravity6::Data::from_flat(&d.to_slots()))
        .collect();
    bench::<grsrp_gravity6::Solver>(c, &gr6);
    bench::<grsrp::Solver>(c, &r20);

    // The whole 5-point solver from five bearing pairs to essential matrices (null space of
    // the epipolar constraints, gs5pt, E = x E1 + y E2 + z E3 + E4): the work PoseLib's
    // `relpose_5pt` does in its essential-matrix form, for comparisons with it.
    let mut k = 0;
    let mut es = Vec::with_capacity(10);
    c.bench_function("essential_5pt (bearings -> E)", |b| {
        b.iter(|| {
            k = (k + 1) % POOL;
            let (b1, b2) = &g5_instances[k].bearings;
            es.clear();
            essential_5pt(black_box(b1), black_box(b2), &mut es);
            black_box(es.len())
        })
    });
}

/// `<name> solve`: one call per iteration, cycling through the instance pool.
fn bench<S: MinimalSolver>(c: &mut Criterion, pool: &[S::Data]) {
    let mut k = 0;
    c.bench_function(&format!("{} solve", S::NAME), |b| {
        b.iter(|| {
            k = (k + 1) % pool.len();
            black_box(S::solve(black_box(&pool[k])))
        })
    });
}

criterion_group!(benches, bench_solvers);
criterion_main!(benches);
