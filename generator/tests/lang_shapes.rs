//! The problem language's names and shapes: digit-leading problem names, data and values
//! of any size, `diff` and Laurent monomials.

use mingen::Problem;

fn temp_dir(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mingen-shapes-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A fresh directory for test `tag` holding the problem file `name` with `source`.
fn problem_file(tag: &str, name: &str, source: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let dir = temp_dir(tag);
    let file = dir.join(name);
    std::fs::write(&file, source).unwrap();
    (dir, file)
}

/// Emits the solver of `file` into `dir` through the build-script API.
fn compile(dir: &std::path::Path, file: &std::path::Path) -> Vec<mingen::build::Compiled> {
    mingen::build::Config::new()
        .problems(&[file])
        .out_dir(dir)
        .cargo_metadata(false)
        .compile()
        .unwrap()
}

#[test]
fn digit_leading_problem_name_emits_a_valid_module() {
    let (dir, file) = problem_file(
        "name",
        "3pra_st0.mp",
        "problem 3pra_st0\nunknown x, y\ndata a: scalar, b: scalar\nx^2 + y^2 = a\nx*y = b\n",
    );
    let out = compile(&dir, &file);
    assert_eq!(out[0].name, "p3pra_st0");
    assert!(mingen::__internal::lang::names::is_rust_ident(&out[0].name));
    let text = std::fs::read_to_string(dir.join("p3pra_st0.rs")).unwrap();
    let parsed = syn::parse_file(&text).expect("the emitted solver parses");
    assert!(!parsed.items.is_empty());
    assert!(text.contains("const NAME: &'static str = \"3pra_st0\";"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn problem_names_as_users_write_them() {
    for (src, name, module) in [
        ("problem 8ptF_radial", "8ptF_radial", "p8ptf_radial"),
        ("problem 3pra_st0", "3pra_st0", "p3pra_st0"),
        ("problem P3P", "P3P", "p3p"),
        ("problem gs5pt", "gs5pt", "gs5pt"),
        ("problem 1e5pt", "1e5pt", "p1e5pt"),
    ] {
        let p = Problem::parse(&format!("{src}\nunknown x\nx = 1\n"), "t.mp").unwrap();
        assert_eq!(p.layout.name, name);
        assert_eq!(p.layout.module_name(), module);
    }
    for (src, msg) in [
        ("problem 1.5pt", "may contain only letters, digits and '_'"),
        (
            "problem a__b",
            "'__' between other characters is not snake case",
        ),
        ("problem Fn", "('fn' is a Rust keyword)"),
        ("problem 8pt x", "expected end of line after the statement"),
    ] {
        let e = Problem::parse(&format!("{src}\nunknown x\nx = 1\n"), "t.mp").unwrap_err();
        assert!(e.to_string().contains(msg), "{src}: {e}");
        assert_eq!(e.line, 1, "{src}");
    }
}

/// `evaluate_direct` (nalgebra matrices, LU determinants) and the polynomial tape
/// (`try_evaluate` over f64, cofactor determinants) agree at random data and unknowns.
fn agree_with_direct_evaluation(p: &Problem, seed: u64) {
    use mingen::__internal::algebra::Ring;
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let data = mingen::__internal::instance::random_data_f64(&p.layout, &mut rng);
    assert_eq!(data.len(), p.layout.data_slot_count());
    let x: Vec<f64> = (0..p.layout.unknown_count())
        .map(|_| rng.gen_range(-1.0..1.0))
        .collect();
    let direct = p.evaluate_direct(&data, &x);
    let polys = p.try_evaluate::<f64>(&data).unwrap();
    let ring = p.evaluate_direct_ring::<f64>(&data, &x).unwrap();
    assert_eq!(direct.len(), polys.len());
    for ((d, poly), r) in direct.iter().zip(&polys).zip(&ring) {
        let v: f64 = poly
            .terms()
            .map(|(m, c)| {
                m.0.iter()
                    .enumerate()
                    .fold(*c, |acc, (i, &e)| acc * x[i].powi(i32::from(e)))
            })
            .fold(f64::zero(), |a, b| a + b);
        assert!((d - v).abs() < 1e-9 * (1.0 + d.abs()), "{d} vs {v}");
        assert!((d - r).abs() < 1e-9 * (1.0 + d.abs()), "{d} vs {r}");
    }
}

#[test]
fn data_kinds_of_any_size_have_slots_and_shapes() {
    let src = "problem sizes\nunknown q[4], x\n\
               data w: vec4, M: mat2x3, v: vec1, A[2]: mat2x2, u: vec3, R: mat3x3\n\
               M * [q[0], q[1], q[2]] = [w[0], w[3]]\n\
               A[1] * [x, q[3]] - w[1] * [1, 2] = 0\n\
               q' * q = 1 + v\n\
               u' * R * u = x\n";
    let p = Problem::parse(src, "sizes.mp").unwrap();
    let names = p.data_slot_names();
    assert_eq!(p.layout.data_slot_count(), 4 + 6 + 1 + 8 + 3 + 9);
    assert_eq!(&names[..4], ["w[0]", "w[1]", "w[2]", "w[3]"]);
    assert_eq!(names[4], "M[0][0]");
    assert_eq!(names[6], "M[0][2]");
    assert_eq!(names[9], "M[1][2]");
    assert_eq!(names[10], "v[0]");
    assert_eq!(names[11], "A[0][0][0]");
    assert_eq!(names[18], "A[1][1][1]");
    assert_eq!(names[19], "u.x");
    assert_eq!(names[22], "R[0][0]");
    let kinds: Vec<String> = p.layout.data.iter().map(|d| d.kind.keyword()).collect();
    assert_eq!(kinds, ["vec4", "mat2x3", "vec1", "mat2x2", "vec3", "mat3"]);
    // 2 + 2 + 1 + 1 scalar equations, row-major.
    assert_eq!(p.equation_count(), 6);
    agree_with_direct_evaluation(&p, 1);
}

#[test]
fn values_of_any_shape() {
    let src = "problem shapes\nunknown q[4], x, y\ndata B: mat4x4, C: mat2x3, w: vec5\n\
               let m = [[x, 1, 2], [y, x, 3]]\n\
               m * C' - C * m' = 0\n\
               let z = [q[0], q[1], q[2], q[3], x]\n\
               dot(z, w) = 0\n\
               det(x * B + [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) = 0\n\
               trace(B * x) - y = 0\n\
               det([[x, y], [1, x]]) - q[0] = 0\n\
               m[1] * [x, y, 1] = m[0][2]\n\
               det([[q[0], 1, 2, 3, 4, 5], [1, q[1], 0, 0, 0, 0], [2, 0, q[2], 0, 0, 0], \
                    [3, 0, 0, q[3], 0, 0], [4, 0, 0, 0, x, 0], [5, 0, 0, 0, 0, y]]) = 1\n\
               q' * B * q = 1\n";
    let p = Problem::parse(src, "shapes.mp").unwrap();
    // 4 (2x2) + 1 + 1 + 1 + 1 + 1 + 1 + 1
    assert_eq!(p.equation_count(), 11);
    agree_with_direct_evaluation(&p, 2);
    agree_with_direct_evaluation(&p, 3);
}

#[test]
fn emitted_data_struct_for_sized_kinds() {
    let (dir, file) = problem_file(
        "data",
        "sized.mp",
        "problem sized\nunknown x, y\ndata w: vec4, M: mat2x3, big: vec40\n\
         x^2 + w[0]*y = w[1] + big[39]\ny^2 + M[0][1]*x = M[1][2]\n",
    );
    let out = compile(&dir, &file);
    let text = std::fs::read_to_string(&out[0].path).unwrap();
    syn::parse_file(&text).expect("the emitted solver parses");
    assert!(text.contains("pub w: [f64; 4],"), "{text}");
    assert!(text.contains("pub m: [[f64; 3]; 2],"));
    assert!(text.contains("pub big: [f64; 40],"));
    // [f64; 40] has no Default: the struct implements it by hand.
    assert!(text.contains("impl Default for Data"));
    assert!(text.contains("slots[9]") && text.contains("data.m[1][2]"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn diff_matches_the_hand_expanded_derivative() {
    let by_diff = "problem g\nunknown x, y\ndata a: scalar, b: scalar\n\
                   let cost = (x^2*y - a)^2 + (x + b*y)^2\n\
                   diff(cost, x) = 0\ndiff(cost, y) = 0\ndiff(cost, x) + diff(a*b, y) = 0\n";
    let by_hand = "problem g\nunknown x, y\ndata a: scalar, b: scalar\n\
                   2*(x^2*y - a)*(2*x*y) + 2*(x + b*y) = 0\n\
                   2*(x^2*y - a)*x^2 + 2*b*(x + b*y) = 0\n\
                   4*x^3*y^2 - 4*a*x*y + 2*x + 2*b*y = 0\n";
    let d = Problem::parse(by_diff, "d.mp").unwrap().expand();
    let h = Problem::parse(by_hand, "h.mp").unwrap().expand();
    assert_eq!(d, h);
    // Entries of a vector unknown, matrix expressions and determinants.
    let src = "problem g\nunknown q[3]\ndata A: mat3, B: mat3, C: mat2x2\n\
               diff(det(A + q[0]*B + q[1]*q[2]*I), q[0]) = 0\n\
               diff(det(C*q[1] + [[q[0], 0], [0, 1]]), q[1]) = 0\n\
               diff(q' * A * q, q[2]) = 0\n";
    let p = Problem::parse(src, "g.mp").unwrap();
    let hand = "problem g\nunknown q[3]\ndata A: mat3, B: mat3, C: mat2x2\n\
                0 = 0\n0 = 0\n((A + A') * q)[2] = 0\n";
    let h = Problem::parse(hand, "h.mp").unwrap();
    assert_eq!(p.expand()[2], h.expand()[2]);
    // Central differences of the determinant equations at a random point.
    let data: Vec<f64> = (0..p.layout.data_slot_count())
        .map(|k| ((k * 37 % 11) as f64 - 5.0) / 7.0)
        .collect();
    let at = [0.3, -0.7, 0.4];
    let f = |q: [f64; 3]| {
        let src = "problem f\nunknown q[3]\ndata A: mat3, B: mat3, C: mat2x2\n\
                   det(A + q[0]*B + q[1]*q[2]*I) = 0\ndet(C*q[1] + [[q[0], 0], [0, 1]]) = 0\n";
        Problem::parse(src, "f.mp")
            .unwrap()
            .evaluate_direct(&data, &q)
    };
    let h = 1e-5;
    let g = p.evaluate_direct(&data, &at);
    let (plus0, minus0) = (f([at[0] + h, at[1], at[2]]), f([at[0] - h, at[1], at[2]]));
    let (plus1, minus1) = (f([at[0], at[1] + h, at[2]]), f([at[0], at[1] - h, at[2]]));
    assert!((g[0] - (plus0[0] - minus0[0]) / (2.0 * h)).abs() < 1e-6);
    assert!((g[1] - (plus1[1] - minus1[1]) / (2.0 * h)).abs() < 1e-6);
}

#[test]
fn laurent_equations_are_multiplied_by_the_smallest_clearing_monomial() {
    let laurent = "problem l\nunknown x, y\ndata a: scalar, b: scalar\n\
                   x + x^-1 = a\ny/x + 2/(x*y) = b\nx * x^-1 = a\nx^-2 * y = 1\n\
                   (x*y)^-1 * x^3 - a = 0\n";
    let hand = "problem l\nunknown x, y\ndata a: scalar, b: scalar\n\
                x^2 + 1 = a*x\ny^2 + 2 = b*x*y\n1 = a\ny = x^2\nx^2 - a*y = 0\n";
    let l = Problem::parse(laurent, "l.mp").unwrap();
    let h = Problem::parse(hand, "h.mp").unwrap();
    assert_eq!(l.expand(), h.expand());
    agree_with_direct_evaluation(&l, 4);
    let (data, x) = ([0.5, -1.5], [0.7, -0.3]);
    assert_eq!(l.evaluate_direct(&data, &x).len(), 5);
    for (u, v) in l
        .evaluate_direct(&data, &x)
        .iter()
        .zip(h.evaluate_direct(&data, &x))
    {
        assert!((u - v).abs() < 1e-12, "{u} vs {v}");
    }
    // A Laurent problem solves like its polynomial form: x^2 - a x + 1 = 0 and
    // y^2 - b x y + 2 = 0 have 4 solutions.
    let (dir, file) = problem_file(
        "laurent",
        "l.mp",
        "problem laurent2\nunknown x, y\ndata a: scalar, b: scalar\n\
         x + 1/x = a\ny/x + 2/(x*y) = b\n",
    );
    let plan = mingen::plan_file(&file, &Default::default()).unwrap();
    assert_eq!(plan.summary_json()["solutions"], 4);
    std::fs::remove_dir_all(&dir).unwrap();
}
