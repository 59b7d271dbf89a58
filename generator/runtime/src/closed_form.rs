//! Real roots of monic polynomials of degree at most 4 in closed form: the characteristic
//! polynomials of small action matrices ([`super::sturm`]), where a formula and a Newton
//! polish cost less than isolating the roots with a Sturm sequence.
//!
//! - degree 2: the quadratic formula in its cancellation-free form (`q = -(b + sign(b)
//!   sqrt(D)) / 2`, roots `q` and `c / q`);
//! - degree 3: the depressed cubic `t^3 + p t + q`, three real roots by the trigonometric
//!   (Viète) form, one by the hyperbolic one;
//! - degree 4: Ferrari's method: the depressed quartic `y^4 + p y^2 + q y + r` factored
//!   into two quadratics through the largest root of the resolvent cubic
//!   `8 m^3 + 8 p m^2 + (2 p^2 - 8 r) m - q^2` (biquadratic when `q` is zero).
//!
//! - 2x2 matrices: eigenvalues from the trace and `(a - d)^2 + 4 b c`, each eigenvector
//!   the larger of the two null vectors of `A - lambda I`'s rows ([`eigenpairs_2x2`]).
//!
//! Every root is then polished by Newton's iteration on the polynomial as given (at most
//! [`NEWTON_STEPS`], a step kept only if it lowers `|p|`), which restores the accuracy
//! the formulas lose to cancellation. Close to a double root the formulas cannot tell a
//! real pair from a complex one reliably: the functions return `None` there, and the
//! caller falls back on its general method.

use super::sturm_sequence::eval_monic;

/// Newton steps polishing each root.
const NEWTON_STEPS: usize = 2;
/// Polished roots whose distance is at most this (relative to the largest root magnitude,
/// at least 1) may have converged to one root: `None`.
const SEPARATION: f64 = 1e-7;
/// A discriminant within this of zero, relative to the size of its terms, cannot tell a
/// close real pair from a complex one: `None`.
const DISCRIMINANT_TOL: f64 = 1e-12;

/// `x` after at most [`NEWTON_STEPS`] Newton steps on the monic polynomial with lower
/// coefficients `c`, each kept only if it lowers `|p|`.
fn polish<const N: usize>(c: &[f64; N], mut x: f64) -> f64 {
    let (mut px, mut dpx) = eval_monic(c, x);
    for _ in 0..NEWTON_STEPS {
        if px == 0.0 || dpx == 0.0 {
            break;
        }
        let next = x - px / dpx;
        let (pn, dpn) = eval_monic(c, next);
        if pn.abs().partial_cmp(&px.abs()) != Some(std::cmp::Ordering::Less) {
            break;
        }
        (x, px, dpx) = (next, pn, dpn);
    }
    x
}

/// The real roots of `x^N + c[N-1] x^(N-1) + ... + c[0]` (`N` at most 4) in increasing order
/// into `roots`, their number returned; `None` for `N > 4`, a non-finite coefficient or
/// root, or roots closer than the formulas can separate (see the module documentation).
pub(crate) fn monic_real_roots<const N: usize>(
    c: &[f64; N],
    roots: &mut [f64; N],
) -> Option<usize> {
    if N > 4 || c.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let mut found = [0.0f64; 4];
    let n = match N {
        0 => 0,
        1 => {
            found[0] = -c[0];
            1
        }
        2 => quadratic(c[1], c[0], &mut found)?,
        3 => cubic(c[2], c[1], c[0], &mut found)?,
        _ => quartic(c[3], c[2], c[1], c[0], &mut found)?,
    };
    let found = &mut found[..n];
    for x in found.iter_mut() {
        *x = polish(c, *x);
        if !x.is_finite() {
            return None;
        }
    }
    // At most four finite values: an insertion sort without the generic sort's machinery.
    for i in 1..found.len() {
        let mut j = i;
        while j > 0 && found[j - 1] > found[j] {
            found.swap(j - 1, j);
            j -= 1;
        }
    }
    let scale = found.iter().fold(1.0f64, |s, x| s.max(x.abs()));
    if found.windows(2).any(|w| w[1] - w[0] <= SEPARATION * scale) {
        return None;
    }
    roots[..n].copy_from_slice(found);
    Some(n)
}

/// Real roots of `x^2 + b x + c` (unsorted): `None` when the discriminant is within
/// [`DISCRIMINANT_TOL`] of zero.
fn quadratic(b: f64, c: f64, out: &mut [f64; 4]) -> Option<usize> {
    let d = b * b - 4.0 * c;
    if d.abs() <= DISCRIMINANT_TOL * (b * b + 4.0 * c.abs()) {
        return None;
    }
    if d < 0.0 {
        return Some(0);
    }
    let q = -0.5 * (b + d.sqrt().copysign(b));
    if q == 0.0 {
        return None;
    }
    out[0] = q;
    out[1] = c / q;
    Some(2)
}

/// `x^3 + a x^2 + b x + c` with `x = t - s` is `t^3 + p t + q`: `(s, p, q)`.
fn depressed(a: f64, b: f64, c: f64) -> (f64, f64, f64) {
    let s = a / 3.0;
    (s, b - a * s, (2.0 * s * s - b) * s + c)
}

/// For `t^3 + p t + q` with three real roots (`p < 0`): `(amplitude, phi)` such that the
/// roots are `amplitude * cos(phi - 2 pi k / 3)`, `k = 0` the largest (Viète).
fn trigonometric(p: f64, q: f64) -> (f64, f64) {
    let r = (-p / 3.0).sqrt();
    (2.0 * r, (1.5 * q / (p * r)).clamp(-1.0, 1.0).acos() / 3.0)
}

/// The real root of `t^3 + p t + q` when the other two are complex (hyperbolic forms).
fn single_real_root(p: f64, q: f64) -> f64 {
    if p == 0.0 {
        (-q).cbrt()
    } else if p < 0.0 {
        let r = (-p / 3.0).sqrt();
        -2.0 * q.signum() * r * ((1.5 * q.abs() / (-p * r)).max(1.0).acosh() / 3.0).cosh()
    } else {
        let r = (p / 3.0).sqrt();
        -2.0 * r * ((1.5 * q / (p * r)).asinh() / 3.0).sinh()
    }
}

/// Real roots of `x^3 + a x^2 + b x + c` (unsorted), `None` near a double root.
fn cubic(a: f64, b: f64, c: f64, out: &mut [f64; 4]) -> Option<usize> {
    let (s, p, q) = depressed(a, b, c);
    // Discriminant -(4 p^3 + 27 q^2): positive for three distinct real roots.
    let (p3, q2) = (4.0 * p * p * p, 27.0 * q * q);
    let disc = -(p3 + q2);
    if disc.abs() <= DISCRIMINANT_TOL * (p3.abs() + q2) {
        return None;
    }
    if disc < 0.0 {
        out[0] = single_real_root(p, q) - s;
        return Some(1);
    }
    let (amplitude, phi) = trigonometric(p, q);
    let tau = 2.0 * std::f64::consts::PI / 3.0;
    for (k, o) in out.iter_mut().take(3).enumerate() {
        *o = amplitude * (phi - tau * k as f64).cos() - s;
    }
    Some(3)
}

/// The largest real root of `x^3 + a x^2 + b x + c`, polished by Newton's iteration: the
/// formulas of [`cubic`] without its refusal near a double root (the largest root is
/// continuous there; NaN for non-finite input).
fn largest_cubic_root(a: f64, b: f64, c: f64) -> f64 {
    let (s, p, q) = depressed(a, b, c);
    let t = if 4.0 * p * p * p + 27.0 * q * q < 0.0 {
        let (amplitude, phi) = trigonometric(p, q);
        amplitude * phi.cos()
    } else {
        single_real_root(p, q)
    };
    polish(&[c, b, a], t - s)
}

/// Real roots of `x^4 + a x^3 + b x^2 + c x + d` (unsorted).
fn quartic(a: f64, b: f64, c: f64, d: f64, out: &mut [f64; 4]) -> Option<usize> {
    let s = a / 4.0;
    let s2 = s * s;
    // y = x + s: y^4 + p y^2 + q y + r.
    let p = b - 6.0 * s2;
    let q = c - 2.0 * b * s + 8.0 * s2 * s;
    let r = d - c * s + b * s2 - 3.0 * s2 * s2;
    let size = 1.0 + p.abs() + q.abs().sqrt() + r.abs().sqrt();
    let mut n = 0;
    if q.abs() <= f64::EPSILON * size * size * size {
        // Biquadratic: y^2 = z with z^2 + p z + r = 0.
        let mut z = [0.0; 4];
        let nz = quadratic(p, r, &mut z)?;
        for &zk in &z[..nz] {
            if zk > 0.0 {
                let y = zk.sqrt();
                out[n] = y - s;
                out[n + 1] = -y - s;
                n += 2;
            } else if zk == 0.0 {
                return None;
            }
        }
        return Some(n);
    }
    // Resolvent: m^3 + p m^2 + (p^2 / 4 - r) m - q^2 / 8 = 0 has a positive root (its
    // value at 0 is -q^2 / 8 < 0); its largest real root is the best conditioned.
    let m = largest_cubic_root(p, 0.25 * p * p - r, -0.125 * q * q);
    if m.is_nan() || m <= 0.0 {
        return None;
    }
    // y^4 + p y^2 + q y + r = (y^2 + p/2 + m)^2 - 2m (y - q / (4m))^2
    //   = (y^2 - w y + p/2 + m + q/(2w)) (y^2 + w y + p/2 + m - q/(2w)), w = sqrt(2m).
    let w = (2.0 * m).sqrt();
    let half = 0.5 * p + m;
    let shift = 0.5 * q / w;
    for (lin, cons) in [(-w, half + shift), (w, half - shift)] {
        let mut y = [0.0; 4];
        let ny = quadratic(lin, cons, &mut y)?;
        for &yk in &y[..ny] {
            out[n] = yk - s;
            n += 1;
        }
    }
    Some(n)
}

/// The acceptance residual of [`eigenpairs_2x2`]: `|A v - lambda v|` relative to the
/// largest entry of `A`.
const EIGENPAIR_RESIDUAL: f64 = 1e-13;

/// Up to two eigenpairs `(lambda, unit v)` of a 2x2 matrix.
pub(crate) type Eigenpairs2 = [(f64, [f64; 2]); 2];

/// Real eigenpairs of `[[a, b], [c, d]]` in closed form, unit vectors, in increasing order
/// of eigenvalue: `Some` of none or two pairs; `None` (the caller's general method decides)
/// for a non-finite or zero matrix, a (near) double eigenvalue, or a pair whose residual is
/// above [`EIGENPAIR_RESIDUAL`].
pub(crate) fn eigenpairs_2x2(m: [[f64; 2]; 2]) -> Option<(Eigenpairs2, usize)> {
    let [[a, b], [c, d]] = m;
    let size = a.abs().max(b.abs()).max(c.abs()).max(d.abs());
    if !size.is_finite() || size == 0.0 {
        return None;
    }
    // (a - d)^2 + 4 b c = tr^2 - 4 det, without its cancellation for distinct diagonals.
    let half = 0.5 * (a - d);
    let disc = half * half + b * c;
    if disc.abs() <= DISCRIMINANT_TOL * (half * half + (b * c).abs()) {
        return None;
    }
    let mut pairs = [(0.0, [0.0; 2]); 2];
    if disc < 0.0 {
        return Some((pairs, 0));
    }
    let mean = 0.5 * (a + d);
    let root = disc.sqrt();
    for (k, lambda) in [mean - root, mean + root].into_iter().enumerate() {
        // Null vectors of the rows (a - l, b) and (c, d - l); the longer is the better.
        let (v1, v2) = ([b, lambda - a], [lambda - d, c]);
        // Entries are at most a few times `size`: squares neither overflow nor underflow
        // for any matrix an action can be.
        let n1 = v1[0] * v1[0] + v1[1] * v1[1];
        let n2 = v2[0] * v2[0] + v2[1] * v2[1];
        let (v, n2) = if n1 >= n2 { (v1, n1) } else { (v2, n2) };
        let n = n2.sqrt();
        if n.is_nan() || n <= f64::EPSILON * size {
            return None;
        }
        let v = [v[0] / n, v[1] / n];
        let r0 = a * v[0] + b * v[1] - lambda * v[0];
        let r1 = c * v[0] + d * v[1] - lambda * v[1];
        let tolerance = EIGENPAIR_RESIDUAL * size;
        if (r0 * r0 + r1 * r1).partial_cmp(&(tolerance * tolerance))
            != Some(std::cmp::Ordering::Less)
        {
            return None;
        }
        pairs[k] = (lambda, v);
    }
    Some((pairs, 2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Lower coefficients of the monic polynomial with the given roots.
    fn from_roots<const N: usize>(roots: &[f64]) -> [f64; N] {
        let mut full = vec![1.0];
        for &r in roots {
            let mut next = vec![0.0; full.len() + 1];
            for (k, &f) in full.iter().enumerate() {
                next[k + 1] += f;
                next[k] -= r * f;
            }
            full = next;
        }
        std::array::from_fn(|k| full[k])
    }

    fn check<const N: usize>(rng: &mut ChaCha8Rng, real: usize) {
        // `real` real roots in [-1, 1], the rest complex pairs.
        let mut roots: Vec<f64> = (0..real).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let mut coefs = vec![1.0];
        for &r in &roots {
            coefs = mul(&coefs, &[-r, 1.0]);
        }
        for _ in 0..(N - real) / 2 {
            let (re, im) = (rng.gen_range(-1.0..1.0), rng.gen_range(0.05..1.0));
            coefs = mul(&coefs, &[re * re + im * im, -2.0 * re, 1.0]);
        }
        let c: [f64; N] = std::array::from_fn(|k| coefs[k]);
        roots.sort_by(f64::total_cmp);
        let mut got = [0.0; N];
        match monic_real_roots(&c, &mut got) {
            Some(n) => {
                assert_eq!(n, real, "{c:?}: {got:?} against {roots:?}");
                for (g, r) in got[..n].iter().zip(&roots) {
                    assert!((g - r).abs() < 1e-9, "{c:?}: {got:?} against {roots:?}");
                }
            }
            // Only close roots may be refused.
            None => assert!(
                roots.windows(2).any(|w| w[1] - w[0] < 1e-3),
                "{c:?} refused, roots {roots:?}"
            ),
        }
    }

    /// Product of two polynomials given by coefficients in increasing degree.
    fn mul(a: &[f64], b: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; a.len() + b.len() - 1];
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                out[i + j] += x * y;
            }
        }
        out
    }

    #[test]
    fn roots_of_random_polynomials_up_to_degree_four() {
        let mut rng = ChaCha8Rng::seed_from_u64(44);
        for _ in 0..2000 {
            check::<1>(&mut rng, 1);
            check::<2>(&mut rng, 2);
            check::<2>(&mut rng, 0);
            check::<3>(&mut rng, 3);
            check::<3>(&mut rng, 1);
            check::<4>(&mut rng, 4);
            check::<4>(&mut rng, 2);
            check::<4>(&mut rng, 0);
        }
    }

    #[test]
    fn eigenpairs_of_2x2_matrices() {
        let mut rng = ChaCha8Rng::seed_from_u64(45);
        let (mut real, mut complex) = (0, 0);
        for _ in 0..5000 {
            let m: [[f64; 2]; 2] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
            let reference =
                crate::real_eigenpairs(&nalgebra::Matrix2::new(m[0][0], m[0][1], m[1][0], m[1][1]));
            match eigenpairs_2x2(m) {
                Some((pairs, n)) => {
                    assert_eq!(n, reference.len(), "{m:?}");
                    for (lambda, v) in &pairs[..n] {
                        assert!(
                            reference.iter().any(|(l, _)| (l - lambda).abs() < 1e-12),
                            "{m:?}"
                        );
                        assert!((v[0].hypot(v[1]) - 1.0).abs() < 1e-15);
                    }
                    if n == 2 {
                        assert!(pairs[0].0 < pairs[1].0);
                        real += 1;
                    } else {
                        complex += 1;
                    }
                }
                None => panic!("{m:?} refused"),
            }
        }
        assert!(real > 1000 && complex > 1000, "{real} {complex}");
        // A double eigenvalue, a zero and a non-finite matrix are left to the general path.
        assert_eq!(eigenpairs_2x2([[1.0, 1.0], [0.0, 1.0]]), None);
        assert_eq!(eigenpairs_2x2([[0.0; 2]; 2]), None);
        assert_eq!(eigenpairs_2x2([[f64::NAN, 0.0], [0.0, 1.0]]), None);
        // Badly scaled entries keep their accuracy.
        let (pairs, n) = eigenpairs_2x2([[1e8, 1.0], [1e-8, 2.0]]).unwrap();
        assert_eq!(n, 2);
        assert!(
            (pairs[1].0 - 1e8).abs() < 1e-6 && (pairs[0].0 - 2.0).abs() < 1e-9,
            "{pairs:?}"
        );
    }

    #[test]
    fn special_forms() {
        let mut r = [0.0; 4];
        // Biquadratic with four real roots: (x^2 - 1)(x^2 - 4).
        assert_eq!(
            monic_real_roots(&from_roots::<4>(&[-2.0, -1.0, 1.0, 2.0]), &mut r),
            Some(4)
        );
        assert_eq!(r, [-2.0, -1.0, 1.0, 2.0]);
        // x^3 (p = q = 0) is a triple root: refused.
        assert_eq!(monic_real_roots(&[0.0; 3], &mut [0.0; 3]), None);
        // A double root is refused, the general method decides.
        assert_eq!(
            monic_real_roots(&from_roots::<2>(&[0.5, 0.5]), &mut [0.0; 2]),
            None
        );
        assert_eq!(
            monic_real_roots(&from_roots::<4>(&[0.1, 0.3, 0.3, 0.9]), &mut [0.0; 4]),
            None
        );
        // Non-finite coefficients and degree 5 are refused.
        assert_eq!(monic_real_roots(&[f64::NAN, 0.0], &mut [0.0; 2]), None);
        assert_eq!(monic_real_roots(&[0.0; 5], &mut [0.0; 5]), None);
        // Roots far from 1 keep relative accuracy: 1e-4 and 1e4.
        let mut r2 = [0.0; 2];
        assert_eq!(
            monic_real_roots(&from_roots::<2>(&[1e-4, 1e4]), &mut r2),
            Some(2)
        );
        assert!(
            (r2[0] - 1e-4).abs() < 1e-18 && (r2[1] - 1e4).abs() < 1e-9,
            "{r2:?}"
        );
    }
}
