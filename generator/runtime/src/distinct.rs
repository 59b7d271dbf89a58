//! Near-duplicate solutions, which a redundant basis can produce: two read-outs that
//! [`crate::screen_redundant_readout`] polishes onto the same solution (a spurious
//! eigenvalue next to a solution's mixes their eigenvectors). No heap allocation.

/// Two solutions closer than this, relative to `max(1, max_i |y_i|)` in every unknown,
/// are one.
pub const DUPLICATE_TOLERANCE: f64 = 1e-7;

/// Whether `x` repeats `y`: every unknown within [`DUPLICATE_TOLERANCE`] times
/// `max(1, max_i |y_i|)` (over the unknowns `x` has).
pub fn repeats(x: &[f64], y: &[f64]) -> bool {
    let scale = y[..x.len().min(y.len())]
        .iter()
        .fold(1.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(y)
        .all(|(a, b)| (a - b).abs() <= DUPLICATE_TOLERANCE * scale)
}

/// The solutions kept so far (at most `CAP` of `N` unknowns), to drop a read-out that
/// repeats one ([`DistinctSolutions::insert`]).
#[derive(Clone, Debug)]
pub struct DistinctSolutions<const N: usize, const CAP: usize> {
    kept: [[f64; N]; CAP],
    len: usize,
}

impl<const N: usize, const CAP: usize> Default for DistinctSolutions<N, CAP> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize, const CAP: usize> DistinctSolutions<N, CAP> {
    /// None kept.
    pub fn new() -> Self {
        DistinctSolutions {
            kept: [[0.0; N]; CAP],
            len: 0,
        }
    }

    /// `false` if `x` repeats a kept solution ([`DUPLICATE_TOLERANCE`]); otherwise keeps
    /// it (while there is room) and returns `true`. A solution of more than `N` unknowns
    /// is never a repeat and is not kept.
    pub fn insert(&mut self, x: &[f64]) -> bool {
        if x.len() > N {
            return true;
        }
        if self.kept[..self.len].iter().any(|y| repeats(x, y)) {
            return false;
        }
        if self.len < CAP {
            self.kept[self.len][..x.len()].copy_from_slice(x);
            self.len += 1;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeats_are_dropped_and_distinct_solutions_kept() {
        let mut seen = DistinctSolutions::<2, 3>::new();
        assert!(seen.insert(&[1.0, 2.0]));
        assert!(!seen.insert(&[1.0 + 1e-9, 2.0 - 1e-9]));
        assert!(seen.insert(&[1.0 + 1e-3, 2.0]));
        // Relative to the solution's size: 1e-5 apart at 1e3 is a repeat.
        assert!(seen.insert(&[1e3, 0.0]));
        assert!(!seen.insert(&[1e3 + 1e-5, 0.0]));
        // Full: still answers, keeps no more.
        assert!(seen.insert(&[5.0, 5.0]));
        assert!(seen.insert(&[5.0, 5.0]));
        assert!(seen.insert(&[1.0; 3]));
    }
}
