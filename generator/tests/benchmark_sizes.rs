//! The template benchmark (`templates/benchmark/`, the minimal problems of Martyushev,
//! Vrablikova, Bhayani and Pajdla): every file states the solution count it must have and
//! the template size mingen reached (`# recorded: RxC`, or `RxC + NxM reduction` when the
//! solver row-reduces its equations first; written by `tools/benchmark_record.py`);
//! planning it again must give that count and at most that elimination area (the
//! template's, plus the reduction's). A regression guard on the template search, not a timing test.
//! The same for the sizes with redundant solving bases (`# recorded redundant: ...`,
//! `tools/benchmark_record.py --redundant-basis`), planned with them.
//! Problems recorded as planned within more than [`MAX_RECORDED_SECONDS`] are left to
//! `python3 tools/benchmark_record.py --check`, which plans every one, so that the test
//! suite stays short.

use mingen::plan_files;
use mingen::TemplateOptions;
use std::path::{Path, PathBuf};

/// Problems whose recorded planning time is above this are not planned by the test.
const MAX_RECORDED_SECONDS: f64 = 5.0;

fn benchmark_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/benchmark");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "mp"))
        .collect();
    files.sort();
    files
}

/// The value of the first `# KEY:` comment line.
fn header(text: &str, key: &str) -> Option<String> {
    text.lines().find_map(|l| {
        let rest = l.trim_start().strip_prefix('#')?.trim_start();
        Some(
            rest.strip_prefix(key)?
                .strip_prefix(':')?
                .trim()
                .to_string(),
        )
    })
}

/// The elimination area recorded at the start of `text` (`RxC`, or `RxC + NxM reduction`)
/// as its text, the area, and the `within N s` figure after it.
fn size(text: &str) -> Option<(String, usize, f64)> {
    let head = text.split(", planned").next()?.trim();
    let area = |word: &str| -> Option<usize> {
        let (r, c) = word.split_once('x')?;
        Some(r.parse::<usize>().ok()? * c.parse::<usize>().ok()?)
    };
    let mut words = head.split_whitespace();
    let mut total = area(words.next()?)?;
    if words.next() == Some("+") {
        total += area(words.next()?)?;
    }
    let seconds = text
        .split_once("within ")
        .and_then(|(_, rest)| rest.split_whitespace().next()?.parse().ok())
        .unwrap_or(f64::INFINITY);
    Some((head.to_string(), total, seconds))
}

/// Threads planning the guarded files (their plans are independent).
const PLANNING_THREADS: usize = 2;

/// Plans every file with a `# KEY:` size recorded within [`MAX_RECORDED_SECONDS`] with
/// `options` and lists each count that differs from the file's and each template larger in
/// area than recorded.
fn check_recorded(key: &str, options: &TemplateOptions) -> Vec<String> {
    let files = benchmark_files();
    assert!(files.len() >= 40, "the benchmark has {} files", files.len());
    // The guarded files: name, expected count, recorded size and area.
    let mut guarded = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        let name = f.file_stem().unwrap().to_string_lossy().into_owned();
        let count: Option<usize> = header(&text, "Expected solution count")
            .and_then(|v| v.split_whitespace().next().and_then(|n| n.parse().ok()));
        // Files without a template (their reason is in the header) are not guarded.
        let Some((recorded, recorded_area, seconds)) = header(&text, key).and_then(|v| size(&v))
        else {
            continue;
        };
        if seconds <= MAX_RECORDED_SECONDS {
            guarded.push((f.clone(), name, count, recorded, recorded_area));
        }
    }
    assert!(!guarded.is_empty(), "no benchmark file has a `{key}` size");
    let paths: Vec<PathBuf> = guarded.iter().map(|g| g.0.clone()).collect();
    let plans = plan_files(&paths, options, PLANNING_THREADS);
    let mut failures = Vec::new();
    for ((_, name, count, recorded, recorded_area), plan) in guarded.iter().zip(plans) {
        match plan {
            Ok(plan) => {
                let t = &plan.generated.built.template;
                if let Some(n) = *count {
                    if plan.generated.count != n {
                        failures.push(format!(
                            "{name}: {} solutions, expected {n}",
                            plan.generated.count
                        ));
                    }
                }
                if t.elimination_area() > *recorded_area {
                    let (r, c) = t.eliminated_size();
                    let reduction = t
                        .reduction_size()
                        .map(|(n, m)| format!(" + {n}x{m} reduction"))
                        .unwrap_or_default();
                    failures.push(format!(
                        "{name}: {r}x{c}{reduction} is larger than the {key} {recorded}"
                    ));
                }
            }
            Err(e) => failures.push(format!("{name}: {e}")),
        }
    }
    failures
}

#[test]
fn benchmark_templates_keep_their_counts_and_do_not_grow() {
    let failures = check_recorded("recorded", &TemplateOptions::default());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The same with redundant solving bases (`--redundant-basis yes`; the sizes of
/// `tools/benchmark_record.py --redundant-basis`).
#[test]
fn redundant_basis_templates_keep_their_counts_and_do_not_grow() {
    let options = TemplateOptions {
        redundant_bases: true,
        ..TemplateOptions::default()
    };
    let failures = check_recorded("recorded redundant", &options);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
