//! Real eigenpairs of small dense matrices through the characteristic polynomial: a faster
//! alternative to the QR back end ([`super::real_eigenpairs_hqr`]) for action matrices.
//!
//! 1. Balancing (powers of 2), scaling to 1-norm 1, and reduction to upper
//!    Hessenberg form `H = S^-1 A S` by stabilised elementary similarities (Gaussian
//!    elimination with partial pivoting; `S` kept), see [`super::hessenberg`].
//! 2. Characteristic polynomial of `H` by the Hessenberg determinant recurrence
//!    (O(N^3 / 6)); every root lies in `[-1, 1]`.
//! 3. Its real roots: Sturm sequence (stored as linear quotients, O(N) per evaluation),
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
//! Every loop is bounded. The QR back end takes over when the Sturm sequence degenerates
//! (a remainder vanishes exactly: multiple roots or special structure), when a root is not
//! confirmed by inverse iteration (moved by more than [`AGREE_TOL`], or a residual above
//! [`ACCEPT_RESIDUAL`]: a spurious real root from a complex pair near the real axis), or
//! when two roots converge to one eigenvalue.

use super::hessenberg::{
    eigenvector_by_recurrence, hessenberg_of_columns, hyman_newton_step, inverse_iteration,
    normalise, subdiagonal_reciprocals, transpose,
};
use super::{real_eigenpairs_hqr, SolutionSet};
use nalgebra::{SMatrix, SVector};

/// Maximum bisection levels (the bracket shrinks by 2^-60 relative to `[-1, 1]`).
const MAX_BISECT: u32 = 60;
/// A root of the characteristic polynomial of the scaled matrix (norm 1) is accepted if
/// inverse iteration moves it by at most this; otherwise the QR back end is used.
const AGREE_TOL: f64 = 1e-7;
/// An eigenpair of the scaled matrix (norm 1) whose residual after inverse iteration is
/// above this is not trusted: the QR back end decides.
const ACCEPT_RESIDUAL: f64 = 1e-11;
/// The eigenvector from the Hessenberg backward recurrence is taken if the backward error
/// of the pair (scaled matrix of norm 1) is at most this; otherwise inverse iteration.
const FAST_RESIDUAL: f64 = 2e-15;
/// Maximum safeguarded Newton iterations per root.
const MAX_NEWTON: u32 = 40;
/// Octasection rounds before Newton's iteration (see `Sturm::polish_all`).
const OCTASECTIONS: usize = 1;

/// Same contract as [`super::real_eigenpairs`]: the real eigenvalues and unit eigenvectors
/// of `m` (at most `N`; in increasing order of eigenvalue unless the QR back end took
/// over), an empty set for non-finite or zero input; never panics, no heap allocation. A
/// real double root may be reported once; complex pairs very close to the real axis are
/// reported as one real eigenvalue only when the QR back end takes over.
pub fn real_eigenpairs_sturm<const N: usize>(
    m: &SMatrix<f64, N, N>,
) -> SolutionSet<(f64, SVector<f64, N>), N> {
    let mut out = SolutionSet::filled_with((0.0, SVector::zeros()));
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
    let sturm = Sturm::new(&p)?;
    let mut roots = [0.0f64; N];
    let nroots = sturm.real_roots(&p, &mut roots);
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
        // prev has degree d + 1, cur degree d; both leading coefficients are +-1 (p is
        // monic, p' / N too, and every later member is normalised), so the quotient needs
        // no division and each step one reciprocal.
        let mut d = N - 1;
        let mut k = 1;
        while d >= 1 {
            // prev = (alpha x + beta) cur + r; then prev <- -r / c (degree d - 1).
            let alpha = prev_lead * cur_lead;
            let beta = (prev[d] - alpha * cur[d - 1]) * cur_lead;
            let lead_r =
                prev[d - 1] - alpha * if d >= 2 { cur[d - 2] } else { 0.0 } - beta * cur[d - 1];
            let c = lead_r.abs();
            if !(c > 0.0 && c.is_finite() && alpha.is_finite() && beta.is_finite()) {
                return None;
            }
            s.alpha[k] = alpha;
            s.beta[k] = beta;
            s.c[k] = c;
            let minus_inv_c = -1.0 / c;
            let mut below = 0.0;
            for j in 0..d - 1 {
                let r = prev[j] - alpha * below - beta * cur[j];
                below = cur[j];
                prev[j] = r * minus_inv_c;
            }
            prev_lead = if lead_r > 0.0 { -1.0 } else { 1.0 };
            std::mem::swap(&mut prev, &mut cur);
            std::mem::swap(&mut prev_lead, &mut cur_lead);
            d -= 1;
            k += 1;
        }
        // Now prev is S_{N-1} (degree 1) and cur is S_N (degree 0).
        s.lead1 = prev_lead;
        s.c1 = prev[0];
        s.lead0 = cur_lead;
        Some(s)
    }

    /// Sign changes of the sequence at each of the `K` points, and `p` (= `S_0`) there.
    /// The points are evaluated in lockstep (independent recurrences: `K` of them cost
    /// about as much as one on a pipelined core). Zeros are counted as signed values: an
    /// interior zero `S_k(x) = 0` lies between `S_{k-1}(x)` and `S_{k+1}(x)` of opposite
    /// signs, so either sign gives the same count; only `p(x) = 0` exactly (a root on a
    /// sampling point) can shift one root to the neighbouring interval.
    #[inline]
    fn changes<const K: usize>(&self, x: [f64; K]) -> ([u32; K], [f64; K]) {
        let mut next = [self.lead0; K]; // S_N, +-1
        let mut cur = [0.0f64; K]; // S_{N-1}
        let mut n = [0u64; K];
        for q in 0..K {
            cur[q] = self.lead1 * x[q] + self.c1;
            n[q] = (cur[q].to_bits() ^ next[q].to_bits()) >> 63;
        }
        for k in (1..N).rev() {
            let (a, b, c) = (self.alpha[k], self.beta[k], self.c[k]);
            for q in 0..K {
                let prev = (a * x[q] + b) * cur[q] - c * next[q];
                n[q] += (prev.to_bits() ^ cur[q].to_bits()) >> 63;
                next[q] = cur[q];
                cur[q] = prev;
            }
        }
        (n.map(|v| v as u32), cur)
    }

    /// Writes the real roots of `p` (every eigenvalue of a matrix of 1-norm 1 lies in
    /// `[-1, 1]`) into `roots` in increasing order; returns their number.
    ///
    /// Isolation by quadrisection on Sturm counts (three interior points per interval,
    /// evaluated together), then [`Self::polish_all`] on the intervals holding one root.
    fn real_roots(&self, p: &[f64; N], roots: &mut [f64; N]) -> usize {
        let bound = root_bound(p);
        let ([vlo, vhi], [plo, phi]) = self.changes([-bound, bound]);
        if vlo <= vhi {
            return 0;
        }
        // Stack of disjoint intervals (a, b] with va - vb >= 1 roots and p(a), p(b); right
        // parts pushed first so that roots come out in increasing order. At most N - 1
        // intervals wait at any time (each holds a root, and one is being split).
        let mut stack = [Interval::default(); N];
        let mut top = 1usize;
        stack[0] = Interval {
            a: -bound,
            b: bound,
            va: vlo,
            vb: vhi,
            pa: plo,
            pb: phi,
            depth: 0,
        };
        let mut nroots = 0usize;
        // Isolated roots (output slot, interval), polished together at the end.
        let mut pending = [(0usize, Interval::default()); N];
        let mut npending = 0usize;
        while top > 0 {
            top -= 1;
            let iv = stack[top];
            let count = iv.va.saturating_sub(iv.vb);
            if count == 0 {
                continue;
            }
            let w = iv.b - iv.a;
            let xs = [iv.a + 0.25 * w, iv.a + 0.5 * w, iv.a + 0.75 * w];
            let split = count > 1 && iv.depth < MAX_BISECT / 2 && iv.a < xs[0] && xs[2] < iv.b;
            if !split {
                if nroots < N {
                    if count == 1 {
                        pending[npending] = (nroots, iv);
                        npending += 1;
                    } else {
                        roots[nroots] = xs[1]; // an unresolvable cluster: one representative
                    }
                    nroots += 1;
                }
                continue;
            }
            let (vs, ps) = self.changes(xs);
            let pts = [
                (iv.a, iv.va, iv.pa),
                (xs[0], vs[0], ps[0]),
                (xs[1], vs[1], ps[1]),
                (xs[2], vs[2], ps[2]),
                (iv.b, iv.vb, iv.pb),
            ];
            for q in (0..4).rev() {
                let (a, va, pa) = pts[q];
                let (b, vb, pb) = pts[q + 1];
                if va > vb && top < N {
                    stack[top] = Interval {
                        a,
                        b,
                        va,
                        vb,
                        pa,
                        pb,
                        depth: iv.depth + 1,
                    };
                    top += 1;
                }
            }
        }
        self.polish_all(p, &pending[..npending], roots);
        nroots
    }

    /// Polishes every isolated root (`(slot, interval)`, the interval holding exactly one
    /// root) into `roots[slot]`. The roots are iterated in lockstep, one step of each per
    /// round: their evaluations are independent, so a pipelined core overlaps them (one
    /// root at a time is bound by the latency of Horner's recurrence).
    ///
    /// Per root: [`OCTASECTIONS`] octasection rounds on the sign of `p` (seven points
    /// evaluated together cost about one Newton step; each shrinks the bracket 8x toward
    /// Newton's quadratic regime), then Newton from the regula-falsi point, safeguarded by the
    /// bracket (bisection whenever a step leaves it), to about 1e-12 relative (inverse
    /// iteration refines the eigenvalue afterwards). An interval whose ends have equal
    /// signs (even multiplicity in floating point) is bisected on the Sturm counts instead.
    fn polish_all(&self, p: &[f64; N], pending: &[(usize, Interval)], roots: &mut [f64; N]) {
        let n = pending.len();
        let mut a = [0.0f64; N];
        let mut b = [0.0f64; N];
        let mut pa = [0.0f64; N];
        let mut pb = [0.0f64; N];
        let mut neg_at_a = [false; N];
        // `bracketed`: a sign change, the root ends in x; `active`: still iterating.
        let mut bracketed = [false; N];
        let mut active = [false; N];
        let mut x = [0.0f64; N];
        for (r, (slot, iv)) in pending.iter().enumerate() {
            (a[r], b[r], pa[r], pb[r]) = (iv.a, iv.b, iv.pa, iv.pb);
            if iv.pa == 0.0 {
                roots[*slot] = iv.a;
            } else if iv.pb == 0.0 {
                roots[*slot] = iv.b;
            } else if (iv.pa > 0.0) == (iv.pb > 0.0) {
                roots[*slot] = self.bisect_counts(iv);
            } else {
                neg_at_a[r] = iv.pa < 0.0;
                bracketed[r] = true;
                active[r] = true;
            }
        }
        for _ in 0..OCTASECTIONS {
            for r in 0..n {
                if !active[r] {
                    continue;
                }
                let w = (b[r] - a[r]) * 0.125;
                let xs: [f64; 7] = std::array::from_fn(|q| a[r] + (q + 1) as f64 * w);
                let ps = eval_monic_at(p, xs);
                let mut q = 0;
                while q < 7 && (ps[q] < 0.0) == neg_at_a[r] && ps[q] != 0.0 {
                    q += 1;
                }
                if q < 7 && ps[q] == 0.0 {
                    x[r] = xs[q];
                    active[r] = false;
                    continue;
                }
                if q > 0 {
                    a[r] = xs[q - 1];
                    pa[r] = ps[q - 1];
                }
                if q < 7 {
                    b[r] = xs[q];
                    pb[r] = ps[q];
                }
            }
        }
        for r in 0..n {
            if !active[r] {
                continue;
            }
            x[r] = a[r] - pa[r] * (b[r] - a[r]) / (pb[r] - pa[r]);
            if !(x[r] > a[r] && x[r] < b[r]) {
                x[r] = 0.5 * (a[r] + b[r]);
            }
        }
        for _ in 0..MAX_NEWTON {
            let mut any = false;
            for r in 0..n {
                if !active[r] {
                    continue;
                }
                let (px, dpx) = eval_monic(p, x[r]);
                if px == 0.0 {
                    active[r] = false;
                    continue;
                }
                if (px < 0.0) == neg_at_a[r] {
                    a[r] = x[r];
                } else {
                    b[r] = x[r];
                }
                let step = px / dpx;
                // 1e-12 relative suffices (stricter tests stall at the rounding level of
                // p); the absolute floor (|H| = 1) ends roots at 0.
                let tol = 1e-12 * x[r].abs() + 1e-15;
                let nx = x[r] - step;
                if step.abs() <= tol {
                    if nx >= a[r] && nx <= b[r] {
                        x[r] = nx;
                    }
                    active[r] = false;
                    continue;
                }
                x[r] = if nx > a[r] && nx < b[r] {
                    nx
                } else {
                    0.5 * (a[r] + b[r])
                };
                // NaN-safe: a NaN bracket ends the iteration too.
                if (b[r] - a[r]).partial_cmp(&tol) != Some(std::cmp::Ordering::Greater) {
                    active[r] = false;
                    continue;
                }
                any = true;
            }
            if !any {
                break;
            }
        }
        for (r, (slot, _)) in pending.iter().enumerate() {
            if bracketed[r] {
                roots[*slot] = x[r];
            }
        }
    }

    /// The root in `iv` by bisection on the Sturm counts (an interval whose ends have equal
    /// signs of `p`: even multiplicity in floating point).
    fn bisect_counts(&self, iv: &Interval) -> f64 {
        let (mut a, mut b) = (iv.a, iv.b);
        for _ in 0..MAX_BISECT {
            let mid = 0.5 * (a + b);
            if !(a < mid && mid < b) {
                break;
            }
            if self.changes([mid]).0[0] < iv.va {
                b = mid;
            } else {
                a = mid;
            }
        }
        0.5 * (a + b)
    }
}

/// Horner evaluation of the monic polynomial with lower coefficients `c` at `K` points
/// in lockstep.
#[inline]
fn eval_monic_at<const N: usize, const K: usize>(c: &[f64; N], x: [f64; K]) -> [f64; K] {
    let mut p = [1.0f64; K];
    for &ck in c.iter().rev() {
        for q in 0..K {
            p[q] = p[q] * x[q] + ck;
        }
    }
    p
}

/// An interval `(a, b]` of the root isolation: Sturm counts and values of `p` at its ends.
#[derive(Clone, Copy, Default)]
struct Interval {
    a: f64,
    b: f64,
    va: u32,
    vb: u32,
    pa: f64,
    pb: f64,
    depth: u32,
}

/// A power of two bounding the moduli of the roots of the monic `p` (lower coefficients),
/// at most 1 (the matrix is scaled to 1-norm 1): Fujiwara's bound
/// `2 max |c_{N-k}|^(1/k)` (`|c_0 / 2|` for `k = N`), rounded up to a power of two without
/// `powf`, times 1.01 so that roots on the bound are inside.
fn root_bound<const N: usize>(p: &[f64; N]) -> f64 {
    // Smallest b = 2^-j (j <= 60) with |c_{N-k}| <= b^k for every k; Fujiwara: 2b.
    let fits = |b: f64| {
        let mut bk = 1.0;
        for (k, &ck) in p.iter().rev().enumerate() {
            bk *= b;
            let a = if k == N - 1 { 0.5 * ck.abs() } else { ck.abs() };
            if a.partial_cmp(&bk)
                .map_or(true, |o| o == std::cmp::Ordering::Greater)
            {
                return false;
            }
        }
        true
    };
    let mut b = 1.0f64;
    for _ in 0..60 {
        if !fits(0.5 * b) {
            break;
        }
        b *= 0.5;
    }
    (2.0 * b).min(1.0) * 1.01
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
