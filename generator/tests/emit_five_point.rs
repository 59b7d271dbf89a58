//! Emission tests on the classic 5-point problem (Stewénius/Nistér 10x20 template) and a
//! small problem with linear elimination. Set `MINGEN_EMIT_OUT=DIR` to keep the emitted
//! files in DIR (default: a temporary directory).

use mingen::__internal::algebra::{Monomial, MonomialOrder, Poly, Ring, Q};
use mingen::__internal::emit::{
    emit_solver, generated_header, EliminationSpec, Program, SolverSpec, Traced, Tracer,
};
use mingen::__internal::problem::{DataKind, DataSymbol, ProblemLayout, UnknownSymbol};
use mingen::__internal::template::{EliminationTemplate, TemplateRow};
use nalgebra::{DMatrix, Matrix3, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;

type M3<C> = [[Poly<C>; 3]; 3];

/// E = x E1 + y E2 + z E3 + E4 from four data matrices (in 3 unknowns x, y, z).
fn essential<C: Ring>(e: &[[[C; 3]; 3]; 4]) -> M3<C> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            Poly::from_terms(
                3,
                [
                    (Monomial::var(3, 0), e[0][i][j].clone()),
                    (Monomial::var(3, 1), e[1][i][j].clone()),
                    (Monomial::var(3, 2), e[2][i][j].clone()),
                    (Monomial::one(3), e[3][i][j].clone()),
                ],
            )
        })
    })
}

fn matmul<C: Ring>(a: &M3<C>, b: &M3<C>) -> M3<C> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut s = Poly::zero(3);
            for k in 0..3 {
                s = s.add(&a[i][k].mul(&b[k][j]));
            }
            s
        })
    })
}

fn transpose<C: Ring>(a: &M3<C>) -> M3<C> {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i].clone()))
}

/// det(E) = 0 and 2 E E' E - trace(E E') E = 0 (10 cubics in x, y, z).
fn five_point_equations<C: Ring>(e: &[[[C; 3]; 3]; 4]) -> Vec<Poly<C>> {
    let m = essential(e);
    let det = m[0][0]
        .mul(&m[1][1].mul(&m[2][2]).sub(&m[1][2].mul(&m[2][1])))
        .sub(&m[0][1].mul(&m[1][0].mul(&m[2][2]).sub(&m[1][2].mul(&m[2][0]))))
        .add(&m[0][2].mul(&m[1][0].mul(&m[2][1]).sub(&m[1][1].mul(&m[2][0]))));
    let eet = matmul(&m, &transpose(&m));
    let tr = eet[0][0].add(&eet[1][1]).add(&eet[2][2]);
    let eete = matmul(&eet, &m);
    let two = Poly::constant(3, C::from_i64(2));
    let mut out = vec![det];
    for i in 0..3 {
        for j in 0..3 {
            out.push(two.mul(&eete[i][j]).sub(&tr.mul(&m[i][j])));
        }
    }
    out
}

fn data_array<C: Clone>(slots: &[C]) -> [[[C; 3]; 3]; 4] {
    std::array::from_fn(|k| {
        std::array::from_fn(|i| std::array::from_fn(|j| slots[9 * k + 3 * i + j].clone()))
    })
}

fn five_point_layout() -> ProblemLayout {
    ProblemLayout {
        name: "fivept".into(),
        unknowns: ["x", "y", "z"]
            .iter()
            .enumerate()
            .map(|(i, n)| UnknownSymbol {
                name: n.to_string(),
                len: None,
                first_var: i,
                hidden: false,
            })
            .collect(),
        data: (0..4)
            .map(|k| DataSymbol {
                name: format!("E{}", k + 1),
                kind: DataKind::Mat3,
                len: None,
                first_slot: 9 * k,
            })
            .collect(),
        eliminate: vec![],
        positive: vec![],
        options: Default::default(),
    }
}

/// The hand-built 10x20 template: basis = monomials of degree <= 2 (grevlex, descending),
/// action x, reducible = x * (degree-2 basis monomials), excess = cubics without x.
fn five_point_template() -> EliminationTemplate {
    let order = MonomialOrder::Grevlex;
    let basis = Monomial::all_up_to_degree(3, 2, order);
    let action = Monomial::var(3, 0);
    let reducible: Vec<Monomial> = basis
        .iter()
        .filter(|b| b.degree() == 2)
        .map(|b| action.mul(b))
        .collect();
    let excess: Vec<Monomial> = Monomial::all_of_degree(3, 3, order)
        .into_iter()
        .filter(|m| m.0[0] == 0)
        .collect();
    assert_eq!((basis.len(), reducible.len(), excess.len()), (10, 6, 4));
    let columns: Vec<Monomial> = excess
        .iter()
        .chain(&reducible)
        .chain(&basis)
        .cloned()
        .collect();
    EliminationTemplate {
        nvars: 3,
        rows: (0..10)
            .map(|e| TemplateRow {
                equation: e,
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

fn five_point_spec() -> (SolverSpec, Tracer) {
    let tracer = Tracer::new();
    let inputs = tracer.inputs(36);
    let equations = five_point_equations(&data_array(&inputs));
    let spec = SolverSpec {
        layout: five_point_layout(),
        template: five_point_template(),
        equations,
        problem_path: "templates/fivept.mp".into(),
        elimination: None,
        polish: None,
        sign_folds: Vec::new(),
        code_form: mingen::__internal::emit::CodeForm::Auto,
    };
    (spec, tracer)
}

fn out_dir() -> PathBuf {
    let dir = std::env::var_os("MINGEN_EMIT_OUT")
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("mingen-emit-tests"));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn rel_close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn traced_dag_matches_direct_f64_evaluation() {
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let (spec, tracer) = five_point_spec();
    let all_coeffs: Vec<(usize, Monomial, Traced)> = spec
        .equations
        .iter()
        .enumerate()
        .flat_map(|(e, p)| p.terms().map(move |(m, c)| (e, m.clone(), c.clone())))
        .collect();
    let outputs: Vec<Traced> = all_coeffs.iter().map(|(_, _, c)| c.clone()).collect();
    let program = Program::build(&outputs, &[], 36).unwrap();
    for _ in 0..50 {
        let data: Vec<f64> = (0..36).map(|_| rng.gen_range(-2.0..2.0)).collect();
        let direct = five_point_equations(&data_array(&data));
        let all_nodes = tracer.eval_all(&data);
        let prog = program.eval(&data);
        for (k, (e, m, c)) in all_coeffs.iter().enumerate() {
            let want = direct[*e].coeff(m);
            let traced = c.eval_f64(&data);
            assert!(
                rel_close(traced, want, 1e-12),
                "eq {e} {m:?}: {traced} vs {want}"
            );
            assert!(rel_close(prog[k], want, 1e-12), "program eq {e} {m:?}");
            if let mingen::__internal::emit::traced::TracedValue::Node { id, neg } = c.value() {
                let v = all_nodes[id as usize];
                assert_eq!(if neg { -v } else { v }, traced);
            }
        }
        // Every coefficient of the direct evaluation is traced (no lost monomials).
        for (e, p) in direct.iter().enumerate() {
            assert_eq!(p.len(), spec.equations[e].len());
        }
    }
}

#[test]
fn common_subexpressions_are_shared() {
    let (spec, tracer) = five_point_spec();
    let outputs: Vec<Traced> = spec
        .equations
        .iter()
        .flat_map(|p| p.terms().map(|(_, c)| c.clone()).collect::<Vec<_>>())
        .collect();
    let program = Program::build(&outputs, &[], 36).unwrap();
    // Naive: the coefficients expanded as polynomials in the 36 data scalars.
    let data_vars: Vec<Poly<Q>> = (0..36).map(|i| Poly::var(36, i)).collect();
    let expanded = five_point_equations(&data_array(&data_vars));
    let (mut terms, mut naive_ops) = (0usize, 0usize);
    for p in &expanded {
        for (_, c) in p.terms() {
            terms += c.len();
            for (m, _) in c.terms() {
                naive_ops += m.degree() as usize; // multiplications incl. the coefficient
            }
            naive_ops += c.len() - 1; // additions
        }
    }
    println!(
        "5-point coefficients: {} outputs, {} traced nodes in the graph, {} live ops in {} statements; \
         naive expansion: {} terms, {} ops",
        outputs.len(),
        tracer.node_count(),
        program.op_count(),
        program.stmts.len(),
        terms,
        naive_ops
    );
    assert_eq!(outputs.len(), 200);
    assert!(
        program.op_count() * 3 < naive_ops,
        "sharing should beat the naive expansion by far"
    );
}

#[test]
fn template_satisfies_the_convention_numerically() {
    // An instance with a known solution (x0, y0, z0): E4 = E0 - x0 E1 - y0 E2 - z0 E3 for an
    // essential matrix E0. Gauss-Jordan + action matrix must satisfy M v = x0 v.
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (spec, _tracer) = five_point_spec();
    let t = &spec.template;
    let fill: Vec<(usize, Traced)> = t
        .rows
        .iter()
        .enumerate()
        .flat_map(|(i, r)| {
            let col = |m: &Monomial| {
                t.columns
                    .iter()
                    .position(|c| *c == r.multiplier.mul(m))
                    .unwrap()
            };
            spec.equations[r.equation]
                .terms()
                .map(|(m, c)| (i * 20 + col(m), c.clone()))
                .collect::<Vec<_>>()
        })
        .collect();
    let outputs: Vec<Traced> = fill.iter().map(|(_, c)| c.clone()).collect();
    let program = Program::build(&outputs, &[], 36).unwrap();
    for _ in 0..20 {
        let rot = Rotation3::from_scaled_axis(Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        ));
        let tv = Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        let e0: Matrix3<f64> = tv.cross_matrix() * rot.matrix();
        let sol = [
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        ];
        let mut data = vec![0.0; 36];
        for (k, slot) in data.iter_mut().enumerate().take(27) {
            let _ = k;
            *slot = rng.gen_range(-1.0..1.0);
        }
        for i in 0..3 {
            for j in 0..3 {
                data[27 + 3 * i + j] = e0[(i, j)]
                    - sol[0] * data[3 * i + j]
                    - sol[1] * data[9 + 3 * i + j]
                    - sol[2] * data[18 + 3 * i + j];
            }
        }
        let vals = program.eval(&data);
        let mut m = DMatrix::<f64>::zeros(10, 20);
        for ((pos, _), v) in fill.iter().zip(&vals) {
            m[(pos / 20, pos % 20)] = *v;
        }
        // Gauss-Jordan on the first 10 columns with partial pivoting (the runtime's contract).
        for j in 0..10 {
            let p = (j..10)
                .max_by(|&a, &b| m[(a, j)].abs().total_cmp(&m[(b, j)].abs()))
                .unwrap();
            m.swap_rows(j, p);
            let piv = m[(j, j)];
            assert!(piv.abs() > 1e-12);
            let row = m.row(j) / piv;
            m.set_row(j, &row);
            for i in 0..10 {
                if i != j {
                    let f = m[(i, j)];
                    let r = m.row(i) - m.row(j) * f;
                    m.set_row(i, &r);
                }
            }
        }
        let mut a = DMatrix::<f64>::zeros(10, 10);
        for (j, b) in t.basis.iter().enumerate() {
            let c = t
                .columns
                .iter()
                .position(|c| *c == b.mul(&Monomial::var(3, 0)))
                .unwrap();
            if c >= 10 {
                a[(j, c - 10)] = 1.0;
            } else {
                for k in 0..10 {
                    a[(j, k)] = -m[(c, 10 + k)];
                }
            }
        }
        let v = nalgebra::DVector::from_iterator(
            10,
            t.basis.iter().map(|b| {
                b.0.iter()
                    .zip(&sol)
                    .map(|(&e, &s)| s.powi(e as i32))
                    .product::<f64>()
            }),
        );
        let r = &a * &v - &v * sol[0];
        assert!(
            r.norm() < 1e-8 * v.norm(),
            "M v = x v violated: {}",
            r.norm()
        );
    }
}

#[test]
fn five_point_emission_is_deterministic_parses_and_has_the_header() {
    let (spec1, _t1) = five_point_spec();
    let (spec2, _t2) = five_point_spec();
    let a = emit_solver(&spec1).unwrap();
    let b = emit_solver(&spec2).unwrap();
    let c = emit_solver(&spec1).unwrap();
    assert_eq!(a, b, "independent traces emit identical bytes");
    assert_eq!(a, c);
    let first = a.lines().next().unwrap();
    assert_eq!(first, generated_header("fivept"));
    assert_eq!(
        first,
        "// @generated by mingen from templates/fivept.mp — do not edit"
    );
    syn::parse_file(&a).expect("emitted code parses");
    for needle in [
        "pub struct Data",
        "pub e1: [[f64; 3]; 3]",
        "pub struct Solution",
        "pub const MAX_SOLUTIONS: usize = 10;",
        "pub type Solutions = mingen_runtime::SolutionSet<Solution, MAX_SOLUTIONS>;",
        "pub fn solve(data: &Data) -> Solutions",
        "mingen_runtime::lu_solve_template_fixed::<10, 20, 10, 4>(&mut m)",
        "mingen_runtime::real_eigenpairs_sturm::<10>(&a)",
        "let mut m = [0.0f64; 200];",
    ] {
        assert!(a.contains(needle), "missing `{needle}`");
    }
    let path = out_dir().join("fivept.rs");
    std::fs::write(&path, &a).unwrap();
    println!(
        "emitted {} ({} lines, {} bytes)",
        path.display(),
        a.lines().count(),
        a.len()
    );
}

/// A toy problem with elimination: unknowns `s` and `t[3]`; the template solves
/// s^2 = d0 (basis {s, 1}); t is the null vector of [[1, s, d1], [d2, 1, s]].
#[test]
fn elimination_emission_parses() {
    let tracer = Tracer::new();
    let d = tracer.inputs(4);
    let layout = ProblemLayout {
        name: "toyelim".into(),
        unknowns: vec![
            UnknownSymbol {
                name: "s".into(),
                len: None,
                first_var: 0,
                hidden: false,
            },
            UnknownSymbol {
                name: "t".into(),
                len: Some(3),
                first_var: 1,
                hidden: false,
            },
        ],
        data: vec![
            DataSymbol {
                name: "D".into(),
                kind: DataKind::Scalar,
                len: Some(2),
                first_slot: 0,
            },
            DataSymbol {
                name: "x1".into(),
                kind: DataKind::Point,
                len: None,
                first_slot: 2,
            },
        ],
        eliminate: vec![1, 2, 3],
        positive: vec![],
        options: Default::default(),
    };
    let s2 = Monomial(vec![2]);
    let s = Monomial(vec![1]);
    let one = Monomial(vec![0]);
    let eq = Poly::from_terms(1, [(s2.clone(), Traced::one()), (one.clone(), d[0].neg())]);
    let template = EliminationTemplate {
        nvars: 1,
        rows: vec![TemplateRow {
            equation: 0,
            multiplier: one.clone(),
        }],
        columns: vec![s2, s.clone(), one.clone()],
        n_excess: 0,
        n_reducible: 1,
        n_dependent: 0,
        n_hidden: 0,
        basis: vec![s.clone(), one.clone()],
        action: mingen::__internal::template::Action::var(1, 0),
        sparse: None,
        unrolled: None,
        reduction: None,
        fold: None,
        shift: None,
        spurious_eigenvalues: 0,
        flipped: Vec::new(),
    };
    let cst = |c: Traced| Poly::constant(1, c);
    let sv = Poly::<Traced>::var(1, 0);
    let coefficient_matrix = vec![
        vec![cst(Traced::one()), sv.clone(), cst(d[1].mul(&d[2]))],
        vec![
            cst(d[2].clone()),
            sv.add(&cst(d[3].clone())),
            sv.mul(&sv).sub(&cst(d[1].clone())),
        ],
    ];
    let spec = SolverSpec {
        layout,
        template,
        equations: vec![eq],
        problem_path: String::new(),
        elimination: Some(EliminationSpec {
            eliminated: vec![1, 2, 3],
            remaining: vec![0],
            coefficient_matrix,
            inhomogeneous: false,
        }),
        polish: None,
        sign_folds: Vec::new(),
        code_form: mingen::__internal::emit::CodeForm::Auto,
    };
    let a = emit_solver(&spec).unwrap();
    assert_eq!(a, emit_solver(&spec).unwrap());
    syn::parse_file(&a).expect("emitted code parses");
    assert!(a.starts_with(&generated_header("toyelim")));
    assert!(a.contains("mingen_runtime::null_vector3(&rows)"));
    assert!(a.contains("t: [n[0], n[1], n[2]]"));
    std::fs::write(out_dir().join("toyelim.rs"), &a).unwrap();

    // Inconsistent elimination info is an error, not a panic.
    let mut bad = spec.clone();
    bad.elimination.as_mut().unwrap().eliminated = vec![1, 2];
    assert!(emit_solver(&bad).is_err());
    let mut bad = spec.clone();
    bad.elimination = None;
    assert!(emit_solver(&bad).is_err());
}

#[test]
fn invalid_templates_are_rejected() {
    let (spec, _t) = five_point_spec();
    let mut bad = spec.clone();
    bad.template.n_reducible = 5;
    bad.template.n_excess = 5;
    assert!(emit_solver(&bad).is_err());
    let mut bad = spec.clone();
    bad.template.rows.truncate(9);
    assert!(emit_solver(&bad).is_err());
    let mut bad = spec.clone();
    bad.template.columns.swap(0, 1);
    bad.template.columns.swap(0, 15);
    assert!(emit_solver(&bad).is_err());
    let mut bad = spec.clone();
    bad.layout.name = "five-point".into();
    assert!(emit_solver(&bad).is_err(), "not a module name");
    let mut bad = spec.clone();
    bad.layout.data[1].name = bad.layout.data[0].name.clone();
    assert!(emit_solver(&bad).is_err(), "field name collision");
    // Names that differ only in case keep their spelling as fields.
    let mut cased = spec;
    cased.layout.data[1].name = cased.layout.data[0].name.to_lowercase();
    let code = emit_solver(&cased).unwrap();
    syn::parse_file(&code).expect("emitted code parses");
    let (upper, lower) = (&cased.layout.data[0].name, &cased.layout.data[1].name);
    assert!(code.contains(&format!("pub {upper}:")) && code.contains(&format!("pub {lower}:")));
    assert!(code.contains("#[allow(non_snake_case)]"));
}

/// Templates above 40 rows are allocated on the heap (here: the 5-point rows repeated to 45
/// rows; the extra rows reduce to zero and do not change the solutions).
#[test]
fn large_templates_use_the_heap() {
    let (mut spec, _t) = five_point_spec();
    spec.layout.name = "fivept_big".into();
    spec.problem_path = String::new();
    let rows = spec.template.rows.clone();
    spec.template.rows = (0..45).map(|i| rows[i % 10].clone()).collect();
    let a = emit_solver(&spec).unwrap();
    syn::parse_file(&a).expect("emitted code parses");
    assert!(a.starts_with(&generated_header("fivept_big")));
    assert!(a.contains("let mut m = vec![0.0f64; 900];"));
    assert!(a.contains("mingen_runtime::lu_solve_template_fixed::<45, 20, 10, 4>(&mut m)"));
    std::fs::write(out_dir().join("fivept_big.rs"), &a).unwrap();
}
