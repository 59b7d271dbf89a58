//! Dense linear algebra mod P on raw residues (`u32 < P`): Gauss-Jordan, incremental
//! echelon bases, left kernels, characteristic polynomials, polynomial gcd.

use crate::budget::{Deadline, Exhausted};

#[inline]
pub(crate) fn mulmod<const P: u32>(a: u32, b: u32) -> u32 {
    ((a as u64 * b as u64) % P as u64) as u32
}
#[inline]
pub(crate) fn addmod<const P: u32>(a: u32, b: u32) -> u32 {
    let s = a + b;
    if s >= P {
        s - P
    } else {
        s
    }
}
#[inline]
pub(crate) fn submod<const P: u32>(a: u32, b: u32) -> u32 {
    if a >= b {
        a - b
    } else {
        a + P - b
    }
}
pub(crate) fn invmod<const P: u32>(a: u32) -> u32 {
    debug_assert!(a != 0);
    let (mut r0, mut r1) = (P as i64, a as i64);
    let (mut s0, mut s1) = (0i64, 1i64);
    while r1 != 0 {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (s0, s1) = (s1, s0 - q * s1);
    }
    s0.rem_euclid(P as i64) as u32
}

/// `dst -= c * src` on the indices `nz` (the non-zeros of `src`).
#[inline]
fn axpy<const P: u32>(dst: &mut [u32], c: u32, src: &[u32], nz: &[usize]) {
    let nc = P - c; // -c
    for &k in nz {
        dst[k] = ((dst[k] as u64 + nc as u64 * src[k] as u64) % P as u64) as u32;
    }
}

/// In-place Gauss-Jordan elimination (columns in index order, rows swapped as needed).
/// With `full`, entries above pivots are eliminated too (reduced row echelon form).
/// Pivots are searched in the first `ncols` columns only; row operations act on whole
/// rows. Returns the pivot column of each of the first `rank` rows.
pub(crate) fn gauss_jordan<const P: u32>(
    m: &mut [Vec<u32>],
    ncols: usize,
    full: bool,
) -> Vec<usize> {
    gauss_jordan_within::<P>(m, ncols, full, None).expect("no budget, never exhausted")
}

/// [`gauss_jordan`] that stops (leaving `m` partly reduced) once the budget runs out.
pub(crate) fn gauss_jordan_within<const P: u32>(
    m: &mut [Vec<u32>],
    ncols: usize,
    full: bool,
    deadline: Option<&Deadline>,
) -> Result<Vec<usize>, Exhausted> {
    let nrows = m.len();
    let width = m.first().map_or(0, |r| r.len());
    let mut pivots = Vec::new();
    let mut r = 0;
    let mut nz: Vec<usize> = Vec::new();
    for c in 0..ncols {
        if r == nrows {
            break;
        }
        let Some(i) = (r..nrows).find(|&i| m[i][c] != 0) else {
            continue;
        };
        if r % 64 == 63 {
            if let Some(d) = deadline {
                d.check_time()?;
            }
        }
        m.swap(r, i);
        let inv = invmod::<P>(m[r][c]);
        nz.clear();
        for (k, x) in m[r].iter_mut().enumerate().take(width).skip(c) {
            if *x != 0 {
                *x = mulmod::<P>(*x, inv);
                nz.push(k);
            }
        }
        let (before, rest) = m.split_at_mut(r);
        let (prow, after) = rest.split_first_mut().expect("row r exists");
        for row in after.iter_mut() {
            let f = row[c];
            if f != 0 {
                axpy::<P>(row, f, prow, &nz);
            }
        }
        if full {
            for row in before.iter_mut() {
                let f = row[c];
                if f != 0 {
                    axpy::<P>(row, f, prow, &nz);
                }
            }
        }
        pivots.push(c);
        r += 1;
    }
    Ok(pivots)
}

/// The inverse of the square matrix `m` mod P (Gauss-Jordan on `[m | I]`), `None` when
/// `m` is singular.
pub(crate) fn inverse<const P: u32>(m: &[Vec<u32>]) -> Option<Vec<Vec<u32>>> {
    let n = m.len();
    let mut aug: Vec<Vec<u32>> = m
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut r = row.clone();
            r.extend((0..n).map(|j| u32::from(i == j)));
            r
        })
        .collect();
    let piv = gauss_jordan::<P>(&mut aug, n, true);
    if piv.len() < n {
        return None;
    }
    Some(aug.into_iter().map(|r| r[n..].to_vec()).collect())
}

/// An incrementally built echelon basis of a row space (for choosing independent rows).
pub(crate) struct EchelonBasis<const P: u32> {
    ncols: usize,
    /// Row with pivot at column c (monic, zero before c), if any.
    by_pivot: Vec<Option<Vec<u32>>>,
    nzs: Vec<Vec<usize>>,
}

impl<const P: u32> EchelonBasis<P> {
    pub(crate) fn new(ncols: usize) -> Self {
        EchelonBasis {
            ncols,
            by_pivot: vec![None; ncols],
            nzs: vec![Vec::new(); ncols],
        }
    }
    /// Inserts `v` if it is independent of the basis; returns whether it was.
    pub(crate) fn insert(&mut self, mut v: Vec<u32>) -> bool {
        for c in 0..self.ncols {
            if v[c] == 0 {
                continue;
            }
            match &self.by_pivot[c] {
                Some(row) => {
                    let f = v[c];
                    axpy::<P>(&mut v, f, row, &self.nzs[c]);
                }
                None => {
                    let inv = invmod::<P>(v[c]);
                    let mut nz = Vec::new();
                    for (k, x) in v.iter_mut().enumerate().skip(c) {
                        if *x != 0 {
                            *x = mulmod::<P>(*x, inv);
                            nz.push(k);
                        }
                    }
                    self.by_pivot[c] = Some(v);
                    self.nzs[c] = nz;
                    return true;
                }
            }
        }
        false
    }
    /// The pivot columns of the rows inserted so far, increasing.
    pub(crate) fn pivot_columns(&self) -> Vec<usize> {
        (0..self.ncols)
            .filter(|&c| self.by_pivot[c].is_some())
            .collect()
    }
}

/// The support (row indices) of the left kernel of `m` (rows x `ncols`): the rows that
/// take part in some linear dependency among the rows; `None` once `deadline` runs out.
pub(crate) fn left_kernel_support<const P: u32>(
    m: &[Vec<u32>],
    ncols: usize,
    deadline: Option<&Deadline>,
) -> Option<Vec<bool>> {
    let nrows = m.len();
    let mut aug: Vec<Vec<u32>> = m
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut v = Vec::with_capacity(ncols + nrows);
            v.extend_from_slice(&row[..ncols]);
            v.resize(ncols + nrows, 0);
            v[ncols + i] = 1;
            v
        })
        .collect();
    let piv = gauss_jordan_within::<P>(&mut aug, ncols, false, deadline).ok()?;
    let rank = piv.len();
    let mut supp = vec![false; nrows];
    for row in &aug[rank..] {
        for (i, s) in supp.iter_mut().enumerate() {
            if row[ncols + i] != 0 {
                *s = true;
            }
        }
    }
    Some(supp)
}

/// Characteristic polynomial det(t I - M) of a square matrix, coefficients from the constant
/// term up (monic, length n + 1), via reduction to upper Hessenberg form.
#[cfg(test)]
pub(crate) fn charpoly<const P: u32>(m: &[Vec<u32>]) -> Vec<u32> {
    // Without a deadline nothing can run out.
    charpoly_within::<P>(m, None).unwrap_or_default()
}

/// [`charpoly`] checking `deadline` between columns: its cost is cubic in the size, which
/// for a basis of thousands of monomials is seconds, so the clock is read well inside it.
pub(crate) fn charpoly_within<const P: u32>(
    m: &[Vec<u32>],
    deadline: Option<&Deadline>,
) -> Result<Vec<u32>, Exhausted> {
    let check = |k: usize| match deadline {
        Some(d) if k % 16 == 0 => d.check_time(),
        _ => Ok(()),
    };
    let n = m.len();
    let mut h: Vec<Vec<u32>> = m.to_vec();
    // Similarity reduction to Hessenberg form.
    for j in 0..n.saturating_sub(2) {
        check(j)?;
        let Some(i) = (j + 1..n).find(|&i| h[i][j] != 0) else {
            continue;
        };
        if i != j + 1 {
            h.swap(i, j + 1);
            for row in h.iter_mut() {
                row.swap(i, j + 1);
            }
        }
        let inv = invmod::<P>(h[j + 1][j]);
        for i in j + 2..n {
            let u = mulmod::<P>(h[i][j], inv);
            if u == 0 {
                continue;
            }
            // Row i -= u * row j+1; column j+1 += u * column i.
            let pivot_row = h[j + 1].clone();
            for (x, &y) in h[i].iter_mut().zip(&pivot_row) {
                *x = submod::<P>(*x, mulmod::<P>(u, y));
            }
            for row in h.iter_mut() {
                let v = mulmod::<P>(u, row[i]);
                row[j + 1] = addmod::<P>(row[j + 1], v);
            }
        }
    }
    // Recurrence on leading principal submatrices: p_k = (t - h_kk) p_{k-1}
    //   - sum_{i<k} h_ik * prod_{l=i+1..k} h_{l,l-1} * p_{i-1}.
    let mut polys: Vec<Vec<u32>> = vec![vec![1]];
    for k in 0..n {
        check(k)?;
        let prev = &polys[k];
        let mut p = vec![0u32; k + 2];
        for (d, &c) in prev.iter().enumerate() {
            p[d + 1] = addmod::<P>(p[d + 1], c);
            p[d] = submod::<P>(p[d], mulmod::<P>(h[k][k], c));
        }
        let mut prod = 1u32;
        for i in (0..k).rev() {
            prod = mulmod::<P>(prod, h[i + 1][i]);
            if prod == 0 {
                break;
            }
            let f = mulmod::<P>(h[i][k], prod);
            if f == 0 {
                continue;
            }
            for (d, &c) in polys[i].iter().enumerate() {
                p[d] = submod::<P>(p[d], mulmod::<P>(f, c));
            }
        }
        polys.push(p);
    }
    Ok(polys.pop().unwrap_or_default())
}

fn trim(p: &mut Vec<u32>) {
    while p.last() == Some(&0) {
        p.pop();
    }
}

/// Monic gcd of two univariate polynomials (coefficients from the constant term up).
pub(crate) fn poly_gcd<const P: u32>(a: &[u32], b: &[u32]) -> Vec<u32> {
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    trim(&mut a);
    trim(&mut b);
    while !b.is_empty() {
        // a mod b
        let inv = invmod::<P>(*b.last().expect("non-empty"));
        while a.len() >= b.len() {
            let f = mulmod::<P>(*a.last().expect("non-empty"), inv);
            let s = a.len() - b.len();
            for (k, &c) in b.iter().enumerate() {
                a[s + k] = submod::<P>(a[s + k], mulmod::<P>(f, c));
            }
            trim(&mut a);
        }
        std::mem::swap(&mut a, &mut b);
    }
    if let Some(&l) = a.last() {
        let inv = invmod::<P>(l);
        for c in a.iter_mut() {
            *c = mulmod::<P>(*c, inv);
        }
    }
    a
}

/// The derivative of a univariate polynomial (coefficients from the constant term up).
pub(crate) fn derivative<const P: u32>(p: &[u32]) -> Vec<u32> {
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(k, &c)| mulmod::<P>(c, (k as u64 % P as u64) as u32))
        .collect()
}

/// Whether a univariate polynomial has no repeated root (gcd with its derivative is 1).
pub(crate) fn is_squarefree<const P: u32>(p: &[u32]) -> bool {
    poly_gcd::<P>(p, &derivative::<P>(p)).len() == 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::P1;

    #[test]
    fn charpoly_of_companion_and_similarity() {
        // Companion matrix of t^3 - 6t^2 + 11t - 6 = (t-1)(t-2)(t-3).
        let p = P1;
        let neg = |x: u32| (p - x) % p;
        let m = vec![vec![0, 1, 0], vec![0, 0, 1], vec![6, neg(11), 6]];
        assert_eq!(charpoly::<P1>(&m), vec![neg(6), 11, neg(6), 1]);
        assert!(is_squarefree::<P1>(&charpoly::<P1>(&m)));
        // Diagonal with repeated eigenvalue.
        let d = vec![vec![2, 0, 0], vec![0, 2, 0], vec![0, 0, 5]];
        assert!(!is_squarefree::<P1>(&charpoly::<P1>(&d)));
        // A dense matrix: trace and determinant checks.
        let a = vec![vec![1, 2, 3], vec![4, 5, 6], vec![7, 8, 10]];
        let cp = charpoly::<P1>(&a);
        assert_eq!(cp[2], neg(16)); // -trace
        assert_eq!(cp[0], 3); // -det = -(-3)
    }

    #[test]
    fn kernel_support_and_echelon() {
        let m = vec![vec![1, 0], vec![0, 1], vec![1, 1], vec![0, 0]];
        let s = left_kernel_support::<P1>(&m, 2, None).unwrap();
        assert_eq!(s, vec![true, true, true, true]);
        let m = vec![vec![1, 0], vec![0, 1], vec![2, 0]];
        assert_eq!(
            left_kernel_support::<P1>(&m, 2, None).unwrap(),
            vec![true, false, true]
        );
        let mut e = EchelonBasis::<P1>::new(2);
        assert!(e.insert(vec![1, 1]));
        assert!(!e.insert(vec![2, 2]));
        assert!(e.insert(vec![0, 3]));
    }
}
