//! Robust timings of the runtime for noisy shared machines: the candidates are timed in
//! interleaved batches and the minimum batch mean is reported.
//! `cargo test --release -p rspose --test runtime_timing -- --ignored --nocapture`

use nalgebra::SMatrix;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rspose::runtime::{
    gauss_jordan, lu_solve_template, lu_solve_template_fixed, real_eigenpairs,
    real_eigenpairs_sturm,
};
use std::hint::black_box;
use std::time::Instant;

/// Minimum over `rounds` interleaved rounds of the mean time (ns) per call of each
/// candidate, in batches of `n[k]` calls.
fn time_interleaved(rounds: usize, cands: &mut [(&str, usize, &mut dyn FnMut())]) {
    let mut best = vec![f64::INFINITY; cands.len()];
    for _ in 0..rounds {
        for (k, (_, n, f)) in cands.iter_mut().enumerate() {
            let t = Instant::now();
            for _ in 0..*n {
                f();
            }
            best[k] = best[k].min(t.elapsed().as_secs_f64() / *n as f64);
        }
    }
    for ((name, _, _), b) in cands.iter().zip(best) {
        println!("{name:<32} {:9.0} ns", b * 1e9);
    }
}

#[test]
#[ignore]
fn runtime_timings() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut a = [0.0; 200];
    for (k, x) in a.iter_mut().enumerate() {
        *x = rng.gen_range(-1.0..1.0) + if k % 21 == 0 { 3.0 } else { 0.0 };
    }
    let m10 = SMatrix::<f64, 10, 10>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    let m20 = SMatrix::<f64, 20, 20>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    time_interleaved(
        2000,
        &mut [
            ("copy 10x20 only", 50, &mut || {
                black_box(black_box(a));
            }),
            ("gauss_jordan 10x20", 50, &mut || {
                let mut m = black_box(a);
                black_box(gauss_jordan(&mut m, 10, 20, 10));
                black_box(m);
            }),
            ("lu_solve_template 10x20 (4)", 50, &mut || {
                let mut m = black_box(a);
                black_box(lu_solve_template(&mut m, 10, 20, 10, 4));
                black_box(m);
            }),
            ("lu_solve_template_fixed 10x20 (4)", 50, &mut || {
                let mut m = black_box(a);
                black_box(lu_solve_template_fixed::<10, 20, 10, 4>(&mut m));
                black_box(m);
            }),
            ("real_eigenpairs_sturm 10x10", 5, &mut || {
                black_box(real_eigenpairs_sturm(black_box(&m10)));
            }),
            ("Schur::try_new 10x10", 5, &mut || {
                black_box(nalgebra::Schur::try_new(black_box(m10), f64::EPSILON, 310));
            }),
            ("real_eigenpairs 10x10", 5, &mut || {
                black_box(real_eigenpairs(black_box(&m10)));
            }),
            ("real_eigenpairs 20x20", 2, &mut || {
                black_box(real_eigenpairs(black_box(&m20)));
            }),
        ],
    );
}
