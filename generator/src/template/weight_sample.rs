//! The weight vectors of the weighted monomial orders the template search tries (see
//! docs/ARCHITECTURE.md §2, "How a template is searched"): the grid of 1s and 2s, the wide
//! sample, the narrow sample and the neighbours a climb moves to. Pure functions of the
//! number of unknowns and a seed, so the search is deterministic.

/// Seed offset of the weight vectors of [`sampled_weights`].
const WEIGHTS_SEED: u64 = 0x3E16_0000;

/// The largest weights of [`sampled_weights`]'s sample, in turn.
const WEIGHT_TOPS: [u32; 4] = [3, 5, 8, 12];

/// Every weight vector of 1s and 2s for `nvars` variables but the two constant ones
/// (grevlex), when there are at most `max`; otherwise none. Their cones lie nearest
/// grevlex's, and their ties keep grevlex's tie-breaking on some variables.
pub(super) fn ones_and_twos(nvars: usize, max: usize) -> Vec<Vec<u32>> {
    let n = 1usize
        .checked_shl(nvars as u32)
        .map_or(usize::MAX, |n| n - 2);
    if nvars < 2 || n > max {
        return Vec::new();
    }
    (1..=n)
        .map(|bits| {
            (0..nvars)
                .map(|i| 1 + ((bits >> (nvars - 1 - i)) & 1) as u32)
                .collect()
        })
        .collect()
}

/// `count` distinct weight vectors for `nvars` variables, none all equal (that order is
/// grevlex), with entries uniform in `1..=top`, `top` cycling through
/// [`WEIGHT_TOPS`], from a generator seeded by `seed`: a sample of the Gröbner fan's
/// cones, whose orders the weighted templates of Martyushev et al. come from.
pub(super) fn sampled_weights(nvars: usize, count: usize, seed: u64) -> Vec<Vec<u32>> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed ^ WEIGHTS_SEED);
    let mut out: Vec<Vec<u32>> = Vec::new();
    if nvars < 2 {
        return out;
    }
    // Enough draws for `count` distinct vectors where that many exist.
    for _ in 0..count.saturating_mul(4) {
        if out.len() == count {
            break;
        }
        let top = WEIGHT_TOPS[out.len() % WEIGHT_TOPS.len()];
        let w: Vec<u32> = (0..nvars).map(|_| rng.gen_range(1..=top)).collect();
        if w.iter().all(|&x| x == w[0]) || out.contains(&w) {
            continue;
        }
        out.push(w);
    }
    out
}

/// The smallest weights of [`narrow_weights`]'s vectors, in turn; each vector's entries
/// lie in `[k, 4k]`.
const NARROW_LOWS: [u32; 2] = [4, 16];

/// Up to `count` distinct weight vectors for `nvars` variables, none all equal, with
/// entries uniform in `[k, 4k]`, `k` cycling through [`NARROW_LOWS`], from a generator
/// seeded by `seed`: orders near grevlex's by ratio but far from it in the fan, the region
/// the templates of Martyushev et al. come from (their order finder samples weights
/// uniform in `[200, 800]`). Finer `k` reach smaller cones.
pub(super) fn narrow_weights(
    nvars: usize,
    visible: usize,
    count: usize,
    seed: u64,
) -> Vec<(usize, Vec<u32>)> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed ^ NARROW_WEIGHTS_SEED);
    let mut out: Vec<(usize, Vec<u32>)> = Vec::new();
    if nvars < 2 || visible == 0 {
        return out;
    }
    for _ in 0..count.saturating_mul(4) {
        if out.len() == count {
            break;
        }
        let unknown = out.len() % visible;
        let low = NARROW_LOWS[(out.len() / visible) % NARROW_LOWS.len()];
        let mut w: Vec<u32> = (0..nvars).map(|_| rng.gen_range(low..=4 * low)).collect();
        let heaviest = (0..nvars)
            .max_by_key(|&i| (w[i], std::cmp::Reverse(i)))
            .unwrap_or(0);
        w.swap(unknown, heaviest);
        if w.iter().all(|&x| x == w[0]) || out.iter().any(|(_, o)| *o == w) {
            continue;
        }
        out.push((unknown, w));
    }
    out
}

/// Seed offset of the weight vectors of [`narrow_weights`].
const NARROW_WEIGHTS_SEED: u64 = 0x4A77_0000;

/// The weight vectors one step from `w`: each weight one up or one down (staying
/// positive), then, on the doubled vector, each weight one up or down (the finer cones
/// between).
pub(super) fn neighbours(w: &[u32]) -> Vec<Vec<u32>> {
    let mut out: Vec<Vec<u32>> = Vec::new();
    let doubled: Vec<u32> = w.iter().map(|x| 2 * x).collect();
    for base in [w.to_vec(), doubled] {
        for i in 0..base.len() {
            for up in [true, false] {
                let mut v = base.clone();
                if up {
                    v[i] += 1;
                } else if v[i] > 1 {
                    v[i] -= 1;
                } else {
                    continue;
                }
                if !out.contains(&v) && v.iter().any(|&x| x != v[0]) {
                    out.push(v);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn narrow_vectors_stay_within_a_factor_four_and_weight_their_unknown_heaviest() {
        let v = narrow_weights(5, 4, 200, 7);
        assert_eq!(v.len(), 200);
        assert_eq!(v, narrow_weights(5, 4, 200, 7), "deterministic");
        for (k, (unknown, w)) in v.iter().enumerate() {
            assert_eq!(*unknown, k % 4, "unknowns in turn among the visible ones");
            let low = NARROW_LOWS[(k / 4) % NARROW_LOWS.len()];
            assert!(w.iter().all(|&x| (low..=4 * low).contains(&x)), "{w:?}");
            assert_eq!(w[*unknown], *w.iter().max().unwrap(), "{w:?}");
            assert!(w.iter().any(|&x| x != w[0]));
            assert!(w.iter().all(|&x| x <= crate::groebner::MAX_WEIGHT));
        }
        let distinct: std::collections::BTreeSet<_> = v.iter().map(|(_, w)| w).collect();
        assert_eq!(distinct.len(), v.len());
        assert!(narrow_weights(1, 1, 10, 7).is_empty());
        assert!(narrow_weights(3, 0, 10, 7).is_empty());
    }

    #[test]
    fn wide_vectors_and_the_grid() {
        let v = sampled_weights(4, 50, 3);
        assert_eq!(v.len(), 50);
        for (k, w) in v.iter().enumerate() {
            let top = WEIGHT_TOPS[k % WEIGHT_TOPS.len()];
            assert!(w.iter().all(|&x| (1..=top).contains(&x)), "{w:?}");
            assert!(w.iter().any(|&x| x != w[0]));
        }
        assert_eq!(ones_and_twos(3, 100).len(), 6);
        assert!(ones_and_twos(8, 100).is_empty());
        let n = neighbours(&[1, 2]);
        assert!(!n.contains(&vec![2, 2]), "all-equal vectors are grevlex");
        assert!(n.contains(&vec![1, 3]) && n.contains(&vec![3, 4]), "{n:?}");
    }
}
