//! Mutation of problem files, shared by the fuzz tests of the parser (`lang_fuzz.rs`) and
//! of the whole planning pipeline (`pipeline_fuzz.rs`).
#![allow(dead_code)]

use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};

/// Bytes inserted by [`mutate`]: the language's punctuation, digits and a few letters.
pub const ALPHABET: &[u8] = b"[](){}'*+-/=,:;.#0123456789 \n\tabcIkxtv_";
/// Words inserted by [`mutate`]: keywords, builtins, kinds, ranges and literals.
pub const WORDS: &[&str] = &[
    "problem",
    "unknown",
    "data",
    "eliminate",
    "let",
    "for",
    "in",
    "skew",
    "det",
    "trace",
    "I",
    "point",
    "rotation",
    "..",
    "0..5",
    "99999999999999999999",
    "0.5",
    "[",
    "]",
    "(",
    ")",
    "{",
    "}",
    "'",
    "=",
    "\n",
];

/// `src` with 1 to 4 random edits: bytes deleted, inserted, swapped or replaced, a
/// keyword or literal inserted, two tokens swapped, a chunk duplicated.
pub fn mutate(src: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut s = src.to_vec();
    for _ in 0..rng.gen_range(1..=4) {
        let len = s.len().max(1);
        match rng.gen_range(0..7) {
            0 if !s.is_empty() => {
                let i = rng.gen_range(0..s.len());
                let n = rng.gen_range(1..=8).min(s.len() - i);
                s.drain(i..i + n);
            }
            1 => {
                let i = rng.gen_range(0..=s.len());
                s.insert(i, *ALPHABET.choose(rng).unwrap());
            }
            2 if s.len() >= 2 => {
                let (i, j) = (rng.gen_range(0..s.len()), rng.gen_range(0..s.len()));
                s.swap(i, j);
            }
            3 => {
                let i = rng.gen_range(0..=s.len());
                let w = WORDS.choose(rng).unwrap().as_bytes();
                s.splice(i..i, w.iter().copied());
            }
            4 => {
                // Token shuffle: swap two whitespace-separated tokens.
                let text = String::from_utf8_lossy(&s).into_owned();
                let mut toks: Vec<&str> = text.split(' ').collect();
                if toks.len() >= 2 {
                    let (i, j) = (rng.gen_range(0..toks.len()), rng.gen_range(0..toks.len()));
                    toks.swap(i, j);
                }
                s = toks.join(" ").into_bytes();
            }
            5 if !s.is_empty() => {
                // Duplicate a chunk.
                let i = rng.gen_range(0..s.len());
                let n = rng.gen_range(1..=40).min(s.len() - i);
                let chunk: Vec<u8> = s[i..i + n].to_vec();
                let at = rng.gen_range(0..=s.len());
                s.splice(at..at, chunk);
            }
            _ => {
                let i = rng.gen_range(0..len);
                if let Some(b) = s.get_mut(i) {
                    *b = rng.gen();
                }
            }
        }
    }
    s
}

/// The problem files `templates/<dir>/*.mp` of each of `dirs` (`""`: `templates/` itself),
/// sorted by path, with their contents.
pub fn problem_files(dirs: &[&str]) -> Vec<(PathBuf, Vec<u8>)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates");
    let mut out = Vec::new();
    for d in dirs {
        let dir = root.join(d);
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "mp") {
                if let Ok(text) = std::fs::read(&p) {
                    out.push((p, text));
                }
            }
        }
    }
    out.sort();
    out
}
