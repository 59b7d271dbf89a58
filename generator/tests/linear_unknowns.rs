//! Planning without being told: unknowns that appear only linearly with data coefficients
//! are eliminated and unknowns fixed by affine equations substituted (when that keeps the
//! solutions), equations that are linear combinations of others are dropped, and names
//! that differ only in case give distinct fields.

use mingen::Problem;
use mingen::ProblemOptions;
use mingen::TemplateOptions;
use mingen::{emit_plan_from, plan, SolverPlan};

fn planned(src: &str, opts: &TemplateOptions) -> SolverPlan {
    let problem = Problem::parse(src, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    plan(problem, "t.mp", opts).unwrap_or_else(|e| panic!("{e}"))
}

fn eliminated(p: &SolverPlan) -> Vec<String> {
    p.eliminated_names()
}

fn audit_median(p: &SolverPlan) -> f64 {
    let a = mingen::__internal::audit::audit_plan(
        p,
        &mingen::__internal::audit::AuditOptions {
            instances: 200,
            seed: 7,
            ..Default::default()
        },
    );
    assert_eq!(a.failures, 0, "{a}");
    a.median_log10_residual
}

/// The upright 2-point absolute pose, written with all three rows of each cross product
/// (the third is a combination of the other two), the yaw as (cos, sin): every equation
/// but `c^2 + s^2 = 1` is affine in (c, s, t).
const UP2P: &str = "problem up2p_plain
unknown c, s, t[3]
data pw[2]: vec3, x[2]: point
let R = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
for i in 0..2 {
  skew(x[i]) * (R * pw[i] + t) = 0 * t
}
c*c + s*s = 1
";

/// The same with the yaw as a half-angle tangent (a scaled rotation): the equations are
/// quadratic in s, and t appears only in terms `data * t`.
const UP2P_TAN: &str = "problem up2p_tan
unknown s, t[3]
data pw[2]: vec3, x[2]: point
let R = [[1 - s*s, 0, 2*s], [0, 1 + s*s, 0], [-2*s, 0, 1 - s*s]]
for i in 0..2 {
  skew(x[i]) * (R * pw[i] + t) = 0 * t
}
";

#[test]
fn a_translation_that_appears_only_linearly_is_eliminated_automatically() {
    let opts = TemplateOptions::default();
    let auto = planned(UP2P_TAN, &opts);
    assert_eq!(eliminated(&auto), ["t1", "t2", "t3"]);
    assert!(auto.problem.substitution().is_none());
    let (rows, cols) = auto.generated.built.template.eliminated_size();
    // Kept: the same count, a larger template.
    let kept = planned(&format!("{UP2P_TAN}option auto_eliminate = no\n"), &opts);
    assert!(eliminated(&kept).is_empty());
    assert_eq!(kept.generated.count, auto.generated.count);
    let (krows, kcols) = kept.generated.built.template.eliminated_size();
    assert!(
        rows * cols < krows * kcols,
        "{rows}x{cols} vs {krows}x{kcols}"
    );
    assert!(audit_median(&auto) < -12.0);
    // The command line overrides the file either way.
    let off = TemplateOptions {
        overrides: ProblemOptions {
            auto_eliminate: Some(false),
            ..ProblemOptions::default()
        },
        ..TemplateOptions::default()
    };
    assert!(eliminated(&planned(UP2P_TAN, &off)).is_empty());
    // The emitted solver still returns every declared unknown.
    let code = emit_plan_from(&auto, "t.mp").unwrap();
    assert!(code.contains("pub const UNKNOWNS: usize = 4;"));
}

#[test]
fn affine_equations_with_dependent_rows_are_substituted() {
    // Six affine equations of rank four: four unknowns solved from four of them, the
    // other two implied and left out, c^2 + s^2 = 1 left in c.
    let p = planned(UP2P, &TemplateOptions::default());
    assert_eq!(eliminated(&p), ["s", "t1", "t2", "t3"]);
    let (used, implied) = p.problem.substitution().unwrap();
    assert_eq!((used.len(), implied.len()), (4, 2));
    assert_eq!(p.generated.count, 2);
    assert_eq!(p.generated.built.template.eliminated_size(), (1, 3));
    assert!(audit_median(&p) < -12.0);
}

#[test]
fn affine_equations_are_substituted_and_a_homogeneous_unknown_keeps_both_signs() {
    // The epipolar constraints with a known rotation are linear and homogeneous in t.
    // Minors would identify t and -t; instead two of t1, t2, t3 are solved from them by
    // Cramer's rule and substituted into t't = 1, which keeps both solutions. That leaves
    // an equation even in t1: the plan folds it (`t1^2` one solution) and the solver
    // recovers both signs.
    let src = "problem kr
unknown t[3]
data x1[2]: point, x2[2]: point, R: rotation
for i in 0..2 {
  x2[i]' * skew(t) * R * x1[i] = 0
}
t' * t = 1
";
    let opts = TemplateOptions::default();
    let p = planned(src, &opts);
    assert_eq!(eliminated(&p), ["t2", "t3"]);
    assert_eq!(p.problem.substitution(), Some((&[0, 1][..], &[][..])));
    assert_eq!((p.solution_count(), p.generated.count), (2, 1));
    assert_eq!(p.problem.sign_folds().len(), 1);
    assert_eq!(p.generated.built.template.eliminated_size(), (1, 2));
    assert!(audit_median(&p) < -13.0);
    let unfolded = planned(&format!("{src}option sign_symmetry = no\n"), &opts);
    assert_eq!(unfolded.generated.count, 2);
    assert_eq!(unfolded.generated.built.template.eliminated_size(), (1, 3));
    assert!(audit_median(&unfolded) < -13.0);
    let kept = planned(&format!("{src}option auto_eliminate = no\n"), &opts);
    assert!(eliminated(&kept).is_empty());
    assert_eq!(kept.solution_count(), 2);
    // The five-point problem on the entries of E: five entries substituted, the
    // published 10x20.
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../templates/classic/relpose_5pt_entries.mp");
    let p = planned(&std::fs::read_to_string(file).unwrap(), &opts);
    assert_eq!(eliminated(&p), ["e4", "e5", "e6", "e7", "e8"]);
    assert_eq!(p.generated.count, 10);
    assert_eq!(p.generated.built.template.eliminated_size(), (10, 20));
    assert!(audit_median(&p) < -13.0);
}

#[test]
fn dependent_equations_are_dropped_and_the_solutions_kept() {
    // After the automatic elimination of t the 15 maximal minors of the 6 x 4 matrix
    // [A b] (A of data only, rank 3) are multiples of one: of the three left null vectors
    // of A, two are x_i' (x_i × ·), which annihilate b as well.
    let p = planned(UP2P_TAN, &TemplateOptions::default());
    let kept = p
        .problem
        .independent()
        .expect("dependent equations dropped");
    assert_eq!(kept.len(), 1, "{kept:?}");
    assert_eq!(p.generated.count, 2);
    // Without elimination the third rows of the cross products go, the other four stay
    // with c^2 + s^2 = 1.
    let plain = planned(
        &format!("{UP2P}option auto_eliminate = no\n"),
        &TemplateOptions::default(),
    );
    assert_eq!(plain.problem.independent().map(<[usize]>::len), Some(5));
    assert_eq!(plain.generated.count, 2);
    assert!(audit_median(&plain) < -12.0);
}

#[test]
fn names_that_differ_only_in_case_are_distinct_fields() {
    // x (image points) and X (world points), as users write them.
    let src = "problem p2p_known_rotation
unknown t[3]
data x[2]: point, X[2]: vec3, R: rotation
for i in 0..2 {
  let P = R*X[i] + t
  x[i][1]*P[2] - P[1] = 0
}
let P0 = R*X[0] + t
P0[0] - x[0][0]*P0[2] = 0
";
    let p = planned(src, &TemplateOptions::default());
    // Three unknowns, all linear: nothing would be left, so nothing is eliminated.
    assert!(eliminated(&p).is_empty());
    assert_eq!(p.generated.count, 1);
    let code = emit_plan_from(&p, "t.mp").unwrap();
    assert!(code.contains("pub x: [[f64; 2]; 2],"), "{code}");
    assert!(code.contains("pub X: [[f64; 3]; 2],"));
    assert!(code.contains("#[allow(non_snake_case)]"));
    syn::parse_file(&code).expect("the emitted code parses");
}

#[test]
fn data_only_coefficients_are_factored_once_per_instance() {
    // `eliminate t` of the upright 2-point pose: t's coefficients are data (skew(x)), so
    // the solver factors them once and solves per solution; the upright relative pose's
    // translation has coefficients in (c, s): a null vector per solution.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let opts = TemplateOptions::default();
    let up2p = mingen::plan_file(&root.join("templates/classic/up2p_elim.mp"), &opts).unwrap();
    let source = emit_plan_from(&up2p, "up2p_elim.mp").unwrap();
    let compact: String = source.split_whitespace().collect();
    assert!(
        compact.contains("mingen_runtime::LeastSquares::<6,3,>::new("),
        "{source}"
    );
    assert!(compact.contains("elim_ls.solve("));
    assert!(!source.contains("null_vector"));
    // The interpreter recovers t the same way: the audit's residuals are at rounding level.
    assert!(audit_median(&up2p) < -14.0);
    let upright = mingen::plan_file(
        &root.join("templates/classic/relpose_upright_3pt_elim.mp"),
        &opts,
    )
    .unwrap();
    let source = emit_plan_from(&upright, "relpose_upright_3pt_elim.mp").unwrap();
    assert!(!source.contains("LeastSquares"));
    assert!(source.contains("null_vector"));
}
