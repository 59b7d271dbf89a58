//! Exploration of basis selection and shrinking for developers: prints template sizes
//! over column orders and removal orders instead of choosing one. Not a pipeline stage;
//! `examples/explore_basis.rs` is its command line.

use super::candidates::{candidates, Blocks, Candidate};
use super::select::{select_basis, BasisOrder};
use super::shrink::{shrink, shrink_ordered};
use super::Action;
use crate::algebra::{Fp, Monomial, Poly};
use std::collections::BTreeMap;

/// For each action variable of `actions` and each column order of `orders`, selects a basis
/// among the multiples up to degree `d`, shrinks its template and prints the size; then a
/// summary per action of the distinct bases, smallest template first.
pub fn explore<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    nvars: usize,
    count: usize,
    actions: &[usize],
    orders: &[BasisOrder],
    d: u32,
) {
    let cands = candidates(eqs, d, &[]);
    for &av in actions {
        let action = Action::var(nvars, av);
        let mut seen: BTreeMap<Vec<Monomial>, (usize, usize, usize)> = BTreeMap::new();
        for o in orders {
            let Some(b) = select_basis::<P>(&cands, nvars, &action, count, o) else {
                continue;
            };
            if let Some(e) = seen.get_mut(&b) {
                e.2 += 1;
                continue;
            }
            let blocks = Blocks::new(&b, &action, nvars);
            let refs: Vec<&Candidate> = cands.iter().collect();
            if !blocks.reducible_by::<P>(&refs) {
                seen.insert(b, (0, 0, 1));
                continue;
            }
            let mut h = Vec::new();
            let kept = shrink::<P>(&blocks, cands.clone(), &mut h, None).expect("no budget");
            let nc = blocks.excess_of(kept.iter()).len() + blocks.reducible.len() + b.len();
            println!("action {av} {o:?}: {}x{} B {:?}", kept.len(), nc, b);
            seen.insert(b, (kept.len(), nc, 1));
        }
        let mut v: Vec<_> = seen.into_iter().collect();
        v.sort_by_key(|(_, (r, c, _))| r * c);
        for (b, (r, c, n)) in v {
            println!("SUMMARY action {av}: {r}x{c} ({n} orders) B {b:?}");
        }
    }
}

/// Shrinks the template of the basis selected with `order` at degree `d` under `tries`
/// random removal orders (every other one sorted by degree) and prints how often each
/// size came out: how much the deterministic removal order leaves on the table.
pub fn explore_random_shrink<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    nvars: usize,
    count: usize,
    action_var: usize,
    order: &BasisOrder,
    d: u32,
    tries: u64,
) {
    use rand::seq::SliceRandom;
    use rand::SeedableRng;
    let action = Action::var(nvars, action_var);
    let cands = candidates(eqs, d, &[]);
    let b = select_basis::<P>(&cands, nvars, &action, count, order).expect("basis");
    let blocks = Blocks::new(&b, &action, nvars);
    let mut sizes = BTreeMap::new();
    for seed in 0..tries {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut rows = cands.clone();
        rows.shuffle(&mut rng);
        if seed % 2 == 0 {
            rows.sort_by_key(|c| c.degree);
        }
        let mut h = Vec::new();
        let kept = shrink_ordered::<P>(&blocks, rows, &mut h, None).expect("no budget");
        let nc = blocks.excess_of(kept.iter()).len() + blocks.reducible.len() + count;
        *sizes.entry((kept.len(), nc)).or_insert(0) += 1;
    }
    println!("action {action_var} {order:?}: {sizes:?}");
}
