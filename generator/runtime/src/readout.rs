//! Reading the unknowns off an eigenvector of the action matrix.

/// A ratio of eigenvector entries (unit vectors) is read only if its denominator (for
/// several pairs, the root of the sum of their squares) exceeds this: a smaller one is
/// numerical noise or a solution at infinity, and the eigenvector is skipped.
pub const MIN_UNIT_ENTRY: f64 = 1e-12;

/// Reads every unknown off the unit eigenvector `v ∝ (b_0(s), ..., b_{n-1}(s))` of the
/// action matrix into `out` (one entry per element of `pairs`); `false` (skip this
/// eigenvector) if `v[one]` (the basis monomial 1) is not finite, if an unknown's
/// denominators are at most [`MIN_UNIT_ENTRY`] (see there), or if an unknown is not
/// finite.
///
/// `pairs[i]` lists the read-out pairs `(j, k)` of unknown `x_i`: `b_k = x_i * b_j`. An
/// empty list leaves `out[i]` as it is: that unknown is not in the basis and is read by
/// [`read_linear`] instead. One
/// pair gives the plain ratio `v[k] / v[j]`; several give the least-squares combination
/// `sum_p v[j_p] v[k_p] / sum_p v[j_p]^2`, which weights each ratio by `v[j]^2`. An
/// eigenvector accurate to `e` gives `x` from one pair to about `e / |v[j]|`, so the plain
/// `v[x] / v[1]` loses the accuracy of large solutions (where `v[1]` is tiny next to the
/// higher-degree monomials); the combination is dominated by the largest denominators.
/// So a solution far from the origin, whose `v[1]` is below [`MIN_UNIT_ENTRY`], is still
/// read when every unknown has a pair with a large denominator.
///
/// The emitted solvers call it with constant pairs (inlined and unrolled), the interpreter
/// with the template's. Never panics: out-of-range indices make it return `false`.
#[inline]
pub fn read_unknowns(v: &[f64], one: usize, pairs: &[&[(usize, usize)]], out: &mut [f64]) -> bool {
    read_unknowns_with_eigenvalue(v, one, pairs, None, out)
}

/// [`read_unknowns`], except that the unknown `action.0`, whose eigenvalue `action.1` the
/// eigenvector belongs to (the action is that unknown alone), is the eigenvalue where its
/// pairs cannot be read (their denominators at most [`MIN_UNIT_ENTRY`]: a basis shifted by
/// a monomial that is large at this solution, or a solution far from the origin). `None`:
/// exactly [`read_unknowns`]. Never panics.
#[inline]
pub fn read_unknowns_with_eigenvalue(
    v: &[f64],
    one: usize,
    pairs: &[&[(usize, usize)]],
    action: Option<(usize, f64)>,
    out: &mut [f64],
) -> bool {
    let Some(&w) = v.get(one) else {
        return false;
    };
    if !w.is_finite() || out.len() != pairs.len() {
        return false;
    }
    for (i, (x, p)) in out.iter_mut().zip(pairs).enumerate() {
        if p.is_empty() {
            continue;
        }
        let value = match (read_pairs(v, p), action) {
            (Some(value), _) => value,
            (None, Some((a, lambda))) if a == i && lambda.is_finite() => lambda,
            (None, _) => return false,
        };
        *x = value;
    }
    true
}

/// One unknown from its pairs (see [`read_unknowns`]); `None` for a denominator at most
/// [`MIN_UNIT_ENTRY`], an index out of range or a non-finite value.
#[inline]
fn read_pairs(v: &[f64], p: &[(usize, usize)]) -> Option<f64> {
    let value = match *p {
        [(j, k)] => match (v.get(j), v.get(k)) {
            (Some(a), Some(b)) if a.abs() > MIN_UNIT_ENTRY => b / a,
            _ => return None,
        },
        _ => {
            let (mut num, mut den) = (0.0, 0.0);
            for &(j, k) in p {
                let (a, b) = (v.get(j)?, v.get(k)?);
                num += a * b;
                den += a * a;
            }
            if den <= MIN_UNIT_ENTRY * MIN_UNIT_ENTRY {
                return None;
            }
            num / den
        }
    };
    value.is_finite().then_some(value)
}

/// Reads an unknown `x` that is not in the basis off the unit eigenvector `v ∝ (b_0(s),
/// ..., b_{n-1}(s))` through its reduced template row `x + sum_k row[k] b_k` (a linear
/// equation makes `x` a combination of basis monomials): `x = -sum_k row[k] v[k] / v[one]`.
/// `None` (skip this eigenvector) if `v[one]` is not finite or at most [`MIN_UNIT_ENTRY`],
/// if the lengths differ, or if the value is not finite. Never panics.
#[inline]
pub fn read_linear(v: &[f64], one: usize, row: &[f64]) -> Option<f64> {
    let w = *v.get(one)?;
    if !w.is_finite() || w.abs() <= MIN_UNIT_ENTRY || row.len() != v.len() {
        return None;
    }
    let dot: f64 = row.iter().zip(v).map(|(r, x)| r * x).sum();
    let x = -dot / w;
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_action_unknown_falls_back_to_its_eigenvalue() {
        // A basis (p^3, p, a p) shifted by p (its unit at 1), at p = 1e8 and a = 0.5: the only
        // pair of a, (p, a p), has a denominator below MIN_UNIT_ENTRY.
        let (p, a) = (1e8f64, 0.5);
        let n = (p.powi(6) + p * p + a * a * p * p).sqrt();
        let v = [p.powi(3) / n, p / n, a * p / n];
        let pairs: [&[(usize, usize)]; 1] = [&[(1, 2)]];
        let mut out = [0.0];
        assert!(!read_unknowns(&v, 1, &pairs, &mut out));
        assert!(!read_unknowns_with_eigenvalue(
            &v,
            1,
            &pairs,
            Some((1, 0.5)),
            &mut out
        ));
        assert!(read_unknowns_with_eigenvalue(
            &v,
            1,
            &pairs,
            Some((0, a)),
            &mut out
        ));
        assert_eq!(out, [a]);
    }

    #[test]
    fn uses_the_large_entries() {
        // Basis (x^2, x, 1) at x = 1e6, unit vector, entries perturbed by 1e-13 absolute:
        // v[x] / v[1] is off by ~10 %, the combination with v[x^2] / v[x] by ~1e-7.
        let x = 1e6;
        let n = (x * x * x * x + x * x + 1.0f64).sqrt();
        let v = [x * x / n + 1e-13, x / n - 1e-13, 1.0 / n + 1e-13];
        let mut plain = [0.0];
        let mut both = [0.0];
        assert!(read_unknowns(&v, 2, &[&[(2, 1)]], &mut plain));
        assert!(read_unknowns(&v, 2, &[&[(2, 1), (1, 0)]], &mut both));
        assert!((plain[0] - x).abs() > 0.05 * x, "{plain:?}");
        assert!((both[0] - x).abs() < 1e-6 * x, "{both:?}");
    }

    #[test]
    fn reads_solutions_far_from_the_origin() {
        // Basis (x^4, x^3, x^2, x, 1) at x = 1e4: v[1] is 1e-16, below MIN_UNIT_ENTRY, but the
        // pairs (x^k, x^{k+1}) with large x^k read x; the single pair (1, x) cannot.
        let x = 1e4f64;
        let b = [x.powi(4), x.powi(3), x * x, x, 1.0];
        let n = b.iter().map(|e| e * e).sum::<f64>().sqrt();
        let v: Vec<f64> = b.iter().map(|e| e / n).collect();
        assert!(v[4] < MIN_UNIT_ENTRY);
        let mut out = [0.0];
        assert!(read_unknowns(
            &v,
            4,
            &[&[(4, 3), (3, 2), (2, 1), (1, 0)]],
            &mut out
        ));
        assert!((out[0] - x).abs() < 1e-9 * x, "{out:?}");
        assert!(!read_unknowns(&v, 4, &[&[(4, 3)]], &mut out));
    }

    #[test]
    fn linear_read_out() {
        // Basis (t3, 1) with t1 = 2 t3 - 1: the reduced row of t1 is t1 - 2 t3 + 1.
        let t3 = 0.75;
        let n = (t3 * t3 + 1.0f64).sqrt();
        let v = [t3 / n, 1.0 / n];
        let t1 = read_linear(&v, 1, &[-2.0, 1.0]).unwrap();
        assert!((t1 - (2.0 * t3 - 1.0)).abs() < 1e-15, "{t1}");
        // The ratio read-out leaves an unknown with no pairs alone.
        let mut out = [7.0, 0.0];
        assert!(read_unknowns(&v, 1, &[&[], &[(1, 0)]], &mut out));
        assert_eq!(out[0], 7.0);
        assert!((out[1] - t3).abs() < 1e-15);
        assert_eq!(read_linear(&[1.0, 1e-13], 1, &[1.0, 1.0]), None);
        assert_eq!(read_linear(&v, 1, &[1.0]), None);
        assert_eq!(read_linear(&v, 5, &[1.0, 1.0]), None);
        assert_eq!(read_linear(&[f64::INFINITY, 1.0], 1, &[1.0, 1.0]), None);
    }

    #[test]
    fn rejects_points_at_infinity_and_bad_input() {
        let mut out = [0.0; 2];
        assert!(read_unknowns(
            &[0.5, 1.0],
            1,
            &[&[(1, 0)], &[(1, 1)]],
            &mut out
        ));
        assert_eq!(out, [0.5, 1.0]);
        assert!(!read_unknowns(
            &[1.0, 1e-13],
            1,
            &[&[(1, 0)], &[(1, 1)]],
            &mut out
        ));
        assert!(!read_unknowns(
            &[1.0, f64::NAN],
            1,
            &[&[(1, 0)], &[(1, 1)]],
            &mut out
        ));
        assert!(!read_unknowns(
            &[1.0, 0.5],
            1,
            &[&[(1, 7)], &[(1, 1)]],
            &mut out
        ));
        assert!(!read_unknowns(&[1.0, 0.5], 1, &[&[(1, 0)]], &mut out));
        // 0 / 0 in a combination whose denominators all vanish.
        assert!(!read_unknowns(
            &[0.0, 0.5],
            1,
            &[&[(0, 0), (0, 0)], &[(1, 1)]],
            &mut out
        ));
    }
}
