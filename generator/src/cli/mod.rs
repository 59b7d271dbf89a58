//! The subcommands, one file each, and what they share: the command line's types, the
//! options of the algebra (`SearchArgs`), and `CliError`, which `main` turns into one line on
//! stderr and an exit code (2 for bad input).

/// `writeln!` into a `String` (infallible).
macro_rules! outln {
    ($out:expr, $($arg:tt)*) => {{
        use std::fmt::Write as _;
        let _ = writeln!($out, $($arg)*);
    }};
}

mod audit;
mod codegen;
mod generate;
mod inspect;
mod report;

use clap::{Parser, Subcommand};
use mingen::{CodeForm, PipelineError, ProblemError, TemplateOptions};
use std::path::PathBuf;

#[derive(Parser)]
#[command(name = "mingen", version, about = "Minimal-solver generator")]
pub struct Cli {
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
        /// Problems planned and audited at a time, each on a thread of its own with its own
        /// budget (1 to 256; more than the machine's cores only shares them). The rows and
        /// their figures do not depend on it, except the seconds when cores are shared.
        #[arg(long, default_value_t = 1, value_parser = job_count)]
        jobs: usize,
        #[command(flatten)]
        search: SearchArgs,
    },
    /// With --out, write one problem's solver to that path, a module for any crate that
    /// depends on mingen-runtime. Without --out, this repository's solvers: for problem
    /// files (or all of templates/*.mp with --all), write solver/src/generated/<name>.rs
    /// under the workspace root, the nearest directory above the current one that holds
    /// templates/ and solver/src/ (an error if there is none).
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
        /// Problems planned at a time without --out, each on a thread of its own with its
        /// own budget (1 to 256); the files written do not depend on it.
        #[arg(long, default_value_t = 1, value_parser = job_count, conflicts_with = "out")]
        jobs: usize,
        #[command(flatten)]
        search: SearchArgs,
    },
}

/// `--instances`: a count from 1 to [`mingen::MAX_INSTANCES`], checked before
/// anything is allocated for it.
fn instance_count(s: &str) -> Result<usize, String> {
    let max = mingen::MAX_INSTANCES;
    match s.parse::<usize>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!("expected an integer from 1 to {max}, found '{s}'")),
    }
}

/// `--jobs`: a thread count from 1 to 256.
fn job_count(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if (1..=256).contains(&n) => Ok(n),
        _ => Err(format!("expected an integer from 1 to 256, found '{s}'")),
    }
}

/// Options of the algebra (count and template search), shared by every subcommand that
/// plans a problem. Options given here override the problem file's `option` lines.
#[derive(clap::Args, Clone, Debug)]
struct SearchArgs {
    /// Wall-clock budget of one problem's algebra, in seconds (Gröbner bases, template
    /// search and validation raise their degrees until they succeed or this runs out).
    #[arg(long, default_value_t = mingen::__internal::budget::DEFAULT_MAX_SECONDS)]
    max_seconds: f64,
    /// Memory budget of one problem's algebra, in MiB (estimated; a step that would need
    /// more is not started).
    #[arg(long, value_name = "MIB", default_value_t = mingen::__internal::budget::DEFAULT_MAX_MEMORY_MB)]
    max_memory: u64,
    /// The action: an unknown's name (e.g. t1), its inverse (`1/t1`, a Laurent action:
    /// the basis is the quotient basis times t1) or `random` (a random linear combination
    /// of the unknowns). Default: every unknown, then a random combination if no unknown
    /// has distinct eigenvalues.
    #[arg(long, value_name = "NAME|1/NAME|random")]
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
    /// default: the file's `option newton`, else 0, 2, 4 or 8 as the plan measures its
    /// template, see `inspect`'s `polishing:` line; where the plan chooses 0, solutions
    /// whose residual is above 1e-10 still get 2 unless the check costs more than a small
    /// part of the solve; `--newton 0` polishes none).
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
    /// Solve a system whose solutions come in sign pairs (every equation even or odd in
    /// some unknowns) at half its size and recover both signs (`yes`, when the count
    /// halves), or as written (`no`); default: the file's `option sign_symmetry`, else
    /// folded unless the system as written has a template of at most half the area.
    #[arg(long, value_name = "yes|no", value_parser = ["yes", "no"])]
    sign_symmetry: Option<String>,
    /// Let the template's basis have more monomials than solutions when that makes the
    /// template smaller and loses no solution on the plan's measurement (`yes`), or keep a
    /// quotient basis (`no`, the default: the larger eigenvalue problem makes the emitted
    /// solvers slower); default: the file's `option redundant_basis`.
    #[arg(long, value_name = "yes|no", value_parser = ["yes", "no"])]
    redundant_basis: Option<String>,
    /// How many weighted monomial orders to sample for other quotient bases (0 to 1024;
    /// default: the file's `option weighted_orders`, else 32); more may find smaller
    /// templates and take longer.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(0..=1024))]
    weighted_orders: Option<u64>,
    /// How a `nonzero` polynomial with constant coefficients is saturated: inside the
    /// template (`template`), by a hidden unknown (`unknown`), or both searched and the
    /// smaller template kept (`smaller`, the default; the longer search); default: the
    /// file's `option saturation`.
    #[arg(long, value_name = "smaller|template|unknown", value_parser = ["smaller", "template", "unknown"])]
    saturation: Option<String>,
    /// A weighted monomial order to try before all others: one positive weight per unknown
    /// of the system, in the order `inspect` lists them, comma-separated (e.g. `4,2,3,2`);
    /// may be given several times.
    #[arg(long, value_name = "W,W,...", value_parser = weight_vector)]
    weights: Vec<WeightVector>,
}

/// One `--weights` vector.
#[derive(Clone, Debug)]
struct WeightVector(Vec<u32>);

/// `--weights`: comma-separated integers from 1 to [`mingen::__internal::groebner::MAX_WEIGHT`].
fn weight_vector(s: &str) -> Result<WeightVector, String> {
    use mingen::__internal::groebner::MAX_WEIGHT;
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
            budget: mingen::Budget::new(self.max_seconds, self.max_memory),
            overrides: mingen::ProblemOptions {
                action: self.action.clone(),
                extra_degree: self.extra_degree,
                basis: self.basis.clone(),
                newton: self.newton,
                auto_eliminate: self.auto_eliminate.as_deref().map(|v| v == "yes"),
                reduce_equations: self.reduce_equations.as_deref().map(|v| v == "yes"),
                sign_symmetry: self.sign_symmetry.as_deref().map(|v| v == "yes"),
                redundant_basis: self.redundant_basis.as_deref().map(|v| v == "yes"),
                weighted_orders: self.weighted_orders.map(|n| n as usize),
                saturation: self
                    .saturation
                    .as_deref()
                    .and_then(mingen::PolynomialSaturation::parse),
            },
            weights: self.weights.iter().map(|w| w.0.clone()).collect(),
            ..TemplateOptions::default()
        })
    }
}

/// A failure reported on one line of stderr with an exit code.
pub struct CliError {
    /// The message, one line.
    pub message: String,
    /// The exit code.
    pub code: u8,
}

impl From<codegen::GenerateError> for CliError {
    fn from(e: codegen::GenerateError) -> Self {
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

/// Writes to stdout; a closed pipe (`mingen inspect F | head`) is not an error.
pub(crate) fn emit(text: &str) -> Result<(), CliError> {
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

/// Runs one subcommand.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Inspect { file, json, search } => search
            .options()
            .and_then(|o| inspect::inspect(&file, json, &o)),
        Command::Generate {
            files,
            all,
            check,
            out,
            code_form,
            jobs,
            search,
        } => search.options().and_then(|o| match out {
            Some(out) => {
                let form = match code_form.as_deref() {
                    Some("inline") => CodeForm::Inline,
                    Some("table") => CodeForm::Table,
                    _ => CodeForm::Auto,
                };
                generate::generate_out(&files, all, &out, check, &o, form)
            }
            None => generate::generate(files, all, check, jobs, &o),
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
            let files = audit::AuditFiles {
                instances: instances_from.as_deref(),
                solutions: solutions_from.as_deref(),
            };
            audit::audit(&file, instances, seed, files, json, &o)
        }),
        Command::Report {
            paths,
            markdown: _,
            json,
            instances,
            seed,
            jobs,
            search,
        } => search
            .options()
            .and_then(|o| report::report(&paths, instances, seed, json, jobs, &o)),
    }
}
