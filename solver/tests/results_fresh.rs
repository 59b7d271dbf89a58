//! The committed experiment results (`results/`, paper preset, and `results/default/`,
//! library defaults) were produced by the current numerics: for every sweep, two trials of
//! every level are re-run and must reproduce their lines of `SWEEP-trials.csv` exactly, and
//! `SWEEP.csv` must be the summary of `SWEEP-trials.csv` (all but the timing column).
//! After a change to the numerics, regenerate with
//! `rspose experiment SWEEP --trials 100 --out results` and
//! `rspose experiment SWEEP --trials 100 --out results/default --preset default`.

use rspose::experiment::{
    scene_trial, summarize_levels, to_csv, trial_line, trial_seed, MethodOutcome, Sweep,
};
use rspose::methods::Preset;
use rspose::{EstimateOptions, Method};
use std::path::Path;

const SEED: u64 = 2024;
const TRIALS: usize = 100;
const SWEEPS: [Sweep; 6] = Sweep::ALL;

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn options(preset: Preset, m: Method, seed: u64) -> EstimateOptions {
    let mut o = preset.options(m);
    o.robust.seed = seed;
    o
}

fn without_timing(csv: &str) -> Vec<String> {
    csv.lines()
        .map(|l| {
            let mut f: Vec<&str> = l.split(',').collect();
            f.remove(8);
            f.join(",")
        })
        .collect()
}

fn parse_outcome(line: &str) -> (usize, MethodOutcome) {
    let f: Vec<&str> = line.split(',').collect();
    let num = |s: &str| (!s.is_empty()).then(|| s.parse::<f64>().unwrap());
    (
        f[1].parse().unwrap(),
        MethodOutcome {
            method: f[2].to_string(),
            rotation_error_deg: num(f[3]),
            translation_error_deg: num(f[4]),
            seconds: 0.0,
            inliers: (!f[5].is_empty()).then(|| f[5].parse().unwrap()),
        },
    )
}

fn check(dir: &Path, preset: Preset) {
    let methods = Method::ALL;
    for sweep in SWEEPS {
        let trials = read(&dir.join(format!("{}-trials.csv", sweep.name())));
        let lines: Vec<&str> = trials.lines().skip(1).collect();
        let levels = sweep.levels();
        // Every method, and the sweep's variants (`rectified+k`).
        let per_trial = methods.len() + usize::from(levels[0].compare_readout_refinement);
        assert_eq!(lines.len(), levels.len() * TRIALS * per_trial, "{sweep:?}");
        // Re-run two trials of every level.
        for (li, level) in levels.iter().enumerate() {
            for ti in [0, TRIALS - 1] {
                let seed = trial_seed(SEED, li, ti);
                let outcomes = scene_trial(level, seed, &methods, |m| options(preset, m, seed));
                assert_eq!(outcomes.len(), per_trial, "{sweep:?}");
                for (k, o) in outcomes.iter().enumerate() {
                    let at = (li * TRIALS + ti) * per_trial + k;
                    assert_eq!(
                        trial_line(level.value, ti, o).trim_end(),
                        lines[at],
                        "{}: {sweep:?} level {li} trial {ti} is stale",
                        dir.display()
                    );
                }
            }
        }
        // The summary is the summary of those trials.
        let mut outcomes: Vec<Vec<MethodOutcome>> = vec![Vec::new(); levels.len() * TRIALS];
        for (i, line) in lines.iter().enumerate() {
            let (trial, o) = parse_outcome(line);
            outcomes[(i / (TRIALS * per_trial)) * TRIALS + trial].push(o);
        }
        let summary = to_csv(&summarize_levels(&levels, TRIALS, &outcomes));
        assert_eq!(
            without_timing(&summary),
            without_timing(&read(&dir.join(format!("{}.csv", sweep.name())))),
            "{}: {}.csv is not the summary of its trials",
            dir.display(),
            sweep.name()
        );
    }
}

#[test]
fn committed_paper_preset_results_are_fresh() {
    check(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../results"),
        Preset::Paper,
    );
}

#[test]
fn committed_default_preset_results_are_fresh() {
    check(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../results/default"),
        Preset::Default,
    );
}

/// The experiment tables of `docs/EXPERIMENTS.md` are those the committed summaries give
/// (as `tools/readme_tables.py` prints them).
#[test]
fn readme_tables_come_from_the_committed_results() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let readme = read(&root.join("docs/EXPERIMENTS.md"));
    for dir in ["results", "results/default"] {
        for sweep in SWEEPS {
            let csv = read(&root.join(dir).join(format!("{}.csv", sweep.name())));
            let rows: Vec<Vec<&str>> = csv
                .lines()
                .skip(1)
                .map(|l| l.split(',').collect())
                .collect();
            // Levels and methods (and variants such as `rectified+k`) in the file's order.
            let (mut levels, mut methods): (Vec<&str>, Vec<&str>) = (Vec::new(), Vec::new());
            for r in &rows {
                if !levels.contains(&r[0]) {
                    levels.push(r[0]);
                }
                if !methods.contains(&r[1]) {
                    methods.push(r[1]);
                }
            }
            let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
            assert_eq!(
                methods[..names.len()],
                names[..],
                "{dir}/{}.csv",
                sweep.name()
            );
            for level in levels {
                let cells: Vec<String> = methods
                    .iter()
                    .map(|m| {
                        let r = rows.iter().find(|r| r[0] == level && r[1] == *m).unwrap();
                        let f = |s: &str| s.parse::<f64>().unwrap();
                        format!("{:.2} / {:.2}", f(r[2]), f(r[5]))
                    })
                    .collect();
                let line = format!("| {level} | {} |", cells.join(" | "));
                assert!(
                    readme.contains(&line),
                    "docs/EXPERIMENTS.md lacks `{line}` ({dir}/{}.csv); run tools/readme_tables.py {dir}",
                    sweep.name()
                );
            }
        }
    }
}
