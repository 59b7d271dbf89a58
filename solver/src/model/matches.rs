//! Pixel correspondences between two images: what every estimator takes as input, so it
//! belongs to the model rather than to the pair file that stores them.

/// One pixel correspondence `[[u1, v1], [u2, v2]]` (image 1, image 2).
pub type Match = [[f64; 2]; 2];

/// The number of distinct matches (bitwise, with `-0.0` and `0.0` the same): duplicates add
/// no constraint, so a sample of them is degenerate.
pub fn distinct_matches(matches: &[Match]) -> usize {
    let mut keys: Vec<[u64; 4]> = matches
        .iter()
        .map(|m| {
            [m[0][0], m[0][1], m[1][0], m[1][1]].map(|x| if x == 0.0 { 0u64 } else { x.to_bits() })
        })
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys.len()
}
