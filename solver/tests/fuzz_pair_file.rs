//! Seeded mutation fuzzing of the pair file: mutated copies of a simulated pair and of a
//! real recording's pair are parsed, validated and estimated; none may panic, every refusal
//! is one bounded line that says where, and the whole run stays within a few seconds
//! (`rspose::data::mutate`; the table of outcomes is `docs/ROBUSTNESS.md`).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rspose::data::mutate::{case, run_case, Outcome};
use rspose::{simulate, SimulationOptions};
use serde_json::Value;
use std::time::{Duration, Instant};

/// Cases per base file: enough to reach every mutation a few times on every method.
const CASES: usize = 200;

fn bases() -> Vec<(&'static str, Value)> {
    let sim = simulate(&SimulationOptions {
        seed: 7,
        ..Default::default()
    })
    .expect("simulated pair");
    let real = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/cc9pro/pair-100-101.json"
    ))
    .expect("real pair");
    vec![
        (
            "simulated",
            serde_json::from_str(&sim.to_json_string()).unwrap(),
        ),
        ("cc9pro", serde_json::from_str(&real).unwrap()),
    ]
}

#[test]
fn mutated_pair_files_never_panic_and_every_refusal_says_where() {
    let start = Instant::now();
    for (name, base) in bases() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        for i in 0..CASES {
            let (mutations, text, method) = case(&base, i, &mut rng);
            let outcome = run_case(&text, method);
            assert!(
                !matches!(outcome, Outcome::Panicked(_)),
                "{name} case {i} ({mutations:?}, {method}): {outcome:?}"
            );
            assert!(
                outcome.message_ok(),
                "{name} case {i} ({mutations:?}, {method}): {outcome:?}"
            );
        }
    }
    assert!(
        start.elapsed() < Duration::from_secs(30),
        "the run took {:?}",
        start.elapsed()
    );
}
