//! A template whose basis is the power basis of its action's unknown: the action matrix is
//! a companion matrix, the unknown is its eigenvalue, and the emitted solver solves the
//! polynomial from the template's reduced row (`mingen_runtime::real_eigenpairs_companion`).

use mingen::__internal::interpret::solve_template_real;
use mingen::{emit_plan_from, plan, Problem, TemplateOptions};

/// A quartic in one unknown with data coefficients, and a second unknown fixed by the
/// first: the basis is `[x^3, x^2, x, 1]` and `y` is read off its reduced row.
const QUARTIC: &str = "problem quartic_and_line
unknown x, y
data c: vec4, k: scalar
x^4 + c[3]*x^3 + c[2]*x^2 + c[1]*x + c[0] = 0
y - k*x*x = 1
";

#[test]
fn the_power_basis_gives_a_companion_action_read_by_its_eigenvalue() {
    let problem = Problem::parse(QUARTIC, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    let opts = TemplateOptions {
        // The univariate polynomial: one action, one template.
        actions: mingen::ActionChoice::Unknowns(vec![0]),
        ..TemplateOptions::default()
    };
    let p = plan(problem, "t.mp", &opts).unwrap_or_else(|e| panic!("{e}"));
    let t = &p.generated.built.template;
    assert_eq!(t.basis.len(), 4);
    assert_eq!(t.companion_unknown(), Some(0), "{:?}", t.basis);

    // Roots 1, 2, -3, -0.5: (x - 1)(x - 2)(x + 3)(x + 0.5); y = 1 + k x^2.
    let (c, k) = ([3.0, 2.5, -7.0, 0.5], 0.25);
    let data = [c[0], c[1], c[2], c[3], k];
    let (equations, _) = p.equations::<f64>(&data);
    let mut got = solve_template_real(t, &equations);
    got.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let want = [-3.0, -0.5, 1.0, 2.0];
    assert_eq!(got.len(), 4, "{got:?}");
    for (s, x) in got.iter().zip(want) {
        assert!((s[0] - x).abs() < 1e-12, "{got:?}");
        assert!((s[1] - (1.0 + k * x * x)).abs() < 1e-12, "{got:?}");
    }

    let code = emit_plan_from(&p, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    assert!(code.contains("real_eigenpairs_companion"), "{code}");
    assert!(!code.contains("real_eigenpairs_sturm"), "{code}");
}

#[test]
fn other_bases_keep_the_general_eigenproblem() {
    // Two unknowns of degree two each: no power basis of one unknown.
    let src = "problem two_conics
unknown x, y
data a: vec3, b: vec3
x*x + a[0]*y*y + a[1]*x + a[2] = 0
y*y + b[0]*x*y + b[1]*y + b[2] = 0
";
    let problem = Problem::parse(src, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    let p = plan(problem, "t.mp", &TemplateOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let t = &p.generated.built.template;
    assert_eq!(t.companion_unknown(), None, "{:?}", t.basis);
    let code = emit_plan_from(&p, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    assert!(!code.contains("real_eigenpairs_companion"));
}

#[test]
fn a_basis_of_one_reads_the_other_unknowns_off_their_own_rows() {
    // One solution: the basis is [1], the action's unknown is the eigenvalue and the others
    // (outside the basis too) are read off their own reduced rows, not the action's.
    let src = "problem line_pair
option auto_eliminate = no
unknown x, y, z
data a: vec3, b: vec3, c: vec3
a[0]*x + a[1]*y + a[2]*z = 1
b[0]*x + b[1]*y + b[2]*z = 2
c[0]*x + c[1]*y + c[2]*z = 3
";
    for action in 0..3 {
        let problem = Problem::parse(src, "t.mp").unwrap_or_else(|e| panic!("{e}"));
        let opts = TemplateOptions {
            actions: mingen::ActionChoice::Unknowns(vec![action]),
            ..TemplateOptions::default()
        };
        let p = plan(problem, "t.mp", &opts).unwrap_or_else(|e| panic!("{e}"));
        let t = &p.generated.built.template;
        assert_eq!(t.basis.len(), 1, "{:?}", t.basis);
        assert_eq!(t.companion_unknown(), Some(action));
        // x = (1, -2, 0.5) for these rows.
        let want = [1.0, -2.0, 0.5];
        let rows = [[2.0, 1.0, 2.0], [1.0, 3.0, 14.0], [-1.0, -1.0, 4.0]];
        let data: Vec<f64> = rows.iter().flatten().copied().collect();
        for (r, rhs) in rows.iter().zip([1.0, 2.0, 3.0]) {
            let lhs: f64 = r.iter().zip(want).map(|(a, x)| a * x).sum();
            assert!((lhs - rhs).abs() < 1e-14, "{lhs} {rhs}");
        }
        let (equations, _) = p.equations::<f64>(&data);
        let got = solve_template_real(t, &equations);
        assert_eq!(got.len(), 1, "action {action}: {got:?}");
        for (g, w) in got[0].iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "action {action}: {got:?}");
        }
    }
}
