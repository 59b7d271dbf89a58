//! Per-stage costs of the generated solvers on the instances of `benches/solvers.rs`, and
//! the runtime alternatives on the templates and action matrices they build.
//!
//! `cargo bench -p rspose --bench stages`
//!
//! - `<name>/1 coefficients`, `2 + elimination`, `3 + action matrix`, `4 solve`:
//!   `solve_staged` with an observer that stops after that stage, so the differences are
//!   the stage costs;
//! - `<name>/gauss_jordan` vs `lu_solve_template` on the captured filled templates, and the
//!   Sturm and QR eigen back ends on the captured action matrices (nalgebra's Schur form,
//!   the reference, is timed in `mingen-runtime`'s `benches/runtime.rs`).

#[path = "../tests/planted/mod.rs"]
mod planted;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use mingen_runtime::nalgebra::SMatrix;
use mingen_runtime::{
    gauss_jordan, lu_solve_template, lu_solve_template_sparse, real_eigenpairs_hqr,
    real_eigenpairs_sturm, MinimalSolver, SparseLuPlan, Stages,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rspose::generated::{grsrp, grsrp10, grsrp_gravity, gs5pt};

/// Stops after stage `0` (filled), `1` (eliminated) or `2` (action); any other value
/// never stops.
struct StopAfter(u8);

impl Stages for StopAfter {
    fn filled(&mut self, _: &[f64]) -> bool {
        self.0 != 0
    }
    fn eliminated(&mut self, _: &[f64]) -> bool {
        self.0 != 1
    }
    fn action(&mut self, _: &[f64]) -> bool {
        self.0 != 2
    }
}

/// Keeps copies of the filled template and of the action matrix (column-major).
#[derive(Default)]
struct Capture {
    filled: Vec<f64>,
    action: Vec<f64>,
}

impl Stages for Capture {
    fn filled(&mut self, m: &[f64]) -> bool {
        self.filled = m.to_vec();
        true
    }
    fn action(&mut self, a: &[f64]) -> bool {
        self.action = a.to_vec();
        true
    }
}

/// The stage benchmarks of solver `S` (`NB` = `S::MAX_SOLUTIONS`, the action matrix size).
/// `sparse`: the solver's sparse elimination plan, if it has one (benchmarked beside the
/// dense LU on the same templates).
fn stages<S: MinimalSolver, const NB: usize>(
    c: &mut Criterion,
    pool: &[S::Data],
    sparse: Option<&SparseLuPlan>,
) {
    assert_eq!(NB, S::MAX_SOLUTIONS, "action matrix size of {}", S::NAME);
    let [rows, cols, pivots, first] = S::TEMPLATE_SHAPE;
    let mut templates = Vec::new();
    let mut actions = Vec::new();
    for d in pool {
        let mut cap = Capture::default();
        let _ = S::solve_staged(d, &mut cap);
        if !cap.filled.is_empty() && !cap.action.is_empty() {
            templates.push(cap.filled);
            actions.push(SMatrix::<f64, NB, NB>::from_column_slice(&cap.action));
        }
    }
    assert!(
        !actions.is_empty(),
        "{}: no instance reached the eigen stage",
        S::NAME
    );
    let mut g = c.benchmark_group(S::NAME);
    for (label, stop) in [
        ("1 coefficients", 0),
        ("2 + elimination", 1),
        ("3 + action matrix", 2),
        ("4 solve", 3),
    ] {
        let mut k = 0;
        g.bench_function(label, |b| {
            b.iter(|| {
                k = (k + 1) % pool.len();
                black_box(S::solve_staged(black_box(&pool[k]), &mut StopAfter(stop)))
            })
        });
    }
    let mut buf = vec![0.0; rows * cols];
    let mut k = 0;
    g.bench_function("gauss_jordan", |b| {
        b.iter(|| {
            k = (k + 1) % templates.len();
            buf.copy_from_slice(&templates[k]);
            black_box(gauss_jordan(&mut buf, rows, cols, pivots))
        })
    });
    g.bench_function("lu_solve_template", |b| {
        b.iter(|| {
            k = (k + 1) % templates.len();
            buf.copy_from_slice(&templates[k]);
            black_box(lu_solve_template(&mut buf, rows, cols, pivots, first))
        })
    });
    if let Some(plan) = sparse {
        g.bench_function("lu_solve_template_sparse", |b| {
            b.iter(|| {
                k = (k + 1) % templates.len();
                buf.copy_from_slice(&templates[k]);
                black_box(lu_solve_template_sparse(&mut buf, plan))
            })
        });
    }
    g.bench_function("eigen Sturm", |b| {
        b.iter(|| {
            k = (k + 1) % actions.len();
            black_box(real_eigenpairs_sturm(black_box(&actions[k])))
        })
    });
    g.bench_function("eigen QR", |b| {
        b.iter(|| {
            k = (k + 1) % actions.len();
            black_box(real_eigenpairs_hqr(black_box(&actions[k])))
        })
    });
    g.finish();
}

fn bench_stages(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let g5: Vec<gs5pt::Data> = (0..64)
        .map(|_| planted::gs5pt_instance(&mut rng).data)
        .collect();
    let rs: Vec<planted::Grsrp> = (0..64).map(|_| planted::grsrp_instance(&mut rng)).collect();
    let r10: Vec<grsrp10::Data> = rs.iter().map(|i| i.data10()).collect();
    let r20: Vec<grsrp::Data> = rs.iter().map(|i| i.data20()).collect();
    let gr: Vec<grsrp_gravity::Data> = (0..64)
        .map(|_| planted::gravity_instance(&mut rng).data)
        .collect();
    stages::<gs5pt::Solver, 10>(c, &g5, None);
    stages::<grsrp10::Solver, 10>(c, &r10, None);
    stages::<grsrp_gravity::Solver, 12>(c, &gr, Some(&grsrp_gravity::SPARSE_PLAN));
    stages::<grsrp::Solver, 20>(c, &r20, Some(&grsrp::SPARSE_PLAN));
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_millis(300))
        .measurement_time(std::time::Duration::from_secs(1));
    targets = bench_stages
}
criterion_main!(benches);
