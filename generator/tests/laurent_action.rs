//! Laurent actions (`option action = 1/x`, `--action 1/x`, `TemplateOptions::laurent_actions`):
//! multiplication by `1 / x` on the quotient basis times `x`. The template proves `x`
//! invertible on the solutions, the validation compares its characteristic polynomial
//! with the inverse of `x`'s normal-form matrix, and the solvers read the unknowns off the
//! eigenvectors relative to the basis's unit `x`.

use mingen::{audit_plan, emit_plan_from, plan_file, plan_source, AuditOptions, TemplateOptions};
use std::path::Path;

fn five_point() -> String {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/benchmark/5p.mp");
    std::fs::read_to_string(file).unwrap()
}

#[test]
fn an_inverse_action_solves_on_the_shifted_basis() {
    let src = format!("{}\noption action = 1/x\n", five_point());
    let p = plan_source(&src, "5p.mp", &TemplateOptions::default()).unwrap();
    let t = &p.generated.built.template;
    assert_eq!(p.generated.count, 10);
    let x = 0;
    assert_eq!(t.action.inverse_of(), Some(x));
    assert_eq!(t.action.single(), None);
    // Every basis monomial is a multiple of x, and the unit is x (1 times x).
    assert!(t.basis.iter().all(|b| b.0[x] > 0), "{:?}", t.basis);
    assert_eq!(t.unit().0, vec![1, 0, 0]);
    // The reducible monomials are b / x outside the basis: below it, not above.
    let max_basis = t.basis.iter().map(|b| b.degree()).max().unwrap();
    let reducible = &t.columns[t.n_excess..t.n_excess + t.n_reducible];
    assert!(reducible.iter().all(|r| r.degree() < max_basis));
    assert!(p.generated.validation.as_ref().unwrap().instances >= 2);
    // The interpreted solver: the real solutions of uniform instances, at rounding level.
    let a = audit_plan(
        &p,
        &AuditOptions {
            instances: 100,
            seed: 5,
            ..Default::default()
        },
    );
    assert!(a.median_log10_residual < -11.0, "{a}");
    assert_eq!(a.failures, 0, "{a}");
    // The emitted solver builds its action matrix from the products b / x.
    let code = emit_plan_from(&p, "5p.mp").unwrap();
    assert!(
        code.contains("1/x"),
        "the action is named in the solver's documentation"
    );
}

#[test]
fn laurent_actions_are_searched_beside_the_unknowns() {
    let options = TemplateOptions {
        laurent_actions: true,
        ..TemplateOptions::default()
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/benchmark/5p.mp");
    let p = plan_file(&path, &options).unwrap();
    let names: Vec<String> = p
        .generated
        .per_action
        .iter()
        .map(|(a, _)| a.display_with(&["x".into(), "y".into(), "z".into()]))
        .collect();
    assert_eq!(names, ["x", "y", "z", "1/x", "1/y", "1/z"]);
    assert!(p.generated.per_action.iter().all(|(_, s)| s.is_some()));
    // Ties go to the unknown, tried first.
    assert_eq!(p.generated.built.template.action.single(), Some(0));
}

#[test]
fn an_unknown_that_vanishes_on_a_solution_has_no_inverse_action() {
    // x (x - a) = 0, y = b x + c: one solution has x = 0, where 1/x is undefined.
    let src = "problem z\nunknown x, y\ndata a: scalar, b: scalar, c: scalar\n\
               x*(x - a) = 0\ny - b*x - c = 0\noption auto_eliminate = no\n";
    let forward = plan_source(src, "z.mp", &TemplateOptions::default()).unwrap();
    assert_eq!(forward.generated.count, 2);
    let inverse = format!("{src}option action = 1/x\n");
    let err = plan_source(&inverse, "z.mp", &TemplateOptions::default())
        .err()
        .expect("1/x cannot act where x = 0");
    assert!(err.to_string().contains("1/x"), "{err}");
}

#[test]
fn the_option_names_an_unknown_after_the_slash() {
    let src = five_point();
    for (bad, want) in [
        ("option action = 1/q", "'1/NAME'"),
        ("option action = 1/", "an unknown after '1/'"),
    ] {
        let err = plan_source(
            &format!("{src}\n{bad}\n"),
            "5p.mp",
            &TemplateOptions::default(),
        )
        .err()
        .unwrap_or_else(|| panic!("{bad} is refused"));
        assert!(err.to_string().contains(want), "{bad}: {err}");
    }
}
