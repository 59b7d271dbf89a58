//! The Schur complement of a template's rows whose pivot block is constant, formed when
//! the template is filled.
//!
//! Multiples of an equation with numeric coefficients on some monomials (a unit-norm or
//! rotation constraint, `u² + v² + w² + s² - 1` with data `s`) have the same entries there
//! on every instance. With the template ordered so that `k` such rows come first and `k`
//! columns where their entries are constants come first, `[M11 M12; M21 M22]` with `M11`
//! (k x k) constant and invertible, the elimination of the template reduces the rows of the
//! Schur complement `M22 - M21 M11⁻¹ M12` exactly as the whole template's would, `k` rows
//! and columns smaller. The generator computes `M11⁻¹` in exact arithmetic; the solver
//! forms the complement with it (the reduction of Martyushev, Vrablikova and Pajdla's
//! solvers, `M(k+1:end,k+1:end) - M(k+1:end,1:k)/M(1:k,1:k)*M(1:k,k+1:end)`, with the
//! division done by the generator).

/// The constant inverse `M11⁻¹` of a template's folded block, row by row, sparse, and the
/// shape it folds.
#[derive(Clone, Copy, Debug)]
pub struct ConstantFold<'a> {
    /// Rows of the complement (the template's rows after the folded ones).
    pub rows: usize,
    /// The number of rows and columns folded, `k`.
    pub folded: usize,
    /// Columns of the complement (the filled matrix has `folded + cols`).
    pub cols: usize,
    /// Offsets into `inv_cols` and `inv_vals`, one per row of `M11⁻¹` plus the end.
    pub inv_start: &'a [u32],
    /// The column (in `0..folded`) of each non-zero of `M11⁻¹`.
    pub inv_cols: &'a [u16],
    /// The non-zeros of `M11⁻¹`.
    pub inv_vals: &'a [f64],
    /// Offsets into `m12_cols`, one per folded row plus the end.
    pub m12_start: &'a [u32],
    /// The columns (in `0..cols`) where each folded row of `M12` may be non-zero.
    pub m12_cols: &'a [u16],
}

/// Writes the Schur complement `out = M22 - M21 M11⁻¹ M12` of the filled matrix
/// `filled = [M11 M12; M21 M22]` (`(plan.folded + plan.rows) x (plan.folded + plan.cols)`,
/// row-major; `M11` itself is not read, nor `M12` outside `plan.m12_cols`) into `out` (`plan.rows x plan.cols`, row-major),
/// with `t` (`plan.folded` entries) as scratch. Returns `false`, leaving `out` unspecified,
/// when a length or index disagrees with `plan` (the generator never emits such a plan;
/// the check keeps the never-panics contract).
pub fn fold_constant_rows(
    filled: &[f64],
    plan: &ConstantFold<'_>,
    t: &mut [f64],
    out: &mut [f64],
) -> bool {
    let (k, cols) = (plan.folded, plan.cols);
    let width = k + cols;
    // Only the shapes are checked up front; the plan's indices are checked where they are
    // used (`get`), so that a call costs no pass over the plan.
    let consistent = filled.len() == (k + plan.rows) * width
        && out.len() == plan.rows * cols
        && t.len() == k
        && plan.inv_start.len() == k + 1
        && plan.inv_cols.len() == plan.inv_vals.len()
        && plan.m12_start.len() == k + 1;
    if !consistent {
        return false;
    }
    let (top, bottom) = filled.split_at(k * width);
    for (src, dst) in bottom.chunks_exact(width).zip(out.chunks_exact_mut(cols)) {
        dst.copy_from_slice(&src[k..]);
        // t = M21[i, :] M11⁻¹
        t.iter_mut().for_each(|x| *x = 0.0);
        for (p, &a) in src[..k].iter().enumerate() {
            if a == 0.0 {
                continue;
            }
            let range = plan.inv_start[p] as usize..plan.inv_start[p + 1] as usize;
            let (Some(qs), Some(vs)) = (plan.inv_cols.get(range.clone()), plan.inv_vals.get(range))
            else {
                return false;
            };
            for (&q, &v) in qs.iter().zip(vs) {
                let Some(tq) = t.get_mut(usize::from(q)) else {
                    return false;
                };
                *tq += a * v;
            }
        }
        // row -= t M12
        for (q, &tq) in t.iter().enumerate() {
            if tq == 0.0 {
                continue;
            }
            let m12 = &top[q * width + k..(q + 1) * width];
            let range = plan.m12_start[q] as usize..plan.m12_start[q + 1] as usize;
            let Some(columns) = plan.m12_cols.get(range) else {
                return false;
            };
            for &c in columns {
                let c = usize::from(c);
                let (Some(d), Some(&x)) = (dst.get_mut(c), m12.get(c)) else {
                    return false;
                };
                *d -= tq * x;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fold of `[M11 M12; M21 M22]` is `M22 - M21 M11⁻¹ M12`.
    #[test]
    fn complement_of_two_folded_rows() {
        // M11 = [[2, 0], [1, 1]], M11⁻¹ = [[0.5, 0], [-0.5, 1]].
        let plan = ConstantFold {
            rows: 1,
            folded: 2,
            cols: 2,
            inv_start: &[0, 1, 3],
            inv_cols: &[0, 0, 1],
            inv_vals: &[0.5, -0.5, 1.0],
            m12_start: &[0, 2, 4],
            m12_cols: &[0, 1, 0, 1],
        };
        // M12 = [[4, 2], [1, 3]], M21 = [[2, 1]], M22 = [[10, 20]].
        let filled = [2.0, 0.0, 4.0, 2.0, 1.0, 1.0, 1.0, 3.0, 2.0, 1.0, 10.0, 20.0];
        let (mut t, mut out) = ([0.0; 2], [0.0; 2]);
        assert!(fold_constant_rows(&filled, &plan, &mut t, &mut out));
        // M21 M11⁻¹ = [0.5, 1]; [0.5, 1] M12 = [3, 4]; complement [7, 16].
        assert_eq!(out, [7.0, 16.0]);
        let mut short = [0.0; 1];
        assert!(!fold_constant_rows(&filled, &plan, &mut t, &mut short));
        let bad = ConstantFold {
            inv_cols: &[0, 2, 1],
            ..plan
        };
        assert!(!fold_constant_rows(&filled, &bad, &mut t, &mut out));
    }
}
