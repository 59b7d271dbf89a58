//! Instances read from a text file (`mingen audit FILE --instances-from DATA`), so that a
//! simulator can feed geometric instances instead of uniform random ones.
//!
//! Format: one instance per line, whitespace-separated numbers (Rust `f64` syntax), one
//! per data slot in the problem's slot order ([`ProblemLayout::data_slot_names`]; `mingen
//! inspect --json` lists them as `data_slot_names`): the data symbols in declaration
//! order, array elements in order, each element's slots in its kind's order (a point
//! `x y`, a vec3 `x y z`, a matrix row-major). Blank lines and lines starting with `#` are
//! skipped.
//!
//! A solutions file (`--solutions-from`, planted solutions) has the same format with one
//! number per unknown (declaration order, vectors element by element, eliminated unknowns
//! included, hidden ones of `nonzero` not) on the line of its instance.

use crate::problem::ProblemLayout;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why an instances file could not be read.
#[derive(Debug, Error)]
pub enum InstancesError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A line has the wrong number of columns.
    #[error("line {line}: {found} numbers, but the problem has {expected} {what} ({names})")]
    Columns {
        /// 1-based line number.
        line: usize,
        /// Numbers on the line.
        found: usize,
        /// The problem's data slot count (or unknown count, for a solutions file).
        expected: usize,
        /// `data slots` or `unknowns`.
        what: &'static str,
        /// The slot names, in order (abbreviated when long).
        names: String,
    },
    /// A column is not a finite number.
    #[error("line {line}, column {column}: `{text}` is not a finite number")]
    Number {
        /// 1-based line number.
        line: usize,
        /// 1-based column (number) index.
        column: usize,
        /// The offending text.
        text: String,
    },
    /// No instance in the file.
    #[error("no instances (every line is blank or a # comment)")]
    Empty,
}

/// Names for an error message, the middle left out when there are many.
fn abbreviated(names: &[String]) -> String {
    if names.len() <= 12 {
        return names.join(" ");
    }
    format!(
        "{} ... {}",
        names[..6].join(" "),
        names[names.len() - 3..].join(" ")
    )
}

/// Parses instances (see the module documentation) for a problem with this layout.
pub fn parse_instances(
    text: &str,
    layout: &ProblemLayout,
) -> Result<Vec<Vec<f64>>, InstancesError> {
    parse_rows(text, &layout.data_slot_names(), "data slots")
}

/// Parses planted solutions (see the module documentation): one number per name in
/// `unknowns` on each line.
pub fn parse_solutions(text: &str, unknowns: &[String]) -> Result<Vec<Vec<f64>>, InstancesError> {
    parse_rows(text, unknowns, "unknowns")
}

/// Lines of `names.len()` finite numbers.
fn parse_rows(
    text: &str,
    names: &[String],
    what: &'static str,
) -> Result<Vec<Vec<f64>>, InstancesError> {
    let expected = names.len();
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let body = line.trim();
        if body.is_empty() || body.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = body.split_whitespace().collect();
        if fields.len() != expected {
            return Err(InstancesError::Columns {
                line: i + 1,
                found: fields.len(),
                expected,
                what,
                names: abbreviated(names),
            });
        }
        let values = fields
            .iter()
            .enumerate()
            .map(|(c, f)| match f.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(InstancesError::Number {
                    line: i + 1,
                    column: c + 1,
                    text: (*f).to_string(),
                }),
            })
            .collect::<Result<Vec<f64>, _>>()?;
        out.push(values);
    }
    if out.is_empty() {
        return Err(InstancesError::Empty);
    }
    Ok(out)
}

/// Reads and parses an instances file.
pub fn read_instances(
    path: &Path,
    layout: &ProblemLayout,
) -> Result<Vec<Vec<f64>>, InstancesError> {
    parse_instances(&read_text(path)?, layout)
}

/// Reads and parses a solutions file (see [`parse_solutions`]).
pub fn read_solutions(path: &Path, unknowns: &[String]) -> Result<Vec<Vec<f64>>, InstancesError> {
    parse_solutions(&read_text(path)?, unknowns)
}

fn read_text(path: &Path) -> Result<String, InstancesError> {
    std::fs::read_to_string(path).map_err(|source| InstancesError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Writes instances in the format [`parse_instances`] reads (shortest round-trip
/// representation of each number).
pub fn format_instances<'a>(instances: impl IntoIterator<Item = &'a [f64]>) -> String {
    let mut s = String::new();
    for inst in instances {
        let line: Vec<String> = inst.iter().map(|x| format!("{x:?}")).collect();
        s.push_str(&line.join(" "));
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Problem;

    fn layout() -> ProblemLayout {
        Problem::parse(
            "problem p\nunknown x\ndata a: scalar, b: point\nb' * b * x * x - a = 0\n",
            "p.mp",
        )
        .expect("parses")
        .layout
    }

    #[test]
    fn reads_and_round_trips() {
        let l = layout();
        let text = "# a b.x b.y\n1 2 3\n\n  -0.5e-3\t4 5  \n";
        let got = parse_instances(text, &l).unwrap();
        assert_eq!(got, vec![vec![1.0, 2.0, 3.0], vec![-0.5e-3, 4.0, 5.0]]);
        let again = format_instances(got.iter().map(Vec::as_slice));
        assert_eq!(parse_instances(&again, &l).unwrap(), got);
    }

    #[test]
    fn errors_name_the_line_and_columns() {
        let l = layout();
        let e = parse_instances("1 2 3\n1 2\n", &l).unwrap_err();
        assert!(matches!(
            e,
            InstancesError::Columns {
                line: 2,
                found: 2,
                expected: 3,
                ..
            }
        ));
        assert_eq!(
            e.to_string(),
            "line 2: 2 numbers, but the problem has 3 data slots (a b.x b.y)"
        );
        let e = parse_instances("1 2 x3\n", &l).unwrap_err();
        assert!(matches!(
            e,
            InstancesError::Number {
                line: 1,
                column: 3,
                ..
            }
        ));
        assert!(matches!(
            parse_instances("1 2 inf\n", &l),
            Err(InstancesError::Number { column: 3, .. })
        ));
        assert!(matches!(
            parse_instances("# nothing\n\n", &l),
            Err(InstancesError::Empty)
        ));
    }
}
