//! Shared by the workspace tests: the emitted solvers behind one flat, slot-based interface,
//! and the shipped problem files.
#![allow(dead_code)]

use mingen_runtime::{FlatValues, MinimalSolver};
use std::path::{Path, PathBuf};

/// One emitted solver (`rspose::generated::<name>::Solver`) seen through its flat forms
/// (`mingen_runtime::FlatValues`): data slots in, unknowns out.
pub struct Emitted {
    /// Module name = problem name.
    pub name: &'static str,
    /// Number of data slots.
    pub slots: usize,
    /// Number of scalar unknowns.
    pub unknowns: usize,
    /// `MAX_SOLUTIONS`.
    pub max_solutions: usize,
    /// The solutions of the data with these slots, each as its unknowns.
    pub solve: fn(&[f64]) -> Vec<Vec<f64>>,
    /// The data from these slots, back in flat form.
    pub round_trip: fn(&[f64]) -> Vec<f64>,
}

/// The flat view of the solver type `S`.
fn flat<S: MinimalSolver>() -> Emitted {
    Emitted {
        name: S::NAME,
        slots: <S::Data as FlatValues>::LEN,
        unknowns: <S::Solution as FlatValues>::LEN,
        max_solutions: S::MAX_SOLUTIONS,
        solve: |d: &[f64]| {
            let data = S::Data::from_flat(d).expect("one value per data slot");
            S::solve(&data)
                .as_ref()
                .iter()
                .map(FlatValues::to_flat_vec)
                .collect()
        },
        round_trip: |d: &[f64]| {
            S::Data::from_flat(d)
                .expect("one value per data slot")
                .to_flat_vec()
        },
    }
}

/// Every module of `rspose::generated`, in name order.
pub fn emitted_solvers() -> Vec<Emitted> {
    use rspose::generated::{grsrp, grsrp10, grsrp_gravity, grsrp_gravity6, gs5pt};
    vec![
        flat::<grsrp::Solver>(),
        flat::<grsrp10::Solver>(),
        flat::<grsrp_gravity::Solver>(),
        flat::<grsrp_gravity6::Solver>(),
        flat::<gs5pt::Solver>(),
    ]
}

/// The emitted solver of problem `name`.
pub fn emitted(name: &str) -> Emitted {
    emitted_solvers()
        .into_iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("no emitted solver `{name}` in tests/tests/common/mod.rs"))
}

/// The workspace root.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
}

/// `templates/<name>.mp`.
pub fn problem_file(name: &str) -> PathBuf {
    root().join("templates").join(format!("{name}.mp"))
}

/// The names of the shipped problems (`templates/*.mp`), sorted.
pub fn shipped_problems() -> Vec<String> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("templates"))
        .expect("templates/ is readable")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "mp"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| {
            mingen::Problem::from_file(f)
                .expect("shipped problem parses")
                .layout
                .name
        })
        .collect()
}

/// Every shipped problem has an emitted solver listed in [`emitted_solvers`].
pub fn assert_all_emitted_listed() {
    let listed: Vec<&str> = emitted_solvers().iter().map(|e| e.name).collect();
    for p in shipped_problems() {
        assert!(
            listed.contains(&p.as_str()),
            "problem `{p}` is shipped but its solver is not listed in tests/tests/common/mod.rs"
        );
    }
}
