//! `mingen generate`: one problem's solver to any path (`--out`), or this repository's
//! solvers (`--all`, problem files) through [`super::codegen`].

use super::codegen::{generate_to, generate_with, problem_files, workspace_root};
use super::CliError;
use mingen::{CodeForm, TemplateOptions};
use std::path::{Path, PathBuf};

pub(super) fn generate_out(
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
    let f = generate_to(file, out, check, options, code_form)?;
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

pub(super) fn generate(
    files: Vec<PathBuf>,
    all: bool,
    check: bool,
    jobs: usize,
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
    let report = generate_with(&root, &files, all, check, jobs, options)?;
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
