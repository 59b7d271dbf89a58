//! Thousands of randomly mutated versions of the shipped problem files go through the
//! parser and checker (and, when they parse, a direct evaluation mod p): no input panics.

mod fuzz_input;

use fuzz_input::{mutate, problem_files, WORDS};
use mingen::__internal::algebra::{Fp, P1};
use mingen::__internal::instance::random_data_fp;
use mingen::Problem;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

#[test]
fn mutated_problem_files_never_panic() {
    let sources: Vec<Vec<u8>> = problem_files(&[""]).into_iter().map(|(_, s)| s).collect();
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
