//! The fold of a template's rows with constant pivots (`template/fold.rs`) against an
//! independent Schur complement: the folded matrix the interpreter (and the emitted
//! solvers, `tests/tests/agreement.rs`) eliminates equals `M22 - M21 M11⁻¹ M12` computed by
//! nalgebra's LU from the whole filled template, and `M11`'s determinant is the same on
//! every instance (a number, so no instance makes the fold singular).

use mingen::__internal::instance::random_data_f64;
use mingen::__internal::interpret::fill_template;
use mingen::__internal::template::TemplateOptions;
use mingen::plan_file;
use nalgebra::DMatrix;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

fn template_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../templates/{name}.mp"))
}

/// Checks the fold of `name`'s template on random instances; returns (constant block
/// rows, pivot rows).
fn fold_is_the_schur_complement(name: &str) -> (usize, usize) {
    let plan = plan_file(&template_path(name), &TemplateOptions::default()).unwrap();
    let t = &plan.generated.built.template;
    let f = t.fold.as_ref().expect("the template has a fold");
    let k = t.folded_rows();
    let mut whole_t = t.clone();
    whole_t.fold = None;
    whole_t.sparse = None;
    let (rows, cols) = t.filled_size();
    let (er, ec) = t.eliminated_size();
    assert_eq!((er + k, ec + k), (rows, cols));
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut det0: Option<f64> = None;
    for _ in 0..20 {
        let data = random_data_f64(&plan.problem.layout, &mut rng);
        let (equations, _) = plan.equations(&data);
        let whole =
            DMatrix::from_row_slice(rows, cols, &fill_template(&whole_t, &equations).unwrap());
        let folded = DMatrix::from_row_slice(er, ec, &fill_template(t, &equations).unwrap());
        let m11 = whole.view((0, 0), (k, k)).into_owned();
        let det = m11.determinant();
        match det0 {
            None => det0 = Some(det),
            Some(d) => assert!(
                (det - d).abs() <= 1e-9 * d.abs(),
                "{name}: det {det} vs {d}"
            ),
        }
        assert!(det.abs() > 1e-12, "{name}: singular M11");
        let x = m11
            .lu()
            .solve(&whole.view((0, k), (k, ec)).into_owned())
            .expect("M11 invertible");
        let complement = whole.view((k, k), (er, ec)) - whole.view((k, 0), (er, k)) * x;
        let scale = complement.amax().max(1.0);
        let err = (&complement - &folded).amax();
        assert!(
            err <= 1e-9 * scale,
            "{name}: complement differs by {err} (scale {scale})"
        );
    }
    (f.rows, f.pivot_inv.len())
}

#[test]
fn triangular_fold_of_4pra_is_the_schur_complement() {
    let (_, pivots) = fold_is_the_schur_complement("benchmark/4pra");
    assert!(
        pivots > 0,
        "4pra's multiples of u² + v² + w² + s² - 1 pivot in a triangle"
    );
}

#[test]
fn constant_fold_of_grsrp_gravity_is_the_schur_complement() {
    let (block, _) = fold_is_the_schur_complement("grsrp_gravity");
    assert!(block > 0);
}
