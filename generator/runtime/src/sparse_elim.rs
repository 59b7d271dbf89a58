//! Sparse elimination of a template with partial pivoting over a precomputed structure.
//!
//! A template row is a monomial multiple of one equation, so a large template is mostly
//! zeros, at positions that do not depend on the data. The generator orders the columns of
//! each block (excess, then reducible) and the rows so that little fill arises, and bounds
//! the structure of every step over all pivot choices: at step `k` the candidate rows (row
//! `k` and the rows below it that may be non-zero in column `k`) all take, after the step,
//! the union of their patterns, whichever of them is the pivot (George and Ng's static
//! structure for partial pivoting). [`SparseLuPlan`] records it. Rows outside the candidates
//! are exactly zero in column `k`, so choosing the largest candidate is the dense LU's
//! partial pivoting: the same pivots and the same arithmetic on the non-zeros, in far fewer
//! operations.
//!
//! The result has [`crate::lu_solve_template`]'s layout: rows `first_row..pivot_cols` read
//! `col_k + sum_j m[k][pivot_cols + j] * rhs_j`, zero on the other pivot columns.

use crate::elim::column_tolerances;

/// The structure of a template's elimination (see the module documentation). Step `k`
/// eliminates column `k`, its pivot ending in row `k`, for `k < pivot_cols`.
#[derive(Clone, Copy, Debug)]
pub struct SparseLuPlan<'a> {
    /// Template rows.
    pub rows: usize,
    /// Template columns: `pivot_cols` eliminated ones, then the right-hand side.
    pub cols: usize,
    /// Columns eliminated (and rows that receive a pivot).
    pub pivot_cols: usize,
    /// The first row that is back-substituted (rows before it keep their upper triangular
    /// form; for a template ordered `excess | reducible | basis`, the number of excess
    /// columns eliminated).
    pub first_row: usize,
    /// `pattern[pattern_start[k]..pattern_start[k + 1]]`: the pivot columns `c > k` where
    /// a candidate row of step `k` may be non-zero, ascending. The right-hand side columns
    /// are treated as dense.
    pub pattern_start: &'a [u32],
    /// See `pattern_start`.
    pub pattern: &'a [u16],
    /// `targets[target_start[k]..target_start[k + 1]]`: the rows `i > k` that may be
    /// non-zero in column `k` at step `k` (the candidates besides row `k`), ascending.
    pub target_start: &'a [u32],
    /// See `target_start`.
    pub targets: &'a [u16],
}

impl SparseLuPlan<'_> {
    /// Whether the plan's lengths agree with its shape and with a matrix of `len`
    /// entries (every index is also checked where it is used).
    pub fn fits(&self, len: usize) -> bool {
        let Some(n) = self.rows.checked_mul(self.cols) else {
            return false;
        };
        n <= len
            && self.pivot_cols <= self.rows
            && self.pivot_cols <= self.cols
            && self.first_row <= self.pivot_cols
            && self.pattern_start.len() == self.pivot_cols + 1
            && self.target_start.len() == self.pivot_cols + 1
            && self.pattern_start.last().map(|&e| e as usize) == Some(self.pattern.len())
            && self.target_start.last().map(|&e| e as usize) == Some(self.targets.len())
    }
}

/// Reduces the row-major template `m` along the plan (see the module documentation), with
/// the contract of [`crate::lu_solve_template`]: `false` (leaving garbage) if some column
/// gets no pivot larger than its tolerance ([`crate::PIVOT_TOL`], relative to the
/// column's largest input entry), if an entry is not finite, or if the plan does not fit
/// `m` or indexes outside it. Never panics; allocates the tolerances
/// ([`lu_solve_template_sparse_fixed`] keeps them on the stack).
pub fn lu_solve_template_sparse(m: &mut [f64], plan: &SparseLuPlan) -> bool {
    if !plan.fits(m.len()) {
        return false;
    }
    let mut tol = vec![0.0; plan.pivot_cols];
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { sparse_core_avx2(m, plan, plan.cols, &mut tol) };
    }
    sparse_core(m, plan, plan.cols, &mut tol)
}

/// [`lu_solve_template_sparse`] with the template width and the number of pivot columns
/// as constants (the emitted solvers' form: the right-hand-side updates then have a length
/// known to the compiler). Returns `false` also if the plan disagrees with them.
#[inline]
pub fn lu_solve_template_sparse_fixed<const COLS: usize, const PIVOTS: usize>(
    m: &mut [f64],
    plan: &SparseLuPlan,
) -> bool {
    if plan.cols != COLS || plan.pivot_cols != PIVOTS || !plan.fits(m.len()) {
        return false;
    }
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { sparse_fixed_avx2::<COLS, PIVOTS>(m, plan) };
    }
    let mut tol = [0.0; PIVOTS];
    sparse_core(m, plan, COLS, &mut tol)
}

/// [`sparse_core`] compiled with AVX2 enabled: wider row operations. Without FMA every
/// entry sees the same multiplications and subtractions, so the results are bit-identical
/// to the baseline build's.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn sparse_core_avx2(
    m: &mut [f64],
    plan: &SparseLuPlan,
    cols: usize,
    tol: &mut [f64],
) -> bool {
    sparse_core(m, plan, cols, tol)
}

/// [`lu_solve_template_sparse_fixed`]'s AVX2 build (see [`sparse_core_avx2`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn sparse_fixed_avx2<const COLS: usize, const PIVOTS: usize>(
    m: &mut [f64],
    plan: &SparseLuPlan,
) -> bool {
    let mut tol = [0.0; PIVOTS];
    sparse_core(m, plan, COLS, &mut tol)
}

/// `dst[j] -= f * src[j]` over equal-length slices.
#[inline(always)]
fn axpy_neg(dst: &mut [f64], f: f64, src: &[f64]) {
    for (a, &b) in dst.iter_mut().zip(src) {
        *a -= f * b;
    }
}

/// Whether every index of step `k` is in range: pattern columns in `k < c < pivots`,
/// targets in `k < i < rows`.
#[inline(always)]
fn step_in_range(pattern: &[u16], targets: &[u16], k: usize, pivots: usize, rows: usize) -> bool {
    pattern
        .iter()
        .all(|&c| (c as usize) > k && (c as usize) < pivots)
        && targets
            .iter()
            .all(|&i| (i as usize) > k && (i as usize) < rows)
}

/// `tol`: work space of one entry per pivot column (the per-column tolerances).
#[inline(always)]
fn sparse_core(m: &mut [f64], plan: &SparseLuPlan, cols: usize, tol: &mut [f64]) -> bool {
    let (rows, pivots) = (plan.rows, tol.len());
    let m = &mut m[..rows * cols];
    if !column_tolerances(m, cols, tol) {
        return false;
    }
    let span = |start: &[u32], k: usize| start[k] as usize..start[k + 1] as usize;
    for k in 0..pivots {
        let (Some(pattern), Some(targets)) = (
            plan.pattern.get(span(plan.pattern_start, k)),
            plan.targets.get(span(plan.target_start, k)),
        ) else {
            return false;
        };
        if !step_in_range(pattern, targets, k, pivots, rows) {
            return false;
        }
        // Partial pivoting among the candidates (every other row is zero in column k).
        let (upper, lower) = m.split_at_mut((k + 1) * cols);
        let prow = &mut upper[k * cols..];
        let (mut p, mut best) = (k, prow[k].abs());
        for &i in targets {
            let a = lower[(i as usize - k - 1) * cols + k].abs();
            if a > best {
                best = a;
                p = i as usize;
            }
        }
        if !(best > tol[k] && best <= f64::MAX) {
            return false;
        }
        // Where the pattern fills at least half of the remaining pivot columns, contiguous
        // (vectorised) row operations over all of them beat indexed ones; the entries
        // outside the pattern are zero in every candidate row, so both give the same numbers.
        let contiguous = 2 * pattern.len() >= pivots - k - 1;
        if p != k {
            let other = &mut lower[(p - k - 1) * cols..(p - k) * cols];
            if contiguous {
                prow[k..].swap_with_slice(&mut other[k..]);
            } else {
                std::mem::swap(&mut prow[k], &mut other[k]);
                for &c in pattern {
                    std::mem::swap(&mut prow[c as usize], &mut other[c as usize]);
                }
                prow[pivots..].swap_with_slice(&mut other[pivots..]);
            }
        }
        let inv = 1.0 / prow[k];
        prow[k] = 1.0;
        if contiguous {
            prow[k + 1..].iter_mut().for_each(|x| *x *= inv);
        } else {
            for &c in pattern {
                prow[c as usize] *= inv;
            }
            prow[pivots..].iter_mut().for_each(|x| *x *= inv);
        }
        let prow = &*prow;
        for &i in targets {
            let at = (i as usize - k - 1) * cols;
            let row = &mut lower[at..at + cols];
            let f = row[k];
            if f == 0.0 {
                continue;
            }
            row[k] = 0.0;
            if contiguous {
                axpy_neg(&mut row[k + 1..], f, &prow[k + 1..]);
            } else {
                for &c in pattern {
                    let c = c as usize;
                    row[c] -= f * prow[c];
                }
                axpy_neg(&mut row[pivots..], f, &prow[pivots..]);
            }
        }
    }
    // Back substitution, bottom-up, of the requested rows: row k's later pivot columns are
    // cleared with rows that are already fully reduced.
    for k in (plan.first_row..pivots).rev() {
        let (upper, lower) = m.split_at_mut((k + 1) * cols);
        let rowk = &mut upper[k * cols..];
        for &l in &plan.pattern[span(plan.pattern_start, k)] {
            let l = l as usize;
            let f = rowk[l];
            if f == 0.0 {
                continue;
            }
            rowk[l] = 0.0;
            let at = (l - k - 1) * cols;
            axpy_neg(&mut rowk[pivots..], f, &lower[at + pivots..at + cols]);
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lu_solve_template;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    type OwnedPlan = (Vec<u32>, Vec<u16>, Vec<u32>, Vec<u16>);

    /// The plan of `pattern` (row-major booleans) in its natural order, by the generator's
    /// rule: after step k every candidate row holds the union of the candidates' patterns.
    fn plan_of(pattern: &[bool], rows: usize, cols: usize, pivots: usize) -> OwnedPlan {
        let mut nz: Vec<Vec<bool>> = (0..rows)
            .map(|r| pattern[r * cols..(r + 1) * cols].to_vec())
            .collect();
        let (mut ps, mut p, mut ts, mut t) = (vec![0u32], vec![], vec![0u32], vec![]);
        for k in 0..pivots {
            let tg: Vec<usize> = (k + 1..rows).filter(|&i| nz[i][k]).collect();
            let mut union = nz[k].clone();
            for &i in &tg {
                for c in 0..cols {
                    union[c] |= nz[i][c];
                }
            }
            for &i in &tg {
                nz[i] = union.clone();
                nz[i][k] = false;
            }
            nz[k] = union.clone();
            p.extend((k + 1..pivots).filter(|&c| union[c]).map(|c| c as u16));
            t.extend(tg.iter().map(|&i| i as u16));
            ps.push(p.len() as u32);
            ts.push(t.len() as u32);
        }
        (ps, p, ts, t)
    }

    /// A random sparse template (a band, a few scattered entries, a dense right-hand side)
    /// with `extra` rows beyond the pivot columns, and its pattern.
    fn sparse(rng: &mut ChaCha8Rng, n: usize, extra: usize, rhs: usize) -> (Vec<f64>, Vec<bool>) {
        let (rows, cols) = (n + extra, n + rhs);
        let mut m = vec![0.0; rows * cols];
        let mut pat = vec![false; rows * cols];
        for r in 0..rows {
            for c in 0..cols {
                let near = c + 2 >= r && c <= r + 3;
                if near || c >= n || rng.gen::<f64>() < 0.05 {
                    pat[r * cols + c] = true;
                    m[r * cols + c] = rng.gen_range(-1.0..1.0);
                }
            }
        }
        (m, pat)
    }

    fn plan<'a>(
        o: &'a OwnedPlan,
        rows: usize,
        cols: usize,
        n: usize,
        first: usize,
    ) -> SparseLuPlan<'a> {
        SparseLuPlan {
            rows,
            cols,
            pivot_cols: n,
            first_row: first,
            pattern_start: &o.0,
            pattern: &o.1,
            target_start: &o.2,
            targets: &o.3,
        }
    }

    #[test]
    fn equals_the_dense_lu_with_partial_pivoting() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for &(n, extra, rhs, first) in &[
            (12, 0, 5, 7),
            (30, 4, 10, 20),
            (40, 0, 6, 0),
            (25, 3, 8, 25),
        ] {
            let (rows, cols) = (n + extra, n + rhs);
            for _ in 0..10 {
                let (orig, pat) = sparse(&mut rng, n, extra, rhs);
                let owned = plan_of(&pat, rows, cols, n);
                let mut s = orig.clone();
                let mut d = orig.clone();
                let dense_ok = lu_solve_template(&mut d, rows, cols, n, first);
                assert_eq!(
                    lu_solve_template_sparse(&mut s, &plan(&owned, rows, cols, n, first)),
                    dense_ok
                );
                if !dense_ok {
                    continue;
                }
                // Same pivots, same operations on the non-zeros: the same numbers.
                for r in first..n {
                    for c in 0..cols {
                        let (a, b) = (s[r * cols + c], d[r * cols + c]);
                        assert!(
                            a == b || (a - b).abs() < 1e-12,
                            "row {r} col {c}: {a} vs {b}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn singular_bad_input_and_bad_plans_give_false() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let (n, rhs) = (12, 4);
        let cols = n + rhs;
        let (orig, pat) = sparse(&mut rng, n, 0, rhs);
        let owned = plan_of(&pat, n, cols, n);
        let p = plan(&owned, n, cols, n, 3);
        assert!(lu_solve_template_sparse_fixed::<16, 12>(
            &mut orig.clone(),
            &p
        ));
        let mut m = orig.clone();
        m[5] = f64::NAN;
        assert!(!lu_solve_template_sparse(&mut m, &p));
        let mut m = orig.clone();
        m[..cols].fill(0.0);
        assert!(!lu_solve_template_sparse(&mut m, &p));
        let bad = SparseLuPlan {
            pattern_start: &owned.0[1..],
            ..p
        };
        assert!(!lu_solve_template_sparse(&mut orig.clone(), &bad));
        assert!(!lu_solve_template_sparse_fixed::<17, 12>(
            &mut orig.clone(),
            &p
        ));
        assert!(!lu_solve_template_sparse(&mut orig[..10].to_vec(), &p));
        let wild_pattern = [u16::MAX; 1];
        let starts = [0u32, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1];
        let wild = SparseLuPlan {
            pattern: &wild_pattern,
            pattern_start: &starts,
            ..p
        };
        assert!(!lu_solve_template_sparse(&mut orig.clone(), &wild));
        let backwards = [0u16; 1];
        let wild = SparseLuPlan {
            targets: &backwards,
            target_start: &starts,
            ..p
        };
        assert!(!lu_solve_template_sparse(&mut orig.clone(), &wild));
    }
}
