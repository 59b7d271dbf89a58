//! Seeded mutations of a pair file, and the outcome of reading and estimating the result:
//! the robustness harness behind `solver/tests/fuzz_pair_file.rs` and
//! `cargo run --release -p rspose --example fuzz_report` (`docs/ROBUSTNESS.md`).
//!
//! A mutation edits the file's JSON tree (delete, duplicate, rename or swap a key, replace a
//! number by an extreme, a value by one of another type, an array by a huge one) or its text
//! (truncation). [`run_case`] then parses, validates and estimates the text as `rspose
//! estimate` would and classifies what happened; a panic is caught and reported as such.

use crate::data::pair_estimate::{estimate_pair, PairEstimateError, RowModel};
use crate::data::pair_file::{PairFile, PairFileError};
use crate::methods::{EstimateError, EstimateOptions, Method};
use rand::seq::SliceRandom;
use rand::Rng;
use serde_json::Value;
use std::path::Path;

/// Longest array a mutation builds: large enough to exercise the size handling of every
/// field, small enough for a test run.
pub const HUGE_ARRAY: usize = 20_000;

/// Longest error message [`Outcome::message_ok`] accepts, characters: a message printing a
/// number with hundreds of digits is unreadable.
pub const MAX_MESSAGE: usize = 600;

/// The kinds of mutation, in the order of the report's tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mutation {
    /// Delete an object's key.
    DeleteKey,
    /// Write an object's key twice.
    DuplicateKey,
    /// Misspell an object's key.
    RenameKey,
    /// Swap the values of two keys of one object.
    SwapValues,
    /// Replace a number by 0, -1, 1e300, -1e300 or the smallest subnormal.
    ExtremeNumber,
    /// Replace a number by the string `"NaN"`.
    NanString,
    /// Replace a value by one of another type.
    WrongType,
    /// Replace an array by a huge one (its first element repeated, or its elements cycled).
    HugeArray,
    /// Cut the text at a random byte.
    Truncate,
}

impl Mutation {
    /// Every mutation.
    pub const ALL: [Mutation; 9] = [
        Mutation::DeleteKey,
        Mutation::DuplicateKey,
        Mutation::RenameKey,
        Mutation::SwapValues,
        Mutation::ExtremeNumber,
        Mutation::NanString,
        Mutation::WrongType,
        Mutation::HugeArray,
        Mutation::Truncate,
    ];

    /// Its name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Mutation::DeleteKey => "delete key",
            Mutation::DuplicateKey => "duplicate key",
            Mutation::RenameKey => "rename key",
            Mutation::SwapValues => "swap values",
            Mutation::ExtremeNumber => "extreme number",
            Mutation::NanString => "NaN string",
            Mutation::WrongType => "wrong type",
            Mutation::HugeArray => "huge array",
            Mutation::Truncate => "truncate",
        }
    }
}

/// Every node of `v` as a path of object keys and array indices (the root is `[]`). Arrays
/// longer than a few elements contribute their first, second and last element only, so a
/// long match list does not drown the other fields.
fn paths(v: &Value, prefix: &mut Vec<PathStep>, out: &mut Vec<Vec<PathStep>>) {
    out.push(prefix.clone());
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                prefix.push(PathStep::Key(k.clone()));
                paths(child, prefix, out);
                prefix.pop();
            }
        }
        Value::Array(a) => {
            let mut idx: Vec<usize> = (0..a.len().min(2)).collect();
            if a.len() > 2 {
                idx.push(a.len() - 1);
            }
            for i in idx {
                prefix.push(PathStep::Index(i));
                paths(&a[i], prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

/// One step of a path into a JSON tree.
#[derive(Debug, Clone, PartialEq)]
enum PathStep {
    Key(String),
    Index(usize),
}

fn node_mut<'a>(v: &'a mut Value, path: &[PathStep]) -> &'a mut Value {
    path.iter().fold(v, |v, step| match step {
        PathStep::Key(k) => &mut v[k.as_str()],
        PathStep::Index(i) => &mut v[*i],
    })
}

/// Applies `mutation` to the JSON text of `base` once, choosing where with `rng`; returns
/// the mutated text (a mutation with no place to apply leaves the text unchanged).
pub fn mutate(base: &Value, mutation: Mutation, rng: &mut impl Rng) -> String {
    let mut v = base.clone();
    let mut all = Vec::new();
    paths(&v, &mut Vec::new(), &mut all);
    let pick = |rng: &mut dyn rand::RngCore, pred: &dyn Fn(&Value) -> bool, v: &Value| {
        let candidates: Vec<&Vec<PathStep>> = all
            .iter()
            .filter(|p| pred(node_ref(v, p)))
            .collect::<Vec<_>>();
        candidates.choose(rng).map(|p| (*p).clone())
    };
    match mutation {
        Mutation::DeleteKey | Mutation::RenameKey | Mutation::SwapValues => {
            if let Some(p) = pick(rng, &|n| n.as_object().is_some_and(|o| !o.is_empty()), &v) {
                let obj = node_mut(&mut v, &p).as_object_mut().expect("an object");
                let keys: Vec<String> = obj.keys().cloned().collect();
                let key = keys.choose(rng).expect("non-empty").clone();
                match mutation {
                    Mutation::DeleteKey => {
                        obj.remove(&key);
                    }
                    Mutation::RenameKey => {
                        let value = obj.remove(&key).expect("present");
                        let mut misspelt: String = key.chars().filter(|&c| c != '_').collect();
                        if misspelt == key {
                            misspelt.push('s');
                        }
                        obj.insert(misspelt, value);
                    }
                    _ => {
                        let other = keys.choose(rng).expect("non-empty").clone();
                        let a = obj[&key].clone();
                        let b = std::mem::replace(obj.get_mut(&other).expect("present"), a);
                        obj.insert(key, b);
                    }
                }
            }
            v.to_string()
        }
        Mutation::DuplicateKey => {
            // serde_json's tree holds each key once: write the duplicate into the text.
            let text = v.to_string();
            match v.as_object().and_then(|o| {
                let keys: Vec<&String> = o.keys().collect();
                keys.choose(rng)
                    .map(|k| (k.to_string(), o[k.as_str()].clone()))
            }) {
                Some((k, value)) => format!("{{{}:{},{}", Value::from(k), value, &text[1..]),
                None => text,
            }
        }
        Mutation::ExtremeNumber | Mutation::NanString => {
            if let Some(p) = pick(rng, &|n| n.is_number(), &v) {
                let extremes = [0.0, -1.0, 1e300, -1e300, 5e-324];
                *node_mut(&mut v, &p) = match mutation {
                    Mutation::NanString => Value::from("NaN"),
                    _ => Value::from(*extremes.choose(rng).expect("non-empty")),
                };
            }
            v.to_string()
        }
        Mutation::WrongType => {
            if let Some(p) = pick(rng, &|_| true, &v) {
                let others = [
                    Value::Null,
                    Value::from(true),
                    Value::from("x"),
                    Value::from(1),
                    serde_json::json!({}),
                    serde_json::json!([]),
                ];
                *node_mut(&mut v, &p) = others.choose(rng).expect("non-empty").clone();
            }
            v.to_string()
        }
        Mutation::HugeArray => {
            if let Some(p) = pick(rng, &|n| n.as_array().is_some_and(|a| !a.is_empty()), &v) {
                let node = node_mut(&mut v, &p);
                let a = node.as_array().expect("an array").clone();
                let cycled = rng.gen_bool(0.5);
                *node = Value::Array(
                    (0..HUGE_ARRAY)
                        .map(|i| a[if cycled { i % a.len() } else { 0 }].clone())
                        .collect(),
                );
            }
            v.to_string()
        }
        Mutation::Truncate => {
            let text = v.to_string();
            let cut = rng.gen_range(0..text.len().max(1));
            text[..cut].to_string()
        }
    }
}

fn node_ref<'a>(v: &'a Value, path: &[PathStep]) -> &'a Value {
    path.iter().fold(v, |v, step| match step {
        PathStep::Key(k) => &v[k.as_str()],
        PathStep::Index(i) => &v[*i],
    })
}

/// What reading and estimating a (mutated) pair file gave.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Refused while parsing or validating the file, with the message `rspose` prints.
    RefusedFile(String),
    /// The file was valid but the estimate refused its content (e.g. too few matches).
    RefusedEstimate(String),
    /// Valid input without a solution.
    NoSolution,
    /// An estimate with at least one quality flag raised.
    Flagged,
    /// An estimate with no flag.
    Accepted,
    /// The library panicked, with the panic's message.
    Panicked(String),
}

impl Outcome {
    /// The outcome's column in the report.
    pub fn column(&self) -> usize {
        match self {
            Outcome::RefusedFile(_) => 0,
            Outcome::RefusedEstimate(_) => 1,
            Outcome::NoSolution => 2,
            Outcome::Flagged => 3,
            Outcome::Accepted => 4,
            Outcome::Panicked(_) => 5,
        }
    }

    /// The report's column names, in [`column`](Self::column) order.
    pub const COLUMNS: [&'static str; 6] = [
        "refused (file)",
        "refused (estimate)",
        "no solution",
        "flagged",
        "accepted",
        "panic",
    ];

    /// Whether a refusal's message is one line of bounded length that says where: a file
    /// error names a field (in backquotes) or a line and column. Other outcomes pass.
    pub fn message_ok(&self) -> bool {
        match self {
            Outcome::RefusedFile(m) => {
                one_bounded_line(m) && (m.contains('`') || m.contains(" line "))
            }
            Outcome::RefusedEstimate(m) => one_bounded_line(m),
            _ => true,
        }
    }
}

fn one_bounded_line(m: &str) -> bool {
    !m.is_empty() && !m.contains('\n') && m.chars().count() <= MAX_MESSAGE
}

/// Parses and validates `text` as a pair file (as `rspose estimate` reads one), then
/// estimates it with `method`'s default options; a panic anywhere is caught.
pub fn run_case(text: &str, method: Method) -> Outcome {
    let result = std::panic::catch_unwind(|| {
        let pair = match PairFile::from_json_str(text, Path::new("PAIR.json")) {
            Ok(p) => p,
            Err(e) => return Outcome::RefusedFile(e.to_string()),
        };
        match estimate_pair(
            &pair,
            &EstimateOptions::for_method(method),
            RowModel::Integrated,
            None,
        ) {
            Ok(est) if est.quality.flags().is_empty() => Outcome::Accepted,
            Ok(_) => Outcome::Flagged,
            Err(PairEstimateError::Estimate(EstimateError::NoSolution)) => Outcome::NoSolution,
            Err(PairEstimateError::Pair(e @ PairFileError::InvalidField { .. })) => {
                Outcome::RefusedFile(e.to_string())
            }
            Err(e) => Outcome::RefusedEstimate(e.to_string()),
        }
    });
    result.unwrap_or_else(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        Outcome::Panicked(message)
    })
}

/// The methods the cases cycle through: one per family of estimator.
pub const METHODS: [Method; 4] = [
    Method::Rectified,
    Method::GrsrpPlus,
    Method::Gsrp,
    Method::GrsrpGravity,
];

/// One mutated case: `count` mutations (1 to 3) of `base` chosen by `rng`, the text, and
/// the method it is estimated with.
pub fn case(base: &Value, index: usize, rng: &mut impl Rng) -> (Vec<Mutation>, String, Method) {
    let count = rng.gen_range(1..=3);
    let mut text = base.to_string();
    let mut applied = Vec::new();
    for _ in 0..count {
        let Ok(v) = serde_json::from_str::<Value>(&text) else {
            break;
        };
        let m = *Mutation::ALL.choose(rng).expect("non-empty");
        text = mutate(&v, m, rng);
        applied.push(m);
    }
    (applied, text, METHODS[index % METHODS.len()])
}
