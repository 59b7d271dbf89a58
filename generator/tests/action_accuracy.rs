//! The plan's choice of action by accuracy (`action_accuracy.rs`): where the first
//! template's solver fails its polishing sample, the other unknowns' templates of no larger
//! area are measured and the most accurate one kept; where the action is named, nothing
//! is compared.

use mingen::{
    audit_plan, plan_file, AuditOptions, ProblemOptions, TemplateOptions, ACCURACY_INSTANCES,
};
use std::path::Path;

fn repo(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path)
}

/// `relpose_7p_fuv_angle_w_sat`: the three actions give templates of one size (44 x 50);
/// `a`, the one the search finds first, fails a few percent of uniform instances, `b` far
/// fewer. The plan keeps the one it measured best, and the audit on other instances
/// agrees.
#[test]
fn the_most_accurate_of_equally_small_templates_is_kept() {
    let file = repo("templates/benchmark/relpose_7p_fuv_angle_w_sat.mp");
    let plan = plan_file(&file, &TemplateOptions::default()).unwrap();
    let compared = plan
        .action_accuracy
        .as_ref()
        .expect("the first template fails its sample");
    let first = &compared.tried[0];
    let kept = &compared.tried[compared.kept];
    assert_ne!(compared.kept, 0, "{compared:?}");
    let area = |t: &mingen::ActionTrial| t.size.map(|(r, c)| r * c);
    assert!(area(kept) <= area(first), "{compared:?}");
    assert!(
        kept.failure_rate.unwrap() < first.failure_rate.unwrap(),
        "{compared:?}"
    );
    // Every measured rate is a count over the comparison's instances.
    for t in compared.tried.iter().filter_map(|t| t.failure_rate) {
        let count = t * ACCURACY_INSTANCES as f64;
        assert!((count - count.round()).abs() < 1e-9, "{compared:?}");
    }
    let template = &plan.generated.built.template;
    assert_eq!(
        template.action.display_with(&plan.variable_names()),
        kept.action
    );
    // On the audit's own instances (another seed): at most 1 % fail.
    let report = audit_plan(&plan, &AuditOptions::default());
    assert!(report.failures * 100 <= report.instances, "{report}");

    // Named on the command line (or in the file), the action is not compared.
    let named = TemplateOptions {
        overrides: ProblemOptions {
            action: Some(first.action.clone()),
            ..Default::default()
        },
        ..TemplateOptions::default()
    };
    let as_named = plan_file(&file, &named).unwrap();
    assert!(as_named.action_accuracy.is_none());
    let t = &as_named.generated.built.template;
    assert_eq!(
        t.action.display_with(&as_named.variable_names()),
        first.action
    );
    let named_report = audit_plan(&as_named, &AuditOptions::default());
    assert!(
        named_report.failures > report.failures,
        "{named_report}\n{report}"
    );
}
