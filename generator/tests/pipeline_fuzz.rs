//! Seeded mutations of the shipped problem files, and extreme problems built to exhaust
//! time or memory, go through the whole planning pipeline (`plan_source`: parse, check,
//! expansion, rewrites, Gröbner bases, template search, validation) on a small budget: no
//! input panics, every refusal is one line, and every run stays within a bounded multiple
//! of the budget. `-- --nocapture` prints the table of outcomes (docs/ROBUSTNESS.md).

mod fuzz_input;

use fuzz_input::{mutate, problem_files};
use mingen::{plan_source, Budget, Exhausted, PipelineError, TemplateOptions};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// The budget of every case.
const SECONDS: f64 = 0.25;
const MEMORY_MIB: u64 = 256;
/// The wall-clock a case may take, as a multiple of its budget: the stages check the
/// clock between steps, and a step (one normal form, one product of polynomials) may
/// overrun it; the first two validation instances always run.
const TIME_FACTOR: f64 = 8.0;
/// Mutated cases.
const MUTATIONS: usize = 300;
/// The longest refusal message accepted: one line naming what and where.
const MAX_MESSAGE: usize = 2000;

/// Problems built to exhaust a stage, from the reports of issue 31: each must be refused
/// (or planned) within the budget.
fn extreme_cases() -> Vec<(&'static str, String)> {
    let sum12 = "(u[0]+u[1]+u[2]+u[3]+u[4]+u[5]+u[6]+u[7]+u[8]+u[9]+u[10]+u[11])";
    let quadratics: String = (0..12)
        .map(|k| {
            let terms: Vec<String> = (0..12)
                .map(|i| format!("a[{k}][{i}]*u[{i}]*u[{}]", (i + k) % 12))
                .collect();
            format!("{} + a[{k}][12]*u[{k}] = 1\n", terms.join(" + "))
        })
        .collect();
    let squares = |n: usize| -> String { (0..n).map(|i| format!("u[{i}]^2 = a[{i}]\n")).collect() };
    vec![
        (
            "total degree 250",
            "problem d\nunknown x, y\ndata a: scalar, b: scalar\n\
             x^32*x^32*x^32*x^29*y^32*y^32*y^32*y^29 = a\nx + y = b\n"
                .into(),
        ),
        (
            "x^64*y^64 = a",
            "problem d\nunknown x, y\ndata a: scalar, b: scalar\nx^32*x^32*y^32*y^32 = a\nx + y = b\n"
                .into(),
        ),
        (
            "(sum of 12 unknowns)^96",
            format!(
                "problem s\nunknown u[12]\ndata a[12]: scalar\n{}",
                (0..12)
                    .map(|k| format!("{sum12}^32*{sum12}^32*{sum12}^32 = a[{k}]\n"))
                    .collect::<String>()
            ),
        ),
        (
            "a Laurent equation u1^-1 (sum of 12 unknowns)^96 (its shifts are found while parsing)",
            format!(
                "problem s\nunknown u[12]\ndata a: scalar\nu[0]^-1 * {sum12}^32*{sum12}^32*{sum12}^32 = a\n"
            ),
        ),
        (
            "12 quadratics in 12 unknowns",
            format!("problem q\nunknown u[12]\ndata a[12]: vec13\n{quadratics}"),
        ),
        (
            "a literal of 200,000 digits",
            format!(
                "problem l\nunknown x\ndata a: scalar\nx^2 = a + {}\n",
                "7".repeat(200_000)
            ),
        ),
        (
            "a literal of 1,000,000 digits",
            format!("problem l\nunknown x\ndata a: scalar\nx = {}\n", "1".repeat(1_000_000)),
        ),
        (
            "100,000 data slots",
            "problem d\nunknown x\ndata d[100000]: scalar\nx^2 = d[0]\n".into(),
        ),
        (
            "2048 solutions (u_i^2 = 1, 11 unknowns)",
            format!("problem u\nunknown u[11]\ndata a[11]: scalar\n{}", squares(11)),
        ),
        (
            "32768 solutions (15 unknowns)",
            format!("problem u\nunknown u[15]\ndata a[15]: scalar\n{}", squares(15)),
        ),
        (
            "a constant with no image mod p",
            "problem m\nunknown x, y\ndata a: scalar\nx^2 = a\ny^2 = x + 1/2147483629\n".into(),
        ),
        (
            "a name of 100,000 characters",
            format!("problem n\nunknown {}\ndata a: scalar\n", "x".repeat(100_000)),
        ),
        (
            "a deep product",
            format!(
                "problem p\nunknown x, y\ndata a: scalar\n{}x{} = a\ny = x\n",
                "(1 + ".repeat(100),
                ")".repeat(100)
            ),
        ),
    ]
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Outcome {
    Planned,
    Refused,
    CountError,
    BudgetTime,
    BudgetMemory,
    Other,
    Panic,
}

const OUTCOMES: [(Outcome, &str); 7] = [
    (Outcome::Planned, "planned"),
    (Outcome::Refused, "refused at parse/check"),
    (Outcome::CountError, "count error"),
    (Outcome::BudgetTime, "budget exceeded (time)"),
    (Outcome::BudgetMemory, "budget exceeded (memory)"),
    (Outcome::Other, "other"),
    (Outcome::Panic, "panic"),
];

fn classify(e: &PipelineError) -> Outcome {
    match (e, e.exhausted()) {
        (_, Some(Exhausted::Time(_))) => Outcome::BudgetTime,
        (_, Some(Exhausted::Memory { .. })) => Outcome::BudgetMemory,
        (
            PipelineError::Problem(_)
            | PipelineError::Eliminate { .. }
            | PipelineError::Option { .. }
            | PipelineError::Expansion { .. },
            None,
        ) => Outcome::Refused,
        (PipelineError::Template { .. }, None) => Outcome::CountError,
        _ => Outcome::Other,
    }
}

/// One case through the pipeline: its outcome, seconds, and the refusal's message.
fn run(text: &str, options: &TemplateOptions) -> (Outcome, f64, Option<String>) {
    let start = Instant::now();
    let r = catch_unwind(AssertUnwindSafe(|| plan_source(text, "fuzz.mp", options)));
    let seconds = start.elapsed().as_secs_f64();
    match r {
        Ok(Ok(_)) => (Outcome::Planned, seconds, None),
        Ok(Err(e)) => (classify(&e), seconds, Some(e.to_string())),
        Err(_) => (Outcome::Panic, seconds, None),
    }
}

/// Peak resident memory of this process, in MiB (Linux), if known.
fn peak_rss_mib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib >> 10)
}

#[test]
fn mutated_and_extreme_problems_stay_within_the_budget() {
    let options = TemplateOptions {
        budget: Budget::new(SECONDS, MEMORY_MIB),
        ..TemplateOptions::default()
    };
    let limit = SECONDS * TIME_FACTOR;
    let sources = problem_files(&["", "classic"]);
    assert!(!sources.is_empty(), "no shipped problem files");
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let mut table: Vec<(String, Vec<usize>)> = Vec::new();
    let mut tally = |target: &str, o: Outcome| {
        let k = OUTCOMES.iter().position(|(x, _)| *x == o).unwrap_or(0);
        match table.iter_mut().find(|(t, _)| t == target) {
            Some((_, counts)) => counts[k] += 1,
            None => {
                let mut counts = vec![0; OUTCOMES.len()];
                counts[k] += 1;
                table.push((target.to_string(), counts));
            }
        }
    };
    let mut failures: Vec<String> = Vec::new();
    let mut slowest = (0.0f64, String::new());
    let mut check = |what: &str, (outcome, seconds, message): &(Outcome, f64, Option<String>)| {
        if *seconds > slowest.0 {
            slowest = (*seconds, what.to_string());
        }
        if *outcome == Outcome::Panic {
            failures.push(format!("{what}: panicked"));
        }
        if *seconds > limit {
            failures.push(format!(
                "{what}: {seconds:.2} s, over {limit} s ({outcome:?})"
            ));
        }
        if let Some(m) = message {
            if m.contains('\n') || m.len() > MAX_MESSAGE || m.is_empty() {
                failures.push(format!(
                    "{what}: not one bounded line ({} bytes): {}",
                    m.len(),
                    m.chars().take(200).collect::<String>()
                ));
            }
        }
    };
    // A panic's default message would flood the output; the outcome records it.
    let hook = std::panic::take_hook();
    let mut planned_extremes = Vec::new();
    std::panic::set_hook(Box::new(|_| {}));
    let started = Instant::now();
    for case in 0..MUTATIONS {
        let (path, text) = &sources[rng.gen_range(0..sources.len())];
        let mutated = mutate(text, &mut rng);
        let text = String::from_utf8_lossy(&mutated);
        let target = if path.parent().is_some_and(|d| d.ends_with("classic")) {
            "mutated templates/classic/*.mp"
        } else {
            "mutated templates/*.mp"
        };
        let r = run(&text, &options);
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        check(
            &format!("mutation {case} of {}", name.unwrap_or_default()),
            &r,
        );
        tally(target, r.0);
    }
    for (name, text) in extreme_cases() {
        let r = run(&text, &options);
        println!("extreme: {name}: {:?} in {:.2} s", r.0, r.1);
        check(&format!("extreme case {name}"), &r);
        if r.0 == Outcome::Planned {
            // Planned within this budget, the case would no longer exercise what it was
            // built for.
            planned_extremes.push(name);
        }
        tally("extreme cases (issue 31)", r.0);
    }
    std::panic::set_hook(hook);
    let total = started.elapsed().as_secs_f64();
    println!(
        "\n| cases | {} |",
        OUTCOMES
            .iter()
            .map(|(_, n)| *n)
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!("|---|{}", "---|".repeat(OUTCOMES.len()));
    for (target, counts) in &table {
        let n: usize = counts.iter().sum();
        println!(
            "| {target} ({n}) | {} |",
            counts
                .iter()
                .map(|c| c.to_string())
                .collect::<Vec<_>>()
                .join(" | ")
        );
    }
    println!(
        "\nbudget {SECONDS} s, {MEMORY_MIB} MiB; slowest case {:.2} s ({}); {total:.1} s in all; peak memory {} MiB",
        slowest.0,
        slowest.1,
        peak_rss_mib().map_or("?".into(), |m| m.to_string())
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(planned_extremes.is_empty(), "planned: {planned_extremes:?}");
}
