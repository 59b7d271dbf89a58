//! The action matrix of a pencil template: some basis monomials' relations taken the other
//! way round.
//!
//! A template's relation matrix `R` (row j: the basis coordinates of `action * b_j`, or of
//! `b_j / action` for a flipped `j`) gives, at every solution `s` with basis vector `v`,
//! `action(s) T1 v = T0 v`, where `T1`'s row j is `e_j` and `T0`'s is `R_j` for an unflipped
//! `j`, the other way round for a flipped one. The action matrix `M = T1^-1 T0` keeps the
//! unflipped rows of `R`; its flipped rows `F` solve the `|F| x |F|` system
//! `R_FF M_F = E_F - R_FU R_U` (`U` the unflipped rows, `E_F` the flipped rows of the
//! identity). Only that small system is factored: the flipped rows are few.

use super::PIVOT_TOL;

/// Overwrites the flipped rows of the relation matrix `a` (`n x n`, column-major as
/// nalgebra stores it) with those of the action matrix `M = T1^-1 T0` (module
/// documentation). `flipped` holds increasing row indices below `n`; `scratch` at least
/// `k (k + n)` entries, `k = flipped.len()`. Gauss-Jordan elimination with partial
/// pivoting of `[R_FF | E_F - R_FU R_U]`; returns `false`, leaving `a` unspecified, when a
/// pivot is at most [`PIVOT_TOL`] times the largest entry of `R_FF` (the pencil is
/// singular on this instance), when a result is not finite, or when a length disagrees.
pub fn pencil_action_rows(a: &mut [f64], n: usize, flipped: &[usize], scratch: &mut [f64]) -> bool {
    let k = flipped.len();
    let width = k + n;
    if a.len() != n * n || scratch.len() < k * width || flipped.iter().any(|&j| j >= n) {
        return false;
    }
    let at = |a: &[f64], r: usize, c: usize| a[c * n + r];
    let is_flipped = |j: usize| flipped.binary_search(&j).is_ok();
    let w = &mut scratch[..k * width];
    let mut scale = 0.0f64;
    for (p, &i) in flipped.iter().enumerate() {
        let row = &mut w[p * width..(p + 1) * width];
        for (q, &l) in flipped.iter().enumerate() {
            row[q] = at(a, i, l);
            scale = scale.max(row[q].abs());
        }
        for c in 0..n {
            let mut x = if c == i { 1.0 } else { 0.0 };
            for l in (0..n).filter(|&l| !is_flipped(l)) {
                let r = at(a, i, l);
                if r != 0.0 {
                    x -= r * at(a, l, c);
                }
            }
            row[k + c] = x;
        }
    }
    if !(scale.is_finite() && scale > 0.0) {
        return false;
    }
    for col in 0..k {
        let pivot_row = (col..k)
            .max_by(|&x, &y| {
                w[x * width + col]
                    .abs()
                    .total_cmp(&w[y * width + col].abs())
            })
            .unwrap_or(col);
        let pivot = w[pivot_row * width + col];
        if pivot.abs() <= PIVOT_TOL * scale || !pivot.is_finite() {
            return false;
        }
        if pivot_row != col {
            for c in 0..width {
                w.swap(pivot_row * width + c, col * width + c);
            }
        }
        let inv = 1.0 / pivot;
        for c in col..width {
            w[col * width + c] *= inv;
        }
        for r in (0..k).filter(|&r| r != col) {
            let f = w[r * width + col];
            if f != 0.0 {
                for c in col..width {
                    w[r * width + c] -= f * w[col * width + c];
                }
            }
        }
    }
    for (p, &i) in flipped.iter().enumerate() {
        for c in 0..n {
            let x = w[p * width + k + c];
            if !x.is_finite() {
                return false;
            }
            a[c * n + i] = x;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Column-major `n x n` from rows.
    fn col_major(rows: &[&[f64]]) -> Vec<f64> {
        let n = rows.len();
        (0..n * n).map(|i| rows[i % n][i / n]).collect()
    }

    #[test]
    fn flipped_rows_solve_the_pencil() {
        // x^2 - 5x + 6 = 0 (roots 2 and 3) on the basis (x^2, x), action x: the action
        // matrix is M = [[5, -6], [1, 0]] (x^3 = 5x^2 - 6x, x * x = x^2).
        let m = [[5.0, -6.0], [1.0, 0.0]];
        // Row 1 flipped: its relation is x / x = 1 = (5x - x^2) / 6, coordinates
        // (-1/6, 5/6); the pencil gives M back.
        let mut r = col_major(&[&m[0], &[-1.0 / 6.0, 5.0 / 6.0]]);
        let mut s = [0.0; 3];
        assert!(pencil_action_rows(&mut r, 2, &[1], &mut s));
        for (i, row) in m.iter().enumerate() {
            for (j, &x) in row.iter().enumerate() {
                assert!(
                    (r[j * 2 + i] - x).abs() < 1e-14,
                    "{i} {j}: {}",
                    r[j * 2 + i]
                );
            }
        }
        // Row 0 flipped instead (x^2 / x = x, coordinates e_1) with row 1 unflipped
        // (x * x = x^2, e_0): T1 = [[0, 1], [0, 1]] is singular, and so is R_00 = 0.
        let mut singular = col_major(&[&[0.0, 1.0], &[1.0, 0.0]]);
        assert!(!pencil_action_rows(&mut singular, 2, &[0], &mut s));
        // Lengths that disagree, and non-finite input, fail without panicking.
        assert!(!pencil_action_rows(&mut r, 3, &[1], &mut s));
        assert!(!pencil_action_rows(&mut r, 2, &[1], &mut [0.0; 2]));
        assert!(!pencil_action_rows(&mut r, 2, &[2], &mut s));
        let mut bad = col_major(&[&m[0], &[f64::NAN, 1.0]]);
        assert!(!pencil_action_rows(&mut bad, 2, &[1], &mut s));
    }
}
