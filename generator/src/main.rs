//! The `mingen` command line. Each subcommand is one function returning a [`CliError`];
//! `main` prints the error on one line and exits with its code (2 for bad input).

use clap::{Parser, Subcommand};
use mingen::algebra::MonomialOrder;
use mingen::{Problem, ProblemError};
use serde_json::{json, Map, Value};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "mingen", version, about = "Minimal-solver generator")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Parse a problem file and describe it: unknowns, data, equations (degree and
    /// monomial support in the unknowns).
    Inspect {
        /// The problem file (`templates/*.mp`).
        file: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
}

/// A failure reported on one line of stderr with an exit code.
struct CliError {
    message: String,
    code: u8,
}

impl From<ProblemError> for CliError {
    fn from(e: ProblemError) -> Self {
        CliError {
            message: e.to_string(),
            code: 2,
        }
    }
}

/// `writeln!` into a `String` (infallible).
macro_rules! outln {
    ($out:expr, $($arg:tt)*) => {{
        use std::fmt::Write as _;
        let _ = writeln!($out, $($arg)*);
    }};
}

/// Writes to stdout; a closed pipe (`mingen inspect F | head`) is not an error.
fn emit(text: &str) -> Result<(), CliError> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
    {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(CliError {
            message: format!("cannot write the output: {e}"),
            code: 1,
        }),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Inspect { file, json } => inspect(&file, json),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{}", e.message);
            ExitCode::from(e.code)
        }
    }
}

/// The language-level facts about a problem, as a JSON object that later stages (Gröbner
/// basis, template) extend with their own keys.
fn problem_summary(p: &Problem) -> Map<String, Value> {
    let names = p.unknown_names();
    let equations = p.expand();
    let mut m = Map::new();
    m.insert("name".into(), json!(p.name()));
    m.insert("unknowns".into(), json!(names));
    m.insert(
        "data".into(),
        Value::Array(
            p.layout
                .data
                .iter()
                .map(|d| {
                    json!({
                        "name": d.name,
                        "kind": d.kind.keyword(),
                        "len": d.len,
                        "slots": d.slot_count(),
                    })
                })
                .collect(),
        ),
    );
    m.insert("data_slots".into(), json!(p.layout.data_slot_count()));
    m.insert("equations".into(), json!(equations.len()));
    m.insert(
        "equation_degrees".into(),
        json!(equations
            .iter()
            .map(|e| e.degree().unwrap_or(0))
            .collect::<Vec<_>>()),
    );
    m.insert(
        "equation_supports".into(),
        json!(equations
            .iter()
            .map(|e| e
                .support(MonomialOrder::Grevlex)
                .iter()
                .map(|mono| mono.display_with(&names))
                .collect::<Vec<_>>())
            .collect::<Vec<_>>()),
    );
    m.insert(
        "eliminated".into(),
        json!(p
            .layout
            .eliminate
            .iter()
            .filter_map(|&i| names.get(i).cloned())
            .collect::<Vec<_>>()),
    );
    m
}

fn inspect(file: &PathBuf, as_json: bool) -> Result<(), CliError> {
    let p = Problem::from_file(file)?;
    let summary = problem_summary(&p);
    if as_json {
        let text = serde_json::to_string_pretty(&Value::Object(summary)).unwrap_or_default();
        return emit(&format!("{text}\n"));
    }
    let names = p.unknown_names();
    let mut out = String::new();
    outln!(out, "problem {}", p.name());
    outln!(out, "unknowns ({}): {}", names.len(), names.join(" "));
    if !p.layout.eliminate.is_empty() {
        let el: Vec<&str> = p
            .layout
            .eliminate
            .iter()
            .filter_map(|&i| names.get(i).map(String::as_str))
            .collect();
        outln!(out, "eliminate: {}", el.join(" "));
    }
    outln!(out, "data ({} slots):", p.layout.data_slot_count());
    for d in &p.layout.data {
        let len = d.len.map(|n| format!("[{n}]")).unwrap_or_default();
        outln!(out, "  {}{}: {}", d.name, len, d.kind.keyword());
    }
    let lines = p.equation_lines();
    let equations = p.expand();
    outln!(out, "equations: {}", equations.len());
    for (i, (e, line)) in equations.iter().zip(&lines).enumerate() {
        let support: Vec<String> = e
            .support(MonomialOrder::Grevlex)
            .iter()
            .map(|m| m.display_with(&names))
            .collect();
        let data_terms: usize = e.terms().map(|(_, c)| c.len()).sum();
        outln!(
            out,
            "  [{i}] line {line}: degree {}, {} monomials, {} data terms: {}",
            e.degree().unwrap_or(0),
            support.len(),
            data_terms,
            support.join(" ")
        );
    }
    emit(&out)
}
