//! The `mingen` command line. Each subcommand is one function returning a [`CliError`];
//! `main` prints the error on one line and exits with its code (2 for bad input).

use clap::{Parser, Subcommand};
use mingen::algebra::MonomialOrder;
use mingen::generate::{plan_file, problem_files, workspace_root, GenerateError};
use mingen::template::TemplateOptions;
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
    /// Emit solver/src/generated/<name>.rs for problem files (or all of templates/*.mp).
    Generate {
        /// Problem files.
        files: Vec<PathBuf>,
        /// Every problem file in templates/ (and the module list generated/mod.rs).
        #[arg(long)]
        all: bool,
        /// Write nothing; exit 1 naming each stale or missing generated file.
        #[arg(long)]
        check: bool,
    },
}

/// A failure reported on one line of stderr with an exit code.
struct CliError {
    message: String,
    code: u8,
}

impl From<GenerateError> for CliError {
    fn from(e: GenerateError) -> Self {
        CliError {
            message: e.to_string(),
            code: 2,
        }
    }
}

impl From<ProblemError> for CliError {
    fn from(e: ProblemError) -> Self {
        CliError {
            message: e.to_string(),
            code: 2,
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Inspect { file, json } => inspect(&file, json),
        Command::Generate { files, all, check } => generate(files, all, check),
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
    let mut summary = problem_summary(&p);
    let plan = plan_file(file, &TemplateOptions::default())?;
    if let Value::Object(algebra) = plan.summary_json() {
        summary.extend(algebra);
    }
    if as_json {
        println!(
            "{}",
            serde_json::to_string_pretty(&Value::Object(summary)).unwrap_or_default()
        );
        return Ok(());
    }
    let names = p.unknown_names();
    println!("problem {}", p.name());
    println!("unknowns ({}): {}", names.len(), names.join(" "));
    if !p.layout.eliminate.is_empty() {
        let el: Vec<&str> = p
            .layout
            .eliminate
            .iter()
            .filter_map(|&i| names.get(i).map(String::as_str))
            .collect();
        println!("eliminate: {}", el.join(" "));
    }
    println!("data ({} slots):", p.layout.data_slot_count());
    for d in &p.layout.data {
        let len = d.len.map(|n| format!("[{n}]")).unwrap_or_default();
        println!("  {}{}: {}", d.name, len, d.kind.keyword());
    }
    let lines = p.equation_lines();
    let equations = p.expand();
    println!("equations: {}", equations.len());
    for (i, (e, line)) in equations.iter().zip(&lines).enumerate() {
        let support: Vec<String> = e
            .support(MonomialOrder::Grevlex)
            .iter()
            .map(|m| m.display_with(&names))
            .collect();
        let data_terms: usize = e.terms().map(|(_, c)| c.len()).sum();
        println!(
            "  [{i}] line {line}: degree {}, {} monomials, {} data terms: {}",
            e.degree().unwrap_or(0),
            support.len(),
            data_terms,
            support.join(" ")
        );
    }
    print_plan(&plan);
    Ok(())
}

/// The algebra part of `inspect`: count, basis, template and how it was shrunk.
fn print_plan(plan: &mingen::pipeline::SolverPlan) {
    let names = plan.variable_names();
    let g = &plan.generated;
    let t = &g.built.template;
    println!("solutions: {}", g.count);
    println!(
        "basis ({}): {}",
        t.basis.len(),
        t.basis
            .iter()
            .map(|m| m.display_with(&names))
            .collect::<Vec<_>>()
            .join(" ")
    );
    println!("action: {}", t.action.display_with(&names));
    let (rows, cols) = t.size();
    println!(
        "template: {rows} x {cols} ({} excess, {} reducible, {} basis columns)",
        t.n_excess,
        t.n_reducible,
        t.basis.len()
    );
    println!("shrinking:");
    for (step, r, c) in &g.built.history {
        println!("  {r:>5} x {c:<5} {step}");
    }
    println!("template per action variable:");
    for (v, size) in &g.per_action {
        let name = names.get(*v).cloned().unwrap_or_default();
        match size {
            Some((r, c)) => println!("  {name:<6} {r} x {c}"),
            None => println!("  {name:<6} failed"),
        }
    }
    if let Some(v) = &g.validation {
        println!("validation: {v:?}");
    }
    println!(
        "seconds: {:.3} (analysis {:.3}, templates {:.3}, validation {:.3})",
        plan.seconds, g.seconds.0, g.seconds.1, g.seconds.2
    );
}

fn generate(files: Vec<PathBuf>, all: bool, check: bool) -> Result<(), CliError> {
    let root = workspace_root()?;
    if all && !files.is_empty() {
        return Err(CliError {
            message: "give problem files or --all, not both".into(),
            code: 2,
        });
    }
    if !all && files.is_empty() {
        return Err(CliError {
            message: "nothing to generate: give problem files or --all".into(),
            code: 2,
        });
    }
    let files = if all { problem_files(&root)? } else { files };
    let report = mingen::generate::generate(&root, &files, all, check)?;
    let stale: Vec<_> = report.iter().filter(|f| !f.fresh).collect();
    for f in &report {
        let rel = f
            .path
            .strip_prefix(&root)
            .unwrap_or(&f.path)
            .display()
            .to_string();
        match (check, f.fresh) {
            (_, true) => eprintln!("fresh   {rel}"),
            (true, false) => eprintln!("stale   {rel}"),
            (false, false) => eprintln!("wrote   {rel}"),
        }
    }
    if check && !stale.is_empty() {
        return Err(CliError {
            message: format!(
                "{} generated file(s) are stale; run `cargo run --release -p mingen -- generate --all`",
                stale.len()
            ),
            code: 1,
        });
    }
    Ok(())
}
