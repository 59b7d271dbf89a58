//! `mingen report`: one table row per problem file, as Markdown or JSON.

use super::{emit, CliError};
use mingen::{AuditOptions, TemplateOptions};
use std::path::PathBuf;

pub(super) fn report(
    paths: &[PathBuf],
    instances: usize,
    seed: u64,
    as_json: bool,
    jobs: usize,
    template: &TemplateOptions,
) -> Result<(), CliError> {
    let options = AuditOptions {
        instances,
        seed,
        time_limit: super::audit::time_limit(template.budget),
    };
    let rows = mingen::report_with(paths, &options, template, jobs).map_err(|e| CliError {
        message: e.to_string(),
        code: 2,
    })?;
    if as_json {
        let text =
            serde_json::to_string_pretty(&mingen::to_json(&rows)).unwrap_or_else(|_| "[]".into());
        emit(&format!("{text}\n"))
    } else {
        emit(&mingen::to_markdown(&rows))
    }
}
