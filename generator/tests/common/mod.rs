//! Test systems built directly with `Poly` arithmetic on random Z_p data (the parser is
//! developed separately): the 5-point problem in Stewénius form, G-RSRP (6 unknowns), its
//! eliminated form `grsrp10` (3 unknowns), a positive-dimensional and an inconsistent system.
#![allow(dead_code)]

use mingen::__internal::algebra::{Fp, Poly, Ring};
use mingen::__internal::quotient::{InstanceRng, InstanceSource};
use rand::Rng;

type P3<const P: u32> = [Poly<Fp<P>>; 3];

fn rnd<const P: u32>(rng: &mut InstanceRng) -> Fp<P> {
    Fp::new(rng.gen_range(0..P as i64))
}
fn cst<const P: u32>(n: usize, c: Fp<P>) -> Poly<Fp<P>> {
    Poly::constant(n, c)
}
fn cross<const P: u32>(a: &P3<P>, b: &P3<P>) -> P3<P> {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}
fn dot<const P: u32>(a: &P3<P>, b: &P3<P>) -> Poly<Fp<P>> {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}
fn matvec<const P: u32>(m: &[[Fp<P>; 3]; 3], v: &P3<P>) -> P3<P> {
    let n = v[0].nvars();
    std::array::from_fn(|i| {
        (0..3).fold(Poly::zero(n), |acc, j| acc.add(&v[j].mul(&cst(n, m[i][j]))))
    })
}
fn constvec<const P: u32>(n: usize, v: [Fp<P>; 3]) -> P3<P> {
    v.map(|c| cst(n, c))
}

/// A random rotation mod P from a Cayley parameter q:
/// R = ((1 - q'q) I + 2 q q' + 2 [q]x) / (1 + q'q).
fn cayley<const P: u32>(rng: &mut InstanceRng) -> [[Fp<P>; 3]; 3] {
    loop {
        let q: [Fp<P>; 3] = std::array::from_fn(|_| rnd(rng));
        let qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
        let one = Fp::<P>::new(1);
        let two = Fp::<P>::new(2);
        let Some(s) = mingen::__internal::algebra::Field::inv(&(one + qq)) else {
            continue;
        };
        let skew = [
            [Fp::new(0), -q[2], q[1]],
            [q[2], Fp::new(0), -q[0]],
            [-q[1], q[0], Fp::new(0)],
        ];
        return std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let d = if i == j { one - qq } else { Fp::new(0) };
                (d + two * q[i] * q[j] + two * skew[i][j]) * s
            })
        });
    }
}

/// The five G-RSRP point equations written as `row_k(a) . t`, with `row_k` a 3-vector of
/// polynomials of degree <= 1 in `a` (the first three variables of an `n`-variable ring).
fn grsrp_rows<const P: u32>(n: usize, rng: &mut InstanceRng) -> Vec<P3<P>> {
    let r0 = cayley::<P>(rng);
    let w1: [Fp<P>; 3] = std::array::from_fn(|_| rnd(rng));
    let w2: [Fp<P>; 3] = std::array::from_fn(|_| rnd(rng));
    let a: P3<P> = std::array::from_fn(|i| Poly::var(n, i));
    (0..5)
        .map(|_| {
            let x1 = [rnd(rng), rnd(rng), Fp::new(1)];
            let x2 = [rnd(rng), rnd(rng), Fp::new(1)];
            let (v1, v2) = (rnd::<P>(rng), rnd::<P>(rng));
            let x1p = constvec(n, x1);
            // u = (I - v1 [w1]x) x1
            let w1x = cross(&constvec(n, w1), &x1p);
            let u: P3<P> = std::array::from_fn(|i| x1p[i].sub(&w1x[i].mul(&cst(n, v1))));
            // (I + [a]x) u
            let au = cross(&a, &u);
            let u2: P3<P> = std::array::from_fn(|i| u[i].add(&au[i]));
            let u3 = matvec(&r0, &u2);
            // (I + v2 [w2]x) u3
            let wu = cross(&constvec(n, w2), &u3);
            let w: P3<P> = std::array::from_fn(|i| u3[i].add(&wu[i].mul(&cst(n, v2))));
            // x2' [t]x w = t . (w x x2)
            cross(&w, &constvec(n, x2))
        })
        .collect()
}

/// The test systems.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fixture {
    /// 5-point relative pose, Stewénius form: 10 cubics in x, y, z; 10 solutions.
    Gs5pt,
    /// G-RSRP: unknowns a1 a2 a3 t1 t2 t3; 5 bilinear equations and t't = 1; 20 solutions.
    Grsrp,
    /// G-RSRP with t eliminated: the 10 maximal minors in a1 a2 a3; 10 solutions.
    Grsrp10,
    /// G-RSRP with known gravity (`templates/grsrp_gravity.mp`): unknowns c s t1 t2 t3,
    /// 3 bilinear point equations, c^2 + s^2 = 1, t't = 1.
    GrsrpGravity,
    /// G-RSRP without its last point equation: positive-dimensional.
    GrsrpMissingPoint,
    /// x = 0 and x = 1 in (x, y): inconsistent.
    Inconsistent,
}

impl InstanceSource for Fixture {
    fn nvars(&self) -> usize {
        match self {
            Fixture::Gs5pt | Fixture::Grsrp10 => 3,
            Fixture::Grsrp | Fixture::GrsrpMissingPoint => 6,
            Fixture::GrsrpGravity => 5,
            Fixture::Inconsistent => 2,
        }
    }
    fn var_names(&self) -> Vec<String> {
        let v: &[&str] = match self {
            Fixture::Gs5pt => &["x", "y", "z"],
            Fixture::Grsrp10 => &["a1", "a2", "a3"],
            Fixture::Grsrp | Fixture::GrsrpMissingPoint => &["a1", "a2", "a3", "t1", "t2", "t3"],
            Fixture::GrsrpGravity => &["c", "s", "t1", "t2", "t3"],
            Fixture::Inconsistent => &["x", "y"],
        };
        v.iter().map(|s| s.to_string()).collect()
    }
    fn instance<const P: u32>(&self, rng: &mut InstanceRng) -> Vec<Poly<Fp<P>>> {
        match self {
            Fixture::Gs5pt => gs5pt(rng),
            Fixture::Grsrp | Fixture::GrsrpMissingPoint => {
                let n = 6;
                let rows = grsrp_rows::<P>(n, rng);
                let t: P3<P> = std::array::from_fn(|i| Poly::var(n, 3 + i));
                let keep = if *self == Fixture::Grsrp { 5 } else { 4 };
                let mut eqs: Vec<Poly<Fp<P>>> =
                    rows.iter().take(keep).map(|r| dot(r, &t)).collect();
                eqs.push(dot(&t, &t).sub(&cst(n, Fp::new(1))));
                eqs
            }
            Fixture::Grsrp10 => {
                let rows = grsrp_rows::<P>(3, rng);
                let mut eqs = Vec::new();
                for i in 0..5 {
                    for j in i + 1..5 {
                        for k in j + 1..5 {
                            eqs.push(dot(&rows[i], &cross(&rows[j], &rows[k])));
                        }
                    }
                }
                eqs
            }
            Fixture::GrsrpGravity => gravity(rng),
            Fixture::Inconsistent => {
                let x = Poly::<Fp<P>>::var(2, 0);
                vec![x.clone(), x.sub(&cst(2, Fp::new(1)))]
            }
        }
    }
}

fn gs5pt<const P: u32>(rng: &mut InstanceRng) -> Vec<Poly<Fp<P>>> {
    let n = 3;
    let basis: Vec<[[Fp<P>; 3]; 3]> = (0..4)
        .map(|_| std::array::from_fn(|_| std::array::from_fn(|_| rnd(rng))))
        .collect();
    let coef = |k: usize| -> Poly<Fp<P>> {
        if k < 3 {
            Poly::var(n, k)
        } else {
            Poly::constant(n, Fp::<P>::one())
        }
    };
    let e: Vec<Vec<Poly<Fp<P>>>> = (0..3)
        .map(|i| {
            (0..3)
                .map(|j| {
                    (0..4).fold(Poly::zero(n), |acc, k| {
                        acc.add(&coef(k).mul(&cst(n, basis[k][i][j])))
                    })
                })
                .collect()
        })
        .collect();
    let mm = |a: &Vec<Vec<Poly<Fp<P>>>>, b: &Vec<Vec<Poly<Fp<P>>>>| -> Vec<Vec<Poly<Fp<P>>>> {
        (0..3)
            .map(|i| {
                (0..3)
                    .map(|j| (0..3).fold(Poly::zero(n), |acc, k| acc.add(&a[i][k].mul(&b[k][j]))))
                    .collect()
            })
            .collect()
    };
    let et: Vec<Vec<Poly<Fp<P>>>> = (0..3)
        .map(|i| (0..3).map(|j| e[j][i].clone()).collect())
        .collect();
    let eet = mm(&e, &et);
    let tr = eet[0][0].add(&eet[1][1]).add(&eet[2][2]);
    let eete = mm(&eet, &e);
    let two = cst(n, Fp::new(2));
    let det = {
        let r = |i: usize| -> P3<P> { std::array::from_fn(|j| e[i][j].clone()) };
        dot(&r(0), &cross(&r(1), &r(2)))
    };
    let mut eqs = vec![det];
    for i in 0..3 {
        for j in 0..3 {
            eqs.push(two.mul(&eete[i][j]).sub(&tr.mul(&e[i][j])));
        }
    }
    eqs
}

/// G-RSRP with known gravity: x2' [t]x (I + v2 [w2]x) G2' Ry(c, s) G1 (I - v1 [w1]x) x1 = 0.
fn gravity<const P: u32>(rng: &mut InstanceRng) -> Vec<Poly<Fp<P>>> {
    let n = 5;
    let g1 = cayley::<P>(rng);
    let g2 = cayley::<P>(rng);
    let w1: [Fp<P>; 3] = std::array::from_fn(|_| rnd(rng));
    let w2: [Fp<P>; 3] = std::array::from_fn(|_| rnd(rng));
    let (c, s) = (Poly::<Fp<P>>::var(n, 0), Poly::<Fp<P>>::var(n, 1));
    let t: P3<P> = std::array::from_fn(|i| Poly::var(n, 2 + i));
    let z = Poly::<Fp<P>>::zero(n);
    let one = cst(n, Fp::new(1));
    let ry: [P3<P>; 3] = [
        [c.clone(), z.clone(), s.clone()],
        [z.clone(), one.clone(), z.clone()],
        [s.neg(), z.clone(), c.clone()],
    ];
    let g2t: [[Fp<P>; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| g2[j][i]));
    let mut eqs = Vec::new();
    for _ in 0..3 {
        let x1 = [rnd(rng), rnd(rng), Fp::new(1)];
        let x2 = [rnd(rng), rnd(rng), Fp::new(1)];
        let (v1, v2) = (rnd::<P>(rng), rnd::<P>(rng));
        let x1p = constvec(n, x1);
        let w1x = cross(&constvec(n, w1), &x1p);
        let u: P3<P> = std::array::from_fn(|i| x1p[i].sub(&w1x[i].mul(&cst(n, v1))));
        let u = matvec(&g1, &u);
        let u: P3<P> = std::array::from_fn(|i| dot(&ry[i], &u));
        let u = matvec(&g2t, &u);
        let wu = cross(&constvec(n, w2), &u);
        let w: P3<P> = std::array::from_fn(|i| u[i].add(&wu[i].mul(&cst(n, v2))));
        eqs.push(dot(&t, &cross(&w, &constvec(n, x2))));
    }
    eqs.push(c.mul(&c).add(&s.mul(&s)).sub(&one));
    eqs.push(dot(&t, &t).sub(&one));
    eqs
}
