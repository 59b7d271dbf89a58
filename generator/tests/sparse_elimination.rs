//! The sparse elimination of a shipped large template reproduces the dense LU with partial
//! pivoting (same pivots, same arithmetic on the non-zeros), and small templates are
//! written out as straight-line code along their own order (whose numbers
//! `tests/tests/unrolled_elimination.rs` of the workspace compares with the dense LU's).

use mingen::__internal::instance::random_data_f64;
use mingen::__internal::interpret::fill_template;
use mingen::__internal::template::{TemplateOptions, SPARSE_MIN_PIVOTS, UNROLLED_MAX_UPDATES};
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
fn small_templates_are_written_out_along_their_own_order() {
    for name in ["gs5pt", "classic/p3p", "classic/gp3p", "classic/up2p_elim"] {
        let plan = plan_file(&template_path(name), &TemplateOptions::default()).unwrap();
        let t = &plan.generated.built.template;
        assert!(t.pivot_columns() < SPARSE_MIN_PIVOTS, "{name}");
        assert!(t.sparse.is_none(), "{name}");
        let e = t
            .unrolled
            .as_ref()
            .expect("a small template is written out");
        assert!(
            e.sparse_updates <= e.dense_updates.min(UNROLLED_MAX_UPDATES),
            "{name}"
        );
        // Its own order: no step is planned without its pivot column's filled entries.
        let (_, cols) = t.eliminated_size();
        for k in 0..t.pivot_columns() {
            assert!(
                e.filled.iter().any(|&i| i as usize % cols == k),
                "{name}: column {k}"
            );
        }
        let source = mingen::emit_plan_from(&plan, name).unwrap();
        assert!(source.contains("fn eliminate_template("), "{name}");
        assert!(!source.contains("lu_solve_template"), "{name}");
    }
    // A large template keeps its reordered plan, and nothing is written out for it.
    let plan = plan_file(&template_path("grsrp_gravity"), &TemplateOptions::default()).unwrap();
    let t = &plan.generated.built.template;
    assert!(t.sparse.is_some() && t.unrolled.is_none());
}
