//! The symbolic expansion of every shipped problem agrees with direct matrix evaluation,
//! in f64 (relative 1e-12) and exactly mod p; evaluation over Poly<Q> with symbolic data
//! equals `expand()`; everything is deterministic.

use mingen::__internal::algebra::{Fp, Monomial, Poly, Ring, P1, Q};
use mingen::__internal::instance::{random_data_f64, random_data_fp};
use mingen::Problem;
use num_traits::ToPrimitive;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;

type F = Fp<P1>;

fn templates() -> Vec<(PathBuf, Problem)> {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../templates"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("templates directory")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "mp"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "expected the shipped problems in {dir:?}");
    files
        .into_iter()
        .map(|f| {
            let p = Problem::from_file(&f).unwrap_or_else(|e| panic!("{e}"));
            (f, p)
        })
        .collect()
}

fn mono_f64(m: &Monomial, x: &[f64]) -> f64 {
    m.0.iter().zip(x).map(|(&e, v)| v.powi(e as i32)).product()
}

fn mono_fp(m: &Monomial, x: &[F]) -> F {
    m.0.iter()
        .zip(x)
        .fold(F::one(), |acc, (&e, v)| acc * v.pow(e as u64))
}

/// Value and sum of absolute term values of an expanded equation at (data, unknowns).
fn eval_expanded_f64(p: &Poly<Poly<Q>>, data: &[f64], unknowns: &[f64]) -> (f64, f64) {
    let (mut val, mut scale) = (0.0, 0.0);
    for (m, coeff) in p.terms() {
        let um = mono_f64(m, unknowns);
        for (dm, c) in coeff.terms() {
            let t = c.to_f64().expect("finite rational") * mono_f64(dm, data) * um;
            val += t;
            scale += t.abs();
        }
    }
    (val, scale)
}

fn reduce_at(p: &Poly<Poly<Q>>, data: &[F]) -> Poly<F> {
    Poly::from_terms(
        p.nvars(),
        p.terms().map(|(m, coeff)| {
            let v = coeff.terms().fold(F::zero(), |acc, (dm, c)| {
                acc + F::from_rational(c).expect("coefficient mod p") * mono_fp(dm, data)
            });
            (m.clone(), v)
        }),
    )
}

#[test]
fn expansion_matches_direct_evaluation_in_f64() {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    for (file, p) in templates() {
        let expanded = p.expand();
        assert_eq!(expanded.len(), p.equation_count());
        let nu = p.layout.unknown_count();
        for _ in 0..100 {
            let data = random_data_f64(&p.layout, &mut rng);
            let unknowns: Vec<f64> = (0..nu).map(|_| rng.gen_range(-1.0..=1.0)).collect();
            let direct = p.evaluate_direct(&data, &unknowns);
            let via_f64: Vec<f64> = p
                .evaluate::<f64>(&data)
                .iter()
                .map(|q| q.eval(&unknowns))
                .collect();
            for (i, e) in expanded.iter().enumerate() {
                let (val, scale) = eval_expanded_f64(e, &data, &unknowns);
                let tol = 1e-12 * scale.max(1e-300);
                assert!(
                    (val - direct[i]).abs() <= tol,
                    "{file:?} equation {i}: expanded {val} direct {} (scale {scale})",
                    direct[i]
                );
                assert!(
                    (via_f64[i] - direct[i]).abs() <= tol,
                    "{file:?} equation {i}: evaluate::<f64> {} direct {}",
                    via_f64[i],
                    direct[i]
                );
            }
        }
    }
}

#[test]
fn expansion_matches_evaluation_mod_p_exactly() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    for (file, p) in templates() {
        let expanded = p.expand();
        let nu = p.layout.unknown_count();
        for _ in 0..20 {
            let data = random_data_fp::<P1>(&p.layout, &mut rng);
            let unknowns: Vec<F> = (0..nu).map(|_| Fp(rng.gen_range(0..P1))).collect();
            let evaluated = p.evaluate::<F>(&data);
            let direct = p.evaluate_direct_ring(&data, &unknowns).unwrap();
            for (i, e) in expanded.iter().enumerate() {
                let reduced = reduce_at(e, &data);
                assert_eq!(reduced, evaluated[i], "{file:?} equation {i}");
                assert_eq!(reduced.eval(&unknowns), direct[i], "{file:?} equation {i}");
            }
        }
    }
}

#[test]
fn evaluate_over_symbolic_data_equals_expand() {
    for (file, p) in templates() {
        let nd = p.layout.data_slot_count();
        let data: Vec<Poly<Q>> = (0..nd).map(|i| Poly::var(nd, i)).collect();
        let generic = p.evaluate::<Poly<Q>>(&data);
        assert_eq!(generic, p.expand(), "{file:?}");
    }
}

#[test]
fn expansion_is_deterministic() {
    for (file, p) in templates() {
        let a = format!("{:?}", p.expand());
        let again = Problem::from_file(&file).unwrap();
        let b = format!("{:?}", again.expand());
        assert_eq!(a, b, "{file:?}");
        assert_eq!(p.layout, again.layout);
    }
}

#[test]
fn shipped_problem_shapes() {
    let all = templates();
    let get = |name: &str| {
        all.iter()
            .find(|(_, p)| p.name() == name)
            .map(|(_, p)| p)
            .unwrap_or_else(|| panic!("{name} shipped"))
    };
    let g = get("grsrp");
    assert_eq!(g.unknown_names(), ["a1", "a2", "a3", "t1", "t2", "t3"]);
    assert_eq!(g.layout.data_slot_count(), 45);
    assert_eq!(g.equation_count(), 6);
    let names = g.data_slot_names();
    assert_eq!(names[0], "x1[0].x");
    assert_eq!(names[1], "x1[0].y");
    assert_eq!(names[20], "v1[0]");
    assert_eq!(names[30], "w1.x");
    assert_eq!(names[44], "R0[2][2]");
    assert!(g.layout.eliminate.is_empty());
    let degrees: Vec<u32> = g.expand().iter().map(|e| e.degree().unwrap()).collect();
    assert_eq!(degrees, [2; 6]);

    let g10 = get("grsrp10");
    assert_eq!(g10.layout.eliminate, [3, 4, 5]);

    let five = get("gs5pt");
    assert_eq!(five.unknown_names(), ["x", "y", "z"]);
    assert_eq!(five.equation_count(), 10);
    let degrees: Vec<u32> = five.expand().iter().map(|e| e.degree().unwrap()).collect();
    assert_eq!(degrees, [3; 10]);

    let grav = get("grsrp_gravity");
    assert_eq!(grav.unknown_names(), ["c", "s", "t1", "t2", "t3"]);
    assert_eq!(grav.equation_count(), 5);
}

/// The gravity model with exact data: build a true instance (rotation about y, unit t,
/// bearings consistent with the gyro model) and check all equations vanish.
#[test]
fn grsrp_vanishes_on_a_consistent_instance() {
    use nalgebra::{Matrix3, Vector3};
    let p = templates()
        .into_iter()
        .find(|(_, p)| p.name() == "grsrp")
        .unwrap()
        .1;
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let skew = |v: Vector3<f64>| v.cross_matrix();
    let r0 = Matrix3::from_row_slice(&mingen::__internal::instance::random_rotation_f64(&mut rng));
    let a = Vector3::new(0.01, -0.02, 0.015);
    let t = Vector3::new(0.3, -0.5, 0.8).normalize();
    let (w1, w2) = (
        Vector3::new(1e-3, 2e-3, -1e-3),
        Vector3::new(-2e-3, 1e-3, 3e-3),
    );
    let mut data = Vec::new();
    let (mut x1s, mut x2s, mut v1s, mut v2s) = (vec![], vec![], vec![], vec![]);
    for _ in 0..5 {
        let x1 = Vector3::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0), 1.0);
        let (v1, v2) = (rng.gen_range(0.0..10.0), rng.gen_range(0.0..10.0));
        // Epipolar line of x1 in image 2 under the model: l = E x1 with
        // x2' [t]x (I + v2 W2) R0 (I + [a]x) (I - v1 W1) x1 = 0.
        let l = (skew(t) * (Matrix3::identity() + v2 * skew(w2)))
            * r0
            * (Matrix3::identity() + skew(a))
            * (Matrix3::identity() - v1 * skew(w1))
            * x1;
        // A point with third coordinate 1 on the line l: choose x, solve y.
        let x = rng.gen_range(-1.0..1.0);
        let y = -(l[0] * x + l[2]) / l[1];
        x1s.push(x1);
        x2s.push(Vector3::new(x, y, 1.0));
        v1s.push(v1);
        v2s.push(v2);
    }
    for x in &x1s {
        data.extend([x[0], x[1]]);
    }
    for x in &x2s {
        data.extend([x[0], x[1]]);
    }
    data.extend(&v1s);
    data.extend(&v2s);
    data.extend(w1.iter());
    data.extend(w2.iter());
    data.extend(r0.transpose().iter()); // column-major iteration of R0' = R0 row-major
    let unknowns = [a[0], a[1], a[2], t[0], t[1], t[2]];
    for (i, r) in p.evaluate_direct(&data, &unknowns).iter().enumerate() {
        assert!(r.abs() < 1e-12, "equation {i}: residual {r}");
    }
    let polys = p.evaluate::<f64>(&data);
    for (i, q) in polys.iter().enumerate() {
        assert!(q.eval(&unknowns).abs() < 1e-12, "equation {i}");
    }
}
