//! `eliminate` through the data row reduction of the block of equations linear in the
//! eliminated unknowns (`mingen::__internal::eliminate::reduce_block`), as the worksheets
//! of Martyushev et al. row-reduce their coefficient matrices: where the block's maximal
//! minors would add a spurious component (dependent data rows) or cannot be formed (the
//! eliminated unknowns enter another equation non-linearly), the solutions stay those of
//! the system as written, and the solver recovers the eliminated unknowns.

use mingen::__internal::audit::{audit_plan, audit_plan_planted, AuditOptions};
use mingen::__internal::eliminate::BlockMode;
use mingen::{plan, plan_file, Problem, SolverPlan, TemplateOptions};
use std::path::Path;

fn planned(src: &str) -> SolverPlan {
    let problem = Problem::parse(src, "t.mp").unwrap_or_else(|e| panic!("{e}"));
    plan(problem, "t.mp", &TemplateOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn mode(p: &SolverPlan) -> Option<BlockMode> {
    p.problem.block_reduction().map(|b| b.mode)
}

/// Two equations linear in `t` through the columns `t x` and `t`, and one quadratic in
/// `t`: the minors of the block cannot take the third, substitution can.
const SUBSTITUTED: &str = "problem substituted
unknown t, x, y
data a: vec3, b: vec3, c: vec3, d: vec3
(a[0]*x + a[1])*t + a[2]*x^2 + b[0]*y + b[1] = 0
(c[0]*x + c[1])*t + c[2]*y^2 + b[2]*x + d[0] = 0
t^2 + d[1]*x*y + d[2]*t + 1 = 0
";

#[test]
fn substitution_keeps_the_solutions_of_the_system_as_written() {
    let written = planned(SUBSTITUTED);
    let eliminated =
        planned(&SUBSTITUTED.replace("unknown t, x, y\n", "unknown t, x, y\neliminate t\n"));
    assert_eq!(mode(&written), None);
    assert_eq!(mode(&eliminated), Some(BlockMode::Substitute));
    assert_eq!(eliminated.eliminated_names(), vec!["t".to_string()]);
    assert_eq!(eliminated.solution_count(), written.solution_count());
    let report = audit_plan(
        &eliminated,
        &AuditOptions {
            instances: 200,
            seed: 3,
            ..Default::default()
        },
    );
    // The residual is taken on the equations as written, `t` recovered from the block.
    assert!(report.failures <= 2, "{report}");
    assert!(report.median_log10_residual < -10.0, "{report}");
}

/// The refraction problem of the benchmark: the five rows are linear in the centre
/// `(v, w)` through sixteen columns of rank three, so two combinations of rows are free
/// of it and the minors of all five rows vanish on a curve.
#[test]
fn dependent_rows_give_the_published_count_and_recover_planted_poses() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/benchmark/refract5p.mp");
    let p = plan_file(&path, &TemplateOptions::default()).expect("plans");
    assert_eq!(mode(&p), Some(BlockMode::Minors));
    let b = p.problem.block_reduction().expect("a block reduction");
    assert_eq!((b.columns.len(), b.pivot_rows.len()), (16, 3));
    assert_eq!(p.solution_count(), 16);
    assert_eq!(p.visible_unknowns(), 5);

    // Planted poses: the scene point X_k seen through the unnormalised Cayley rotation
    // Rn of (x, y, z) from the centre c = (v, w, 0) along xx_k = Rn (X_k - c).
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut uniform = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let (mut instances, mut solutions) = (Vec::new(), Vec::new());
    for _ in 0..100 {
        let s: Vec<f64> = (0..5).map(|_| uniform()).collect();
        let (v, w, x, y, z) = (s[0], s[1], s[2], s[3], s[4]);
        let rn = [
            [
                x * x - y * y - z * z + 1.0,
                2.0 * (x * y + z),
                2.0 * (x * z - y),
            ],
            [
                2.0 * (x * y - z),
                -x * x + y * y - z * z + 1.0,
                2.0 * (y * z + x),
            ],
            [
                2.0 * (x * z + y),
                2.0 * (y * z - x),
                -x * x - y * y + z * z + 1.0,
            ],
        ];
        let (mut xx, mut big_x) = (Vec::new(), Vec::new());
        for _ in 0..5 {
            let p = [2.0 * uniform(), 2.0 * uniform(), 2.0 * uniform() + 4.0];
            let d = [p[0] - v, p[1] - w, p[2]];
            let scale = uniform() + 2.0;
            for row in &rn {
                xx.push(scale * (row[0] * d[0] + row[1] * d[1] + row[2] * d[2]));
            }
            big_x.extend(p);
        }
        xx.extend(big_x);
        instances.push(xx);
        solutions.push(s);
    }
    let report = audit_plan_planted(&p, &instances, Some(&solutions));
    let planted = report.planted.as_ref().expect("planted solutions");
    assert!(planted.recovered >= 95, "{report}");
}

/// The refractive pose with unknown focal length: the solved rows cleared of the free
/// rows' pivot monomials give the worksheet's four equations on 27 monomials (its `4x27`
/// coefficient matrix), solved through their row reduction; the system is even or odd in
/// `w, x, y` and folds, by `x` or `y`, to a template far smaller than the one as written
/// (144x180), which folding by `w`, the first pivot declared, does not. A regression
/// guard on both choices (its size is recorded in the file too, for
/// `tools/benchmark_record.py --check`).
#[test]
fn refraction_with_focal_length_has_the_worksheet_support_and_folds_by_its_best_pivot() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/benchmark/p6pf_refract.mp");
    let p = plan_file(&path, &TemplateOptions::default()).expect("plans");
    assert_eq!(mode(&p), Some(BlockMode::Minors));
    assert_eq!(p.solution_count(), 36);
    let folds = p.problem.sign_folds();
    assert_eq!(folds.len(), 1, "folded");
    let by = p.sign_symmetry_description().unwrap_or_default();
    assert!(!by.contains("folded by w"), "{by}");
    let t = &p.generated.built.template;
    assert_eq!(t.reduction_size(), Some((4, 27)));
    assert!(
        t.elimination_area() <= 65 * 83 + 4 * 27,
        "{:?}",
        t.eliminated_size()
    );
}
