//! µs per call of every generated solver on fixed random instances (seeded; realistic data:
//! the nullspace basis of five random correspondences for `gs5pt`, random points, rows,
//! small gyro rates and rotations for `grsrp*`). Each iteration solves the next instance of
//! a pool of 64, so that data-dependent branches (number of real roots) are averaged.
//!
//! `cargo bench -p rspose --bench solvers -- --warm-up-time 1 --measurement-time 3`
//!
//! The per-stage breakdown (coefficients, elimination, eigen) on the same instances is
//! printed by `cargo test --release -p rspose --test solver_stages -- --ignored --nocapture`.

#[path = "../tests/planted/mod.rs"]
mod planted;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rspose::generated::{grsrp, grsrp10, grsrp_gravity, gs5pt};

const POOL: usize = 64;

fn bench_solvers(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let g5: Vec<gs5pt::Data> = (0..POOL)
        .map(|_| planted::gs5pt_instance(&mut rng).data)
        .collect();
    let rs: Vec<planted::Grsrp> = (0..POOL)
        .map(|_| planted::grsrp_instance(&mut rng))
        .collect();
    let r10: Vec<grsrp10::Data> = rs.iter().map(|i| i.data10()).collect();
    let r20: Vec<grsrp::Data> = rs.iter().map(|i| i.data20()).collect();
    let gr: Vec<grsrp_gravity::Data> = (0..POOL)
        .map(|_| planted::gravity_instance(&mut rng).data)
        .collect();

    macro_rules! bench {
        ($name:literal, $module:ident, $pool:expr) => {{
            let pool = &$pool;
            let mut k = 0;
            c.bench_function($name, |b| {
                b.iter(|| {
                    k = (k + 1) % POOL;
                    black_box($module::solve(black_box(&pool[k])))
                })
            });
        }};
    }
    bench!("gs5pt solve", gs5pt, g5);
    bench!("grsrp10 solve", grsrp10, r10);
    bench!("grsrp_gravity solve", grsrp_gravity, gr);
    bench!("grsrp solve", grsrp, r20);
}

criterion_group!(benches, bench_solvers);
criterion_main!(benches);
