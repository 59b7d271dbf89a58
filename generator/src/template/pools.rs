//! Candidate pools of basis selection: all multiples of the equations up to a total
//! degree, within a *multidegree*, or within a dilate of their Newton polytope
//! ([`super::newton_polytope`]).
//!
//! A multidegree partitions the unknowns into groups and caps each group's degree: every
//! monomial of every multiple keeps the degree of each group within its cap. One group is
//! the total degree; every unknown in a group of its own is a box of exponents. These are
//! the supports of multihomogeneous Macaulay matrices, and they fit equations whose degree
//! differs between unknowns (degree 3 in each of three unknowns but 6 in all, or 3 in a
//! block of unknowns and 6 in another) far better than a total degree does: the total
//! degree that contains such equations' multiples holds many more rows that reach
//! monomials of no use. Their quotient bases are not standard in any order, so only basis
//! selection ([`super::select`]) finds them.

use super::candidates::{binomial, candidate_bytes, candidates, pool_size, Candidate};
use super::newton_polytope::{monomials_inside, multipliers_inside, newton_facets, Facet};
use crate::algebra::{Field, Fp, Monomial, MonomialOrder, Poly};

/// A candidate pool of basis selection.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Pool {
    /// All multiples of the equations up to this total degree.
    TotalDegree(u32),
    /// All multiples whose every monomial has degree at most `caps[g]` in the unknowns of
    /// `groups[g]` (a partition of the unknowns), for every group g.
    Multidegree {
        /// The groups of unknowns (indices), a partition of them.
        groups: Vec<Vec<usize>>,
        /// Each group's largest degree.
        caps: Vec<u32>,
    },
    /// All multiples whose every monomial `a` has `facet.normal . a <= bound` for the
    /// facets of the equations' Newton polytope, each raised above its support, and total
    /// degree at most `degree` (a guard: the facets found may not bound).
    Polytope {
        /// The facets ([`newton_facets`]).
        facets: Vec<Facet>,
        /// How far each facet is raised above its support.
        raise: Vec<u32>,
        /// The total degree guard.
        degree: u32,
    },
}

/// The families of pools that basis selection searches one after the other (each until
/// a pool of it gives a basis): the total degree, each partition of the unknowns, the
/// Newton polytope.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum PoolFamily {
    /// [`Pool::TotalDegree`].
    TotalDegree,
    /// [`Pool::Multidegree`] with this partition.
    Partition(Vec<Vec<usize>>),
    /// [`Pool::Polytope`].
    Polytope,
}

impl Pool {
    /// The pool's family and size (the total degree, the sum of the caps or of the
    /// raises): basis selection tries a family's pools by increasing size and stops after
    /// the first size that gives a template.
    pub(crate) fn family_and_size(&self) -> (PoolFamily, u32) {
        match self {
            Pool::TotalDegree(d) => (PoolFamily::TotalDegree, *d),
            Pool::Multidegree { groups, caps } => {
                (PoolFamily::Partition(groups.clone()), caps.iter().sum())
            }
            Pool::Polytope { raise, .. } => (PoolFamily::Polytope, raise.iter().sum()),
        }
    }

    /// The facets' raised bounds of a [`Pool::Polytope`], each at least large enough to
    /// hold 1 and the unknowns (a selected basis contains them, `super::select`).
    fn bounds(facets: &[Facet], raise: &[u32]) -> Vec<i64> {
        facets
            .iter()
            .zip(raise)
            .map(|(f, &r)| {
                let unit = f.normal.iter().map(|&n| i64::from(n)).max().unwrap_or(0);
                (f.support + i64::from(r)).max(unit).max(0)
            })
            .collect()
    }

    /// "all multiples up to degree 7", "all multiples within degrees 3 in w, x, y; 6 in z".
    pub(crate) fn describe(&self, names: &[String]) -> String {
        match self {
            Pool::TotalDegree(d) => format!("all multiples up to degree {d}"),
            Pool::Multidegree { groups, caps } => {
                let name = |i: usize| names.get(i).cloned().unwrap_or_else(|| format!("x{i}"));
                let parts: Vec<String> = groups
                    .iter()
                    .zip(caps)
                    .map(|(g, c)| {
                        let vars: Vec<String> = g.iter().map(|&i| name(i)).collect();
                        format!("{c} in {}", vars.join(", "))
                    })
                    .collect();
                format!("all multiples within degrees {}", parts.join("; "))
            }
            Pool::Polytope { raise, .. } => {
                let r: Vec<String> = raise.iter().map(|r| r.to_string()).collect();
                format!(
                    "all multiples within the Newton polytope, facets raised by {}",
                    r.join(", ")
                )
            }
        }
    }

    /// Number of candidate rows.
    pub(crate) fn rows<F: Field>(&self, eqs: &[Poly<F>]) -> u64 {
        match self {
            Pool::TotalDegree(d) => pool_size(eqs, *d, &[]),
            Pool::Multidegree { groups, caps } => eqs
                .iter()
                .filter_map(|f| room(f, groups, caps))
                .map(|room| monomials_within(groups, &room))
                .fold(0u64, u64::saturating_add),
            Pool::Polytope {
                facets,
                raise,
                degree,
            } => {
                let bounds = Pool::bounds(facets, raise);
                eqs.iter()
                    .map(|f| multipliers_inside(f, facets, &bounds, *degree).len() as u64)
                    .fold(0u64, u64::saturating_add)
            }
        }
    }

    /// Estimated bytes of the candidates and of their dense matrix.
    pub(crate) fn bytes<const P: u32>(&self, eqs: &[Poly<Fp<P>>]) -> u64 {
        match self {
            Pool::TotalDegree(d) => candidate_bytes(eqs, *d, &[]),
            Pool::Multidegree { .. } | Pool::Polytope { .. } => {
                let cols = self.columns(eqs);
                let terms = eqs.iter().map(|f| f.len() as u64).max().unwrap_or(0);
                self.rows(eqs)
                    .saturating_mul(cols.saturating_mul(4).saturating_add(terms * 48))
            }
        }
    }

    /// Number of columns (the monomials a multiple may have).
    fn columns<F: Field>(&self, eqs: &[Poly<F>]) -> u64 {
        let n = eqs.first().map_or(0, |f| f.nvars());
        match self {
            Pool::TotalDegree(d) => binomial(n as u64 + u64::from(*d), n as u64),
            Pool::Multidegree { groups, caps } => monomials_within(groups, caps),
            Pool::Polytope {
                facets,
                raise,
                degree,
            } => monomials_inside(n, facets, &Pool::bounds(facets, raise), *degree).len() as u64,
        }
    }

    /// The candidate rows, equation by equation, multipliers descending in grevlex.
    pub(crate) fn candidates<const P: u32>(&self, eqs: &[Poly<Fp<P>>]) -> Vec<Candidate> {
        let (groups, caps) = match self {
            Pool::TotalDegree(d) => return candidates(eqs, *d, &[]),
            Pool::Multidegree { groups, caps } => (groups, caps),
            Pool::Polytope {
                facets,
                raise,
                degree,
            } => {
                let bounds = Pool::bounds(facets, raise);
                let mut out = Vec::new();
                for (i, f) in eqs.iter().enumerate() {
                    let df = f.degree().unwrap_or(0);
                    for m in multipliers_inside(f, facets, &bounds, *degree) {
                        let d = df + m.degree();
                        out.push(Candidate::multiple(i, f, m, d));
                    }
                }
                return out;
            }
        };
        let mut out = Vec::new();
        for (i, f) in eqs.iter().enumerate() {
            let Some(room) = room(f, groups, caps) else {
                continue;
            };
            let df = f.degree().unwrap_or(0);
            for m in multipliers(f.nvars(), groups, &room) {
                let degree = df + m.degree();
                out.push(Candidate::multiple(i, f, m, degree));
            }
        }
        out
    }
}

/// The number of monomials of degree at most `caps[g]` in each group g.
fn monomials_within(groups: &[Vec<usize>], caps: &[u32]) -> u64 {
    groups.iter().zip(caps).fold(1u64, |a, (g, &c)| {
        a.saturating_mul(binomial(g.len() as u64 + c as u64, g.len() as u64))
    })
}

fn group_degree(m: &Monomial, group: &[usize]) -> u32 {
    group.iter().map(|&i| m.0[i] as u32).sum()
}

/// The equations' largest degree in each group of unknowns.
fn largest_degrees<F: Field>(eqs: &[Poly<F>], groups: &[Vec<usize>]) -> Vec<u32> {
    groups
        .iter()
        .map(|g| {
            eqs.iter()
                .flat_map(|f| f.terms().map(|(m, _)| group_degree(m, g)))
                .max()
                .unwrap_or(0)
        })
        .collect()
}

/// The largest degree of each group a multiplier of `f` may have within `caps` (`None` if
/// `f` itself does not fit).
fn room<F: Field>(f: &Poly<F>, groups: &[Vec<usize>], caps: &[u32]) -> Option<Vec<u32>> {
    let mut room = caps.to_vec();
    for (m, _) in f.terms() {
        for ((r, g), &cap) in room.iter_mut().zip(groups).zip(caps) {
            *r = (*r).min(cap.checked_sub(group_degree(m, g))?);
        }
    }
    Some(room)
}

/// Every monomial in `nvars` unknowns of degree at most `room[g]` in each group g,
/// descending grevlex.
fn multipliers(nvars: usize, groups: &[Vec<usize>], room: &[u32]) -> Vec<Monomial> {
    let mut out = vec![Monomial(vec![0; nvars])];
    for (g, &r) in groups.iter().zip(room) {
        let k = g.len();
        let within = Monomial::all_up_to_degree(k, r, MonomialOrder::Grevlex);
        out = out
            .into_iter()
            .flat_map(|m| {
                within.iter().map(move |w| {
                    let mut v = m.0.clone();
                    for (&i, &e) in g.iter().zip(&w.0) {
                        v[i] = e;
                    }
                    Monomial(v)
                })
            })
            .collect();
    }
    out.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
    out
}

/// The raises of a multidegree's caps above the equations' own degrees, one entry per
/// group, by increasing sum: none; 1 on one group, on all; 2 on one group, on all.
fn raises(groups: usize) -> Vec<Vec<u32>> {
    let mut out: Vec<Vec<u32>> = vec![vec![0; groups]];
    for k in 1..=2 {
        for g in 0..groups {
            let mut r = vec![0; groups];
            r[g] = k;
            out.push(r);
        }
        out.push(vec![k; groups]);
    }
    out.sort_by_key(|r| r.iter().sum::<u32>());
    out.dedup();
    out
}

/// The pools basis selection tries, in order:
/// 1. the box of the equations' largest exponent of each unknown, raised as [`raises`]
///    lists;
/// 2. for three unknowns or more, each unknown against the others (two groups), the
///    equations' largest degrees in each raised the same way;
/// 3. the total degrees `maxeq + 1 ..= maxeq + 3`.
///
/// A partition is tried only when the multidegree of the equations' own largest degrees
/// has fewer monomials than their total degree `maxeq` (the equations are sparse in it;
/// equations that fill their total degree are better served by it), and each of its
/// multidegrees only while it has no more rows than the total degree `maxeq + 2`.
pub(crate) fn pools<F: Field>(eqs: &[Poly<F>], nvars: usize, maxeq: u32) -> Vec<Pool> {
    let limit = pool_size(eqs, maxeq + 2, &[]);
    let total_monomials = binomial(nvars as u64 + maxeq as u64, nvars as u64);
    let mut partitions: Vec<Vec<Vec<usize>>> = vec![(0..nvars).map(|i| vec![i]).collect()];
    if nvars >= 3 {
        for v in 0..nvars {
            let rest: Vec<usize> = (0..nvars).filter(|&i| i != v).collect();
            partitions.push(vec![vec![v], rest]);
        }
    }
    let mut out = Vec::new();
    for groups in partitions {
        let top = largest_degrees(eqs, &groups);
        if monomials_within(&groups, &top) >= total_monomials {
            continue;
        }
        for raise in raises(groups.len()) {
            let pool = Pool::Multidegree {
                groups: groups.clone(),
                caps: top.iter().zip(&raise).map(|(t, k)| t + k).collect(),
            };
            if pool.rows(eqs) <= limit {
                out.push(pool);
            }
        }
    }
    out.extend(polytope_pools(eqs, nvars, maxeq));
    out.extend((maxeq + 1..=maxeq + 3).map(Pool::TotalDegree));
    out
}

/// The pools of the equations' Newton polytope ([`newton_facets`]) with its facets raised
/// as [`raises`] lists, when the polytope has fewer monomials than both the box of the
/// equations' exponents and their total degree (the equations are sparse beyond a
/// multidegree), each only while its candidate matrix is no larger than that of the total
/// degree `maxeq + 3`.
fn polytope_pools<F: Field>(eqs: &[Poly<F>], nvars: usize, maxeq: u32) -> Vec<Pool> {
    let Some(facets) = newton_facets(eqs) else {
        return Vec::new();
    };
    let singletons: Vec<Vec<usize>> = (0..nvars).map(|i| vec![i]).collect();
    let exponents = largest_degrees(eqs, &singletons);
    // A guard on the total degree well past any raise of the facets.
    let degree = 2 * (maxeq + 2);
    let supports: Vec<i64> = facets.iter().map(|f| f.support).collect();
    let inside = monomials_inside(nvars, &facets, &supports, degree).len() as u64;
    let total = binomial(nvars as u64 + u64::from(maxeq), nvars as u64);
    if inside >= monomials_within(&singletons, &exponents) || inside >= total {
        return Vec::new();
    }
    // The candidate matrix of the largest total degree tried.
    let limit = pool_size(eqs, maxeq + 3, &[])
        .saturating_mul(binomial(nvars as u64 + u64::from(maxeq) + 3, nvars as u64));
    raises(facets.len())
        .into_iter()
        .map(|raise| Pool::Polytope {
            facets: facets.clone(),
            raise,
            degree,
        })
        .filter(|p| p.rows(eqs).saturating_mul(p.columns(eqs)) <= limit)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Ring, P1};

    fn boxed(caps: &[u32]) -> Pool {
        Pool::Multidegree {
            groups: (0..caps.len()).map(|i| vec![i]).collect(),
            caps: caps.to_vec(),
        }
    }

    fn one(n: usize) -> Poly<Fp<P1>> {
        Poly::constant(n, Fp::one())
    }

    #[test]
    fn box_pools_hold_exactly_the_multiples_within_their_exponents() {
        // f = x^3 y + y^2 + 1, g = x y + 1 in (x, y); box (4, 3).
        let n = 2;
        let x = Poly::<Fp<P1>>::var(n, 0);
        let y = Poly::<Fp<P1>>::var(n, 1);
        let one = one(n);
        let f = x.mul(&x).mul(&x).mul(&y).add(&y.mul(&y)).add(&one);
        let g = x.mul(&y).add(&one);
        let eqs = vec![f, g];
        let pool = boxed(&[4, 3]);
        let cands = pool.candidates(&eqs);
        assert_eq!(cands.len() as u64, pool.rows(&eqs));
        // f: multipliers x^a y^b, a <= 1, b <= 1; g: a <= 3, b <= 2.
        assert_eq!(cands.len(), 2 * 2 + 4 * 3);
        for c in &cands {
            assert!(c.terms.iter().all(|(m, _)| m.0[0] <= 4 && m.0[1] <= 3));
            let eq = &eqs[c.row.equation];
            assert_eq!(c.degree, eq.degree().unwrap() + c.row.multiplier.degree());
        }
        let distinct: std::collections::HashSet<_> = cands.iter().map(|c| c.row.clone()).collect();
        assert_eq!(distinct.len(), cands.len());
        // An equation that does not fit contributes nothing.
        assert_eq!(boxed(&[2, 3]).rows(&eqs), 2 * 3);
    }

    #[test]
    fn boxes_come_first_and_only_while_no_larger_than_a_total_degree() {
        assert_eq!(
            raises(2),
            [[0, 0], [1, 0], [0, 1], [1, 1], [2, 0], [0, 2], [2, 2]].map(Vec::from)
        );
        // Degrees (6, 3) in (x, y), total 9: the box of the exponents is small.
        let n = 2;
        let x = Poly::<Fp<P1>>::var(n, 0);
        let y = Poly::<Fp<P1>>::var(n, 1);
        let x6y3 = (0..6)
            .fold(one(n), |p, _| p.mul(&x))
            .mul(&y.mul(&y).mul(&y));
        let eqs = vec![x6y3.add(&y), x6y3.add(&x).add(&one(n))];
        let p = pools(&eqs, n, 9);
        // Rows 2, 4, 4, 8, 6, 6 and 18 against 12 multiples up to degree 11: by
        // increasing raise, all but the last.
        let boxes = [[6, 3], [7, 3], [6, 4], [7, 4], [8, 3], [6, 5]].map(|c| boxed(&c));
        assert_eq!(p[..6], boxes);
        assert!(!p.contains(&boxed(&[8, 5])));
        assert_eq!(p[p.len() - 3..], [10, 11, 12].map(Pool::TotalDegree));
        // A dense quadric in 6 unknowns fills its total degree: no multidegree.
        let n = 6;
        let q = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .fold(one(n), |p, (i, j)| {
                p.add(&Poly::var(n, i).mul(&Poly::var(n, j)))
            });
        let p = pools(&[q.clone(), q], n, 2);
        assert_eq!(p, [3, 4, 5].map(Pool::TotalDegree));
    }

    #[test]
    fn a_newton_polytope_pool_holds_the_multiples_inside_its_raised_facets() {
        // x^a y^b with b <= 3, a <= 2 b (the stitching problem's support): 16 monomials of
        // a box of 28 and of a total degree 9 of 55.
        let n = 2;
        let mut f = Poly::<Fp<P1>>::zero(n);
        let mut g = Poly::<Fp<P1>>::zero(n);
        for b in 0..=3u16 {
            for a in 0..=2 * b {
                f.add_term(Monomial(vec![a, b]), Fp::new(i64::from(3 * a + b + 1)));
                g.add_term(Monomial(vec![a, b]), Fp::new(i64::from(a + 5 * b + 2)));
            }
        }
        let eqs = vec![f, g];
        let polytopes: Vec<Pool> = pools(&eqs, n, 9)
            .into_iter()
            .filter(|p| matches!(p, Pool::Polytope { .. }))
            .collect();
        let raised = polytopes
            .iter()
            .find(|p| matches!(p, Pool::Polytope { raise, .. } if raise == &[0, 2, 0]))
            .expect("y <= 3 raised by two");
        let cands = raised.candidates(&eqs);
        assert_eq!(cands.len() as u64, raised.rows(&eqs));
        // Multipliers x^a y^b with b <= 2 and a <= 2 b + 1 (the facet a <= 2 b moved to
        // hold the unknown x): 12 of each equation.
        assert_eq!(cands.len(), 24);
        for c in &cands {
            let (a, b) = (c.row.multiplier.0[0], c.row.multiplier.0[1]);
            assert!(b <= 2 && a <= 2 * b + 1, "{:?}", c.row.multiplier);
            assert!(c
                .terms
                .iter()
                .all(|(m, _)| m.0[1] <= 5 && m.0[0] <= 2 * m.0[1] + 1));
        }
        assert_eq!(
            raised.family_and_size(),
            (PoolFamily::Polytope, 2),
            "sized by its raises"
        );
        // A dense quadric's polytope is its total degree: no polytope pool.
        let n = 3;
        let q = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .fold(one(n), |p, (i, j)| {
                p.add(&Poly::var(n, i).mul(&Poly::var(n, j)))
            })
            .add(&Poly::var(n, 0));
        assert!(!pools(&[q.clone(), q], n, 2)
            .iter()
            .any(|p| matches!(p, Pool::Polytope { .. })));
    }

    #[test]
    fn a_block_of_unknowns_against_one_is_tried_where_the_equations_are_sparse_in_it() {
        // (w, x, y, z): degree 1 in w, x, y together, 3 in z, 4 in all.
        let n = 4;
        let v = |i| Poly::<Fp<P1>>::var(n, i);
        let z3 = v(3).mul(&v(3)).mul(&v(3));
        let eqs = vec![
            v(0).mul(&z3)
                .add(&v(1).mul(&v(3)).mul(&v(3)))
                .add(&v(2))
                .add(&one(n)),
            v(1).mul(&z3).add(&v(0)).add(&one(n)),
            v(2).mul(&z3).add(&v(3)).add(&one(n)),
        ];
        let p = pools(&eqs, n, 4);
        assert_eq!(p[0], boxed(&[1, 1, 1, 3]));
        let z_against_rest = Pool::Multidegree {
            groups: vec![vec![3], vec![0, 1, 2]],
            caps: vec![3, 1],
        };
        assert!(p.contains(&z_against_rest));
        let cands = z_against_rest.candidates(&eqs);
        assert_eq!(cands.len() as u64, z_against_rest.rows(&eqs));
        assert_eq!(cands.len(), 3, "the equations alone");
        // w against (x, y, z): degree 4 in (x, y, z) spans as many monomials as degree 4.
        assert!(!p.iter().any(|p| matches!(p,
            Pool::Multidegree { groups, .. } if groups.len() == 2 && groups[0] == [0])));
        assert_eq!(
            z_against_rest.describe(&["w", "x", "y", "z"].map(String::from)),
            "all multiples within degrees 3 in z; 1 in w, x, y"
        );
    }
}
