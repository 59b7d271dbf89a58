//! Reading the unknowns off an eigenvector of the action matrix.

/// A ratio of eigenvector entries (unit vectors) is accurate only if its denominator (for
/// several pairs, the root of the sum of their squares) exceeds this: an eigenvector
/// accurate to `e` gives the ratio to about `e / |denominator|`. Below it the ratio is
/// still read (a real eigenvector of a quotient basis's action matrix is a solution, and a
/// solution far from the origin has tiny low-degree entries; the polishing on the original
/// equations, where the plan chooses it, restores its accuracy), but the eigenvalue is
/// preferred for the action's own unknown, and only an exactly zero denominator or a
/// non-finite ratio skips the eigenvector.
pub const MIN_UNIT_ENTRY: f64 = 1e-12;

/// Reads every unknown off the unit eigenvector `v ∝ (b_0(s), ..., b_{n-1}(s))` of the
/// action matrix into `out` (one entry per element of `pairs`); `false` (skip this
/// eigenvector) if `v[one]` (the basis monomial 1) is not finite, if an unknown's
/// denominators are all zero, or if an unknown is not finite (a denominator at most
/// [`MIN_UNIT_ENTRY`] gives a less accurate ratio, see there).
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
/// pairs cannot be read accurately (their denominators at most [`MIN_UNIT_ENTRY`]: a basis
/// shifted by a monomial that is large at this solution, or a solution far from the
/// origin). `None`: exactly [`read_unknowns`]. Never panics.
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
        let eigenvalue = action
            .filter(|&(a, lambda)| a == i && lambda.is_finite())
            .map(|(_, lambda)| lambda);
        let value = match (read_pairs(v, p), eigenvalue) {
            (Some((value, true)), _) | (Some((value, false)), None) => value,
            (_, Some(lambda)) => lambda,
            (None, None) => return false,
        };
        *x = value;
    }
    true
}

/// One unknown from its pairs (see [`read_unknowns`]) and whether its denominator exceeds
/// [`MIN_UNIT_ENTRY`] (the ratio is accurate); `None` for a zero denominator, an index out
/// of range or a non-finite value.
#[inline]
fn read_pairs(v: &[f64], p: &[(usize, usize)]) -> Option<(f64, bool)> {
    let (value, accurate) = match *p {
        [(j, k)] => {
            let (a, b) = (*v.get(j)?, *v.get(k)?);
            (b / a, a.abs() > MIN_UNIT_ENTRY)
        }
        _ => {
            let (mut num, mut den) = (0.0, 0.0);
            for &(j, k) in p {
                let (a, b) = (v.get(j)?, v.get(k)?);
                num += a * b;
                den += a * a;
            }
            (num / den, den > MIN_UNIT_ENTRY * MIN_UNIT_ENTRY)
        }
    };
    // Also `None` for 0 / 0 and x / 0.
    value.is_finite().then_some((value, accurate))
}

/// Reads an unknown `x` that is not in the basis off the unit eigenvector `v ∝ (b_0(s),
/// ..., b_{n-1}(s))` through its reduced template row `x + sum_k row[k] b_k` (a linear
/// equation makes `x` a combination of basis monomials): `x = -sum_k row[k] v[k] / v[one]`
/// (less accurate where `|v[one]|` is at most [`MIN_UNIT_ENTRY`], see there). `None` (skip
/// this eigenvector) if `v[one]` is zero or not finite, if the lengths differ, or if the
/// value is not finite. Never panics.
#[inline]
pub fn read_linear(v: &[f64], one: usize, row: &[f64]) -> Option<f64> {
    let w = *v.get(one)?;
    if !w.is_finite() || row.len() != v.len() {
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
        // pair of a, (p, a p), has a denominator below MIN_UNIT_ENTRY, so the ratio is read
        // (roughly: the entries carry an error of 1e-20) unless `a` is the action, whose
        // eigenvalue is exact.
        let (p, a) = (1e8f64, 0.5);
        let n = (p.powi(6) + p * p + a * a * p * p).sqrt();
        let v = [p.powi(3) / n, p / n, a * p / n + 1e-20];
        assert!(v[1] < MIN_UNIT_ENTRY);
        let pairs: [&[(usize, usize)]; 1] = [&[(1, 2)]];
        let mut out = [0.0];
        assert!(read_unknowns(&v, 1, &pairs, &mut out));
        assert!((out[0] - a).abs() < 1e-3 && out[0] != a, "{out:?}");
        // Another unknown's eigenvalue does not stand in for it.
        let mut other = [0.0];
        assert!(read_unknowns_with_eigenvalue(
            &v,
            1,
            &pairs,
            Some((1, 0.25)),
            &mut other
        ));
        assert_eq!(other, out);
        assert!(read_unknowns_with_eigenvalue(
            &v,
            1,
            &pairs,
            Some((0, a)),
            &mut out
        ));
        assert_eq!(out, [a]);
        // An accurate ratio is preferred to the eigenvalue.
        let mut near = [0.0];
        assert!(read_unknowns_with_eigenvalue(
            &[0.6, 0.8],
            0,
            &[&[(0, 1)]],
            Some((0, 1.0)),
            &mut near
        ));
        assert!((near[0] - 0.8 / 0.6).abs() < 1e-15, "{near:?}");
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
        // Basis (x^4, x^3, x^2, x, 1) at x = 1e4: v[1] is 1e-16, below MIN_UNIT_ENTRY; the
        // pairs (x^k, x^{k+1}) with large x^k read x accurately.
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
        // The single pair (1, x) reads x from a denominator of 1e-16: roughly in general,
        // exactly here (the entries carry no error).
        assert!(read_unknowns(&v, 4, &[&[(4, 3)]], &mut out));
        assert!((out[0] - x).abs() < 1e-9 * x, "{out:?}");
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
        assert_eq!(read_linear(&[1.0, 0.0], 1, &[1.0, 1.0]), None);
        // A unit entry below MIN_UNIT_ENTRY still reads (a far solution).
        let far = read_linear(&[1.0, 1e-13], 1, &[1.0, 0.0]).unwrap();
        assert!((far + 1e13).abs() < 1.0, "{far}");
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
            &[1.0, 0.0],
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
