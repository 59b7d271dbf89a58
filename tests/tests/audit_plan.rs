//! `mingen::__internal::audit::audit_plan`, the library side of `mingen audit FILE`, on shipped problems.

mod common;

use common::problem_file;
use mingen::plan_file;
use mingen::TemplateOptions;
use mingen::{audit_plan, AuditOptions};

fn audit(name: &str, instances: usize) -> mingen::AuditReport {
    let plan = plan_file(&problem_file(name), &TemplateOptions::default())
        .unwrap_or_else(|e| panic!("planning {name}: {e}"));
    let report = audit_plan(
        &plan,
        &AuditOptions {
            instances,
            seed: 1,
            ..AuditOptions::default()
        },
    );
    println!("{name}:\n{report}");
    assert_eq!(report.instances, instances);
    assert_eq!(report.solutions_expected, plan.generated.count);
    // The histogram holds every instance with a real solution and every unsolved one.
    assert_eq!(
        report.histogram.iter().map(|b| b.1).sum::<usize>() + report.no_real_solutions,
        instances
    );
    // Deterministic for a fixed seed.
    let again = audit_plan(
        &plan,
        &AuditOptions {
            instances: 20,
            seed: 1,
            ..AuditOptions::default()
        },
    );
    let first = audit_plan(
        &plan,
        &AuditOptions {
            instances: 20,
            seed: 1,
            ..AuditOptions::default()
        },
    );
    assert_eq!(again, first);
    report
}

#[test]
fn audit_plan_gs5pt() {
    let r = audit("gs5pt", 1000);
    assert!(
        r.median_log10_residual < -11.0,
        "gs5pt: median log10 residual {}",
        r.median_log10_residual
    );
    assert!(
        (r.failures as f64) <= 0.005 * r.instances as f64,
        "gs5pt: {} failures of {}",
        r.failures,
        r.instances
    );
}

#[test]
fn audit_plan_grsrp10_with_elimination() {
    let r = audit("grsrp10", 1000);
    assert!(
        r.median_log10_residual < -11.0,
        "grsrp10: median log10 residual {}",
        r.median_log10_residual
    );
    assert!(
        (r.failures as f64) <= 0.005 * r.instances as f64,
        "grsrp10: {} failures of {}",
        r.failures,
        r.instances
    );
}
