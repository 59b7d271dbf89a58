//! The emitted solvers (`rspose::generated::*`) agree with the interpreted solver
//! (`mingen::interpret`) on the same template: on [`INSTANCES`] random f64 instances per
//! problem (`mingen::instance::random_data_f64`, fixed seed) both return the same real
//! solutions, as sets, to [`REL_TOL`] (relative to `max(1, max_i |x_i|)` of the solution).
//!
//! Eliminated unknowns (`eliminate t`) are a null vector whose sign is arbitrary in both
//! solvers, so that block is compared up to sign.
//!
//! Each instance falls in one class:
//! - *agree*: same number of real solutions, all matched to [`REL_TOL`];
//! - *count differs*: the smaller set is matched to [`REL_TOL`], the other has extra
//!   solutions. The solvers decide "real" differently (the emitted one on the 2x2 blocks of
//!   the real Schur form, `mingen_runtime::NEAR_REAL_TOL`; the interpreter on the
//!   imaginary parts of the solution, `mingen::interpret::REAL_TOL`) and a near-double root
//!   may split or merge by rounding. Allowed on at most [`MAX_COUNT_DIFFERS`] of instances;
//! - *emitted found none*: the emitted solver returns nothing while the interpreter finds
//!   real solutions with residual below 1e-6. That is a failure of the emitted solver;
//!   allowed on at most [`MAX_EMITTED_NONE`] of instances (DESIGN §7's failure budget);
//! - *values differ*: some solution is not matched to [`REL_TOL`]. On an ill-conditioned
//!   instance the two elimination orders (the interpreter scales rows, the emitted code does
//!   not) round differently. Allowed on a per-problem fraction (`max_value_differs`) if the
//!   emitted solutions are about as accurate as the interpreted ones (worst normalised
//!   residual on the original equations at most 100 times the interpreter's, or below
//!   1e-10, or below the audit's failure threshold [`GOOD_RESIDUAL`] — both then solve the
//!   instance as well as DESIGN §7 asks); otherwise the instance is an *emitted worse*
//!   failure.

mod common;

use common::{assert_all_emitted_listed, emitted, problem_file, Emitted};
use mingen::algebra::Poly;
use mingen::generate::plan_file;
use mingen::instance::random_data_f64;
use mingen::interpret::{normalized_residual, recover_eliminated, solve_template_real};
use mingen::pipeline::SolverPlan;
use mingen::template::TemplateOptions;
use nalgebra::Complex;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Number of random instances per problem.
const INSTANCES: usize = 1000;
/// Agreement tolerance, relative to `max(1, max_i |x_i|)` of the interpreted solution.
const REL_TOL: f64 = 1e-9;
/// Largest allowed fraction of instances where the real-solution counts differ.
const MAX_COUNT_DIFFERS: f64 = 0.01;
/// Largest allowed fraction of instances where the emitted solver finds no solution but the
/// interpreter does.
const MAX_EMITTED_NONE: f64 = 0.005;
/// A solution with a worst normalised residual below this is a genuine solution.
const GOOD_RESIDUAL: f64 = 1e-6;

/// The interpreted real solutions of one instance, eliminated unknowns recovered and merged
/// back into the problem's flat unknown order.
fn interpreted(plan: &SolverPlan, data: &[f64]) -> Vec<Vec<f64>> {
    let n = plan.problem.layout.unknown_count();
    let (equations, elimination) = plan.equations::<f64>(data);
    let sols = solve_template_real(&plan.generated.built.template, &equations);
    let Some(el) = elimination else {
        return sols;
    };
    sols.into_iter()
        .filter_map(|s| {
            let z: Vec<Complex<f64>> = s.iter().map(|&x| Complex::new(x, 0.0)).collect();
            let e = recover_eliminated(&el.coefficient_matrix, &z)?;
            let mut full = vec![f64::NAN; n];
            for (k, &i) in el.remaining.iter().enumerate() {
                full[i] = s[k];
            }
            for (j, &i) in el.eliminated.iter().enumerate() {
                full[i] = e[j].re;
            }
            Some(full)
        })
        .collect()
}

/// Relative distance of an emitted solution `a` from an interpreted one `b`; the entries at
/// `eliminated` are compared up to a common sign.
fn distance(a: &[f64], b: &[f64], eliminated: &[usize]) -> f64 {
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let mut plain = 0.0f64;
    let (mut same, mut flipped) = (0.0f64, 0.0f64);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        if eliminated.contains(&i) {
            same = same.max((x - y).abs());
            flipped = flipped.max((x + y).abs());
        } else {
            plain = plain.max((x - y).abs());
        }
    }
    let d = plain.max(same.min(flipped)) / scale;
    if d.is_nan() {
        f64::INFINITY
    } else {
        d
    }
}

/// Greedy matching by increasing distance: the matched distances (one per pair, at most
/// `min(|a|, |b|)`), pairs further apart than `cutoff` left unmatched.
fn match_sets(a: &[Vec<f64>], b: &[Vec<f64>], eliminated: &[usize], cutoff: f64) -> Vec<f64> {
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            let d = distance(x, y, eliminated);
            if d <= cutoff {
                pairs.push((d, i, j));
            }
        }
    }
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    let (mut used_a, mut used_b) = (vec![false; a.len()], vec![false; b.len()]);
    let mut out = Vec::new();
    for (d, i, j) in pairs {
        if !used_a[i] && !used_b[j] {
            used_a[i] = true;
            used_b[j] = true;
            out.push(d);
        }
    }
    out
}

/// Worst normalised residual of real solutions on the original equations.
fn worst_residual(original: &[Poly<f64>], sols: &[Vec<f64>]) -> f64 {
    let mut worst = 0.0f64;
    for s in sols {
        let z: Vec<Complex<f64>> = s.iter().map(|&x| Complex::new(x, 0.0)).collect();
        for e in original {
            let r = normalized_residual(e, &z);
            worst = if r.is_nan() {
                f64::INFINITY
            } else {
                worst.max(r)
            };
        }
    }
    worst
}

#[derive(Default, Debug)]
struct Tally {
    instances: usize,
    agree: usize,
    count_differs: usize,
    value_differs: usize,
    emitted_none: Vec<String>,
    emitted_worse: Vec<String>,
    emitted_solutions: usize,
    interpreted_solutions: usize,
    worst_agreeing: f64,
}

fn describe(k: usize, a: &[Vec<f64>], b: &[Vec<f64>], data: &[f64]) -> String {
    format!(
        "instance {k}: emitted {} solutions {a:?}\n  interpreted {} solutions {b:?}\n  data {data:?}",
        a.len(),
        b.len()
    )
}

fn run(name: &str, seed: u64) -> Tally {
    let solver: Emitted = emitted(name);
    let plan = plan_file(&problem_file(name), &TemplateOptions::default())
        .unwrap_or_else(|e| panic!("planning {name}: {e}"));
    let layout = &plan.problem.layout;
    assert_eq!(
        layout.data_slot_count(),
        solver.slots,
        "{name}: Data::SLOTS"
    );
    assert_eq!(
        layout.unknown_count(),
        solver.unknowns,
        "{name}: Solution::UNKNOWNS"
    );
    let eliminated = layout.eliminate.clone();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut t = Tally::default();
    for k in 0..INSTANCES {
        let data = random_data_f64(layout, &mut rng);
        assert_eq!(
            (solver.round_trip)(&data),
            data,
            "{name}: from_slots/to_slots"
        );
        let a = (solver.solve)(&data);
        let b = interpreted(&plan, &data);
        t.instances += 1;
        t.emitted_solutions += a.len();
        t.interpreted_solutions += b.len();
        let matched = match_sets(&a, &b, &eliminated, REL_TOL);
        let smaller = a.len().min(b.len());
        let emitted_none = a.is_empty() && !b.is_empty();
        if matched.len() == smaller && !emitted_none {
            if a.len() == b.len() {
                t.agree += 1;
                let worst = matched.iter().fold(0.0f64, |m, &d| m.max(d));
                t.worst_agreeing = t.worst_agreeing.max(worst);
            } else {
                t.count_differs += 1;
                if std::env::var("AGREEMENT_DEBUG").is_ok() {
                    let original = plan.problem.evaluate::<f64>(&data);
                    eprintln!(
                        "{} residuals emitted {:e} interpreted {:e}",
                        describe(k, &a, &b, &data),
                        worst_residual(&original, &a),
                        worst_residual(&original, &b)
                    );
                }
            }
            continue;
        }
        let original = plan.problem.evaluate::<f64>(&data);
        let (ra, rb) = (worst_residual(&original, &a), worst_residual(&original, &b));
        if a.is_empty() {
            if rb < GOOD_RESIDUAL {
                t.emitted_none.push(describe(k, &a, &b, &data));
            } else {
                t.count_differs += 1;
            }
        } else if ra <= (100.0 * rb).max(1e-10) || ra < GOOD_RESIDUAL {
            t.value_differs += 1;
        } else {
            t.emitted_worse.push(format!(
                "{} (worst residual emitted {ra:.2e}, interpreted {rb:.2e})",
                describe(k, &a, &b, &data)
            ));
        }
    }
    t
}

fn check(name: &str, seed: u64, max_value_differs: f64) {
    let t = run(name, seed);
    let n = t.instances as f64;
    let pct = |x: usize| 100.0 * x as f64 / n;
    println!(
        "{name}: {} instances (seed {seed}): agree to {REL_TOL:e} {} ({:.1} %), count differs {} \
         ({:.1} %), values differ (ill-conditioned, equally accurate) {} ({:.1} %), emitted \
         found none {} ({:.1} %), emitted less accurate {} ({:.1} %); mean real solutions \
         emitted {:.3} / interpreted {:.3}; worst distance among agreeing {:.1e}",
        t.instances,
        t.agree,
        pct(t.agree),
        t.count_differs,
        pct(t.count_differs),
        t.value_differs,
        pct(t.value_differs),
        t.emitted_none.len(),
        pct(t.emitted_none.len()),
        t.emitted_worse.len(),
        pct(t.emitted_worse.len()),
        t.emitted_solutions as f64 / n,
        t.interpreted_solutions as f64 / n,
        t.worst_agreeing,
    );
    for msg in t.emitted_none.iter().chain(&t.emitted_worse).take(2) {
        println!("{name}: {msg}");
    }
    assert!(
        t.emitted_worse.is_empty(),
        "{name}: the emitted solver is less accurate than the interpreter on {} instances; first: {}",
        t.emitted_worse.len(),
        t.emitted_worse[0]
    );
    assert!(
        t.emitted_none.len() as f64 <= MAX_EMITTED_NONE * n,
        "{name}: the emitted solver finds no solution while the interpreter finds real ones on \
         {} of {} instances; first: {}",
        t.emitted_none.len(),
        t.instances,
        t.emitted_none[0]
    );
    assert!(
        t.count_differs as f64 <= MAX_COUNT_DIFFERS * n,
        "{name}: the real-solution counts differ on {} of {} instances",
        t.count_differs,
        t.instances
    );
    assert!(
        t.value_differs as f64 <= max_value_differs * n,
        "{name}: solutions differ beyond {REL_TOL:e} on {} of {} instances",
        t.value_differs,
        t.instances
    );
}

#[test]
fn every_shipped_problem_is_checked() {
    assert_all_emitted_listed();
    let checked = [
        "grsrp",
        "grsrp10",
        "grsrp_gravity",
        "grsrp_gravity6",
        "gs5pt",
    ];
    for p in common::shipped_problems() {
        assert!(
            checked.contains(&p.as_str()),
            "add an agreement test for `{p}` in tests/tests/agreement.rs"
        );
    }
}

#[test]
fn agreement_gs5pt() {
    check("gs5pt", 1, 0.01);
}

#[test]
fn agreement_grsrp10() {
    check("grsrp10", 2, 0.01);
}

#[test]
fn agreement_grsrp_gravity() {
    // A 90 x 102 template with a 12 x 12 action matrix whose spectrum is symmetric under
    // ±t: less well conditioned than the 10 x 20 ones (about 1.6 % of instances agree to
    // 1e-8 rather than 1e-9, with equally small residuals).
    check("grsrp_gravity", 3, 0.03);
}

#[test]
fn agreement_grsrp_gravity6() {
    check("grsrp_gravity6", 5, 0.01);
}

#[test]
fn agreement_grsrp() {
    // grsrp's 80 x 100 template (20 x 20 action matrix) is the least stable (DESIGN §7 asks a median log10
    // error below -9 only), so agreement to 1e-9 fails on more ill-conditioned instances.
    check("grsrp", 4, 0.15);
}

/// Instance `k` (0-based) of the random sequence with `seed`, and the problem's original
/// equations on it.
fn nth_instance(name: &str, seed: u64, k: usize) -> (Vec<f64>, Vec<Poly<f64>>) {
    let problem = mingen::Problem::from_file(problem_file(name)).expect("problem parses");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut data = Vec::new();
    for _ in 0..=k {
        data = random_data_f64(&problem.layout, &mut rng);
    }
    let original = problem.evaluate::<f64>(&data);
    (data, original)
}

/// Reproducer (agreement_grsrp_gravity, instance 10 of seed 3): the interpreter finds 4 real
/// solutions with residuals ~1e-10; the emitted solver returns none because
/// `mingen_runtime::real_eigenpairs` gives up when `Schur::try_new` does not converge
/// within its cap of `30 N + 10` iterations.
#[test]
fn reproducer_grsrp_gravity_finds_the_real_solutions() {
    let (data, original) = nth_instance("grsrp_gravity", 3, 10);
    let sols = (emitted("grsrp_gravity").solve)(&data);
    assert!(
        !sols.is_empty(),
        "grsrp_gravity returns no solution; the interpreter finds 4 real ones; data {data:?}"
    );
    let r = worst_residual(&original, &sols);
    assert!(r < GOOD_RESIDUAL, "worst residual {r:e}");
}

/// Reproducer (agreement_grsrp, instance 955 of seed 4): the action matrix has entries up to
/// 5.5e5, so `NEAR_REAL_TOL * max|m_ij|` = 5.5e-3 accepts the complex eigenvalue pairs
/// `t2 = ±1.0938 ± 4.5e-3 i` and `±0.6026 ± 1.1e-3 i` (solutions with `Im a1` = 0.43 and
/// 0.33) as real double eigenvalues: 4 spurious solutions with residual 0.67.
#[test]
fn reproducer_grsrp_returns_no_spurious_solutions() {
    let (data, original) = nth_instance("grsrp", 4, 955);
    let sols = (emitted("grsrp").solve)(&data);
    for s in &sols {
        let r = worst_residual(&original, std::slice::from_ref(s));
        assert!(
            r < GOOD_RESIDUAL,
            "grsrp returns {s:?} with residual {r:.2e} ({} solutions; the interpreter finds 8 \
             real ones); data {data:?}",
            sols.len()
        );
    }
}
