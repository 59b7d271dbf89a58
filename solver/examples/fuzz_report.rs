//! The outcome table of the pair-file mutation fuzzing (`docs/ROBUSTNESS.md`):
//! `cargo run --release -p rspose --example fuzz_report [CASES]` (default 500 per base
//! file). Mutates a simulated pair and a real recording's pair with seed 31
//! (`rspose::data::mutate`), parses, validates and estimates each case, and prints one row
//! per base file and one per mutation kind with the count of each outcome, then the slowest
//! case. Exits non-zero when a case panicked or a refusal's message was not one bounded
//! line saying where.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rspose::data::mutate::{case, run_case, Mutation, Outcome};
use rspose::{simulate, SimulationOptions};
use serde_json::Value;
use std::time::{Duration, Instant};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let cases: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(500);
    let sim = simulate(&SimulationOptions {
        seed: 7,
        ..Default::default()
    })?;
    let real = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/cc9pro/pair-100-101.json"
    ))?;
    let bases: [(&str, Value); 2] = [
        ("simulated", serde_json::from_str(&sim.to_json_string())?),
        ("cc9pro pair-100-101", serde_json::from_str(&real)?),
    ];
    let mut by_mutation = vec![[0usize; 6]; Mutation::ALL.len()];
    let mut bad = 0;
    let mut slowest = (Duration::ZERO, String::new());
    let header = |first: &str| {
        println!("| {first} | {} |", Outcome::COLUMNS.join(" | "));
        println!("|---|{}", "---|".repeat(Outcome::COLUMNS.len()));
    };
    header("base file");
    for (name, base) in &bases {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let mut counts = [0usize; 6];
        for i in 0..cases {
            let (mutations, text, method) = case(base, i, &mut rng);
            let start = Instant::now();
            let outcome = run_case(&text, method);
            let took = start.elapsed();
            if took > slowest.0 {
                slowest = (took, format!("{name} case {i} ({mutations:?}, {method})"));
            }
            if matches!(outcome, Outcome::Panicked(_)) || !outcome.message_ok() {
                bad += 1;
                eprintln!("{name} case {i} ({mutations:?}, {method}): {outcome:?}");
            }
            counts[outcome.column()] += 1;
            for m in mutations {
                let k = Mutation::ALL.iter().position(|&x| x == m).unwrap_or(0);
                by_mutation[k][outcome.column()] += 1;
            }
        }
        let row: Vec<String> = counts.iter().map(|c| c.to_string()).collect();
        println!("| {name} | {} |", row.join(" | "));
    }
    println!();
    header("mutation (cases it took part in)");
    for (m, counts) in Mutation::ALL.iter().zip(&by_mutation) {
        let row: Vec<String> = counts.iter().map(|c| c.to_string()).collect();
        println!("| {} | {} |", m.name(), row.join(" | "));
    }
    println!();
    println!(
        "slowest case: {:.0} ms, {}",
        slowest.0.as_secs_f64() * 1e3,
        slowest.1
    );
    if bad > 0 {
        return Err(format!("{bad} cases panicked or had a bad message").into());
    }
    Ok(())
}
