//! Linear least squares with a matrix shared by many right-hand sides: the recovery of
//! eliminated unknowns whose coefficients are data only (a translation, say). The
//! equations are `A n + b(u) = 0`, `A` the same for every solution `u` of an instance, so
//! `A` is factored once per instance and each solution costs a product with `Qᵀ` and a back
//! substitution, where the general recovery ([`super::null_vector`] of `[A b]`) factors the
//! whole matrix per solution.
//!
//! `A` (`rows x k`, `rows >= k`) is scaled by the power of two at or below its largest
//! `|a_ij|` (exactly: no rounding) and factored `A = Q R` by Householder reflections;
//! `n = -R⁻¹ (Qᵀ b)[..k]`, with `b` scaled alike, minimises `|A n + b|`. For equations
//! that have an exact solution (a minimal problem's, at one of its solutions) that
//! solution is the one returned. The factorisation keeps each reflection's `2 / vᵀv` and
//! the reciprocals of `R`'s diagonal, so that a solve multiplies only: it runs once per
//! solution, the factorisation once per instance.

/// A diagonal entry of `R` at most this (of the scaled matrix) makes `A` rank deficient.
const RANK_TOL: f64 = 1e-12;

/// Per column of the factorisation: the first entry `v_0` of its reflection's vector (the
/// others are stored below `R`'s diagonal), `2 / vᵀv`, and `1 / R_jj`.
type Reflection = (f64, f64, f64);

/// The factorisation `A = Q R` of a fixed-size `R x K` matrix (see the module
/// documentation); [`LeastSquares::solve`] per right-hand side. No heap allocation.
#[derive(Clone, Debug)]
pub struct LeastSquares<const R: usize, const K: usize> {
    /// Householder vectors below the diagonal, `R` on and above it (row-major).
    qr: [[f64; K]; R],
    /// Per column, its reflection and `R`'s diagonal ([`Reflection`]).
    reflections: [Reflection; K],
    /// The reciprocal of the power of two `A` and every `b` are scaled by.
    inv_scale: f64,
}

impl<const R: usize, const K: usize> LeastSquares<R, K> {
    /// Factors `a`; `None` if `K == 0`, `R < K`, an entry is not finite, `a` is zero (or
    /// its largest entry subnormal), or its rank is below `K`. Never panics.
    #[inline]
    pub fn new(a: &[[f64; K]; R]) -> Option<Self> {
        let mut qr = *a;
        let mut reflections = [(0.0, 0.0, 0.0); K];
        let inv_scale = factor(&mut qr, R, K, &mut reflections)?;
        Some(LeastSquares {
            qr,
            reflections,
            inv_scale,
        })
    }

    /// The `n` minimising `|A n + b|` (for consistent equations, `A n = -b`); `None` if a
    /// value is not finite. Never panics.
    #[inline]
    pub fn solve(&self, b: &[f64; R]) -> Option<[f64; K]> {
        let mut work = *b;
        let mut n = [0.0; K];
        solve(
            &self.qr,
            R,
            K,
            &self.reflections,
            self.inv_scale,
            &mut work,
            &mut n,
        )
        .then_some(n)
    }
}

/// [`LeastSquares`] for sizes known at run time only (the interpreter's entry point): `a`
/// row-major `rows x k`, one right-hand side `b` of `rows` entries; the same algorithm and
/// the same bits. Allocates its work space.
pub fn least_squares_dyn(a: &[f64], rows: usize, k: usize, b: &[f64]) -> Option<Vec<f64>> {
    if a.len() != rows * k || b.len() != rows {
        return None;
    }
    let mut qr = RowMajor {
        entries: a.to_vec(),
        cols: k,
    };
    let mut reflections = vec![(0.0, 0.0, 0.0); k];
    let inv_scale = factor(&mut qr, rows, k, &mut reflections)?;
    let mut work = b.to_vec();
    let mut n = vec![0.0; k];
    solve(&qr, rows, k, &reflections, inv_scale, &mut work, &mut n).then_some(n)
}

/// Entry access shared by the fixed-size array (whose indices the compiler checks once and
/// whose loops it unrolls) and the run-time-sized row-major matrix, so that both run the
/// same operations in the same order.
trait Grid {
    fn get(&self, i: usize, j: usize) -> f64;
    fn get_mut(&mut self, i: usize, j: usize) -> &mut f64;
    /// Every entry, for the scaling pass.
    fn entries_mut(&mut self) -> &mut [f64];
}

impl<const R: usize, const K: usize> Grid for [[f64; K]; R] {
    #[inline(always)]
    fn get(&self, i: usize, j: usize) -> f64 {
        self[i][j]
    }
    #[inline(always)]
    fn get_mut(&mut self, i: usize, j: usize) -> &mut f64 {
        &mut self[i][j]
    }
    #[inline(always)]
    fn entries_mut(&mut self) -> &mut [f64] {
        self.as_flattened_mut()
    }
}

/// A row-major matrix of `cols` columns.
struct RowMajor {
    entries: Vec<f64>,
    cols: usize,
}

impl Grid for RowMajor {
    fn get(&self, i: usize, j: usize) -> f64 {
        self.entries[i * self.cols + j]
    }
    fn get_mut(&mut self, i: usize, j: usize) -> &mut f64 {
        &mut self.entries[i * self.cols + j]
    }
    fn entries_mut(&mut self) -> &mut [f64] {
        &mut self.entries
    }
}

/// Scales the `r x k` matrix `a` by the power of two at or below its largest `|a_ij|` and
/// overwrites it with its Householder QR (see [`LeastSquares::qr`]); returns the scale's
/// reciprocal, `None` if the matrix is not of full column rank (or not finite, or its
/// largest entry zero or subnormal, or `r < k`, or `k == 0`). Inlined, so that
/// [`LeastSquares`]'s fixed sizes unroll its loops.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // indices shared with `Grid`'s (i, j)
fn factor<G: Grid>(a: &mut G, r: usize, k: usize, reflections: &mut [Reflection]) -> Option<f64> {
    if k == 0 || r < k {
        return None;
    }
    let mut max = 0.0f64;
    let mut finite = true;
    for x in a.entries_mut().iter() {
        finite &= x.is_finite();
        max = max.max(x.abs());
    }
    if !finite || !max.is_normal() {
        return None;
    }
    // 2^floor(log2 max): the exponent bits alone. Its reciprocal is exact.
    let inv_scale = 1.0 / f64::from_bits(max.to_bits() & 0x7ff0_0000_0000_0000);
    a.entries_mut().iter_mut().for_each(|x| *x *= inv_scale);
    for j in 0..k {
        // The sums in the order of the iterator sums they replace (the same bits).
        let ajj = a.get(j, j);
        let mut column = -0.0 + ajj * ajj;
        let mut below = -0.0;
        for i in j + 1..r {
            column += a.get(i, j) * a.get(i, j);
            below += a.get(i, j) * a.get(i, j);
        }
        let norm = column.sqrt();
        if norm.is_nan() || norm <= RANK_TOL {
            return None;
        }
        // Reflection mapping a[j.., j] to (alpha, 0, ...): v = a[j.., j] - alpha e_1.
        let alpha = if ajj > 0.0 { -norm } else { norm };
        let v0 = ajj - alpha;
        let beta = 2.0 / (v0 * v0 + below);
        for c in j + 1..k {
            let mut d = -0.0;
            for i in j + 1..r {
                d += a.get(i, j) * a.get(i, c);
            }
            let f = beta * (v0 * a.get(j, c) + d);
            *a.get_mut(j, c) -= f * v0;
            for i in j + 1..r {
                let aij = a.get(i, j);
                *a.get_mut(i, c) -= f * aij;
            }
        }
        *a.get_mut(j, j) = alpha;
        reflections[j] = (v0, beta, 1.0 / alpha);
    }
    Some(inv_scale)
}

/// `n = -R⁻¹ (Qᵀ (b · inv_scale))[..k]` from the factorisation of [`factor`]; `b` is work
/// space.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // indices shared with `Grid`'s (i, j)
fn solve<G: Grid>(
    qr: &G,
    r: usize,
    k: usize,
    reflections: &[Reflection],
    inv_scale: f64,
    b: &mut [f64],
    n: &mut [f64],
) -> bool {
    b.iter_mut().for_each(|x| *x *= inv_scale);
    for (j, &(v0, beta, _)) in reflections.iter().enumerate().take(k) {
        let mut d = -0.0;
        for i in j + 1..r {
            d += qr.get(i, j) * b[i];
        }
        let f = beta * (v0 * b[j] + d);
        b[j] -= f * v0;
        for i in j + 1..r {
            b[i] -= f * qr.get(i, j);
        }
    }
    for i in (0..k).rev() {
        let mut s = -0.0;
        for l in i + 1..k {
            s += qr.get(i, l) * n[l];
        }
        n[i] = -(b[i] + s) * reflections[i].2;
    }
    n.iter().all(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn solves_consistent_and_overdetermined_systems() {
        let mut rng = ChaCha8Rng::seed_from_u64(71);
        for _ in 0..200 {
            let a: [[f64; 3]; 6] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
            let n: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-5.0..5.0));
            // Consistent: b = -A n.
            let b: [f64; 6] = std::array::from_fn(|i| -(0..3).map(|j| a[i][j] * n[j]).sum::<f64>());
            let ls = LeastSquares::new(&a).unwrap();
            let got = ls.solve(&b).unwrap();
            for j in 0..3 {
                assert!((got[j] - n[j]).abs() < 1e-11, "{got:?} {n:?}");
            }
            // The same bits at run-time sizes.
            let dynamic = least_squares_dyn(a.as_flattened(), 6, 3, &b).unwrap();
            assert_eq!(dynamic, got.to_vec());
            // Inconsistent: the residual is orthogonal to the columns (normal equations).
            let noisy: [f64; 6] = std::array::from_fn(|i| b[i] + rng.gen_range(-0.1..0.1));
            let x = ls.solve(&noisy).unwrap();
            let res: Vec<f64> = (0..6)
                .map(|i| (0..3).map(|j| a[i][j] * x[j]).sum::<f64>() + noisy[i])
                .collect();
            let gradient = (0..3).map(|j| (0..6).map(|i| a[i][j] * res[i]).sum::<f64>());
            for g in gradient {
                assert!(g.abs() < 1e-12, "{g}");
            }
        }
    }

    #[test]
    fn rank_deficiency_and_bad_input_give_none() {
        let rank1 = [[1.0, 2.0], [2.0, 4.0], [-1.0, -2.0]];
        assert!(LeastSquares::new(&rank1).is_none());
        assert!(LeastSquares::new(&[[0.0; 2]; 3]).is_none());
        assert!(LeastSquares::new(&[[f64::NAN, 1.0], [1.0, 0.0]]).is_none());
        assert!(LeastSquares::<1, 2>::new(&[[1.0, 0.0]]).is_none());
        let ls = LeastSquares::new(&[[1.0, 0.0], [0.0, 1.0]]).unwrap();
        assert!(ls.solve(&[f64::INFINITY, 0.0]).is_none());
        assert_eq!(least_squares_dyn(&[1.0; 5], 3, 2, &[0.0; 3]), None);
    }
}
