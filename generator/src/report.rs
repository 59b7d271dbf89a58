//! `mingen report`: one table row per problem file (unknowns, solutions, template size
//! against the published one, action, audit figures, generation time), as Markdown or
//! JSON. Everything but the seconds is deterministic (seeded instances, fixed pipeline).
//!
//! Two header comments of a problem file are read: `# published: TEXT` (the best
//! published template or solver, e.g. `31x46 (PoseLib relpose_6pt_focal)`, or, for the
//! benchmark of Martyushev et al., their sizes by kind: `std 76x100, red 73x97 (...)`,
//! see [`PublishedSizes`]) and `# Macaulay2: N ...` (an independent count). Template sizes
//! compare by area (rows x columns), as the field does.

use crate::audit::{audit_plan, AuditOptions, AuditReport};
use crate::pipeline::{plan, SolverPlan};
use crate::template::TemplateOptions;
use crate::Problem;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a report could not be made at all (a failing problem is a row, not an error).
#[derive(Debug, Error)]
pub enum ReportError {
    /// A path given is neither a readable problem file nor a readable directory.
    #[error("{path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A directory holds no `*.mp` file.
    #[error("{0}: no problem files (*.mp)")]
    Empty(String),
}

/// One row of the report.
#[derive(Clone, Debug)]
pub struct ReportRow {
    /// The problem file as given.
    pub file: String,
    /// The problem name (the file stem if the file does not parse).
    pub problem: String,
    /// Unknown scalars of the template, and the eliminated ones.
    pub unknowns: Vec<String>,
    /// Eliminated unknowns (recovered as a null vector).
    pub eliminated: Vec<String>,
    /// Number of solutions, when it was found (also when no template was).
    pub solutions: Option<usize>,
    /// The independent count from the `# Macaulay2:` header line.
    pub macaulay2: Option<String>,
    /// Template size as eliminated by the solver (rows, columns), after the fold of its
    /// constant-pivot rows if it has one.
    pub template: Option<(usize, usize)>,
    /// The number of rows (and columns) folded before the elimination
    /// (`template` plus this many of each is the template whole).
    pub folded: usize,
    /// Size (equations, monomials) of the equations' coefficient matrix the solver
    /// row-reduces before filling the template, if it does.
    pub reduction: Option<(usize, usize)>,
    /// The `# published:` header line.
    pub published: Option<String>,
    /// The template sizes read from the `# published:` line.
    pub published_sizes: PublishedSizes,
    /// The action monomial.
    pub action: Option<String>,
    /// The audit on random instances.
    pub audit: Option<AuditReport>,
    /// Wall-clock seconds of the generation (the algebra pipeline).
    pub seconds: f64,
    /// When the plan grew a redundant basis (`--redundant-basis yes`): what it measured
    /// and whether it kept it ([`crate::RedundantCheck`]); `template` is the size it kept.
    pub redundant: Option<crate::RedundantCheck>,
    /// Why there is no solver, if there is none.
    pub error: Option<String>,
}

/// The problem files named by `paths`: files as given, directories by their `*.mp` files
/// (not recursively), sorted.
pub fn problem_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, ReportError> {
    let mut out = Vec::new();
    for p in paths {
        let io = |source| ReportError::Io {
            path: p.display().to_string(),
            source,
        };
        if p.is_dir() {
            let mut files: Vec<PathBuf> = std::fs::read_dir(p)
                .map_err(io)?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.is_file() && f.extension().is_some_and(|x| x == "mp"))
                .collect();
            if files.is_empty() {
                return Err(ReportError::Empty(p.display().to_string()));
            }
            files.sort();
            out.extend(files);
        } else {
            std::fs::metadata(p).map_err(io)?;
            out.push(p.clone());
        }
    }
    Ok(out)
}

/// Published template sizes `(rows, columns)`, read from a `# published:` header line:
/// `std RxC` (standard quotient basis), `red RxC` (redundant solving basis; the smallest
/// if several), `nstd RxC` (a non-standard basis), `std-whole RxC` (the standard-basis
/// template before the Schur complement reduction of their solver, see below) and a bare
/// leading `RxC` (a size whose kind is not stated, e.g. a PoseLib solver's).
///
/// Where a problem names `schur_pols`, Martyushev et al. count their template after
/// eliminating the multiples of those equations first (their solvers'
/// `M(k+1:end,k+1:end) - M(k+1:end,1:k)/M(1:k,1:k)*M(1:k,k+1:end)`, "Schur complement
/// reduction"): `std` is then `k` rows and `k` columns smaller than the template it is
/// computed from. mingen
/// counts its templates the same way (after folding its own rows with constant pivots,
/// `template/fold.rs`), so `std` is the size to compare with, and `std-whole` compares
/// with mingen's template whole.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PublishedSizes {
    /// With the standard basis of some monomial order.
    pub std: Option<(usize, usize)>,
    /// `std`'s template whole, before their Schur complement reduction.
    pub std_whole: Option<(usize, usize)>,
    /// With a redundant solving basis.
    pub red: Option<(usize, usize)>,
    /// With a non-standard basis.
    pub nstd: Option<(usize, usize)>,
    /// Of unstated kind.
    pub other: Option<(usize, usize)>,
}

impl PublishedSizes {
    /// Parses the text of a `# published:` line (see the type's documentation).
    pub fn parse(text: &str) -> PublishedSizes {
        fn size(t: &str) -> Option<(usize, usize)> {
            let t = t.trim_matches(|c: char| c == ',' || c == ';' || c == '(' || c == ')');
            let (r, c) = t.split_once('x')?;
            Some((r.parse().ok()?, c.parse().ok()?))
        }
        let smaller = |a: Option<(usize, usize)>, b: (usize, usize)| match a {
            Some(a) if a.0 * a.1 <= b.0 * b.1 => Some(a),
            _ => Some(b),
        };
        let mut out = PublishedSizes::default();
        let words: Vec<&str> = text.split_whitespace().collect();
        for (k, w) in words.iter().enumerate() {
            let next = words.get(k + 1).and_then(|n| size(n));
            match (w.trim_start_matches('(').trim_end_matches(':'), next) {
                ("std", Some(s)) => out.std = smaller(out.std, s),
                ("std-whole", Some(s)) => out.std_whole = smaller(out.std_whole, s),
                ("red", Some(s)) => out.red = smaller(out.red, s),
                ("nstd", Some(s)) => out.nstd = smaller(out.nstd, s),
                _ => {}
            }
        }
        if let Some(s) = words.first().and_then(|w| size(w)) {
            out.other = Some(s);
        }
        out
    }
    /// The area of the standard-basis template counted as mingen counts its own: whole
    /// (`std-whole`) where given, else `std`.
    pub fn std_whole_area(&self) -> Option<usize> {
        self.std_whole.or(self.std).map(|(r, c)| r * c)
    }
    /// The smallest area among the sizes given (`std-whole` aside: it is `std` counted
    /// otherwise).
    pub fn best_area(&self) -> Option<usize> {
        [self.std, self.red, self.nstd, self.other]
            .into_iter()
            .flatten()
            .map(|(r, c)| r * c)
            .min()
    }
}

/// The text after `# KEY:` on the first comment line that has it.
fn header_value(source: &str, key: &str) -> Option<String> {
    source.lines().find_map(|l| {
        let rest = l.trim_start().strip_prefix('#')?.trim_start();
        let value = rest.strip_prefix(key)?.strip_prefix(':')?;
        Some(value.trim().to_string())
    })
}

/// The report row of one problem file: plan (count, template) with `options`, then audit
/// with `audit`.
pub fn report_row_with(file: &Path, audit: &AuditOptions, options: &TemplateOptions) -> ReportRow {
    let shown = file.display().to_string();
    let source = crate::expand::read_problem_text(file).unwrap_or_default();
    let published = header_value(&source, "published");
    let mut row = ReportRow {
        file: shown.clone(),
        problem: file
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default(),
        unknowns: Vec::new(),
        eliminated: Vec::new(),
        solutions: None,
        macaulay2: header_value(&source, "Macaulay2")
            .and_then(|v| v.split_whitespace().next().map(str::to_string)),
        template: None,
        folded: 0,
        reduction: None,
        published_sizes: published
            .as_deref()
            .map(PublishedSizes::parse)
            .unwrap_or_default(),
        published,
        action: None,
        audit: None,
        seconds: 0.0,
        redundant: None,
        error: None,
    };
    let problem = match Problem::from_file_within(file, options.budget) {
        Ok(p) => p,
        Err(e) => {
            row.error = Some(e.to_string());
            return row;
        }
    };
    row.problem = problem.layout.name.clone();
    let start = std::time::Instant::now();
    let planned: Result<SolverPlan, _> = plan(problem, &shown, options);
    row.seconds = start.elapsed().as_secs_f64();
    match planned {
        Ok(p) => {
            let names = p.variable_names();
            let t = &p.generated.built.template;
            // Hidden unknowns (of `nonzero`) are the last variables; not shown.
            let shown = names.len() - p.problem.layout.hidden_count().min(names.len());
            row.unknowns = names[..shown].to_vec();
            row.eliminated = p.eliminated_names();
            row.solutions = Some(p.solution_count());
            row.template = Some(t.eliminated_size());
            row.folded = t.folded_rows();
            row.reduction = t.reduction_size();
            row.action = Some(t.action.display_with(&names));
            row.redundant = p.redundant_check.clone();
            row.audit = Some(audit_plan(&p, audit));
        }
        Err(e) => {
            row.solutions = e.solution_count();
            row.error = Some(e.to_string());
        }
    }
    row
}

/// The report of every problem file named by `paths` (see `problem_files`).
pub fn report(paths: &[PathBuf], audit: &AuditOptions) -> Result<Vec<ReportRow>, ReportError> {
    report_with(paths, audit, &TemplateOptions::default(), 1)
}

/// [`report`] with explicit template options, planning and auditing at most `threads`
/// problems at a time (each on one thread with its own `options.budget`; rows in the
/// files' order whatever the number of threads, and each row's `seconds` its own plan's).
pub fn report_with(
    paths: &[PathBuf],
    audit: &AuditOptions,
    options: &TemplateOptions,
    threads: usize,
) -> Result<Vec<ReportRow>, ReportError> {
    let files = problem_files(paths)?;
    Ok(crate::parallel::map_in_order(&files, threads, |f| {
        report_row_with(f, audit, options)
    }))
}

impl ReportRow {
    /// The row as a JSON object.
    pub fn to_json(&self) -> Value {
        json!({
            "file": self.file,
            "problem": self.problem,
            "unknowns": self.unknowns,
            "eliminated": self.eliminated,
            "solutions": self.solutions,
            "macaulay2": self.macaulay2,
            "template": self.template.map(|(r, c)| json!({"rows": r, "cols": c})),
            "folded_rows": self.folded,
            "equation_reduction": self.reduction.map(|(r, c)| json!({"rows": r, "cols": c})),
            "published": self.published,
            "area_over_std": self.area_ratio(self.published_sizes.std.map(|(r, c)| r * c)),
            "whole_area_over_std_whole": self.whole_area_ratio(self.published_sizes.std_whole_area()),
            "area_over_best": self.area_ratio(self.published_sizes.best_area()),
            "action": self.action,
            "audit": self.audit.as_ref().map(|a| json!({
                "instances": a.instances,
                "median_log10_residual": a.median_log10_residual,
                "p99_log10_residual": a.p99_log10_residual,
                "failures": a.failures,
                "other_polishing": a.other_polishing.as_ref().map(|u| json!({
                    "newton_steps": u.newton_steps,
                    "median_log10_residual": u.median_log10_residual,
                    "p99_log10_residual": u.p99_log10_residual,
                    "failures": u.failures,
                })),
            })),
            "seconds": self.seconds,
            "redundant_basis": self.redundant.as_ref().map(crate::RedundantCheck::to_json),
            "error": self.error,
        })
    }

    /// Our elimination area (the template's `rows x cols`, plus the equations'
    /// coefficient matrix's when they are row-reduced first) over `area`, when both are
    /// known.
    pub fn area_ratio(&self, area: Option<usize>) -> Option<f64> {
        let (r, c) = self.template?;
        let ours = r * c + self.reduction.map_or(0, |(n, m)| n * m);
        area.filter(|&a| a > 0).map(|a| ours as f64 / a as f64)
    }

    /// [`ReportRow::area_ratio`] with the template counted whole, before the fold of its
    /// rows: the like-for-like ratio to a published size counted whole.
    pub fn whole_area_ratio(&self, area: Option<usize>) -> Option<f64> {
        let (r, c) = self.template?;
        let (r, c) = (r + self.folded, c + self.folded);
        let ours = r * c + self.reduction.map_or(0, |(n, m)| n * m);
        area.filter(|&a| a > 0).map(|a| ours as f64 / a as f64)
    }

    fn markdown_cells(&self) -> Vec<String> {
        let dash = || "—".to_string();
        let mut unknowns = self.unknowns.join(", ");
        if !self.eliminated.is_empty() {
            unknowns.push_str(&format!(" ({} eliminated)", self.eliminated.join(", ")));
        }
        vec![
            format!("`{}`", self.problem),
            if unknowns.is_empty() {
                dash()
            } else {
                unknowns
            },
            self.solutions.map_or_else(dash, |n| n.to_string()),
            self.macaulay2.clone().unwrap_or_else(dash),
            match (self.template, &self.error) {
                (Some((r, c)), _) => {
                    let mut text = format!("{r}x{c}");
                    if let Some((n, m)) = self.reduction {
                        text.push_str(&format!(" + {n}x{m} reduction"));
                    }
                    if self.folded > 0 {
                        text.push_str(&format!(" ({} rows folded)", self.folded));
                    }
                    match &self.redundant {
                        Some(red) if red.kept => text.push_str(&format!(
                            " (redundant basis: {} spurious eigenvalues)",
                            red.spurious_eigenvalues
                        )),
                        Some(red) => text.push_str(&format!(
                            " (a redundant basis, {}x{}, dropped: {:.3} against {:.3} real solutions, {} against {} failures)",
                            red.redundant_size.0,
                            red.redundant_size.1,
                            red.mean_real.0,
                            red.mean_real.1,
                            red.failures.0,
                            red.failures.1
                        )),
                        None => {}
                    }
                    text
                }
                (None, Some(_)) => "none".to_string(),
                (None, None) => dash(),
            },
            self.published.clone().unwrap_or_else(dash),
            self.area_ratio(self.published_sizes.std.map(|(r, c)| r * c))
                .map_or_else(dash, |x| format!("{x:.2}")),
            self.whole_area_ratio(self.published_sizes.std_whole_area())
                .map_or_else(dash, |x| format!("{x:.2}")),
            self.area_ratio(self.published_sizes.best_area())
                .map_or_else(dash, |x| format!("{x:.2}")),
            self.action.clone().unwrap_or_else(dash),
            self.audit.as_ref().map_or_else(dash, |a| {
                format!(
                    "{:.2} / {:.2} / {} of {}",
                    a.median_log10_residual, a.p99_log10_residual, a.failures, a.instances
                )
            }),
            self.audit
                .as_ref()
                .and_then(|a| Some((a, a.other_polishing.as_ref()?)))
                .map_or_else(dash, |(a, u)| {
                    format!(
                        "{:.2} / {:.2} / {} of {} ({})",
                        u.median_log10_residual,
                        u.p99_log10_residual,
                        u.failures,
                        a.instances,
                        match u.newton_steps {
                            0 => "unpolished".to_string(),
                            n => format!("newton {n}"),
                        }
                    )
                }),
            format!("{:.2}", self.seconds),
        ]
    }
}

/// The rows as one JSON array.
pub fn to_json(rows: &[ReportRow]) -> Value {
    Value::Array(rows.iter().map(ReportRow::to_json).collect())
}

/// The rows as a Markdown table, followed by the reasons of rows without a solver.
pub fn to_markdown(rows: &[ReportRow]) -> String {
    let header = [
        "problem",
        "unknowns",
        "solutions",
        "Macaulay2",
        "template",
        "published",
        "area / std",
        "whole / std whole",
        "area / best",
        "action",
        "audit: median / p99 log10 residual / failures",
        "other polishing",
        "seconds",
    ];
    let mut out = format!("| {} |\n", header.join(" | "));
    out.push_str(&format!("|{}\n", "---|".repeat(header.len())));
    for r in rows {
        let cells: Vec<String> = r
            .markdown_cells()
            .into_iter()
            .map(|c| c.replace('|', "\\|"))
            .collect();
        out.push_str(&format!("| {} |\n", cells.join(" | ")));
    }
    for r in rows {
        if let Some(e) = &r.error {
            out.push_str(&format!("\n`{}`: {e}\n", r.problem));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_values_are_read_from_comment_lines_only() {
        let src = "# Title\n#  published: 31x46 (PoseLib)\nproblem p\n# Macaulay2: 15 (x)\n";
        assert_eq!(
            header_value(src, "published").as_deref(),
            Some("31x46 (PoseLib)")
        );
        assert_eq!(header_value(src, "Macaulay2").as_deref(), Some("15 (x)"));
        assert_eq!(header_value("published: 3\n", "published"), None);
        assert_eq!(header_value("# publishedx: 3\n", "published"), None);
    }

    #[test]
    fn published_sizes_are_read_by_kind() {
        let p = PublishedSizes::parse("std 76x100, red 73x97, red 80x90 (eliminationTemplates)");
        assert_eq!(p.std, Some((76, 100)));
        assert_eq!(p.red, Some((73, 97)));
        assert_eq!(p.nstd, None);
        assert_eq!(p.other, None);
        assert_eq!(p.best_area(), Some(73 * 97));
        assert_eq!(p.std_whole_area(), Some(76 * 100));
        let w = PublishedSizes::parse("std 16x36 (std-whole 36x56), red 12x36");
        assert_eq!(w.std, Some((16, 36)));
        assert_eq!(w.std_whole, Some((36, 56)));
        assert_eq!(w.std_whole_area(), Some(36 * 56));
        assert_eq!(w.best_area(), Some(12 * 36));
        let q = PublishedSizes::parse("25x35 (PoseLib p35pf)");
        assert_eq!(q.other, Some((25, 35)));
        assert_eq!(q.std, None);
        assert_eq!(
            PublishedSizes::parse("a Gröbner-basis solver").best_area(),
            None
        );
    }
}
