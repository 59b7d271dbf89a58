//! Driver of `tools/emitted_solver/run.sh`: runs an emitted solver (`src/solver.rs`, any
//! problem) on instances from a file and prints its per-call time, its solution count and,
//! given planted solutions, how many it recovers.
//!
//! Usage: `driver INSTANCES [SOLUTIONS] [SIGN_FREE]`. INSTANCES has one instance per line
//! (the problem's data slots, whitespace-separated), or is `random:N` for N instances with
//! every slot uniform in [-1, 1] (seeded); SOLUTIONS one planted solution per
//! line (every unknown in declaration order). SIGN_FREE lists comma-separated unknown
//! indices whose joint sign is free (an eliminated homogeneous unknown such as a unit
//! translation): the planted solution counts as recovered with those entries negated too.

mod solver;

use mingen_runtime::{FlatValues, MinimalSolver};
use std::hint::black_box;
use std::process::ExitCode;
use std::time::Instant;

/// A planted solution is recovered when the nearest returned solution is this close,
/// relative to the planted solution's largest entry.
const RECOVERY_TOLERANCE: f64 = 1e-6;

fn read_rows(path: &str, width: usize) -> Result<Vec<Vec<f64>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let row = line
            .split_whitespace()
            .map(str::parse::<f64>)
            .collect::<Result<Vec<f64>, _>>()
            .map_err(|e| format!("{path}:{}: {e}", i + 1))?;
        if row.len() != width {
            return Err(format!(
                "{path}:{}: {} numbers, the problem has {width}",
                i + 1,
                row.len()
            ));
        }
        rows.push(row);
    }
    Ok(rows)
}

/// `count` instances of `width` slots uniform in [-1, 1] (xorshift64*, fixed seed).
fn random_rows(count: usize, width: usize) -> Vec<Vec<f64>> {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        let bits = state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..count).map(|_| (0..width).map(|_| next()).collect()).collect()
}

fn run() -> Result<(), String> {
    type S = solver::Solver;
    let args: Vec<String> = std::env::args().collect();
    let instances = args.get(1).ok_or("usage: driver INSTANCES [SOLUTIONS] [SIGN_FREE]")?;
    let width = <S as MinimalSolver>::Data::LEN;
    let rows = match instances.strip_prefix("random:") {
        Some(n) => random_rows(n.parse().map_err(|e| format!("{instances}: {e}"))?, width),
        None => read_rows(instances, width)?,
    };
    let data: Vec<<S as MinimalSolver>::Data> = rows
        .iter()
        .filter_map(|r| <S as MinimalSolver>::Data::from_flat(r))
        .collect();
    if data.is_empty() {
        return Err(format!("{instances}: no instances"));
    }
    // Per-call time: the median of rounds over all instances.
    let rounds = (2000 / data.len()).clamp(3, 25);
    let mut times = Vec::new();
    let mut solutions = 0usize;
    for _ in 0..rounds {
        let t = Instant::now();
        solutions = 0;
        for d in &data {
            solutions += black_box(S::solve(black_box(d))).as_ref().len();
        }
        times.push(t.elapsed().as_secs_f64() * 1e6 / data.len() as f64);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{} instances x {rounds} rounds: {:.3} us per call (median round; fastest {:.3}), {:.2} real solutions per instance",
        data.len(),
        times[times.len() / 2],
        times[0],
        solutions as f64 / data.len() as f64
    );
    let Some(planted) = args.get(2) else {
        return Ok(());
    };
    let truths = read_rows(planted, <S as MinimalSolver>::Solution::LEN)?;
    if truths.len() != data.len() {
        return Err(format!(
            "{planted}: {} solutions for {} instances",
            truths.len(),
            data.len()
        ));
    }
    let sign_free: Vec<usize> = match args.get(3) {
        Some(s) => s
            .split(',')
            .map(|x| x.trim().parse::<usize>().map_err(|e| format!("SIGN_FREE `{x}`: {e}")))
            .collect::<Result<_, _>>()?,
        None => Vec::new(),
    };
    let mut errors = Vec::new();
    let mut missed = Vec::new();
    for (k, (d, truth)) in data.iter().zip(&truths).enumerate() {
        let mut flipped = truth.clone();
        for &i in &sign_free {
            if let Some(x) = flipped.get_mut(i) {
                *x = -*x;
            }
        }
        let scale = truth.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        let mut best = f64::INFINITY;
        for s in S::solve(d).as_ref() {
            let s = s.to_flat_vec();
            for t in [truth, &flipped] {
                let e = s.iter().zip(t).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
                best = best.min(e / scale);
            }
        }
        if best > RECOVERY_TOLERANCE {
            missed.push((k, best));
        }
        errors.push(best);
    }
    let recovered = errors.iter().filter(|&&e| e <= RECOVERY_TOLERANCE).count();
    errors.sort_by(f64::total_cmp);
    let log = |e: f64| e.max(1e-17).log10();
    println!(
        "planted solution recovered (to {RECOVERY_TOLERANCE:e}): {recovered} of {}; error log10 median {:.2}, p99 {:.2}",
        errors.len(),
        log(errors[errors.len() / 2]),
        log(errors[(errors.len() * 99 / 100).min(errors.len() - 1)])
    );
    if !missed.is_empty() {
        let shown: Vec<String> = missed
            .iter()
            .take(5)
            .map(|(k, e)| format!("line {} ({e:.1e})", k + 1))
            .collect();
        println!("not recovered: {}", shown.join(", "));
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
