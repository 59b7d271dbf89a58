//! Row reduction of a problem's equations on their data, before the template is filled.
//!
//! A template built from row-reduced equations can be much smaller than one built from
//! the equations as written: each reduced equation has a pivot monomial that no other
//! equation contains, so fewer multiples are needed to eliminate the monomials above the
//! basis. The generator chooses the pivot monomials (one per equation, on a generic
//! instance); the solver reduces its own data's equations to them with
//! [`reduce_equations`] and fills the template from the reduced coefficients.

/// Reduces the equations' coefficient matrix `q` in place to reduced row echelon form on
/// the pivot columns `pivots`.
///
/// `q` holds `pivots.len()` equations, row-major, `n_mon` coefficients each (one column
/// per monomial, in the order the generator fixed). Afterwards row `k` has `1` in column
/// `pivots[k]` and `0` in every other pivot column: row `k` is the reduced equation whose
/// pivot is `pivots[k]`, whichever input row it came from. This is Gauss-Jordan
/// elimination on the pivot columns with partial pivoting over the rows not yet used,
/// i.e. `q <- A^-1 q` for `A = q[:, pivots]`.
///
/// Returns `false` (leaving `q` partly reduced) when the sizes disagree, a pivot column is
/// out of range, or `A` is singular or has non-finite entries (data degenerate for the
/// reduction); never panics.
pub fn reduce_equations(q: &mut [f64], n_mon: usize, pivots: &[usize]) -> bool {
    reduce_core(q, n_mon, pivots)
}

/// [`reduce_equations`] with the shape as constants (`N_EQ` equations of `N_MON`
/// coefficients): inlined into an emitted solver, whose pivots are constants too, its
/// loops unroll. The same operations in the same order, so the same numbers.
#[inline]
pub fn reduce_equations_fixed<const N_EQ: usize, const N_MON: usize>(
    q: &mut [f64],
    pivots: &[usize; N_EQ],
) -> bool {
    reduce_core(q, N_MON, pivots)
}

#[inline(always)]
fn reduce_core(q: &mut [f64], n_mon: usize, pivots: &[usize]) -> bool {
    let n = pivots.len();
    if n.checked_mul(n_mon) != Some(q.len()) || pivots.iter().any(|&p| p >= n_mon) {
        return false;
    }
    for (k, &p) in pivots.iter().enumerate() {
        let mut best = (0.0f64, k);
        for i in k..n {
            let a = q[i * n_mon + p].abs();
            if a > best.0 {
                best = (a, i);
            }
        }
        let (size, r) = best;
        if !(size > 0.0 && size.is_finite()) {
            return false;
        }
        if r != k {
            let (head, tail) = q.split_at_mut(r * n_mon);
            head[k * n_mon..(k + 1) * n_mon].swap_with_slice(&mut tail[..n_mon]);
        }
        let inv = 1.0 / q[k * n_mon + p];
        for x in &mut q[k * n_mon..(k + 1) * n_mon] {
            *x *= inv;
        }
        q[k * n_mon + p] = 1.0;
        for i in (0..n).filter(|&i| i != k) {
            let (pivot_row, row) = if i < k {
                let (head, tail) = q.split_at_mut(k * n_mon);
                (&tail[..n_mon], &mut head[i * n_mon..(i + 1) * n_mon])
            } else {
                let (head, tail) = q.split_at_mut(i * n_mon);
                (&head[k * n_mon..(k + 1) * n_mon], &mut tail[..n_mon])
            };
            let f = row[p];
            if f != 0.0 {
                for (x, y) in row.iter_mut().zip(pivot_row) {
                    *x -= f * y;
                }
                row[p] = 0.0;
            }
        }
    }
    q.iter().all(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduces_to_the_given_pivots_whatever_the_row_order() {
        // Equations x + 2y + 3 = 0 and 2x + y + 1 = 0 on columns (x, y, 1), given in both
        // row orders: the reduced rows are x - 1/3 = 0 and y + 5/3 = 0.
        let rows = [[1.0, 2.0, 3.0], [2.0, 1.0, 1.0]];
        for order in [[0, 1], [1, 0]] {
            let mut q: Vec<f64> = order.iter().flat_map(|&i| rows[i]).collect();
            assert!(reduce_equations(&mut q, 3, &[0, 1]));
            let want = [1.0, 0.0, -1.0 / 3.0, 0.0, 1.0, 5.0 / 3.0];
            for (a, b) in q.iter().zip(want) {
                assert!((a - b).abs() < 1e-15, "{q:?}");
            }
        }
    }

    #[test]
    fn the_fixed_form_gives_the_same_numbers() {
        let rows = [
            1.5, -2.0, 0.25, 3.0, 2.0, 1.0, -1.0, 0.5, -0.75, 4.0, 1.0, 2.0,
        ];
        let (mut a, mut b) = (rows.to_vec(), rows.to_vec());
        assert!(reduce_equations(&mut a, 4, &[1, 0, 3]));
        assert!(reduce_equations_fixed::<3, 4>(&mut b, &[1, 0, 3]));
        assert_eq!(a, b);
        assert!(!reduce_equations_fixed::<3, 5>(&mut b, &[1, 0, 3]));
    }

    #[test]
    fn refuses_singular_or_malformed_input() {
        let mut q = vec![1.0, 2.0, 2.0, 4.0];
        assert!(!reduce_equations(&mut q, 2, &[0, 1]));
        let mut q = vec![1.0, 2.0, 3.0];
        assert!(!reduce_equations(&mut q, 2, &[0]));
        let mut q = vec![1.0, 2.0];
        assert!(!reduce_equations(&mut q, 2, &[2]));
        let mut q = vec![f64::NAN, 1.0];
        assert!(!reduce_equations(&mut q, 2, &[0]));
    }
}
