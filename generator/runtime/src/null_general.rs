//! Null vectors of `R x N` matrices for any `N`: the recovery of linearly eliminated
//! unknowns when there are not exactly three of them, or when the equations are
//! inhomogeneous in them (the constant column appended, [`dehomogenize`]).

/// Rank threshold: a pivot of the QR factorisation (rows scaled so that max |a_ij| = 1)
/// at most this makes the matrix rank deficient beyond a one-dimensional null space.
const RANK_TOL: f64 = 1e-12;

/// Unit null vector (sign arbitrary) of the `R x N` matrix with the given rows, for a
/// matrix of rank `N - 1` (at least `N - 1` rows): Householder QR with column pivoting of
/// the rows scaled to max |a_ij| = 1, then back substitution with the last pivoted unknown
/// set to 1. With more rows than `N - 1` the extra rows enter the factorisation, so
/// inconsistent (noisy) rows are weighed together rather than ignored.
///
/// `None` if `N == 0`, `R < N - 1`, an entry is not finite, every entry is zero, or the
/// rank is below `N - 1`. Never panics, never allocates.
pub fn null_vector<const R: usize, const N: usize>(rows: &[[f64; N]; R]) -> Option<[f64; N]> {
    let mut a = *rows;
    let (mut perm, mut x, mut out) = ([0usize; N], [0.0; N], [0.0; N]);
    null_vector_core(a.as_flattened_mut(), R, N, &mut perm, &mut x, &mut out).then_some(out)
}

/// [`null_vector`] for a matrix whose size is known at run time only (row-major `rows x
/// n` entries; the interpreter's entry point): the same algorithm and result. Allocates
/// its work space.
pub fn null_vector_dyn(entries: &[f64], rows: usize, n: usize) -> Option<Vec<f64>> {
    if entries.len() != rows * n {
        return None;
    }
    let mut a = entries.to_vec();
    let (mut perm, mut x, mut out) = (vec![0usize; n], vec![0.0; n], vec![0.0; n]);
    null_vector_core(&mut a, rows, n, &mut perm, &mut x, &mut out).then_some(out)
}

/// The affine point of a homogeneous null vector `v` (its last entry the homogenising
/// coordinate): `v[..K] / v[K]` into `out`. `false` (a solution at infinity) if
/// `|v[K]|` is at most [`crate::MIN_UNIT_ENTRY`] of the unit vector or a value is not
/// finite.
pub fn dehomogenize(v: &[f64], out: &mut [f64]) -> bool {
    let k = out.len();
    if v.len() != k + 1 {
        return false;
    }
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let w = v[k];
    // Also false for NaN.
    if w.abs().partial_cmp(&(crate::MIN_UNIT_ENTRY * norm)) != Some(std::cmp::Ordering::Greater) {
        return false;
    }
    for (o, x) in out.iter_mut().zip(v) {
        *o = x / w;
    }
    out.iter().all(|x| x.is_finite())
}

/// Divides every entry of `a` by the largest magnitude among them and returns it; `None`
/// (`a` untouched) if an entry is not finite or every entry is zero.
pub(crate) fn scale_to_unit_max(a: &mut [f64]) -> Option<f64> {
    let mut max = 0.0f64;
    for x in a.iter() {
        if !x.is_finite() {
            return None;
        }
        max = max.max(x.abs());
    }
    if max == 0.0 {
        return None;
    }
    a.iter_mut().for_each(|x| *x /= max);
    Some(max)
}

/// The algorithm of [`null_vector`] on row-major `a` (`r x n`, overwritten); `perm` and `x`
/// are work space of length `n`.
fn null_vector_core(
    a: &mut [f64],
    r: usize,
    n: usize,
    perm: &mut [usize],
    x: &mut [f64],
    out: &mut [f64],
) -> bool {
    if n == 0 || r + 1 < n || scale_to_unit_max(a).is_none() {
        return false;
    }
    for (j, p) in perm.iter_mut().enumerate() {
        *p = j;
    }
    let at = |i: usize, j: usize| i * n + j;
    for j in 0..n - 1 {
        // Column pivoting: the remaining column of largest norm (rows j..r).
        let (mut best, mut best_norm) = (j, -1.0);
        for c in j..n {
            let s: f64 = (j..r).map(|i| a[at(i, c)] * a[at(i, c)]).sum();
            if s > best_norm {
                best_norm = s;
                best = c;
            }
        }
        if best != j {
            for i in 0..r {
                a.swap(at(i, j), at(i, best));
            }
            perm.swap(j, best);
        }
        let norm = best_norm.sqrt();
        if norm.is_nan() || norm <= RANK_TOL {
            return false;
        }
        // Householder reflection mapping a[j.., j] to (alpha, 0, ...).
        let alpha = if a[at(j, j)] > 0.0 { -norm } else { norm };
        let v0 = a[at(j, j)] - alpha;
        // v = (v0, a[j+1.., j]); H = I - 2 v v^T / v^T v, v^T v = 2 norm (norm + |a_jj|).
        let vtv = v0 * v0 + (j + 1..r).map(|i| a[at(i, j)] * a[at(i, j)]).sum::<f64>();
        if vtv > 0.0 {
            for c in j + 1..n {
                let mut d = v0 * a[at(j, c)];
                for i in j + 1..r {
                    d += a[at(i, j)] * a[at(i, c)];
                }
                let f = 2.0 * d / vtv;
                a[at(j, c)] -= f * v0;
                for i in j + 1..r {
                    a[at(i, c)] -= f * a[at(i, j)];
                }
            }
        }
        a[at(j, j)] = alpha;
    }
    // R x = 0 with x[n-1] = 1 (pivoted order), by back substitution.
    x[n - 1] = 1.0;
    for i in (0..n - 1).rev() {
        let s: f64 = (i + 1..n).map(|l| a[at(i, l)] * x[l]).sum();
        x[i] = -s / a[at(i, i)];
    }
    let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !norm.is_finite() || norm == 0.0 {
        return false;
    }
    // Pivoted position i holds unknown perm[i].
    for (i, &p) in perm.iter().enumerate() {
        out[p] = x[i] / norm;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Rows orthogonal to a random unit vector `v` (so `v` spans the null space).
    fn matrix<const R: usize, const N: usize>(rng: &mut ChaCha8Rng) -> ([[f64; N]; R], [f64; N]) {
        let mut v: [f64; N] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.iter_mut().for_each(|x| *x /= n);
        let rows = std::array::from_fn(|_| {
            let mut r: [f64; N] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let d: f64 = r.iter().zip(&v).map(|(a, b)| a * b).sum();
            r.iter_mut().zip(&v).for_each(|(a, b)| *a -= d * b);
            r
        });
        (rows, v)
    }

    fn up_to_sign(a: &[f64], b: &[f64]) -> f64 {
        let dist = |sign: f64| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (sign * x - y).abs())
                .fold(0.0, f64::max)
        };
        dist(1.0).min(dist(-1.0))
    }

    #[test]
    fn recovers_the_null_space_of_square_and_tall_matrices() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        for _ in 0..200 {
            let (rows, v) = matrix::<3, 4>(&mut rng);
            let got = null_vector(&rows).unwrap();
            assert!(up_to_sign(&got, &v) < 1e-12, "{got:?} {v:?}");
            let (rows, v) = matrix::<7, 5>(&mut rng);
            let got = null_vector(&rows).unwrap();
            assert!(up_to_sign(&got, &v) < 1e-12, "{got:?} {v:?}");
            let dynamic = null_vector_dyn(rows.as_flattened(), 7, 5).unwrap();
            assert_eq!(dynamic, got.to_vec());
        }
    }

    #[test]
    fn agrees_with_null_vector3_on_three_columns() {
        let mut rng = ChaCha8Rng::seed_from_u64(32);
        for _ in 0..100 {
            let (rows, v) = matrix::<6, 3>(&mut rng);
            let a = null_vector(&rows).unwrap();
            let b = crate::null_vector3(&rows).unwrap();
            assert!(up_to_sign(&a, &b) < 1e-12 && up_to_sign(&a, &v) < 1e-12);
        }
    }

    #[test]
    fn rank_deficiency_and_bad_input_give_none() {
        // Rank 1 in 3 columns: a two-dimensional null space.
        let rows = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [-1.0, -2.0, -3.0]];
        assert_eq!(null_vector(&rows), None);
        assert_eq!(null_vector(&[[0.0; 4]; 3]), None);
        assert_eq!(null_vector(&[[1.0, 0.0, 0.0, 0.0]; 2]), None); // too few rows
        let mut rows = [
            [1.0, 2.0, 3.0, 4.0],
            [0.0, 1.0, 0.0, 1.0],
            [1.0, 0.0, 1.0, 0.0],
        ];
        assert!(null_vector(&rows).is_some());
        rows[1][2] = f64::NAN;
        assert_eq!(null_vector(&rows), None);
        assert_eq!(null_vector_dyn(&[1.0, 2.0], 1, 3), None);
    }

    #[test]
    fn affine_points_of_null_vectors() {
        let mut out = [0.0; 2];
        assert!(dehomogenize(&[2.0, -4.0, 2.0], &mut out));
        assert_eq!(out, [1.0, -2.0]);
        assert!(!dehomogenize(&[1.0, 1.0, 1e-14], &mut out));
        assert!(!dehomogenize(&[1.0, 1.0], &mut out));
    }
}
