//! Numerical stability of the generated solvers on random instances with a planted real
//! solution: the planted solution must be found (relative error < 1e-6) in at least 99.5 %
//! of the instances, and the median log10 error must meet the stability targets (median below −11 for the 10-solution solvers, −9 for `grsrp`).
//! `cargo test --release -p rspose --test generated_accuracy -- --nocapture`

mod planted;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rspose::generated::{grsrp, grsrp10, grsrp_gravity, gs5pt};

const FOUND: f64 = 1e-6;

/// Prints and checks the statistics of `errors` (one per instance).
fn check(name: &str, errors: &[f64], median_target: f64, min_found: f64) {
    let n = errors.len();
    let found = errors.iter().filter(|&&e| e < FOUND).count();
    let mut logs: Vec<f64> = errors
        .iter()
        .map(|e| e.max(1e-18).log10().min(10.0))
        .collect();
    logs.sort_by(f64::total_cmp);
    let median = logs[n / 2];
    let p95 = logs[n * 95 / 100];
    let rate = found as f64 / n as f64;
    println!(
        "{name:<14} n = {n:5}  found {:6.2} %  median log10 err {median:6.2}  95th pct {p95:6.2}",
        100.0 * rate
    );
    assert!(
        rate >= min_found,
        "{name}: planted solution found in {found} of {n}"
    );
    assert!(
        median < median_target,
        "{name}: median log10 error {median}"
    );
}

#[test]
fn gs5pt_finds_planted_solution() {
    let mut rng = ChaCha8Rng::seed_from_u64(501);
    let errors: Vec<f64> = (0..2000)
        .map(|_| {
            let inst = planted::gs5pt_instance(&mut rng);
            planted::gs5pt_error(&inst, &gs5pt::solve(&inst.data))
        })
        .collect();
    check("gs5pt", &errors, -11.0, 0.995);
}

#[test]
fn grsrp10_finds_planted_solution() {
    let mut rng = ChaCha8Rng::seed_from_u64(502);
    let errors: Vec<f64> = (0..2000)
        .map(|_| {
            let inst = planted::grsrp_instance(&mut rng);
            let sols = grsrp10::solve(&inst.data10());
            inst.error(sols.iter().map(|s| (s.a, s.t)))
        })
        .collect();
    check("grsrp10", &errors, -11.0, 0.995);
}

#[test]
fn grsrp_finds_planted_solution() {
    let mut rng = ChaCha8Rng::seed_from_u64(503);
    let errors: Vec<f64> = (0..300)
        .map(|_| {
            let inst = planted::grsrp_instance(&mut rng);
            let sols = grsrp::solve(&inst.data20());
            inst.error(sols.iter().map(|s| (s.a, s.t)))
        })
        .collect();
    check("grsrp", &errors, -9.0, 0.99);
}

#[test]
fn grsrp_gravity_finds_planted_solution() {
    let mut rng = ChaCha8Rng::seed_from_u64(504);
    let errors: Vec<f64> = (0..1000)
        .map(|_| {
            let inst = planted::gravity_instance(&mut rng);
            inst.error(&grsrp_gravity::solve(&inst.data))
        })
        .collect();
    check("grsrp_gravity", &errors, -9.0, 0.99);
}
