//! Shared by the workspace tests: the emitted solvers behind one flat, slot-based interface,
//! and the shipped problem files.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// One emitted solver (`rspose::generated::<name>`) seen through its flat forms:
/// `Data::from_slots` in, `Solution::to_unknowns` out.
pub struct Emitted {
    /// Module name = problem name.
    pub name: &'static str,
    /// `Data::SLOTS`.
    pub slots: usize,
    /// `Solution::UNKNOWNS`.
    pub unknowns: usize,
    /// `MAX_SOLUTIONS`.
    pub max_solutions: usize,
    /// `solve(&Data::from_slots(d))`, each solution as `to_unknowns()`.
    pub solve: fn(&[f64]) -> Vec<Vec<f64>>,
    /// `Data::from_slots(d).to_slots()`.
    pub round_trip: fn(&[f64]) -> Vec<f64>,
}

macro_rules! emitted {
    ($($m:ident),* $(,)?) => {
        vec![$({
            use rspose::generated::$m as m;
            Emitted {
                name: stringify!($m),
                slots: m::Data::SLOTS,
                unknowns: m::Solution::UNKNOWNS,
                max_solutions: m::MAX_SOLUTIONS,
                solve: |d: &[f64]| {
                    let slots: [f64; m::Data::SLOTS] =
                        d.try_into().expect("one value per data slot");
                    m::solve(&m::Data::from_slots(&slots))
                        .iter()
                        .map(|s| s.to_unknowns().to_vec())
                        .collect()
                },
                round_trip: |d: &[f64]| {
                    let slots: [f64; m::Data::SLOTS] =
                        d.try_into().expect("one value per data slot");
                    m::Data::from_slots(&slots).to_slots().to_vec()
                },
            }
        }),*]
    };
}

/// Every module of `rspose::generated`, in name order.
pub fn emitted_solvers() -> Vec<Emitted> {
    emitted!(grsrp, grsrp10, grsrp_gravity, gs5pt)
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
    mingen::generate::problem_files(root())
        .expect("templates/ is readable")
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
