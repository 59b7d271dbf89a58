//! Declared names that the emitter turns into Rust identifiers, checked where they are
//! declared so that a problem `inspect` accepts is one `generate` can emit: the problem
//! name becomes a module name, data and unknown symbols become struct fields (lowercased).
//! A Rust keyword, or two names equal after lowercasing, is an error at the declaration.

use super::ast::Name;
use super::LangError;
use std::collections::HashMap;

/// Whether `s` is a Rust identifier that is not a keyword (the emitter's own test).
pub fn is_rust_ident(s: &str) -> bool {
    syn::parse_str::<proc_macro2::Ident>(s).is_ok()
}

/// The problem name must be a Rust module name.
pub fn check_problem_name(name: &Name) -> Result<(), LangError> {
    if is_rust_ident(&name.name) {
        Ok(())
    } else {
        Err(LangError::new(
            name.pos,
            format!(
                "problem name '{}' cannot be a Rust module name (it is a Rust keyword)",
                name.name
            ),
        ))
    }
}

/// The field names taken so far, per struct (data, solution), with the declared names.
#[derive(Default)]
pub struct FieldNames {
    data: HashMap<String, String>,
    unknowns: HashMap<String, String>,
    /// Scalar names of the unknowns (`t1 t2 t3` for `t[3]`), which name the unknowns in
    /// messages and the solution's flat order.
    scalars: HashMap<String, String>,
}

impl FieldNames {
    /// Records a data symbol's field name, or says why it cannot be one.
    pub fn data(&mut self, name: &Name) -> Result<(), LangError> {
        field(&mut self.data, name, "data")
    }

    /// Records an unknown's field name and scalar names (`len` entries for an array).
    pub fn unknown(&mut self, name: &Name, len: Option<usize>) -> Result<(), LangError> {
        field(&mut self.unknowns, name, "unknown")?;
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

fn field(taken: &mut HashMap<String, String>, name: &Name, what: &str) -> Result<(), LangError> {
    let lower = name.name.to_lowercase();
    if !is_rust_ident(&lower) {
        return Err(LangError::new(
            name.pos,
            format!(
                "{what} name '{}' cannot be emitted: its field name '{lower}' is a Rust keyword",
                name.name
            ),
        ));
    }
    if let Some(other) = taken.get(&lower) {
        return Err(LangError::new(
            name.pos,
            format!(
                "{what} name '{}' clashes with '{other}': both become the field name '{lower}' (names are lowercased)",
                name.name
            ),
        ));
    }
    taken.insert(lower, name.name.clone());
    Ok(())
}
