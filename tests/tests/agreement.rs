//! The emitted solvers (`rspose::generated::*`) agree with the interpreted solver
//! (`mingen::__internal::interpret`) on the same template: on [`INSTANCES`] random f64 instances per
//! problem (`mingen::__internal::instance::random_data_f64`, fixed seed) both return the same real
//! solutions, as sets, to [`REL_TOL`] (relative to `max(1, max_i |x_i|)` of the solution),
//! on at least [`MIN_AGREEMENT`] of the instances.
//!
//! Both run the same `mingen-runtime` code (elimination, eigen back end, read-out,
//! recovery of eliminated unknowns) on matrices of the same size; they differ only in how
//! the template's coefficients are evaluated (shared intermediates in the emitted code,
//! `Poly<f64>` in the interpreter), so they agree to rounding. An instance *agrees* if
//! both return the same number of real solutions and every one is matched to [`REL_TOL`];
//! otherwise it is listed (a near-double root may split or merge by rounding).
//!
//! Eliminated unknowns (`eliminate t`) are a null vector whose sign is arbitrary in both
//! solvers, so that block is compared up to sign.

mod common;

use common::{assert_all_emitted_listed, emitted, problem_file, Emitted};
use mingen::__internal::algebra::Poly;
use mingen::__internal::instance::random_data_f64;
use mingen::__internal::interpret::{normalized_residual, recover_eliminated, solve_template_real};
use mingen::__internal::symmetry::unfold_all;
use mingen::plan_file;
use mingen::SolverPlan;
use mingen::TemplateOptions;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Number of random instances per problem.
const INSTANCES: usize = 2000;
/// Agreement tolerance, relative to `max(1, max_i |x_i|)` of the interpreted solution.
const REL_TOL: f64 = 1e-10;
/// Smallest fraction of instances on which the two solvers must agree.
const MIN_AGREEMENT: f64 = 0.999;
/// A solution with a worst normalised residual below this is a genuine solution.
const GOOD_RESIDUAL: f64 = 1e-6;

/// The interpreted real solutions of one instance, eliminated unknowns recovered and merged
/// back into the problem's flat unknown order.
fn interpreted(plan: &SolverPlan, data: &[f64]) -> Vec<Vec<f64>> {
    let n = plan.problem.layout.unknown_count();
    let (equations, elimination) = plan.equations::<f64>(data);
    let folds = plan.problem.sign_folds();
    let sols: Vec<Vec<f64>> = solve_template_real(&plan.generated.built.template, &equations)
        .iter()
        .flat_map(|s| unfold_all(folds, s))
        .collect();
    let Some(el) = elimination else {
        return sols;
    };
    sols.into_iter()
        .filter_map(|s| {
            let e = recover_eliminated(&el.coefficient_matrix, &s, el.inhomogeneous)?;
            let mut full = vec![f64::NAN; n];
            for (k, &i) in el.remaining.iter().enumerate() {
                full[i] = s[k];
            }
            for (j, &i) in el.eliminated.iter().enumerate() {
                full[i] = e[j];
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
        for e in original {
            let r = normalized_residual(e, s);
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
    disagree: Vec<String>,
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
        if a.len() == b.len() && matched.len() == a.len() {
            t.agree += 1;
            let worst = matched.iter().fold(0.0f64, |m, &d| m.max(d));
            t.worst_agreeing = t.worst_agreeing.max(worst);
        } else {
            let original = plan.problem.evaluate::<f64>(&data);
            t.disagree.push(format!(
                "{} (worst residual emitted {:.2e}, interpreted {:.2e})",
                describe(k, &a, &b, &data),
                worst_residual(&original, &a),
                worst_residual(&original, &b)
            ));
        }
    }
    t
}

fn check(name: &str, seed: u64) {
    let t = run(name, seed);
    let n = t.instances as f64;
    println!(
        "{name}: {} instances (seed {seed}): agree to {REL_TOL:e} on {} ({:.2} %), differ on {}; \
         mean real solutions emitted {:.3} / interpreted {:.3}; worst distance among agreeing \
         {:.1e}",
        t.instances,
        t.agree,
        100.0 * t.agree as f64 / n,
        t.disagree.len(),
        t.emitted_solutions as f64 / n,
        t.interpreted_solutions as f64 / n,
        t.worst_agreeing,
    );
    for msg in t.disagree.iter().take(2) {
        println!("{name}: {msg}");
    }
    assert!(
        t.agree as f64 >= MIN_AGREEMENT * n,
        "{name}: the emitted and interpreted solvers differ beyond {REL_TOL:e} on {} of {} \
         instances; first: {}",
        t.disagree.len(),
        t.instances,
        t.disagree[0]
    );
    assert!(t.worst_agreeing <= REL_TOL);
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
    check("gs5pt", 1);
}

#[test]
fn agreement_grsrp10() {
    check("grsrp10", 2);
}

#[test]
fn agreement_grsrp_gravity() {
    check("grsrp_gravity", 3);
}

#[test]
fn agreement_grsrp_gravity6() {
    check("grsrp_gravity6", 5);
}

#[test]
fn agreement_grsrp() {
    check("grsrp", 4);
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
