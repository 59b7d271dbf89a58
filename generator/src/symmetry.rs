//! Sign symmetry (Larsson and Åström, ECCV 2016; ARCHITECTURE §2, "Sign symmetry"):
//! systems whose solutions come in pairs `x` and `-x` on a set of unknowns, solved at half
//! the size.
//!
//! A set `S` of the system's variables is a *sign symmetry* when every equation is even or
//! odd in them: all its monomials have the same parity of their total degree in `S`. Then
//! flipping the signs of `S` maps solutions to solutions. Folding by a pivot `x_p` of `S`
//! replaces `x_p` by `s = x_p²` and each other `x_j` of `S` by `t_j = x_j / x_p`: a monomial
//! `x^e` with degree `k` in `S` becomes `x_p^k t^e`, i.e. `s^(k/2) t^e` for even `k` and
//! `x_p s^((k-1)/2) t^e` for odd `k`, where the odd equations lose their common factor
//! `x_p`. The folded system has one solution per pair (when no solution has `x_p = 0`,
//! which [`crate::rewrite::sign_fold_alternatives`] checks), so its template and action are
//! built for half the count; the solver recovers both signs
//! ([`mingen_runtime::unfold_signs`]). The variables keep their positions, so everything
//! downstream (template, read-out, elimination) works on the folded system unchanged.

use crate::algebra::{Monomial, Poly, Ring};

/// One fold (see the module documentation), in the system's variable indices.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct SignFold {
    /// The variable whose square replaces it.
    pub pivot: usize,
    /// The other variables of the symmetry, each replaced by its ratio to the pivot
    /// (increasing).
    pub scaled: Vec<usize>,
}

impl SignFold {
    /// The monomial `x^e` folded: the pivot's exponent becomes half (rounded down) of the
    /// total degree in the symmetry's variables, the scaled variables keep theirs.
    pub fn fold_monomial(&self, m: &Monomial) -> Monomial {
        let mut e = m.0.clone();
        let k: u32 = std::iter::once(&self.pivot)
            .chain(&self.scaled)
            .map(|&j| u32::from(m.0[j]))
            .sum();
        e[self.pivot] = (k / 2) as crate::algebra::Exponent;
        Monomial(e)
    }

    /// `p` with every monomial folded (terms that fold together are added).
    pub fn fold_poly<C: Ring>(&self, p: &Poly<C>) -> Poly<C> {
        let mut out = Poly::zero(p.nvars());
        for (m, c) in p.terms() {
            out.add_term(self.fold_monomial(m), c.clone());
        }
        out
    }

    /// The solutions of the unfolded variables from one solution `w` of the folded system:
    /// none, or the pair `x_p = ±√s` (see [`mingen_runtime::unfold_sign`]).
    pub fn unfold(&self, w: &[f64]) -> Vec<Vec<f64>> {
        // Hidden variables of the symmetry are not part of a solution.
        let scaled: Vec<usize> = self
            .scaled
            .iter()
            .copied()
            .filter(|&j| j < w.len())
            .collect();
        let fold = (self.pivot, scaled.as_slice());
        let mut plus = w.to_vec();
        if !mingen_runtime::unfold_sign(&mut plus, fold) {
            return Vec::new();
        }
        let mut minus = plus.clone();
        mingen_runtime::flip_sign(&mut minus, fold);
        vec![plus, minus]
    }

    /// The variables of the symmetry: the pivot and the scaled ones, increasing.
    pub fn variables(&self) -> Vec<usize> {
        let mut v: Vec<usize> = std::iter::once(self.pivot)
            .chain(self.scaled.iter().copied())
            .collect();
        v.sort_unstable();
        v
    }
}

/// The solutions of the original variables from one solution `w` of a system folded by
/// `folds` (in the order they were applied; undone in reverse): `2^folds.len()` vectors at
/// most, none when a square is not positive.
pub fn unfold_all(folds: &[SignFold], w: &[f64]) -> Vec<Vec<f64>> {
    folds.iter().rev().fold(vec![w.to_vec()], |acc, f| {
        acc.iter().flat_map(|x| f.unfold(x)).collect()
    })
}

/// The sign symmetries of equations with the monomials `supports` (in `nvars` variables,
/// at most 32): a basis of the variable sets `S`, as bit masks, for which every equation
/// has monomials of one parity of degree in `S`, i.e. the null space over GF(2) of the
/// parity differences of each equation's monomials. One null vector per free variable of
/// the reduced echelon form, in variable order, so deterministic. Empty for more than 32
/// variables.
pub(crate) fn sign_symmetries(supports: &[Vec<Monomial>], nvars: usize) -> Vec<u32> {
    if nvars > 32 || nvars == 0 {
        return Vec::new();
    }
    let parity = |m: &Monomial| -> u32 {
        m.0.iter()
            .enumerate()
            .filter(|(_, &e)| e % 2 == 1)
            .fold(0u32, |acc, (i, _)| acc | (1 << i))
    };
    // Constraints: sigma . (parity(m) ^ parity(m0)) = 0 over GF(2).
    let mut rows: Vec<u32> = Vec::new();
    for support in supports {
        let mut terms = support.iter().map(parity);
        let Some(first) = terms.next() else { continue };
        rows.extend(terms.map(|q| q ^ first).filter(|&r| r != 0));
    }
    // Reduced row echelon form over GF(2), pivots on the lowest set bit.
    let mut basis: Vec<(usize, u32)> = Vec::new();
    for mut r in rows {
        for &(b, v) in &basis {
            if r >> b & 1 == 1 {
                r ^= v;
            }
        }
        if r == 0 {
            continue;
        }
        let b = r.trailing_zeros() as usize;
        for (_, v) in basis.iter_mut() {
            if *v >> b & 1 == 1 {
                *v ^= r;
            }
        }
        basis.push((b, r));
    }
    let pivots: u32 = basis.iter().fold(0, |acc, &(b, _)| acc | (1 << b));
    // One null vector per free variable f: x_f = 1, each pivot variable b = row_b's bit f.
    (0..nvars)
        .filter(|&f| pivots >> f & 1 == 0)
        .map(|f| {
            basis
                .iter()
                .filter(|(_, v)| v >> f & 1 == 1)
                .fold(1u32 << f, |acc, &(b, _)| acc | (1 << b))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Fp, Ring, P1};

    type F = Fp<P1>;

    fn poly(nvars: usize, terms: &[(&[u16], i64)]) -> Poly<F> {
        Poly::from_terms(
            nvars,
            terms
                .iter()
                .map(|(e, c)| (Monomial(e.to_vec()), F::from_i64(*c))),
        )
    }

    fn supports(eqs: &[Poly<F>]) -> Vec<Vec<Monomial>> {
        eqs.iter()
            .map(|p| p.terms().map(|(m, _)| m.clone()).collect())
            .collect()
    }

    #[test]
    fn p3p_like_system_is_symmetric_in_all_depths() {
        // x² - 2xy + y² - 1, x² + z² - 2, y z - 3: even in {x, y, z} only.
        let eqs = vec![
            poly(
                3,
                &[
                    (&[2, 0, 0], 1),
                    (&[1, 1, 0], -2),
                    (&[0, 2, 0], 1),
                    (&[0, 0, 0], -1),
                ],
            ),
            poly(3, &[(&[2, 0, 0], 1), (&[0, 0, 2], 1), (&[0, 0, 0], -2)]),
            poly(3, &[(&[0, 1, 1], 1), (&[0, 0, 0], -3)]),
        ];
        assert_eq!(sign_symmetries(&supports(&eqs), 3), vec![0b111]);
    }

    #[test]
    fn independent_symmetries_and_none() {
        // x² - 1, y z - 1: {x} and {y, z}.
        let eqs = vec![
            poly(3, &[(&[2, 0, 0], 1), (&[0, 0, 0], -1)]),
            poly(3, &[(&[0, 1, 1], 1), (&[0, 0, 0], -1)]),
        ];
        let s = sign_symmetries(&supports(&eqs), 3);
        assert_eq!(s.len(), 2);
        assert!(s.contains(&0b001) && s.contains(&0b110));
        // x + y - 1 has none.
        let eqs = vec![poly(2, &[(&[1, 0], 1), (&[0, 1], 1), (&[0, 0], -1)])];
        assert!(sign_symmetries(&supports(&eqs), 2).is_empty());
    }

    #[test]
    fn odd_equations_lose_the_pivot() {
        // x y² + x³ (odd in {x, y}) folded by x: s t² + s.
        let f = SignFold {
            pivot: 0,
            scaled: vec![1],
        };
        let p = poly(2, &[(&[1, 2], 1), (&[3, 0], 1)]);
        assert_eq!(f.fold_poly(&p), poly(2, &[(&[1, 2], 1), (&[1, 0], 1)]));
        // Even: x² - 2 x y + 5 becomes s - 2 s t + 5.
        let p = poly(2, &[(&[2, 0], 1), (&[1, 1], -2), (&[0, 0], 5)]);
        assert_eq!(
            f.fold_poly(&p),
            poly(2, &[(&[1, 0], 1), (&[1, 1], -2), (&[0, 0], 5)])
        );
    }

    #[test]
    fn unfold_recovers_both_signs() {
        let f = SignFold {
            pivot: 1,
            scaled: vec![0],
        };
        // x = (6, -2): s = 4, t = -3.
        let got = unfold_all(&[f], &[-3.0, 4.0]);
        assert_eq!(got, vec![vec![-6.0, 2.0], vec![6.0, -2.0]]);
    }
}
