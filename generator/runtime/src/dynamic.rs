//! Entry points whose sizes are known at run time only (the interpreter behind
//! `mingen audit`): they dispatch to the const-generic functions the emitted solvers
//! call, instantiated at the template's size, so both run the same code on the same
//! matrix. Unlike the fixed-size functions these allocate their result.

use super::{real_eigenpairs_hqr, real_eigenpairs_sturm};
use nalgebra::SMatrix;

/// Action matrices up to this size use the characteristic-polynomial / Sturm eigen back
/// end ([`real_eigenpairs_sturm`]), larger ones Francis QR with exceptional shifts
/// ([`real_eigenpairs_hqr`]). The emitter and [`real_eigenpairs_dyn`] both decide by it.
pub const STURM_MAX_BASIS: usize = 20;

/// Largest action matrix [`real_eigenpairs_dyn`] accepts: each size is a separate
/// instantiation of the eigen back end, compiled into every crate that calls it.
pub const MAX_DYNAMIC_BASIS: usize = 128;

/// One real eigenpair: eigenvalue and unit eigenvector.
pub type DynEigenpair = (f64, Vec<f64>);

/// The real eigenpairs of the `n x n` matrix stored column-major in `a` (nalgebra's
/// layout, `a.len() == n * n`), computed by the back end an emitted solver of that size
/// uses ([`real_eigenpairs_sturm`] up to [`STURM_MAX_BASIS`], else
/// [`real_eigenpairs_hqr`]) and in the same order. `None` if `a.len() != n * n` or
/// `n > MAX_DYNAMIC_BASIS`; otherwise the contract of those functions (empty for
/// non-finite or zero input). Never panics.
pub fn real_eigenpairs_dyn(a: &[f64], n: usize) -> Option<Vec<DynEigenpair>> {
    if n.checked_mul(n) != Some(a.len()) {
        return None;
    }
    macro_rules! dispatch {
        ($($sturm:literal)*; $($hqr:literal)*) => {
            match n {
                0 => Some(Vec::new()),
                $($sturm => Some(at_size::<$sturm>(a, true)),)*
                $($hqr => Some(at_size::<$hqr>(a, false)),)*
                _ => None,
            }
        };
    }
    dispatch!(
        1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20;
        21 22 23 24 25 26 27 28 29 30 31 32 33 34 35 36 37 38 39 40 41 42
        43 44 45 46 47 48 49 50 51 52 53 54 55 56 57 58 59 60 61 62 63 64
        65 66 67 68 69 70 71 72 73 74 75 76 77 78 79 80 81 82 83 84 85 86 87 88 89 90 91
        92 93 94 95 96 97 98 99 100 101 102 103 104 105 106 107 108 109 110 111 112 113
        114 115 116 117 118 119 120 121 122 123 124 125 126 127 128
    )
}

/// [`real_eigenpairs_dyn`] at the constant size `N`.
fn at_size<const N: usize>(a: &[f64], sturm: bool) -> Vec<DynEigenpair> {
    let m = SMatrix::<f64, N, N>::from_column_slice(a);
    let pairs = if sturm {
        real_eigenpairs_sturm(&m)
    } else {
        real_eigenpairs_hqr(&m)
    };
    pairs
        .iter()
        .map(|(lam, v)| (*lam, v.iter().copied().collect()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
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
        assert!(real_eigenpairs_dyn(&[1.0; 129 * 129], 129).is_none());
        assert!(real_eigenpairs_dyn(&[], usize::MAX).is_none());
        assert_eq!(real_eigenpairs_dyn(&[], 0), Some(Vec::new()));
        assert!(real_eigenpairs_dyn(&[f64::NAN; 9], 3).unwrap().is_empty());
    }
}
