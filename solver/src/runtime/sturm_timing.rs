//! Timings of the Sturm back end's steps (ignored tests).
//!
//! `cargo test --release -p rspose --lib piece_timing -- --ignored --nocapture`: the
//! cost of each step on the action matrices of the 10-solution generated solvers.

use super::*;
use crate::generated::gs5pt;
use crate::runtime::hessenberg::hessenberg;
use crate::runtime::Stages;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;

struct Capture(Vec<f64>);
impl Stages for Capture {
    fn action(&mut self, a: &[f64]) -> bool {
        self.0 = a.to_vec();
        false
    }
}

fn gs5pt_actions(n: usize) -> Vec<[[f64; 10]; 10]> {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut out = Vec::new();
    while out.len() < n {
        let mut slots = [0.0; 36];
        for x in slots.iter_mut() {
            *x = rng.gen_range(-1.0..1.0);
        }
        let mut c = Capture(Vec::new());
        let _ = gs5pt::solve_staged(&gs5pt::Data::from_slots(&slots), &mut c);
        if c.0.len() == 100 {
            let mut a = [[0.0; 10]; 10];
            for (j, col) in c.0.chunks(10).enumerate() {
                for (i, x) in col.iter().enumerate() {
                    a[i][j] = *x;
                }
            }
            out.push(a);
        }
    }
    out
}

#[repr(C)]
struct Timespec {
    sec: i64,
    nsec: i64,
}
extern "C" {
    fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
}

/// Time on the CPU of this thread (ns; Linux `CLOCK_THREAD_CPUTIME_ID`), so that other
/// processes on the shared machine do not count.
fn cpu_ns() -> u64 {
    let mut ts = Timespec { sec: 0, nsec: 0 };
    // SAFETY: a valid pointer to a timespec-layout struct; clock id 3 is
    // CLOCK_THREAD_CPUTIME_ID on Linux.
    unsafe { clock_gettime(3, &mut ts) };
    ts.sec as u64 * 1_000_000_000 + ts.nsec as u64
}

struct Instant(u64);
impl Instant {
    fn now() -> Self {
        Instant(cpu_ns())
    }
}

fn ns(t: Instant, n: usize) -> f64 {
    (cpu_ns() - t.0) as f64 / n as f64
}

/// Only the whole back end, many times: for `perf stat -e cycles:u` comparisons.
#[test]
#[ignore]
fn whole_only() {
    let mats: Vec<_> = gs5pt_actions(500)
        .iter()
        .map(|a| SMatrix::<f64, 10, 10>::from_fn(|i, j| a[i][j]))
        .collect();
    for _ in 0..200 {
        for m in &mats {
            black_box(real_eigenpairs_sturm(black_box(m)));
        }
    }
}

#[test]
#[ignore]
fn pieces() {
    let mats = gs5pt_actions(500);
    let n = mats.len();
    let prepared: Vec<_> = mats
        .iter()
        .map(|a| {
            let mut a = *a;
            balance(&mut a);
            let s = a
                .iter()
                .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
                .fold(0.0, f64::max);
            for r in a.iter_mut() {
                for x in r.iter_mut() {
                    *x /= s;
                }
            }
            a
        })
        .collect();
    let mut best = [f64::INFINITY; 7];
    let mut nr = 0;
    for _ in 0..15 {
        let t = Instant::now();
        for a in &mats {
            let mut a = *black_box(a);
            black_box(balance(&mut a));
        }
        let tb = ns(t, n);
        let t = Instant::now();
        for a in &prepared {
            let mut a = *black_box(a);
            black_box(hessenberg(&mut a));
            black_box(a);
        }
        let th = ns(t, n);
        let hs: Vec<_> = prepared
            .iter()
            .map(|a| {
                let mut a = *a;
                hessenberg(&mut a);
                a
            })
            .collect();
        let t = Instant::now();
        for h in &hs {
            black_box(char_poly(black_box(h)));
        }
        let tc = ns(t, n);
        let ps: Vec<_> = hs.iter().map(|h| char_poly(h).unwrap()).collect();
        let t = Instant::now();
        for p in &ps {
            black_box(Sturm::new(black_box(p)));
        }
        let ts = ns(t, n);
        let sturms: Vec<_> = ps.iter().map(Sturm::new).collect();
        let t = Instant::now();
        nr = 0;
        let mut all_roots = Vec::new();
        for (p, s) in ps.iter().zip(&sturms) {
            let Some(s) = s else { continue };
            let mut roots = [0.0; 10];
            let k = s.real_roots(black_box(p), &mut roots);
            nr += k;
            all_roots.push(roots[..k].to_vec());
        }
        let tr = ns(t, nr.max(1));
        let t = Instant::now();
        for (h, roots) in hs.iter().zip(&all_roots) {
            for &mu in roots {
                black_box(inverse_iteration(black_box(h), mu));
            }
        }
        let ti = ns(t, nr.max(1));
        let t = Instant::now();
        for a in &mats {
            black_box(real_eigenpairs_sturm(&SMatrix::<f64, 10, 10>::from_fn(
                |i, j| a[i][j],
            )));
        }
        let tw = ns(t, n);
        for (b, t) in best.iter_mut().zip([tb, th, tc, ts, tr, ti, tw]) {
            *b = b.min(t);
        }
    }
    let [tb, th, tc, ts, tr, ti, tw] = best;
    let fallbacks = mats
        .iter()
        .filter(|a| {
            let m = SMatrix::<f64, 10, 10>::from_fn(|i, j| a[i][j]);
            let mut out = SolutionSet::filled_with((0.0, SVector::zeros()));
            sturm_eigenpairs(&m, &mut out).is_none()
        })
        .count();
    println!("QR fallbacks: {fallbacks} of {n}");
    let (mut fast, mut total) = (0, 0);
    for a in &prepared {
        let mut h = *a;
        hessenberg(&mut h);
        let p = char_poly(&h).unwrap();
        let Some(st) = Sturm::new(&p) else { continue };
        let mut roots = [0.0; 10];
        let k = st.real_roots(&p, &mut roots);
        let inv = subdiagonal_reciprocals(&h);
        for &mu in &roots[..k] {
            total += 1;
            if inv
                .as_ref()
                .and_then(|r| eigenvector_by_recurrence(&h, r, mu))
                .is_some_and(|(_, res)| res <= FAST_RESIDUAL)
            {
                fast += 1;
            }
        }
    }
    println!("eigenvectors by recurrence: {fast} of {total}");
    println!(
        "gs5pt action matrices ({:.2} real roots), min of 15 rounds: balance {tb:.0} ns, hessenberg {th:.0}, charpoly {tc:.0}, sturm new {ts:.0}, roots {tr:.0} per root, inverse iteration {ti:.0} per root; whole {tw:.0}",
        nr as f64 / n as f64
    );
}
