//! The Schur complement of a template's rows whose pivots are constants in a triangle,
//! formed when the template is filled.
//!
//! A multiple `m f` of an equation with a numeric coefficient on some monomial `x` (`u² +
//! v² + w² + c` with data `c`: the coefficient of `m u²` is 1 on every instance) can pivot
//! on the column `m x`. Ordered so that no folded row has an entry in the pivot column of a
//! row after it, the folded rows' block `M11` is lower triangular with a constant diagonal:
//! its determinant is a non-zero number, so the Schur complement `M22 - M21 M11⁻¹ M12`
//! exists on every instance, and it reduces the rows exactly as the whole template's
//! elimination would, `k` rows and columns smaller. Entries below the diagonal may depend
//! on the data (this is the data-dependent part of Martyushev, Vrablikova and Pajdla's
//! `schur_pols` blocks); forward substitution with the known pivots forms the complement,
//! no pivot search and no division by data.

/// The pivots of a template's triangular fold and the shape it folds.
#[derive(Clone, Copy, Debug)]
pub struct TriangularFold<'a> {
    /// Rows of the complement (the matrix's rows after the folded ones).
    pub rows: usize,
    /// The number of rows and columns folded, `k`.
    pub folded: usize,
    /// Columns of the complement (the matrix has `folded + cols`).
    pub cols: usize,
    /// `1 / pivot` of each folded row: row `i` pivots on column `i`, where no folded row
    /// before it has an entry.
    pub pivot_inv: &'a [f64],
}

/// Writes the Schur complement of the first `plan.folded` rows and columns of `m`
/// (`(plan.folded + plan.rows) x (plan.folded + plan.cols)`, row-major), which is
/// overwritten as scratch, into `out` (`plan.rows x plan.cols`, row-major). Row `i < k`
/// eliminates column `i` from the rows after it with the pivot `1 / plan.pivot_inv[i]`
/// (the rows before it are zero there, so the pivot is the filled entry and is not
/// changed by the earlier steps). Returns `false`, leaving `out` unspecified, when a
/// length disagrees with `plan` (the generator never emits such a plan; the check keeps
/// the never-panics contract).
pub fn fold_triangular_rows(m: &mut [f64], plan: &TriangularFold<'_>, out: &mut [f64]) -> bool {
    let (k, cols) = (plan.folded, plan.cols);
    let width = k + cols;
    if m.len() != (k + plan.rows) * width
        || out.len() != plan.rows * cols
        || plan.pivot_inv.len() != k
    {
        return false;
    }
    // The non-zero columns of the pivot row, right of its pivot: the rows it updates
    // touch only those.
    let mut pattern: Vec<usize> = Vec::with_capacity(width);
    for (i, &inv) in plan.pivot_inv.iter().enumerate() {
        let (upper, lower) = m.split_at_mut((i + 1) * width);
        let pivot_row = &upper[i * width..];
        pattern.clear();
        pattern.extend((i + 1..width).filter(|&c| pivot_row[c] != 0.0));
        for row in lower.chunks_exact_mut(width) {
            let a = row[i];
            if a == 0.0 {
                continue;
            }
            let f = a * inv;
            for &c in &pattern {
                row[c] -= f * pivot_row[c];
            }
        }
    }
    for (src, dst) in m[k * width..]
        .chunks_exact(width)
        .zip(out.chunks_exact_mut(cols))
    {
        dst.copy_from_slice(&src[k..]);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fold of `[M11 M12; M21 M22]` with `M11` lower triangular is
    /// `M22 - M21 M11⁻¹ M12`.
    #[test]
    fn complement_of_two_triangular_rows() {
        // M11 = [[2, 0], [3, 1]], M11⁻¹ = [[0.5, 0], [-1.5, 1]].
        let plan = TriangularFold {
            rows: 1,
            folded: 2,
            cols: 2,
            pivot_inv: &[0.5, 1.0],
        };
        // M12 = [[4, 2], [1, 3]], M21 = [[2, 1]], M22 = [[10, 20]].
        let mut m = [2.0, 0.0, 4.0, 2.0, 3.0, 1.0, 1.0, 3.0, 2.0, 1.0, 10.0, 20.0];
        let mut out = [0.0; 2];
        assert!(fold_triangular_rows(&mut m, &plan, &mut out));
        // M21 M11⁻¹ = [1 - 1.5, 1] = [-0.5, 1]; [-0.5, 1] M12 = [-1, 2]; complement
        // [11, 18].
        assert_eq!(out, [11.0, 18.0]);
        let mut short = [0.0; 1];
        assert!(!fold_triangular_rows(&mut m, &plan, &mut short));
        let bad = TriangularFold {
            pivot_inv: &[0.5],
            ..plan
        };
        assert!(!fold_triangular_rows(&mut m, &bad, &mut out));
    }
}
