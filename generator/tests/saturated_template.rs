//! Saturation inside the template (`template/search/saturated.rs`): a `nonzero` monomial
//! is not carried as a hidden unknown, the template reduces the shifted monomials `s R`
//! onto `s B` with multiples of the equations as written, and the solver reads the
//! unknowns relative to the entry of `s`; a `nonzero` polynomial with constant
//! coefficients likewise, with columns that stand for multiples of a power of it
//! (`template/shift.rs`).

use mingen::__internal::audit::{audit_plan, audit_plan_planted, AuditOptions};
use mingen::{plan, Problem, SolverPlan, TemplateOptions};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn planned(src: &str) -> SolverPlan {
    let problem = Problem::parse(src, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    plan(problem, "t.mp", &TemplateOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// Three equations in `x, y` times polynomials: the line `x = y = 0` (any `z`) is a
/// spurious component, and no equation is divisible by `x`, so `nonzero x` stays a
/// saturation; four solutions remain.
const SPURIOUS_LINE: &str = "problem spurious_line
unknown x, y, z
data a: vec3, b: vec3, c: vec3, d: scalar
x*(z + a[0]) + y*(a[1]*z + a[2]) = 0
x*(b[0]*y + b[1]*z + d) + y*(z^2 + b[2]) = 0
x*(c[0]*x + c[1]*z) + y*(c[2] + z) = 0
nonzero x
";

/// A planted solution `(x, y, z)` and data (slot order a, b, c, d) solving every
/// equation there: `a[2]`, `b[2]` and `c[2]` are solved for.
fn planted_instance(rng: &mut ChaCha8Rng) -> (Vec<f64>, Vec<f64>) {
    let mut r = |lo: f64, hi: f64| rng.gen_range(lo..hi);
    let (x, y, z) = (r(0.5, 2.0), r(0.5, 2.0), r(-2.0, 2.0));
    let mut d: Vec<f64> = (0..10).map(|_| r(-1.0, 1.0)).collect();
    d[2] = -(x * (z + d[0]) + y * d[1] * z) / y;
    d[5] = -x * (d[3] * y + d[4] * z + d[9]) / y - z * z;
    d[8] = -x * (d[6] * x + d[7] * z) / y - z;
    (d, vec![x, y, z])
}

/// `p` audits well on uniform data and recovers the planted solutions of `instance`.
fn assert_solves(p: &SolverPlan, instance: fn(&mut ChaCha8Rng) -> (Vec<f64>, Vec<f64>)) {
    let report = audit_plan(
        p,
        &AuditOptions {
            instances: 200,
            seed: 5,
            ..Default::default()
        },
    );
    assert!(report.median_log10_residual < -10.0, "{report}");
    assert!(report.failures <= 2, "{report}");
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let (instances, solutions): (Vec<_>, Vec<_>) = (0..100).map(|_| instance(&mut rng)).unzip();
    let planted = audit_plan_planted(p, &instances, Some(&solutions));
    let recovered = planted
        .planted
        .as_ref()
        .expect("planted solutions")
        .recovered;
    assert!(recovered >= 98, "{planted}");
}

#[test]
fn a_monomial_saturation_is_built_into_the_template() {
    let p = planned(SPURIOUS_LINE);
    assert_eq!(p.solution_count(), 4);
    let built = &p.generated.built;
    assert!(
        built.basis_choice.contains("saturated inside the template"),
        "{}",
        built.basis_choice
    );
    let t = &built.template;
    // No row is a multiple of the hidden equation `u x - 1`: no column has the hidden
    // unknown, and the basis is shifted by a power of x.
    let visible = t.visible_vars();
    assert!(t
        .columns
        .iter()
        .all(|m| m.0[visible..].iter().all(|&e| e == 0)));
    let unit = t.unit();
    assert!(
        unit.0[0] >= 1 && unit.0[1..].iter().all(|&e| e == 0),
        "{unit:?}"
    );
    assert_solves(&p, planted_instance);
}

#[test]
fn the_emitted_solver_reads_relative_to_the_shift() {
    let p = planned(SPURIOUS_LINE);
    let code = mingen::emit_plan_from(&p, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    // The hidden unknown is not part of the solution.
    assert!(code.contains("pub const UNKNOWNS: usize = 3;"), "{code}");
}

/// [`SPURIOUS_LINE`] with `x` replaced by the polynomial `s = x + y^2 + 1`: the spurious
/// component is the line `s = y = 0` (`x = -1`, any `z`), and `nonzero x + y^2 + 1` is a
/// saturation by a polynomial with constant coefficients.
const SPURIOUS_CURVE: &str = "problem spurious_curve
unknown x, y, z
data a: vec3, b: vec3, c: vec3, d: scalar
let s = x + y^2 + 1
s*(z + a[0]) + y*(a[1]*z + a[2]) = 0
s*(b[0]*y + b[1]*z + d) + y*(z^2 + b[2]) = 0
s*(c[0]*x + c[1]*z) + y*(c[2] + z) = 0
nonzero x + y^2 + 1
";

/// The solution count of [`SPURIOUS_CURVE`] (of the saturation; the analysis counts it
/// with the hidden unknown, apart from any template).
const COUNT_CURVE: usize = 7;

/// A planted solution of [`SPURIOUS_CURVE`] and its data, as [`planted_instance`].
fn planted_curve_instance(rng: &mut ChaCha8Rng) -> (Vec<f64>, Vec<f64>) {
    let mut r = |lo: f64, hi: f64| rng.gen_range(lo..hi);
    let (x, y, z) = (r(0.5, 2.0), r(0.5, 2.0), r(-2.0, 2.0));
    let s = x + y * y + 1.0;
    let mut d: Vec<f64> = (0..10).map(|_| r(-1.0, 1.0)).collect();
    d[2] = -(s * (z + d[0]) + y * d[1] * z) / y;
    d[5] = -s * (d[3] * y + d[4] * z + d[9]) / y - z * z;
    d[8] = -s * (d[6] * x + d[7] * z) / y - z;
    (d, vec![x, y, z])
}

#[test]
fn a_polynomial_saturation_is_built_into_the_template() {
    let p = planned(&format!("{SPURIOUS_CURVE}option saturation = template\n"));
    let built = &p.generated.built;
    assert!(
        built.basis_choice.contains("shifted by the polynomial"),
        "{}",
        built.basis_choice
    );
    let t = &built.template;
    // The columns stand for multiples of a power of s; none has the hidden unknown.
    let shift = t
        .shift
        .as_ref()
        .expect("a template shifted by a polynomial");
    assert!(shift.terms.len() > 1, "{shift:?}");
    let visible = t.visible_vars();
    assert!(t
        .columns
        .iter()
        .all(|m| m.0[visible..].iter().all(|&e| e == 0)));
    assert_eq!(p.solution_count(), COUNT_CURVE);
    // Its structure (the shifted coordinates' pattern) gives it an elimination plan, which
    // the emitted solver follows (the classic corpus's `p2p2pl` and `p35pf` recover their
    // planted poses through the sparse one: tests/tests/corpus.rs).
    assert!(t.unrolled.is_some() || t.sparse.is_some());
    assert_solves(&p, planted_curve_instance);
    // The emitted solver fills the same coordinates.
    let code = mingen::emit_plan_from(&p, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    assert!(code.contains("pub const UNKNOWNS: usize = 3;"), "{code}");
}

#[test]
fn a_polynomial_saturation_keeps_the_smaller_of_the_template_and_the_hidden_unknown() {
    let route = |value: &str| planned(&format!("{SPURIOUS_CURVE}option saturation = {value}\n"));
    let (template, unknown) = (route("template"), route("unknown"));
    assert!(template.generated.built.template.shift.is_some());
    // The hidden unknown's template has it in its columns.
    let t = &unknown.generated.built.template;
    assert!(t.shift.is_none());
    let visible = t.visible_vars();
    assert!(t
        .columns
        .iter()
        .any(|m| m.0[visible..].iter().any(|&e| e > 0)));
    // The default searches both and keeps the smaller (after the fold).
    let smaller = planned(SPURIOUS_CURVE);
    let area = |p: &SolverPlan| p.generated.built.folded_area();
    assert_eq!(area(&smaller), area(&template).min(area(&unknown)));
    for p in [&smaller, &unknown] {
        assert_eq!(p.solution_count(), COUNT_CURVE);
        assert_solves(p, planted_curve_instance);
    }
    let bad = Problem::parse(
        &format!("{SPURIOUS_CURVE}option saturation = maybe\n"),
        "t.mp",
    )
    .err()
    .map(|e| e.to_string())
    .unwrap_or_default();
    assert!(bad.contains("option saturation: expected"), "{bad}");
}
