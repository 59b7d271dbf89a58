//! Elimination of row-major template matrices.
//!
//! Both routines work in place on a row-major `rows x cols` slice whose first `pivot_cols`
//! columns are to be eliminated (the template's `excess | reducible` blocks) and whose
//! remaining `cols - pivot_cols` columns are the right-hand side (the basis block).
//!
//! `lu_solve_template` does less work than `gauss_jordan` because it back-substitutes only
//! the rows the action matrix needs; emitted solvers use its fixed-size form
//! (`benches/runtime.rs` compares them).

/// Relative pivot tolerance. [`gauss_jordan`]: a pivot whose magnitude is at most
/// `PIVOT_TOL * max|m_ij|` (over the whole input) makes the elimination fail. The template
/// eliminations ([`lu_solve_template`], [`crate::lu_solve_template_sparse`]) compare the
/// pivot of column `j` with `PIVOT_TOL * max_i |m_ij|`, that column's own largest input
/// entry: a template's columns are monomials whose values, and so whose coefficients,
/// can differ by orders of magnitude (a small unknown's powers, small data), and a column
/// of small entries is not singular for that.
pub const PIVOT_TOL: f64 = 1e-14;

/// `tol[j] = PIVOT_TOL * max_i |m[i][j]|` for the first `tol.len()` columns of the
/// row-major `rows x cols` matrix `m`; `false` if an entry is not finite (or their sum
/// overflows). Branch-free, so that it vectorises (inlined into the AVX2 eliminations).
#[inline(always)]
pub(crate) fn column_tolerances(m: &[f64], cols: usize, tol: &mut [f64]) -> bool {
    tol.iter_mut().for_each(|t| *t = 0.0);
    for row in m.chunks_exact(cols) {
        for (t, &x) in tol.iter_mut().zip(row) {
            let a = x.abs();
            *t = if a > *t { a } else { *t };
        }
    }
    tol.iter_mut().for_each(|t| *t *= PIVOT_TOL);
    // The finiteness check sums in four lanes (`scale_of`): one running sum would be a
    // chain of dependent additions.
    scale_of(m).is_some()
}

/// Largest magnitude of the entries, or `None` if one is not finite. Branch-free over
/// four lanes so that it vectorises (non-finite entries make the lane sums non-finite; a
/// finite matrix whose entries sum beyond `f64::MAX` is rejected as well).
#[inline(always)]
pub(crate) fn scale_of(m: &[f64]) -> Option<f64> {
    let mut mx = [0.0f64; 4];
    let mut sum = [0.0f64; 4];
    let chunks = m.chunks_exact(4);
    let rest = chunks.remainder();
    for c in chunks {
        for k in 0..4 {
            let a = c[k].abs();
            mx[k] = if a > mx[k] { a } else { mx[k] };
            sum[k] += a;
        }
    }
    for (k, &x) in rest.iter().enumerate() {
        let a = x.abs();
        mx[k] = if a > mx[k] { a } else { mx[k] };
        sum[k] += a;
    }
    let total = (sum[0] + sum[1]) + (sum[2] + sum[3]);
    if !total.is_finite() {
        return None;
    }
    Some(mx[0].max(mx[1]).max(mx[2].max(mx[3])))
}

/// Row index of the largest `|m[i][j]|` over `i in j..rows`, and that magnitude.
#[inline]
fn find_pivot(m: &[f64], rows: usize, cols: usize, j: usize) -> (usize, f64) {
    let mut p = j;
    let mut best = m[j * cols + j].abs();
    for i in j + 1..rows {
        let a = m[i * cols + j].abs();
        if a > best {
            best = a;
            p = i;
        }
    }
    (p, best)
}

/// Swaps columns `j..cols` of rows `j < p` (columns before `j` are zero in both rows).
#[inline]
fn swap_rows_from(m: &mut [f64], cols: usize, j: usize, p: usize) {
    if p != j {
        let (a, b) = m.split_at_mut(p * cols);
        a[j * cols + j..(j + 1) * cols].swap_with_slice(&mut b[j..cols]);
    }
}

/// `row[j] := 0; row[j+1..] -= row[j] * prow` where `prow` is the pivot row from `j + 1`.
#[inline(always)]
fn eliminate_row(row: &mut [f64], j: usize, prow: &[f64]) {
    let f = row[j];
    if f != 0.0 {
        row[j] = 0.0;
        for (a, &b) in row[j + 1..].iter_mut().zip(prow) {
            *a -= f * b;
        }
    }
}

/// Checks the arguments and returns the used part of `m`.
#[inline]
fn checked(m: &mut [f64], rows: usize, cols: usize, pivot_cols: usize) -> Option<&mut [f64]> {
    let n = rows.checked_mul(cols)?;
    if m.len() < n || pivot_cols > rows || pivot_cols > cols {
        return None;
    }
    Some(&mut m[..n])
}

/// In-place Gauss-Jordan elimination with partial (row) pivoting of the row-major
/// `rows x cols` matrix `m`, eliminating the first `pivot_cols` columns in order.
///
/// On success (`true`), for every `j < pivot_cols` row `j` has 1 at column `j` and every
/// other row has 0 there (rows are permuted so that pivot `j` sits in row `j`); columns
/// `pivot_cols..cols` hold the reduced right-hand side: row `j` reads
/// `col_j + sum_k m[j][pivot_cols + k] * rhs_k`. Rows beyond `pivot_cols` (tall templates)
/// are reduced too.
///
/// Returns `false` (leaving garbage) if some column gets no pivot larger than
/// `PIVOT_TOL * max|m_ij|`, if an entry is not finite, if `m.len() < rows * cols`, or if
/// `pivot_cols > min(rows, cols)`. Never panics, never allocates.
pub fn gauss_jordan(m: &mut [f64], rows: usize, cols: usize, pivot_cols: usize) -> bool {
    let Some(m) = checked(m, rows, cols, pivot_cols) else {
        return false;
    };
    let Some(scale) = scale_of(m) else {
        return false;
    };
    let tol = scale * PIVOT_TOL;
    for j in 0..pivot_cols {
        let (p, best) = find_pivot(m, rows, cols, j);
        if !(best > tol && best <= f64::MAX) {
            return false;
        }
        swap_rows_from(m, cols, j, p);
        let (before, rest) = m.split_at_mut(j * cols);
        let (prow, after) = rest.split_at_mut(cols);
        let inv = 1.0 / prow[j];
        prow[j] = 1.0;
        for x in &mut prow[j + 1..] {
            *x *= inv;
        }
        let prow = &prow[j + 1..];
        for row in before.chunks_exact_mut(cols) {
            eliminate_row(row, j, prow);
        }
        for row in after.chunks_exact_mut(cols) {
            eliminate_row(row, j, prow);
        }
    }
    true
}

/// Same contract as [`gauss_jordan`] but only rows `first_row..pivot_cols` are fully
/// reduced: forward elimination with partial pivoting (unit pivots), then back
/// substitution for rows `pivot_cols - 1` down to `first_row` only.
///
/// On success, rows `first_row..pivot_cols` are exactly what [`gauss_jordan`] leaves
/// (1 on the diagonal, 0 elsewhere in the first `pivot_cols` columns, the reduced
/// right-hand side after), up to rounding. Rows `< first_row` hold the unit upper
/// triangular factor (not reduced), rows `>= pivot_cols` their forward-eliminated
/// remainder. For a template ordered `excess | reducible | basis`, pass
/// `first_row = n_excess`: the excess rows are never back-substituted.
///
/// Cost for the 5-point 10x20 template with `first_row = 4`: about 0.65x the flops of
/// `gauss_jordan`; measured 0.75-0.8x its time at 10x20 and ~0.5x at 100x120.
///
/// Returns `false` on the same conditions as [`gauss_jordan`] except that the pivot of
/// column `j` is compared with that column's tolerance ([`PIVOT_TOL`]), or if
/// `first_row > pivot_cols`. Never panics; allocates the `pivot_cols` tolerances
/// ([`lu_solve_template_fixed`], the emitted solvers' form, keeps them on the stack).
pub fn lu_solve_template(
    m: &mut [f64],
    rows: usize,
    cols: usize,
    pivot_cols: usize,
    first_row: usize,
) -> bool {
    let mut tol = vec![0.0; pivot_cols.min(cols)];
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { lu_core_avx2(m, rows, cols, pivot_cols, first_row, &mut tol) };
    }
    lu_core(m, rows, cols, pivot_cols, first_row, &mut tol)
}

/// [`lu_core`] compiled with AVX2 enabled: wider row operations. Without FMA every entry
/// sees the same multiplications and subtractions, so the results are bit-identical to the
/// baseline build's.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn lu_core_avx2(
    m: &mut [f64],
    rows: usize,
    cols: usize,
    pivot_cols: usize,
    first_row: usize,
    tol: &mut [f64],
) -> bool {
    lu_core(m, rows, cols, pivot_cols, first_row, tol)
}

/// [`lu_solve_template_fixed`]'s AVX2 build (see [`lu_core_avx2`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn lu_fixed_avx2<
    const ROWS: usize,
    const COLS: usize,
    const PIVOTS: usize,
    const FIRST: usize,
>(
    m: &mut [f64],
) -> bool {
    let mut tol = [0.0; PIVOTS];
    lu_core(m, ROWS, COLS, PIVOTS, FIRST, &mut tol)
}

/// [`lu_solve_template`] with the shape as constants (`ROWS x COLS`, `PIVOTS` pivot
/// columns, back substitution from row `FIRST`), which the emitted solvers use: with every
/// loop bound known the compiler drops the bounds checks and unrolls the short rows.
#[inline]
pub fn lu_solve_template_fixed<
    const ROWS: usize,
    const COLS: usize,
    const PIVOTS: usize,
    const FIRST: usize,
>(
    m: &mut [f64],
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { lu_fixed_avx2::<ROWS, COLS, PIVOTS, FIRST>(m) };
    }
    let mut tol = [0.0; PIVOTS];
    lu_core(m, ROWS, COLS, PIVOTS, FIRST, &mut tol)
}

/// `tol`: work space of `pivot_cols` entries (the per-column tolerances, [`PIVOT_TOL`]).
#[inline(always)]
fn lu_core(
    m: &mut [f64],
    rows: usize,
    cols: usize,
    pivot_cols: usize,
    first_row: usize,
    tol: &mut [f64],
) -> bool {
    if first_row > pivot_cols || tol.len() != pivot_cols {
        return false;
    }
    let Some(m) = checked(m, rows, cols, pivot_cols) else {
        return false;
    };
    if !column_tolerances(m, cols, tol) {
        return false;
    }
    // Forward elimination (rows below the pivot only), pivot rows scaled to unit pivots.
    for j in 0..pivot_cols {
        let (p, best) = find_pivot(m, rows, cols, j);
        if !(best > tol[j] && best <= f64::MAX) {
            return false;
        }
        swap_rows_from(m, cols, j, p);
        let (_, rest) = m.split_at_mut(j * cols);
        let (prow, after) = rest.split_at_mut(cols);
        let inv = 1.0 / prow[j];
        prow[j] = 1.0;
        for x in &mut prow[j + 1..] {
            *x *= inv;
        }
        let prow = &prow[j + 1..];
        for row in after.chunks_exact_mut(cols) {
            eliminate_row(row, j, prow);
        }
    }
    // Back substitution, bottom-up, for the requested rows only.
    for k in (first_row..pivot_cols).rev() {
        let (upper, lower) = m.split_at_mut((k + 1) * cols);
        let rowk = &mut upper[k * cols..];
        for (l, rowl) in (k + 1..pivot_cols).zip(lower.chunks_exact(cols)) {
            let f = rowk[l];
            if f != 0.0 {
                rowk[l] = 0.0;
                for (a, &b) in rowk[pivot_cols..].iter_mut().zip(&rowl[pivot_cols..]) {
                    *a -= f * b;
                }
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random(rng: &mut ChaCha8Rng, rows: usize, cols: usize, density: f64) -> Vec<f64> {
        (0..rows * cols)
            .map(|_| {
                if rng.gen::<f64>() < density {
                    rng.gen_range(-1.0..1.0)
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// max |A X - B| where the original is [A | B] and X is read from the reduced rows.
    fn check_solution(orig: &[f64], red: &[f64], rows: usize, cols: usize, pc: usize) -> f64 {
        let r = cols - pc;
        let mut worst: f64 = 0.0;
        for i in 0..rows {
            for c in 0..r {
                // A X = B, X[k][c] = red[k][pc + c]; GJ row reads col_k + X_k rhs = 0 => A X = B.
                let mut s = 0.0;
                for k in 0..pc {
                    s += orig[i * cols + k] * red[k * cols + pc + c];
                }
                worst = worst.max((s - orig[i * cols + pc + c]).abs());
            }
        }
        worst
    }

    #[test]
    fn gauss_jordan_reduces_random_templates() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for &(rows, cols, density) in &[(10, 20, 1.0), (10, 20, 0.5), (30, 45, 0.3), (1, 3, 1.0)] {
            for _ in 0..20 {
                let orig = random(&mut rng, rows, cols, density);
                let mut m = orig.clone();
                if !gauss_jordan(&mut m, rows, cols, rows) {
                    continue; // singular sparse draw
                }
                for i in 0..rows {
                    for j in 0..rows {
                        let want = if i == j { 1.0 } else { 0.0 };
                        assert_eq!(m[i * cols + j], want);
                    }
                }
                assert!(check_solution(&orig, &m, rows, cols, rows) < 1e-9);
                let mut l = orig.clone();
                let first = rows / 3;
                assert!(lu_solve_template(&mut l, rows, cols, rows, first));
                for i in first..rows {
                    for j in 0..cols {
                        let d = (l[i * cols + j] - m[i * cols + j]).abs();
                        assert!(d < 1e-9, "row {i} col {j}: {d}");
                    }
                }
            }
        }
    }

    #[test]
    fn tall_templates_and_partial_pivot_columns() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (rows, cols, pc) = (12, 20, 8);
        let orig = random(&mut rng, rows, cols, 1.0);
        let mut m = orig.clone();
        assert!(gauss_jordan(&mut m, rows, cols, pc));
        for i in 0..rows {
            for j in 0..pc {
                assert_eq!(m[i * cols + j], if i == j { 1.0 } else { 0.0 });
            }
        }
    }

    #[test]
    fn columns_of_small_entries_are_not_singular() {
        // Scaling column 3 by 1e-20 (a monomial whose values, and coefficients, are tiny)
        // scales row 3 of the reduced right-hand side by 1e20 and nothing else: the pivot
        // is compared with its own column, not with the largest entry of the template.
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let (rows, cols) = (10, 20);
        let orig = random(&mut rng, rows, cols, 1.0);
        let mut small = orig.clone();
        for i in 0..rows {
            small[i * cols + 3] *= 1e-20;
        }
        let (mut a, mut b) = (orig.clone(), small.clone());
        assert!(lu_solve_template(&mut a, rows, cols, rows, 0));
        assert!(lu_solve_template(&mut b, rows, cols, rows, 0));
        for i in 0..rows {
            let f = if i == 3 { 1e20 } else { 1.0 };
            for j in rows..cols {
                let (x, y) = (a[i * cols + j], b[i * cols + j] / f);
                assert!((x - y).abs() <= 1e-9 * x.abs().max(1.0), "{i} {j}: {x} {y}");
            }
        }
        // A column that is tiny because the template is singular still fails: column 3
        // made a combination of columns 0 and 1 up to 1e-17 of its size.
        let mut dep = orig.clone();
        for i in 0..rows {
            dep[i * cols + 3] =
                orig[i * cols] - 2.0 * orig[i * cols + 1] + 1e-17 * orig[i * cols + 3];
        }
        assert!(!lu_solve_template(&mut dep, rows, cols, rows, 0));
        let mut dep_fixed = dep.clone();
        assert!(!lu_solve_template_fixed::<10, 20, 10, 0>(&mut dep_fixed));
    }

    #[test]
    fn failures_do_not_panic() {
        let mut m = vec![0.0; 200];
        assert!(!gauss_jordan(&mut m, 10, 20, 10));
        assert!(!lu_solve_template(&mut m, 10, 20, 10, 4));
        let mut m = vec![1.0; 10];
        assert!(!gauss_jordan(&mut m, 10, 20, 10)); // too short
        assert!(!gauss_jordan(&mut m, usize::MAX, 3, 1)); // overflow
        assert!(!gauss_jordan(&mut m, 2, 5, 3)); // more pivots than rows
        assert!(!lu_solve_template(&mut m, 2, 5, 2, 3));
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut m = random(&mut rng, 10, 20, 1.0);
        m[57] = f64::NAN;
        assert!(!gauss_jordan(&mut m.clone(), 10, 20, 10));
        assert!(!lu_solve_template(&mut m, 10, 20, 10, 0));
        let mut m = random(&mut rng, 10, 20, 1.0);
        m[199] = f64::INFINITY;
        assert!(!gauss_jordan(&mut m, 10, 20, 10));
        // Rank-deficient left block: row 3 = 2 * row 1.
        let mut m = random(&mut rng, 10, 20, 1.0);
        for c in 0..10 {
            m[3 * 20 + c] = 2.0 * m[20 + c];
        }
        assert!(!gauss_jordan(&mut m.clone(), 10, 20, 10));
        assert!(!lu_solve_template(&mut m, 10, 20, 10, 4));
        // Empty is fine.
        assert!(gauss_jordan(&mut [], 0, 0, 0));
    }
}
