//! Real eigenpairs by the Francis double-shift QR iteration: eigenvalues of the
//! Hessenberg form (no Schur vectors accumulated), eigenvectors by inverse iteration on
//! the Hessenberg form (O(n^2) per eigenvalue). One implementation for every size, on the
//! heap ([`super::hessenberg_dyn`]): the fixed-size entry point [`real_eigenpairs_hqr`]
//! of the emitted solvers and the run-time-size one of the interpreter
//! ([`real_eigenpairs_hqr_dyn`]) compute the same bits, and a large action matrix does
//! not live on the stack.

use super::hessenberg_dyn::{balance, hessenberg, inverse_iteration, normalise, Square};
use super::{SolutionSet, NEAR_REAL_TOL};
use nalgebra::{SMatrix, SVector};

/// Maximum Francis iterations per eigenvalue (as in EISPACK `hqr`).
const MAX_ITS: usize = 30;

/// Maximum Francis iterations per eigenvalue on the retries after a stall. A redundant
/// solving basis (`mingen`'s `option redundant_basis`) often has its spurious eigenvalues
/// in a defective cluster (a Jordan block at 0 of a Laurent action), which rounding splits
/// into a ring of nearly equal eigenvalues; the double-shift iteration converges on it
/// linearly, not quadratically, and needs more than [`MAX_ITS`] sweeps to deflate it.
const RETRY_MAX_ITS: usize = 10 * MAX_ITS;

/// `H a H` with the Householder reflection `H = I - 2 u u^T / u^T u` for a fixed generic
/// `u` (two choices, by `which`): a similarity, so the spectrum is that of `a`.
fn reflect(a: &Square, which: usize) -> Square {
    let n = a.n();
    let u: Vec<f64> = (0..n)
        .map(|i| {
            if which == 1 {
                1.0 + 0.37 * i as f64 + ((i * 7919) % 13) as f64 * 0.11
            } else {
                ((i * 2_654_435_761) % 1009) as f64 / 1009.0 - 0.43
            }
        })
        .collect();
    let uu: f64 = u.iter().map(|x| x * x).sum();
    // H a H = a - 2/uu (u (u^T a) + (a u) u^T) + 4/uu^2 (u^T a u) u u^T.
    let mut ua = vec![0.0; n]; // u^T a
    let mut au = vec![0.0; n]; // a u
    for i in 0..n {
        for j in 0..n {
            ua[j] += u[i] * a[(i, j)];
            au[i] += a[(i, j)] * u[j];
        }
    }
    let uau: f64 = (0..n).map(|i| u[i] * au[i]).sum();
    let mut out = a.clone();
    for i in 0..n {
        for j in 0..n {
            out[(i, j)] +=
                -2.0 / uu * (u[i] * ua[j] + au[i] * u[j]) + 4.0 / (uu * uu) * uau * u[i] * u[j];
        }
    }
    out
}

/// Eigenvalues (re, im) of an upper Hessenberg matrix (destroyed), by the Francis
/// double-shift QR iteration (after Numerical Recipes `hqr`); returns the total number of
/// iterations, `None` if it does not converge within `max_its` for some eigenvalue.
fn hqr(h: &mut Square, wr: &mut [f64], wi: &mut [f64], max_its: usize) -> Option<usize> {
    let mut total = 0;
    // 1-based indices as in the classic formulation; a!(i, j) is h[i-1][j-1].
    macro_rules! a {
        ($i:expr, $j:expr) => {
            h[(($i - 1) as usize, ($j - 1) as usize)]
        };
    }
    let n = h.n() as isize;
    let mut anorm = 0.0;
    for i in 1..=n {
        for j in (i - 1).max(1)..=n {
            anorm += a!(i, j).abs();
        }
    }
    let mut nn = n;
    let mut t = 0.0;
    let (mut p, mut q, mut r) = (0.0f64, 0.0f64, 0.0f64);
    let (mut x, mut y, mut z, mut w, mut s);
    while nn >= 1 {
        let mut its = 0;
        loop {
            let mut l = nn;
            while l >= 2 {
                s = a!(l - 1, l - 1).abs() + a!(l, l).abs();
                if s == 0.0 {
                    s = anorm;
                }
                if a!(l, l - 1).abs() + s == s {
                    a!(l, l - 1) = 0.0;
                    break;
                }
                l -= 1;
            }
            x = a!(nn, nn);
            if l == nn {
                wr[(nn - 1) as usize] = x + t;
                wi[(nn - 1) as usize] = 0.0;
                nn -= 1;
            } else {
                y = a!(nn - 1, nn - 1);
                w = a!(nn, nn - 1) * a!(nn - 1, nn);
                if l == nn - 1 {
                    p = 0.5 * (y - x);
                    q = p * p + w;
                    z = q.abs().sqrt();
                    x += t;
                    let (i1, i2) = ((nn - 2) as usize, (nn - 1) as usize);
                    if q >= 0.0 {
                        z = p + z.copysign(p);
                        wr[i1] = x + z;
                        wr[i2] = x + z;
                        if z != 0.0 {
                            wr[i2] = x - w / z;
                        }
                        wi[i1] = 0.0;
                        wi[i2] = 0.0;
                    } else {
                        wr[i1] = x + p;
                        wr[i2] = x + p;
                        wi[i1] = -z;
                        wi[i2] = z;
                    }
                    nn -= 2;
                } else {
                    if its == max_its {
                        return None;
                    }
                    if its == 10 || its == 20 {
                        // Exceptional shift.
                        t += x;
                        for i in 1..=nn {
                            a!(i, i) -= x;
                        }
                        s = a!(nn, nn - 1).abs() + a!(nn - 1, nn - 2).abs();
                        x = 0.75 * s;
                        y = x;
                        w = -0.4375 * s * s;
                    }
                    its += 1;
                    total += 1;
                    let mut m = nn - 2;
                    while m >= l {
                        z = a!(m, m);
                        r = x - z;
                        s = y - z;
                        p = (r * s - w) / a!(m + 1, m) + a!(m, m + 1);
                        q = a!(m + 1, m + 1) - z - r - s;
                        r = a!(m + 2, m + 1);
                        s = p.abs() + q.abs() + r.abs();
                        p /= s;
                        q /= s;
                        r /= s;
                        if m == l {
                            break;
                        }
                        let u = a!(m, m - 1).abs() * (q.abs() + r.abs());
                        let v =
                            p.abs() * (a!(m - 1, m - 1).abs() + z.abs() + a!(m + 1, m + 1).abs());
                        if u + v == v {
                            break;
                        }
                        m -= 1;
                    }
                    for i in m + 2..=nn {
                        a!(i, i - 2) = 0.0;
                        if i != m + 2 {
                            a!(i, i - 3) = 0.0;
                        }
                    }
                    let mut k = m;
                    while k < nn {
                        if k != m {
                            p = a!(k, k - 1);
                            q = a!(k + 1, k - 1);
                            r = 0.0;
                            if k != nn - 1 {
                                r = a!(k + 2, k - 1);
                            }
                            x = p.abs() + q.abs() + r.abs();
                            if x != 0.0 {
                                p /= x;
                                q /= x;
                                r /= x;
                            }
                        }
                        s = (p * p + q * q + r * r).sqrt().copysign(p);
                        if s != 0.0 {
                            if k == m {
                                if l != m {
                                    a!(k, k - 1) = -a!(k, k - 1);
                                }
                            } else {
                                a!(k, k - 1) = -s * x;
                            }
                            p += s;
                            x = p / s;
                            y = q / s;
                            z = r / s;
                            q /= p;
                            r /= p;
                            for j in k..=nn {
                                p = a!(k, j) + q * a!(k + 1, j);
                                if k != nn - 1 {
                                    p += r * a!(k + 2, j);
                                    a!(k + 2, j) -= p * z;
                                }
                                a!(k + 1, j) -= p * y;
                                a!(k, j) -= p * x;
                            }
                            let mmin = if nn < k + 3 { nn } else { k + 3 };
                            for i in l..=mmin {
                                p = x * a!(i, k) + y * a!(i, k + 1);
                                if k != nn - 1 {
                                    p += z * a!(i, k + 2);
                                    a!(i, k + 2) -= p * r;
                                }
                                a!(i, k + 1) -= p * q;
                                a!(i, k) -= p;
                            }
                        }
                        k += 1;
                    }
                }
            }
            if l >= nn - 1 {
                break;
            }
        }
    }
    Some(total)
}

/// Same contract as [`super::real_eigenpairs`] (real eigenvalues with unit eigenvectors,
/// at most `N`, empty on non-finite/zero input or non-convergence, near-real pairs per
/// [`NEAR_REAL_TOL`] taken as one real eigenvalue), by a different, faster algorithm:
/// reduction to Hessenberg form by stabilised elementary similarities, eigenvalues by the
/// Francis double-shift QR iteration without accumulating Schur vectors (EISPACK/NR
/// `balanc` without permutations + `elmhes` + `hqr`, at most 30 iterations per
/// eigenvalue), then each real eigenvalue's
/// eigenvector by inverse iteration on the Hessenberg form `H - lambda I` (O(N^2) per
/// eigenvalue; one to three steps, until the residual is at rounding level), transformed
/// back by the similarity of the reduction. Order: as the iteration deflates them. The
/// work is done by [`real_eigenpairs_hqr_dyn`] (on the heap); no panic.
pub fn real_eigenpairs_hqr<const N: usize>(
    m: &SMatrix<f64, N, N>,
) -> SolutionSet<(f64, SVector<f64, N>), N> {
    let mut out = SolutionSet::filled_with((0.0, SVector::zeros()));
    let mut a = Square::zeros(N);
    for i in 0..N {
        for j in 0..N {
            a[(i, j)] = m[(i, j)];
        }
    }
    for (lam, v) in eigenpairs(a) {
        out.push((lam, SVector::from_iterator(v)));
    }
    out
}

/// [`real_eigenpairs_hqr`] for an `n x n` matrix stored column-major in `a` (nalgebra's
/// layout, `a.len() == n * n`), of any size: the same pairs, bit for bit, in the same
/// order. Empty if `a.len() != n * n`.
pub fn real_eigenpairs_hqr_dyn(a: &[f64], n: usize) -> Vec<(f64, Vec<f64>)> {
    if n.checked_mul(n) != Some(a.len()) {
        return Vec::new();
    }
    let mut m = Square::zeros(n);
    for j in 0..n {
        for i in 0..n {
            m[(i, j)] = a[j * n + i];
        }
    }
    eigenpairs(m)
}

/// The real eigenpairs of the row-major `a` (see [`real_eigenpairs_hqr`]).
fn eigenpairs(mut a: Square) -> Vec<(f64, Vec<f64>)> {
    let n = a.n();
    let mut out = Vec::new();
    let finite = (0..n).all(|i| a.row(i).iter().all(|v| v.is_finite()));
    if !finite || n == 0 {
        return out;
    }
    // Eigenvectors of the balanced D^-1 a D are D^-1 times a's: multiplied back by D below.
    let d = balance(&mut a);
    // Work on a / |a|_inf (norm 1: the tolerances of the inverse iteration are absolute).
    let scale = (0..n)
        .map(|i| a.row(i).iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    if !(scale > 0.0 && scale.is_finite()) {
        return out;
    }
    let inv = 1.0 / scale;
    for i in 0..n {
        for x in a.row_mut(i).iter_mut() {
            *x *= inv;
        }
    }
    let mut h0 = a.clone();
    let sim = hessenberg(&mut h0);
    let (mut wr, mut wi) = (vec![0.0; n], vec![0.0; n]);
    // The eigenvalues may come from a similar matrix (eigenvectors are computed on `h0`,
    // the Hessenberg form of `a` itself): if QR stalls, retry on `H a H` for a fixed
    // generic Householder reflection `H`, which breaks the exact structure of action
    // matrices (unit rows, ±λ spectra of sign-symmetric problems) that slow convergence
    // comes from.
    let mut converged = false;
    for attempt in 0..3 {
        let mut h = if attempt == 0 {
            h0.clone()
        } else {
            let mut r = reflect(&a, attempt);
            let _ = hessenberg(&mut r);
            r
        };
        let its = if attempt == 0 { MAX_ITS } else { RETRY_MAX_ITS };
        if hqr(&mut h, &mut wr, &mut wi, its).is_some() {
            converged = true;
            break;
        }
    }
    if !converged {
        return out;
    }
    let mut k = 0;
    while k < n {
        let lam = wr[k];
        let real = wi[k] == 0.0;
        // Relative to the eigenvalue (see `NEAR_REAL_TOL`), floored at rounding level.
        let near = !real && wi[k].abs() <= (NEAR_REAL_TOL * lam.abs()).max(f64::EPSILON);
        if real || near {
            if let Some(pair) = inverse_iteration(&h0, lam) {
                let mut v = sim.apply(pair.vector);
                for (x, di) in v.iter_mut().zip(&d) {
                    *x *= di;
                }
                if normalise(&mut v).is_some() {
                    out.push((lam * scale, v));
                }
            }
        }
        // A complex (or near-real) pair occupies two consecutive slots.
        k += if real { 1 } else { 2 };
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real_eigenpairs;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn residual<const N: usize>(m: &SMatrix<f64, N, N>, lam: f64, v: &SVector<f64, N>) -> f64 {
        (m * v - v * lam).norm() / m.norm()
    }

    #[test]
    fn agrees_with_schur_version() {
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        let mut mismatched = 0;
        for trial in 0..500 {
            let m = SMatrix::<f64, 10, 10>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            let m = if trial % 2 == 0 { m + m.transpose() } else { m };
            let fast = real_eigenpairs_hqr(&m);
            let slow = real_eigenpairs(&m);
            if fast.len() != slow.len() {
                mismatched += 1;
            }
            for (lam, v) in &fast {
                assert!(residual(&m, *lam, v) < 1e-12, "{}", residual(&m, *lam, v));
                assert!(slow.iter().any(|(l, _)| (l - lam).abs() < 1e-9));
            }
        }
        assert_eq!(mismatched, 0);
    }

    #[test]
    fn sizes_and_degenerate_inputs() {
        let one = SMatrix::<f64, 1, 1>::new(-4.0);
        let p = real_eigenpairs_hqr(&one);
        assert_eq!((p.len(), p[0].0), (1, -4.0));
        let rot = SMatrix::<f64, 2, 2>::new(0.0, -1.0, 1.0, 0.0);
        assert!(real_eigenpairs_hqr(&rot).is_empty());
        let two = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 3.0, 4.0);
        assert_eq!(real_eigenpairs_hqr(&two).len(), 2);
        let mut m = SMatrix::<f64, 20, 20>::identity();
        assert_eq!(real_eigenpairs_hqr(&m).len(), 20);
        m[(3, 4)] = f64::NAN;
        assert!(real_eigenpairs_hqr(&m).is_empty());
        assert!(real_eigenpairs_hqr(&SMatrix::<f64, 5, 5>::zeros()).is_empty());
        let jordan = SMatrix::<f64, 3, 3>::new(2.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 5.0);
        for (lam, v) in &real_eigenpairs_hqr(&jordan) {
            assert!(residual(&jordan, *lam, v) < 1e-6);
        }
        let mut rng = ChaCha8Rng::seed_from_u64(22);
        for _ in 0..100 {
            let m = SMatrix::<f64, 20, 20>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            for (lam, v) in &real_eigenpairs_hqr(&m) {
                assert!(residual(&m, *lam, v) < 1e-12);
            }
        }
    }

    #[test]
    fn balancing_keeps_small_eigenvector_entries_accurate() {
        // A = D S diag(1..N) S^-1 D^-1 with D spanning 1e-6..1e6 (the scaling of monomials
        // of different degrees): the eigenvectors D S e_i have entries of very different
        // magnitudes; each must be accurate relative to its scale d_i, not only to the
        // largest entry.
        const N: usize = 24;
        let mut rng = ChaCha8Rng::seed_from_u64(23);
        let mut worst: f64 = 0.0;
        for _ in 0..20 {
            let s = SMatrix::<f64, N, N>::from_fn(|i, j| {
                f64::from(u8::from(i == j)) * 2.0 + rng.gen_range(-0.3..0.3)
            });
            let si = s.try_inverse().unwrap();
            let d: [f64; N] =
                std::array::from_fn(|i| 10f64.powf(-6.0 + 12.0 * i as f64 / (N - 1) as f64));
            let lam =
                SMatrix::<f64, N, N>::from_fn(|i, j| if i == j { 1.0 + i as f64 } else { 0.0 });
            let core = s * lam * si;
            let a = SMatrix::<f64, N, N>::from_fn(|i, j| d[i] * core[(i, j)] / d[j]);
            let pairs = real_eigenpairs_hqr(&a);
            assert_eq!(pairs.len(), N);
            for (l, v) in &pairs {
                let k = (l.round() as usize) - 1;
                let truth: [f64; N] = std::array::from_fn(|i| d[i] * s[(i, k)]);
                // Compare v with truth up to scale, entry by entry, relative to each entry.
                let (p, q) = (0..N).fold((0.0, 0.0), |(p, q), i| {
                    (p + v[i] * truth[i], q + truth[i] * truth[i])
                });
                let c = p / q;
                for i in 0..N {
                    worst = worst.max((v[i] - c * truth[i]).abs() / (c * d[i]).abs());
                }
            }
        }
        assert!(worst < 1e-10, "worst relative entry error {worst:e}");
    }
}
