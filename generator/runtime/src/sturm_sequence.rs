//! The real roots of a monic polynomial whose roots lie in `[-1, 1]` (the characteristic
//! polynomial of a matrix scaled to 1-norm 1, see [`super::sturm`]): a Sturm sequence
//! stored as linear quotients (O(N) per evaluation), quadrisection on sign-change counts
//! until each interval holds one root, one octasection round on the sign of `p`, then
//! Newton steps safeguarded by the bracket. Every loop is bounded.

/// Maximum bisection levels (the bracket shrinks by 2^-60 relative to `[-1, 1]`).
const MAX_BISECT: u32 = 60;
/// Maximum safeguarded Newton iterations per root.
const MAX_NEWTON: u32 = 40;
/// Octasection rounds before Newton's iteration (see `Sturm::polish_all`).
const OCTASECTIONS: usize = 1;

/// Horner evaluation of the monic polynomial with lower coefficients `c` and its derivative.
#[inline]
pub(super) fn eval_monic<const N: usize>(c: &[f64; N], x: f64) -> (f64, f64) {
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
pub(super) struct Sturm<const N: usize> {
    alpha: [f64; N],
    beta: [f64; N],
    c: [f64; N],
    /// `S_{N-1} = lead1 * x + c1` and `S_N = lead0`.
    lead1: f64,
    c1: f64,
    lead0: f64,
}

impl<const N: usize> Sturm<N> {
    pub(super) fn new(p: &[f64; N]) -> Option<Self> {
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
    pub(super) fn real_roots(&self, p: &[f64; N], roots: &mut [f64; N]) -> usize {
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
