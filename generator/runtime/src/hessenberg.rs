//! Upper Hessenberg form of small dense matrices and inverse iteration on it, at a size
//! fixed at compile time: the core of the Sturm eigen back end
//! ([`super::real_eigenpairs_sturm`]), on the stack for its small matrices. The QR back end
//! runs the same steps at run-time sizes on the heap ([`super::hessenberg_dyn`]).
//!
//! Convention: matrices are row-major `[[f64; N]; N]` (`a[i][j]`), scaled by the caller so
//! that their norm is about 1 (the tolerances below are absolute).

/// Inverse iteration stops after one step once the residual of the pair (matrix of norm
/// about 1) is below this.
const RESID_TOL: f64 = 5e-16;

/// The similarity `S = P_0 L_0 P_1 L_1 ... P_{N-3} L_{N-3}` of the Hessenberg reduction
/// `H = S^-1 A S` (`P_k` swaps indices `k + 1` and the pivot row, `L_k = I + m_k
/// e_{k+1}^T` with `m_k` zero above index `k + 2`), stored with the permutations moved to
/// the left as in a row-pivoted LU: `S = P L`, `P = P_0 ... P_{N-3}` as the gather
/// `(P z)[i] = z[gather[i]]`, `L = L'_0 ... L'_{N-3}` with `mult[k] = P_{N-3} ... P_{k+1}
/// m_k`. Applying `S` is then one pass of multiply-adds and one gather, instead of swaps
/// interleaved with the multiply-adds.
/// A step that had nothing to eliminate (its column already reduced) has zero multipliers.
pub(super) struct Similarity<const N: usize> {
    gather: [usize; N],
    mult: [[f64; N]; N],
}

impl<const N: usize> Similarity<N> {
    /// `S y`: an eigenvector of `H` becomes one of `A`.
    #[allow(clippy::needless_range_loop)] // indexed loops unroll; zip/skip chains did not
    pub(super) fn apply(&self, mut y: [f64; N]) -> [f64; N] {
        // L y: L'_{N-3} first; step k reads y[k+1], which no later-applied step changes.
        for k in (0..N.saturating_sub(2)).rev() {
            let yk1 = y[k + 1];
            let m = &self.mult[k];
            for i in k + 2..N {
                y[i] += m[i] * yk1;
            }
        }
        std::array::from_fn(|i| y[self.gather[i]])
    }
}

/// Reduces the row-major `a` to upper Hessenberg form in place by stabilised elementary
/// similarities (Gaussian elimination with partial pivoting, EISPACK `elmhes`): half the
/// work of Householder reflections, multipliers bounded by 1. Entries below the
/// subdiagonal are set to zero; returns the similarity for the eigenvectors. A column that
/// is already reduced costs one scan (see [`Similarity`]). The work is done on the
/// transpose by [`hessenberg_of_columns`].
#[cfg(test)]
pub(super) fn hessenberg<const N: usize>(a: &mut [[f64; N]; N]) -> Similarity<N> {
    let mut cols = transpose(a);
    let s = hessenberg_of_columns(&mut cols);
    *a = transpose(&cols);
    s
}

/// The transpose of a square array of arrays (row-major <-> column-major).
pub(super) fn transpose<const N: usize>(a: &[[f64; N]; N]) -> [[f64; N]; N] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// [`hessenberg`] on a matrix stored by columns (`cols[j][i]` is entry `(i, j)`), reduced
/// in place (still by columns). In this layout both updates of a step are contiguous
/// multiply-adds over columns, which vectorise; by rows the column update is a dot product
/// per row, which does not.
#[allow(clippy::needless_range_loop)] // indexed loops over const-size arrays unroll
pub(super) fn hessenberg_of_columns<const N: usize>(cols: &mut [[f64; N]; N]) -> Similarity<N> {
    let a = cols;
    let mut s = Similarity {
        gather: std::array::from_fn(|i| i),
        mult: [[0.0; N]; N],
    };
    let mut perm: [usize; N] = std::array::from_fn(|i| (i + 1).min(N - 1));
    for k in 0..N.saturating_sub(2) {
        // Pivot: the largest of column k from row k + 1 down; nothing to do if the rows
        // below k + 1 are already zero (no interchange, no multipliers).
        let (mut p, mut below) = (k + 1, 0.0f64);
        for i in k + 2..N {
            let x = a[k][i].abs();
            if x > below {
                below = x;
                p = i;
            }
        }
        if below == 0.0 {
            continue;
        }
        if a[k][k + 1].abs() >= below {
            p = k + 1;
        }
        perm[k] = p;
        if p != k + 1 {
            // Earlier multipliers follow the row interchange (S = P L, see Similarity).
            for m in s.mult.iter_mut().take(k) {
                m.swap(p, k + 1);
            }
            a.swap(p, k + 1);
            for col in a.iter_mut() {
                col.swap(p, k + 1);
            }
        }
        let inv = 1.0 / a[k][k + 1];
        let mut m = [0.0f64; N];
        for i in k + 2..N {
            m[i] = a[k][i] * inv;
            a[k][i] = 0.0;
        }
        s.mult[k] = m;
        // Rows: row_i -= m_i row_{k+1} (i > k + 1), column by column.
        for j in k + 1..N {
            let pj = a[j][k + 1];
            for i in k + 2..N {
                a[j][i] -= m[i] * pj;
            }
        }
        // Columns: col_{k+1} += sum_i m_i col_i.
        let (head, tail) = a.split_at_mut(k + 2);
        let target = &mut head[k + 1];
        for (col, &mi) in tail.iter().zip(&m[k + 2..]) {
            for r in 0..N {
                target[r] += mi * col[r];
            }
        }
    }
    // P = P_0 (P_1 (... (P_{N-3} z))) as a gather: the same swaps applied to the indices.
    for k in (0..N.saturating_sub(2)).rev() {
        s.gather.swap(k + 1, perm[k]);
    }
    s
}

/// An approximate eigenpair of a matrix of norm about 1 from [`inverse_iteration`].
pub(super) struct Eigenpair<const N: usize> {
    /// The eigenvalue, refined from the shift.
    pub lambda: f64,
    /// The eigenvector, unit 2-norm.
    pub vector: [f64; N],
    /// `|H v - lambda v|` (2-norm): the backward error of the pair. A real shift near a
    /// complex eigenvalue cannot make it small.
    pub residual: f64,
}

/// LU factors with partial pivoting of `H - mu I` for an upper Hessenberg `H`:
/// `P_k` swaps rows `k, k + 1` (if `swap[k]`), then row `k + 1 -= l[k] * row k`; `u` is
/// the upper triangular factor, `rdiag` the reciprocals of its diagonal. Tiny pivots are
/// replaced by `+-TINY` (the shift is meant to be an eigenvalue).
struct HessenbergLu<const N: usize> {
    u: [[f64; N]; N],
    swap: [bool; N],
    l: [f64; N],
    rdiag: [f64; N],
}

/// Pivot floor of [`HessenbergLu`] (|H| about 1).
const TINY: f64 = f64::EPSILON * 1e-3;

#[inline(always)]
fn guard(x: f64) -> f64 {
    if x.abs() < TINY {
        if x < 0.0 {
            -TINY
        } else {
            TINY
        }
    } else {
        x
    }
}

impl<const N: usize> HessenbergLu<N> {
    /// Factors `h - mu I`. The row being eliminated is carried in a local array and the
    /// pivot row written to `u` once: no rows are swapped in memory (swapping rows that
    /// were just updated stalls on store forwarding).
    #[inline(always)]
    fn factor(h: &[[f64; N]; N], mu: f64) -> Self {
        let mut lu = HessenbergLu {
            u: [[0.0; N]; N],
            swap: [false; N],
            l: [0.0; N],
            rdiag: [0.0; N],
        };
        let mut cur = h[0];
        cur[0] -= mu;
        for k in 0..N.saturating_sub(1) {
            let mut next = h[k + 1];
            next[k + 1] -= mu;
            let s = next[k].abs() > cur[k].abs();
            let (mut piv, oth) = if s { (next, cur) } else { (cur, next) };
            lu.swap[k] = s;
            piv[k] = guard(piv[k]);
            let f = oth[k] / piv[k];
            lu.l[k] = f;
            cur = oth;
            cur[k] = 0.0;
            for j in k + 1..N {
                cur[j] -= f * piv[j];
            }
            lu.u[k] = piv;
        }
        if N > 0 {
            cur[N - 1] = guard(cur[N - 1]);
            lu.u[N - 1] = cur;
        }
        for (i, r) in lu.rdiag.iter_mut().enumerate() {
            *r = 1.0 / lu.u[i][i];
        }
        lu
    }

    /// `y := U^-1 y`, column-oriented: the updates of the remaining right-hand side are
    /// independent, so the dependency chain is one multiply-add per row.
    #[inline(always)]
    fn back(&self, y: &mut [f64; N]) {
        for i in (0..N).rev() {
            let yi = y[i] * self.rdiag[i];
            y[i] = yi;
            for (yj, row) in y.iter_mut().zip(&self.u).take(i) {
                *yj -= row[i] * yi;
            }
        }
    }

    /// `y := (P L)^-1 y` (the forward part of a solve).
    #[inline(always)]
    fn forward(&self, y: &mut [f64; N]) {
        for k in 0..N - 1 {
            if self.swap[k] {
                y.swap(k, k + 1);
            }
            y[k + 1] -= self.l[k] * y[k];
        }
    }

    /// `P_0 L_0 ... P_{N-2} L_{N-2} e`: `(H - mu I) U^-1 e` (O(N)).
    #[inline(always)]
    fn residual_of_first_step(&self) -> [f64; N] {
        let mut r0 = [1.0f64; N];
        for k in (0..N - 1).rev() {
            r0[k + 1] += self.l[k] * r0[k];
            if self.swap[k] {
                r0.swap(k, k + 1);
            }
        }
        r0
    }
}

/// Scales `y` to unit norm; its former norm, or `None` if zero or not finite.
#[inline(always)]
pub(super) fn normalise<const N: usize>(y: &mut [f64; N]) -> Option<f64> {
    let n = y.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(n > 0.0 && n.is_finite()) {
        return None;
    }
    let r = 1.0 / n;
    for x in y.iter_mut() {
        *x *= r;
    }
    Some(n)
}

/// Inverse iteration (at most two steps after the first solve) for the eigenvalue near `mu`
/// of the upper Hessenberg `h`, or `None` (non-finite iterates).
pub(super) fn inverse_iteration<const N: usize>(
    h: &[[f64; N]; N],
    mu: f64,
) -> Option<Eigenpair<N>> {
    let lu = HessenbergLu::factor(h, mu);
    // Step 1: U y = e (LAPACK hein's first step).
    let mut y = [1.0f64; N];
    lu.back(&mut y);
    refine(&lu, mu, y)
}

/// The rest of [`inverse_iteration`] after the first solve `y = U^-1 e`.
fn refine<const N: usize>(lu: &HessenbergLu<N>, mu: f64, mut y: [f64; N]) -> Option<Eigenpair<N>> {
    let n = normalise(&mut y)?;
    // (H - mu I) y n = r0: Rayleigh quotient and residual of this first step; it is
    // usually accurate enough.
    let r0 = lu.residual_of_first_step();
    let inv_n = 1.0 / n;
    let q: f64 = r0.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>() * inv_n;
    let lam1 = mu + q;
    let r2: f64 = r0
        .iter()
        .zip(&y)
        .map(|(a, b)| (a * inv_n - q * b) * (a * inv_n - q * b))
        .sum();
    if lam1.is_finite() && r2 <= RESID_TOL * RESID_TOL {
        return Some(Eigenpair {
            lambda: lam1,
            vector: y,
            residual: r2.sqrt(),
        });
    }
    let mut lam = mu;
    let mut residual = f64::INFINITY;
    for _ in 0..2 {
        let y0 = y;
        lu.forward(&mut y);
        lu.back(&mut y);
        // (H - mu I) y = y0 and y0 ~ eigenvector: y ~ y0 / (lambda - mu).
        let d: f64 = y.iter().zip(&y0).map(|(a, b)| a * b).sum();
        let n = normalise(&mut y)?;
        if d != 0.0 && d.is_finite() {
            lam = mu + 1.0 / d;
            // Residual of the normalised pair: (H - lam I) y = (y0 - n y / d) / n. Small
            // enough (backward error at the rounding level of |H| = 1): done.
            let g = n / d;
            let r2: f64 = y0
                .iter()
                .zip(&y)
                .map(|(a, b)| (a - g * b) * (a - g * b))
                .sum();
            residual = r2.sqrt() / n;
            if residual <= RESID_TOL {
                break;
            }
        }
    }
    Some(Eigenpair {
        lambda: lam,
        vector: y,
        residual,
    })
}

/// Reciprocals `1 / h[i][i-1]` of the subdiagonal (index `i`, entry 0 unused), or `None`
/// if one is zero or not finite (the Hessenberg matrix is reduced: use
/// [`inverse_iteration`]).
pub(super) fn subdiagonal_reciprocals<const N: usize>(h: &[[f64; N]; N]) -> Option<[f64; N]> {
    let mut r = [0.0f64; N];
    for i in 1..N {
        r[i] = 1.0 / h[i][i - 1];
        if !r[i].is_finite() {
            return None;
        }
    }
    Some(r)
}

/// One Newton step for an eigenvalue of the unreduced upper Hessenberg `h` on Hyman's
/// determinant: the row-0 residual `r(mu)` of the backward recurrence of
/// [`eigenvector_by_recurrence`] (with `y[N-1] = 1`) is `det(h - mu I)` over the product of
/// the subdiagonal, so `mu - r / r'` (the recurrence differentiated alongside) refines `mu`
/// against `h` itself rather than against the rounded characteristic polynomial. `None` if
/// the step is not finite.
pub(super) fn hyman_newton_step<const N: usize>(
    h: &[[f64; N]; N],
    inv_sub: &[f64; N],
    mu: f64,
) -> Option<f64> {
    if N == 0 {
        return None;
    }
    let mut y = [0.0f64; N];
    let mut dy = [0.0f64; N];
    let mut acc = [0.0f64; N];
    let mut dacc = [0.0f64; N];
    y[N - 1] = 1.0;
    for i in (1..N).rev() {
        let (yi, dyi) = (y[i], dy[i]);
        for ((a, da), row) in acc.iter_mut().zip(dacc.iter_mut()).zip(h).take(i + 1) {
            *a += row[i] * yi;
            *da += row[i] * dyi;
        }
        y[i - 1] = -(acc[i] - mu * yi) * inv_sub[i];
        dy[i - 1] = -(dacc[i] - yi - mu * dyi) * inv_sub[i];
    }
    let r = acc[0] + h[0][0] * y[0] - mu * y[0];
    let dr = dacc[0] + h[0][0] * dy[0] - y[0] - mu * dy[0];
    let next = mu - r / dr;
    next.is_finite().then_some(next)
}

/// The eigenvector of the unreduced upper Hessenberg `h` for the eigenvalue `lambda`, by
/// the backward recurrence of `(h - lambda I) y = 0`: `y[N-1] = 1`, row `i` (from the
/// bottom) gives `y[i-1]`. Rows `1..N` are then satisfied to rounding; row 0 is not used,
/// and its residual is the backward error of the pair (about `p(lambda)` over the product
/// of the subdiagonal). `inv_sub` from [`subdiagonal_reciprocals`].
///
/// Returns the unit vector and `|row 0 residual| / |y|`, or `None` on overflow. O(N^2 / 2)
/// with a dependency chain of one multiply-add per row (the row sums are accumulated as
/// soon as each `y[j]` is known): several times cheaper than [`inverse_iteration`], which
/// remains the fallback when the residual is not small (an inaccurate `lambda`, or growth
/// in the recurrence).
pub(super) fn eigenvector_by_recurrence<const N: usize>(
    h: &[[f64; N]; N],
    inv_sub: &[f64; N],
    lambda: f64,
) -> Option<([f64; N], f64)> {
    if N == 0 {
        return None;
    }
    let mut y = [0.0f64; N];
    // acc[i] = sum_{j > i-ish, known} h[i][j] y[j], completed when y[i] is known.
    let mut acc = [0.0f64; N];
    y[N - 1] = 1.0;
    for i in (1..N).rev() {
        let yi = y[i];
        for (a, row) in acc.iter_mut().zip(h).take(i + 1) {
            *a += row[i] * yi;
        }
        y[i - 1] = -(acc[i] - lambda * yi) * inv_sub[i];
    }
    let y0 = y[0];
    acc[0] += h[0][0] * y0;
    let r0 = acc[0] - lambda * y0;
    let n = normalise(&mut y)?;
    let res = r0.abs() / n;
    res.is_finite().then_some((y, res))
}

/// Balances `a` in place by a diagonal similarity `D^-1 a D` with powers of 2 (exact;
/// EISPACK `balanc` without permutations, at most 8 sweeps); returns `D`. Action matrices
/// are often badly scaled (rows of monomials of different degrees, solutions of different
/// magnitudes), which costs the eigenvalues and eigenvectors accuracy (LAPACK's `dgeev`
/// balances by default for the same reason).
pub(crate) fn balance<const N: usize>(a: &mut [[f64; N]; N]) -> [f64; N] {
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

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SMatrix;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn to_rows<const N: usize>(m: &SMatrix<f64, N, N>) -> [[f64; N]; N] {
        std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
    }

    /// `S^-1 A S` is the returned Hessenberg form, also when leading columns are already
    /// reduced (unit rows of an action matrix, permuted to the front) and skipped.
    #[test]
    fn similarity_reproduces_the_reduction() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for lead_units in [0usize, 1, 3] {
            let mut m = SMatrix::<f64, 7, 7>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
            for k in 0..lead_units {
                m.column_mut(k).fill(0.0);
                m[(k + 1, k)] = rng.gen_range(0.5..2.0);
            }
            let mut a = to_rows(&m);
            let sim = hessenberg(&mut a);
            for (i, row) in a.iter().enumerate() {
                for &x in &row[..i.saturating_sub(1)] {
                    assert_eq!(x, 0.0);
                }
            }
            // A S = S H, column by column: S e_j through `apply`.
            let h = SMatrix::<f64, 7, 7>::from_fn(|i, j| a[i][j]);
            let s = SMatrix::<f64, 7, 7>::from_fn(|i, j| {
                sim.apply(std::array::from_fn(|q| if q == j { 1.0 } else { 0.0 }))[i]
            });
            assert!((m * s - s * h).norm() < 1e-13, "lead {lead_units}");
        }
    }

    /// Hyman's Newton step converges quadratically to an eigenvalue of `h`, and the
    /// recurrence at the refined value leaves a rounding-level residual.
    #[test]
    fn hyman_newton_refines_an_eigenvalue() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let m = SMatrix::<f64, 8, 8>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
        let mut h = to_rows(&m);
        hessenberg(&mut h);
        let inv_sub = subdiagonal_reciprocals(&h).unwrap();
        let eigs = m.complex_eigenvalues();
        let lam = eigs
            .iter()
            .filter(|z| z.im == 0.0)
            .map(|z| z.re)
            .next()
            .expect("this seed gives a real eigenvalue");
        let mu0 = lam + 1e-6;
        let mu1 = hyman_newton_step(&h, &inv_sub, mu0).unwrap();
        assert!((mu1 - lam).abs() < 1e-10, "{mu1} vs {lam}");
        let mu2 = hyman_newton_step(&h, &inv_sub, mu1).unwrap();
        let (_, res) = eigenvector_by_recurrence(&h, &inv_sub, mu2).unwrap();
        assert!(res < 1e-14, "residual {res}");
    }
}
