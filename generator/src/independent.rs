//! A linearly independent subset of a system's equations (the stage between `eliminate`
//! and the Gröbner work).
//!
//! Equations that are linear combinations of others, with coefficients that do not involve
//! the unknowns, add nothing to the ideal, to the monomial multiples a template is built
//! from, or to the solutions: every multiple `m f` of such an `f` is the same combination
//! of the multiples `m g_i`. They are common: the maximal minors after `eliminate` (all
//! `C(rows, columns)` of them, of which `rows - columns + 1` span the rest when the matrix
//! has a column of data only, as for an absolute pose's translation), or all three rows
//! of a cross product `x × P = 0` (the third is `-(x1 r1 + x2 r2)`). Keeping them would
//! multiply the work of every later stage and the code emitted for their coefficients.
//!
//! The subset is chosen on one random instance mod p, greedily in order of total degree,
//! then number of terms, then index (simple equations first), and confirmed on a second
//! instance: the kept equations must be independent there and span every equation. A
//! dependency that holds on two random instances holds for the data family but with
//! probability about degree / p.

use crate::algebra::{Fp, Monomial, Poly};
use crate::template::linalg::EchelonBasis;
use std::collections::HashMap;

/// The indices of a linearly independent subset of `first`'s equations that spans them
/// all, confirmed on `second` (the same system on another instance; see the module
/// documentation). `None` when every equation is needed (nothing to drop) or the two
/// instances disagree.
pub fn independent_subset<const P: u32>(
    first: &[Poly<Fp<P>>],
    second: &[Poly<Fp<P>>],
) -> Option<Vec<usize>> {
    if first.len() != second.len() || first.is_empty() {
        return None;
    }
    let mut order: Vec<usize> = (0..first.len()).collect();
    order.sort_by_key(|&i| (first[i].degree().unwrap_or(0), first[i].len(), i));
    let (rows, ncols) = coefficient_rows(first);
    let mut basis = EchelonBasis::<P>::new(ncols);
    let mut kept: Vec<usize> = order
        .into_iter()
        .filter(|&i| basis.insert(rows[i].clone()))
        .collect();
    if kept.len() == first.len() {
        return None;
    }
    kept.sort_unstable();
    // On the second instance: the kept equations independent, and no other equation
    // outside their span.
    let (rows, ncols) = coefficient_rows(second);
    let mut basis = EchelonBasis::<P>::new(ncols);
    if !kept.iter().all(|&i| basis.insert(rows[i].clone())) {
        return None;
    }
    let spans_all = (0..rows.len())
        .filter(|i| kept.binary_search(i).is_err())
        .all(|i| !basis.insert(rows[i].clone()));
    spans_all.then_some(kept)
}

/// Each equation's coefficients over the monomials of the whole system (a column per
/// monomial, in order of first appearance), and the number of columns.
fn coefficient_rows<const P: u32>(equations: &[Poly<Fp<P>>]) -> (Vec<Vec<u32>>, usize) {
    let mut columns: HashMap<&Monomial, usize> = HashMap::new();
    for e in equations {
        for (m, _) in e.terms() {
            let next = columns.len();
            columns.entry(m).or_insert(next);
        }
    }
    let ncols = columns.len();
    let rows = equations
        .iter()
        .map(|e| {
            let mut row = vec![0u32; ncols];
            for (m, c) in e.terms() {
                row[columns[m]] = c.value();
            }
            row
        })
        .collect();
    (rows, ncols)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::P1;

    type F = Fp<P1>;

    fn poly(terms: &[(&[u16], i64)]) -> Poly<F> {
        let mut p = Poly::zero(2);
        for (e, c) in terms {
            p.add_term(Monomial(e.to_vec()), F::new(*c));
        }
        p
    }

    #[test]
    fn a_combination_of_other_equations_is_dropped_and_the_rest_kept() {
        // f0 = x^2 + y, f1 = x y - 1, f2 = 2 f0 - 3 f1 (dependent), f3 = 0.
        let system = |a: i64| {
            let f0 = poly(&[(&[2, 0], 1), (&[0, 1], a)]);
            let f1 = poly(&[(&[1, 1], 1), (&[0, 0], -1)]);
            let mut f2 = Poly::zero(2);
            for (m, c) in f0.terms() {
                f2.add_term(m.clone(), *c * F::new(2));
            }
            for (m, c) in f1.terms() {
                f2.add_term(m.clone(), *c * F::new(-3));
            }
            vec![f0, f1, f2, Poly::zero(2)]
        };
        assert_eq!(independent_subset(&system(5), &system(7)), Some(vec![0, 1]));
    }

    #[test]
    fn independent_equations_are_all_needed() {
        let s = vec![
            poly(&[(&[2, 0], 1), (&[0, 1], 1)]),
            poly(&[(&[1, 1], 1), (&[0, 0], -1)]),
        ];
        assert_eq!(independent_subset(&s, &s), None);
    }

    #[test]
    fn a_dependency_that_the_second_instance_breaks_keeps_everything() {
        let first = vec![
            poly(&[(&[1, 0], 1)]),
            poly(&[(&[1, 0], 2)]),
            poly(&[(&[0, 1], 1)]),
        ];
        let second = vec![
            poly(&[(&[1, 0], 1)]),
            poly(&[(&[1, 0], 2), (&[0, 0], 1)]),
            poly(&[(&[0, 1], 1)]),
        ];
        assert_eq!(independent_subset(&first, &second), None);
    }
}
