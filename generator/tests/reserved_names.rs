//! Symbols named by Rust keywords (`gen` is reserved from edition 2024 on) are emitted as
//! raw identifiers, so the solver builds in a crate of any edition; names that cannot be
//! emitted at all are refused where they are declared.

use mingen::Problem;
use mingen::TemplateOptions;
use mingen::{emit_plan_from, plan};

#[test]
fn keyword_symbols_become_raw_identifiers() {
    let src = "problem kw\nunknown gen\nunknown fn\ndata try: scalar\ndata b: scalar\n\
               gen^2 + fn - try = 0\nfn^2 - b = 0\n";
    let problem = Problem::parse(src, "kw.mp").unwrap();
    let p = plan(problem, "kw.mp", &TemplateOptions::default()).unwrap();
    let code = emit_plan_from(&p, "kw.mp").unwrap();
    for raw in ["pub r#gen: f64", "pub r#fn: f64", "pub r#try: f64"] {
        assert!(code.contains(raw), "{raw} missing");
    }
    syn::parse_file(&code).expect("the emitted solver parses");
}

#[test]
fn names_that_cannot_be_emitted_are_refused_at_their_declaration() {
    for (src, word, line) in [
        ("problem gen\nunknown x\nx = 1\n", "gen", 1),
        ("problem p\nunknown self\nself = 1\n", "self", 2),
    ] {
        let e = Problem::parse(src, "t.mp").unwrap_err();
        assert!(e.to_string().contains(word), "{src}: {e}");
        assert_eq!(e.line, line, "{src}: {e}");
    }
}
