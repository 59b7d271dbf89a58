//! The plan's choice of polishing when the problem file does not set `option newton`: it
//! follows the figures it measured, a poorly conditioned template gets polished, a
//! well-conditioned one does not, the file and the command line override it, and the
//! emitted solver and the audit carry the choice.

use mingen::{
    audit_plan, emit_plan_from, plan_file, plan_source, AuditOptions, ProblemOptions, SolverPlan,
    TemplateOptions, AUTO_POLISH_FAILURE_RATE, AUTO_POLISH_INSTANCES, AUTO_POLISH_MEDIAN,
    AUTO_POLISH_MORE_INSTANCES, AUTO_POLISH_P99, AUTO_POLISH_STEPS, AUTO_POLISH_STEP_CHOICES,
    POOR_CHECK_MAX_SHARE,
};
use std::path::Path;

const CIRCLE_HYPERBOLA: &str =
    "problem c\nunknown x, y\ndata a: scalar, b: scalar\nx*x + y*y = a\nx*y = b\n";

fn repo(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path)
}

/// The recorded figures decide the steps, by the documented rule.
fn assert_consistent(plan: &SolverPlan) {
    let a = plan.auto_polishing.as_ref().expect("the plan chose");
    // The first instances, and more only after one failure.
    let more = a.instances == AUTO_POLISH_INSTANCES + AUTO_POLISH_MORE_INSTANCES;
    assert!(a.instances == AUTO_POLISH_INSTANCES || more, "{a:?}");
    if more {
        assert!(a.failures >= 1, "{a:?}");
    } else {
        assert!(a.failures == 0 || a.failures >= 2, "{a:?}");
    }
    let poor = a.median_log10_residual > AUTO_POLISH_MEDIAN
        || a.p99_log10_residual > AUTO_POLISH_P99
        || a.failures as f64 >= AUTO_POLISH_FAILURE_RATE * a.instances as f64;
    if poor {
        assert!(AUTO_POLISH_STEP_CHOICES.contains(&a.steps), "{a:?}");
    } else {
        assert_eq!(a.steps, 0, "{a:?}");
    }
    assert_eq!(plan.problem.layout.options.newton, Some(a.steps));
    // Steps chosen because they pass rest on the first instances and the further ones.
    let passes = (a.chosen_failures as f64) < AUTO_POLISH_FAILURE_RATE * a.chosen_instances as f64;
    if a.steps > 0 && passes {
        assert_eq!(
            a.chosen_instances,
            AUTO_POLISH_INSTANCES + AUTO_POLISH_MORE_INSTANCES,
            "{a:?}"
        );
    }
    let source = emit_plan_from(plan, "t.mp").unwrap();
    assert_eq!(
        source.replace(char::is_whitespace, "").contains(&format!(
            "newton_polish_with(&mutx,{},newton_values,newton_jacobian",
            a.steps
        )),
        a.steps > 0
    );
    assert_eq!(source.contains("newton_polish"), a.steps > 0);
    // No steps for every solution: the poor ones are polished where the check is cheap.
    assert!(!a.polish_poor || a.steps == 0, "{a:?}");
    assert_eq!(plan.polishes_poor_solutions_only(), a.polish_poor);
    assert_eq!(source.contains("polish_poor_solution"), a.polish_poor);
}

/// The poor solutions are polished where checking every solution's residual costs little
/// beside the solve (P3P: 12 terms for each of 8 solutions against a 12x16 template after
/// a 3x7 reduction and a 4x4 eigenproblem), not where the solve is a closed form about as
/// cheap as the check (the upright relative pose in the tangent of the half angle: 31
/// terms, 4 solutions, a 1x5 template and its quartic).
#[test]
fn poor_solutions_are_polished_where_the_check_is_cheap() {
    let share = |plan: &SolverPlan| {
        let data = vec![0.5; plan.problem.layout.data_slot_count()];
        let terms: usize = plan
            .visible_equations(&data)
            .iter()
            .map(|e| e.terms().count())
            .sum();
        let t = &plan.generated.built.template;
        let n = t.basis.len();
        let eigen = match t.companion_unknown() {
            Some(_) => n * n,
            None => 10 * n * n * n,
        };
        (terms * plan.solution_count()) as f64 / (t.elimination_area() + eigen) as f64
    };
    for (file, cheap) in [
        ("templates/classic/p3p.mp", true),
        ("templates/classic/relpose_upright_3pt_tan.mp", false),
    ] {
        let plan = plan_file(&repo(file), &TemplateOptions::default()).unwrap();
        assert_consistent(&plan);
        let a = plan.auto_polishing.as_ref().unwrap();
        assert_eq!(a.steps, 0, "{file}: {a:?}");
        let ratio = share(&plan);
        assert_eq!(ratio <= POOR_CHECK_MAX_SHARE, cheap, "{file}: {ratio}");
        assert_eq!(plan.polishes_poor_solutions_only(), cheap, "{file}");
        assert_eq!(
            plan.summary_json()["polishing"]["poor_solutions_only"],
            cheap
        );
    }
}

#[test]
fn a_well_conditioned_template_is_not_polished() {
    let plan = plan_source(CIRCLE_HYPERBOLA, "c.mp", &TemplateOptions::default()).unwrap();
    assert_consistent(&plan);
    assert_eq!(plan.auto_polishing.as_ref().unwrap().steps, 0);
    // The same plan again: the instances are seeded, the choice the same.
    let again = plan_source(CIRCLE_HYPERBOLA, "c.mp", &TemplateOptions::default()).unwrap();
    assert_eq!(plan.auto_polishing, again.auto_polishing);
}

#[test]
fn the_file_and_the_command_line_override_the_choice() {
    let from_file = plan_source(
        &format!("{CIRCLE_HYPERBOLA}option newton = 3\n"),
        "c.mp",
        &TemplateOptions::default(),
    )
    .unwrap();
    assert_eq!(from_file.auto_polishing, None);
    assert_eq!(from_file.problem.layout.options.newton_steps(), 3);
    // `option newton = 0` turns polishing off, the poor solutions' included.
    let off = plan_source(
        &format!("{CIRCLE_HYPERBOLA}option newton = 0\n"),
        "c.mp",
        &TemplateOptions::default(),
    )
    .unwrap();
    assert!(!off.polishes_poor_solutions_only());
    let source = emit_plan_from(&off, "t.mp").unwrap();
    assert!(!source.contains("newton_polish"));
    assert!(!source.contains("polish_poor_solution"));
    let opts = TemplateOptions {
        overrides: ProblemOptions {
            newton: Some(1),
            ..Default::default()
        },
        ..TemplateOptions::default()
    };
    let from_cli = plan_source(
        &format!("{CIRCLE_HYPERBOLA}option newton = 3\n"),
        "c.mp",
        &opts,
    )
    .unwrap();
    assert_eq!(from_cli.auto_polishing, None);
    assert_eq!(from_cli.problem.layout.options.newton_steps(), 1);
    let json = from_cli.summary_json();
    assert_eq!(json["polishing"]["newton_steps"], 1);
    assert!(json["polishing"]["chosen"].is_null());
}

#[test]
fn a_poorly_conditioned_template_is_polished_and_the_audit_shows_both() {
    // Weighted PnP: its template fails on a few percent of uniform instances unpolished.
    let plan = plan_file(
        &repo("templates/benchmark/wpnp.mp"),
        &TemplateOptions::default(),
    )
    .unwrap();
    assert_consistent(&plan);
    let chosen = plan.auto_polishing.clone().unwrap();
    assert_eq!(chosen.steps, AUTO_POLISH_STEPS, "{chosen:?}");
    let json = plan.summary_json();
    assert_eq!(json["polishing"]["newton_steps"], AUTO_POLISH_STEPS);
    assert_eq!(
        json["polishing"]["chosen"]["instances"],
        AUTO_POLISH_INSTANCES
    );
    // The audit solves as the emitted solver does (polished) and shows the unpolished
    // figures beside: polishing only lowers the residuals.
    let report = audit_plan(
        &plan,
        &AuditOptions {
            instances: 200,
            seed: 5,
            time_limit: None,
        },
    );
    let unpolished = report.other_polishing.as_ref().expect("unpolished figures");
    assert_eq!(unpolished.newton_steps, 0);
    assert!(
        report.median_log10_residual <= unpolished.median_log10_residual,
        "{report}"
    );
    assert!(
        report.p99_log10_residual <= unpolished.p99_log10_residual,
        "{report}"
    );
    assert!(report.failures < unpolished.failures, "{report}");
}

/// Where two steps leave the plan's sample failing, more are chosen: the unsynchronised
/// relative pose (its unknowns `t, u, v` eliminated by Cramer's rule on the data) converges
/// from further away than two steps reach.
#[test]
fn more_steps_are_chosen_where_two_leave_failures() {
    let mut plan = plan_file(
        &repo("templates/benchmark/unsynch_relpose.mp"),
        &TemplateOptions::default(),
    )
    .unwrap();
    assert_consistent(&plan);
    let chosen = plan.auto_polishing.clone().unwrap();
    assert!(chosen.steps > AUTO_POLISH_STEPS, "{chosen:?}");
    let options = AuditOptions {
        instances: 200,
        seed: 9,
        time_limit: None,
    };
    let with_chosen = audit_plan(&plan, &options);
    plan.problem.layout.options.newton = Some(AUTO_POLISH_STEPS);
    let with_two = audit_plan(&plan, &options);
    assert!(
        with_chosen.failures < with_two.failures,
        "{} steps: {with_chosen}\n{AUTO_POLISH_STEPS} steps: {with_two}",
        chosen.steps
    );
}
