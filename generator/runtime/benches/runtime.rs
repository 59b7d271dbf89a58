//! Timings of the numeric runtime used by emitted solvers: the elimination routines and
//! the eigen back ends side by side on the same matrices.
//! `cargo bench -p mingen-runtime --bench runtime`
//!
//! Each elimination iteration includes copying the template into the work buffer
//! (10x20: 200 f64, ~20 ns), since emitted solvers fill a fresh matrix every call.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mingen_runtime::{
    gauss_jordan, lu_solve_template, lu_solve_template_fixed, real_eigenpairs, real_eigenpairs_hqr,
    real_eigenpairs_sturm,
};
use nalgebra::SMatrix;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A random template: dense left block for small sizes; for big ones a sparse-ish block
/// (density `d`) plus a strong diagonal so that it is non-singular.
fn template(rng: &mut ChaCha8Rng, rows: usize, cols: usize, d: f64) -> Vec<f64> {
    let mut m = vec![0.0; rows * cols];
    for i in 0..rows {
        for j in 0..cols {
            if rng.gen::<f64>() < d {
                m[i * cols + j] = rng.gen_range(-1.0..1.0);
            }
        }
        m[i * cols + i] += 3.0;
    }
    m
}

fn bench_elimination(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let small = template(&mut rng, 10, 20, 1.0);
    let mut small_arr = [0.0; 200];
    small_arr.copy_from_slice(&small);
    c.bench_function("gauss_jordan 10x20", |b| {
        b.iter(|| {
            let mut m = black_box(small_arr);
            black_box(gauss_jordan(&mut m, 10, 20, 10));
            m
        })
    });
    c.bench_function("lu_solve_template 10x20 (first_row 4)", |b| {
        b.iter(|| {
            let mut m = black_box(small_arr);
            black_box(lu_solve_template(&mut m, 10, 20, 10, 4));
            m
        })
    });
    c.bench_function("lu_solve_template_fixed 10x20 (first_row 4)", |b| {
        b.iter(|| {
            let mut m = black_box(small_arr);
            black_box(lu_solve_template_fixed::<10, 20, 10, 4>(&mut m));
            m
        })
    });
    let big = template(&mut rng, 100, 120, 0.15);
    let mut buf = big.clone();
    c.bench_function("gauss_jordan 100x120 (15% dense)", |b| {
        b.iter(|| {
            buf.copy_from_slice(black_box(&big));
            black_box(gauss_jordan(&mut buf, 100, 120, 100))
        })
    });
    c.bench_function("lu_solve_template 100x120 (15% dense, first_row 80)", |b| {
        b.iter(|| {
            buf.copy_from_slice(black_box(&big));
            black_box(lu_solve_template(&mut buf, 100, 120, 100, 80))
        })
    });
}

/// `V diag(lambda) V^-1` with random `V` and eigenvalues in `[-1, 1]`.
fn with_real_spectrum<const N: usize>(rng: &mut ChaCha8Rng) -> SMatrix<f64, N, N> {
    let v = SMatrix::<f64, N, N>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    let d = SMatrix::<f64, N, N>::from_diagonal(&nalgebra::SVector::<f64, N>::from_fn(|_, _| {
        rng.gen_range(-1.0..1.0)
    }));
    v * d * v.try_inverse().expect("a random matrix is invertible")
}

fn bench_eigen(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let m10 = SMatrix::<f64, 10, 10>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    let m20 = SMatrix::<f64, 20, 20>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    c.bench_function("real_eigenpairs 10x10", |b| {
        b.iter(|| real_eigenpairs(black_box(&m10)))
    });
    c.bench_function("real_eigenpairs 20x20", |b| {
        b.iter(|| real_eigenpairs(black_box(&m20)))
    });
    // Small actions with real spectra (V diag V^-1): the closed-form root path.
    let m2 = with_real_spectrum::<2>(&mut rng);
    let m4 = with_real_spectrum::<4>(&mut rng);
    c.bench_function("real_eigenpairs_sturm 2x2 (2 real)", |b| {
        b.iter(|| real_eigenpairs_sturm(black_box(&m2)))
    });
    c.bench_function("real_eigenpairs_sturm 4x4 (4 real)", |b| {
        b.iter(|| real_eigenpairs_sturm(black_box(&m4)))
    });
    c.bench_function("real_eigenpairs_hqr 4x4 (4 real)", |b| {
        b.iter(|| real_eigenpairs_hqr(black_box(&m4)))
    });
    c.bench_function("real_eigenpairs_sturm 10x10", |b| {
        b.iter(|| real_eigenpairs_sturm(black_box(&m10)))
    });
    c.bench_function("real_eigenpairs_sturm 20x20", |b| {
        b.iter(|| real_eigenpairs_sturm(black_box(&m20)))
    });
    c.bench_function("real_eigenpairs_hqr 10x10", |b| {
        b.iter(|| real_eigenpairs_hqr(black_box(&m10)))
    });
    c.bench_function("real_eigenpairs_hqr 20x20", |b| {
        b.iter(|| real_eigenpairs_hqr(black_box(&m20)))
    });
    c.bench_function("nalgebra Schur::try_new only 10x10", |b| {
        b.iter(|| nalgebra::Schur::try_new(black_box(m10), f64::EPSILON, 310))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2));
    targets = bench_elimination, bench_eigen
}
criterion_main!(benches);
