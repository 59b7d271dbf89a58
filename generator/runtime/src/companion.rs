//! Real eigenpairs of companion matrices in closed form: the action matrix of `x` on the
//! power basis `[x^(N-1), ..., x, 1]` (a univariate problem, a one-row template), whose
//! first row holds the reduced row of `x^N` and whose other rows shift the basis. Its
//! characteristic polynomial is that row; for `N` of 3 or 4 the roots come in closed form
//! with a Newton polish ([`super::closed_form`]) and each eigenvector is
//! `(lambda^(N-1), ..., lambda, 1)`: no balancing, no Hessenberg reduction, no eigenvector
//! computation.

use super::closed_form::monic_real_roots;
use super::hessenberg::normalise;
use super::SolutionSet;
use nalgebra::{SMatrix, SVector};

/// The real eigenpairs of `m` if it is a companion matrix in the layout above (`m[(i, i -
/// 1)] = 1` for `i >= 1`, every other entry of rows `1..N` zero) and `N` is 3 or 4;
/// eigenvalues increasing, unit eigenvectors. `None` for any other matrix, a non-finite
/// first row, roots too close for the closed form to separate, or an eigenvector that
/// overflows: the general path decides then.
pub(crate) fn companion_eigenpairs<const N: usize>(
    m: &SMatrix<f64, N, N>,
) -> Option<SolutionSet<(f64, SVector<f64, N>), N>> {
    if N != 3 && N != 4 {
        return None;
    }
    for i in 1..N {
        for j in 0..N {
            if m[(i, j)] != if j + 1 == i { 1.0 } else { 0.0 } {
                return None;
            }
        }
    }
    closed_form_eigenpairs(&std::array::from_fn(|k| m[(0, k)]))
}

/// The closed-form path of [`companion_eigenpairs`] on the companion matrix's first row
/// `row` (`N` of 3 or 4; `None` otherwise and where that function gives `None`).
fn closed_form_eigenpairs<const N: usize>(
    row: &[f64; N],
) -> Option<SolutionSet<(f64, SVector<f64, N>), N>> {
    if N != 3 && N != 4 {
        return None;
    }
    // Row 0 reads x * x^(N-1) = sum_k row[k] b_k with b_k = x^(N-1-k): the monic
    // polynomial x^N - sum_k row[k] x^(N-1-k), lower coefficients from the constant up.
    let c: [f64; N] = std::array::from_fn(|j| -row[N - 1 - j]);
    let mut roots = [0.0f64; N];
    let n = monic_real_roots(&c, &mut roots)?;
    let mut out = SolutionSet::filled_with((0.0, SVector::zeros()));
    for &lambda in &roots[..n] {
        let mut v = [1.0f64; N];
        for k in (0..N - 1).rev() {
            v[k] = v[k + 1] * lambda;
        }
        normalise(&mut v)?;
        out.push((lambda, SVector::from(v)));
    }
    Some(out)
}

/// The real eigenpairs (eigenvalues increasing, unit eigenvectors) of the companion matrix
/// whose first row is `row` and whose rows `1..N` shift the basis (`m[(i, i - 1)] = 1`):
/// the action of `x` on the power basis `[x^(N-1), ..., x, 1]`, whose eigenvalues are the
/// real roots of `x^N - sum_k row[k] x^(N-1-k)`. For `N` of 3 or 4 the roots come in
/// closed form with a Newton polish and each eigenvector is the powers of its root,
/// exactly as [`real_eigenpairs_sturm`](crate::real_eigenpairs_sturm) treats such a
/// matrix, without building it; otherwise, and where the closed form declines (roots too
/// close to separate), the matrix goes to `real_eigenpairs_sturm`. The emitted solvers
/// call it when the template's basis is the power basis of the action's unknown. Never
/// panics; a non-finite row gives no pairs.
#[must_use]
pub fn real_eigenpairs_companion<const N: usize>(
    row: &[f64; N],
) -> SolutionSet<(f64, SVector<f64, N>), N> {
    if let Some(pairs) = closed_form_eigenpairs(row) {
        return pairs;
    }
    let mut m = SMatrix::<f64, N, N>::zeros();
    for (k, x) in row.iter().enumerate() {
        m[(0, k)] = *x;
    }
    for i in 1..N {
        m[(i, i - 1)] = 1.0;
    }
    crate::real_eigenpairs_sturm(&m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real_eigenpairs;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The companion matrix of the monic polynomial with the given roots (and the complex
    /// pair `re ± i im` when `pair` is given), in the layout the emitter builds.
    fn companion<const N: usize>(roots: &[f64], pair: Option<(f64, f64)>) -> SMatrix<f64, N, N> {
        // Coefficients from the leading one down.
        let mut p = vec![1.0];
        let mut times = |factor: &[f64]| {
            let mut q = vec![0.0; p.len() + factor.len() - 1];
            for (i, a) in p.iter().enumerate() {
                for (j, b) in factor.iter().enumerate() {
                    q[i + j] += a * b;
                }
            }
            p = q;
        };
        for r in roots {
            times(&[1.0, -r]);
        }
        if let Some((re, im)) = pair {
            times(&[1.0, -2.0 * re, re * re + im * im]);
        }
        let mut m = SMatrix::<f64, N, N>::zeros();
        for k in 0..N {
            m[(0, k)] = -p[k + 1];
        }
        for i in 1..N {
            m[(i, i - 1)] = 1.0;
        }
        m
    }

    #[test]
    fn companion_roots_are_the_eigenpairs() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        for trial in 0..300 {
            let (m, mut planted) = if trial % 2 == 0 {
                let r: Vec<f64> = (0..4).map(|_| rng.gen_range(-5.0..5.0)).collect();
                (companion::<4>(&r, None), r)
            } else {
                let r: Vec<f64> = (0..2).map(|_| rng.gen_range(-5.0..5.0)).collect();
                let pair = (rng.gen_range(-2.0..2.0), rng.gen_range(0.5..2.0));
                (companion::<4>(&r, Some(pair)), r)
            };
            let Some(pairs) = companion_eigenpairs(&m) else {
                continue;
            };
            planted.sort_by(f64::total_cmp);
            assert_eq!(pairs.len(), planted.len(), "{m}");
            let general = real_eigenpairs(&m);
            for ((lambda, v), x) in pairs.iter().zip(&planted) {
                assert!((lambda - x).abs() < 1e-9 * (1.0 + x.abs()), "{lambda} {x}");
                assert!((m * v - v * *lambda).norm() < 1e-10 * m.norm());
                assert!(general
                    .iter()
                    .any(|(g, _)| (g - lambda).abs() < 1e-8 * (1.0 + x.abs())));
            }
        }
        let m3 = companion::<3>(&[-1.0, 0.5, 2.0], None);
        let pairs = companion_eigenpairs(&m3).expect("a cubic with distinct roots");
        let got: Vec<f64> = pairs.iter().map(|(l, _)| *l).collect();
        assert!(
            got.iter()
                .zip([-1.0, 0.5, 2.0])
                .all(|(a, b)| (a - b).abs() < 1e-12),
            "{got:?}"
        );
    }

    #[test]
    fn eigenpairs_from_the_first_row_are_those_of_the_matrix() {
        let mut rng = ChaCha8Rng::seed_from_u64(10);
        for trial in 0..200 {
            let r: Vec<f64> = (0..4).map(|_| rng.gen_range(-5.0..5.0)).collect();
            // Every fifth one with a double root: the closed form declines it, the general
            // path takes the matrix.
            let r = if trial % 5 == 0 {
                vec![r[0], r[0], r[2], r[3]]
            } else {
                r
            };
            let m = companion::<4>(&r, None);
            let row: [f64; 4] = std::array::from_fn(|k| m[(0, k)]);
            let from_row = real_eigenpairs_companion(&row);
            let from_matrix = crate::real_eigenpairs_sturm(&m);
            assert_eq!(from_row.len(), from_matrix.len(), "{r:?}");
            for ((l1, v1), (l2, v2)) in from_row.iter().zip(from_matrix.iter()) {
                assert_eq!(l1, l2);
                assert_eq!(v1, v2);
            }
        }
        let m3 = companion::<3>(&[-1.0, 0.5, 2.0], None);
        let row: [f64; 3] = std::array::from_fn(|k| m3[(0, k)]);
        assert_eq!(real_eigenpairs_companion(&row).len(), 3);
        // Sizes without a closed form go to the general path; a non-finite row has none.
        let m5 = companion::<5>(&[-2.0, -1.0, 0.5, 1.0, 3.0], None);
        let row: [f64; 5] = std::array::from_fn(|k| m5[(0, k)]);
        assert_eq!(real_eigenpairs_companion(&row).len(), 5);
        assert!(real_eigenpairs_companion(&[f64::NAN, 0.0, 1.0, 2.0]).is_empty());
    }

    #[test]
    fn other_matrices_and_double_roots_are_left_to_the_general_path() {
        let mut m = companion::<4>(&[1.0, 2.0, 3.0, 4.0], None);
        assert!(companion_eigenpairs(&m).is_some());
        m[(2, 3)] = 1e-300;
        assert!(companion_eigenpairs(&m).is_none());
        assert!(companion_eigenpairs(&companion::<4>(&[1.0, 1.0, 3.0, 4.0], None)).is_none());
        assert!(companion_eigenpairs(&SMatrix::<f64, 5, 5>::zeros()).is_none());
        let mut m = companion::<3>(&[1.0, 2.0, 3.0], None);
        m[(0, 0)] = f64::NAN;
        assert!(companion_eigenpairs(&m).is_none());
    }
}
