//! Real eigenpairs of small dense matrices through the characteristic polynomial: a faster
//! alternative to the Schur back end ([`super::real_eigenpairs`]) for action matrices.
//!
//! 1. Householder reduction to upper Hessenberg form `H = Q^T A Q` (reflectors kept).
//! 2. Characteristic polynomial of `H / s` (`s = |A|_inf`, so every root lies in
//!    `[-1, 1]`) by the Hessenberg determinant recurrence (O(N^3 / 6)).
//! 3. Its real roots: Sturm sequence (stored as linear quotients, O(N) per evaluation),
//!    bisection on sign-change counts until each interval holds one root, then
//!    Laguerre (or Newton) steps safeguarded by the bracket.
//! 4. For every real root, inverse iteration on `H - lambda I` (Hessenberg LU with partial
//!    pivoting, O(N^2)): the first solve, then up to two more steps until the residual of
//!    the pair is at the rounding level, which make the eigenvector accurate to working
//!    precision even though the root of the polynomial is less accurate than an eigenvalue
//!    from the Schur form; the eigenvalue is refined from the last step; `v = Q y`.
//!
//! Every loop is bounded. If the Sturm sequence degenerates (a remainder vanishes exactly:
//! multiple roots or special structure) the Schur back end is used instead.

use super::{real_eigenpairs, SolutionSet};
use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, DimDiff, DimSub, SMatrix, SVector, U1};

/// Maximum bisection levels (the bracket shrinks by 2^-60 relative to `[-1, 1]`).
const MAX_BISECT: u32 = 60;
/// A root of the characteristic polynomial of the scaled matrix (norm 1) is accepted if
/// inverse iteration moves it by at most this; otherwise the Schur back end is used.
const AGREE_TOL: f64 = 1e-7;
/// Maximum safeguarded Newton iterations per root.
const MAX_NEWTON: u32 = 40;
/// Inverse iteration stops after one step once the residual of the pair (scaled matrix of
/// norm 1) is below this.
const RESID_TOL: f64 = 5e-16;

/// Same contract as [`real_eigenpairs`]: the real eigenvalues and unit eigenvectors of `m`
/// (at most `N`, in increasing order of eigenvalue here), an empty set for non-finite or
/// zero input; never panics, no heap allocation. A real double root may be reported once;
/// complex pairs very close to the real axis are not reported (the Schur back end reports
/// them as one real eigenvalue).
pub fn real_eigenpairs_sturm<const N: usize>(
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
    // Row-major copy.
    let mut a = [[0.0f64; N]; N];
    for (i, row) in a.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = m[(i, j)];
            if !x.is_finite() {
                return out;
            }
        }
    }
    if N == 1 {
        return real_eigenpairs(m);
    }
    let d = balance(&mut a);
    let mut scale = 0.0f64;
    for row in &a {
        scale = scale.max(row.iter().map(|x| x.abs()).sum::<f64>());
    }
    if !scale.is_finite() {
        return out;
    }
    if scale == 0.0 {
        return real_eigenpairs(m);
    }
    let inv = 1.0 / scale;
    for row in a.iter_mut() {
        for x in row.iter_mut() {
            *x *= inv;
        }
    }
    let refl = hessenberg(&mut a);
    let h = a;
    let Some(p) = char_poly(&h) else {
        return real_eigenpairs(m);
    };
    let Some(sturm) = Sturm::new(&p) else {
        return real_eigenpairs(m);
    };
    let mut roots = [0.0f64; N];
    let nroots = sturm.real_roots(&p, &mut roots);
    let mut lams = [0.0f64; N];
    for (k, &mu) in roots[..nroots].iter().enumerate() {
        // The root must agree with the eigenvalue refined by inverse iteration on H (an
        // inaccurate characteristic polynomial shows here), and roots must stay distinct.
        let Some((lam_mu, y)) = inverse_iteration(&h, mu) else {
            return real_eigenpairs(m);
        };
        let agrees = (lam_mu - mu).abs() <= AGREE_TOL; // false for NaN
        if !agrees || lams[..k].contains(&lam_mu) {
            return real_eigenpairs(m);
        }
        lams[k] = lam_mu;
        let mut v = refl.apply(y);
        for (vi, di) in v.iter_mut().zip(&d) {
            *vi *= di;
        }
        let lam = lam_mu * scale;
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n > 0.0 && n.is_finite() && lam.is_finite() {
            out.push((lam, SVector::from_fn(|i, _| v[i] / n)));
        }
    }
    out
}

/// Balances `a` in place by a diagonal similarity `D^-1 a D` with powers of 2 (exact;
/// EISPACK `balanc` without permutations, at most 8 sweeps); returns `D`. Action matrices
/// are often badly scaled (norm 1e3-1e4 for eigenvalues of order 1), which would make the
/// characteristic polynomial's roots inaccurate.
fn balance<const N: usize>(a: &mut [[f64; N]; N]) -> [f64; N] {
    let mut d = [1.0f64; N];
    for _ in 0..8 {
        let mut done = true;
        for i in 0..N {
            let mut c = 0.0;
            let mut r = 0.0;
            for (j, row) in a.iter().enumerate() {
                if j != i {
                    c += row[i].abs();
                    r += a[i][j].abs();
                }
            }
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let s = c + r;
            let (mut cc, mut rr, mut f) = (c, r, 1.0f64);
            for _ in 0..64 {
                if cc < 0.5 * rr {
                    cc *= 2.0;
                    rr *= 0.5;
                    f *= 2.0;
                } else if cc >= 2.0 * rr {
                    cc *= 0.5;
                    rr *= 2.0;
                    f *= 0.5;
                } else {
                    break;
                }
            }
            if cc + rr < 0.95 * s {
                done = false;
                d[i] *= f;
                let g = 1.0 / f;
                for x in a[i].iter_mut() {
                    *x *= g;
                }
                for row in a.iter_mut() {
                    row[i] *= f;
                }
            }
        }
        if done {
            break;
        }
    }
    d
}

/// Householder reflectors `P_k = I - beta_k v_k v_k^T` of the Hessenberg reduction.
struct Reflectors<const N: usize> {
    v: [[f64; N]; N],
    beta: [f64; N],
}

impl<const N: usize> Reflectors<N> {
    /// `Q y = P_0 P_1 ... P_{N-3} y`.
    fn apply(&self, mut y: [f64; N]) -> [f64; N] {
        for k in (0..N.saturating_sub(2)).rev() {
            let b = self.beta[k];
            if b == 0.0 {
                continue;
            }
            let v = &self.v[k];
            let d: f64 = v.iter().zip(&y).skip(k + 1).map(|(a, b)| a * b).sum();
            let f = b * d;
            for (yi, vi) in y.iter_mut().zip(v).skip(k + 1) {
                *yi -= f * vi;
            }
        }
        y
    }
}

/// Reduces the row-major `a` to upper Hessenberg form in place (entries below the
/// subdiagonal set to zero) by Householder similarities; returns the reflectors.
#[allow(clippy::needless_range_loop)]
fn hessenberg<const N: usize>(a: &mut [[f64; N]; N]) -> Reflectors<N> {
    let mut r = Reflectors {
        v: [[0.0; N]; N],
        beta: [0.0; N],
    };
    for k in 0..N.saturating_sub(2) {
        let mut norm2 = 0.0;
        for row in a.iter().skip(k + 1) {
            norm2 += row[k] * row[k];
        }
        let x0 = a[k + 1][k];
        let tail = norm2 - x0 * x0;
        if tail == 0.0 {
            continue; // already reduced
        }
        let norm = norm2.sqrt();
        let alpha = if x0 >= 0.0 { -norm } else { norm };
        let v = &mut r.v[k];
        for (vi, row) in v.iter_mut().zip(a.iter()).skip(k + 1) {
            *vi = row[k];
        }
        v[k + 1] -= alpha;
        let vn2 = tail + v[k + 1] * v[k + 1];
        let beta = 2.0 / vn2;
        r.beta[k] = beta;
        // Left: rows k+1.., columns k+1.. (column k becomes [alpha, 0, ...]).
        let mut w = [0.0f64; N];
        for i in k + 1..N {
            let vi = v[i];
            for j in k + 1..N {
                w[j] += vi * a[i][j];
            }
        }
        for i in k + 1..N {
            let f = beta * v[i];
            for j in k + 1..N {
                a[i][j] -= f * w[j];
            }
            a[i][k] = 0.0;
        }
        a[k + 1][k] = alpha;
        // Right: all rows, columns k+1..
        for row in a.iter_mut() {
            let mut s = 0.0;
            for j in k + 1..N {
                s += row[j] * v[j];
            }
            let f = beta * s;
            for j in k + 1..N {
                row[j] -= f * v[j];
            }
        }
    }
    r
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

/// Horner evaluation of the monic polynomial with lower coefficients `c` and its derivative.
#[inline]
fn eval_monic<const N: usize>(c: &[f64; N], x: f64) -> (f64, f64) {
    let mut p = 1.0;
    let mut dp = 0.0;
    for &ck in c.iter().rev() {
        dp = dp * x + p;
        p = p * x + ck;
    }
    (p, dp)
}

/// Horner evaluation of the monic polynomial with lower coefficients `c`, its derivative
/// and half its second derivative.
#[inline]
fn eval_monic2<const N: usize>(c: &[f64; N], x: f64) -> (f64, f64, f64) {
    let mut p = 1.0;
    let mut dp = 0.0;
    let mut ddp = 0.0;
    for &ck in c.iter().rev() {
        ddp = ddp * x + dp;
        dp = dp * x + p;
        p = p * x + ck;
    }
    (p, dp, 2.0 * ddp)
}

/// Sturm sequence `S_0 = p`, `S_1 = p' / N`, `S_{k+1} = -rem(S_{k-1}, S_k) / c_k` (`c_k > 0`
/// makes the leading coefficient +-1), stored as `S_{k-1} = (alpha_k x + beta_k) S_k -
/// c_k S_{k+1}` so that evaluating the whole sequence costs O(N).
struct Sturm<const N: usize> {
    alpha: [f64; N],
    beta: [f64; N],
    c: [f64; N],
    /// `S_{N-1} = lead1 * x + c1` and `S_N = lead0`.
    lead1: f64,
    c1: f64,
    lead0: f64,
}

impl<const N: usize> Sturm<N> {
    fn new(p: &[f64; N]) -> Option<Self> {
        let mut s = Sturm {
            alpha: [0.0; N],
            beta: [0.0; N],
            c: [0.0; N],
            lead1: 0.0,
            c1: 0.0,
            lead0: 0.0,
        };
        // Polynomials as (lead, lower coefficients, degree).
        let mut prev_lead = 1.0f64;
        let mut prev = *p;
        let nf = N as f64;
        let mut cur_lead = 1.0f64;
        let mut cur = [0.0f64; N];
        for j in 0..N - 1 {
            cur[j] = (j + 1) as f64 * p[j + 1] / nf;
        }
        // prev has degree d + 1, cur degree d.
        let mut d = N - 1;
        let mut k = 1;
        while d >= 1 {
            // prev = (alpha x + beta) cur + r.
            let alpha = prev_lead / cur_lead;
            let beta = (prev[d] - alpha * cur[d - 1]) / cur_lead;
            let mut r = [0.0f64; N];
            for j in 0..d {
                let below = if j >= 1 { cur[j - 1] } else { 0.0 };
                r[j] = prev[j] - alpha * below - beta * cur[j];
            }
            let lead_r = r[d - 1];
            let c = lead_r.abs();
            if !(c > 0.0 && c.is_finite() && alpha.is_finite() && beta.is_finite()) {
                return None;
            }
            s.alpha[k] = alpha;
            s.beta[k] = beta;
            s.c[k] = c;
            // next = -r / c: leading coefficient -sign(lead_r), degree d - 1.
            let mut next = [0.0f64; N];
            for j in 0..d - 1 {
                next[j] = -r[j] / c;
            }
            let next_lead = if lead_r > 0.0 { -1.0 } else { 1.0 };
            prev = cur;
            prev_lead = cur_lead;
            cur = next;
            cur_lead = next_lead;
            d -= 1;
            k += 1;
        }
        // Now prev is S_{N-1} (degree 1) and cur is S_N (degree 0).
        s.lead1 = prev_lead;
        s.c1 = prev[0];
        s.lead0 = cur_lead;
        Some(s)
    }

    /// Number of sign changes of the sequence at `x`.
    fn changes(&self, x: f64) -> u32 {
        let mut next = self.lead0; // S_N, +-1
        let mut cur = self.lead1 * x + self.c1; // S_{N-1}
        let mut last = next;
        let mut n = 0u32;
        if cur != 0.0 {
            n += u32::from((cur < 0.0) != (last < 0.0));
            last = cur;
        }
        for k in (1..N).rev() {
            let prev = (self.alpha[k] * x + self.beta[k]) * cur - self.c[k] * next;
            if prev != 0.0 {
                n += u32::from((prev < 0.0) != (last < 0.0));
                last = prev;
            }
            next = cur;
            cur = prev;
        }
        n
    }

    /// Writes the real roots of `p` (every eigenvalue of a matrix of infinity norm 1 lies in
    /// `[-1, 1]`) into `roots` in increasing order; returns their number.
    fn real_roots(&self, p: &[f64; N], roots: &mut [f64; N]) -> usize {
        // Fujiwara's bound 2 max |c_{N-k}|^(1/k) (tight within a factor 2N, often much
        // smaller than the norm bound 1 for badly scaled action matrices), capped by it.
        let mut bound = 0.0f64;
        for (k, &ck) in p.iter().rev().enumerate() {
            let a = ck.abs();
            if a > 0.0 {
                let r = if k == N - 1 { 0.5 * a } else { a };
                bound = bound.max(r.powf(1.0 / (k + 1) as f64));
            }
        }
        let bound = (2.0 * bound * (1.0 + 1e-12)).min(1.0) * 1.01;
        if bound.is_nan() || bound <= 0.0 {
            return 0;
        }
        let lo = -bound;
        let hi = bound;
        let (vlo, vhi) = (self.changes(lo), self.changes(hi));
        if vlo <= vhi {
            return 0;
        }
        // Stack of disjoint intervals (a, b] holding va - vb >= 1 roots; right halves
        // pushed first so that roots come out in increasing order.
        let mut stack = [(0.0f64, 0.0f64, 0u32, 0u32, 0u32); N];
        let mut top = 0usize;
        stack[0] = (lo, hi, vlo, vhi, 0);
        top += 1;
        let mut nroots = 0usize;
        while top > 0 {
            top -= 1;
            let (a, b, va, vb, depth) = stack[top];
            let count = va.saturating_sub(vb);
            if count == 0 {
                continue;
            }
            let mid = 0.5 * (a + b);
            if count == 1 || depth >= MAX_BISECT || !(a < mid && mid < b) {
                if nroots < N {
                    roots[nroots] = if count == 1 {
                        self.polish(p, a, b, va)
                    } else {
                        mid
                    };
                    nroots += 1;
                }
                continue;
            }
            let vm = self.changes(mid);
            for (x, y, vx, vy) in [(mid, b, vm, vb), (a, mid, va, vm)] {
                if vx > vy && top < N {
                    stack[top] = (x, y, vx, vy, depth + 1);
                    top += 1;
                }
            }
        }
        nroots
    }

    /// The single root of `p` in `(a, b]`: Newton steps kept inside the bracket (bisection
    /// when a step leaves it); `va` is the sign-change count at `a`.
    fn polish(&self, p: &[f64; N], mut a: f64, mut b: f64, va: u32) -> f64 {
        let (pa, _) = eval_monic(p, a);
        let (pb, _) = eval_monic(p, b);
        if pa == 0.0 {
            return a;
        }
        if pb == 0.0 {
            return b;
        }
        if (pa > 0.0) == (pb > 0.0) {
            // Even multiplicity in floating point: bisect on the Sturm counts.
            for _ in 0..MAX_BISECT {
                let mid = 0.5 * (a + b);
                if !(a < mid && mid < b) {
                    break;
                }
                if self.changes(mid) < va {
                    b = mid;
                } else {
                    a = mid;
                }
            }
            return 0.5 * (a + b);
        }
        let neg_at_a = pa < 0.0;
        // Laguerre steps (cubic convergence, global for real-rooted polynomials), Newton when
        // the Laguerre discriminant is negative (complex roots nearby), bisection whenever a
        // step leaves the bracket.
        let n = N as f64;
        let mut x = 0.5 * (a + b);
        for _ in 0..MAX_NEWTON {
            let (px, dpx, ddpx) = eval_monic2(p, x);
            if px == 0.0 {
                return x;
            }
            if (px < 0.0) == neg_at_a {
                a = x;
            } else {
                b = x;
            }
            let g = dpx / px;
            let hh = g * g - ddpx / px;
            let disc = (n - 1.0) * (n * hh - g * g);
            let step = if disc >= 0.0 {
                let sq = disc.sqrt();
                let den = if g >= 0.0 { g + sq } else { g - sq };
                n / den
            } else {
                px / dpx
            };
            let mut nx = x - step;
            if !(nx > a && nx < b) {
                nx = 0.5 * (a + b);
            }
            // Inverse iteration refines the eigenpair afterwards: 1e-12 relative suffices
            // (stricter tests stall at the rounding level of p and cost every iteration);
            // the absolute floor (|H| = 1) ends roots at 0.
            let tol = 1e-12 * x.abs() + 1e-15;
            let done = (nx - x).abs() <= tol || b - a <= tol;
            x = nx;
            if done || a >= b || a.is_nan() || b.is_nan() {
                break;
            }
        }
        x
    }
}

/// Inverse iteration (at most two steps after the first solve) for the eigenvalue near `mu` of the upper Hessenberg
/// `h`: the eigenvector (unnormalised) and the refined eigenvalue, or `None`.
#[allow(clippy::needless_range_loop)]
fn inverse_iteration<const N: usize>(h: &[[f64; N]; N], mu: f64) -> Option<(f64, [f64; N])> {
    // LU with partial pivoting of the Hessenberg H - mu I: P_k swaps rows k, k+1, then
    // row k+1 -= l_k row k.
    let mut u = *h;
    for (i, row) in u.iter_mut().enumerate() {
        row[i] -= mu;
    }
    let mut swap = [false; N];
    let mut l = [0.0f64; N];
    let tiny = f64::EPSILON * 1e-3; // |H| ~ 1 after scaling
    for k in 0..N - 1 {
        if u[k + 1][k].abs() > u[k][k].abs() {
            u.swap(k, k + 1);
            swap[k] = true;
        }
        let mut piv = u[k][k];
        if piv.abs() < tiny {
            piv = if piv < 0.0 { -tiny } else { tiny };
            u[k][k] = piv;
        }
        let f = u[k + 1][k] / piv;
        l[k] = f;
        if f != 0.0 {
            let (top, bottom) = u.split_at_mut(k + 1);
            let (rk, rk1) = (&top[k], &mut bottom[0]);
            for (x, &y) in rk1.iter_mut().zip(rk.iter()).skip(k + 1) {
                *x -= f * y;
            }
        }
        u[k + 1][k] = 0.0;
    }
    if u[N - 1][N - 1].abs() < tiny {
        u[N - 1][N - 1] = if u[N - 1][N - 1] < 0.0 { -tiny } else { tiny };
    }
    let mut rdiag = [0.0f64; N];
    for (i, r) in rdiag.iter_mut().enumerate() {
        *r = 1.0 / u[i][i];
    }
    let back = |y: &mut [f64; N]| {
        for i in (0..N).rev() {
            let mut s = y[i];
            for j in i + 1..N {
                s -= u[i][j] * y[j];
            }
            y[i] = s * rdiag[i];
        }
    };
    let normalise = |y: &mut [f64; N]| -> Option<f64> {
        let n = y.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        for x in y.iter_mut() {
            *x /= n;
        }
        Some(n)
    };
    // Step 1: U y = e (LAPACK hein's first step).
    let mut y = [1.0f64; N];
    back(&mut y);
    let n = normalise(&mut y)?;
    // (H - mu I) y n = r0 = P_0 L_0 ... P_{N-2} L_{N-2} e (O(N)): Rayleigh quotient and
    // residual of this first step; it is usually accurate enough.
    let mut r0 = [1.0f64; N];
    for k in (0..N - 1).rev() {
        r0[k + 1] += l[k] * r0[k];
        if swap[k] {
            r0.swap(k, k + 1);
        }
    }
    let q: f64 = r0.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>() / n;
    let lam1 = mu + q;
    let r2: f64 = r0
        .iter()
        .zip(&y)
        .map(|(a, b)| (a / n - q * b) * (a / n - q * b))
        .sum();
    if lam1.is_finite() && r2 <= RESID_TOL * RESID_TOL {
        return Some((lam1, y));
    }
    let mut lam = mu;
    for step in 0..2 {
        let y0 = y;
        for k in 0..N - 1 {
            if swap[k] {
                y.swap(k, k + 1);
            }
            y[k + 1] -= l[k] * y[k];
        }
        back(&mut y);
        // (H - mu I) y = y0 and y0 ~ eigenvector: y ~ y0 / (lambda - mu).
        let d: f64 = y.iter().zip(&y0).map(|(a, b)| a * b).sum();
        let n = normalise(&mut y)?;
        if d != 0.0 && d.is_finite() {
            lam = mu + 1.0 / d;
            // Residual of the normalised pair: (H - lam I) y = (y0 - n y / d) / n. Small
            // enough (backward error at the rounding level of |H| = 1): done.
            if step == 0 {
                let g = n / d;
                let r2: f64 = y0
                    .iter()
                    .zip(&y)
                    .map(|(a, b)| (a - g * b) * (a - g * b))
                    .sum();
                if r2 <= RESID_TOL * RESID_TOL * n * n {
                    break;
                }
            }
        }
    }
    Some((lam, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SMatrix;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn residual<const N: usize>(m: &SMatrix<f64, N, N>, lam: f64, v: &SVector<f64, N>) -> f64 {
        (m * v - v * lam).norm() / m.norm()
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

#[cfg(test)]
mod piece_timing {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::hint::black_box;
    use std::time::Instant;

    #[test]
    #[ignore]
    fn pieces() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mats: Vec<[[f64; 10]; 10]> = (0..500)
            .map(|_| {
                let mut a = [[0.0; 10]; 10];
                for r in a.iter_mut() {
                    for x in r.iter_mut() {
                        *x = rng.gen_range(-1.0..1.0);
                    }
                }
                a
            })
            .collect();
        for _ in 0..3 {
            let t = Instant::now();
            for a in &mats {
                let mut a = *black_box(a);
                black_box(balance(&mut a));
            }
            let tb = t.elapsed().as_secs_f64() / 500.0 * 1e9;
            let t = Instant::now();
            for a in &mats {
                let mut a = *black_box(a);
                black_box(hessenberg(&mut a));
                black_box(a);
            }
            let th = t.elapsed().as_secs_f64() / 500.0 * 1e9;
            let hs: Vec<_> = mats
                .iter()
                .map(|a| {
                    let mut a = *a;
                    hessenberg(&mut a);
                    a
                })
                .collect();
            let t = Instant::now();
            for h in &hs {
                black_box(char_poly(black_box(h)));
            }
            let tc = t.elapsed().as_secs_f64() / 500.0 * 1e9;
            let ps: Vec<_> = hs.iter().map(|h| char_poly(h).unwrap()).collect();
            let t = Instant::now();
            for p in &ps {
                black_box(Sturm::new(black_box(p)));
            }
            let ts = t.elapsed().as_secs_f64() / 500.0 * 1e9;
            let t = Instant::now();
            let mut nr = 0;
            for p in &ps {
                let s = Sturm::new(p).unwrap();
                let mut roots = [0.0; 10];
                nr += s.real_roots(black_box(p), &mut roots);
                black_box(roots);
            }
            let tr = t.elapsed().as_secs_f64() / 500.0 * 1e9;
            let t = Instant::now();
            for h in &hs {
                black_box(inverse_iteration(black_box(h), 0.1));
            }
            let ti = t.elapsed().as_secs_f64() / 500.0 * 1e9;
            println!("balance {tb:.0} ns, hessenberg {th:.0}, charpoly {tc:.0}, sturm new {ts:.0}, sturm+roots {tr:.0} ({:.1} roots), inverse iteration {ti:.0} per root", nr as f64 / 500.0);
        }
    }
}
