//! The interpreted solver and the audit on the 5-point problem in Stewénius form
//! (10 cubics in x, y, z; classic 10x20 template, action x), plus an eliminated-unknowns
//! audit on a small system.

use mingen::__internal::algebra::{Monomial, MonomialOrder, Poly};
use mingen::__internal::audit::{audit, AuditInstance, AuditOptions, EliminatedUnknowns};
use mingen::__internal::interpret::{normalized_residual, solve_template, solve_template_real};
use mingen::__internal::template::{EliminationTemplate, TemplateRow};
use nalgebra::{DMatrix, Matrix3, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type P = Poly<f64>;

fn mono(e: [u16; 3]) -> Monomial {
    Monomial(e.to_vec())
}

/// The classic template: rows = the 10 equations (multiplier 1); columns
/// excess {y^3, y^2z, yz^2, z^3} | reducible x * {x^2, xy, y^2, xz, yz, z^2} |
/// basis {x^2, xy, y^2, xz, yz, z^2, x, y, z, 1}.
fn five_point_template() -> EliminationTemplate {
    let basis: Vec<Monomial> = Monomial::all_up_to_degree(3, 2, MonomialOrder::Grevlex);
    assert_eq!(basis.len(), 10);
    let x = mono([1, 0, 0]);
    let reducible: Vec<Monomial> = basis
        .iter()
        .map(|b| x.mul(b))
        .filter(|m| !basis.contains(m))
        .collect();
    assert_eq!(reducible.len(), 6);
    let excess: Vec<Monomial> = Monomial::all_of_degree(3, 3, MonomialOrder::Grevlex)
        .into_iter()
        .filter(|m| !reducible.contains(m))
        .collect();
    assert_eq!(excess.len(), 4);
    let columns: Vec<Monomial> = excess
        .iter()
        .chain(&reducible)
        .chain(&basis)
        .cloned()
        .collect();
    EliminationTemplate {
        nvars: 3,
        rows: (0..10)
            .map(|equation| TemplateRow {
                equation,
                multiplier: Monomial::one(3),
            })
            .collect(),
        columns,
        n_excess: 4,
        n_reducible: 6,
        n_dependent: 0,
        n_hidden: 0,
        basis,
        action: mingen::__internal::template::Action::var(3, 0),
        sparse: None,
        unrolled: None,
        reduction: None,
        fold: None,
        shift: None,
        spurious_eigenvalues: 0,
        flipped: Vec::new(),
    }
}

/// A random real 5-point instance: the 10 Stewénius equations, and the ground-truth
/// (x, y, z) (E_true ∝ x E1 + y E2 + z E3 + E4).
fn five_point_instance(rng: &mut ChaCha8Rng) -> (Vec<P>, [f64; 3]) {
    let axis = Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    );
    let r = Rotation3::new(axis * 0.5).into_inner();
    let t = Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    )
    .normalize();
    let mut q = DMatrix::<f64>::zeros(9, 9);
    for k in 0..5 {
        let p = Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(3.0..6.0),
        );
        let x1 = p / p.z;
        let p2 = r * p + t;
        let x2 = p2 / p2.z;
        for i in 0..3 {
            for j in 0..3 {
                q[(k, 3 * i + j)] = x2[i] * x1[j];
            }
        }
    }
    let svd = q.svd(false, true);
    let vt = svd.v_t.unwrap();
    let mut idx: Vec<usize> = (0..9).collect();
    idx.sort_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]));
    // Null space basis: the 4 right singular vectors of the (near-)zero singular values.
    let e: Vec<Matrix3<f64>> = idx[..4]
        .iter()
        .map(|&k| Matrix3::from_fn(|i, j| vt[(k, 3 * i + j)]))
        .collect();
    let skew = Matrix3::new(0.0, -t.z, t.y, t.z, 0.0, -t.x, -t.y, t.x, 0.0);
    let et = skew * r;
    let coef: Vec<f64> = e.iter().map(|ek| ek.dot(&et)).collect();
    let truth = [coef[0] / coef[3], coef[1] / coef[3], coef[2] / coef[3]];

    let lin = |i: usize, j: usize| -> P {
        Poly::from_terms(
            3,
            [
                (mono([1, 0, 0]), e[0][(i, j)]),
                (mono([0, 1, 0]), e[1][(i, j)]),
                (mono([0, 0, 1]), e[2][(i, j)]),
                (mono([0, 0, 0]), e[3][(i, j)]),
            ],
        )
    };
    let em: Vec<Vec<P>> = (0..3)
        .map(|i| (0..3).map(|j| lin(i, j)).collect())
        .collect();
    let mut eqs = Vec::new();
    // det E.
    let minor = |a: usize, b: usize, c: usize, d: usize| {
        em[1][a].mul(&em[2][b]).sub(&em[1][c].mul(&em[2][d]))
    };
    let det = em[0][0]
        .mul(&minor(1, 2, 2, 1))
        .sub(&em[0][1].mul(&minor(0, 2, 2, 0)))
        .add(&em[0][2].mul(&minor(0, 1, 1, 0)));
    eqs.push(det);
    // 2 E E^T E - tr(E E^T) E.
    let eet: Vec<Vec<P>> = (0..3)
        .map(|i| {
            (0..3)
                .map(|j| (0..3).fold(Poly::zero(3), |acc, k| acc.add(&em[i][k].mul(&em[j][k]))))
                .collect()
        })
        .collect();
    let tr = eet[0][0].add(&eet[1][1]).add(&eet[2][2]);
    for (i, row) in em.iter().enumerate() {
        for (j, eij) in row.iter().enumerate() {
            let eete = (0..3).fold(Poly::zero(3), |acc, k| acc.add(&eet[i][k].mul(&em[k][j])));
            eqs.push(eete.scale(&2.0).sub(&tr.mul(eij)));
        }
    }
    (eqs, truth)
}

fn instance(rng: &mut ChaCha8Rng) -> AuditInstance {
    let (eqs, truth) = five_point_instance(rng);
    AuditInstance {
        equations: eqs.clone(),
        original: eqs,
        eliminated: None,
        newton_steps: 0,
        poor_only: false,
        planted: Some(truth.to_vec()),
        positive: vec![],
        sign_folds: Vec::new(),
    }
}

#[test]
fn five_point_solutions_satisfy_the_equations_and_contain_the_truth() {
    let template = five_point_template();
    assert_eq!(template.size(), (10, 20));
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    for _ in 0..50 {
        let (eqs, truth) = five_point_instance(&mut rng);
        let sols = solve_template(&template, &eqs).unwrap();
        assert_eq!(sols.solutions.len(), sols.eigenpairs);
        for s in &sols.solutions {
            for e in &eqs {
                let r = normalized_residual(e, s);
                assert!(r < 1e-9, "residual {r}");
            }
        }
        let real = solve_template_real(&template, &eqs);
        assert!(!real.is_empty() && real.len() % 2 == 0);
        let hit = real
            .iter()
            .any(|s| (0..3).all(|i| (s[i] - truth[i]).abs() <= 1e-7 * (1.0 + truth[i].abs())));
        assert!(hit, "truth {truth:?} not among {real:?}");
    }
}

#[test]
fn five_point_audit() {
    let template = five_point_template();
    let opts = AuditOptions::default();
    assert_eq!((opts.instances, opts.seed), (1000, 1));
    let report = audit(&template, 10, &opts, instance);
    println!("{report}");
    println!("{}", report.to_json());
    assert_eq!(report.instances, 1000);
    assert!(report.median_log10_residual < -11.0, "{report}");
    assert!(report.failures <= 5, "{report}");
    // The geometric instance every audit instance was made from is recovered.
    let planted = report.planted.as_ref().expect("planted solutions given");
    assert_eq!(planted.instances, 1000);
    assert!(planted.recovered >= 995, "{report}");
    assert!(planted.median_log10_error < -11.0, "{report}");
    let json = report.to_json();
    for key in [
        "instances",
        "median_log10_residual",
        "p99_log10_residual",
        "failures",
        "histogram",
        "planted",
    ] {
        assert!(json.get(key).is_some(), "missing {key}");
    }
    let total: u64 = json["histogram"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["count"].as_u64().unwrap())
        .sum();
    assert_eq!(total, 1000);
    // Same seed, same report.
    let small = AuditOptions {
        instances: 20,
        seed: 9,
        ..AuditOptions::default()
    };
    assert_eq!(
        audit(&template, 10, &small, instance),
        audit(&template, 10, &small, instance)
    );
}

/// Unknowns (x, y, t1, t2, t3): the three points (1,1), (2,3), (3,-1) in (x, y), then
/// x t1 - t2 = 0 and y t2 - t3 = 0 (t linear, eliminated: three unknowns, as the emitted
/// solvers support) and t1^2 + t2^2 + t3^2 = 1 (its normalisation, dropped).
#[test]
fn audit_with_eliminated_unknowns() {
    let m2 = |e: [u16; 2]| Monomial(e.to_vec());
    let m5 = |e: [u16; 5]| Monomial(e.to_vec());
    let e0 = Poly::from_terms(
        2,
        [
            (m2([2, 0]), 3.0),
            (m2([1, 0]), -11.0),
            (m2([0, 0]), 7.0),
            (m2([0, 1]), 1.0),
        ],
    );
    let e1 = Poly::from_terms(
        2,
        [
            (m2([3, 0]), 3.0),
            (m2([2, 0]), -11.0),
            (m2([1, 1]), 4.0),
            (m2([1, 0]), 6.0),
            (m2([0, 1]), -7.0),
            (m2([0, 0]), 5.0),
        ],
    );
    let row = |equation, e| TemplateRow {
        equation,
        multiplier: m2(e),
    };
    let template = EliminationTemplate {
        nvars: 2,
        rows: vec![row(1, [0, 0]), row(0, [1, 0]), row(0, [0, 0])],
        columns: vec![
            m2([3, 0]),
            m2([2, 0]),
            m2([1, 1]),
            m2([1, 0]),
            m2([0, 1]),
            m2([0, 0]),
        ],
        n_excess: 1,
        n_reducible: 2,
        n_dependent: 0,
        n_hidden: 0,
        basis: vec![m2([1, 0]), m2([0, 1]), m2([0, 0])],
        action: mingen::__internal::template::Action::var(2, 0),
        sparse: None,
        unrolled: None,
        reduction: None,
        fold: None,
        shift: None,
        spurious_eigenvalues: 0,
        flipped: Vec::new(),
    };
    let widen = |p: &P| {
        Poly::from_terms(
            5,
            p.terms().map(|(m, &c)| (m5([m.0[0], m.0[1], 0, 0, 0]), c)),
        )
    };
    let original = vec![
        widen(&e0),
        widen(&e1),
        Poly::from_terms(5, [(m5([1, 0, 1, 0, 0]), 1.0), (m5([0, 0, 0, 1, 0]), -1.0)]),
        Poly::from_terms(5, [(m5([0, 1, 0, 1, 0]), 1.0), (m5([0, 0, 0, 0, 1]), -1.0)]),
        Poly::from_terms(
            5,
            [
                (m5([0, 0, 2, 0, 0]), 1.0),
                (m5([0, 0, 0, 2, 0]), 1.0),
                (m5([0, 0, 0, 0, 2]), 1.0),
                (m5([0, 0, 0, 0, 0]), -1.0),
            ],
        ),
    ];
    let zero = Poly::constant(2, 0.0);
    let matrix = vec![
        vec![Poly::var(2, 0), Poly::constant(2, -1.0), zero.clone()],
        vec![zero, Poly::var(2, 1), Poly::constant(2, -1.0)],
    ];
    let opts = AuditOptions {
        instances: 5,
        seed: 3,
        ..AuditOptions::default()
    };
    let report = audit(&template, 3, &opts, |_| AuditInstance {
        equations: vec![e0.clone(), e1.clone()],
        original: original.clone(),
        eliminated: Some(EliminatedUnknowns {
            matrix: matrix.clone(),
            positions: vec![2, 3, 4],
            inhomogeneous: false,
        }),
        newton_steps: 0,
        poor_only: false,
        planted: None,
        positive: vec![],
        sign_folds: Vec::new(),
    });
    assert!(report.planted.is_none());
    assert_eq!(report.failures, 0, "{report}");
    assert!(report.p99_log10_residual < -13.0, "{report}");
    assert_eq!(report.mean_real_solutions, 3.0);
}
