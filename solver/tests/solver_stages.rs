//! Per-stage timings of the generated solvers on the benchmark's instances (noisy shared
//! machines: candidates timed in interleaved rounds, medians of the per-round means).
//! `cargo test --release -p rspose --test solver_stages -- --ignored --nocapture`
//!
//! - cumulative: `solve_staged` with an observer that stops after filling the template
//!   (coefficients), after the elimination, after building the action matrix, and the whole
//!   solve; the differences are the stage costs;
//! - the runtime alternatives on the captured templates and action matrices: Gauss-Jordan
//!   vs LU + partial back substitution, Schur vs Sturm eigen back end.

mod planted;

use nalgebra::SMatrix;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rspose::generated::{grsrp, grsrp10, grsrp_gravity, gs5pt};
use rspose::runtime::{
    gauss_jordan, lu_solve_template, real_eigenpairs, real_eigenpairs_hqr, real_eigenpairs_sturm,
    Stages,
};
use std::hint::black_box;
use std::time::Instant;

/// Stops after stage `stop` (0 filled, 1 eliminated, 2 action; 3 = never) and keeps copies.
struct Probe {
    stop: u8,
    filled: Vec<f64>,
    action: Vec<f64>,
}

impl Stages for Probe {
    fn filled(&mut self, m: &[f64]) -> bool {
        if self.stop == 9 {
            self.filled = m.to_vec();
        }
        self.stop != 0
    }
    fn eliminated(&mut self, _m: &[f64]) -> bool {
        self.stop != 1
    }
    fn action(&mut self, a: &[f64]) -> bool {
        if self.stop == 9 {
            self.action = a.to_vec();
        }
        self.stop != 2
    }
}

fn probe(stop: u8) -> Probe {
    Probe {
        stop,
        filled: Vec::new(),
        action: Vec::new(),
    }
}

/// Median over `rounds` interleaved rounds of the mean ns per call of each candidate
/// (a call = one pass over the instance pool, divided by the pool size).
fn time(rounds: usize, pool: usize, cands: &mut [(&str, &mut dyn FnMut())]) -> Vec<f64> {
    let mut samples = vec![Vec::new(); cands.len()];
    for _ in 0..rounds {
        for (k, (_, f)) in cands.iter_mut().enumerate() {
            let t = Instant::now();
            f();
            samples[k].push(t.elapsed().as_secs_f64() * 1e9 / pool as f64);
        }
    }
    samples
        .iter_mut()
        .map(|s| {
            s.sort_by(f64::total_cmp);
            s[s.len() / 2]
        })
        .collect()
}

macro_rules! stages_of {
    ($name:literal, $module:ident, $pool:expr, $rounds:expr) => {{
        const NB: usize = $module::MAX_SOLUTIONS;
        let [rows, cols, pivots, first] = $module::TEMPLATE_SHAPE;
        let pool = &$pool;
        let n = pool.len();
        // Capture the filled templates and action matrices.
        let mut templates = Vec::new();
        let mut actions = Vec::new();
        for d in pool.iter() {
            let mut p = probe(9);
            let _ = $module::solve_staged(d, &mut p);
            if !p.filled.is_empty() && !p.action.is_empty() {
                templates.push(p.filled);
                actions.push(SMatrix::<f64, NB, NB>::from_column_slice(&p.action));
            }
        }
        let mut buf = vec![0.0; rows * cols];
        let mut buf2 = buf.clone();
        let t = time(
            $rounds,
            n,
            &mut [
                ("coefficients", &mut || {
                    for d in pool.iter() {
                        black_box($module::solve_staged(black_box(d), &mut probe(0)));
                    }
                }),
                ("+ elimination", &mut || {
                    for d in pool.iter() {
                        black_box($module::solve_staged(black_box(d), &mut probe(1)));
                    }
                }),
                ("+ action matrix", &mut || {
                    for d in pool.iter() {
                        black_box($module::solve_staged(black_box(d), &mut probe(2)));
                    }
                }),
                ("solve", &mut || {
                    for d in pool.iter() {
                        black_box($module::solve(black_box(d)));
                    }
                }),
            ],
        );
        println!(
            "{:<14} coefficients {:8.2} µs | elimination {:8.2} µs | action {:6.2} µs | eigen + read-out {:7.2} µs | solve {:8.2} µs",
            $name,
            t[0] / 1e3,
            (t[1] - t[0]) / 1e3,
            (t[2] - t[1]) / 1e3,
            (t[3] - t[2]) / 1e3,
            t[3] / 1e3
        );
        let nt = templates.len();
        let na = actions.len();
        let r = time(
            $rounds,
            1,
            &mut [
                ("gauss_jordan", &mut || {
                    for m in &templates {
                        buf.copy_from_slice(m);
                        black_box(gauss_jordan(&mut buf, rows, cols, pivots));
                    }
                }),
                ("lu_solve_template", &mut || {
                    for m in &templates {
                        buf2.copy_from_slice(m);
                        black_box(lu_solve_template(&mut buf2, rows, cols, pivots, first));
                    }
                }),
                ("real_eigenpairs", &mut || {
                    for a in &actions {
                        black_box(real_eigenpairs(black_box(a)));
                    }
                }),
                ("real_eigenpairs_sturm", &mut || {
                    for a in &actions {
                        black_box(real_eigenpairs_sturm(black_box(a)));
                    }
                }),
                ("real_eigenpairs_hqr", &mut || {
                    for a in &actions {
                        black_box(real_eigenpairs_hqr(black_box(a)));
                    }
                }),
            ],
        );
        println!(
            "{:<14} on captured data ({}x{}, {}x{}): gauss_jordan {:8.2} µs, lu_solve_template {:8.2} µs, Schur eigen {:6.2} µs, Sturm eigen {:6.2} µs, HQR eigen {:6.2} µs",
            "",
            rows,
            cols,
            NB,
            NB,
            r[0] / 1e3 / nt as f64,
            r[1] / 1e3 / nt as f64,
            r[2] / 1e3 / na as f64,
            r[3] / 1e3 / na as f64,
            r[4] / 1e3 / na as f64
        );
    }};
}

#[test]
#[ignore]
fn stage_timings() {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let g5: Vec<gs5pt::Data> = (0..64)
        .map(|_| planted::gs5pt_instance(&mut rng).data)
        .collect();
    let rs: Vec<planted::Grsrp> = (0..64).map(|_| planted::grsrp_instance(&mut rng)).collect();
    let r10: Vec<grsrp10::Data> = rs.iter().map(|i| i.data10()).collect();
    let r20: Vec<grsrp::Data> = rs.iter().take(16).map(|i| i.data20()).collect();
    let gr: Vec<grsrp_gravity::Data> = (0..64)
        .map(|_| planted::gravity_instance(&mut rng).data)
        .collect();
    stages_of!("gs5pt", gs5pt, g5, 301);
    stages_of!("grsrp10", grsrp10, r10, 301);
    stages_of!("grsrp_gravity", grsrp_gravity, gr, 101);
    stages_of!("grsrp", grsrp, r20, 21);
}
