//! Per-call time of the two forms of emitted coefficient code on the same data:
//! `cargo run --release -p workspace-tests --example code_forms`.
//!
//! Prints, for each problem built in both forms (`src/lib.rs`'s `inline` and `table`
//! modules), the microseconds per `solve` of each form, interleaved in rounds so that drift
//! of the machine's speed hits both alike.

use mingen_runtime::{FlatValues, MinimalSolver};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::Instant;
use workspace_tests as ex;

fn per_call<S: MinimalSolver>(data: &[S::Data]) -> f64 {
    let t = Instant::now();
    for d in data {
        black_box(S::solve(black_box(d)));
    }
    t.elapsed().as_secs_f64() * 1e6 / data.len() as f64
}

fn compare<A: MinimalSolver, B: MinimalSolver>(name: &str, instances: usize, rounds: usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let flat: Vec<Vec<f64>> = (0..instances)
        .map(|_| {
            (0..A::Data::LEN)
                .map(|_| rng.gen_range(-1.0..1.0))
                .collect()
        })
        .collect();
    let a: Vec<A::Data> = flat.iter().filter_map(|f| A::Data::from_flat(f)).collect();
    let b: Vec<B::Data> = flat.iter().filter_map(|f| B::Data::from_flat(f)).collect();
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    for _ in 0..rounds {
        ta.push(per_call::<A>(&a));
        tb.push(per_call::<B>(&b));
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (ma, mb) = (median(&mut ta), median(&mut tb));
    println!(
        "{name:<22} inline {ma:8.2} us   table {mb:8.2} us   table/inline {:.3}",
        mb / ma
    );
}

fn main() {
    compare::<ex::inline::p35pf::Solver, ex::table::p35pf::Solver>("p35pf", 2000, 9);
    compare::<ex::inline::relpose_5pt_entries::Solver, ex::table::relpose_5pt_entries::Solver>(
        "relpose_5pt_entries",
        500,
        9,
    );
}
