//! Sign symmetry (`symmetry.rs`): a system whose equations are each even or odd in a set
//! of unknowns is folded to half its solutions, the solver returns both signs, and a
//! fold that would lose solutions (a pivot that vanishes on some) is not made.

use mingen::__internal::audit::{audit_plan, AuditOptions, AuditReport};
use mingen::{emit_plan_from, plan, Problem, SolverPlan, TemplateOptions};

fn planned(src: &str) -> SolverPlan {
    let problem = Problem::parse(src, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    plan(problem, "t.mp", &TemplateOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn audited(p: &SolverPlan) -> AuditReport {
    audit_plan(
        p,
        &AuditOptions {
            instances: 300,
            seed: 11,
            ..Default::default()
        },
    )
}

fn p3p() -> String {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/classic/p3p.mp");
    std::fs::read_to_string(file).unwrap()
}

#[test]
fn p3p_is_solved_at_half_the_size_with_both_signs() {
    let folded = planned(&p3p());
    let plain = planned(&format!("{}\noption sign_symmetry = no\n", p3p()));
    assert_eq!(folded.problem.sign_folds().len(), 1);
    assert!(plain.problem.sign_folds().is_empty());
    assert_eq!((folded.solution_count(), folded.generated.count), (8, 4));
    assert_eq!(plain.generated.count, 8);
    assert_eq!(folded.generated.built.template.basis.len(), 4);
    let area = |p: &SolverPlan| {
        let (r, c) = p.generated.built.template.eliminated_size();
        r * c
    };
    assert!(area(&folded) < area(&plain));
    // The same instances: the same real solutions, accurate, none missed.
    let (a, b) = (audited(&folded), audited(&plain));
    assert_eq!(a.solutions_expected, 8);
    assert_eq!(a.failures, 0, "{a}");
    assert!(a.median_log10_residual < -11.0, "{a}");
    assert!(
        (a.mean_real_solutions - b.mean_real_solutions).abs() < 1e-9,
        "{a}\n{b}"
    );
    assert_eq!(a.mean_kept_solutions, b.mean_kept_solutions);
    // The emitted solver unfolds each eigenvector into both signs.
    let code = emit_plan_from(&folded, "templates/classic/p3p.mp").unwrap();
    assert!(code.contains("mingen_runtime::unfold_signs"), "{code}");
    assert!(code.contains("pub const MAX_SOLUTIONS: usize = 8;"));
    let summary = folded.summary_json();
    assert_eq!(summary["solutions"], 8);
    assert!(summary["sign_symmetry"]
        .as_str()
        .unwrap()
        .starts_with("d1 d2 d3"));
}

#[test]
fn odd_equations_lose_their_common_factor() {
    // Even: x^2 + a y^2 - b; odd in {x, y}: x y^2 + c x^3 + d y. Bezout 6, no solution
    // with x = 0 (then y = 0 and b = 0): 3 pairs.
    let src = "problem odd
unknown x, y
data a: scalar, b: scalar, c: scalar, d: scalar
x^2 + a*y^2 - b = 0
x*y^2 + c*x^3 + d*y = 0
";
    let p = planned(src);
    assert_eq!(p.problem.sign_folds().len(), 1);
    assert_eq!((p.solution_count(), p.generated.count), (6, 3));
    let r = audited(&p);
    assert_eq!(r.failures, 0, "{r}");
    assert!(r.median_log10_residual < -11.0, "{r}");
    // Real solutions come in pairs.
    let plain = audited(&planned(&format!("{src}option sign_symmetry = no\n")));
    assert!((r.mean_real_solutions - plain.mean_real_solutions).abs() < 1e-9);
    assert!(r.mean_real_solutions > 0.5);
}

#[test]
fn a_fold_whose_pivot_vanishes_on_a_solution_is_not_made() {
    // x^2 + a y^2 - b and c x y: four solutions (0, ±y0) and (±x0, 0), in sign pairs,
    // but either pivot is zero on two of them.
    let src = "problem axes
unknown x, y
data a: scalar, b: scalar, c: scalar
x^2 + a*y^2 - b = 0
c*x*y = 0
";
    let p = planned(src);
    assert!(p.problem.sign_folds().is_empty());
    assert_eq!((p.solution_count(), p.generated.count), (4, 4));
}

#[test]
fn two_independent_symmetries_are_both_folded() {
    // x^2 - a, y^2 + b y z + c z^2 - d, y z - e: {x} and {y, z}: 2 x 4 solutions, in
    // groups of four.
    let src = "problem two
unknown x, y, z
data a: scalar, b: scalar, c: scalar, d: scalar, e: scalar
x^2 - a = 0
y^2 + b*y*z + c*z^2 - d = 0
y*z - e = 0
";
    let p = planned(src);
    assert_eq!(p.problem.sign_folds().len(), 2);
    assert_eq!((p.solution_count(), p.generated.count), (8, 2));
    let r = audited(&p);
    assert_eq!(r.failures, 0, "{r}");
    let plain = audited(&planned(&format!("{src}option sign_symmetry = no\n")));
    assert!((r.mean_real_solutions - plain.mean_real_solutions).abs() < 1e-9);
}

#[test]
fn a_hidden_unknown_of_the_symmetry_is_scaled_but_not_returned() {
    // `nonzero d[0]` adds u with u d1 = 1: the symmetry flips u with the depths.
    let p = planned(&format!("{}\nnonzero d[0]\n", p3p()));
    let folds = p.problem.sign_folds();
    assert_eq!(folds.len(), 1);
    assert_eq!(
        (folds[0].pivot, folds[0].scaled.as_slice()),
        (0, &[1, 2, 3][..])
    );
    assert_eq!((p.solution_count(), p.generated.count), (8, 4));
    let r = audited(&p);
    assert_eq!(r.failures, 0, "{r}");
    // The emitted unfolding touches the declared unknowns only.
    let code = emit_plan_from(&p, "t.mp").unwrap();
    assert!(code.contains("= [(0, &[1, 2])];"), "{code}");
}

#[test]
fn every_pivot_of_a_fold_is_searched_and_the_smallest_template_kept() {
    // The pivot shapes the folded system (the others become `t_j / t_p`), and with it the
    // template: the upright relative pose folds to 38x42 by t1, the first pivot declared,
    // and to 32x36 by t2. The plan must search both and keep t2's.
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../templates/classic/relpose_upright_3pt.mp");
    let p = planned(&std::fs::read_to_string(file).unwrap());
    let folds = p.problem.sign_folds();
    assert_eq!(folds.len(), 1, "folded");
    // c, s come first: variable 3 is t2.
    assert_eq!(folds[0].pivot, 3, "folded by t2");
    assert_eq!(p.generated.built.template.elimination_area(), 32 * 36);
    let r = audited(&p);
    assert_eq!(r.failures, 0, "{r}");
}
