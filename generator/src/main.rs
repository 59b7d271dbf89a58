//! The `mingen` command line. Each subcommand is one function returning a [`CliError`];
//! `main` prints the error on one line and exits with its code (2 for bad input).

use clap::{Parser, Subcommand};
use mingen::algebra::MonomialOrder;
use mingen::emit::CodeForm;
use mingen::generate::{problem_files, workspace_root, GenerateError};
use mingen::pipeline::{plan_file, PipelineError};
use mingen::template::TemplateOptions;
use mingen::{Problem, ProblemError};
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};
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
        #[command(flatten)]
        search: SearchArgs,
    },
    /// Numerical stability of a problem's template: random real instances through the
    /// interpreted template, normalised residuals, failures, a histogram.
    Audit {
        /// The problem file.
        file: PathBuf,
        /// Number of random instances (1 to 10,000,000).
        #[arg(long, default_value_t = 1000, value_parser = instance_count)]
        instances: usize,
        /// Seed of the random instances.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// Read the instances from this file instead: one per line, whitespace-separated
        /// numbers in the order of the problem's data slots (`mingen inspect` lists them).
        #[arg(long, value_name = "DATA", conflicts_with_all = ["instances", "seed"])]
        instances_from: Option<PathBuf>,
        /// A known solution per instance of --instances-from (same line order; every
        /// unknown in declaration order, eliminated ones included): reports how many are
        /// recovered by the closest returned solution, and how accurately.
        #[arg(long, value_name = "SOLUTIONS", requires = "instances_from")]
        solutions_from: Option<PathBuf>,
        #[command(flatten)]
        search: SearchArgs,
    },
    /// One table row per problem: unknowns, solutions, template against the published
    /// size, action, audit median / p99 / failures, generation seconds.
    Report {
        /// Problem files or directories (their *.mp files).
        #[arg(required = true)]
        paths: Vec<PathBuf>,
        /// Print a Markdown table (the default).
        #[arg(long, conflicts_with = "json")]
        markdown: bool,
        /// Print one JSON array, one object per problem.
        #[arg(long)]
        json: bool,
        /// Random instances of each audit (1 to 10,000,000).
        #[arg(long, default_value_t = 1000, value_parser = instance_count)]
        instances: usize,
        /// Seed of the audit instances.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        #[command(flatten)]
        search: SearchArgs,
    },
    /// Emit solver/src/generated/<name>.rs for problem files (or all of templates/*.mp),
    /// or, with --out, one problem's solver as a module for any crate that depends on
    /// mingen-runtime.
    Generate {
        /// Problem files.
        files: Vec<PathBuf>,
        /// Every problem file in templates/ (and the module list generated/mod.rs).
        #[arg(long)]
        all: bool,
        /// Write nothing; exit 1 naming each stale or missing generated file.
        #[arg(long)]
        check: bool,
        /// Write the solver of the one problem file given here instead (a self-contained
        /// module: it refers to mingen_runtime only).
        #[arg(long, value_name = "PATH.rs")]
        out: Option<PathBuf>,
        /// Form of the coefficient code with --out: `inline` (straight-line code in
        /// `solve`), `table` (coefficient functions of bounded size and a fill table:
        /// compile time linear in the template's size) or `auto` (table above 2048
        /// template entries plus coefficient statements).
        #[arg(long, value_name = "auto|inline|table", value_parser = ["auto", "inline", "table"], requires = "out")]
        code_form: Option<String>,
        #[command(flatten)]
        search: SearchArgs,
    },
}

/// `--instances`: a count from 1 to [`mingen::audit::MAX_INSTANCES`], checked before
/// anything is allocated for it.
fn instance_count(s: &str) -> Result<usize, String> {
    let max = mingen::audit::MAX_INSTANCES;
    match s.parse::<usize>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!("expected an integer from 1 to {max}, found '{s}'")),
    }
}

/// Options of the algebra (count and template search), shared by every subcommand that
/// plans a problem. Options given here override the problem file's `option` lines.
#[derive(clap::Args, Clone, Debug)]
struct SearchArgs {
    /// Wall-clock budget of one problem's algebra, in seconds (Gröbner bases, template
    /// search and validation raise their degrees until they succeed or this runs out).
    #[arg(long, default_value_t = mingen::budget::DEFAULT_MAX_SECONDS)]
    max_seconds: f64,
    /// Memory budget of one problem's algebra, in MiB (estimated; a step that would need
    /// more is not started).
    #[arg(long, value_name = "MIB", default_value_t = mingen::budget::DEFAULT_MAX_MEMORY_MB)]
    max_memory: u64,
    /// The action: an unknown's name (e.g. t1) or `random` (a random linear combination
    /// of the unknowns). Default: every unknown, then a random combination if no unknown
    /// has distinct eigenvalues.
    #[arg(long, value_name = "NAME|random")]
    action: Option<String>,
    /// Candidate degrees tried above the start degree, as a hard bound (default: 4, then
    /// raised until a template is found or the budget runs out).
    #[arg(long, value_name = "N")]
    extra_degree: Option<u32>,
    /// Quotient basis: `standard` (grevlex standard monomials) or `selected` (also bases
    /// selected among the template's columns; the default).
    #[arg(long, value_name = "standard|selected", value_parser = ["standard", "selected"])]
    basis: Option<String>,
    /// Gauss-Newton steps polishing every solution on the original equations (0 to 8;
    /// default: the file's `option newton`, else 0).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=8))]
    newton: Option<u32>,
    /// Solve unknowns from affine equations and substitute them, or else eliminate the
    /// unknowns that appear only linearly with data coefficients (`yes`, the default, when
    /// it keeps the solution count), or keep them (`no`); default: the file's
    /// `option auto_eliminate`.
    #[arg(long, value_name = "yes|no", value_parser = ["yes", "no"])]
    auto_eliminate: Option<String>,
    /// Also build templates from the equations row-reduced on their data and keep the
    /// smaller (`yes`, the default), or use the equations as written only (`no`); default:
    /// the file's `option reduce_equations`.
    #[arg(long, value_name = "yes|no", value_parser = ["yes", "no"])]
    reduce_equations: Option<String>,
    /// How many weighted monomial orders to sample for other quotient bases (0 to 1024;
    /// default: the file's `option weighted_orders`, else 32); more may find smaller
    /// templates and take longer.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(0..=1024))]
    weighted_orders: Option<u64>,
    /// A weighted monomial order to try before all others: one positive weight per unknown
    /// of the system, in the order `inspect` lists them, comma-separated (e.g. `4,2,3,2`);
    /// may be given several times.
    #[arg(long, value_name = "W,W,...", value_parser = weight_vector)]
    weights: Vec<WeightVector>,
}

/// One `--weights` vector.
#[derive(Clone, Debug)]
struct WeightVector(Vec<u32>);

/// `--weights`: comma-separated integers from 1 to [`mingen::groebner::MAX_WEIGHT`].
fn weight_vector(s: &str) -> Result<WeightVector, String> {
    use mingen::groebner::MAX_WEIGHT;
    let bad = || format!("expected comma-separated integers from 1 to {MAX_WEIGHT}, found '{s}'");
    s.split(',')
        .map(|w| match w.trim().parse::<u32>() {
            Ok(w) if (1..=MAX_WEIGHT).contains(&w) => Ok(w),
            _ => Err(bad()),
        })
        .collect::<Result<Vec<u32>, String>>()
        .map(WeightVector)
}

impl SearchArgs {
    fn options(&self) -> Result<TemplateOptions, CliError> {
        if self.max_seconds.is_nan() || self.max_seconds <= 0.0 || self.max_memory == 0 {
            return Err(CliError {
                message: "--max-seconds and --max-memory must be positive".into(),
                code: 2,
            });
        }
        Ok(TemplateOptions {
            budget: mingen::budget::Budget::new(self.max_seconds, self.max_memory),
            overrides: mingen::problem::ProblemOptions {
                action: self.action.clone(),
                extra_degree: self.extra_degree,
                basis: self.basis.clone(),
                newton: self.newton,
                auto_eliminate: self.auto_eliminate.as_deref().map(|v| v == "yes"),
                reduce_equations: self.reduce_equations.as_deref().map(|v| v == "yes"),
                weighted_orders: self.weighted_orders.map(|n| n as usize),
            },
            weights: self.weights.iter().map(|w| w.0.clone()).collect(),
            ..TemplateOptions::default()
        })
    }
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

impl From<PipelineError> for CliError {
    fn from(e: PipelineError) -> Self {
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
        Command::Inspect { file, json, search } => {
            search.options().and_then(|o| inspect(&file, json, &o))
        }
        Command::Generate {
            files,
            all,
            check,
            out,
            code_form,
            search,
        } => search.options().and_then(|o| match out {
            Some(out) => {
                let form = match code_form.as_deref() {
                    Some("inline") => CodeForm::Inline,
                    Some("table") => CodeForm::Table,
                    _ => CodeForm::Auto,
                };
                generate_out(&files, all, &out, check, &o, form)
            }
            None => generate(files, all, check, &o),
        }),
        Command::Audit {
            file,
            instances,
            seed,
            json,
            instances_from,
            solutions_from,
            search,
        } => search.options().and_then(|o| {
            let files = AuditFiles {
                instances: instances_from.as_deref(),
                solutions: solutions_from.as_deref(),
            };
            audit(&file, instances, seed, files, json, &o)
        }),
        Command::Report {
            paths,
            markdown: _,
            json,
            instances,
            seed,
            search,
        } => search
            .options()
            .and_then(|o| report(&paths, instances, seed, json, &o)),
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
                        "first_slot": d.first_slot,
                    })
                })
                .collect(),
        ),
    );
    m.insert("data_slots".into(), json!(p.layout.data_slot_count()));
    // The order of the numbers on a line of `audit --instances-from`.
    m.insert("data_slot_names".into(), json!(p.layout.data_slot_names()));
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

fn inspect(file: &PathBuf, as_json: bool, options: &TemplateOptions) -> Result<(), CliError> {
    let parsed = Problem::from_file(file)?;
    let plan = plan_file(file, options)?;
    // The planned problem: the file's, with what planning added (automatic elimination).
    let p = &plan.problem;
    let mut summary = problem_summary(p);
    summary.insert(
        "eliminated_automatically".into(),
        json!(parsed.layout.eliminate.is_empty() && !p.layout.eliminate.is_empty()),
    );
    if let Value::Object(algebra) = plan.summary_json() {
        summary.extend(algebra);
    }
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
        let how = if !parsed.layout.eliminate.is_empty() {
            ""
        } else if p.substitution().is_some() {
            " (automatic: solved from the affine equations and substituted into the others; `option auto_eliminate = no` keeps them)"
        } else {
            " (automatic: they appear only linearly, with data coefficients; `option auto_eliminate = no` keeps them)"
        };
        outln!(out, "eliminate: {}{how}", el.join(" "));
    }
    outln!(out, "data ({} slots):", p.layout.data_slot_count());
    for d in &p.layout.data {
        let len = d.len.map(|n| format!("[{n}]")).unwrap_or_default();
        outln!(out, "  {}{}: {}", d.name, len, d.kind.keyword());
    }
    outln!(
        out,
        "data slot order (a line of audit --instances-from): {}",
        p.layout.data_slot_names().join(" ")
    );
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
    print_plan(&mut out, &plan);
    emit(&out)
}

/// The algebra part of `inspect`: count, basis, template and how it was shrunk.
fn print_plan(out: &mut String, plan: &mingen::pipeline::SolverPlan) {
    let names = plan.variable_names();
    let g = &plan.generated;
    let t = &g.built.template;
    outln!(out, "solutions: {}", g.count);
    if plan.problem.nonzero_count() > 0 {
        let divisions = plan.problem.divisions();
        let divided = divisions
            .iter()
            .filter(|d| d.iter().any(|&k| k > 0))
            .count();
        let saturation = if plan.problem.is_saturated() {
            "kept (a hidden unknown per nonzero)"
        } else {
            "dropped (the divided system has the same solutions without it)"
        };
        if divided == 0 {
            outln!(
                out,
                "nonzero: divides no equation exactly; saturation {saturation}"
            );
        } else {
            outln!(
                out,
                "nonzero: divided out of {divided} of {} equations; saturation {saturation}",
                divisions.len()
            );
        }
    }
    if let Some(kept) = plan.problem.independent() {
        outln!(
            out,
            "equations kept: {} (the others are linear combinations of them)",
            kept.len()
        );
    }
    outln!(
        out,
        "basis ({}): {}",
        t.basis.len(),
        t.basis
            .iter()
            .map(|m| m.display_with(&names))
            .collect::<Vec<_>>()
            .join(" ")
    );
    outln!(out, "basis from: {}", g.built.basis_choice);
    outln!(out, "action: {}", t.action.display_with(&names));
    if let Some(r) = &t.reduction {
        outln!(
            out,
            "equations: row-reduced on the data first ({} x {} coefficient matrix), pivots {}",
            r.len(),
            r.monomials.len(),
            r.pivots
                .iter()
                .map(|&p| r.monomials[p].display_with(&names))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    let (rows, cols) = t.eliminated_size();
    outln!(
        out,
        "template: {rows} x {cols} ({} excess, {} reducible, {} basis columns)",
        t.n_excess - t.n_dependent,
        t.n_reducible,
        t.basis.len()
    );
    if t.n_dependent > 0 {
        outln!(
            out,
            "  (and {} excess columns that are linear combinations of the others, left out)",
            t.n_dependent
        );
    }
    outln!(out, "shrinking:");
    for (step, r, c) in &g.built.history {
        outln!(out, "  {r:>5} x {c:<5} {step}");
    }
    outln!(out, "template per action variable:");
    for (v, size) in &g.per_action {
        let name = v.display_with(&names);
        match size {
            Some((r, c)) => outln!(out, "  {name:<6} {r} x {c}"),
            None => outln!(out, "  {name:<6} failed"),
        }
    }
    if let Some(v) = &g.validation {
        outln!(out, "validation: {v:?}");
    }
    outln!(
        out,
        "seconds: {:.3} (analysis {:.3}, templates {:.3}, validation {:.3})",
        plan.seconds,
        g.seconds.0,
        g.seconds.1,
        g.seconds.2
    );
}

/// `audit --instances-from` and `--solutions-from`.
struct AuditFiles<'a> {
    instances: Option<&'a Path>,
    solutions: Option<&'a Path>,
}

/// An instances or solutions file's error as a command-line error (exit code 2).
fn file_error(path: &Path, e: mingen::instances_file::InstancesError) -> CliError {
    CliError {
        message: match e {
            e @ mingen::instances_file::InstancesError::Io { .. } => e.to_string(),
            e => format!("{}: {e}", path.display()),
        },
        code: 2,
    }
}

fn audit(
    file: &Path,
    instances: usize,
    seed: u64,
    files: AuditFiles<'_>,
    as_json: bool,
    options: &TemplateOptions,
) -> Result<(), CliError> {
    if instances == 0 {
        return Err(CliError {
            message: "--instances must be at least 1".into(),
            code: 2,
        });
    }
    let plan = plan_file(file, options)?;
    let (report, source) = match files.instances {
        Some(path) => {
            let data = mingen::instances_file::read_instances(path, &plan.problem.layout)
                .map_err(|e| file_error(path, e))?;
            let solutions = match files.solutions {
                Some(spath) => {
                    let names = plan.problem.unknown_names();
                    let names = &names[..plan.visible_unknowns()];
                    let s = mingen::instances_file::read_solutions(spath, names)
                        .map_err(|e| file_error(spath, e))?;
                    if s.len() != data.len() {
                        return Err(CliError {
                            message: format!(
                                "{}: {} solutions for the {} instances of {}",
                                spath.display(),
                                s.len(),
                                data.len(),
                                path.display()
                            ),
                            code: 2,
                        });
                    }
                    Some(s)
                }
                None => None,
            };
            (
                mingen::audit::audit_plan_planted(&plan, &data, solutions.as_deref()),
                format!("instances from {}", path.display()),
            )
        }
        None => {
            let options = mingen::audit::AuditOptions { instances, seed };
            (
                mingen::audit::audit_plan(&plan, &options),
                format!("uniform random instances, seed {seed}"),
            )
        }
    };
    if as_json {
        let text = serde_json::to_string_pretty(&report.to_json()).unwrap_or_default();
        return emit(&format!("{text}\n"));
    }
    let (rows, cols) = plan.generated.built.template.eliminated_size();
    // Far above rounding level without polishing: say what fixes it (Newton steps only
    // sharpen roots the action matrix found, so they are the usual remedy, not a given one).
    let newton = plan.problem.layout.options.newton_steps();
    let hint = if newton == 0 && report.median_log10_residual > -11.0 {
        format!(
            "hint: the median residual is far above rounding level; Gauss-Newton polishing \
             (`option newton = 2` in the problem file, or --newton 2 here) usually brings it \
             there: the `with newton = {}:` line above is what it gives ({})\n",
            mingen::audit::COMPARISON_NEWTON_STEPS,
            file.display()
        )
    } else {
        String::new()
    };
    emit(&format!(
        "problem {} (template {rows} x {cols}, {} solutions; {source})\n{report}{hint}",
        plan.problem.name(),
        plan.generated.count
    ))
}

fn report(
    paths: &[PathBuf],
    instances: usize,
    seed: u64,
    as_json: bool,
    template: &TemplateOptions,
) -> Result<(), CliError> {
    let options = mingen::audit::AuditOptions { instances, seed };
    let rows = mingen::report::report_with(paths, &options, template).map_err(|e| CliError {
        message: e.to_string(),
        code: 2,
    })?;
    if as_json {
        let text = serde_json::to_string_pretty(&mingen::report::to_json(&rows))
            .unwrap_or_else(|_| "[]".into());
        emit(&format!("{text}\n"))
    } else {
        emit(&mingen::report::to_markdown(&rows))
    }
}

fn generate_out(
    files: &[PathBuf],
    all: bool,
    out: &Path,
    check: bool,
    options: &TemplateOptions,
    code_form: CodeForm,
) -> Result<(), CliError> {
    let [file] = files else {
        return Err(CliError {
            message: "--out takes exactly one problem file".into(),
            code: 2,
        });
    };
    if all {
        return Err(CliError {
            message: "--out and --all cannot be combined".into(),
            code: 2,
        });
    }
    let f = mingen::generate::generate_to_with(file, out, check, options, code_form)?;
    match (check, f.fresh) {
        (_, true) => eprintln!("fresh   {}", out.display()),
        (true, false) => {
            return Err(CliError {
                message: format!("{} is stale", out.display()),
                code: 1,
            })
        }
        (false, false) => eprintln!("wrote   {}", out.display()),
    }
    Ok(())
}

fn generate(
    files: Vec<PathBuf>,
    all: bool,
    check: bool,
    options: &TemplateOptions,
) -> Result<(), CliError> {
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
    let report = mingen::generate::generate_with(&root, &files, all, check, options)?;
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
