//! Thousands of randomly mutated versions of the shipped problem files go through the
//! parser and checker (and, when they parse, a direct evaluation mod p): no input panics.

use mingen::__internal::algebra::{Fp, P1};
use mingen::__internal::instance::random_data_fp;
use mingen::Problem;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const ALPHABET: &[u8] = b"[](){}'*+-/=,:;.#0123456789 \n\tabcIkxtv_";
const WORDS: &[&str] = &[
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

fn mutate(src: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
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

#[test]
fn mutated_problem_files_never_panic() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../templates");
    let mut sources = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "mp") {
            sources.push(std::fs::read(&p).unwrap());
        }
    }
    sources.sort();
    let mut rng = ChaCha8Rng::seed_from_u64(0xF022);
    let (mut ok, mut total) = (0, 0);
    for round in 0..6000 {
        let src = &sources[round % sources.len()];
        let m = mutate(src, &mut rng);
        let text = String::from_utf8_lossy(&m);
        total += 1;
        if let Ok(p) = Problem::parse(&text, "fuzz.mp") {
            ok += 1;
            if p.tape_len() < 20_000 {
                let data = random_data_fp::<P1>(&p.layout, &mut rng);
                let unknowns: Vec<Fp<P1>> = (0..p.layout.unknown_count())
                    .map(|_| Fp(rng.gen_range(0..P1)))
                    .collect();
                let _ = p.evaluate_direct_ring(&data, &unknowns);
            }
        }
    }
    // Some mutations (comments, whitespace) leave a valid file; most do not.
    assert!(ok > 0 && ok < total, "{ok} of {total} parsed");
}

#[test]
fn random_token_soup_never_panics() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let extra = ["x", "t", "a", "k", "3", "+", "-", "*", "/", ",", ":", " "];
    for _ in 0..5000 {
        let mut s = String::from("problem p\nunknown t[3], x\ndata d[2]: vec3, R: rotation\n");
        for _ in 0..rng.gen_range(1..60) {
            let w = if rng.gen_bool(0.5) {
                WORDS.choose(&mut rng).unwrap()
            } else {
                extra.choose(&mut rng).unwrap()
            };
            s.push_str(w);
            if rng.gen_bool(0.3) {
                s.push(' ');
            }
        }
        let _ = Problem::parse(&s, "soup.mp");
    }
}
