//! Entry points whose sizes are known at run time only (the interpreter behind
//! `mingen audit`): the same numerics as the functions the emitted solvers call, on the
//! same matrix. Up to [`STURM_MAX_BASIS`] they dispatch to the const-generic Sturm back end
//! instantiated at the matrix's size; above it the QR back end runs on the heap at any size
//! ([`real_eigenpairs_hqr_dyn`], which the fixed-size [`super::real_eigenpairs_hqr`] runs
//! too). Unlike the fixed-size functions these allocate their result.

use super::{real_eigenpairs_hqr_dyn, real_eigenpairs_sturm};
use nalgebra::SMatrix;

/// Action matrices up to this size use the characteristic-polynomial / Sturm eigen back
/// end ([`real_eigenpairs_sturm`]), larger ones Francis QR with exceptional shifts
/// ([`super::real_eigenpairs_hqr`]). The emitter and [`real_eigenpairs_dyn`] both decide by it.
pub const STURM_MAX_BASIS: usize = 20;

/// Largest action matrix [`real_eigenpairs_dyn`] accepts: a bound on its memory (a few
/// `n x n` matrices of f64) and time (O(n^3)), far above any template the search finishes.
pub const MAX_DYNAMIC_BASIS: usize = 1024;

/// One real eigenpair: eigenvalue and unit eigenvector.
pub type DynEigenpair = (f64, Vec<f64>);

/// The real eigenpairs of the `n x n` matrix stored column-major in `a` (nalgebra's
/// layout, `a.len() == n * n`), computed by the back end an emitted solver of that size
/// uses ([`real_eigenpairs_sturm`] up to [`STURM_MAX_BASIS`], else
/// [`super::real_eigenpairs_hqr`]) and in the same order, bit for bit. `None` if
/// `a.len() != n * n` or `n > MAX_DYNAMIC_BASIS`; otherwise the contract of those functions
/// (empty for non-finite or zero input). Never panics.
pub fn real_eigenpairs_dyn(a: &[f64], n: usize) -> Option<Vec<DynEigenpair>> {
    if n.checked_mul(n) != Some(a.len()) || n > MAX_DYNAMIC_BASIS {
        return None;
    }
    macro_rules! dispatch {
        ($($sturm:literal)*) => {
            match n {
                0 => Some(Vec::new()),
                $($sturm => Some(sturm_at_size::<$sturm>(a)),)*
                _ => Some(real_eigenpairs_hqr_dyn(a, n)),
            }
        };
    }
    dispatch!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20)
}

/// [`real_eigenpairs_sturm`] at the constant size `N`.
fn sturm_at_size<const N: usize>(a: &[f64]) -> Vec<DynEigenpair> {
    let m = SMatrix::<f64, N, N>::from_column_slice(a);
    real_eigenpairs_sturm(&m)
        .iter()
        .map(|(lam, v)| (*lam, v.iter().copied().collect()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real_eigenpairs_hqr;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The dynamic entry point returns exactly (bit for bit) what the fixed-size back end
    /// returns, on both sides of the Sturm / QR threshold.
    fn same_as_fixed<const N: usize>(rng: &mut ChaCha8Rng) {
        let m = SMatrix::<f64, N, N>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
        let fixed = if N <= STURM_MAX_BASIS {
            real_eigenpairs_sturm(&m)
        } else {
            real_eigenpairs_hqr(&m)
        };
        let dynamic = real_eigenpairs_dyn(m.as_slice(), N).expect("supported size");
        assert_eq!(dynamic.len(), fixed.len());
        for ((l1, v1), (l2, v2)) in dynamic.iter().zip(fixed.iter()) {
            assert_eq!(*l1, *l2);
            assert_eq!(v1.as_slice(), v2.as_slice());
        }
    }

    #[test]
    fn dispatches_to_the_fixed_size_back_end() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for _ in 0..20 {
            same_as_fixed::<3>(&mut rng);
            same_as_fixed::<10>(&mut rng);
            same_as_fixed::<20>(&mut rng);
            same_as_fixed::<21>(&mut rng);
            same_as_fixed::<40>(&mut rng);
        }
    }

    #[test]
    fn rejects_bad_shapes() {
        assert!(real_eigenpairs_dyn(&[1.0; 5], 2).is_none());
        let n = MAX_DYNAMIC_BASIS + 1;
        assert!(real_eigenpairs_dyn(&vec![1.0; n * n], n).is_none());
        assert!(real_eigenpairs_dyn(&[], usize::MAX).is_none());
        assert_eq!(real_eigenpairs_dyn(&[], 0), Some(Vec::new()));
        assert!(real_eigenpairs_dyn(&[f64::NAN; 9], 3).unwrap().is_empty());
        assert!(real_eigenpairs_dyn(&[f64::NAN; 900], 30)
            .unwrap()
            .is_empty());
    }

    /// Above any fixed size the emitted solvers are instantiated at, the pairs are still
    /// eigenpairs: a matrix with known real spectrum 1..=n (similar to a diagonal one by a
    /// well-conditioned `S`) of side 150.
    #[test]
    fn large_sizes_are_solved() {
        let n = 150;
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        let s = nalgebra::DMatrix::<f64>::from_fn(n, n, |i, j| {
            f64::from(u8::from(i == j)) * 4.0 + rng.gen_range(-0.1..0.1)
        });
        let si = s.clone().try_inverse().expect("S is invertible");
        let d = nalgebra::DMatrix::<f64>::from_fn(
            n,
            n,
            |i, j| {
                if i == j {
                    1.0 + i as f64
                } else {
                    0.0
                }
            },
        );
        let a = &s * d * si;
        let pairs = real_eigenpairs_dyn(a.as_slice(), n).expect("within MAX_DYNAMIC_BASIS");
        assert_eq!(pairs.len(), n);
        let mut found: Vec<f64> = pairs.iter().map(|p| p.0).collect();
        found.sort_by(f64::total_cmp);
        for (k, lam) in found.iter().enumerate() {
            assert!((lam - (1.0 + k as f64)).abs() < 1e-8, "{k}: {lam}");
        }
        for (lam, v) in &pairs {
            let v = nalgebra::DVector::from_column_slice(v);
            let r = (&a * &v - &v * *lam).norm() / a.norm();
            assert!(r < 1e-12, "residual {r:e}");
        }
    }
}
