//! Small templates are eliminated by straight-line code written out along their structure
//! (`EliminationTemplate::unrolled`, `mingen`'s `emit/unrolled.rs`). On random data its
//! result must be the runtime's dense LU with partial pivoting on the same filled
//! template, value for value, on the rows the action matrix reads: the emitted solver is
//! observed between its stages (`mingen_runtime::Stages`), and its filled template is
//! reduced again by `mingen_runtime::lu_solve_template`.

use mingen_runtime::{FlatValues, MinimalSolver, Stages};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use workspace_tests::corpus;

/// The template before and after the solver's elimination (empty if not reached).
#[derive(Default)]
struct Capture {
    filled: Vec<f64>,
    eliminated: Vec<f64>,
}

impl Stages for Capture {
    fn filled(&mut self, template: &[f64]) -> bool {
        self.filled = template.to_vec();
        true
    }
    fn eliminated(&mut self, template: &[f64]) -> bool {
        self.eliminated = template.to_vec();
        false
    }
}

/// Compares the solver's elimination with the dense LU on `instances` random data vectors
/// (entries uniform in [-1, 1]); returns how many were eliminated. Panics at the first
/// difference.
fn eliminates_as_the_dense_lu<S: MinimalSolver>(name: &str, instances: usize) -> usize {
    let [rows, cols, pivots, first] = S::TEMPLATE_SHAPE;
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut eliminated = 0;
    for i in 0..instances {
        let flat: Vec<f64> = (0..S::Data::LEN)
            .map(|_| rng.gen_range(-1.0..1.0))
            .collect();
        let data = S::Data::from_flat(&flat).expect("slot count");
        let mut seen = Capture::default();
        let _ = S::solve_staged(&data, &mut seen);
        if seen.filled.is_empty() {
            continue;
        }
        assert_eq!(seen.filled.len(), rows * cols, "{name}");
        let mut dense = seen.filled.clone();
        let ok = mingen_runtime::lu_solve_template(&mut dense, rows, cols, pivots, first);
        assert_eq!(ok, !seen.eliminated.is_empty(), "{name}, instance {i}");
        if !ok {
            continue;
        }
        eliminated += 1;
        for r in first..pivots {
            let row = r * cols..(r + 1) * cols;
            // `==`: the same values (a zero's sign may differ, a zero multiplier is not
            // skipped by the written-out code).
            assert!(
                seen.eliminated[row.clone()] == dense[row.clone()],
                "{name}, instance {i}, row {r}:\n{:?}\n{:?}",
                &seen.eliminated[row.clone()],
                &dense[row]
            );
        }
    }
    eliminated
}

macro_rules! written_out {
    ($($problem:ident),*) => {
        $(
            #[test]
            fn $problem() {
                let n = eliminates_as_the_dense_lu::<corpus::$problem::Solver>(
                    stringify!($problem),
                    400,
                );
                assert!(n >= 300, "{}: {n} of 400 eliminated", stringify!($problem));
            }
        )*
    };
}

// Templates of each kind of structure: sparse with fill-in (`p3p`, `gp3p`,
// `relpose_6pt_focal`), from reduced equations (`p3p`), dense (`relpose_5pt`), tiny
// (`up2p_elim`). `mingen`'s `tests/sparse_elimination.rs` checks that they are written out.
written_out!(
    p3p,
    gp3p,
    up2p,
    up2p_elim,
    relpose_5pt,
    relpose_6pt_focal,
    relpose_known_rotation_2pt,
    grsrp_gravity_lin
);
