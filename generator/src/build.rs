//! Build-script API: turn a crate's problem files into solvers in `$OUT_DIR`, in the
//! manner of `prost-build`.
//!
//! ```no_run
//! // build.rs of a crate with `mingen` as build-dependency and `mingen-runtime` as
//! // dependency:
//! fn main() -> Result<(), Box<dyn std::error::Error>> {
//!     mingen::build::Config::new()
//!         .problems(&["solvers/mine.mp"])
//!         .compile()?;
//!     Ok(())
//! }
//! ```
//!
//! and in the crate, for the problem named `mine` (its `problem` line):
//!
//! ```text
//! mod mine {
//!     include!(concat!(env!("OUT_DIR"), "/mine.rs"));
//! }
//! // mine::solve(&mine::Data { .. }), or generically through mine::Solver, which
//! // implements mingen_runtime::MinimalSolver.
//! ```
//!
//! Each problem file becomes `<out_dir>/<module>.rs` (the module name is the problem name
//! lowercased, `p` prepended when it starts with a digit: `problem 8ptF` writes `p8ptf.rs`;
//! written only when its content changes), and `cargo:rerun-if-changed=<file>` is printed for it, so the build script
//! reruns when a problem file changes and not otherwise.

use crate::emit::CodeForm;
use crate::emit::{is_fresh, write_output};
use crate::pipeline::{emit_plan_in, plan_file, PipelineError, SolverPlan};
use crate::template::TemplateOptions;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};
use thiserror::Error;

/// Why [`Config::compile`] failed.
#[derive(Debug, Error)]
pub enum BuildError {
    /// No output directory was set and `OUT_DIR` is not in the environment (not run by
    /// cargo as a build script).
    #[error("no output directory: set Config::out_dir or run from a build script (OUT_DIR)")]
    NoOutDir,
    /// [`Config::compile`] was called without problem files.
    #[error("no problem files given to mingen::build::Config")]
    NoProblems,
    /// A problem file could not be read, parsed, analysed or emitted.
    #[error("{file}: {source}")]
    Generate {
        /// The problem file.
        file: PathBuf,
        /// What went wrong.
        source: PipelineError,
    },
    /// Two problem files give the same module name (they would write the same file).
    #[error("problem module `{name}` is declared by both {first} and {second}")]
    DuplicateName {
        /// The module name ([`crate::SolverPlan::module_name`]).
        name: String,
        /// The first file declaring it.
        first: PathBuf,
        /// The second file declaring it.
        second: PathBuf,
    },
    /// Writing a generated file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
}

/// One solver written by [`Config::compile`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Compiled {
    /// The module to declare and the file stem: the problem name lowercased, `p` prepended
    /// when it starts with a digit ([`crate::SolverPlan::module_name`]).
    pub name: String,
    /// The problem file.
    pub problem: PathBuf,
    /// The generated file, `<out_dir>/<module>.rs`.
    pub path: PathBuf,
    /// Whether the file already had this content (nothing was written).
    pub unchanged: bool,
}

/// Which problem files to turn into solvers, and where to write them.
#[derive(Clone, Debug)]
pub struct Config {
    problems: Vec<PathBuf>,
    out_dir: Option<PathBuf>,
    cargo_metadata: bool,
    options: TemplateOptions,
    code_form: CodeForm,
    planning_threads: usize,
}

impl Default for Config {
    fn default() -> Self {
        Self::new()
    }
}

impl Config {
    /// No problem files yet; output to `$OUT_DIR`; prints `cargo:` lines.
    pub fn new() -> Self {
        Config {
            problems: Vec::new(),
            out_dir: None,
            cargo_metadata: true,
            options: TemplateOptions::default(),
            code_form: CodeForm::Auto,
            planning_threads: 1,
        }
    }

    /// Adds problem files (paths relative to the crate root in a build script). The
    /// generated header names each file as given.
    pub fn problems<P: AsRef<Path>>(&mut self, files: &[P]) -> &mut Self {
        self.problems
            .extend(files.iter().map(|f| f.as_ref().to_path_buf()));
        self
    }

    /// Writes into `dir` instead of `$OUT_DIR`.
    pub fn out_dir(&mut self, dir: impl Into<PathBuf>) -> &mut Self {
        self.out_dir = Some(dir.into());
        self
    }

    /// Whether to print `cargo:rerun-if-changed` lines (on by default; off outside build
    /// scripts).
    pub fn cargo_metadata(&mut self, on: bool) -> &mut Self {
        self.cargo_metadata = on;
        self
    }

    /// Template construction options (the defaults are those of `mingen generate`).
    pub fn template_options(&mut self, options: TemplateOptions) -> &mut Self {
        self.options = options;
        self
    }

    /// The form of the emitted coefficient code ([`CodeForm::Auto`] by default: the table
    /// form for large templates only).
    pub fn code_form(&mut self, form: CodeForm) -> &mut Self {
        self.code_form = form;
        self
    }

    /// Plans up to `threads` problems at a time, each on a thread of its own with its own
    /// budget (1, the default, plans them one after the other; 0 counts as 1). The files
    /// written do not depend on it. Cargo runs build scripts beside other jobs without
    /// counting their threads, so more than one is worth it when the problems are many
    /// or slow to plan.
    pub fn planning_threads(&mut self, threads: usize) -> &mut Self {
        self.planning_threads = threads.max(1);
        self
    }

    /// Generates every problem's solver into `<out_dir>/<module>.rs`. Stops at the first
    /// problem (in the order given) that fails; files of earlier problems are kept (each
    /// write is atomic).
    pub fn compile(&self) -> Result<Vec<Compiled>, BuildError> {
        if self.problems.is_empty() {
            return Err(BuildError::NoProblems);
        }
        let out_dir = match &self.out_dir {
            Some(d) => d.clone(),
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(BuildError::NoOutDir)?,
        };
        if self.cargo_metadata {
            // Printed first, so that a failing problem file is watched too.
            for f in &self.problems {
                println!("cargo:rerun-if-changed={}", f.display());
            }
        }
        let plans = crate::parallel::map_in_order(&self.problems, self.planning_threads, |f| {
            cached_plan(f, &self.options)
        });
        let mut seen: BTreeMap<String, PathBuf> = BTreeMap::new();
        let mut compiled = Vec::new();
        for (file, plan) in self.problems.iter().zip(plans) {
            let generate = |source| BuildError::Generate {
                file: file.clone(),
                source,
            };
            let plan = plan.map_err(generate)?;
            let name = plan.module_name();
            if let Some(first) = seen.insert(name.clone(), file.clone()) {
                return Err(BuildError::DuplicateName {
                    name,
                    first,
                    second: file.clone(),
                });
            }
            let source = emit_plan_in(&plan, &file.display().to_string(), self.code_form)
                .map_err(generate)?;
            let path = out_dir.join(format!("{name}.rs"));
            let io = |source| BuildError::Io {
                path: path.clone(),
                source,
            };
            let unchanged = is_fresh(&path, &source).map_err(io)?;
            if !unchanged {
                std::fs::create_dir_all(&out_dir).map_err(io)?;
                write_output(&path, source.as_bytes(), &[]).map_err(io)?;
            }
            compiled.push(Compiled {
                name,
                problem: file.clone(),
                path,
                unchanged,
            });
        }
        Ok(compiled)
    }
}

/// The plan of `file` with `options`, made once per process for the same file contents and
/// options: a build script that emits a problem in several code forms (one [`Config`] per
/// form) plans it once. Planning is deterministic, so a cached plan is the plan.
fn cached_plan(file: &Path, options: &TemplateOptions) -> Result<Arc<SolverPlan>, PipelineError> {
    type Key = (PathBuf, String, String);
    static PLANS: OnceLock<Mutex<HashMap<Key, Arc<SolverPlan>>>> = OnceLock::new();
    let plans = PLANS.get_or_init(Default::default);
    let key = std::fs::read_to_string(file)
        .ok()
        .map(|text| (file.to_path_buf(), text, format!("{options:?}")));
    if let Some(k) = &key {
        if let Some(p) = plans.lock().ok().and_then(|m| m.get(k).cloned()) {
            return Ok(p);
        }
    }
    let plan = Arc::new(plan_file(file, options)?);
    if let (Some(k), Ok(mut m)) = (key, plans.lock()) {
        m.insert(k, plan.clone());
    }
    Ok(plan)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root() -> &'static Path {
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
    }

    #[test]
    fn writes_named_files_and_reports_errors() {
        let dir = std::env::temp_dir().join(format!("mingen-build-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let five = root().join("templates/gs5pt.mp");
        let out = Config::new()
            .problems(&[&five])
            .out_dir(&dir)
            .cargo_metadata(false)
            .compile()
            .unwrap();
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].name, "gs5pt");
        assert!(!out[0].unchanged);
        let text = std::fs::read_to_string(dir.join("gs5pt.rs")).unwrap();
        assert!(text.contains("impl mingen_runtime::MinimalSolver for Solver"));
        assert!(!text.contains("crate::"), "self-contained");
        assert!(
            !text.contains("//!"),
            "no inner doc comments (include! rejects them)"
        );
        let again = Config::new()
            .problems(&[&five])
            .out_dir(&dir)
            .cargo_metadata(false)
            .compile()
            .unwrap();
        assert!(again[0].unchanged);
        // Planned on two threads, the same files (unchanged), in the order given.
        let grsrp10 = root().join("templates/grsrp10.mp");
        let both = Config::new()
            .problems(&[&grsrp10, &five])
            .out_dir(&dir)
            .cargo_metadata(false)
            .planning_threads(2)
            .compile()
            .unwrap();
        assert_eq!(both.len(), 2);
        assert_eq!(
            (both[0].name.as_str(), both[1].name.as_str()),
            ("grsrp10", "gs5pt")
        );
        assert!(!both[0].unchanged && both[1].unchanged);
        let dup = Config::new()
            .problems(&[&five, &five])
            .out_dir(&dir)
            .cargo_metadata(false)
            .compile();
        assert!(matches!(dup, Err(BuildError::DuplicateName { .. })));
        let missing = Config::new()
            .problems(&[dir.join("missing.mp")])
            .out_dir(&dir)
            .cargo_metadata(false)
            .compile();
        assert!(matches!(missing, Err(BuildError::Generate { .. })));
        assert!(matches!(
            Config::new().out_dir(&dir).compile(),
            Err(BuildError::NoProblems)
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
