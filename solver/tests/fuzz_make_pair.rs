//! Seeded mutation fuzzing of `rspose make-pair`'s inputs: one of the recording's four
//! files (gyro log, frame times, calibration, matches) mutated per case, one to three
//! times — lines deleted, duplicated, swapped or replaced by garbage, numbers replaced by
//! extremes, text truncated; the JSON files through `rspose::data::mutate` — and the
//! command run on them. None may panic or abort; a refusal is exit 2 with one bounded line
//! and no output file; an accepted recording writes a pair that `estimate` reads.

mod recording;

use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use recording::{rspose, stderr, Recording};
use rspose::data::mutate::{mutate, Mutation, MAX_MESSAGE};
use serde_json::Value;
use std::time::{Duration, Instant};

/// Cases: enough for every file and mutation kind to come up several times.
const CASES: usize = 400;

/// Numbers and tokens put in place of a number of a text file.
const EXTREMES: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "1e300",
    "-1e300",
    "5e-324",
    "0",
    "-1",
    "",
    "0x10",
    "1,2",
    "abc",
    "99999999999999999999999999999999999999999999999999",
];

/// One line-level mutation of a text file's lines.
fn mutate_lines(lines: &mut Vec<String>, rng: &mut ChaCha8Rng) {
    if lines.is_empty() {
        lines.push("garbage".into());
        return;
    }
    let i = rng.gen_range(0..lines.len());
    match rng.gen_range(0..6) {
        0 => {
            lines.remove(i);
        }
        1 => {
            let l = lines[i].clone();
            lines.insert(i, l);
        }
        2 => {
            let j = rng.gen_range(0..lines.len());
            lines.swap(i, j);
        }
        3 => {
            // One number of the line replaced by an extreme or a malformed token.
            let mut fields: Vec<String> = lines[i].split(',').map(str::to_string).collect();
            let k = rng.gen_range(0..fields.len());
            fields[k] = EXTREMES.choose(rng).unwrap().to_string();
            lines[i] = fields.join(",");
        }
        4 => lines.insert(i, "\u{0}\u{fffd}; DROP TABLE".into()),
        _ => {
            let keep = rng.gen_range(0..=lines[i].len());
            let cut = lines[i].char_indices().map(|(b, _)| b).find(|&b| b >= keep);
            let len = lines[i].len();
            lines[i].truncate(cut.unwrap_or(len));
            lines.truncate(i + 1);
        }
    }
}

fn read_lines(path: &std::path::Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}

#[test]
fn mutated_recordings_never_panic_and_every_refusal_is_one_line() {
    let r = Recording::new("fuzz");
    let names = ["gyro.csv", "frames.txt", "calibration.json", "matches.json"];
    let originals: Vec<String> = names
        .iter()
        .map(|n| std::fs::read_to_string(r.path(n)).unwrap())
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let start = Instant::now();
    let (mut accepted, mut refused) = (0, 0);
    // Per file: (accepted, refused), printed with `-- --nocapture` for docs/ROBUSTNESS.md.
    let mut table = [(0usize, 0usize); 4];
    for case in 0..CASES {
        let which = case % names.len();
        for (n, text) in names.iter().zip(&originals) {
            std::fs::write(r.path(n), text).unwrap();
        }
        let path = r.path(names[which]);
        let times = rng.gen_range(1..=3);
        let text = if names[which].ends_with(".json") {
            let mut v: Value = serde_json::from_str(&originals[which]).unwrap();
            let mut text = originals[which].clone();
            for _ in 0..times {
                let m = *Mutation::ALL.choose(&mut rng).unwrap();
                text = mutate(&v, m, &mut rng);
                match serde_json::from_str(&text) {
                    Ok(next) => v = next,
                    Err(_) => break,
                }
            }
            text
        } else {
            let mut lines = read_lines(&path);
            for _ in 0..times {
                mutate_lines(&mut lines, &mut rng);
            }
            lines.join("\n") + "\n"
        };
        std::fs::write(&path, &text).unwrap();
        let _ = std::fs::remove_file(r.path("pair.json"));
        let o = r.make_pair();
        let err = stderr(&o);
        let what = format!("case {case}, {}:\n{text:.400}\n-> {err}", names[which]);
        assert!(!err.contains("panicked"), "{what}");
        match o.status.code() {
            Some(0) => {
                accepted += 1;
                table[which].0 += 1;
                let pair = r.path("pair.json");
                let e = rspose(&["estimate", pair.to_str().unwrap(), "--method", "gsrp"]);
                assert!(
                    matches!(e.status.code(), Some(0..=2)),
                    "{what}\nestimate: {}",
                    stderr(&e)
                );
                assert!(!stderr(&e).contains("panicked"), "{what}\n{}", stderr(&e));
            }
            Some(2) => {
                refused += 1;
                table[which].1 += 1;
                let line = err.trim_end();
                assert!(
                    !line.contains('\n') && line.chars().count() <= MAX_MESSAGE,
                    "{what}"
                );
                assert!(!r.path("pair.json").exists(), "{what}: output on bad input");
            }
            other => panic!("{what}: exit {other:?}"),
        }
    }
    println!("| mutated file | cases | refused (exit 2, one line) | accepted | panic |");
    println!("|---|---|---|---|---|");
    for (n, (a, f)) in names.iter().zip(table) {
        println!("| `{n}` | {} | {f} | {a} | 0 |", a + f);
    }
    assert!(
        refused > CASES / 2,
        "{refused} refused, {accepted} accepted"
    );
    assert!(
        start.elapsed() < Duration::from_secs(60),
        "the run took {:?}",
        start.elapsed()
    );
}
