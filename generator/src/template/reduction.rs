//! Row reduction of the equations on their data: the data-dependent elimination a
//! template may start from.
//!
//! The equations of one instance are linear combinations of monomials; their coefficient
//! matrix (one row per equation, one column per monomial, columns descending in grevlex)
//! has a reduced row echelon form whose rows generate the same ideal. Each reduced
//! equation has a pivot monomial no other reduced equation contains, and its other
//! monomials are the non-pivot ones after its pivot, so the reduced equations are sparser
//! in their highest monomials: fewer multiples are needed to eliminate the monomials above
//! the basis, and the template can be much smaller. This is what hand-made solvers do
//! when they "row-reduce the data's coefficient matrix" before building a template.
//!
//! Which monomials are pivots and which entries are non-zero is a property of generic
//! data, read off one random instance (`EquationReduction::of`). Every consumer of the
//! template then reduces its own instance's equations to the same pivots
//! ([`EquationReduction::reduce`] exactly over Z_p, [`EquationReduction::reduce_f64`] by
//! [`mingen_runtime::reduce_equations`] as the emitted solvers do) and fills the template
//! from the reduced equations, whose monomials are [`EquationReduction::supports`].

use crate::algebra::{Field, Fp, Monomial, MonomialOrder, Poly};
use std::collections::{BTreeMap, BTreeSet};
use thiserror::Error;

/// The reduced row echelon form the equations are brought to before filling the template
/// (see the module documentation).
///
/// Convention: `monomials` are the columns of the coefficient matrix `Q` (one row per
/// equation, in equation order): the union of the equations' monomials, descending in
/// grevlex. Reduced equation `k` is row `k` of `A^-1 Q` for `A = Q[:, pivots]`: it has
/// coefficient 1 on `monomials[pivots[k]]`, 0 on the other pivots, and its monomials are
/// `supports[k]`. Template rows refer to reduced equations by `k`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EquationReduction {
    /// Columns of the coefficient matrix: every monomial of the equations, descending.
    pub monomials: Vec<Monomial>,
    /// Pivot column (index into `monomials`) of each reduced equation, increasing.
    pub pivots: Vec<usize>,
    /// Monomials (indices into `monomials`, increasing; the pivot first) of each reduced
    /// equation on generic data.
    pub supports: Vec<Vec<usize>>,
}

/// Why an instance's equations cannot be reduced as planned.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum ReductionError {
    /// The instance has another number of equations than the reduction.
    #[error("the instance has {found} equations, the equation reduction {expected}")]
    EquationCount {
        /// Equations of the instance.
        found: usize,
        /// Equations of the reduction.
        expected: usize,
    },
    /// An equation has a monomial the generic equations do not have.
    #[error(
        "equation {equation} has the monomial {monomial:?}, which generic instances do not have"
    )]
    UnexpectedMonomial {
        /// The equation.
        equation: usize,
        /// The monomial.
        monomial: Monomial,
    },
    /// The pivot block is singular on this instance (or not finite).
    #[error(
        "the equations cannot be row-reduced to the planned pivots on this instance (singular)"
    )]
    Singular,
    /// A reduced equation has a non-zero coefficient outside its generic monomials: the
    /// instance is not of the family the reduction was read from.
    #[error("reduced equation {equation} has the monomial {monomial:?}, which generic instances do not have")]
    OutsideSupport {
        /// The reduced equation.
        equation: usize,
        /// The monomial.
        monomial: Monomial,
    },
}

impl EquationReduction {
    /// The reduction of the equations `eqs` of one generic instance mod P, with the reduced
    /// equations; `None` when it would not change which monomials the equations have (so
    /// not the template) or when the equations are linearly dependent.
    pub(crate) fn of<const P: u32>(eqs: &[Poly<Fp<P>>]) -> Option<(Self, Vec<Poly<Fp<P>>>)> {
        let nvars = eqs.first()?.nvars();
        let set: BTreeSet<Monomial> = eqs
            .iter()
            .flat_map(|e| e.terms().map(|(m, _)| m.clone()))
            .collect();
        let mut monomials: Vec<Monomial> = set.into_iter().collect();
        monomials.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
        let index: BTreeMap<&Monomial, usize> =
            monomials.iter().enumerate().map(|(i, m)| (m, i)).collect();
        let mut q: Vec<Vec<Fp<P>>> = eqs
            .iter()
            .map(|e| {
                let mut row = vec![Fp(0); monomials.len()];
                for (m, c) in e.terms() {
                    row[index[m]] = *c;
                }
                row
            })
            .collect();
        // Which monomials each equation has, as column indices (increasing).
        let supports_of = |q: &[Vec<Fp<P>>]| -> Vec<Vec<usize>> {
            q.iter()
                .map(|row| (0..row.len()).filter(|&j| row[j].0 != 0).collect())
                .collect()
        };
        let mut before = supports_of(&q);
        let pivots = row_echelon(&mut q)?;
        let supports = supports_of(&q);
        let mut after = supports.clone();
        before.sort();
        after.sort();
        if before == after {
            return None;
        }
        let red = EquationReduction {
            monomials,
            pivots,
            supports,
        };
        let flat: Vec<Fp<P>> = q.into_iter().flatten().collect();
        let reduced = red.polys(nvars, &flat, false).ok()?;
        Some((red, reduced))
    }

    /// Number of equations (reduced and original).
    pub fn len(&self) -> usize {
        self.pivots.len()
    }

    /// Whether there is no equation.
    pub fn is_empty(&self) -> bool {
        self.pivots.is_empty()
    }

    /// Each reduced equation's monomials on generic data, as monomials.
    pub fn reduced_supports(&self) -> Vec<Vec<Monomial>> {
        self.supports
            .iter()
            .map(|s| s.iter().map(|&j| self.monomials[j].clone()).collect())
            .collect()
    }

    /// The coefficient matrix `Q` of an instance's equations (row-major, `len() x
    /// monomials.len()`).
    fn matrix<C: crate::algebra::Ring>(&self, eqs: &[Poly<C>]) -> Result<Vec<C>, ReductionError> {
        if eqs.len() != self.len() {
            return Err(ReductionError::EquationCount {
                found: eqs.len(),
                expected: self.len(),
            });
        }
        let index: BTreeMap<&Monomial, usize> = self
            .monomials
            .iter()
            .enumerate()
            .map(|(i, m)| (m, i))
            .collect();
        let n = self.monomials.len();
        let mut q = vec![C::zero(); eqs.len() * n];
        for (i, e) in eqs.iter().enumerate() {
            for (m, c) in e.terms() {
                let j = *index
                    .get(m)
                    .ok_or_else(|| ReductionError::UnexpectedMonomial {
                        equation: i,
                        monomial: m.clone(),
                    })?;
                q[i * n + j] = c.clone();
            }
        }
        Ok(q)
    }

    /// The reduced equations of `q` (row-major, reduced), keeping the generic monomials
    /// only; with `exact`, a non-zero coefficient elsewhere is an error.
    fn polys<C: crate::algebra::Ring>(
        &self,
        nvars: usize,
        q: &[C],
        exact: bool,
    ) -> Result<Vec<Poly<C>>, ReductionError> {
        let n = self.monomials.len();
        (0..self.len())
            .map(|k| {
                let row = &q[k * n..(k + 1) * n];
                if exact {
                    let mut s = self.supports[k].iter().peekable();
                    for (j, c) in row.iter().enumerate() {
                        if s.peek() == Some(&&j) {
                            s.next();
                        } else if !c.is_zero() {
                            return Err(ReductionError::OutsideSupport {
                                equation: k,
                                monomial: self.monomials[j].clone(),
                            });
                        }
                    }
                }
                Ok(Poly::from_terms(
                    nvars,
                    self.supports[k]
                        .iter()
                        .map(|&j| (self.monomials[j].clone(), row[j].clone())),
                ))
            })
            .collect()
    }

    /// The reduced equations of an instance, exactly (any field, e.g. Z_p).
    pub fn reduce<F: Field>(&self, eqs: &[Poly<F>]) -> Result<Vec<Poly<F>>, ReductionError> {
        let nvars = eqs.first().map_or(0, Poly::nvars);
        let n = self.monomials.len();
        let q = self.matrix(eqs)?;
        let mut rows: Vec<Vec<F>> = q.chunks(n.max(1)).map(<[F]>::to_vec).collect();
        let pivots = row_echelon(&mut rows).ok_or(ReductionError::Singular)?;
        if pivots != self.pivots {
            return Err(ReductionError::Singular);
        }
        let flat: Vec<F> = rows.into_iter().flatten().collect();
        self.polys(nvars, &flat, true)
    }

    /// The reduced equations of an instance in floating point, computed as the emitted
    /// solvers compute them ([`mingen_runtime::reduce_equations`]); coefficients outside
    /// the generic monomials (rounding errors of structural zeros) are dropped.
    pub fn reduce_f64(&self, eqs: &[Poly<f64>]) -> Result<Vec<Poly<f64>>, ReductionError> {
        let nvars = eqs.first().map_or(0, Poly::nvars);
        let mut q = self.matrix(eqs)?;
        if !mingen_runtime::reduce_equations(&mut q, self.monomials.len(), &self.pivots) {
            return Err(ReductionError::Singular);
        }
        self.polys(nvars, &q, false)
    }
}

/// In-place reduced row echelon form over a field, pivots searched column by column;
/// the pivot column of each row, or `None` when the rows are linearly dependent.
fn row_echelon<F: Field>(q: &mut [Vec<F>]) -> Option<Vec<usize>> {
    let ncols = q.first().map_or(0, Vec::len);
    let mut pivots = Vec::with_capacity(q.len());
    let mut r = 0;
    for j in 0..ncols {
        if r == q.len() {
            break;
        }
        let Some(p) = (r..q.len()).find(|&i| !q[i][j].is_zero()) else {
            continue;
        };
        q.swap(r, p);
        let inv = q[r][j].inv()?;
        let pivot_row: Vec<F> = q[r].iter().map(|c| c.mul(&inv)).collect();
        q[r] = pivot_row;
        for i in 0..q.len() {
            if i != r && !q[i][j].is_zero() {
                let f = q[i][j].clone();
                let (a, b) = if i < r {
                    let (h, t) = q.split_at_mut(r);
                    (&mut h[i], &t[0])
                } else {
                    let (h, t) = q.split_at_mut(i);
                    (&mut t[0], &h[r])
                };
                for (x, y) in a.iter_mut().zip(b) {
                    *x = x.sub(&f.mul(y));
                }
            }
        }
        pivots.push(j);
        r += 1;
    }
    (r == q.len()).then_some(pivots)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::P1;

    type F = Fp<P1>;

    fn poly(terms: &[(&[u16], i64)]) -> Poly<F> {
        Poly::from_terms(
            2,
            terms
                .iter()
                .map(|(e, c)| (Monomial(e.to_vec()), F::new(*c))),
        )
    }

    #[test]
    fn reduces_to_pivots_and_agrees_in_floating_point() {
        // x^2 + 2xy + 3 and 2x^2 + xy + y + 1: reduced, x^2 and xy are pivots.
        let eqs = vec![
            poly(&[(&[2, 0], 1), (&[1, 1], 2), (&[0, 0], 3)]),
            poly(&[(&[2, 0], 2), (&[1, 1], 1), (&[0, 1], 1), (&[0, 0], 1)]),
        ];
        let (red, reduced) = EquationReduction::of(&eqs).expect("changes the supports");
        assert_eq!(red.pivots, vec![0, 1]);
        assert_eq!(red.supports, vec![vec![0, 2, 3], vec![1, 2, 3]]);
        assert_eq!(red.reduce(&eqs).unwrap(), reduced);
        let f: Vec<Poly<f64>> = eqs
            .iter()
            .map(|e| e.map_coeffs(|c| c.symmetric() as f64))
            .collect();
        let rf = red.reduce_f64(&f).unwrap();
        // Reduced: x^2 + 2y/3 - 1/3 and xy - y/3 + 5/3.
        let x2 = Monomial(vec![2, 0]);
        assert!((rf[0].coeff(&x2) - 1.0).abs() < 1e-15);
        let y = Monomial(vec![0, 1]);
        assert!((rf[0].coeff(&y) - 2.0 / 3.0).abs() < 1e-15);
        assert!((rf[1].coeff(&y) + 1.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn no_reduction_when_supports_stay() {
        let eqs = vec![
            poly(&[(&[1, 0], 1), (&[0, 0], 3)]),
            poly(&[(&[0, 1], 2), (&[0, 0], 1)]),
        ];
        assert!(EquationReduction::of(&eqs).is_none());
    }
}
