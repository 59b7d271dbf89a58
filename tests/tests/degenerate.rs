//! Every emitted solver survives degenerate and hostile input: NaN or ±inf in any slot,
//! all-zero data, huge (1e300) and tiny values, repeated correspondences, rank-deficient
//! data and random garbage. Each call must return (no panic, no hang) with no solutions or
//! only finite ones.

mod common;

use common::{assert_all_emitted_listed, emitted_solvers, problem_file, Emitted};
use mingen::__internal::instance::random_data_f64;
use mingen::__internal::problem::ProblemLayout;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

/// Wall-clock budget for all cases of one solver (a hang shows up as this timeout).
const BUDGET: Duration = Duration::from_secs(120);
/// Random garbage cases per solver.
const GARBAGE: usize = 2000;

fn layout(name: &str) -> ProblemLayout {
    mingen::Problem::from_file(problem_file(name))
        .expect("shipped problem parses")
        .layout
}

/// Copies element 0 of every array symbol into its other elements: all correspondences
/// identical.
fn repeat_first(layout: &ProblemLayout, d: &mut [f64]) {
    for s in &layout.data {
        let per = s.kind.slots();
        for e in 1..s.len.unwrap_or(1) {
            for k in 0..per {
                d[s.first_slot + e * per + k] = d[s.first_slot + k];
            }
        }
    }
}

/// Copies the first symbol of each kind into the later symbols of that kind (E1 = E2 = E3 =
/// E4 for the 5-point problem, x1 = x2, G1 = G2, v1 = v2, w1 = w2).
fn repeat_symbols(layout: &ProblemLayout, d: &mut [f64]) {
    for (i, s) in layout.data.iter().enumerate() {
        if let Some(f) = layout.data[..i]
            .iter()
            .find(|f| f.kind == s.kind && f.len == s.len)
        {
            for k in 0..s.slot_count() {
                d[s.first_slot + k] = d[f.first_slot + k];
            }
        }
    }
}

/// A value of random magnitude 1e-300 .. 1e300 and sign, or a special value.
fn garbage_value(rng: &mut ChaCha8Rng) -> f64 {
    match rng.gen_range(0..20) {
        0 => 0.0,
        1 => f64::NAN,
        2 => f64::INFINITY,
        3 => f64::NEG_INFINITY,
        4 => f64::MIN_POSITIVE / 4.0,
        5 => f64::MAX,
        6 => -0.0,
        7 => 1.0,
        8..=11 => rng.gen_range(-1.0..=1.0),
        _ => {
            let e: f64 = rng.gen_range(-300.0..300.0);
            let s = if rng.gen() { 1.0 } else { -1.0 };
            s * 10f64.powf(e)
        }
    }
}

/// All cases for one solver: (description, data).
fn cases(solver: &Emitted) -> Vec<(String, Vec<f64>)> {
    let layout = layout(solver.name);
    let n = solver.slots;
    assert_eq!(layout.data_slot_count(), n);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut out: Vec<(String, Vec<f64>)> = Vec::new();
    let valid = random_data_f64(&layout, &mut rng);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        out.push((format!("all {bad}"), vec![bad; n]));
        for s in 0..n {
            let mut d = valid.clone();
            d[s] = bad;
            out.push((format!("{bad} in slot {s}"), d));
        }
    }
    out.push(("all zero".into(), vec![0.0; n]));
    out.push(("all -0.0".into(), vec![-0.0; n]));
    out.push(("all one".into(), vec![1.0; n]));
    for big in [
        1e300,
        -1e300,
        f64::MAX,
        1e150,
        1e-300,
        f64::MIN_POSITIVE / 2.0,
    ] {
        out.push((format!("all {big:e}"), vec![big; n]));
        out.push((
            format!("valid scaled by {big:e}"),
            valid.iter().map(|x| x * big).collect(),
        ));
        for s in 0..n {
            let mut d = valid.clone();
            d[s] = big;
            out.push((format!("{big:e} in slot {s}"), d));
        }
    }
    for i in 0..50 {
        let mut d = random_data_f64(&layout, &mut rng);
        repeat_first(&layout, &mut d);
        out.push((format!("repeated correspondences #{i}"), d.clone()));
        repeat_symbols(&layout, &mut d);
        out.push((format!("repeated correspondences and symbols #{i}"), d));
        let mut d = random_data_f64(&layout, &mut rng);
        repeat_symbols(&layout, &mut d);
        out.push((format!("repeated symbols #{i}"), d));
        // Zero a random subset of slots of a valid instance.
        let mut d = random_data_f64(&layout, &mut rng);
        for x in d.iter_mut() {
            if rng.gen_bool(0.3) {
                *x = 0.0;
            }
        }
        out.push((format!("valid with zeros #{i}"), d));
    }
    for i in 0..GARBAGE {
        let d: Vec<f64> = match i % 3 {
            // Everywhere garbage.
            0 => (0..n).map(|_| garbage_value(&mut rng)).collect(),
            // A valid instance with a few garbage slots.
            1 => {
                let mut d = random_data_f64(&layout, &mut rng);
                for _ in 0..rng.gen_range(1..4) {
                    let s = rng.gen_range(0..n);
                    d[s] = garbage_value(&mut rng);
                }
                d
            }
            // Finite, wildly scaled.
            _ => (0..n)
                .map(|_| {
                    let e: f64 = rng.gen_range(-200.0..200.0);
                    rng.gen_range(-1.0..=1.0) * 10f64.powf(e)
                })
                .collect(),
        };
        out.push((format!("garbage #{i}"), d));
    }
    out
}

/// Runs every case of `solver` on a worker thread; returns the failures (panics,
/// non-finite or oversized solutions), or fails the test if the worker does not finish
/// within [`BUDGET`] (naming the case it is stuck on).
fn run_solver(solver: &Emitted) -> (usize, Duration, Vec<String>) {
    let cases = Arc::new(cases(solver));
    let current = Arc::new(AtomicUsize::new(0));
    let failures = Arc::new(Mutex::new(Vec::new()));
    let (tx, rx) = mpsc::channel();
    let (solve, max, name) = (solver.solve, solver.max_solutions, solver.name);
    {
        let (cases, current, failures) = (cases.clone(), current.clone(), failures.clone());
        std::thread::spawn(move || {
            let mut slowest = Duration::ZERO;
            for (i, (what, d)) in cases.iter().enumerate() {
                current.store(i, Ordering::SeqCst);
                let start = Instant::now();
                let r = catch_unwind(AssertUnwindSafe(|| solve(d)));
                slowest = slowest.max(start.elapsed());
                let msg = match r {
                    Err(_) => Some(format!("{name}: {what}: panicked; data {d:?}")),
                    Ok(sols) if sols.len() > max => {
                        Some(format!("{name}: {what}: {} > {max} solutions", sols.len()))
                    }
                    Ok(sols) if sols.iter().flatten().any(|x| !x.is_finite()) => Some(format!(
                        "{name}: {what}: non-finite solution {sols:?}; data {d:?}"
                    )),
                    Ok(_) => None,
                };
                if let Some(m) = msg {
                    failures.lock().expect("not poisoned").push(m);
                }
            }
            let _ = tx.send(slowest);
        });
    }
    match rx.recv_timeout(BUDGET) {
        Ok(slowest) => {
            let f = failures.lock().expect("not poisoned").clone();
            (cases.len(), slowest, f)
        }
        Err(_) => {
            let i = current.load(Ordering::SeqCst);
            let (what, d) = &cases[i];
            panic!("{name}: no return within {BUDGET:?}, stuck on case {i} ({what}); data {d:?}");
        }
    }
}

#[test]
fn emitted_solvers_survive_degenerate_input() {
    assert_all_emitted_listed();
    // Silence the default hook's output for caught panics; they are reported below.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut all = Vec::new();
    for solver in emitted_solvers() {
        let (n, slowest, failures) = run_solver(&solver);
        println!(
            "{}: {n} degenerate cases, {} failures, slowest call {slowest:?}",
            solver.name,
            failures.len()
        );
        all.extend(failures);
    }
    std::panic::set_hook(hook);
    assert!(
        all.is_empty(),
        "{} degenerate-input failures; first ones:\n{}",
        all.len(),
        all.iter().take(5).cloned().collect::<Vec<_>>().join("\n")
    );
}
