//! Real eigenpairs of small dense matrices (action matrices).

use super::SolutionSet;
use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, DimDiff, DimSub, SMatrix, SVector, Schur, U1};

/// A complex-conjugate pair of the real Schur form whose imaginary part is at most
/// `NEAR_REAL_TOL * |real part|` (at least `eps * max|m_ij|`) is taken as one real (double)
/// eigenvalue, its real part (a real double root perturbed by rounding splits into such a
/// pair). Relative to the eigenvalue, not to the matrix: badly scaled action matrices have
/// entries many orders above their eigenvalues, and a tolerance on the entries would pass
/// genuinely complex pairs off as real.
pub const NEAR_REAL_TOL: f64 = 1e-8;

/// Shifts tried, as multiples of `|m|_F / N`, when the Schur iteration does not converge.
/// Action matrices of problems with a sign symmetry (solutions `(a, t)` and `(a, -t)`, action
/// variable from `t`) have eigenvalues in `±λ` pairs, on which Francis double-shift QR
/// without exceptional shifts can stall; `m + σI` has the same eigenvectors and breaks the
/// symmetry of the spectrum.
const RETRY_SHIFTS: [f64; 2] = [0.618, -1.7];

/// Iteration cap of the Schur decomposition: `BASE_SWEEPS + SWEEPS_PER_EIGENVALUE * N`.
/// nalgebra's Francis iteration has no exceptional shifts, and action matrices whose
/// spectrum is symmetric (`±λ` pairs and `±a ± bi` quadruples from a sign symmetry of the
/// problem) were seen to need several hundred sweeps at N = 12; the cap only bounds the
/// rare slow cases (typical matrices converge in a few sweeps per eigenvalue).
const SWEEPS_PER_EIGENVALUE: usize = 100;
/// See [`SWEEPS_PER_EIGENVALUE`].
const BASE_SWEEPS: usize = 1000;

/// Real eigenvalues and unit eigenvectors of `m`: `m v = lambda v`, `|v| = 1` (the sign of
/// `v` is arbitrary). At most `N` pairs, in the order of the real Schur form's diagonal.
///
/// Algorithm: real Schur decomposition `m = Q T Q^T` with an iteration cap
/// (`nalgebra::Schur::try_new`); for every real 1x1 block of the quasi-triangular `T` (and
/// for real-eigenvalue or near-real 2x2 blocks, see [`NEAR_REAL_TOL`]) the eigenvector of
/// `T` by back substitution (2x2 blocks above it solved as 2x2 systems; tiny denominators
/// replaced by `eps * max|m_ij|` as in LAPACK `trevc`), then `v = Q y`, normalised.
/// Complex pairs are skipped.
///
/// Returns an empty set, never panics, if `m` has a non-finite entry, is zero, or the
/// Schur iteration does not converge; eigenpairs whose vector is not finite are dropped.
/// No heap allocation.
pub fn real_eigenpairs<const N: usize>(
    m: &SMatrix<f64, N, N>,
) -> SolutionSet<(f64, SVector<f64, N>), N>
where
    Const<N>: DimSub<U1>,
    DefaultAllocator: Allocator<Const<N>, DimDiff<Const<N>, U1>> + Allocator<DimDiff<Const<N>, U1>>,
{
    let mut out = SolutionSet::filled_with((0.0, SVector::zeros()));
    if N == 0 {
        return out;
    }
    let mut scale = 0.0f64;
    for &x in m.iter() {
        let a = x.abs();
        if !a.is_finite() {
            return out;
        }
        scale = scale.max(a);
    }
    if scale == 0.0 {
        return out;
    }
    let max_iter = BASE_SWEEPS + SWEEPS_PER_EIGENVALUE * N;
    let mut shift = 0.0;
    let mut schur = Schur::<f64, Const<N>>::try_new(*m, f64::EPSILON, max_iter);
    for factor in RETRY_SHIFTS {
        if schur.is_some() {
            break;
        }
        shift = factor * m.norm() / N as f64;
        let shifted = m + SMatrix::<f64, N, N>::identity() * shift;
        schur = Schur::<f64, Const<N>>::try_new(shifted, f64::EPSILON, max_iter);
    }
    let Some(schur) = schur else {
        return out;
    };
    let (q, t) = schur.unpack();
    let smin = (f64::EPSILON * scale).max(f64::MIN_POSITIVE);
    let ctx = Ctx { t: &t, scale, smin };

    // Block structure: second[r] is true if row r is the second row of a 2x2 block.
    let mut second = [false; N];
    let mut i = 0;
    while i < N {
        if i + 1 < N && t[(i + 1, i)] != 0.0 {
            second[i + 1] = true;
            i += 2;
        } else {
            i += 1;
        }
    }

    let mut i = 0;
    while i < N {
        if i + 1 < N && second[i + 1] {
            let (a, b, c, d) = (t[(i, i)], t[(i, i + 1)], t[(i + 1, i)], t[(i + 1, i + 1)]);
            let half = 0.5 * (a - d);
            let disc = half * half + b * c;
            let mean = 0.5 * (a + d);
            if disc >= 0.0 {
                let s = disc.sqrt();
                for lam in [mean + s, mean - s] {
                    ctx.push_block2(&q, &second, i, lam, &mut out);
                }
            } else if (-disc).sqrt() <= (NEAR_REAL_TOL * (mean - shift).abs()).max(smin) {
                ctx.push_block2(&q, &second, i, mean, &mut out);
            }
            i += 2;
        } else {
            let mut y = [0.0; N];
            y[i] = 1.0;
            let lam = t[(i, i)];
            ctx.back_substitute(&second, &mut y, i, i, lam);
            push_vector(&q, &y, i, lam, &mut out);
            i += 1;
        }
    }
    for pair in out.as_mut_slice() {
        pair.0 -= shift;
    }
    out
}

struct Ctx<'a, const N: usize> {
    t: &'a SMatrix<f64, N, N>,
    scale: f64,
    smin: f64,
}

impl<const N: usize> Ctx<'_, N> {
    /// Eigenvector for the real eigenvalue `lam` of the 2x2 block at rows `i, i+1`.
    fn push_block2(
        &self,
        q: &SMatrix<f64, N, N>,
        second: &[bool; N],
        i: usize,
        lam: f64,
        out: &mut SolutionSet<(f64, SVector<f64, N>), N>,
    ) {
        let t = self.t;
        let (a, b, c, d) = (t[(i, i)], t[(i, i + 1)], t[(i + 1, i)], t[(i + 1, i + 1)]);
        // Null vector of [a-lam, b; c, d-lam] from its larger row.
        let (r1, r2) = ((a - lam).hypot(b), c.hypot(d - lam));
        let (y0, y1) = if r1 == 0.0 && r2 == 0.0 {
            (1.0, 0.0)
        } else if r1 >= r2 {
            (b, lam - a)
        } else {
            (lam - d, c)
        };
        let mut y = [0.0; N];
        y[i] = y0;
        y[i + 1] = y1;
        self.back_substitute(second, &mut y, i, i + 1, lam);
        push_vector(q, &y, i + 1, lam, out);
    }

    /// Solves `(T - lam I) y = 0` for rows above `k0`, given `y[k0..=k1]` (zero after `k1`).
    fn back_substitute(
        &self,
        second: &[bool; N],
        y: &mut [f64; N],
        k0: usize,
        k1: usize,
        lam: f64,
    ) {
        let t = self.t;
        let mut r = k0;
        while r > 0 {
            let i = r - 1;
            if second[i] {
                // 2x2 block at rows i-1, i.
                let h = i - 1;
                let (mut s0, mut s1) = (0.0, 0.0);
                for j in i + 1..=k1 {
                    s0 += t[(h, j)] * y[j];
                    s1 += t[(i, j)] * y[j];
                }
                let a = t[(h, h)] - lam;
                let b = t[(h, i)];
                let c = t[(i, h)];
                let d = t[(i, i)] - lam;
                let mut det = a * d - b * c;
                let dmin = self.smin * self.scale;
                if det.abs() < dmin {
                    det = if det < 0.0 { -dmin } else { dmin };
                }
                // [a b; c d] z = -s
                y[h] = (-s0 * d + s1 * b) / det;
                y[i] = (-s1 * a + s0 * c) / det;
                r = h;
            } else {
                let mut s = 0.0;
                for j in i + 1..=k1 {
                    s += t[(i, j)] * y[j];
                }
                let mut den = t[(i, i)] - lam;
                if den.abs() < self.smin {
                    den = if den < 0.0 { -self.smin } else { self.smin };
                }
                y[i] = -s / den;
                r = i;
            }
        }
    }
}

/// Pushes `(lam, Q y / |Q y|)` where `y` is zero after `k1`, if finite.
fn push_vector<const N: usize>(
    q: &SMatrix<f64, N, N>,
    y: &[f64; N],
    k1: usize,
    lam: f64,
    out: &mut SolutionSet<(f64, SVector<f64, N>), N>,
) {
    let mut v = SVector::<f64, N>::zeros();
    for (j, &yj) in y.iter().enumerate().take(k1 + 1) {
        if yj != 0.0 {
            v.axpy(yj, &q.column(j), 1.0);
        }
    }
    let n = v.norm();
    if n > 0.0 && n <= f64::MAX && lam.is_finite() {
        v /= n;
        if v.iter().all(|x| x.is_finite()) {
            out.push((lam, v));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Complex, SMatrix};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random<const N: usize>(rng: &mut ChaCha8Rng) -> SMatrix<f64, N, N> {
        SMatrix::from_fn(|_, _| rng.gen_range(-1.0..1.0))
    }

    fn residual<const N: usize>(m: &SMatrix<f64, N, N>, lam: f64, v: &SVector<f64, N>) -> f64 {
        (m * v - v * lam).norm() / m.norm()
    }

    #[test]
    fn symmetric_matches_nalgebra() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _ in 0..50 {
            let a = random::<10>(&mut rng);
            let s = a + a.transpose();
            let pairs = real_eigenpairs(&s);
            assert_eq!(pairs.len(), 10);
            let mut got: Vec<f64> = pairs.iter().map(|p| p.0).collect();
            let mut want: Vec<f64> = s.symmetric_eigenvalues().iter().copied().collect();
            got.sort_by(f64::total_cmp);
            want.sort_by(f64::total_cmp);
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() < 1e-12, "{g} vs {w}");
            }
            for (lam, v) in &pairs {
                assert!(residual(&s, *lam, v) < 1e-13);
                assert!((v.norm() - 1.0).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn known_real_eigenvalues_and_a_complex_pair() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        for trial in 0..50 {
            // D: 8 real eigenvalues plus a pair 0.3 +- 0.7i.
            let mut d = SMatrix::<f64, 10, 10>::zeros();
            let reals: Vec<f64> = (0..8)
                .map(|k| k as f64 - 3.5 + 0.1 * trial as f64)
                .collect();
            for (k, &r) in reals.iter().enumerate() {
                d[(k, k)] = r;
            }
            d[(8, 8)] = 0.3;
            d[(9, 9)] = 0.3;
            d[(8, 9)] = 0.7;
            d[(9, 8)] = -0.7;
            let p = random::<10>(&mut rng) + SMatrix::<f64, 10, 10>::identity() * 2.0;
            let Some(pinv) = p.try_inverse() else {
                continue;
            };
            let m = p * d * pinv;
            let pairs = real_eigenpairs(&m);
            assert_eq!(pairs.len(), 8, "trial {trial}");
            for (lam, v) in &pairs {
                let k = reals
                    .iter()
                    .position(|r| (r - lam).abs() < 1e-8)
                    .expect("eigenvalue is one of the known ones");
                // v parallel to column k of P.
                let pk = p.column(k).normalize();
                assert!((pk.dot(v).abs() - 1.0).abs() < 1e-8);
                assert!(residual(&m, *lam, v) < 1e-12);
            }
        }
    }

    #[test]
    fn general_random_matrices_count_real_eigenvalues() {
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        for _ in 0..200 {
            let m = random::<20>(&mut rng);
            let pairs = real_eigenpairs(&m);
            let ev: Vec<Complex<f64>> = m.complex_eigenvalues().iter().copied().collect();
            let nreal = ev.iter().filter(|c| c.im == 0.0).count();
            assert_eq!(pairs.len(), nreal);
            for (lam, v) in &pairs {
                assert!(residual(&m, *lam, v) < 1e-12, "{}", residual(&m, *lam, v));
            }
        }
    }

    #[test]
    fn double_root_and_small_sizes() {
        // Jordan-like block with a double eigenvalue 2 and a simple 5.
        let m = SMatrix::<f64, 3, 3>::new(2.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 5.0);
        let pairs = real_eigenpairs(&m);
        assert!(pairs.iter().any(|p| (p.0 - 5.0).abs() < 1e-12));
        assert!(pairs.iter().any(|p| (p.0 - 2.0).abs() < 1e-6));
        for (lam, v) in &pairs {
            assert!(residual(&m, *lam, v) < 1e-6);
        }
        let one = SMatrix::<f64, 1, 1>::new(-4.0);
        let p = real_eigenpairs(&one);
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].0, -4.0);
        let rot = SMatrix::<f64, 2, 2>::new(0.0, -1.0, 1.0, 0.0);
        assert!(real_eigenpairs(&rot).is_empty());
        let two = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 3.0, 4.0);
        let p = real_eigenpairs(&two);
        assert_eq!(p.len(), 2);
        for (lam, v) in &p {
            assert!(residual(&two, *lam, v) < 1e-14);
        }
    }

    #[test]
    fn non_finite_and_zero_give_nothing() {
        let mut m = SMatrix::<f64, 10, 10>::identity();
        m[(3, 4)] = f64::NAN;
        assert!(real_eigenpairs(&m).is_empty());
        m[(3, 4)] = f64::INFINITY;
        assert!(real_eigenpairs(&m).is_empty());
        assert!(real_eigenpairs(&SMatrix::<f64, 10, 10>::zeros()).is_empty());
        let huge = SMatrix::<f64, 10, 10>::from_element(1e300);
        for (lam, v) in &real_eigenpairs(&huge) {
            assert!(lam.is_finite() && v.iter().all(|x| x.is_finite()));
        }
    }
}
