//! Emission of the equation reduction (see [`crate::template::reduction`]): the solver
//! writes its equations' coefficients into their coefficient matrix `q`, reduces it to
//! the planned pivots with `mingen_runtime::reduce_equations_fixed`, and fills the template
//! from the reduced coefficients through a constant table.

use super::runtime_api as rt;
use super::table_form::FillTarget;
use super::tokens::lit;
use super::traced::Traced;
use super::EmitError;
use crate::algebra::{Monomial, Poly};
use crate::template::{EliminationTemplate, EquationReduction};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

/// Coefficient matrices with at most this many entries are kept on the stack.
const SMALL_MATRIX_ENTRIES: usize = 4096;

/// The coefficient matrix `q` as the target of the coefficient code.
pub(super) fn equation_matrix_target(red: &EquationReduction) -> FillTarget {
    let len = red.len() * red.monomials.len();
    let len_l = lit(len);
    FillTarget {
        name: format_ident!("q"),
        table: format_ident!("EQUATION_FILL"),
        alloc: if len <= SMALL_MATRIX_ENTRIES {
            quote!(let mut q = [0.0f64; #len_l];)
        } else {
            quote!(let mut q = vec![0.0f64; #len_l];)
        },
        len,
        what: "equations' coefficient matrix",
    }
}

/// Where each coefficient of `equations` goes in `q` (row-major, one row per equation,
/// one column per monomial of the reduction), with the coefficients, in equation and term
/// order.
pub(super) fn equation_entries(
    red: &EquationReduction,
    equations: &[Poly<Traced>],
) -> Result<(Vec<usize>, Vec<Traced>), EmitError> {
    if equations.len() != red.len() {
        return Err(EmitError::Invalid(format!(
            "{} equations but the equation reduction has {}",
            equations.len(),
            red.len()
        )));
    }
    let index: HashMap<&Monomial, usize> = red
        .monomials
        .iter()
        .enumerate()
        .map(|(i, m)| (m, i))
        .collect();
    let n = red.monomials.len();
    let mut pos = Vec::new();
    let mut vals = Vec::new();
    for (i, e) in equations.iter().enumerate() {
        for (m, c) in e.terms() {
            let j = index.get(m).ok_or_else(|| {
                EmitError::Invalid(format!(
                    "equation {i} has the monomial {m:?}, which the equation reduction lacks"
                ))
            })?;
            pos.push(i * n + j);
            vals.push(c.clone());
        }
    }
    Ok((pos, vals))
}

/// The most template entries the inline form fills from `q` by one assignment each
/// rather than through the constant table: straight-line copies with constant indices
/// cost a move each, the table's loop several instructions more per entry, while the
/// compile time stays small.
pub const STRAIGHT_LINE_FILL_MAX_ENTRIES: usize = 1024;

/// The items (pivot constant, fill table) and the code in `solve` after `q` is filled:
/// the reduction, the allocation of the template `m` (`alloc_m`) and its fill from `q`
/// (written out as assignments when `inline` and at most
/// [`STRAIGHT_LINE_FILL_MAX_ENTRIES`], else by `mingen_runtime::fill_template` and a
/// constant table). `column_of` maps monomials to template columns; `cols` is the
/// eliminated width.
pub(super) fn reduce_and_fill_tokens(
    t: &EliminationTemplate,
    red: &EquationReduction,
    column_of: &HashMap<Monomial, usize>,
    cols: usize,
    alloc_m: &TokenStream,
    inline: bool,
) -> Result<(TokenStream, TokenStream), EmitError> {
    let n = red.monomials.len();
    let mut table: Vec<(u32, u32)> = Vec::new();
    let too_large = || {
        EmitError::Unsupported(
            "the template or the equations' coefficient matrix does not fit the fill \
             table's 32-bit indices"
                .into(),
        )
    };
    for (i, row) in t.rows.iter().enumerate() {
        let support = red.supports.get(row.equation).ok_or_else(|| {
            EmitError::Invalid(format!(
                "row {i} refers to reduced equation {} of {}",
                row.equation,
                red.len()
            ))
        })?;
        for &j in support {
            let prod = row.multiplier.mul(&red.monomials[j]);
            let col = column_of.get(&prod).ok_or_else(|| {
                EmitError::Invalid(format!(
                    "row {i}: monomial {prod:?} is not a template column"
                ))
            })?;
            let Some(col) = t.eliminated_column(*col) else {
                continue;
            };
            let entry = u32::try_from(i * cols + col).map_err(|_| too_large())?;
            let code = u32::try_from(2 * (row.equation * n + j)).map_err(|_| too_large())?;
            table.push((entry, code));
        }
    }
    table.sort_unstable();
    let pivots = red.pivots.iter().map(|&p| lit(p));
    let (n_eq, n_l) = (lit(red.len()), lit(n));
    let reduce = rt::reduce_equations();
    let pivot_item = quote! {
        /// The pivot of each reduced equation: a column of the equations' coefficient
        /// matrix `q` (one column per monomial of the equations).
        pub const EQUATION_PIVOTS: [usize; #n_eq] = [#(#pivots),*];
    };
    if inline && table.len() <= STRAIGHT_LINE_FILL_MAX_ENTRIES {
        // Codes are 2 k (never negated here): `m[entry] = q[k]`.
        let fills = table.iter().map(|&(p, code)| {
            let (p, k) = (lit(p as usize), lit((code >> 1) as usize));
            quote!(m[#p] = q[#k];)
        });
        return Ok((
            pivot_item,
            quote! {
                if !#reduce::<#n_eq, #n_l>(&mut q[..], &EQUATION_PIVOTS) {
                    return out;
                }
                #alloc_m
                #(#fills)*
            },
        ));
    }
    let entries = table.iter().map(|&(p, code)| {
        let (p, code) = (Literal::u32_unsuffixed(p), Literal::u32_unsuffixed(code));
        quote!([#p, #code])
    });
    let (n_fill, fill) = (lit(table.len()), rt::fill_template());
    Ok((
        quote! {
            #pivot_item
            /// The template's nonzero entries from the reduced equations: `[entry, 2 k]`,
            /// the entry (row-major) and the entry `q[k]` of the reduced coefficient matrix
            /// it holds.
            #[rustfmt::skip]
            static REDUCED_FILL: [[u32; 2]; #n_fill] = [#(#entries),*];
        },
        quote! {
            if !#reduce::<#n_eq, #n_l>(&mut q[..], &EQUATION_PIVOTS) {
                return out;
            }
            #alloc_m
            #fill(&mut m, &q[..], &REDUCED_FILL);
        },
    ))
}
