//! Both signs of the solutions of a sign-folded system (ARCHITECTURE §2, "Sign
//! symmetry").
//!
//! When every equation of a problem is even or odd in a set of unknowns `S` (flipping the
//! sign of all of them maps solutions to solutions, as P3P's depths), the generator solves
//! the system folded by one *pivot* `x_p` of `S`: its variable `p` holds `s = x_p²` and
//! each other variable `j` of `S` holds `t_j = x_j / x_p`. That system has half the
//! solutions; each one with `s > 0` gives the pair `x_p = ±√s`, `x_j = x_p t_j`. A fold is
//! written `(p, &[j, ...])`; several folds were applied in order and are undone in reverse.

/// One fold: the pivot variable and the variables scaled by it (indices into the solution
/// vector).
pub type SignFold<'a> = (usize, &'a [usize]);

/// Undoes `fold` on `u` in place, giving the solution with `x_p = +√s`: `false` (no real
/// solution; `u` unspecified) when `s` is not positive and finite (`s < 0` is a pair of
/// complex solutions, `s = 0` a degenerate one) or a product is not finite. Never panics:
/// out-of-range indices return `false`.
#[inline]
pub fn unfold_sign(u: &mut [f64], fold: SignFold) -> bool {
    let (p, scaled) = fold;
    let Some(&s) = u.get(p) else {
        return false;
    };
    if !(s > 0.0 && s.is_finite()) {
        return false;
    }
    let r = s.sqrt();
    u[p] = r;
    for &j in scaled {
        match u.get_mut(j) {
            Some(x) if x.is_finite() => *x *= r,
            _ => return false,
        }
    }
    true
}

/// The other sign of an unfolded solution: `x_p` and every scaled variable negated.
/// Out-of-range indices are ignored.
#[inline]
pub fn flip_sign(u: &mut [f64], fold: SignFold) {
    for &j in std::iter::once(&fold.0).chain(fold.1) {
        if let Some(x) = u.get_mut(j) {
            *x = -*x;
        }
    }
}

/// Every real solution of the original unknowns from one solution `w` of a system folded
/// by `folds` (in the order they were applied): at most `2^folds.len()` vectors, written
/// to `out[..n]`, `n` returned (the `+` sign first). `M` must be at least
/// `2^folds.len()`; vectors beyond `M` are not written.
#[inline]
pub fn unfold_signs<const N: usize, const M: usize>(
    w: &[f64; N],
    folds: &[SignFold],
    out: &mut [[f64; N]; M],
) -> usize {
    if M == 0 {
        return 0;
    }
    out[0] = *w;
    let mut n = 1;
    for &fold in folds.iter().rev() {
        let current: [[f64; N]; M] = *out;
        let mut kept = 0;
        for u in &current[..n] {
            let mut u = *u;
            if !unfold_sign(&mut u, fold) {
                continue;
            }
            for sign in 0..2 {
                if sign == 1 {
                    flip_sign(&mut u, fold);
                }
                if kept < M {
                    out[kept] = u;
                    kept += 1;
                }
            }
        }
        n = kept;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_fold_gives_both_signs() {
        // x = (2, -3, 5) folded by pivot 0 scaling 1: s = 4, t = -1.5.
        let w = [4.0, -1.5, 5.0];
        let mut out = [[0.0; 3]; 2];
        assert_eq!(unfold_signs(&w, &[(0, &[1])], &mut out), 2);
        assert_eq!(out[0], [2.0, -3.0, 5.0]);
        assert_eq!(out[1], [-2.0, 3.0, 5.0]);
    }

    #[test]
    fn negative_or_zero_square_gives_none() {
        let mut out = [[0.0; 2]; 2];
        assert_eq!(unfold_signs(&[-1.0, 1.0], &[(0, &[1])], &mut out), 0);
        assert_eq!(unfold_signs(&[0.0, 1.0], &[(0, &[1])], &mut out), 0);
        assert_eq!(unfold_signs(&[f64::NAN, 1.0], &[(0, &[1])], &mut out), 0);
        assert_eq!(unfold_signs(&[1.0, 1.0], &[(5, &[1])], &mut out), 0);
    }

    #[test]
    fn two_folds_undone_in_reverse() {
        // x = (3, 2): fold 1 pivot 0 (s = 9, no scaled), fold 2 pivot 1 (q = 4).
        let w = [9.0, 4.0];
        let mut out = [[0.0; 2]; 4];
        assert_eq!(unfold_signs(&w, &[(0, &[]), (1, &[])], &mut out), 4);
        let mut got: Vec<[f64; 2]> = out.to_vec();
        got.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(
            got,
            vec![[-3.0, -2.0], [-3.0, 2.0], [3.0, -2.0], [3.0, 2.0]]
        );
        // A capacity below 2^folds keeps the first ones only.
        let mut small = [[0.0; 2]; 2];
        assert_eq!(unfold_signs(&w, &[(0, &[]), (1, &[])], &mut small), 2);
    }
}
