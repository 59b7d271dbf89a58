//! The sparse elimination of a shipped large template reproduces the dense LU with partial
//! pivoting (same pivots, same arithmetic on the non-zeros), and small templates keep the
//! dense LU.

use mingen::__internal::instance::random_data_f64;
use mingen::__internal::interpret::fill_template;
use mingen::__internal::template::{TemplateOptions, SPARSE_MIN_PIVOTS};
use mingen::plan_file;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

fn template_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../templates/{name}.mp"))
}

#[test]
fn sparse_plan_matches_the_dense_lu() {
    let plan = plan_file(&template_path("grsrp_gravity"), &TemplateOptions::default()).unwrap();
    let t = &plan.generated.built.template;
    let e = t
        .sparse
        .as_ref()
        .expect("the grsrp_gravity template gets a sparse plan");
    assert!(e.sparse_updates < e.dense_updates);
    let lu = e.as_plan(t);
    let (rows, cols) = t.eliminated_size();
    let (pivots, first) = (t.pivot_columns(), t.first_reduced_row());
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut compared = 0;
    for _ in 0..40 {
        let data = random_data_f64(&plan.problem.layout, &mut rng);
        let (equations, _) = plan.equations(&data);
        let m = fill_template(t, &equations).unwrap();
        let (mut sparse, mut dense) = (m.clone(), m);
        let dense_ok = mingen_runtime::lu_solve_template(&mut dense, rows, cols, pivots, first);
        assert_eq!(
            mingen_runtime::lu_solve_template_sparse(&mut sparse, &lu),
            dense_ok
        );
        if !dense_ok {
            continue;
        }
        compared += 1;
        for r in first..pivots {
            let row = r * cols..(r + 1) * cols;
            let scale = dense[row.clone()]
                .iter()
                .fold(1.0f64, |a, x| a.max(x.abs()));
            for (a, b) in sparse[row.clone()].iter().zip(&dense[row.clone()]) {
                assert!((a - b).abs() <= 1e-12 * scale, "row {r}: {a} vs {b}");
            }
        }
    }
    assert!(compared >= 30);
}

#[test]
fn small_templates_keep_the_dense_lu() {
    let plan = plan_file(&template_path("gs5pt"), &TemplateOptions::default()).unwrap();
    let t = &plan.generated.built.template;
    assert!(t.pivot_columns() < SPARSE_MIN_PIVOTS);
    assert!(t.sparse.is_none());
}
