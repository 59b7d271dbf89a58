//! `mingen generate`: problem files to checked-in solver sources, and the freshness check.
//!
//! Each problem `templates/<name>.mp` becomes `solver/src/generated/<name>.rs`; the module
//! list `solver/src/generated/mod.rs` is generated too. Output is a pure function of the
//! problem files (fixed seeds, ordered maps), so regenerating and comparing byte for byte
//! tells whether the checked-in solvers are stale.

use crate::emit::{
    emit_solver, generated_path, is_fresh, write_atomic, EliminationSpec, EmitError, SolverSpec,
    Tracer,
};
use crate::pipeline::{plan, PipelineError, SolverPlan};
use crate::template::TemplateOptions;
use crate::{Problem, ProblemError};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why generation failed.
#[derive(Debug, Error)]
pub enum GenerateError {
    /// The problem file could not be read or parsed.
    #[error(transparent)]
    Problem(#[from] ProblemError),
    /// The algebra failed (elimination, Gröbner basis, template).
    #[error(transparent)]
    Pipeline(#[from] PipelineError),
    /// The solver could not be emitted.
    #[error("{file}: {source}")]
    Emit {
        /// The problem file.
        file: String,
        /// What went wrong.
        source: EmitError,
    },
    /// Reading or writing a generated file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
    /// No workspace root (a directory with `templates/` and `solver/src/generated/`).
    #[error("cannot find the workspace root (a directory containing templates/ and solver/src/); run from inside the repository")]
    NoWorkspace,
}

/// The workspace root: the nearest ancestor of the current directory that has `templates/`
/// and `solver/src/`, else the one this binary was built from.
pub fn workspace_root() -> Result<PathBuf, GenerateError> {
    let is_root = |d: &Path| d.join("templates").is_dir() && d.join("solver").join("src").is_dir();
    if let Ok(cwd) = std::env::current_dir() {
        if let Some(d) = cwd.ancestors().find(|d| is_root(d)) {
            return Ok(d.to_path_buf());
        }
    }
    let built = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf);
    built
        .filter(|d| is_root(d))
        .ok_or(GenerateError::NoWorkspace)
}

/// All problem files `templates/*.mp` under `root`, sorted by name.
pub fn problem_files(root: &Path) -> Result<Vec<PathBuf>, GenerateError> {
    let dir = root.join("templates");
    let io = |source| GenerateError::Io {
        path: dir.display().to_string(),
        source,
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map_err(io)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "mp"))
        .collect();
    files.sort();
    Ok(files)
}

/// Parses and plans one problem file (the algebra of `inspect` and `generate`).
pub fn plan_file(path: &Path, options: &TemplateOptions) -> Result<SolverPlan, GenerateError> {
    let problem = Problem::from_file(path)?;
    Ok(plan(problem, &path.display().to_string(), options)?)
}

/// Emits the solver source of a planned problem, as checked in under
/// `solver/src/generated/` (header naming `templates/<name>.mp`).
pub fn emit_plan(plan: &SolverPlan) -> Result<String, GenerateError> {
    emit_plan_from(plan, &format!("templates/{}.mp", plan.problem.layout.name))
}

/// Emits the solver source of a planned problem, its header naming the problem file
/// `problem_path`. The source is a self-contained module body for any crate that depends
/// on `mingen-runtime`: it names no `crate::` path and has no inner attributes, so it can
/// be a module file (`mod name;`) or `include!`d into `mod name { ... }`.
pub fn emit_plan_from(plan: &SolverPlan, problem_path: &str) -> Result<String, GenerateError> {
    let layout = &plan.problem.layout;
    let tracer = Tracer::new();
    let data = tracer.inputs(layout.data_slot_count());
    let (equations, elimination) = plan.equations(&data);
    let spec = SolverSpec {
        layout: layout.clone(),
        template: plan.generated.built.template.clone(),
        equations,
        problem_path: problem_path.to_string(),
        elimination: elimination.map(|e| EliminationSpec {
            eliminated: e.eliminated,
            remaining: e.remaining,
            coefficient_matrix: e.coefficient_matrix,
        }),
    };
    emit_solver(&spec).map_err(|source| GenerateError::Emit {
        file: plan.file.clone(),
        source,
    })
}

/// Plans and emits one problem file into `out` (any path, e.g. a module of another crate);
/// with `check`, writes nothing and only reports whether `out` is up to date. The header
/// names the problem file as given.
pub fn generate_to(
    problem: &Path,
    out: &Path,
    check: bool,
) -> Result<GeneratedFile, GenerateError> {
    generate_to_with(problem, out, check, &TemplateOptions::default())
}

/// [`generate_to`] with explicit template options.
pub fn generate_to_with(
    problem: &Path,
    out: &Path,
    check: bool,
    options: &TemplateOptions,
) -> Result<GeneratedFile, GenerateError> {
    let plan = plan_file(problem, options)?;
    let source = emit_plan_from(&plan, &problem.display().to_string())?;
    let io = |source| GenerateError::Io {
        path: out.display().to_string(),
        source,
    };
    let fresh = is_fresh(out, &source).map_err(io)?;
    if !check && !fresh {
        write_atomic(out, &source).map_err(io)?;
    }
    Ok(GeneratedFile {
        path: out.to_path_buf(),
        fresh,
    })
}

/// The generated `solver/src/generated/mod.rs` declaring one module per problem.
pub fn generated_mod_rs(names: &[String]) -> String {
    let mut s = String::from(
        "// @generated by mingen from templates/*.mp — do not edit\n\
         //! Minimal solvers emitted by `mingen generate --all`, one module per problem file\n\
         //! `templates/<name>.mp`. Regenerate with `cargo run --release -p mingen -- generate --all`.\n\n",
    );
    // rustfmt would reformat prettyplease's output and make the files stale.
    for n in names {
        s.push_str(&format!(
            "/// The solver of `templates/{n}.mp` (its [`Solver`]({n}::Solver) type implements \
             `mingen_runtime::MinimalSolver`).\n#[rustfmt::skip]\npub mod {n};\n"
        ));
    }
    s
}

/// One generated file and whether it is (was) up to date.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GeneratedFile {
    /// Its path.
    pub path: PathBuf,
    /// Whether the file on disk already had exactly this content.
    pub fresh: bool,
}

/// Generates the solvers of `files` (and, if `with_mod_rs`, the module list of every problem
/// under `root`); with `check`, writes nothing and only reports freshness.
pub fn generate(
    root: &Path,
    files: &[PathBuf],
    with_mod_rs: bool,
    check: bool,
) -> Result<Vec<GeneratedFile>, GenerateError> {
    generate_with(root, files, with_mod_rs, check, &TemplateOptions::default())
}

/// [`generate`] with explicit template options.
pub fn generate_with(
    root: &Path,
    files: &[PathBuf],
    with_mod_rs: bool,
    check: bool,
    options: &TemplateOptions,
) -> Result<Vec<GeneratedFile>, GenerateError> {
    let options = options.clone();
    let mut outputs: Vec<(PathBuf, String)> = Vec::new();
    for f in files {
        let plan = plan_file(f, &options)?;
        let source = emit_plan(&plan)?;
        outputs.push((generated_path(root, &plan.problem.layout.name), source));
    }
    if with_mod_rs {
        let mut names = Vec::new();
        for f in problem_files(root)? {
            names.push(Problem::from_file(&f)?.layout.name.clone());
        }
        names.sort();
        outputs.push((
            root.join("solver/src/generated/mod.rs"),
            generated_mod_rs(&names),
        ));
    }
    let mut report = Vec::new();
    for (path, source) in outputs {
        let io = |source| GenerateError::Io {
            path: path.display().to_string(),
            source,
        };
        let fresh = is_fresh(&path, &source).map_err(io)?;
        if !check && !fresh {
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(io)?;
            }
            write_atomic(&path, &source).map_err(io)?;
        }
        report.push(GeneratedFile { path, fresh });
    }
    Ok(report)
}
