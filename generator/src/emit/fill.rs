//! The coefficient code of an emitted solver and the fill of its template: every value
//! computed from the data as one straight-line program ([`Coefficients`]), written inline or
//! as tables ([`CodeForm`]), and the fold of the template's constant rows.

use super::coefficients::{signed_f64_literal, Expr, Program, VarStyle};
use super::polish::EquationTerms;
use super::runtime_api as rt;
use super::solver::{Plan, MAX_INLINE_STATEMENTS, SMALL_TEMPLATE_ROWS, TABLE_FORM_MIN_SIZE};
use super::table_form::{table_form_tokens, FillTarget};
use super::tokens::lit;
use super::traced::Traced;
use super::{CodeForm, EmitError};
use crate::algebra::{Monomial, MonomialOrder};
use crate::template::shift::column_coordinates;
use crate::template::{ConstantFold, EliminationTemplate};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashSet;

/// Every coefficient the solver computes from the data, as one straight-line [`Program`]:
/// its outputs are the template fill's values, then the elimination matrix's, then the
/// polishing equations'.
pub(super) struct Coefficients {
    /// The position of each fill value in the filled matrix (the template, or the
    /// equations' coefficient matrix when they are reduced first).
    fill_pos: Vec<usize>,
    /// How many outputs fill the matrix.
    pub(super) n_fill: usize,
    /// The monomials of each entry of the elimination coefficient matrix, row by row.
    pub(super) elim_terms: Vec<Vec<Vec<Monomial>>>,
    /// How many outputs the elimination matrix has.
    pub(super) n_elim: usize,
    /// The polishing equations' terms.
    pub(super) polish_terms: Vec<EquationTerms>,
    pub(super) program: Program,
}

impl Coefficients {
    pub(super) fn new(plan: &Plan) -> Result<Self, EmitError> {
        let spec = plan.spec;
        let t = &spec.template;
        let cols = t.filled_size().1;
        // Template entries (inlinable) or, when the equations are reduced first, the
        // entries of their coefficient matrix; then elimination matrix coefficients (bound
        // before the solution loop). A fold's complement is taken after the fill.
        let (fill_pos, fill_vals) = match &t.reduction {
            Some(red) => super::reduction::equation_entries(red, &spec.equations)?,
            None => {
                let mut fill_pos: Vec<usize> = Vec::new();
                let mut fill_vals: Vec<Traced> = Vec::new();
                let shift: Option<Vec<(Monomial, Traced)>> = match &t.shift {
                    Some(s) => Some(s.terms_in().ok_or_else(|| {
                        EmitError::Unsupported("a shift polynomial outside the reals".into())
                    })?),
                    None => None,
                };
                for (i, row) in t.rows.iter().enumerate() {
                    let terms = column_coordinates(
                        &row.multiplier,
                        &spec.equations[row.equation],
                        shift.as_deref(),
                        t.n_excess,
                        |m| plan.column_of.get(m).copied(),
                    );
                    for (m, c) in terms {
                        // Dependent excess columns are not part of the eliminated matrix.
                        let Some(col) = t.filled_column(plan.column_of[&m]) else {
                            continue;
                        };
                        fill_pos.push(i * cols + col);
                        fill_vals.push(c);
                    }
                }
                (fill_pos, fill_vals)
            }
        };
        // Each template entry is written once: two terms of one row never share a column
        // because the equation's monomials are distinct.
        let mut elim_terms: Vec<Vec<Vec<Monomial>>> = Vec::new();
        let mut elim_vals: Vec<Traced> = Vec::new();
        if let Some(el) = &spec.elimination {
            for row in &el.coefficient_matrix {
                let mut r = Vec::new();
                for p in row {
                    let support = p.support(MonomialOrder::Grevlex);
                    for m in &support {
                        elim_vals.push(p.coeff(m));
                    }
                    r.push(support);
                }
                elim_terms.push(r);
            }
        }
        // Polishing: the original equations' coefficients, bound before the loop with the
        // elimination matrix's.
        let n_elim = elim_vals.len();
        let polish_terms = match &spec.polish {
            Some(p) => super::polish::coefficients(p, &mut elim_vals)?,
            None => Vec::new(),
        };
        let program = Program::build(&fill_vals, &elim_vals, spec.layout.data_slot_count())?;
        Ok(Coefficients {
            fill_pos,
            n_fill: fill_vals.len(),
            elim_terms,
            n_elim,
            polish_terms,
            program,
        })
    }
}

/// The coefficient code and the fill of the template (or of the equations' coefficient
/// matrix, then reduced and filled into the template), in the form [`CodeForm`] asks for.
pub(super) struct Fill {
    /// Items outside `solve`: the coefficient functions and fill tables.
    pub(super) functions: TokenStream,
    /// The code in `solve` that leaves the filled template in `m`.
    pub(super) code: TokenStream,
    /// How the coefficient code names its values, for the code after the fill.
    pub(super) style: VarStyle,
}

pub(super) fn fill_tokens(plan: &Plan, coefficients: &mut Coefficients) -> Result<Fill, EmitError> {
    let spec = plan.spec;
    let t = &spec.template;
    let (rows, cols) = t.eliminated_size();
    let n_slots = spec.layout.data_slot_count();
    let program = &mut coefficients.program;
    let fill_pos = &coefficients.fill_pos;
    let size_l = lit(rows * cols);
    let alloc = if rows <= SMALL_TEMPLATE_ROWS {
        quote!(let mut m = [0.0f64; #size_l];)
    } else {
        quote!(let mut m = vec![0.0f64; #size_l];)
    };
    let table_form = match spec.code_form {
        CodeForm::Auto => coefficients.n_fill + program.stmts.len() > TABLE_FORM_MIN_SIZE,
        // Each `let` opens a scope nested in the previous one, and rustc's debug build
        // recurses through them: past a few thousand in one function it overflows its
        // stack. Code that cannot compile is refused rather than emitted.
        CodeForm::Inline if program.stmts.len() > MAX_INLINE_STATEMENTS => {
            return Err(EmitError::Unsupported(format!(
                "the inline form would have {} coefficient statements in one function, more \
                 than rustc compiles in a debug build (at most {MAX_INLINE_STATEMENTS}); use \
                 the table form (--code-form table, or auto)",
                program.stmts.len()
            )))
        }
        CodeForm::Inline => false,
        CodeForm::Table => true,
    };
    let style = if table_form {
        VarStyle::Array
    } else {
        VarStyle::Locals
    };
    let target = match (&t.reduction, &t.fold) {
        (Some(red), _) => super::reduction::equation_matrix_target(red),
        (None, Some(_)) => {
            let (filled_rows, filled_cols) = t.filled_size();
            let len = filled_rows * filled_cols;
            let len_l = lit(len);
            FillTarget {
                name: format_ident!("mf"),
                table: format_ident!("TEMPLATE_FILL"),
                alloc: if rows <= SMALL_TEMPLATE_ROWS {
                    quote!(let mut mf = [0.0f64; #len_l];)
                } else {
                    quote!(let mut mf = vec![0.0f64; #len_l];)
                },
                len,
                what: "template before its fold",
            }
        }
        (None, None) => FillTarget {
            name: format_ident!("m"),
            table: format_ident!("TEMPLATE_FILL"),
            alloc: alloc.clone(),
            len: rows * cols,
            what: "template",
        },
    };
    let (mut functions, mut code) = if table_form {
        table_form_tokens(program, fill_pos, n_slots, &target)?
    } else {
        let coeff_stmts = program.stmt_tokens();
        let mut fill_order: Vec<(usize, &Expr)> = fill_pos
            .iter()
            .copied()
            .zip(&program.outputs[..coefficients.n_fill])
            .collect();
        fill_order.sort_by_key(|(p, _)| *p);
        let name = &target.name;
        let fills: Vec<TokenStream> = fill_order
            .into_iter()
            .map(|(p, e)| {
                let p = lit(p);
                let e = e.to_tokens();
                quote!(#name[#p] = #e;)
            })
            .collect();
        let target_alloc = &target.alloc;
        (
            quote!(),
            quote! {
                #(#coeff_stmts)*
                #target_alloc
                #(#fills)*
            },
        )
    };
    if let Some(red) = &t.reduction {
        let (items, reduce) = super::reduction::reduce_and_fill_tokens(
            t,
            red,
            &plan.column_of,
            cols,
            &alloc,
            !table_form,
        )?;
        functions.extend(items);
        code.extend(reduce);
    } else if let Some(f) = &t.fold {
        let (items, fold) = fold_tokens(t, f, fill_pos, !table_form, &alloc);
        functions.extend(items);
        code.extend(fold);
    }
    Ok(Fill {
        functions,
        code,
        style,
    })
}

/// The constants of a template's fold (static items) and the code that forms the Schur
/// complement of the filled template `mf` into the template `m` (allocated by `alloc`):
/// the constant block's complement first (written out in the `inline` form when small,
/// [`STRAIGHT_LINE_FOLD_MAX_UPDATES`]), then the pivot rows'.
fn fold_tokens(
    t: &EliminationTemplate,
    f: &ConstantFold,
    fill_pos: &[usize],
    inline: bool,
    alloc: &TokenStream,
) -> (TokenStream, TokenStream) {
    let (rows, cols) = t.eliminated_size();
    let kt = f.pivot_inv.len();
    // The constant block's complement: the pivot rows and the eliminated matrix.
    let (rows1, cols1) = (rows + kt, cols + kt);
    let mut items = TokenStream::new();
    let mut code = TokenStream::new();
    let source = if f.rows > 0 {
        let target = if kt == 0 {
            code.extend(alloc.clone());
            format_ident!("m")
        } else {
            let len = lit(rows1 * cols1);
            code.extend(if rows1 <= SMALL_TEMPLATE_ROWS {
                quote!(let mut mc = [0.0f64; #len];)
            } else {
                quote!(let mut mc = vec![0.0f64; #len];)
            });
            format_ident!("mc")
        };
        if inline && f.updates <= STRAIGHT_LINE_FOLD_MAX_UPDATES {
            let written: HashSet<usize> = fill_pos.iter().copied().collect();
            code.extend(straight_line_fold(f, rows1, cols1, &written, &target));
            target
        } else {
            let (rows_l, cols_l, k_l) = (lit(rows1), lit(cols1), lit(f.rows));
            let ty = rt::constant_fold();
            let fold = rt::fold_constant_rows();
            let starts = f.inv_start.iter().map(|&x| Literal::u32_unsuffixed(x));
            let inv_cols = f.inv_cols.iter().map(|&x| Literal::u16_unsuffixed(x));
            let m12_starts = f.m12_start.iter().map(|&x| Literal::u32_unsuffixed(x));
            let m12_cols = f.m12_cols.iter().map(|&x| Literal::u16_unsuffixed(x));
            let inv_vals = f.inv_vals.iter().map(|&x| signed_f64_literal(x));
            items.extend(quote! {
                /// The inverse of the template's constant block (see
                /// `mingen_runtime::ConstantFold`), computed exactly by the generator.
                #[rustfmt::skip]
                pub static CONSTANT_FOLD: #ty<'static> = #ty {
                    rows: #rows_l,
                    folded: #k_l,
                    cols: #cols_l,
                    inv_start: &[#(#starts),*],
                    inv_cols: &[#(#inv_cols),*],
                    inv_vals: &[#(#inv_vals),*],
                    m12_start: &[#(#m12_starts),*],
                    m12_cols: &[#(#m12_cols),*],
                };
            });
            code.extend(quote! {
                let mut fold_scratch = [0.0f64; #k_l];
                if !#fold(&mf, &CONSTANT_FOLD, &mut fold_scratch, &mut #target) {
                    return out;
                }
            });
            target
        }
    } else {
        format_ident!("mf")
    };
    if kt > 0 {
        let (rows_l, cols_l, k_l) = (lit(rows), lit(cols), lit(kt));
        let ty = rt::triangular_fold();
        let fold = rt::fold_triangular_rows();
        let pivots = f.pivot_inv.iter().map(|&x| signed_f64_literal(x));
        items.extend(quote! {
            /// The inverse pivots of the template's rows folded in a triangle (see
            /// `mingen_runtime::TriangularFold`).
            #[rustfmt::skip]
            pub static TRIANGULAR_FOLD: #ty<'static> = #ty {
                rows: #rows_l,
                folded: #k_l,
                cols: #cols_l,
                pivot_inv: &[#(#pivots),*],
            };
        });
        code.extend(alloc.clone());
        code.extend(quote! {
            if !#fold(&mut #source, &TRIANGULAR_FOLD, &mut m) {
                return out;
            }
        });
    }
    (items, code)
}

/// In the inline form, constant folds of at most this many multiply-adds
/// ([`ConstantFold::updates`]) are written out as straight-line code; larger ones, and
/// every fold of the table form, call `mingen_runtime::fold_constant_rows` with their plan
/// (the code would grow with the fold). Both compute the same values.
pub const STRAIGHT_LINE_FOLD_MAX_UPDATES: usize = 1024;

/// `mingen_runtime::fold_constant_rows` written out for the fold `f` of the filled
/// template `mf` (`(f.rows + rows) x (f.rows + cols)`, the positions `written` filled, the
/// others zero) into `target` (`rows x cols`): per row of the complement, `t = M21[i, :]
/// M11⁻¹` as `t_q = 0 + sum_p M21[i, p] inv[p][q]` in increasing `p`, then `target[i, c] =
/// M22[i, c] - sum_q t_q M12[q, c]` in increasing `q`, the runtime's operations in its
/// order, so its values (it skips a zero factor at run time where this code multiplies it,
/// which can change the sign of a zero only). No plan to walk and every index a constant:
/// the compiler keeps the values in registers.
fn straight_line_fold(
    f: &ConstantFold,
    rows: usize,
    cols: usize,
    written: &HashSet<usize>,
    target: &proc_macro2::Ident,
) -> TokenStream {
    let k = f.rows;
    let width = k + cols;
    let read = |pos: usize| {
        let p = lit(pos);
        quote!(mf[#p])
    };
    // The non-zeros of M12, per folded row: (column, position in `mf`).
    let m12: Vec<Vec<(usize, usize)>> = (0..k)
        .map(|q| {
            let range = f.m12_start[q] as usize..f.m12_start[q + 1] as usize;
            f.m12_cols[range]
                .iter()
                .map(|&c| (usize::from(c), q * width + k + usize::from(c)))
                .filter(|(_, pos)| written.contains(pos))
                .collect()
        })
        .collect();
    let mut code = TokenStream::new();
    for i in 0..rows {
        let row = (k + i) * width;
        // t_q's terms, in increasing p.
        let mut terms: Vec<Vec<TokenStream>> = vec![Vec::new(); k];
        for p in (0..k).filter(|&p| written.contains(&(row + p))) {
            let range = f.inv_start[p] as usize..f.inv_start[p + 1] as usize;
            for (&q, &v) in f.inv_cols[range.clone()].iter().zip(&f.inv_vals[range]) {
                let a = read(row + p);
                // Products by 1 and -1 are exact: `a` and `-a` are the same bits.
                terms[usize::from(q)].push(if v == 1.0 {
                    quote!(+ #a)
                } else if v == -1.0 {
                    quote!(- #a)
                } else {
                    let v = signed_f64_literal(v);
                    quote!(+ #a * #v)
                });
            }
        }
        let t_name = |q: usize| format_ident!("t{}", q);
        // A t_q that no column of M12 reads is left out (the runtime computes it unused).
        let lets = terms
            .iter()
            .enumerate()
            .filter(|(q, ts)| !ts.is_empty() && !m12[*q].is_empty())
            .map(|(q, ts)| {
                let name = t_name(q);
                quote!(let #name = 0.0 #(#ts)*;)
            });
        // Per output column, the subtrahends in increasing q.
        let mut minus: Vec<Vec<TokenStream>> = vec![Vec::new(); cols];
        for (q, entries) in m12.iter().enumerate() {
            if terms[q].is_empty() {
                continue;
            }
            let name = t_name(q);
            for &(c, pos) in entries {
                let x = read(pos);
                minus[c].push(quote!(- #name * #x));
            }
        }
        let stores = (0..cols).filter_map(|c| {
            let m22 = written.contains(&(row + k + c)).then(|| read(row + k + c));
            if minus[c].is_empty() && m22.is_none() {
                return None;
            }
            let first = m22.unwrap_or_else(|| quote!(0.0));
            let rest = &minus[c];
            let at = lit(i * cols + c);
            Some(quote!(#target[#at] = #first #(#rest)*;))
        });
        code.extend(quote! {
            {
                #(#lets)*
                #(#stores)*
            }
        });
    }
    code
}
