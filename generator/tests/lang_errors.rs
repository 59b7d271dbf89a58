//! Malformed problem files: each gives a `LangError` at the right line and column, and the
//! `mingen` binary exits with code 2 printing `FILE:LINE:COL: message`.

use mingen::{LangError, Problem};
use std::process::Command;

/// (name, source, line, column, a fragment of the message)
const CASES: &[(&str, &str, usize, usize, &str)] = &[
    (
        "unknown_symbol",
        "problem p\nunknown x\nx + y = 0\n",
        3,
        5,
        "unknown symbol 'y'",
    ),
    (
        "mat2x3_times_vec4",
        "problem p\nunknown q[4]\ndata M: mat2x3\nM * q = 0\n",
        4,
        3,
        "cannot multiply a 2x3 matrix by a 4x1 column vector: inner dimensions 3 and 4 differ",
    ),
    (
        "add_vec2_vec4",
        "problem p\nunknown q[4]\ndata w: vec2\nw + q = 0\n",
        4,
        3,
        "cannot add a 2x1 column vector and a 4x1 column vector",
    ),
    (
        "kind_too_large",
        "problem p\nunknown x\ndata w: vec100000\nx = 0\n",
        3,
        9,
        "kind 'vec100000' has too many entries (100000; at most 4096)",
    ),
    (
        "matrix_kind_too_large",
        "problem p\nunknown x\ndata M: mat1000x1000\nx = 0\n",
        3,
        9,
        "has too many entries (1000000; at most 4096)",
    ),
    (
        "declaration_too_large",
        "problem p\nunknown x\ndata M[1000]: mat40x40\nx = 0\n",
        3,
        6,
        "data 'M' has too many slots (1600000; at most 1000000 per declaration)",
    ),
    (
        "det_too_large",
        "problem p\nunknown x\ndata M: mat7x7\ndet(x*M) = 0\n",
        4,
        5,
        "det() of a 7x7 matrix is not supported",
    ),
    (
        "trace_not_square",
        "problem p\nunknown x\ndata M: mat2x3\ntrace(x*M) = 0\n",
        4,
        7,
        "trace() takes a square matrix, found a 2x3 matrix",
    ),
    (
        "ragged_matrix_literal",
        "problem p\nunknown x\n[[x, 1], [x]] = 0\n",
        3,
        10,
        "the rows of a matrix literal differ in length: 2 entries in the first, 1 in this one",
    ),
    (
        "diff_by_data",
        "problem p\nunknown x\ndata a: scalar\ndiff(x*a, a) = 0\n",
        4,
        11,
        "diff(EXPR, x) differentiates by an unknown scalar",
    ),
    (
        "diff_one_argument",
        "problem p\nunknown x\ndiff(x) = 0\n",
        3,
        7,
        "',' between the two arguments of diff",
    ),
    (
        "diff_declared",
        "problem p\nunknown diff\n",
        2,
        9,
        "'diff' is built in",
    ),
    (
        "problem_name_dot",
        "problem 1.5pt\nunknown x\nx = 0\n",
        1,
        9,
        "problem name '1.5pt' may contain only letters, digits and '_'",
    ),
    (
        "mat_times_row",
        "problem p\nunknown t[3]\ndata R: mat3\nR * t' = 0\n",
        4,
        3,
        "cannot multiply a 3x3 matrix by a 1x3 row vector",
    ),
    (
        "mat_times_2vector",
        "problem p\nunknown q[2]\ndata R: mat3\nR * q = 0\n",
        4,
        3,
        "cannot multiply a 3x3 matrix by a 2x1 column vector: inner dimensions 3 and 2 differ",
    ),
    (
        "add_vector_to_matrix",
        "problem p\nunknown t[3]\nt + I = 0\n",
        3,
        3,
        "cannot add a 3x1 column vector and a 3x3 matrix",
    ),
    (
        "unclosed_brace",
        "problem p\nunknown x\nfor k in 0..3 {\n  x = k\n",
        3,
        15,
        "unclosed '{'",
    ),
    (
        "bad_range",
        "problem p\nunknown x\nfor k in 5..2 {\n  x = k\n}\n",
        3,
        13,
        "empty range 5..2",
    ),
    (
        "duplicate_name",
        "problem p\nunknown x, x\nx = 1\n",
        2,
        12,
        "duplicate name 'x'",
    ),
    (
        "eliminate_data",
        "problem p\nunknown x\ndata d: scalar\nx = d\neliminate d\n",
        5,
        11,
        "'d' is data, not an unknown",
    ),
    (
        "missing_problem",
        "# no header\nunknown x\nx = 1\n",
        2,
        1,
        "expected 'problem NAME'",
    ),
    (
        "bad_kind",
        "problem p\nunknown x\ndata d: vector\n",
        3,
        9,
        "unknown kind 'vector'",
    ),
    (
        "index_out_of_range",
        "problem p\nunknown t[3]\ndata y[2]: point\ny[2]' * t = 0\n",
        4,
        3,
        "index 2 out of range for 'y'",
    ),
    (
        "unexpected_token",
        "problem p\nunknown x\nx = = 1\n",
        3,
        5,
        "expected an expression, found '='",
    ),
    (
        "unterminated_expression",
        "problem p\nunknown x\nx = x +\n",
        3,
        8,
        "expected an expression after '+', found end of line",
    ),
    (
        "transpose_of_nothing",
        "problem p\nunknown t[3]\n' * t = 0\n",
        3,
        1,
        "transpose of nothing",
    ),
    (
        "unclosed_paren",
        "problem p\nunknown x\nx = (x + 1\n",
        4,
        1,
        "expected ')' to close '(' at 3:5",
    ),
    (
        "no_equals",
        "problem p\nunknown x\nx + 1\n",
        3,
        6,
        "expected '=' in an equation",
    ),
    (
        "sides_differ",
        "problem p\nunknown t[3]\nt = 1\n",
        3,
        3,
        "the sides of '=' differ in shape",
    ),
    (
        "det_of_vector",
        "problem p\nunknown t[3]\ndet(t) = 0\n",
        3,
        5,
        "det() takes a square matrix, found a 3x1 column vector",
    ),
    (
        "declaration_in_loop",
        "problem p\nunknown x\nfor k in 0..2 {\n  unknown y\n}\n",
        4,
        3,
        "must be at the top level",
    ),
    (
        "bad_character",
        "problem p\nunknown x\nx = $\n",
        3,
        5,
        "unexpected character '$'",
    ),
    (
        "divide_by_data",
        "problem p\nunknown x\ndata a: scalar\nx / a = 1\n",
        4,
        5,
        "the divisor must be a constant (numbers and loop variables only)",
    ),
    (
        "divide_by_polynomial",
        "problem p\nunknown x\nx / (x + 1) = 1\n",
        3,
        5,
        "the divisor must be a monomial in the unknowns",
    ),
    (
        "divide_by_data_times_unknown",
        "problem p\nunknown x\ndata a: scalar\n1 / (a*x) = 1\n",
        4,
        5,
        "the divisor must be a monomial in the unknowns",
    ),
    (
        "negative_power_of_matrix",
        "problem p\nunknown x\ndata M: mat3\n(x*M)^-1 = 0\n",
        4,
        1,
        "the divisor must be a scalar monomial in the unknowns, found a 3x3 matrix",
    ),
    (
        "laurent_nonzero",
        "problem p\nunknown x\nnonzero 1/x\nx = 1\n",
        3,
        9,
        "'nonzero' needs a polynomial",
    ),
    (
        "duplicate_problem",
        "problem p\nproblem q\nunknown x\nx = 1\n",
        2,
        1,
        "duplicate 'problem'",
    ),
    (
        "no_equations",
        "problem p\nunknown x\n",
        1,
        1,
        "no equations",
    ),
    (
        "unindexed_array",
        "problem p\nunknown t[3]\ndata x1[5]: point\nx1' * t = 0\n",
        4,
        1,
        "'x1' is an array of 5 points",
    ),
    (
        "unknown_function",
        "problem p\nunknown t[3]\nnorm(t) = 0\n",
        3,
        1,
        "unknown function 'norm'",
    ),
    (
        "builtin_declared",
        "problem p\nunknown I\nI = 0\n",
        2,
        9,
        "'I' is built in",
    ),
    (
        "keyword_as_name",
        "problem p\nunknown for\n",
        2,
        9,
        "found the keyword 'for'",
    ),
    (
        "bad_matrix_literal",
        "problem p\nunknown x\nlet M = [[x, 0, 0], [0, x], [0, 0, x]]\ndet(M) = 0\n",
        3,
        21,
        "the rows of a matrix literal differ in length: 3 entries in the first, 2 in this one",
    ),
    (
        "stray_brace",
        "problem p\nunknown x\n}\n",
        3,
        1,
        "unexpected '}'",
    ),
    (
        "rust_keyword_data",
        "problem p\nunknown x\ndata a: scalar, self: scalar\nx - self = 0\n",
        3,
        17,
        "data name 'self' cannot be emitted: its field name 'self' is a Rust keyword",
    ),
    (
        "rust_keyword_after_lowercasing",
        "problem p\nunknown Crate\nCrate = 0\n",
        2,
        9,
        "field name 'crate' is a Rust keyword",
    ),
    (
        "scalar_name_clash",
        "problem p\nunknown t[3], t2\nt2 = 0\n",
        2,
        15,
        "unknown 't2' gives the scalar unknown 't2', which 't' already gives",
    ),
    (
        "problem_name_keyword",
        "problem struct\nunknown x\nx = 0\n",
        1,
        9,
        "problem name 'struct' cannot be a Rust module name",
    ),
    (
        "array_length_zero",
        "problem p\nunknown t[0]\n",
        2,
        11,
        "array length must be at least 1",
    ),
];

fn parse_err(src: &str) -> LangError {
    match Problem::parse(src, "case.mp") {
        Ok(_) => panic!("expected an error for:\n{src}"),
        Err(e) => e,
    }
}

#[test]
fn malformed_files_give_positioned_errors() {
    for (name, src, line, col, fragment) in CASES {
        let e = parse_err(src);
        assert_eq!(
            (e.line, e.column),
            (*line, *col),
            "{name}: got {e} (expected {line}:{col})"
        );
        assert!(
            e.message.contains(fragment),
            "{name}: message {:?} lacks {fragment:?}",
            e.message
        );
        assert_eq!(e.file, "case.mp");
        assert!(e
            .to_string()
            .starts_with(&format!("case.mp:{line}:{col}: ")));
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let deep = format!(
        "problem p\nunknown x\nx = {}x{}\n",
        "(".repeat(100),
        ")".repeat(100)
    );
    let e = parse_err(&deep);
    assert!(e.message.contains("nested too deeply"), "{e}");
    assert_eq!(e.line, 3);
    let minus = format!("problem p\nunknown x\nx = {}x\n", "-".repeat(10_000));
    assert!(parse_err(&minus).message.contains("nested too deeply"));
    let mut loops = String::from("problem p\nunknown x\n");
    for _ in 0..100 {
        loops.push_str("for k in 0..1 {\n");
    }
    let e = parse_err(&loops);
    assert!(e.message.contains("nested too deeply"), "{e}");
    // Long flat chains are fine (no recursion on chain length).
    let chain = format!("problem p\nunknown x\nx = 0{}\n", " + x".repeat(20_000));
    assert!(Problem::parse(&chain, "chain.mp").is_ok());
    let high = format!("problem p\nunknown x\nx{} = 1\n", " * x".repeat(300));
    assert!(parse_err(&high).message.contains("degree too high"));
    let huge = "problem p\nunknown x\nfor i in 0..100000 {\n for j in 0..100000 {\n x = 1\n }\n}\n";
    assert!(parse_err(huge).message.contains("too many"));
}

#[test]
fn language_features_parse() {
    let src = "# features\nproblem feat; unknown a[3], q[4], x\n\
               data d: scalar, R: rotation, u[2]: vec3,\n  M: mat3\n\
               let S = [[x, 0, 1/2], [0, 1, 0], [0.25, 0, x]]\n\
               for i in 0..2 { for j in 0..3 {\n u[i][j] * q[j + 1] - R[j][i] = 0\n } }\n\
               det(S * M') + trace(skew(a) * skew(u[0]')) = d / 2\n\
               (a' * a)' = 1\n\
               [x, 0, 0] = (R * u[1])\n";
    let p = Problem::parse(src, "f.mp").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.equation_count(), 6 + 1 + 1 + 3);
    assert_eq!(
        p.unknown_names(),
        ["a1", "a2", "a3", "q1", "q2", "q3", "q4", "x"]
    );
    assert_eq!(p.layout.data_slot_count(), 1 + 9 + 6 + 9);
    assert_eq!(p.data_slot_names()[1], "R[0][0]");
    assert_eq!(p.data_slot_names()[10], "u[0].x");
    // 0.25 and 1/2 are exact.
    let e = p.expand();
    assert_eq!(e.len(), 11);
}

#[test]
fn cross_and_dot_are_skew_and_transpose_products() {
    let with_calls = "problem p; unknown t[3]\ndata x1: point, x2: point, R: rotation\n\
                      dot(x2, cross(t, R * x1)) = 0\ndot(t, t) = 1\n";
    let written_out = "problem p; unknown t[3]\ndata x1: point, x2: point, R: rotation\n\
                       x2' * (skew(t) * (R * x1)) = 0\nt' * t = 1\n";
    let (a, b) = (
        Problem::parse(with_calls, "a.mp").unwrap_or_else(|e| panic!("{e}")),
        Problem::parse(written_out, "b.mp").unwrap_or_else(|e| panic!("{e}")),
    );
    assert_eq!(a.expand(), b.expand());
    let e = parse_err("problem p\nunknown t[3]\ndata a: vec3\ncross(a) = t\n");
    assert!(e.to_string().contains("two arguments of cross"), "{e}");
}

#[test]
fn a_byte_order_mark_and_windows_line_ends_are_accepted() {
    let p = Problem::parse(
        "\u{feff}problem p\r\nunknown x\r\ndata a: scalar\r\nx^2 = a\r\n",
        "w.mp",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.equation_count(), 1);
}

#[test]
fn an_unknown_with_a_kind_says_how_to_declare_it() {
    let e = parse_err("problem p\nunknown q: vec3\ndata a: scalar\nq[0] = a\n");
    assert!(e.to_string().contains("unknowns have no kind"), "{e}");
    assert_eq!((e.line, e.column), (2, 10), "{e}");
}

#[test]
fn decimal_exponents_are_exact() {
    let a = Problem::parse(
        "problem p; unknown x, y\nx * 1e-3 + 2.5E2 * y = 0.25e1\nx*y = 1E+1\n",
        "a.mp",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let b = Problem::parse(
        "problem p; unknown x, y\nx * 0.001 + 250 * y = 2.5\nx*y = 10\n",
        "b.mp",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.expand(), b.expand());
    let e = parse_err("problem p\nunknown x\nx = 1e5000\n");
    assert!(e.to_string().contains("out of range"), "{e}");
}

#[test]
fn integer_powers_are_repeated_products() {
    let with_powers = "problem p; unknown c, s, t[3]\ndata a: scalar, R: rotation\n\
                       c^2 + s^2 = 1\n-a * c^3 + (t' * t)^2 = s\n(R^2 * t)[0] = a\n";
    let written_out = "problem p; unknown c, s, t[3]\ndata a: scalar, R: rotation\n\
                       c*c + s*s = 1\n-(a * (c*c*c)) + (t' * t)*(t' * t) = s\n((R*R) * t)[0] = a\n";
    let (a, b) = (
        Problem::parse(with_powers, "a.mp").unwrap_or_else(|e| panic!("{e}")),
        Problem::parse(written_out, "b.mp").unwrap_or_else(|e| panic!("{e}")),
    );
    assert_eq!(a.expand(), b.expand());
    for (src, fragment) in [
        ("x^0 = 1", "integer from 1 to 32"),
        ("x^33 = 1", "integer from 1 to 32"),
        ("x^2.5 = 1", "integer exponent after '^'"),
        ("x^y = 1", "integer exponent after '^'"),
        ("x^ = 1", "integer exponent after '^'"),
    ] {
        let e = parse_err(&format!("problem p\nunknown x, y\n{src}\n"));
        assert!(e.to_string().contains(fragment), "{src}: {e}");
        assert_eq!(e.line, 3, "{src}: {e}");
    }
}

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mingen"))
}

#[test]
fn binary_reports_errors_with_exit_code_2() {
    let dir = std::env::temp_dir().join(format!("mingen-lang-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, src, line, col, fragment) in CASES {
        let path = dir.join(format!("{name}.mp"));
        std::fs::write(&path, src).unwrap();
        let out = bin().arg("inspect").arg(&path).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{name}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let expected = format!("{}:{line}:{col}: ", path.display());
        assert!(
            stderr.starts_with(&expected) && stderr.contains(fragment),
            "{name}: stderr {stderr:?}"
        );
        assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: one line");
        assert!(out.stdout.is_empty(), "{name}: no partial output");
    }
    let missing = dir.join("does-not-exist.mp");
    let out = bin().arg("inspect").arg(&missing).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("does-not-exist.mp") && stderr.contains("cannot read"));
    // Not a regular file: refused at once, never waiting for a writer.
    let not_files = {
        let mut v = vec![dir.clone()];
        #[cfg(unix)]
        {
            let fifo = dir.join("fifo.mp");
            let made = Command::new("mkfifo").arg(&fifo).status();
            if made.is_ok_and(|s| s.success()) {
                v.push(fifo);
            }
        }
        v
    };
    for path in &not_files {
        let out = bin().arg("inspect").arg(path).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{}", path.display());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("not a regular file"), "{stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1);
    }
    let huge = dir.join("huge.mp");
    let f = std::fs::File::create(&huge).unwrap();
    f.set_len(mingen::MAX_PROBLEM_FILE_BYTES + 1).unwrap();
    let err = Problem::from_file(&huge).unwrap_err().to_string();
    assert!(err.contains("larger than 16 MiB"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn binary_inspects_shipped_problems() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../templates/grsrp.mp");
    // Both forms at once: each plans the problem, on a core of its own.
    let piped = |args: &[&str]| {
        bin()
            .args(args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    let json = piped(&["inspect", path, "--json"]);
    let text = piped(&["inspect", path]);
    let out = json.wait_with_output().unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["name"], "grsrp");
    assert_eq!(
        v["unknowns"],
        serde_json::json!(["a1", "a2", "a3", "t1", "t2", "t3"])
    );
    assert_eq!(v["equations"], 6);
    assert_eq!(v["equation_degrees"], serde_json::json!([2, 2, 2, 2, 2, 2]));
    assert_eq!(v["data"][0]["kind"], "point");
    assert_eq!(v["equation_supports"][5][0], "t1^2");
    let text = text.wait_with_output().unwrap();
    assert!(text.status.success());
    let s = String::from_utf8_lossy(&text.stdout);
    assert!(s.contains("problem grsrp") && s.contains("a1*t1"));
}
