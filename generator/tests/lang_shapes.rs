//! The problem language's names and shapes: digit-leading problem names, data and values
//! of any size, `diff` and Laurent monomials.

use mingen::Problem;

fn temp_dir(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mingen-shapes-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn digit_leading_problem_name_emits_a_valid_module() {
    let dir = temp_dir("name");
    let file = dir.join("3pra_st0.mp");
    std::fs::write(
        &file,
        "problem 3pra_st0\nunknown x, y\ndata a: scalar, b: scalar\nx^2 + y^2 = a\nx*y = b\n",
    )
    .unwrap();
    let out = mingen::build::Config::new()
        .problems(&[&file])
        .out_dir(&dir)
        .cargo_metadata(false)
        .compile()
        .unwrap();
    assert_eq!(out[0].name, "p3pra_st0");
    assert!(mingen::lang::names::is_rust_ident(&out[0].name));
    let text = std::fs::read_to_string(dir.join("p3pra_st0.rs")).unwrap();
    let parsed = syn::parse_file(&text).expect("the emitted solver parses");
    assert!(!parsed.items.is_empty());
    assert!(text.contains("const NAME: &'static str = \"3pra_st0\";"));
    // The module list of `generate --all` declares the module name.
    let m = mingen::generate::generated_mod_rs(&["p3pra_st0".to_string()]);
    syn::parse_file(&m).expect("mod.rs parses");
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
