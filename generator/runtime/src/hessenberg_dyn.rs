//! The Hessenberg machinery of [`super::hessenberg`] for matrices whose size is known at
//! run time, stored on the heap: the QR eigen back end ([`super::real_eigenpairs_hqr`])
//! runs on it at every size, so an action matrix of any size is solved by the same code
//! (the interpreter's `real_eigenpairs_dyn` and an emitted solver alike) and a large one
//! does not live on the stack. Each function performs the floating-point operations of its
//! fixed-size counterpart in the same order, so both give the same bits.
//!
//! Convention: [`Square`] is row-major (`a[(i, j)]`), scaled by the caller so that its norm
//! is about 1 (the tolerances are absolute).

use std::ops::{Index, IndexMut};

/// Inverse iteration stops after one step once the residual of the pair (matrix of norm
/// about 1) is below this (as in [`super::hessenberg`]).
const RESID_TOL: f64 = 5e-16;

/// Pivot floor of [`HessenbergLu`] (|H| about 1).
const TINY: f64 = f64::EPSILON * 1e-3;

/// A dense `n x n` matrix, row-major on the heap.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Square {
    n: usize,
    data: Vec<f64>,
}

impl Square {
    /// The zero matrix of side `n`.
    pub(crate) fn zeros(n: usize) -> Self {
        Square {
            n,
            data: vec![0.0; n * n],
        }
    }

    /// Side length.
    pub(crate) fn n(&self) -> usize {
        self.n
    }

    /// Row `i`.
    pub(crate) fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.n..(i + 1) * self.n]
    }

    /// Row `i`, mutable.
    pub(crate) fn row_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.data[i * self.n..(i + 1) * self.n]
    }

    /// Swaps rows `p` and `q`.
    fn swap_rows(&mut self, p: usize, q: usize) {
        if p == q {
            return;
        }
        let n = self.n;
        let (lo, hi) = (p.min(q), p.max(q));
        let (head, tail) = self.data.split_at_mut(hi * n);
        head[lo * n..(lo + 1) * n].swap_with_slice(&mut tail[..n]);
    }

    /// The transpose.
    pub(crate) fn transpose(&self) -> Square {
        let n = self.n;
        let mut t = Square::zeros(n);
        for i in 0..n {
            for j in 0..n {
                t.data[i * n + j] = self.data[j * n + i];
            }
        }
        t
    }
}

impl Index<(usize, usize)> for Square {
    type Output = f64;
    #[inline(always)]
    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        &self.data[i * self.n + j]
    }
}

impl IndexMut<(usize, usize)> for Square {
    #[inline(always)]
    fn index_mut(&mut self, (i, j): (usize, usize)) -> &mut f64 {
        &mut self.data[i * self.n + j]
    }
}

/// The similarity of the Hessenberg reduction, `S = P L` (see
/// [`super::hessenberg::Similarity`]): the gather of `P` and the multipliers of `L`, row
/// `k` of `mult` for step `k`.
pub(crate) struct Similarity {
    gather: Vec<usize>,
    mult: Square,
}

impl Similarity {
    /// `S y`: an eigenvector of `H` becomes one of `A`.
    pub(crate) fn apply(&self, mut y: Vec<f64>) -> Vec<f64> {
        let n = y.len();
        for k in (0..n.saturating_sub(2)).rev() {
            let yk1 = y[k + 1];
            let m = self.mult.row(k);
            for i in k + 2..n {
                y[i] += m[i] * yk1;
            }
        }
        self.gather.iter().map(|&g| y[g]).collect()
    }
}

/// Reduces the row-major `a` to upper Hessenberg form in place by stabilised elementary
/// similarities (EISPACK `elmhes`, worked on the transpose as
/// [`super::hessenberg::hessenberg`] does); returns the similarity for the eigenvectors.
pub(crate) fn hessenberg(a: &mut Square) -> Similarity {
    let mut cols = a.transpose();
    let s = hessenberg_of_columns(&mut cols);
    *a = cols.transpose();
    s
}

/// [`hessenberg`] on a matrix stored by columns (row `j` of `cols` is column `j`).
fn hessenberg_of_columns(a: &mut Square) -> Similarity {
    let n = a.n();
    let mut s = Similarity {
        gather: (0..n).collect(),
        mult: Square::zeros(n),
    };
    let mut perm: Vec<usize> = (0..n).map(|i| (i + 1).min(n.saturating_sub(1))).collect();
    let mut m = vec![0.0f64; n];
    for k in 0..n.saturating_sub(2) {
        let (mut p, mut below) = (k + 1, 0.0f64);
        for i in k + 2..n {
            let x = a[(k, i)].abs();
            if x > below {
                below = x;
                p = i;
            }
        }
        if below == 0.0 {
            continue;
        }
        if a[(k, k + 1)].abs() >= below {
            p = k + 1;
        }
        perm[k] = p;
        if p != k + 1 {
            for kk in 0..k {
                s.mult.row_mut(kk).swap(p, k + 1);
            }
            a.swap_rows(p, k + 1);
            for j in 0..n {
                a.row_mut(j).swap(p, k + 1);
            }
        }
        let inv = 1.0 / a[(k, k + 1)];
        m.iter_mut().for_each(|x| *x = 0.0);
        for i in k + 2..n {
            m[i] = a[(k, i)] * inv;
            a[(k, i)] = 0.0;
        }
        s.mult.row_mut(k).copy_from_slice(&m);
        for j in k + 1..n {
            let pj = a[(j, k + 1)];
            let col = a.row_mut(j);
            for i in k + 2..n {
                col[i] -= m[i] * pj;
            }
        }
        let (head, tail) = a.data.split_at_mut((k + 2) * n);
        let target = &mut head[(k + 1) * n..(k + 2) * n];
        for (col, &mi) in tail.chunks_exact(n).zip(&m[k + 2..]) {
            for r in 0..n {
                target[r] += mi * col[r];
            }
        }
    }
    for k in (0..n.saturating_sub(2)).rev() {
        s.gather.swap(k + 1, perm[k]);
    }
    s
}

/// An approximate eigenpair from [`inverse_iteration`].
pub(crate) struct Eigenpair {
    /// The eigenvector, unit 2-norm.
    pub vector: Vec<f64>,
}

/// LU factors with partial pivoting of `H - mu I` for an upper Hessenberg `H` (see
/// [`super::hessenberg`]'s `HessenbergLu`).
struct HessenbergLu {
    u: Square,
    swap: Vec<bool>,
    l: Vec<f64>,
    rdiag: Vec<f64>,
}

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

impl HessenbergLu {
    /// Factors `h - mu I`.
    fn factor(h: &Square, mu: f64) -> Self {
        let n = h.n();
        let mut lu = HessenbergLu {
            u: Square::zeros(n),
            swap: vec![false; n],
            l: vec![0.0; n],
            rdiag: vec![0.0; n],
        };
        if n == 0 {
            return lu;
        }
        let mut cur = h.row(0).to_vec();
        cur[0] -= mu;
        let mut next = vec![0.0; n];
        for k in 0..n - 1 {
            next.copy_from_slice(h.row(k + 1));
            next[k + 1] -= mu;
            let s = next[k].abs() > cur[k].abs();
            if s {
                std::mem::swap(&mut cur, &mut next);
            }
            // `cur` is the pivot row, `next` the other.
            lu.swap[k] = s;
            cur[k] = guard(cur[k]);
            let f = next[k] / cur[k];
            lu.l[k] = f;
            next[k] = 0.0;
            for j in k + 1..n {
                next[j] -= f * cur[j];
            }
            lu.u.row_mut(k).copy_from_slice(&cur);
            std::mem::swap(&mut cur, &mut next);
        }
        cur[n - 1] = guard(cur[n - 1]);
        lu.u.row_mut(n - 1).copy_from_slice(&cur);
        for (i, r) in lu.rdiag.iter_mut().enumerate() {
            *r = 1.0 / lu.u[(i, i)];
        }
        lu
    }

    /// `y := U^-1 y`, column-oriented.
    fn back(&self, y: &mut [f64]) {
        for i in (0..y.len()).rev() {
            let yi = y[i] * self.rdiag[i];
            y[i] = yi;
            for (j, yj) in y.iter_mut().enumerate().take(i) {
                *yj -= self.u[(j, i)] * yi;
            }
        }
    }

    /// `y := (P L)^-1 y`.
    fn forward(&self, y: &mut [f64]) {
        for k in 0..y.len() - 1 {
            if self.swap[k] {
                y.swap(k, k + 1);
            }
            y[k + 1] -= self.l[k] * y[k];
        }
    }

    /// `(H - mu I) U^-1 e` (O(n)).
    fn residual_of_first_step(&self) -> Vec<f64> {
        let n = self.l.len();
        let mut r0 = vec![1.0f64; n];
        for k in (0..n - 1).rev() {
            r0[k + 1] += self.l[k] * r0[k];
            if self.swap[k] {
                r0.swap(k, k + 1);
            }
        }
        r0
    }
}

/// Scales `y` to unit norm; its former norm, or `None` if zero or not finite.
pub(crate) fn normalise(y: &mut [f64]) -> Option<f64> {
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

/// Inverse iteration for the eigenvalue near `mu` of the upper Hessenberg `h` (see
/// [`super::hessenberg`]'s `inverse_iteration`), or `None` (non-finite iterates or an
/// empty matrix).
pub(crate) fn inverse_iteration(h: &Square, mu: f64) -> Option<Eigenpair> {
    if h.n() == 0 {
        return None;
    }
    let lu = HessenbergLu::factor(h, mu);
    let mut y = vec![1.0f64; h.n()];
    lu.back(&mut y);
    refine(&lu, mu, y)
}

/// The rest of [`inverse_iteration`] after the first solve `y = U^-1 e`.
fn refine(lu: &HessenbergLu, mu: f64, mut y: Vec<f64>) -> Option<Eigenpair> {
    let n = normalise(&mut y)?;
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
        return Some(Eigenpair { vector: y });
    }
    for _ in 0..2 {
        let y0 = y.clone();
        lu.forward(&mut y);
        lu.back(&mut y);
        let d: f64 = y.iter().zip(&y0).map(|(a, b)| a * b).sum();
        let n = normalise(&mut y)?;
        if d != 0.0 && d.is_finite() {
            let g = n / d;
            let r2: f64 = y0
                .iter()
                .zip(&y)
                .map(|(a, b)| (a - g * b) * (a - g * b))
                .sum();
            if r2.sqrt() / n <= RESID_TOL {
                break;
            }
        }
    }
    Some(Eigenpair { vector: y })
}

/// Balances `a` in place by a diagonal similarity `D^-1 a D` with powers of 2 (see
/// [`super::hessenberg`]'s `balance`); returns `D`.
pub(crate) fn balance(a: &mut Square) -> Vec<f64> {
    let n = a.n();
    let mut d = vec![1.0f64; n];
    for _ in 0..8 {
        let mut done = true;
        for i in 0..n {
            let mut c = 0.0;
            let mut r = 0.0;
            for j in 0..n {
                if j != i {
                    c += a[(j, i)].abs();
                    r += a[(i, j)].abs();
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
                for x in a.row_mut(i).iter_mut() {
                    *x *= g;
                }
                for j in 0..n {
                    a[(j, i)] *= f;
                }
            }
        }
        if done {
            break;
        }
    }
    d
}
