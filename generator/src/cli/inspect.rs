//! `mingen inspect`: a problem and its plan, as text or one JSON object.

use super::{emit, CliError};
use mingen::__internal::algebra::{MonomialOrder, Poly, Q};
use mingen::{plan_file, Problem, SolverPlan, TemplateOptions};
use serde_json::{json, Map, Value};
use std::path::PathBuf;

/// The language-level facts about a problem, as a JSON object that later stages (Gröbner
/// basis, template) extend with their own keys.
fn problem_summary(p: &Problem, equations: &[Poly<Poly<Q>>]) -> Map<String, Value> {
    let names = p.unknown_names();
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
        json!(p.layout.names_of(&p.layout.eliminate)),
    );
    m.insert(
        "positive".into(),
        json!(p.layout.names_of(&p.layout.positive)),
    );
    m
}

pub(super) fn inspect(
    file: &PathBuf,
    as_json: bool,
    options: &TemplateOptions,
) -> Result<(), CliError> {
    let parsed = Problem::from_file_within(file, options.budget)?;
    let plan = plan_file(file, options)?;
    // The planned problem: the file's, with what planning added (automatic elimination).
    let p = &plan.problem;
    // The symbolic expansion has the data as variables too, so it can be far larger than
    // the instances planning expanded: it has a budget of its own.
    let deadline = options.budget.start();
    let equations = p.expand_within(Some(&deadline)).map_err(|e| CliError {
        message: format!("{}: {e}", file.display()),
        code: 2,
    })?;
    let mut summary = problem_summary(p, &equations);
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
        let el = plan.eliminated_names();
        let how = if let Some(b) = p.block_reduction() {
            let pivots = b.pivot_rows.len();
            match b.mode {
                mingen::__internal::eliminate::BlockMode::Minors => format!(
                    " (row-reduced on the data: the rows that cancel their {} columns, then the minors of {pivots} rows)",
                    b.columns.len()
                ),
                mingen::__internal::eliminate::BlockMode::Substitute => format!(
                    " (row-reduced on the data: {pivots} rows solved for their {} columns and substituted)",
                    b.columns.len()
                ),
            }
        } else if !parsed.layout.eliminate.is_empty() {
            String::new()
        } else if p.substitution().is_some() {
            " (automatic: solved from the affine equations and substituted into the others; `option auto_eliminate = no` keeps them)".to_string()
        } else {
            " (automatic: they appear only linearly, with data coefficients; `option auto_eliminate = no` keeps them)".to_string()
        };
        outln!(out, "eliminate: {}{how}", el.join(" "));
    }
    if !p.layout.positive.is_empty() {
        let positive = p.layout.names_of(&p.layout.positive);
        outln!(
            out,
            "positive: {} (solutions where one is not positive are dropped)",
            positive.join(" ")
        );
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
fn print_plan(out: &mut String, plan: &SolverPlan) {
    let names = plan.variable_names();
    let g = &plan.generated;
    let t = &g.built.template;
    match plan.sign_symmetry_description() {
        None => outln!(out, "solutions: {}", g.count),
        Some(symmetry) => {
            outln!(
                out,
                "solutions: {} ({} up to sign)",
                plan.solution_count(),
                g.count
            );
            outln!(
                out,
                "sign symmetry: {symmetry}; `option sign_symmetry = no` solves as written"
            );
        }
    }
    if plan.problem.nonzero_count() > 0 {
        let divisions = plan.problem.divisions();
        let divided = divisions
            .iter()
            .filter(|d| d.iter().any(|&k| k > 0))
            .count();
        let t = &plan.generated.built.template;
        let visible = t.visible_vars();
        let hidden_in_template = t
            .columns
            .iter()
            .any(|m| m.0[visible..].iter().any(|&e| e > 0));
        let saturation = if plan.problem.is_saturated() && t.shift.is_some() {
            "kept, inside the template (its columns stand for multiples of a power of the polynomial; no hidden unknown in it)"
        } else if plan.problem.is_saturated() && !hidden_in_template {
            "kept, inside the template (the basis shifted by the monomial; no hidden unknown in it)"
        } else if plan.problem.is_saturated() {
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
    if !t.flipped.is_empty() {
        let flipped: Vec<String> = t
            .flipped
            .iter()
            .map(|&j| t.basis[j].display_with(&names))
            .collect();
        outln!(
            out,
            "  relations taken the other way round (b / action reduced; a pencil): {}",
            flipped.join(" ")
        );
    }
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
        t.first_reduced_row(),
        t.n_reducible,
        t.basis.len()
    );
    if t.folded_rows() > 0 {
        let (fr, fc) = t.filled_size();
        outln!(
            out,
            "  (the Schur complement of the {fr} x {fc} template's {} folded rows: {} in a constant block, {} with constant pivots in a triangle)",
            t.folded_rows(),
            t.fold.as_ref().map_or(0, |f| f.rows),
            t.fold.as_ref().map_or(0, |f| f.pivot_inv.len()),
        );
    }
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
    if let Some(r) = &plan.redundant_check {
        let (rows, cols) = r.redundant_size;
        outln!(
            out,
            "redundant basis: {} ({rows} x {cols} with {} spurious eigenvalues; on {} random instances: {:.3} against {:.3} real solutions, {} against {} failures with the quotient basis)",
            if r.kept { "kept" } else { "dropped" },
            r.spurious_eigenvalues,
            r.instances,
            r.mean_real.0,
            r.mean_real.1,
            r.failures.0,
            r.failures.1
        );
        for (rows, cols) in &r.dropped_smaller {
            outln!(
                out,
                "  measured before it and dropped: {rows} x {cols} (solutions lost or spurious read-outs kept)"
            );
        }
    }
    if let Some(a) = &plan.action_accuracy {
        outln!(
            out,
            "action by accuracy (the first template's solver failed its polishing sample; failures on {} further instances):",
            mingen::ACCURACY_INSTANCES
        );
        for (k, t) in a.tried.iter().enumerate() {
            let size = t
                .size
                .map_or("no template within the budget".to_string(), |(r, c)| {
                    format!("{r} x {c}")
                });
            let measured = match t.failure_rate {
                Some(rate) => format!("{:.1} % failures", 100.0 * rate),
                None if k == 0 => "not measured: no other template as small".to_string(),
                None if t.size.is_some() => "larger, not measured".to_string(),
                None => String::new(),
            };
            let kept = if k == a.kept { " (kept)" } else { "" };
            outln!(out, "  {:<6} {size}  {measured}{kept}", t.action);
        }
    }
    let steps = match plan.polishes_poor_solutions_only() {
        true => format!(
            "poor solutions only ({} Gauss-Newton steps where the residual is above {:e})",
            mingen_runtime::POOR_SOLUTION_STEPS,
            mingen_runtime::POOR_SOLUTION_RESIDUAL
        ),
        false => format!(
            "{} Gauss-Newton steps",
            plan.problem.layout.options.newton_steps()
        ),
    };
    match &plan.auto_polishing {
        Some(a) => outln!(
            out,
            "polishing: {steps} (chosen: unpolished, {} random instances gave median {:.2} and p99 {:.2} log10 residual, {} failures in {}; `option newton = N` sets it)",
            mingen::AUTO_POLISH_INSTANCES,
            a.median_log10_residual,
            a.p99_log10_residual,
            a.failures,
            a.instances
        ),
        None => outln!(out, "polishing: {steps} (as set)"),
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
