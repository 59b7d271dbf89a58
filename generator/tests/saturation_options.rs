//! Saturation (`nonzero`), action and degree options, and budgets: the counts of the
//! saturated and unsaturated Cayley-form 5-point systems, the hidden unknown kept out of
//! the solutions, random-combination actions, and the errors when a budget runs out.

use mingen::plan;
use mingen::Budget;
use mingen::Problem;
use mingen::ProblemOptions;
use mingen::TemplateOptions;

fn planned(src: &str, opts: &TemplateOptions) -> Result<mingen::SolverPlan, String> {
    let problem = Problem::parse(src, "t.mp").map_err(|e| e.to_string())?;
    plan(problem, "t.mp", opts).map_err(|e| e.to_string())
}

/// Audits `p` on `instances` uniform instances and checks the median log10 residual.
fn assert_audit_below(p: &mingen::SolverPlan, instances: usize, seed: u64, median: f64) {
    let a = mingen::__internal::audit::audit_plan(
        p,
        &mingen::__internal::audit::AuditOptions {
            instances,
            seed,
            ..Default::default()
        },
    );
    assert!(a.median_log10_residual < median, "{a}");
}

#[test]
fn nonzero_removes_the_component_and_is_never_returned() {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../templates/classic/relpose_5pt_cayley_sat.mp");
    let src = std::fs::read_to_string(file).unwrap();
    let opts = TemplateOptions::default();
    // Without saturation the component 1 + q'q = 0 is positive-dimensional.
    let unsaturated = src.replace("nonzero 1 + q'*q", "");
    let err = planned(&unsaturated, &opts)
        .err()
        .expect("positive-dimensional");
    assert!(err.contains("positive-dimensional"), "{err}");
    let p = planned(&src, &opts).unwrap();
    assert_eq!(p.generated.count, 20);
    // 1 + q'q divides every 3x3 minor of the eliminated system: divided out, the system
    // has the 20 solutions without saturation, so the hidden unknown is gone.
    assert!(p.problem.divisions().iter().flatten().any(|&k| k > 0));
    assert_eq!(p.problem.layout.hidden_count(), 0);
    assert_eq!(p.generated.built.template.n_hidden, 0);
    let (rows, cols) = p.generated.built.template.eliminated_size();
    assert!(rows <= 40 && cols <= 60, "{rows} x {cols}");
    // The audit measures the declared equations at the real solutions.
    assert_audit_below(&p, 50, 3, -9.0);
    // The emitted solution type has the declared unknowns only (q and t).
    let out = mingen::emit_plan_from(&p, "t.mp").unwrap();
    assert!(
        out.contains("pub const UNKNOWNS: usize = 6;"),
        "hidden unknown leaked into the solution type"
    );
}

#[test]
fn nonzero_expressions_are_divided_out_and_saturation_kept_only_where_needed() {
    let opts = TemplateOptions::default();
    // (x - 1) divides the first equation: divided, the system x + y = b, x y = a has the
    // two solutions the saturated one has (the third, x = 1, is gone), so no hidden
    // unknown remains.
    let head = "problem d\nunknown x, y\ndata a: scalar, b: scalar\n(x - 1)*(x + y - b) = 0\n";
    let without = planned(&format!("{head}x*y = a\n"), &opts).unwrap();
    assert_eq!(without.generated.count, 3);
    let p = planned(&format!("{head}x*y = a\nnonzero x - 1\n"), &opts).unwrap();
    assert_eq!(p.generated.count, 2);
    assert_eq!(p.problem.divisions(), &[vec![1], vec![0]]);
    assert_eq!(p.problem.layout.hidden_count(), 0);
    // A divisor with data in it (leading coefficient 1): divided the same way.
    let p = planned(
        "problem e\nunknown x, y\ndata a: scalar, b: scalar, c: scalar\n\
         (x - a)*(x + y - b) = 0\nx*y = c\nnonzero x - a\n",
        &opts,
    )
    .unwrap();
    assert_eq!(p.generated.count, 2);
    assert_eq!(p.problem.divisions(), &[vec![1], vec![0]]);
    assert_eq!(p.problem.layout.hidden_count(), 0);
    assert_audit_below(&p, 30, 5, -12.0);
    assert!(mingen::emit_plan_from(&p, "e.mp").is_ok());
    // Here the divided system still has a solution with x = 1 ((1, b - 1), the second
    // equation not being a multiple of x - 1): saturation stays and removes it.
    let p = planned(
        &format!("{head}(x - 1)*y + y - b + 1 = 0\nnonzero x - 1\n"),
        &opts,
    )
    .unwrap();
    assert_eq!(p.generated.count, 1);
    assert_eq!(p.problem.layout.hidden_count(), 1);
    assert!(p.problem.divisions().iter().flatten().any(|&k| k > 0));
    assert_audit_below(&p, 30, 4, -12.0);
}

#[test]
fn nonzero_needs_a_scalar_in_the_unknowns() {
    let e = Problem::parse("problem p\nunknown t[3]\nt' * t = 1\nnonzero t\n", "p.mp").unwrap_err();
    assert!(e.to_string().contains("'nonzero' needs a scalar"), "{e}");
    let e = Problem::parse("problem p\nunknown x\nx*x = 1\nnonzero 2\n", "p.mp").unwrap_err();
    assert!(e.to_string().contains("found a constant"), "{e}");
}

#[test]
fn options_choose_the_action_and_are_checked() {
    let src = "problem c\nunknown x, y\ndata a: scalar, b: scalar\nx*x + y*y = a\nx*y = b\n";
    let p = planned(
        &format!("{src}option action = random\n"),
        &TemplateOptions::default(),
    )
    .unwrap();
    let action = &p.generated.built.template.action;
    assert!(action.single().is_none(), "{action:?}");
    assert!(action.coefficients.iter().all(|&c| c != 0));
    // The command line overrides the file.
    let opts = TemplateOptions {
        overrides: ProblemOptions {
            action: Some("y".into()),
            ..ProblemOptions::default()
        },
        ..TemplateOptions::default()
    };
    let p = planned(&format!("{src}option action = random\n"), &opts).unwrap();
    assert_eq!(p.generated.built.template.action.single(), Some(1));
    for (line, what) in [
        ("option action = z", "option action"),
        ("option extra_degree = 99", "option extra_degree"),
        ("option basis = best", "option basis"),
        ("option newton = 9", "option newton"),
        ("option newton = fast", "option newton"),
        ("option auto_eliminate = maybe", "option auto_eliminate"),
        ("option redundant_basis = maybe", "option redundant_basis"),
        (
            "option redundant_basis = yes\noption redundant_basis = no",
            "option redundant_basis is given twice",
        ),
        ("option speed = 3", "unknown option 'speed'"),
    ] {
        let e = Problem::parse(&format!("{src}{line}\n"), "c.mp").unwrap_err();
        assert!(e.to_string().contains(what), "{line}: {e}");
    }
}

#[test]
fn an_exhausted_budget_is_a_clear_error() {
    // The count is found (a few Gröbner pairs, below the first budget check), then the
    // template search stops at once: the error keeps the count and names the budget.
    let src = "problem c\nunknown x, y\ndata a: scalar, b: scalar\nx*x + y*y = a\nx*y = b\n";
    let opts = TemplateOptions {
        budget: Budget {
            max_seconds: 1e-9,
            max_memory_bytes: 1 << 30,
        },
        ..TemplateOptions::default()
    };
    let err = planned(src, &opts).err().expect("no time for a template");
    assert!(err.contains("4 solutions, but no template"), "{err}");
    assert!(err.contains("up to degree"), "{err}");
    assert!(err.contains("time budget"), "{err}");
}

#[test]
fn newton_polishes_solutions_in_the_audit_and_the_emitted_solver() {
    // A circle and a hyperbola (4 solutions): polishing may only lower the residuals, and
    // the emitted solver carries the steps; with `option newton = 0` it does not polish,
    // and the audit shows what polishing would give.
    let src = "problem c\nunknown x, y\ndata a: scalar, b: scalar\nx*x + y*y = a\nx*y = b\n";
    let plain = planned(
        &format!("{src}option newton = 0\n"),
        &TemplateOptions::default(),
    )
    .unwrap();
    assert_eq!(plain.problem.layout.options.newton_steps(), 0);
    assert_eq!(plain.auto_polishing, None);
    assert_eq!(mingen::__internal::problem::DEFAULT_NEWTON_STEPS, 0);
    let polished = planned(
        &format!("{src}option newton = 2\n"),
        &TemplateOptions::default(),
    )
    .unwrap();
    assert_eq!(polished.problem.layout.options.newton, Some(2));
    let audit = |p: &mingen::SolverPlan| {
        mingen::__internal::audit::audit_plan(
            p,
            &mingen::__internal::audit::AuditOptions {
                instances: 200,
                seed: 3,
                ..Default::default()
            },
        )
    };
    let (a, b) = (audit(&plain), audit(&polished));
    assert!(
        b.median_log10_residual <= a.median_log10_residual,
        "{a} {b}"
    );
    assert!(b.failures <= a.failures, "{a} {b}");
    // Each audit's other figures are the other's own (same instances): the unpolished
    // audit shows what two steps give, the polished one what the action matrix gave.
    let with_steps = a.other_polishing.as_ref().expect("figures with polishing");
    assert_eq!(
        with_steps.newton_steps,
        mingen::__internal::audit::COMPARISON_NEWTON_STEPS
    );
    assert_eq!(with_steps.median_log10_residual, b.median_log10_residual);
    assert_eq!(with_steps.failures, b.failures);
    let before = b
        .other_polishing
        .as_ref()
        .expect("figures before polishing");
    assert_eq!(before.newton_steps, 0);
    assert_eq!(before.median_log10_residual, a.median_log10_residual);
    assert_eq!(before.p99_log10_residual, a.p99_log10_residual);
    assert_eq!(before.failures, a.failures);
    let source = mingen::emit_plan_from(&polished, "t.mp").unwrap();
    assert!(source
        .replace(char::is_whitespace, "")
        .contains("newton_polish_with(&mutx,2,newton_values,newton_jacobian"));
    assert!(!mingen::emit_plan_from(&plain, "t.mp")
        .unwrap()
        .contains("newton_polish"));
    // The command line's value replaces the file's.
    let opts = TemplateOptions {
        overrides: ProblemOptions {
            newton: Some(0),
            ..ProblemOptions::default()
        },
        ..TemplateOptions::default()
    };
    let p = planned(&format!("{src}option newton = 2\n"), &opts).unwrap();
    assert_eq!(p.problem.layout.options.newton, Some(0));
}

#[test]
fn generalised_relative_pose_divides_out_its_cayley_denominator() {
    // 6 Plücker-line correspondences, t eliminated: the 4x4 minors (degree 8) are
    // multiples of 1 + q'q; divided, the 64 solutions need no saturation and the
    // template is PoseLib's size (99 x 163) instead of 1102 x 1166 saturated.
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../templates/large/gen_relpose_6pt.mp");
    let src = std::fs::read_to_string(file).unwrap();
    let p = planned(&src, &TemplateOptions::default()).unwrap();
    assert_eq!(p.generated.count, 64);
    assert_eq!(p.problem.layout.hidden_count(), 0);
    assert!(p.problem.divisions().iter().flatten().all(|&k| k <= 1));
    assert_eq!(
        p.problem
            .divisions()
            .iter()
            .flatten()
            .filter(|&&k| k == 1)
            .count(),
        15,
        "every 4x4 minor of the 6 x 4 matrix [A b] is divided once"
    );
    let (rows, cols) = p.generated.built.template.eliminated_size();
    assert!(rows <= 99 && cols <= 163, "{rows} x {cols}");
    assert_audit_below(&p, 40, 6, -12.0);
}
