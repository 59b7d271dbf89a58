//! Declared names that the emitter turns into Rust identifiers, checked where they are
//! declared so that a problem `inspect` accepts is one `generate` can emit: the problem
//! name becomes a module name ([`module_name`]), data and unknown symbols become struct fields (lowercased,
//! except names that differ only in case, which keep their spelling; keywords that can be
//! raw identifiers are written `r#name`). A name that cannot be emitted (`self`, a problem
//! name that is a keyword) is an error at the declaration.

use super::ast::Name;
use super::LangError;
use std::collections::HashMap;

/// Whether `s` is a Rust identifier that is not a keyword of any edition (the emitter's
/// own test, plus `gen`, reserved since edition 2024).
pub fn is_rust_ident(s: &str) -> bool {
    syn::parse_str::<proc_macro2::Ident>(s).is_ok() && !is_raw_keyword(s)
}

/// Keywords of some Rust edition (strict, reserved, and `gen` of edition 2024) that can be
/// raw identifiers. A data or unknown symbol whose field would be one is emitted as
/// `r#name`, so the code builds in a crate of any edition; `self`, `Self`, `super` and
/// `crate` cannot be raw, and a problem (module) name is never escaped.
const RAW_KEYWORDS: &[&str] = &[
    "abstract", "as", "async", "await", "become", "box", "break", "const", "continue", "do", "dyn",
    "else", "enum", "extern", "false", "final", "fn", "for", "gen", "if", "impl", "in", "let",
    "loop", "macro", "match", "mod", "move", "mut", "override", "priv", "pub", "ref", "return",
    "static", "struct", "trait", "true", "try", "type", "typeof", "unsafe", "unsized", "use",
    "virtual", "where", "while", "yield",
];

/// Whether `s` is a keyword that the emitter writes as a raw identifier (`r#s`).
pub fn is_raw_keyword(s: &str) -> bool {
    RAW_KEYWORDS.contains(&s)
}

/// The Rust module (and file stem) of a problem name: the name lowercased, with `p`
/// prepended when it starts with a digit (`8ptF_radial` gives `p8ptf_radial`, `gs5pt`
/// stays `gs5pt`). [`check_problem_name`] accepts only names whose module name is a
/// snake-case Rust identifier.
pub fn module_name(name: &str) -> String {
    let lower = name.to_lowercase();
    if lower.starts_with(|c: char| c.is_ascii_digit()) {
        format!("p{lower}")
    } else {
        lower
    }
}

/// The problem name (letters, digits and `_`, possibly starting with a digit) must give a
/// Rust module name ([`module_name`]) that is not a keyword and is snake case (no `__`
/// between other characters, which rustc's `non_snake_case` lint rejects).
pub fn check_problem_name(name: &Name) -> Result<(), LangError> {
    let n = &name.name;
    if n.is_empty() || !n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(LangError::new(
            name.pos,
            format!("problem name '{n}' may contain only letters, digits and '_'"),
        ));
    }
    let module = module_name(n);
    if module.trim_matches('_').contains("__") {
        return Err(LangError::new(
            name.pos,
            format!(
                "problem name '{n}' cannot be a Rust module name: '__' between other characters is not snake case"
            ),
        ));
    }
    if !is_rust_ident(&module) {
        return Err(LangError::new(
            name.pos,
            if module == *n {
                format!("problem name '{n}' cannot be a Rust module name (it is a Rust keyword)")
            } else {
                format!(
                    "problem name '{n}' cannot be a Rust module name ('{module}' is a Rust keyword)"
                )
            },
        ));
    }
    Ok(())
}

/// The scalar unknown names taken so far; data and unknown names are checked one by one.
#[derive(Default)]
pub struct FieldNames {
    /// Scalar names of the unknowns (`t1 t2 t3` for `t[3]`), which name the unknowns in
    /// messages and the solution's flat order.
    scalars: HashMap<String, String>,
}

impl FieldNames {
    /// Checks that a data symbol gives a field name.
    pub fn data(&mut self, name: &Name) -> Result<(), LangError> {
        field(name, "data")
    }

    /// Checks an unknown's field name and records its scalar names (`len` entries for an array).
    pub fn unknown(&mut self, name: &Name, len: Option<usize>) -> Result<(), LangError> {
        field(name, "unknown")?;
        let scalars: Vec<String> = match len {
            None => vec![name.name.clone()],
            Some(n) => (1..=n).map(|i| format!("{}{i}", name.name)).collect(),
        };
        for s in scalars {
            if let Some(other) = self.scalars.get(&s) {
                return Err(LangError::new(
                    name.pos,
                    format!(
                        "unknown '{}' gives the scalar unknown '{s}', which '{other}' already gives",
                        name.name
                    ),
                ));
            }
            self.scalars.insert(s, name.name.clone());
        }
        Ok(())
    }
}

fn field(name: &Name, what: &str) -> Result<(), LangError> {
    // The field is the lowercased name, or the name as written when another name of the
    // struct lowercases alike (`emit::structs::field_idents`): both must be identifiers.
    let lower = name.name.to_lowercase();
    for field in [&lower, &name.name] {
        if !is_rust_ident(field) && !is_raw_keyword(field) {
            return Err(LangError::new(
                name.pos,
                format!(
                    "{what} name '{}' cannot be emitted: its field name '{field}' is a Rust keyword that cannot be a raw identifier",
                    name.name
                ),
            ));
        }
    }
    Ok(())
}
