//! The Newton polytope of a system, for candidate pools shaped like it (the polytope-based
//! multiplier sets of sparse-resultant solvers: Bhayani, Kukelova and Heikkilä, CVPR 2020).
//!
//! Equations whose monomials fill a polytope other than a simplex or a box (e.g. `x^a y^b`
//! with `a <= 2 b`, `b <= 3`) have far fewer solutions than their degrees say, and the
//! multiples that keep inside a dilate of their polytope reach only the monomials such a
//! template needs, where a total degree or a box holds many more. The polytope is
//! described by its facets `n . a <= h` with primitive integer normals `n`; a pool raises
//! some facets' `h` and takes the multiples whose every monomial stays inside.

use crate::algebra::{Field, Fp, Monomial, MonomialOrder, Poly, P1};
use crate::template::linalg::EchelonBasis;

/// Most unknowns whose Newton polytope is computed: the facet normals are searched among
/// the integer vectors of entries `-2..=2`, `5^n` of them.
pub(crate) const MAX_POLYTOPE_UNKNOWNS: usize = 4;

/// Largest absolute entry of a facet normal searched.
const NORMAL_ENTRY: i32 = 2;

/// A facet of a polytope: every point `a` of it has `normal . a <= support`, with equality
/// on an `(n - 1)`-dimensional face.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Facet {
    /// Primitive integer normal, pointing out of the polytope.
    pub(crate) normal: Vec<i32>,
    /// Largest value of `normal . a` over the polytope.
    pub(crate) support: i64,
}

/// `n . a` for a monomial's exponents `a`.
pub(crate) fn dot(normal: &[i32], m: &Monomial) -> i64 {
    normal
        .iter()
        .zip(&m.0)
        .map(|(&n, &e)| i64::from(n) * i64::from(e))
        .sum()
}

/// The facets of the convex hull of the equations' monomials whose normals have entries in
/// `-2..=2`, in increasing order; `None` for more than [`MAX_POLYTOPE_UNKNOWNS`] unknowns or
/// a hull that is not full-dimensional (no facet bounds it). Facets with other normals are
/// missed, so the facets found may bound a larger polytope than the hull (or none: pools
/// add a total degree as a guard).
pub(crate) fn newton_facets<F: Field>(eqs: &[Poly<F>]) -> Option<Vec<Facet>> {
    let n = eqs.first()?.nvars();
    if n == 0 || n > MAX_POLYTOPE_UNKNOWNS {
        return None;
    }
    let mut points: Vec<Monomial> = eqs
        .iter()
        .flat_map(|f| f.terms().map(|(m, _)| m.clone()))
        .collect();
    points.sort();
    points.dedup();
    if affine_rank(&points) < n {
        return None;
    }
    let mut facets = Vec::new();
    for normal in normals(n) {
        let support = points.iter().map(|m| dot(&normal, m)).max()?;
        let face: Vec<Monomial> = points
            .iter()
            .filter(|m| dot(&normal, m) == support)
            .cloned()
            .collect();
        if affine_rank(&face) == n - 1 {
            facets.push(Facet { normal, support });
        }
    }
    facets.sort();
    Some(facets)
}

/// The primitive integer vectors of `n` entries in `-2..=2` (gcd of the entries 1).
fn normals(n: usize) -> Vec<Vec<i32>> {
    let width = (2 * NORMAL_ENTRY + 1) as usize;
    let total = width.pow(n as u32);
    (0..total)
        .map(|mut code| {
            (0..n)
                .map(|_| {
                    let e = (code % width) as i32 - NORMAL_ENTRY;
                    code /= width;
                    e
                })
                .collect::<Vec<i32>>()
        })
        .filter(|v| v.iter().fold(0, |g, &x| gcd(g, x.unsigned_abs())) == 1)
        .collect()
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Dimension of the affine hull of the points (rank of their differences to the first,
/// computed mod p: exact for the small exponents of equations).
fn affine_rank(points: &[Monomial]) -> usize {
    let Some(first) = points.first() else {
        return 0;
    };
    let n = first.nvars();
    let mut basis = EchelonBasis::<P1>::new(n);
    let mut rank = 0;
    for p in &points[1..] {
        let row: Vec<u32> =
            p.0.iter()
                .zip(&first.0)
                .map(|(&a, &b)| Fp::<P1>::new(i64::from(a) - i64::from(b)).value())
                .collect();
        if basis.insert(row) {
            rank += 1;
        }
    }
    rank
}

/// The monomials `m` of total degree at most `degree` with `facet.normal . m <= bound` for
/// each facet and its bound, descending grevlex.
pub(crate) fn monomials_inside(
    nvars: usize,
    facets: &[Facet],
    bounds: &[i64],
    degree: u32,
) -> Vec<Monomial> {
    Monomial::all_up_to_degree(nvars, degree, MonomialOrder::Grevlex)
        .into_iter()
        .filter(|m| {
            facets
                .iter()
                .zip(bounds)
                .all(|(f, &b)| dot(&f.normal, m) <= b)
        })
        .collect()
}

/// The multipliers `m` of `f` whose product keeps every monomial inside the facets'
/// `bounds` and within total degree `degree` (see [`monomials_inside`]).
pub(crate) fn multipliers_inside<F: Field>(
    f: &Poly<F>,
    facets: &[Facet],
    bounds: &[i64],
    degree: u32,
) -> Vec<Monomial> {
    let Some(df) = f.degree() else {
        return Vec::new();
    };
    let Some(room) = degree.checked_sub(df) else {
        return Vec::new();
    };
    let shifted: Vec<i64> = facets
        .iter()
        .zip(bounds)
        .map(|(facet, &b)| {
            b - f
                .terms()
                .map(|(m, _)| dot(&facet.normal, m))
                .max()
                .unwrap_or(0)
        })
        .collect();
    monomials_inside(f.nvars(), facets, &shifted, room)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::Ring;

    type F = Fp<P1>;

    /// The stitching problem's support: `x^a y^b` with `b <= 3`, `a <= 2 b` (16 monomials).
    fn triangle() -> Vec<Poly<F>> {
        let mut f = Poly::zero(2);
        for b in 0..=3u16 {
            for a in 0..=2 * b {
                f.add_term(Monomial(vec![a, b]), F::one());
            }
        }
        vec![f.clone(), f]
    }

    #[test]
    fn a_triangle_has_three_facets() {
        let facets = newton_facets(&triangle()).unwrap();
        let found: Vec<(Vec<i32>, i64)> = facets
            .iter()
            .map(|f| (f.normal.clone(), f.support))
            .collect();
        assert_eq!(
            found,
            vec![(vec![-1, 0], 0), (vec![0, 1], 3), (vec![1, -2], 0)]
        );
        let bounds: Vec<i64> = facets.iter().map(|f| f.support).collect();
        assert_eq!(monomials_inside(2, &facets, &bounds, 20).len(), 16);
        // Raised by two on y <= 3: nine multipliers of each equation, 36 monomials.
        let raised = [0, 5, 0];
        assert_eq!(monomials_inside(2, &facets, &raised, 20).len(), 36);
        let m = multipliers_inside(&triangle()[0], &facets, &raised, 20);
        assert_eq!(m.len(), 9);
        assert!(m.iter().all(|m| m.0[1] <= 2 && m.0[0] <= 2 * m.0[1]));
    }

    #[test]
    fn a_flat_support_has_no_polytope() {
        // Homogeneous: every monomial of degree 2.
        let mut f = Poly::<F>::zero(2);
        for a in 0..=2u16 {
            f.add_term(Monomial(vec![a, 2 - a]), F::one());
        }
        assert!(newton_facets(&[f]).is_none());
    }
}
