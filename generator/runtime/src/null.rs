//! Null vectors of n x 3 matrices.

#[inline]
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
fn scaled(r: [f64; 3], s: f64) -> [f64; 3] {
    [r[0] * s, r[1] * s, r[2] * s]
}

/// Rank threshold: the best cross product of two rows (scaled so that max |a_ij| = 1)
/// must have a norm above this, otherwise the matrix has rank < 2.
const RANK_TOL: f64 = 1e-12;

/// The cross-product candidate is returned at once if `|A v|` (rows scaled to
/// max |a_ij| = 1) is at most this.
const CONSISTENT_RESID: f64 = 1e-13;

/// Unit null vector (sign arbitrary) of the `R x 3` matrix with the given rows, `R >= 2`:
/// in the least-squares sense, the unit `v` minimising `|A v|`.
///
/// Method: the cross product of the best-conditioned pair of rows (all pairs for
/// `n <= 8`, else the largest row against every other) — exact to rounding when `A` has
/// rank 2 — and, for `n > 2`, the eigenvector of the smallest eigenvalue of `A^T A`
/// (closed-form 3x3 symmetric eigenvalue, then the best cross product of the rows of
/// `A^T A - lambda I`); the candidate with the smaller `|A v|` wins (evaluated on the rows,
/// not on `A^T A`, so noise-free inputs keep their full accuracy). Shortcuts: for three
/// rows, the largest cross product of two of them when the third agrees to 1e-10
/// (`square_fast_path`); otherwise the cross product of the two longest rows (when they
/// are far from parallel), then the best pair, are returned as soon as `|A v| <= 1e-13`
/// (scaled rows).
///
/// `None` if `R < 2`, an entry is not finite, or the rank is below 2.
/// Never panics, never allocates.
#[inline]
pub fn null_vector3<const R: usize>(rows: &[[f64; 3]; R]) -> Option<[f64; 3]> {
    if let [r0, r1, r2] = rows[..] {
        if let Some(v) = square_fast_path([r0, r1, r2]) {
            return Some(v);
        }
    }
    null_vector3_general(rows)
}

/// [`null_vector3`] without its fast path for square matrices.
#[inline(never)]
fn null_vector3_general<const R: usize>(rows: &[[f64; 3]; R]) -> Option<[f64; 3]> {
    let inv = 1.0 / max_abs(rows)?;
    // Scaled once: the fast path alone reads every row three times.
    let scaled_rows: [[f64; 3]; R] = std::array::from_fn(|i| scaled(rows[i], inv));
    null_vector3_scaled(R, |i| scaled_rows[i])
}

/// [`null_vector3`] for any number of rows (a slice; the interpreter's entry point, for
/// matrices whose size is known at run time only): the same algorithm and the same
/// result, the rows scaled as they are read instead of copied. Never allocates.
pub fn null_vector3_rows(rows: &[[f64; 3]]) -> Option<[f64; 3]> {
    if let [r0, r1, r2] = rows[..] {
        if let Some(v) = square_fast_path([r0, r1, r2]) {
            return Some(v);
        }
    }
    let inv = 1.0 / max_abs(rows)?;
    null_vector3_scaled(rows.len(), |i| scaled(rows[i], inv))
}

/// The null vector of a 3 x 3 matrix of rank 2 whose rows are consistent, the usual case
/// at a minimal problem's solutions: the largest of the cross products of two rows,
/// returned only where the pair is far from parallel (its cross product at least
/// [`SQUARE_PAIR_TOL`] times the largest entry squared) and the third row is orthogonal to
/// it to [`SQUARE_CONSISTENT_RESID`] times the largest entry; `None` otherwise (a
/// non-finite entry, or the largest entry's fourth power outside the floating-point
/// range), for the general method to decide. Without the general method's scaled copy of
/// the rows.
#[inline(always)]
fn square_fast_path(rows: [[f64; 3]; 3]) -> Option<[f64; 3]> {
    let (mut largest, mut sum) = (0.0f64, 0.0f64);
    for x in rows.as_flattened() {
        largest = largest.max(x.abs());
        sum += x.abs();
    }
    // A NaN or infinite entry makes the sum non-finite (`max` would skip a NaN).
    if !sum.is_finite() {
        return None;
    }
    let scale = largest * largest;
    let floor = SQUARE_PAIR_TOL * scale;
    let floor = floor * floor;
    if !(floor > f64::MIN_POSITIVE && scale * scale < f64::MAX) {
        return None;
    }
    let [r0, r1, r2] = rows;
    let crosses = [cross(r1, r2), cross(r2, r0), cross(r0, r1)];
    let norms = crosses.map(|c| dot(c, c));
    let mut k = 0;
    if norms[1] > norms[k] {
        k = 1;
    }
    if norms[2] > norms[k] {
        k = 2;
    }
    if norms[k] < floor {
        return None;
    }
    // crosses[k] is orthogonal to the two rows other than rows[k].
    let v = scaled(crosses[k], 1.0 / norms[k].sqrt());
    (dot(rows[k], v).abs() <= SQUARE_CONSISTENT_RESID * largest).then_some(v)
}

/// The smallest cross product (relative to the largest entry squared) that
/// [`square_fast_path`] takes for the null vector of two rows.
const SQUARE_PAIR_TOL: f64 = 1e-4;

/// The largest residual of the third row (relative to the largest entry) with which
/// [`square_fast_path`] takes the cross product of the other two. Looser than
/// [`CONSISTENT_RESID`]: a square matrix evaluated at an approximate root is as
/// inconsistent as the root is inaccurate, and the least-squares null vector is then no
/// nearer the exact one than the cross product (both are off by the rows' error over the
/// second singular value); what the check keeps from the fast path is a matrix of full
/// rank, whose least-squares vector is the meaningful answer.
const SQUARE_CONSISTENT_RESID: f64 = 1e-10;

/// Largest `|a_ij|`; `None` if an entry is not finite or every entry is zero.
fn max_abs(rows: &[[f64; 3]]) -> Option<f64> {
    let mut s = 0.0f64;
    for r in rows {
        for &x in r {
            let a = x.abs();
            if !a.is_finite() {
                return None;
            }
            s = s.max(a);
        }
    }
    (s > 0.0).then_some(s)
}

/// The algorithm of [`null_vector3`] on `n` rows `row(i)`, already scaled so that
/// `max |a_ij| = 1`.
#[inline(always)]
fn null_vector3_scaled(n: usize, row: impl Fn(usize) -> [f64; 3]) -> Option<[f64; 3]> {
    if n < 2 {
        return None;
    }
    let resid = |v: [f64; 3]| -> f64 {
        (0..n)
            .map(|i| {
                let d = dot(row(i), v);
                d * d
            })
            .sum()
    };

    // Fast path: the two longest rows, if they are far from parallel, give the null vector
    // of a consistent (rank-2) matrix directly.
    if n > 2 {
        let (mut i1, mut i2, mut n1, mut n2) = (0, 0, -1.0f64, -1.0f64);
        for i in 0..n {
            let ri = row(i);
            let q = dot(ri, ri);
            if q > n1 {
                (i2, n2) = (i1, n1);
                (i1, n1) = (i, q);
            } else if q > n2 {
                (i2, n2) = (i, q);
            }
        }
        let c = cross(row(i1), row(i2));
        let cn = dot(c, c);
        if cn >= 1e-2 * n1 * n2 && cn > 0.0 {
            let v = scaled(c, 1.0 / cn.sqrt());
            if resid(v) <= CONSISTENT_RESID * CONSISTENT_RESID {
                return Some(v);
            }
        }
    }

    let mut best = [0.0; 3];
    let mut bn = 0.0;
    let mut consider = |c: [f64; 3]| {
        let cn = dot(c, c);
        if cn > bn {
            bn = cn;
            best = c;
        }
    };
    if n <= 8 {
        for i in 0..n {
            let ri = row(i);
            for j in i + 1..n {
                consider(cross(ri, row(j)));
            }
        }
    } else {
        let big = (0..n)
            .max_by(|&a, &b| dot(row(a), row(a)).total_cmp(&dot(row(b), row(b))))
            .unwrap_or(0);
        let rb = row(big);
        for j in 0..n {
            if j != big {
                consider(cross(rb, row(j)));
            }
        }
    }
    if bn.is_nan() || bn.sqrt() <= RANK_TOL {
        return None;
    }
    let mut v = scaled(best, 1.0 / bn.sqrt());
    if n == 2 {
        return Some(v);
    }

    // Consistent rows (the usual case: exact or nearly exact solutions) leave the cross
    // product with a residual at rounding level, which the least-squares refinement below
    // cannot improve on: skip it.
    if resid(v) <= CONSISTENT_RESID * CONSISTENT_RESID {
        return Some(v);
    }
    // Gram matrix of the scaled rows.
    let mut g = [[0.0; 3]; 3];
    for i in 0..n {
        let r = row(i);
        for a in 0..3 {
            for b in 0..3 {
                g[a][b] += r[a] * r[b];
            }
        }
    }
    // Smallest eigenvalue of G in closed form (trigonometric method for symmetric 3x3),
    // then the null vector of G - lambda I as its best row cross product.
    let p1 = g[0][1] * g[0][1] + g[0][2] * g[0][2] + g[1][2] * g[1][2];
    let q = (g[0][0] + g[1][1] + g[2][2]) / 3.0;
    let p2 = (g[0][0] - q).powi(2) + (g[1][1] - q).powi(2) + (g[2][2] - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    if p > 0.0 {
        let b = |i: usize, j: usize| (g[i][j] - if i == j { q } else { 0.0 }) / p;
        let det = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1))
            - b(0, 1) * (b(1, 0) * b(2, 2) - b(1, 2) * b(2, 0))
            + b(0, 2) * (b(1, 0) * b(2, 1) - b(1, 1) * b(2, 0));
        let phi = (0.5 * det).clamp(-1.0, 1.0).acos() / 3.0;
        let lmin = q + 2.0 * p * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos();
        let h = [
            [g[0][0] - lmin, g[0][1], g[0][2]],
            [g[1][0], g[1][1] - lmin, g[1][2]],
            [g[2][0], g[2][1], g[2][2] - lmin],
        ];
        let cands = [cross(h[1], h[2]), cross(h[2], h[0]), cross(h[0], h[1])];
        let w = cands
            .into_iter()
            .max_by(|a, b| dot(*a, *a).total_cmp(&dot(*b, *b)))
            .unwrap_or([0.0; 3]);
        let wn = dot(w, w).sqrt();
        if wn > 0.0 && wn <= f64::MAX {
            let w = scaled(w, 1.0 / wn);
            if resid(w) < resid(v) {
                v = w;
            }
        }
    }
    Some(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn unit(rng: &mut ChaCha8Rng) -> [f64; 3] {
        let v = [
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0f64..1.0),
        ];
        scaled(v, 1.0 / dot(v, v).sqrt())
    }

    fn check_exact<const N: usize>(rng: &mut ChaCha8Rng) {
        for _ in 0..100 {
            let t = unit(rng);
            // Rows orthogonal to t: random vectors minus their component along t.
            let rows: [[f64; 3]; N] = std::array::from_fn(|_| {
                let r = unit(rng);
                let d = dot(r, t);
                let r = [r[0] - d * t[0], r[1] - d * t[1], r[2] - d * t[2]];
                scaled(r, rng.gen_range(0.1..10.0))
            });
            let v = null_vector3(&rows).unwrap();
            assert!((dot(v, t).abs() - 1.0).abs() < 1e-12);
            assert!((dot(v, v) - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn exact_null_vectors() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        check_exact::<2>(&mut rng);
        check_exact::<3>(&mut rng);
        check_exact::<5>(&mut rng);
        check_exact::<12>(&mut rng);
    }

    #[test]
    fn least_squares_with_noise() {
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        for _ in 0..100 {
            let rows: [[f64; 3]; 6] = std::array::from_fn(|_| unit(&mut rng));
            let v = null_vector3(&rows).unwrap();
            // Compare with nalgebra's smallest eigenvector of A^T A.
            let a = nalgebra::DMatrix::from_fn(6, 3, |i, j| rows[i][j]);
            let eig = (a.transpose() * &a).symmetric_eigen();
            let k = eig.eigenvalues.imin();
            let e = eig.eigenvectors.column(k);
            let c = (v[0] * e[0] + v[1] * e[1] + v[2] * e[2]).abs();
            let r = |v: [f64; 3]| rows.iter().map(|r| dot(*r, v).powi(2)).sum::<f64>();
            let opt = eig.eigenvalues[k];
            assert!(r(v) <= opt * (1.0 + 1e-9) + 1e-15, "{c} {} {}", r(v), opt);
        }
    }

    #[test]
    fn square_fast_path_agrees_with_the_general_method() {
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        for trial in 0..300 {
            let t = unit(&mut rng);
            // Rank 2 at scales from tiny to huge (beyond the fast path's range at the ends).
            let scale = 10f64.powi(trial % 13 * 50 - 300);
            let rows: [[f64; 3]; 3] = std::array::from_fn(|_| {
                let r = unit(&mut rng);
                let d = dot(r, t);
                scaled([r[0] - d * t[0], r[1] - d * t[1], r[2] - d * t[2]], scale)
            });
            let fast = null_vector3(&rows).unwrap();
            assert_eq!(null_vector3_rows(&rows), Some(fast));
            let general = null_vector3_general(&rows).unwrap();
            assert!((dot(fast, t).abs() - 1.0).abs() < 1e-12, "{scale:e}");
            assert!((dot(fast, general).abs() - 1.0).abs() < 1e-12, "{scale:e}");
        }
        // Full rank: no exact null vector, the least-squares one (the general method's).
        let rows = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1e-3]];
        assert_eq!(square_fast_path(rows), None);
        assert_eq!(null_vector3(&rows), Some([0.0, 0.0, 1.0]));
        // Rank 1 and non-finite entries: none.
        assert_eq!(null_vector3(&[[1.0, 2.0, 3.0]; 3]), None);
        assert_eq!(
            null_vector3(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, f64::NAN, 0.0]]),
            None
        );
        assert_eq!(
            null_vector3(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [f64::INFINITY, 0.0, 0.0]]),
            None
        );
    }

    #[test]
    fn degenerate_inputs() {
        assert_eq!(null_vector3(&[]), None);
        assert_eq!(null_vector3(&[[1.0, 2.0, 3.0]]), None);
        assert_eq!(null_vector3(&[[1.0, 2.0, 3.0], [2.0, 4.0, 6.0]]), None);
        assert_eq!(null_vector3(&[[0.0; 3]; 5]), None);
        assert_eq!(null_vector3(&[[1.0, f64::NAN, 3.0], [0.0, 1.0, 0.0]]), None);
        assert_eq!(
            null_vector3(&[[1.0, 0.0, 0.0], [f64::INFINITY, 1.0, 0.0]]),
            None
        );
        let v = null_vector3(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]).unwrap();
        assert_eq!(v[2].abs(), 1.0);
        let v = null_vector3(&[[1e300, 0.0, 0.0], [0.0, 1e-300, 0.0]]);
        assert!(v.is_none() || v.unwrap().iter().all(|x| x.is_finite()));
    }
}
