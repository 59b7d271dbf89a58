//! Saturation (`nonzero`), action and degree options, and budgets on small problems: the
//! counts of the saturated and unsaturated systems, the hidden unknown kept out of the
//! solutions, random-combination actions, and the errors when a budget runs out.

use mingen::budget::Budget;
use mingen::pipeline::plan;
use mingen::problem::ProblemOptions;
use mingen::template::TemplateOptions;
use mingen::Problem;

/// A circle and a hyperbola, each multiplied by x: the 4 intersections of
/// `x^2 + y^2 = r` and `x y = s` (all with x != 0), and the line x = 0.
const CIRCLE: &str = "problem circle
unknown x, y
data r: scalar, s: scalar
x * (x*x + y*y - r) = 0
x * (x*y - s) = 0
";

fn planned(src: &str, opts: &TemplateOptions) -> Result<mingen::pipeline::SolverPlan, String> {
    let problem = Problem::parse(src, "t.mp").map_err(|e| e.to_string())?;
    plan(problem, "t.mp", opts).map_err(|e| e.to_string())
}

#[test]
fn nonzero_removes_the_component_and_is_never_returned() {
    let opts = TemplateOptions::default();
    // Without saturation x = 0 leaves y free: positive-dimensional.
    let err = planned(CIRCLE, &opts).err().expect("positive-dimensional");
    assert!(err.contains("positive-dimensional"), "{err}");
    let sat = format!("{CIRCLE}nonzero x\n");
    let p = planned(&sat, &opts).unwrap();
    assert_eq!(p.generated.count, 4);
    assert_eq!(p.problem.layout.hidden_count(), 1);
    assert_eq!(p.generated.built.template.n_hidden, 1);
    // The audit measures the declared equations at the real intersections.
    let a = mingen::audit::audit_plan(
        &p,
        &mingen::audit::AuditOptions {
            instances: 200,
            seed: 3,
        },
    );
    assert!(a.median_log10_residual < -10.0, "{a}");
    // The emitted solution type has the declared unknowns only.
    let src = mingen::generate::emit_plan_from(&p, "t.mp").unwrap();
    assert!(src.contains("pub x: f64") && src.contains("pub y: f64"));
    assert!(
        src.contains("pub const UNKNOWNS: usize = 2;"),
        "hidden unknown leaked into the solution type"
    );
}

#[test]
fn nonzero_needs_a_scalar_in_the_unknowns() {
    let e = Problem::parse("problem p\nunknown t[3]\nt't = 1\nnonzero t\n", "p.mp").unwrap_err();
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
        ("option extra_degree = -1", "option extra_degree"),
        ("option basis = best", "option basis"),
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
