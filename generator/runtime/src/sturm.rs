//! Real eigenpairs of small dense matrices through the characteristic polynomial: a faster
//! alternative to the QR back end ([`super::real_eigenpairs_hqr`]) for action matrices.
//!
//! 1. Balancing (powers of 2), scaling to 1-norm 1, and reduction to upper
//!    Hessenberg form `H = S^-1 A S` by stabilised elementary similarities (Gaussian
//!    elimination with partial pivoting; `S` kept), see [`super::hessenberg`].
//! 2. Characteristic polynomial of `H` by the Hessenberg determinant recurrence
//!    (O(N^3 / 6)); every root lies in `[-1, 1]`.
//! 3. Its real roots: in closed form up to degree 4 ([`super::closed_form`]), else (and
//!    near a double root) by [`super::sturm_sequence`]: Sturm sequence (stored as linear
//!    quotients, O(N) per evaluation),
//!    quadrisection on sign-change counts (three points evaluated together) until each
//!    interval holds one root, one octasection round on the sign of `p`, then Newton
//!    steps safeguarded by the bracket.
//! 4. For every real root, the eigenvector of `H` by the backward recurrence (O(N^2 / 2));
//!    if the pair's residual is not at rounding level (the root of the rounded polynomial
//!    is less accurate than an eigenvalue from a QR iteration), one Newton step on Hyman's
//!    determinant of `H` and the recurrence again; if still not, inverse iteration on
//!    `H - lambda I` (Hessenberg LU with partial pivoting, O(N^2), up to three steps, the
//!    eigenvalue refined from the last); `v = S y`.
//!
//! A 2x2 matrix takes none of these steps: its eigenpairs are formulas
//! ([`super::closed_form`]), unless its eigenvalues are (nearly) double or a pair's residual
//! is not at rounding level. Nor does a 3x3 or 4x4 companion matrix (the action of a
//! univariate problem on its power basis), unless its roots are (nearly) double: its
//! characteristic polynomial is its first row ([`super::companion`]).
//!
//! Every loop is bounded. The QR back end takes over when the Sturm sequence degenerates
//! (a remainder vanishes exactly: multiple roots or special structure), when a root is not
//! confirmed by inverse iteration (moved by more than [`AGREE_TOL`], or a residual above
//! [`ACCEPT_RESIDUAL`]: a spurious real root from a complex pair near the real axis), or
//! when two roots converge to one eigenvalue.

use super::closed_form::{eigenpairs_2x2, monic_real_roots};
use super::companion::companion_eigenpairs;
use super::hessenberg::{
    balance, eigenvector_by_recurrence, hessenberg_of_columns, hyman_newton_step,
    inverse_iteration, normalise, subdiagonal_reciprocals, transpose,
};
use super::sturm_sequence::Sturm;
use super::{real_eigenpairs_hqr, SolutionSet};
use nalgebra::{SMatrix, SVector};

/// A root of the characteristic polynomial of the scaled matrix (norm 1) is accepted if
/// inverse iteration moves it by at most this; otherwise the QR back end is used.
const AGREE_TOL: f64 = 1e-7;
/// An eigenpair of the scaled matrix (norm 1) whose residual after inverse iteration is
/// above this is not trusted: the QR back end decides.
const ACCEPT_RESIDUAL: f64 = 1e-11;
/// The eigenvector from the Hessenberg backward recurrence is taken if the backward error
/// of the pair (scaled matrix of norm 1) is at most this; otherwise inverse iteration.
const FAST_RESIDUAL: f64 = 2e-15;

/// Same contract as [`super::real_eigenpairs`]: the real eigenvalues and unit eigenvectors
/// of `m` (at most `N`; in increasing order of eigenvalue unless the QR back end took
/// over), an empty set for non-finite or zero input; never panics, no heap allocation. A
/// real double root may be reported once; complex pairs very close to the real axis are
/// reported as one real eigenvalue only when the QR back end takes over.
pub fn real_eigenpairs_sturm<const N: usize>(
    m: &SMatrix<f64, N, N>,
) -> SolutionSet<(f64, SVector<f64, N>), N> {
    let mut out = SolutionSet::filled_with((0.0, SVector::zeros()));
    if N == 1 {
        // A single solution (a sign-folded pair, say): the entry is the eigenvalue.
        let lambda = m[(0, 0)];
        if lambda.is_finite() {
            out.push((lambda, SVector::from_element(1.0)));
        }
        return out;
    }
    if N == 2 {
        if let Some((pairs, n)) = eigenpairs_2x2([[m[(0, 0)], m[(0, 1)]], [m[(1, 0)], m[(1, 1)]]]) {
            for (lambda, v) in &pairs[..n] {
                out.push((*lambda, SVector::from_fn(|i, _| v[i])));
            }
            return out;
        }
    }
    if let Some(pairs) = companion_eigenpairs(m) {
        return pairs;
    }
    #[cfg(target_arch = "x86_64")]
    let found = if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        unsafe { sturm_eigenpairs_avx2(m, &mut out) }
    } else {
        sturm_eigenpairs(m, &mut out)
    };
    #[cfg(not(target_arch = "x86_64"))]
    let found = sturm_eigenpairs(m, &mut out);
    match found {
        Some(()) => out,
        None => real_eigenpairs_hqr(m),
    }
}

/// [`sturm_eigenpairs`] compiled with AVX2 enabled. Without FMA every operation is the
/// baseline build's, so the results are bit-identical.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn sturm_eigenpairs_avx2<const N: usize>(
    m: &SMatrix<f64, N, N>,
    out: &mut SolutionSet<(f64, SVector<f64, N>), N>,
) -> Option<()> {
    sturm_eigenpairs(m, out)
}

/// The Sturm path of [`real_eigenpairs_sturm`], filling the empty `out` (in place: the
/// set is large, and returning it through an `Option` cost a copy); `None` when the QR
/// back end must be used instead (`N = 1`, zero matrix, degenerate Sturm sequence, a root
/// that inverse iteration does not confirm, or two roots converging to one eigenvalue).
fn sturm_eigenpairs<const N: usize>(
    m: &SMatrix<f64, N, N>,
    out: &mut SolutionSet<(f64, SVector<f64, N>), N>,
) -> Option<()> {
    if N == 0 {
        return Some(());
    }
    // By columns (nalgebra's layout): cols[j][i] = m[(i, j)].
    let mut cols = [[0.0f64; N]; N];
    let mut finite = true;
    for (col, src) in cols.iter_mut().zip(m.column_iter()) {
        for (x, &y) in col.iter_mut().zip(src.iter()) {
            *x = y;
            finite &= y.is_finite();
        }
    }
    if !finite {
        return Some(());
    }
    if N == 1 {
        return None;
    }
    // `balance` reads the array by rows, so it balances m^T: D'^-1 m^T D' is balanced, and
    // so is its transpose D' m D'^-1 = D^-1 m D with D = D'^-1.
    let d_transposed = balance(&mut cols);
    // Largest column sum (the 1-norm; it bounds every eigenvalue as well as any norm).
    let mut scale = 0.0f64;
    for col in &cols {
        scale = scale.max(col.iter().map(|x| x.abs()).sum::<f64>());
    }
    if !scale.is_finite() {
        return Some(());
    }
    if scale == 0.0 {
        return None;
    }
    let inv = 1.0 / scale;
    for col in cols.iter_mut() {
        for x in col.iter_mut() {
            *x *= inv;
        }
    }
    let sim = hessenberg_of_columns(&mut cols);
    let h = transpose(&cols);
    let p = char_poly(&h)?;
    let mut roots = [0.0f64; N];
    // Degree 4 and below in closed form; the Sturm sequence where the formulas cannot
    // separate the roots (and above).
    let nroots = match monic_real_roots(&p, &mut roots) {
        Some(n) => n,
        None => Sturm::new(&p)?.real_roots(&p, &mut roots),
    };
    let mut lams = [0.0f64; N];
    let inv_sub = subdiagonal_reciprocals(&h);
    for (k, &mu) in roots[..nroots].iter().enumerate() {
        // The root must agree with the eigenvalue refined by inverse iteration on H (an
        // inaccurate characteristic polynomial shows here), and roots must stay distinct.
        // A spurious real root (a complex pair near the real axis, perturbed onto it in the
        // computed polynomial: common for the ±λ spectra of sign-symmetric problems) leaves
        // a large residual.
        // The backward recurrence first (cheap); then once more after a Newton step on
        // Hyman's determinant (fixes an inaccurate root: all 7 % of 5-point roots that
        // missed the first time); inverse iteration unless the residual is at rounding level.
        let fast = inv_sub.as_ref().and_then(|r| {
            let first = eigenvector_by_recurrence(&h, r, mu).map(|(y, res)| (mu, y, res));
            if matches!(first, Some((_, _, res)) if res <= FAST_RESIDUAL) {
                return first;
            }
            let mu2 = hyman_newton_step(&h, r, mu).filter(|m| (m - mu).abs() <= AGREE_TOL)?;
            eigenvector_by_recurrence(&h, r, mu2)
                .map(|(y, res)| (mu2, y, res))
                .filter(|(_, _, res)| *res <= FAST_RESIDUAL)
        });
        let (lam_mu, y, residual) = match fast {
            Some(found) => found,
            None => {
                let pair = inverse_iteration(&h, mu)?;
                (pair.lambda, pair.vector, pair.residual)
            }
        };
        let agrees = (lam_mu - mu).abs() <= AGREE_TOL && residual <= ACCEPT_RESIDUAL; // false for NaN
        if !agrees || lams[..k].contains(&lam_mu) {
            return None;
        }
        lams[k] = lam_mu;
        let mut v = sim.apply(y);
        for (vi, di) in v.iter_mut().zip(&d_transposed) {
            *vi /= di;
        }
        let lam = lam_mu * scale;
        if lam.is_finite() && normalise(&mut v).is_some() {
            out.push((lam, SVector::from(v)));
        }
    }
    Some(())
}

/// Lower coefficients `c[0..N]` of the monic characteristic polynomial
/// `det(x I - h) = x^N + c[N-1] x^(N-1) + ... + c[0]` of the upper Hessenberg `h`, by
/// `p_k = (x - h_kk) p_{k-1} - sum_{i<k} h_ik (prod_{j=i+1..k} h_{j,j-1}) p_{i-1}`.
fn char_poly<const N: usize>(h: &[[f64; N]; N]) -> Option<[f64; N]> {
    // p[k] holds the lower coefficients of p_{k+1} (degree k+1, monic).
    let mut p = [[0.0f64; N]; N];
    // full(q, d, j): coefficient j of p_d (p_0 = 1).
    fn coef<const N: usize>(p: &[[f64; N]; N], d: usize, j: usize) -> f64 {
        if j == d {
            1.0
        } else if d == 0 {
            0.0
        } else {
            p[d - 1][j]
        }
    }
    for k in 1..=N {
        let hkk = h[k - 1][k - 1];
        let mut c = [0.0f64; N];
        for (j, cj) in c.iter_mut().enumerate().take(k) {
            let shifted = if j >= 1 { coef(&p, k - 1, j - 1) } else { 0.0 };
            *cj = shifted - hkk * coef(&p, k - 1, j);
        }
        let mut prod = 1.0;
        for i in (1..k).rev() {
            prod *= h[i][i - 1];
            let t = h[i - 1][k - 1] * prod;
            if t != 0.0 {
                for (j, cj) in c.iter_mut().enumerate().take(i) {
                    *cj -= t * coef(&p, i - 1, j);
                }
            }
        }
        p[k - 1] = c;
    }
    let c = p[N - 1];
    c.iter().all(|x| x.is_finite()).then_some(c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hessenberg::hessenberg;
    use crate::real_eigenpairs;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn residual<const N: usize>(m: &SMatrix<f64, N, N>, lam: f64, v: &SVector<f64, N>) -> f64 {
        (m * v - v * lam).norm() / m.norm()
    }

    #[test]
    fn one_by_one_is_its_entry() {
        let got = real_eigenpairs_sturm(&SMatrix::<f64, 1, 1>::new(-2.5));
        assert_eq!(got.len(), 1);
        assert_eq!(got[0].0, -2.5);
        assert_eq!(got[0].1[0], 1.0);
        assert!(real_eigenpairs_sturm(&SMatrix::<f64, 1, 1>::new(f64::NAN)).is_empty());
    }

    #[test]
    fn char_poly_matches_eigenvalues() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let m = SMatrix::<f64, 6, 6>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
        let mut a = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                a[i][j] = m[(i, j)];
            }
        }
        hessenberg(&mut a);
        let c = char_poly(&a).unwrap();
        for ev in m.complex_eigenvalues().iter() {
            // |p(ev)| small.
            let mut p = nalgebra::Complex::new(1.0, 0.0);
            for &ck in c.iter().rev() {
                p = p * ev + ck;
            }
            assert!(p.norm() < 1e-12, "{p}");
        }
    }

    #[test]
    fn matches_schur_on_random_matrices() {
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        for _ in 0..300 {
            let m = SMatrix::<f64, 10, 10>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            let s = real_eigenpairs(&m);
            let t = real_eigenpairs_sturm(&m);
            assert_eq!(s.len(), t.len());
            for (lam, v) in &t {
                assert!(residual(&m, *lam, v) < 1e-12, "{}", residual(&m, *lam, v));
                assert!(s.iter().any(|p| (p.0 - lam).abs() < 1e-9));
            }
        }
        for _ in 0..100 {
            let m = SMatrix::<f64, 20, 20>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            let s = real_eigenpairs(&m);
            let t = real_eigenpairs_sturm(&m);
            assert_eq!(s.len(), t.len());
            for (lam, v) in &t {
                assert!(residual(&m, *lam, v) < 1e-11, "{}", residual(&m, *lam, v));
            }
        }
    }

    /// Spectra symmetric under ± with complex pairs, one cluster of four near 0 (as the
    /// action matrices of sign-symmetric problems have): every reported pair has a small
    /// residual, every real eigenvalue is found, and no complex pair away from the axis is
    /// reported as real.
    #[test]
    fn plus_minus_spectra_have_no_spurious_real_roots() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        for trial in 0..300 {
            // Block diagonal: ±r (real) and ±(a ± b i) with tiny a, then a random similarity.
            let mut d = SMatrix::<f64, 12, 12>::zeros();
            let mut real = Vec::new();
            for blk in 0..3 {
                let r = rng.gen_range(0.1..2.0);
                let i = 4 * blk;
                d[(i, i)] = r;
                d[(i + 1, i + 1)] = -r;
                real.extend([r, -r]);
                let a = if trial % 2 == 0 { 1e-9 } else { 1e-4 } * rng.gen_range(0.5..1.0);
                // One pair per matrix is a cluster of four eigenvalues near 0 (the hard case
                // for the characteristic polynomial), the others well away from the axis.
                let b = if blk == 0 {
                    rng.gen_range(1e-7..1e-5)
                } else {
                    rng.gen_range(1e-3..0.5)
                };
                let sign = if blk % 2 == 0 { 1.0 } else { -1.0 };
                d[(i + 2, i + 2)] = sign * a;
                d[(i + 3, i + 3)] = sign * a;
                d[(i + 2, i + 3)] = -b;
                d[(i + 3, i + 2)] = b;
            }
            let t = SMatrix::<f64, 12, 12>::from_fn(|i, j| {
                rng.gen_range(-1.0..1.0) + if i == j { 3.0 } else { 0.0 }
            });
            let m = t * d * t.try_inverse().unwrap();
            let pairs = real_eigenpairs_sturm(&m);
            for (lam, v) in &pairs {
                assert!(residual(&m, *lam, v) < 1e-10, "trial {trial}: {lam}");
            }
            for r in &real {
                assert!(
                    pairs
                        .iter()
                        .any(|(l, _)| (l - r).abs() < 1e-8 * (1.0 + r.abs())),
                    "trial {trial}: real eigenvalue {r} missed"
                );
            }
            // At most the near-zero cluster may be reported (as near-real, by QR).
            assert!(pairs.len() <= real.len() + 2, "trial {trial}");
        }
    }

    #[test]
    fn degenerate_inputs() {
        let mut m = SMatrix::<f64, 10, 10>::identity();
        let p = real_eigenpairs_sturm(&m);
        for (lam, v) in &p {
            assert!((lam - 1.0).abs() < 1e-12 && residual(&m, *lam, v) < 1e-12);
        }
        m[(3, 4)] = f64::NAN;
        assert!(real_eigenpairs_sturm(&m).is_empty());
        m[(3, 4)] = f64::INFINITY;
        assert!(real_eigenpairs_sturm(&m).is_empty());
        assert!(real_eigenpairs_sturm(&SMatrix::<f64, 10, 10>::zeros()).is_empty());
        let huge = SMatrix::<f64, 10, 10>::from_element(1e300);
        for (lam, v) in &real_eigenpairs_sturm(&huge) {
            assert!(lam.is_finite() && v.iter().all(|x| x.is_finite()));
        }
        let j = SMatrix::<f64, 3, 3>::new(2.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 5.0);
        let p = real_eigenpairs_sturm(&j);
        assert!(p.iter().any(|p| (p.0 - 5.0).abs() < 1e-12));
        let rot = SMatrix::<f64, 2, 2>::new(0.0, -1.0, 1.0, 0.0);
        assert!(real_eigenpairs_sturm(&rot).is_empty());
        let one = SMatrix::<f64, 1, 1>::new(-4.0);
        assert_eq!(real_eigenpairs_sturm(&one).len(), 1);
        // Companion matrix of (x-1)(x-2)...(x-10): wide spread of roots.
        let mut c = SMatrix::<f64, 10, 10>::zeros();
        let mut poly = vec![1.0];
        for r in 1..=10 {
            let mut next = vec![0.0; poly.len() + 1];
            for (k, &a) in poly.iter().enumerate() {
                next[k + 1] += a;
                next[k] -= a * r as f64;
            }
            poly = next;
        }
        for i in 1..10 {
            c[(i, i - 1)] = 1.0;
        }
        for i in 0..10 {
            c[(i, 9)] = -poly[i];
        }
        let p = real_eigenpairs_sturm(&c);
        assert_eq!(p.len(), 10);
        for (lam, _) in &p {
            assert!((lam - lam.round()).abs() < 1e-6, "{lam}");
        }
    }
}
