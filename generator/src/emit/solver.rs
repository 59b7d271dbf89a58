//! The solver emitter: one Rust source file per problem.

use super::action::{action_matrix_tokens, pencil_tokens};
use super::coefficients::{Expr, VarStyle};
use super::files::generated_header_for_path;
use super::fill::{fill_tokens, Coefficients};
use super::runtime_api as rt;
use super::solution_loop::solution_loop;
use super::structs::{data_field_idents, emit_data, emit_solution, slot_access};
use super::tokens::{doc, lit};
use super::traced::Traced;
use super::{EmitError, SolverSpec};
use crate::algebra::{Monomial, Poly};
use crate::template::{EliminationTemplate, ShapeError};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

/// Templates with at most this many rows are kept on the stack; larger ones use a `Vec`.
pub const SMALL_TEMPLATE_ROWS: usize = 40;

/// Solvers whose template entries plus coefficient statements exceed this are emitted in
/// table form (see [`VarStyle::Array`]): straight-line code of that length inside one
/// function makes the compiler's time grow faster than linearly, and its recursion deep
/// enough to overflow rustc's default stack in a debug build.
pub const TABLE_FORM_MIN_SIZE: usize = 2048;

/// The most coefficient statements (`let`s in one function) the inline form may have:
/// beyond them rustc's debug build overflows its stack (see [`TABLE_FORM_MIN_SIZE`], which
/// keeps [`CodeForm::Auto`](super::CodeForm::Auto) below this).
pub const MAX_INLINE_STATEMENTS: usize = TABLE_FORM_MIN_SIZE;

/// Everything `solve` needs, validated and indexed.
pub(super) struct Plan<'a> {
    pub(super) spec: &'a SolverSpec,
    /// Names of the template variables.
    pub(super) var_names: Vec<String>,
    /// For each original unknown scalar: template variable `Ok(k)` or eliminated `Err(j)`.
    pub(super) source: Vec<Result<usize, usize>>,
    pub(super) column_of: HashMap<Monomial, usize>,
    pub(super) basis_one: usize,
    /// Read-out pairs `(j, k)`, `basis[k] = x_i * basis[j]`, of each template variable
    /// (`interpret::readout_pairs`); none for a variable outside the basis, which is read
    /// off its reduced template row (the linear read-out), and none for a companion
    /// action's unknown, the eigenvalue.
    pub(super) readout: Vec<Vec<(usize, usize)>>,
}

fn validate_template(
    t: &EliminationTemplate,
    equations: &[Poly<Traced>],
    names: &[String],
) -> Result<HashMap<Monomial, usize>, EmitError> {
    let bad = |s: String| Err(EmitError::Invalid(s));
    t.check_emittable(names).map_err(|e| match e {
        ShapeError::BasisLacks(_) | ShapeError::ReadoutNotReducible(_) => {
            EmitError::Unsupported(e.to_string())
        }
        e => EmitError::Invalid(e.to_string()),
    })?;
    let column_of: HashMap<Monomial, usize> = t
        .columns
        .iter()
        .enumerate()
        .map(|(i, m)| (m.clone(), i))
        .collect();
    let reduced = t.reduction.as_ref().map(|r| r.reduced_supports());
    if let Some(red) = &t.reduction {
        if red.len() != equations.len() {
            return bad(format!(
                "{} equations but the equation reduction has {}",
                equations.len(),
                red.len()
            ));
        }
    }
    for (i, row) in t.rows.iter().enumerate() {
        let eq = equations.get(row.equation).ok_or_else(|| {
            EmitError::Invalid(format!(
                "row {i} refers to equation {} of {}",
                row.equation,
                equations.len()
            ))
        })?;
        if eq.nvars() != t.nvars || row.multiplier.nvars() != t.nvars {
            return bad(format!(
                "row {i}: equation or multiplier not in the template's {} variables",
                t.nvars
            ));
        }
        let monomials: Vec<&Monomial> = match &reduced {
            Some(r) => r[row.equation].iter().collect(),
            None => eq.terms().map(|(m, _)| m).collect(),
        };
        // A shifted template's columns are coordinates, not its products' monomials
        // (`crate::template::shift`).
        for m in monomials.into_iter().filter(|_| t.shift.is_none()) {
            let p = row.multiplier.mul(m);
            if !column_of.contains_key(&p) {
                return bad(format!("row {i}: monomial {p:?} is not a template column"));
            }
        }
    }
    Ok(column_of)
}

impl<'a> Plan<'a> {
    fn new(spec: &'a SolverSpec) -> Result<Self, EmitError> {
        let t = &spec.template;
        let layout = &spec.layout;
        let n_unknowns = layout.unknown_count();
        let names = layout.unknown_names();
        let template_names: Vec<String> = match &spec.elimination {
            Some(el) => el
                .remaining
                .iter()
                .map(|&i| names.get(i).cloned().unwrap_or_default())
                .collect(),
            None => names.clone(),
        };
        let column_of = validate_template(t, &spec.equations, &template_names)?;
        let mut source = vec![Err(usize::MAX); n_unknowns];
        let var_names: Vec<String>;
        match &spec.elimination {
            None => {
                if !layout.eliminate.is_empty() {
                    return Err(EmitError::Invalid(
                        "the problem eliminates unknowns but no elimination info was given".into(),
                    ));
                }
                if t.nvars != n_unknowns {
                    return Err(EmitError::Invalid(format!(
                        "the template has {} variables, the problem {} unknowns",
                        t.nvars, n_unknowns
                    )));
                }
                for (k, s) in source.iter_mut().enumerate() {
                    *s = Ok(k);
                }
                var_names = names.clone();
            }
            Some(el) => {
                let width = el.eliminated.len() + usize::from(el.inhomogeneous);
                if el.remaining.len() != t.nvars {
                    return Err(EmitError::Invalid(format!(
                        "{} remaining unknowns but the template has {} variables",
                        el.remaining.len(),
                        t.nvars
                    )));
                }
                let mut seen = vec![false; n_unknowns];
                let all = el.remaining.iter().chain(&el.eliminated);
                for &i in all {
                    if i >= n_unknowns || seen[i] {
                        return Err(EmitError::Invalid(format!(
                            "unknown index {i} out of range or listed twice in the elimination info"
                        )));
                    }
                    seen[i] = true;
                }
                if seen.iter().any(|s| !s) {
                    return Err(EmitError::Invalid(
                        "the elimination info does not cover every unknown".into(),
                    ));
                }
                for (k, &i) in el.remaining.iter().enumerate() {
                    source[i] = Ok(k);
                }
                for (j, &i) in el.eliminated.iter().enumerate() {
                    source[i] = Err(j);
                }
                if el.eliminated.is_empty() || el.coefficient_matrix.len() + 1 < width {
                    return Err(EmitError::Invalid(format!(
                        "the elimination coefficient matrix needs at least {} rows",
                        width.max(2) - 1
                    )));
                }
                for (r, row) in el.coefficient_matrix.iter().enumerate() {
                    if row.len() != width {
                        return Err(EmitError::Invalid(format!(
                            "elimination matrix row {r} has {} entries, expected {width}",
                            row.len()
                        )));
                    }
                    if row.iter().any(|p| p.nvars() != t.nvars) {
                        return Err(EmitError::Invalid(format!(
                            "elimination matrix row {r}: entries must be polynomials in the {} template variables",
                            t.nvars
                        )));
                    }
                }
                var_names = el.remaining.iter().map(|&i| names[i].clone()).collect();
            }
        }
        let basis_pos = |m: &Monomial| t.basis.iter().position(|b| b == m);
        let basis_one = basis_pos(&t.unit()).ok_or_else(|| {
            EmitError::Unsupported("the basis does not contain the monomial 1".into())
        })?;
        Ok(Plan {
            spec,
            var_names,
            source,
            column_of,
            basis_one,
            readout: crate::interpret::readout_pairs(t)
                .map_err(|e| EmitError::Unsupported(e.to_string()))?,
        })
    }

    fn mono(&self, m: &Monomial) -> String {
        m.display_with(&self.var_names)
    }
}

/// Emits the solver file for `spec` (see the module documentation of `crate::emit`).
pub fn emit_solver(spec: &SolverSpec) -> Result<String, EmitError> {
    if syn::parse_str::<Ident>(&spec.layout.module_name()).is_err() {
        return Err(EmitError::Unsupported(format!(
            "problem name `{}` does not give a Rust module name (`{}`)",
            spec.layout.name,
            spec.layout.module_name()
        )));
    }
    let plan = Plan::new(spec)?;
    let layout = &spec.layout;
    let t = &spec.template;
    let problem_path = if spec.problem_path.is_empty() {
        format!("templates/{}.mp", layout.name)
    } else {
        spec.problem_path.replace('\\', "/")
    };

    let data_items = emit_data(layout)?;
    let solution_items = emit_solution(layout)?;
    let (solve_fn, stats) = emit_solve(&plan)?;

    let (rows, cols) = t.eliminated_size();
    let nb = t.basis.len();
    let basis: Vec<String> = t.basis.iter().map(|b| plan.mono(b)).collect();
    let dependent = if t.n_dependent > 0 {
        format!(
            " ({} more excess monomials are linear combinations of these and left out)",
            t.n_dependent
        )
    } else {
        String::new()
    };
    let mut module_doc = vec![
        format!(
            "Minimal solver for the problem `{}` (`{}`).",
            layout.name, problem_path
        ),
        String::new(),
        format!(
            "Unknowns: {}. Data: {}.",
            layout
                .declared_unknowns()
                .map(|u| match u.len {
                    Some(n) => format!("`{}[{}]`", u.name, n),
                    None => format!("`{}`", u.name),
                })
                .collect::<Vec<_>>()
                .join(", "),
            layout
                .data
                .iter()
                .map(|d| match d.len {
                    Some(n) => format!("`{}[{}]: {}`", d.name, n, d.kind.keyword()),
                    None => format!("`{}: {}`", d.name, d.kind.keyword()),
                })
                .collect::<Vec<_>>()
                .join(", ")
        ),
        format!(
            "Elimination template {rows} x {cols} ({} excess, {} reducible, {nb} basis \
             columns){dependent}, action `{}`, at most {nb} solutions.",
            t.first_reduced_row(),
            t.n_reducible,
            t.action.display_with(&plan.var_names)
        ),
        format!("Quotient basis: {}.", basis.join(", ")),
        format!(
            "Coefficients: {} arithmetic operations in {} shared intermediates.",
            stats.ops, stats.stmts
        ),
    ];
    if let Some(f) = t.fold.as_ref().filter(|_| t.folded_rows() > 0) {
        let (fr, fc) = t.filled_size();
        let (k, kt) = (f.rows, f.pivot_inv.len());
        let what = match (k, kt) {
            (_, 0) => format!(
                "{k} constant rows (multiples of equations with numeric coefficients), \
                 eliminated exactly by the generator"
            ),
            (0, _) => format!(
                "{kt} rows with constant pivots in a triangle (multiples of equations with \
                 numeric coefficients)"
            ),
            _ => format!(
                "{} folded rows (multiples of equations with numeric coefficients: {k} in a \
                 constant block the generator inverted exactly, {kt} with constant pivots in \
                 a triangle)",
                k + kt
            ),
        };
        module_doc.insert(
            4,
            format!("It is the Schur complement of the {fr} x {fc} template's {what}."),
        );
    }
    if let Some((n, m)) = t.reduction_size() {
        module_doc.insert(
            4,
            format!(
                "Its rows are multiples of the equations row-reduced on the data first (a \
                 {n} x {m} coefficient matrix)."
            ),
        );
    }
    if let Some(el) = &spec.elimination {
        let names = layout.unknown_names();
        let listed = el
            .eliminated
            .iter()
            .map(|&i| format!("`{}`", names[i]))
            .collect::<Vec<_>>()
            .join(", ");
        let (rows, k) = (el.coefficient_matrix.len(), el.eliminated.len());
        module_doc.push(if el.inhomogeneous {
            format!(
                "Eliminated unknowns {listed} are recovered as the null vector of a {rows} x {} \
                 matrix divided by its last entry.",
                k + 1
            )
        } else {
            format!(
                "Eliminated unknowns {listed} are recovered as the unit null vector of a {rows} x \
                 {k} matrix (one of the two signs)."
            )
        });
    }
    module_doc.push(String::new());
    module_doc.push("Do not edit: regenerate with `mingen generate`.".into());
    // Plain comments, not `//!`: an included file (`include!`) may not have inner
    // attributes, and the same text documents the `Solver` type.
    let comment: String = module_doc
        .iter()
        .map(|l| {
            if l.is_empty() {
                "//\n".to_string()
            } else {
                format!("// {l}\n")
            }
        })
        .collect();
    let solver_doc: Vec<TokenStream> = module_doc[..module_doc.len() - 2].iter().map(doc).collect();

    let max = lit(nb << spec.sign_folds.len());
    let set = rt::solution_set();
    let solver_trait = rt::minimal_solver();
    let stages = rt::stages();
    let name = &layout.name;
    let tokens = quote! {
        #data_items

        #solution_items

        /// The largest number of real solutions [`solve`] returns.
        pub const MAX_SOLUTIONS: usize = #max;

        /// The real solutions of one instance.
        pub type Solutions = #set<Solution, MAX_SOLUTIONS>;

        #solve_fn

        #(#solver_doc)*
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        pub struct Solver;

        impl #solver_trait for Solver {
            const NAME: &'static str = #name;
            const MAX_SOLUTIONS: usize = MAX_SOLUTIONS;
            const TEMPLATE_SHAPE: [usize; 4] = TEMPLATE_SHAPE;
            type Data = Data;
            type Solution = Solution;
            type Solutions = Solutions;
            fn solve(data: &Data) -> Solutions {
                solve(data)
            }
            fn solve_staged<S: #stages>(data: &Data, stages: &mut S) -> Solutions {
                solve_staged(data, stages)
            }
        }
    };
    let file: syn::File = syn::parse2(tokens).map_err(|e| EmitError::Internal(e.to_string()))?;
    let body = prettyplease::unparse(&file);
    Ok(format!(
        "{}\n{comment}\n{}",
        generated_header_for_path(&problem_path),
        body
    ))
}

struct Stats {
    ops: usize,
    stmts: usize,
}

/// `coeff * u_a * u_b * ...` terms summed, for an entry of the elimination matrix.
pub(super) fn entry_tokens(terms: &[(Monomial, Expr)], style: VarStyle) -> TokenStream {
    if terms.is_empty() {
        return quote!(0.0);
    }
    let mut out = TokenStream::new();
    for (i, (m, c)) in terms.iter().enumerate() {
        let (neg, c) = match c {
            Expr::Neg(inner) => (true, (**inner).clone()),
            Expr::Const(v) if *v < 0.0 => (true, Expr::Const(-v)),
            other => (false, other.clone()),
        };
        let mut factors: Vec<TokenStream> = Vec::new();
        let is_one = matches!(c, Expr::Const(v) if v == 1.0);
        if !is_one || m.is_one() {
            factors.push(c.tokens(style));
        }
        for (k, &e) in m.0.iter().enumerate() {
            let u = format_ident!("u{}", k);
            for _ in 0..e {
                factors.push(quote!(#u));
            }
        }
        let mut it = factors.into_iter();
        let first = it.next().expect("a term has at least one factor");
        let prod = it.fold(first, |acc, f| quote!(#acc * #f));
        out = match (i, neg) {
            (0, false) => prod,
            (0, true) => quote!(-#prod),
            (_, false) => quote!(#out + #prod),
            (_, true) => quote!(#out - #prod),
        };
    }
    out
}

/// Emits `solve` and `solve_staged`, stage by stage: the data, the coefficients, the
/// template fill, its elimination, the action matrix, the eigenvectors, the read-out of
/// each solution (with the eliminated unknowns and polishing) and the documentation.
fn emit_solve(plan: &Plan) -> Result<(TokenStream, Stats), EmitError> {
    let spec = plan.spec;
    let t = &spec.template;
    let (rows, cols) = t.eliminated_size();
    let nb = t.basis.len();
    let pivots = t.pivot_columns();
    let n_slots = spec.layout.data_slot_count();
    let slot_expr = data_slots(plan)?;
    let mut coefficients = Coefficients::new(plan)?;
    let stats = Stats {
        ops: coefficients.program.op_count(),
        stmts: coefficients.program.stmts.len(),
    };
    let fill = fill_tokens(plan, &mut coefficients)?;
    let (units, from_template_loop) = action_matrix_tokens(t, &plan.column_of, cols, pivots, nb);
    let pencil = pencil_tokens(t, nb);
    let solutions = solution_loop(plan, &coefficients, fill.style)?;
    let elimination = Elimination::new(t);
    let (rows_l, cols_l, pivots_l, nb_l) = (lit(rows), lit(cols), lit(pivots), lit(nb));
    let eigenpairs = match t.companion_unknown() {
        // The first row is the polynomial's: the rest of `a` serves the observer only.
        Some(_) if (3..=4).contains(&nb) => {
            let companion = rt::real_eigenpairs_companion();
            quote!(#companion::<#nb_l>(&::core::array::from_fn(|k| a[(0, k)])))
        }
        _ => {
            let eig = eigen_function(nb);
            quote!(#eig::<#nb_l>(&a))
        }
    };
    let docs: Vec<TokenStream> = solve_docs(plan, elimination.words)
        .iter()
        .map(doc)
        .collect();

    let n_slots_l = lit(n_slots);
    let first_row = &elimination.first_row;
    let elimination_items = &elimination.items;
    let reduce = &elimination.reduce;
    let coefficient_fns = &fill.functions;
    let coefficients_and_fill = &fill.code;
    let stages = rt::stages();
    let smat = rt::smatrix();
    let solve = quote! {
        /// The elimination template's `[rows, cols, pivot columns, first reduced row]`.
        pub const TEMPLATE_SHAPE: [usize; 4] = [#rows_l, #cols_l, #pivots_l, #first_row];
        #elimination_items
        #coefficient_fns

        #(#docs)*
        #[must_use]
        pub fn solve(data: &Data) -> Solutions {
            solve_staged(data, &mut ())
        }

        /// [`solve`] with an observer called between the stages (benchmarks, diagnostics).
        #[doc(hidden)]
        #[must_use]
        #[inline]
        #[rustfmt::skip]
        #[allow(
            clippy::similar_names,
            clippy::many_single_char_names,
            clippy::too_many_lines
        )]
        pub fn solve_staged<S: #stages>(data: &Data, stages: &mut S) -> Solutions {
            let mut out = Solutions::new();
            let d: [f64; #n_slots_l] = [#(#slot_expr),*];
            if d.iter().any(|x| !x.is_finite()) {
                return out;
            }
            #coefficients_and_fill
            if !stages.filled(&m) {
                return out;
            }
            if !#reduce {
                return out;
            }
            if !stages.eliminated(&m) {
                return out;
            }
            let mut a = #smat::<f64, #nb_l, #nb_l>::zeros();
            #(#units)*
            #from_template_loop
            #pencil
            if !stages.action(a.as_slice()) {
                return out;
            }
            let pairs = #eigenpairs;
            #solutions
            out
        }
    };
    Ok((solve, stats))
}

/// The data flattened in slot order: one expression reading each slot from `data`.
fn data_slots(plan: &Plan) -> Result<Vec<TokenStream>, EmitError> {
    let layout = &plan.spec.layout;
    let mut slot_expr: Vec<Option<TokenStream>> = vec![None; layout.data_slot_count()];
    for (d, field) in layout.data.iter().zip(data_field_idents(layout)?) {
        let per = d.kind.slots();
        for e in 0..d.len.unwrap_or(1) {
            for k in 0..per {
                let s = d.first_slot + e * per + k;
                match slot_expr.get_mut(s) {
                    Some(x @ None) => *x = Some(slot_access(&field, d, e, k)),
                    _ => {
                        return Err(EmitError::Invalid(format!(
                            "data slot {s} of `{}` is out of range or used twice",
                            d.name
                        )))
                    }
                }
            }
        }
    }
    Ok(slot_expr
        .into_iter()
        .map(|x| x.expect("all slots covered"))
        .collect())
}

/// The elimination of the filled template: dense or sparse LU.
struct Elimination {
    /// The first row the elimination reduces (the rows above are excess rows).
    first_row: Literal,
    /// The items it needs: the sparse LU's structure (a static) or the written-out
    /// elimination (a function); empty for the dense LU.
    items: TokenStream,
    /// The call that reduces `m`, true on success.
    reduce: TokenStream,
    /// How the documentation names it.
    words: &'static str,
}

impl Elimination {
    fn new(t: &EliminationTemplate) -> Self {
        let (rows, cols) = t.eliminated_size();
        let (rows_l, cols_l, pivots_l) = (lit(rows), lit(cols), lit(t.pivot_columns()));
        let first_row = lit(t.first_reduced_row());
        match &t.sparse {
            Some(e) => {
                let ty = rt::sparse_lu_plan();
                let lu = rt::lu_solve_template_sparse();
                let u32s = |v: &[u32]| {
                    v.iter()
                        .map(|&x| Literal::u32_unsuffixed(x))
                        .collect::<Vec<_>>()
                };
                let u16s = |v: &[u16]| {
                    v.iter()
                        .map(|&x| Literal::u16_unsuffixed(x))
                        .collect::<Vec<_>>()
                };
                let (ps, p, ts, tg) = (
                    u32s(&e.pattern_start),
                    u16s(&e.pattern),
                    u32s(&e.target_start),
                    u16s(&e.targets),
                );
                Elimination {
                    items: quote! {
                        /// The structure of the template's sparse LU with partial pivoting (a bound
                        /// over every pivot choice; see `mingen_runtime::SparseLuPlan`).
                        #[rustfmt::skip]
                        pub static SPARSE_PLAN: #ty<'static> = #ty {
                            rows: #rows_l,
                            cols: #cols_l,
                            pivot_cols: #pivots_l,
                            first_row: #first_row,
                            pattern_start: &[#(#ps),*],
                            pattern: &[#(#p),*],
                            target_start: &[#(#ts),*],
                            targets: &[#(#tg),*],
                        };
                    },
                    reduce: quote!(#lu::<#cols_l, #pivots_l>(&mut m, &SPARSE_PLAN)),
                    first_row,
                    words: "sparse LU with partial pivoting",
                }
            }
            None if t.unrolled.is_some() => {
                let e = t.unrolled.as_ref().expect("checked just above");
                Elimination {
                    items: super::unrolled::eliminate_template_fn(t, e),
                    reduce: quote!(eliminate_template(&mut m)),
                    first_row,
                    words: "LU with partial pivoting written out along the template's structure",
                }
            }
            None => {
                let lu = rt::lu_solve_template();
                Elimination {
                    items: quote!(),
                    reduce: quote!(#lu::<#rows_l, #cols_l, #pivots_l, #first_row>(&mut m)),
                    first_row,
                    words: "LU with partial pivoting",
                }
            }
        }
    }
}

/// The eigen back end for an action matrix of `nb` x `nb`: Sturm sequences on the stack
/// for small bases, Hessenberg QR above.
fn eigen_function(nb: usize) -> TokenStream {
    if nb <= mingen_runtime::STURM_MAX_BASIS {
        rt::real_eigenpairs_sturm()
    } else {
        rt::real_eigenpairs_hqr()
    }
}

/// The lines of `solve`'s documentation: what it computes, stage by stage.
fn solve_docs(plan: &Plan, lu_words: &str) -> Vec<String> {
    let spec = plan.spec;
    let t = &spec.template;
    let (rows, cols) = t.eliminated_size();
    let nb = t.basis.len();
    let basis: Vec<String> = t.basis.iter().map(|b| plan.mono(b)).collect();
    let mut docs = vec![
        format!(
            "Solves `{}`: all real solutions of the problem's equations for the given data.",
            spec.layout.name
        ),
        String::new(),
        format!(
            "Fills a {rows} x {cols} elimination template, reduces it ({lu_words}, \
             back substitution of the {} reducible rows only), builds the {nb} x {nb} \
             action matrix of `{}` on the basis [{}] and reads each unknown `x` off the real \
             eigenvectors `v` as the least-squares ratio of the entries `v[x b]` and `v[b]` \
             over the basis monomials `b` with `x b` in the basis (`v[x] / v[1]` if that is the \
             only one).",
            t.n_reducible,
            t.action.display_with(&plan.var_names),
            basis.join(", ")
        ),
        String::new(),
    ];
    if !t.flipped.is_empty() {
        let flipped: Vec<String> = t.flipped.iter().map(|&j| basis[j].clone()).collect();
        docs.push(format!(
            "The relations of [{}] are taken the other way round (`b / action` reduced, a \
             pencil `action T1 v = T0 v`): the action matrix is `T1^-1 T0`, its flipped rows \
             solved by `mingen_runtime::pencil_action_rows`.",
            flipped.join(", ")
        ));
        docs.push(String::new());
    }
    if let Some(red) = &t.reduction {
        let pivots: Vec<String> = red
            .pivots
            .iter()
            .map(|&p| plan.mono(&red.monomials[p]))
            .collect();
        docs.push(format!(
            "The template's rows are multiples of the equations row-reduced on the data \
             (`mingen_runtime::reduce_equations`) to the pivot monomials [{}].",
            pivots.join(", ")
        ));
        docs.push(String::new());
    }
    for fold in &spec.sign_folds {
        let name = |i: usize| {
            plan.var_names
                .get(i)
                .cloned()
                .unwrap_or_else(|| format!("x{i}"))
        };
        let p = name(fold.pivot);
        let vars: Vec<String> = fold
            .variables()
            .into_iter()
            .map(|j| format!("`{}`", name(j)))
            .collect();
        let others = if fold.scaled.is_empty() {
            String::new()
        } else {
            format!(", the others for their ratios to `{p}`")
        };
        docs.push(format!(
            "Every equation is even or odd in {} together, so solutions come in sign \
             pairs: the template solves the system folded by `{p}` (its `{p}` stands for \
             `{p}^2`{others}), and each solution with `{p}^2 > 0` gives both signs \
             (`mingen_runtime::unfold_signs`).",
            vars.join(", ")
        ));
        docs.push(String::new());
    }
    match &spec.polish {
        Some(p) if p.poor_only => {
            docs.push(format!(
                "Then polishes a poor solution (its worst relative residual on the problem's \
                 original equations above `mingen_runtime::POOR_SOLUTION_RESIDUAL`) by up to \
                 {} Gauss-Newton steps on those equations, each taken only if it (or, up to \
                 four times, half of it) lowers the sum of their squared relative residuals \
                 (`mingen_runtime::polish_poor_solution`; `option newton` polishes every \
                 solution).",
                p.steps
            ));
            docs.push(String::new());
        }
        Some(p) if p.steps > 0 => {
            docs.push(format!(
                "Then polishes each solution by up to {} Gauss-Newton steps on the problem's \
                 original equations (`option newton`), each taken only if it (or, up to four \
                 times, half of it) lowers the sum of their squared relative residuals.",
                p.steps
            ));
            docs.push(String::new());
        }
        _ => {}
    }
    if !spec.layout.positive.is_empty() {
        let positive: Vec<String> = spec
            .layout
            .names_of(&spec.layout.positive)
            .iter()
            .map(|n| format!("`{n}`"))
            .collect();
        docs.push(format!(
            "Solutions where {} is not positive are dropped (declared `positive`).",
            positive.join(", ")
        ));
        docs.push(String::new());
    }
    docs.push("Never panics: non-finite or degenerate data gives no solutions.".into());
    docs
}
