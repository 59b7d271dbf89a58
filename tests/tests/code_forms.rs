//! The table form of emitted solvers (`mingen::CodeForm::Table`, the form large
//! templates get) computes the same bits as the inline form: both solvers of each problem
//! run on the same random data and must return identical solutions. For
//! `relpose_upright_3pt` that also holds the inline form's fold of the constant rows,
//! written out as code, to the runtime's `fold_constant_rows`, which the table form calls.

use mingen_runtime::{FlatValues, MinimalSolver};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use workspace_tests as ex;

/// Solves `instances` random data vectors (entries uniform in [-1, 1]) with both solvers and
/// returns the number of solutions found; panics at the first difference.
fn same_solutions<A: MinimalSolver, B: MinimalSolver>(seed: u64, instances: usize) -> usize {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut found = 0;
    for i in 0..instances {
        let flat: Vec<f64> = (0..A::Data::LEN)
            .map(|_| rng.gen_range(-1.0..1.0))
            .collect();
        let (a, b) = (
            A::Data::from_flat(&flat).expect("slot count"),
            B::Data::from_flat(&flat).expect("same layout"),
        );
        let sa: Vec<Vec<f64>> = A::solve(&a)
            .as_ref()
            .iter()
            .map(|s| s.to_flat_vec())
            .collect();
        let sb: Vec<Vec<f64>> = B::solve(&b)
            .as_ref()
            .iter()
            .map(|s| s.to_flat_vec())
            .collect();
        let bits = |s: &[Vec<f64>]| -> Vec<Vec<u64>> {
            s.iter()
                .map(|v| v.iter().map(|x| x.to_bits()).collect())
                .collect()
        };
        assert_eq!(
            bits(&sa),
            bits(&sb),
            "instance {i}: inline {sa:?}, table {sb:?}"
        );
        found += sa.len();
    }
    found
}

#[test]
fn p35pf_table_form_is_bit_identical() {
    let found = same_solutions::<ex::inline::p35pf::Solver, ex::table::p35pf::Solver>(31, 300);
    assert!(
        found > 300,
        "random instances have real solutions ({found})"
    );
}

#[test]
fn relpose_5pt_entries_table_form_is_bit_identical() {
    let found = same_solutions::<
        ex::inline::relpose_5pt_entries::Solver,
        ex::table::relpose_5pt_entries::Solver,
    >(32, 300);
    assert!(
        found > 300,
        "random instances have real solutions ({found})"
    );
}

#[test]
fn relpose_upright_3pt_fold_written_out_is_bit_identical() {
    let found = same_solutions::<
        ex::inline::relpose_upright_3pt::Solver,
        ex::table::relpose_upright_3pt::Solver,
    >(33, 2000);
    assert!(
        found > 2000,
        "random instances have real solutions ({found})"
    );
}
