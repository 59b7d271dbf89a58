//! `mingen audit`: a template's numerical stability on random or given instances.

use super::{emit, CliError};
use mingen::__internal::audit::AUDIT_BYTES_PER_INSTANCE;
use mingen::__internal::instances_file::{read_instances, read_solutions, InstancesError};
use mingen::{audit_plan, audit_plan_planted, plan_file, AuditOptions, Budget, TemplateOptions};
use std::path::Path;

/// `audit --instances-from` and `--solutions-from`.
pub(super) struct AuditFiles<'a> {
    pub(super) instances: Option<&'a Path>,
    pub(super) solutions: Option<&'a Path>,
}

/// An instances or solutions file's error as a command-line error (exit code 2).
fn file_error(path: &Path, e: InstancesError) -> CliError {
    CliError {
        message: match e {
            e @ InstancesError::Io { .. } => e.to_string(),
            e => format!("{}: {e}", path.display()),
        },
        code: 2,
    }
}

pub(super) fn audit(
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
    // The per-instance figures are kept: their memory is known before any is run.
    let budget = options.budget;
    let needed = (instances as u64).saturating_mul(AUDIT_BYTES_PER_INSTANCE);
    if needed > budget.max_memory_bytes {
        return Err(CliError {
            message: format!(
                "{}: --instances {instances} needs about {} MiB, over the memory budget of {} MiB (raise it with --max-memory)",
                file.display(),
                needed >> 20,
                budget.max_memory_bytes >> 20
            ),
            code: 2,
        });
    }
    let plan = plan_file(file, options)?;
    let (report, source) = match files.instances {
        Some(path) => {
            let data =
                read_instances(path, &plan.problem.layout).map_err(|e| file_error(path, e))?;
            let solutions = match files.solutions {
                Some(spath) => {
                    let names = plan.problem.unknown_names();
                    let names = &names[..plan.visible_unknowns()];
                    let s = read_solutions(spath, names).map_err(|e| file_error(spath, e))?;
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
                audit_plan_planted(&plan, &data, solutions.as_deref()),
                format!("instances from {}", path.display()),
            )
        }
        None => {
            let options = AuditOptions {
                instances,
                seed,
                time_limit: time_limit(budget),
            };
            (
                audit_plan(&plan, &options),
                format!("uniform random instances, seed {seed}"),
            )
        }
    };
    if report.stopped {
        return Err(CliError {
            message: format!(
                "{}: audit stopped after {} of {instances} instances: the time budget of {} s ran out (raise it with --max-seconds, or ask for fewer --instances)",
                file.display(),
                report.instances,
                budget.max_seconds
            ),
            code: 2,
        });
    }
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
            mingen::__internal::audit::COMPARISON_NEWTON_STEPS,
            file.display()
        )
    } else {
        String::new()
    };
    emit(&format!(
        "problem {} (template {rows} x {cols}, {} solutions; {source})\n{report}{hint}",
        plan.problem.name(),
        plan.solution_count()
    ))
}

/// The audit's own wall-clock limit: the same `--max-seconds` as the plan before it.
pub(super) fn time_limit(budget: Budget) -> Option<std::time::Duration> {
    std::time::Duration::try_from_secs_f64(budget.max_seconds).ok()
}
