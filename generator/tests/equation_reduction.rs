//! Templates built from the equations row-reduced on their data (`template/reduction.rs`):
//! chosen where they pay for the reduction, solved as accurately by the interpreter (which
//! runs `mingen_runtime::reduce_equations` as the emitted solvers do), and validated mod p
//! on fresh instances by the pipeline.

use mingen::plan_file;
use mingen::TemplateOptions;
use mingen::{audit_plan, AuditOptions};
use std::path::{Path, PathBuf};

fn benchmark(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../templates/benchmark/{name}.mp"))
}

fn given_only() -> TemplateOptions {
    TemplateOptions {
        reduce_equations: false,
        ..TemplateOptions::default()
    }
}

#[test]
fn reduced_equations_give_a_smaller_template_that_solves_as_well() {
    let f = benchmark("gp4p_scale");
    let reduced = plan_file(&f, &TemplateOptions::default()).unwrap();
    let given = plan_file(&f, &given_only()).unwrap();
    let (tr, tg) = (
        &reduced.generated.built.template,
        &given.generated.built.template,
    );
    assert!(tg.reduction.is_none());
    let red = tr
        .reduction
        .as_ref()
        .expect("gp4p_scale pays for its reduction");
    assert_eq!(red.len(), red.pivots.len());
    assert_eq!(reduced.generated.count, given.generated.count);
    assert!(reduced.generated.validation.is_some(), "validated mod p");
    assert!(
        tr.elimination_area() < tg.elimination_area(),
        "{:?} + {:?} against {:?}",
        tr.eliminated_size(),
        tr.reduction_size(),
        tg.eliminated_size()
    );
    let options = AuditOptions {
        instances: 300,
        seed: 5,
        ..AuditOptions::default()
    };
    for (what, plan) in [("reduced", &reduced), ("given", &given)] {
        let a = audit_plan(plan, &options);
        assert!(
            a.median_log10_residual < -10.0 && a.failures <= 3,
            "{what}: median {} failures {}",
            a.median_log10_residual,
            a.failures
        );
    }
}

#[test]
fn a_reduction_that_does_not_pay_for_itself_is_not_chosen() {
    // The five-point problem's 10 x 20 template is its equations' reduction already: a
    // 6 x 16 template after a 10 x 20 reduction eliminates more entries.
    let p = plan_file(&benchmark("5p"), &TemplateOptions::default()).unwrap();
    let t = &p.generated.built.template;
    assert!(t.reduction.is_none());
    assert_eq!(t.eliminated_size(), (10, 20));
}
