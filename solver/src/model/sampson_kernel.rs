//! The MSAC score of the global-shutter Sampson error, four points per step (AVX2 where
//! the CPU has it): RANSAC spends a large share of its time here.
//!
//! For a point pair `(m1, m2)` and an essential matrix `E`, `g2 = E m1`, `g1 = Eᵀ m2`,
//! `r = m2ᵀ g2`, and the squared Sampson error is `r² / (g1x² + g1y² + g2x² + g2y²)` (see
//! [`super::epipolar`]). The sum is kept in four partial sums, point `i` adding to sum
//! `i mod 4`, and they are added as `(s0 + s1) + (s2 + s3)`: the vector path then needs no
//! horizontal work per point. The scalar path evaluates exactly the same operations in the
//! same order (no fused multiply-adds in either), so both return bit-identical scores and
//! results do not depend on the CPU.

use nalgebra::{Matrix3, Vector3};

/// The bearings of both images by coordinate (structure of arrays), the layout the vector
/// path loads four points at a time from.
#[derive(Debug, Clone, Default)]
pub struct BearingColumns {
    /// `[x1, y1, z1, x2, y2, z2]`, one entry per point in each.
    coords: [Vec<f64>; 6],
}

impl BearingColumns {
    /// Columns of the bearing pairs `(m1[i], m2[i])`; extra entries of the longer slice are
    /// ignored.
    #[must_use]
    pub fn new(m1: &[Vector3<f64>], m2: &[Vector3<f64>]) -> Self {
        let n = m1.len().min(m2.len());
        let column = |v: &[Vector3<f64>], k: usize| v[..n].iter().map(|p| p[k]).collect();
        BearingColumns {
            coords: [
                column(m1, 0),
                column(m1, 1),
                column(m1, 2),
                column(m2, 0),
                column(m2, 1),
                column(m2, 2),
            ],
        }
    }

    /// Number of points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.coords[0].len()
    }

    /// True if there are no points.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// `(Σ_i min(r_i², τ²), #{i : r_i² < τ²})` over the squared Sampson errors `r_i²` of
/// `e` with `τ² = thr_sq` (summed as the module documentation says); may stop once the sum
/// exceeds `bound` (then the sum is above `bound` and the count incomplete). A non-finite
/// error counts as an outlier.
#[must_use]
pub fn msac_sampson(
    cols: &BearingColumns,
    e: &Matrix3<f64>,
    thr_sq: f64,
    bound: f64,
) -> (f64, usize) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { msac_sampson_avx2(cols, e, thr_sq, bound) };
    }
    let mut acc = Accumulator::default();
    acc.points(cols, e, thr_sq, bound, 0);
    acc.result()
}

/// The four partial MSAC sums and the inlier count.
#[derive(Default)]
struct Accumulator {
    sums: [f64; 4],
    inliers: usize,
}

impl Accumulator {
    /// The MSAC sum, `(s0 + s1) + (s2 + s3)`, and the inlier count.
    #[inline(always)]
    fn result(&self) -> (f64, usize) {
        let [a, b, c, d] = self.sums;
        ((a + b) + (c + d), self.inliers)
    }

    /// Adds points `from..` one at a time (the scalar path, and the vector path's tail);
    /// `from` must be a multiple of 4. Stops after a group of four once the sum exceeds
    /// `bound`.
    #[inline(always)]
    fn points(
        &mut self,
        c: &BearingColumns,
        e: &Matrix3<f64>,
        thr_sq: f64,
        bound: f64,
        from: usize,
    ) {
        let [x1, y1, z1, x2, y2, z2] = &c.coords;
        for i in from..c.len() {
            let (n, d) = sampson_terms(e, [x1[i], y1[i], z1[i]], [x2[i], y2[i], z2[i]]);
            // Branch-free: whether a point is an inlier is as good as random to a branch
            // predictor; `min` also maps a non-finite ratio (zero denominator) to τ².
            self.sums[i % 4] += (n / d).min(thr_sq);
            self.inliers += usize::from(n < thr_sq * d);
            if i % 4 == 3 && self.result().0 > bound {
                return;
            }
        }
    }
}

/// `(r², |∇r|²)` of one point pair; the operation order the vector path repeats.
#[inline(always)]
fn sampson_terms(e: &Matrix3<f64>, m1: [f64; 3], m2: [f64; 3]) -> (f64, f64) {
    let g2 = |i: usize| e[(i, 0)] * m1[0] + e[(i, 1)] * m1[1] + e[(i, 2)] * m1[2];
    let g1 = |j: usize| e[(0, j)] * m2[0] + e[(1, j)] * m2[1] + e[(2, j)] * m2[2];
    let (g2x, g2y, g2z) = (g2(0), g2(1), g2(2));
    let (g1x, g1y) = (g1(0), g1(1));
    let r = m2[0] * g2x + m2[1] * g2y + m2[2] * g2z;
    (r * r, g1x * g1x + g1y * g1y + g2x * g2x + g2y * g2y)
}

/// [`msac_sampson`] four points per step with AVX2 (no FMA, so every operation rounds as in
/// [`sampson_terms`]), lane `l` holding partial sum `l`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn msac_sampson_avx2(
    c: &BearingColumns,
    e: &Matrix3<f64>,
    thr_sq: f64,
    bound: f64,
) -> (f64, usize) {
    use std::arch::x86_64::{
        _mm256_add_pd, _mm256_cmp_pd, _mm256_div_pd, _mm256_loadu_pd, _mm256_min_pd,
        _mm256_movemask_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd, _mm256_storeu_pd,
        _CMP_LT_OQ,
    };
    let n = c.len();
    let [x1, y1, z1, x2, y2, z2] = &c.coords;
    let ev: [[_; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| _mm256_set1_pd(e[(i, j)])));
    let thr = _mm256_set1_pd(thr_sq);
    let mut sums = _mm256_setzero_pd();
    let mut acc = Accumulator::default();
    let mut i = 0;
    while i + 4 <= n {
        // SAFETY: i + 4 <= n, the length of every column.
        let load = |v: &[f64]| unsafe { _mm256_loadu_pd(v.as_ptr().add(i)) };
        let (a1, b1, c1) = (load(x1), load(y1), load(z1));
        let (a2, b2, c2) = (load(x2), load(y2), load(z2));
        let mul = |a, b| _mm256_mul_pd(a, b);
        let add = |a, b| _mm256_add_pd(a, b);
        let g2 = |r: usize| add(add(mul(ev[r][0], a1), mul(ev[r][1], b1)), mul(ev[r][2], c1));
        let g1 = |k: usize| add(add(mul(ev[0][k], a2), mul(ev[1][k], b2)), mul(ev[2][k], c2));
        let (g2x, g2y, g2z) = (g2(0), g2(1), g2(2));
        let (g1x, g1y) = (g1(0), g1(1));
        let r = add(add(mul(a2, g2x), mul(b2, g2y)), mul(c2, g2z));
        let num = mul(r, r);
        let den = add(
            add(add(mul(g1x, g1x), mul(g1y, g1y)), mul(g2x, g2x)),
            mul(g2y, g2y),
        );
        // `_mm256_min_pd` returns its second operand when the first is NaN, as `f64::min`.
        sums = add(sums, _mm256_min_pd(_mm256_div_pd(num, den), thr));
        let inlier_mask = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(num, mul(thr, den)));
        acc.inliers += inlier_mask.count_ones() as usize;
        i += 4;
        _mm256_storeu_pd(acc.sums.as_mut_ptr(), sums);
        if acc.result().0 > bound {
            return acc.result();
        }
    }
    acc.points(c, e, thr_sq, bound, i);
    acc.result()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn random_columns(
        n: usize,
        seed: u64,
    ) -> (BearingColumns, Vec<Vector3<f64>>, Vec<Vector3<f64>>) {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        let mut bearing = || Vector3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 1.0);
        let m1: Vec<_> = (0..n).map(|_| bearing()).collect();
        let m2: Vec<_> = (0..n).map(|_| bearing()).collect();
        (BearingColumns::new(&m1, &m2), m1, m2)
    }

    #[test]
    fn every_path_gives_the_same_bits_as_the_per_point_formula() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(3);
        for n in [0, 1, 3, 4, 5, 17, 150] {
            let (cols, m1, m2) = random_columns(n, n as u64);
            for _ in 0..20 {
                let e = Matrix3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
                let thr_sq = rng.gen_range(1e-7..1e-3);
                // Reference: nalgebra's products, one point at a time, four partial sums.
                let (mut sums, mut inliers) = ([0.0; 4], 0);
                for (i, (a, b)) in m1.iter().zip(&m2).enumerate() {
                    let g2 = e * a;
                    let g1 = e.tr_mul(b);
                    let r = b.dot(&g2);
                    let d = g1.x * g1.x + g1.y * g1.y + g2.x * g2.x + g2.y * g2.y;
                    sums[i % 4] += (r * r / d).min(thr_sq);
                    inliers += usize::from(r * r < thr_sq * d);
                }
                let sum = (sums[0] + sums[1]) + (sums[2] + sums[3]);
                let (s, k) = msac_sampson(&cols, &e, thr_sq, f64::INFINITY);
                assert_eq!((s.to_bits(), k), (sum.to_bits(), inliers), "n = {n}");
                let mut scalar = Accumulator::default();
                scalar.points(&cols, &e, thr_sq, f64::INFINITY, 0);
                let (ss, sk) = scalar.result();
                assert_eq!((ss.to_bits(), sk), (sum.to_bits(), inliers));
                // Bounded: stops above the bound, never below it.
                if sum > 0.0 {
                    let (sb, _) = msac_sampson(&cols, &e, thr_sq, 0.5 * sum);
                    assert!(sb > 0.5 * sum && sb <= sum);
                }
            }
        }
    }

    #[test]
    fn degenerate_points_are_outliers() {
        let m1 = vec![Vector3::zeros(); 6];
        let m2 = vec![Vector3::new(f64::NAN, 0.0, 1.0); 6];
        let cols = BearingColumns::new(&m1, &m2);
        let (s, k) = msac_sampson(&cols, &Matrix3::identity(), 0.25, f64::INFINITY);
        assert_eq!((s, k), (1.5, 0));
    }
}
