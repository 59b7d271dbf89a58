//! The table form of large solvers: coefficient statements spread over functions of
//! bounded size that write one coefficient array, and a constant table that fills a matrix
//! (the template, or the equations' coefficient matrix when they are reduced first) from it.

use super::coefficients::Program;
use super::runtime_api as rt;
use super::tokens::{doc, lit};
use super::EmitError;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// Coefficient statements per function in table form.
const STATEMENTS_PER_FUNCTION: usize = 512;

/// The matrix the coefficients are written to.
pub(super) struct FillTarget {
    /// Its variable in `solve` (`m`: the template).
    pub(super) name: Ident,
    /// The name of the fill table (`TEMPLATE_FILL` for the template).
    pub(super) table: Ident,
    /// Its allocation (`let mut m = ...;`).
    pub(super) alloc: TokenStream,
    /// Its number of entries.
    pub(super) len: usize,
    /// What it is, for the table's documentation ("template").
    pub(super) what: &'static str,
}

/// The table form's items (the coefficient functions and the fill table) and the code in
/// `solve` that computes the coefficients and fills the matrix `target.name` (allocated
/// by `target.alloc`) through the table `target.table`.
pub(super) fn table_form_tokens(
    program: &mut Program,
    fill_pos: &[usize],
    n_slots: usize,
    target: &FillTarget,
) -> Result<(TokenStream, TokenStream), EmitError> {
    let template_len = target.len;
    let too_large = |coefficients: usize| {
        EmitError::Unsupported(format!(
            "a template of {template_len} entries or {coefficients} coefficients does not fit \
             the fill table's 32-bit indices"
        ))
    };
    if u32::try_from(template_len).is_err() {
        return Err(too_large(program.stmts.len()));
    }
    let refs = program.bind_outputs(0..fill_pos.len());
    let mut table = Vec::with_capacity(fill_pos.len());
    for (&p, &(k, neg)) in fill_pos.iter().zip(&refs) {
        let code = u32::try_from(2 * k + usize::from(neg)).map_err(|_| too_large(k))?;
        table.push((p as u32, code));
    }
    table.sort_unstable();
    let entries = table.iter().map(|&(p, code)| {
        let (p, code) = (Literal::u32_unsuffixed(p), Literal::u32_unsuffixed(code));
        quote!([#p, #code])
    });
    let n_fill = lit(table.len());
    let nc = lit(program.stmts.len());
    let n_slots_l = lit(n_slots);
    let stmts = program.stmt_tokens_array();
    let mut fns = Vec::new();
    let mut calls = Vec::new();
    for (i, chunk) in stmts.chunks(STATEMENTS_PER_FUNCTION).enumerate() {
        let name = format_ident!("coefficients_{}", i);
        let doc = doc(format!(
            "Coefficient statements {} to {} (table form).",
            i * STATEMENTS_PER_FUNCTION,
            i * STATEMENTS_PER_FUNCTION + chunk.len() - 1
        ));
        fns.push(quote! {
            #doc
            #[inline(never)]
            #[rustfmt::skip]
            #[allow(unused_variables, clippy::too_many_lines)]
            fn #name(d: &[f64; #n_slots_l], c: &mut [f64; #nc]) {
                #(#chunk)*
            }
        });
        calls.push(quote!(#name(&d, &mut c);));
    }
    let (zeroed, fill) = (rt::zeroed_coefficients(), rt::fill_template());
    let (name, table, alloc) = (&target.name, &target.table, &target.alloc);
    let table_doc = [
        doc(format!(
            "The {}'s nonzero entries: `[entry, 2 k + negated]`, the entry (row-major)",
            target.what
        )),
        doc("and the coefficient `c[k]` it holds (negated if the low bit is set)."),
    ];
    Ok((
        quote! {
            #(#fns)*
            #(#table_doc)*
            #[rustfmt::skip]
            static #table: [[u32; 2]; #n_fill] = [#(#entries),*];
        },
        quote! {
            let mut c = #zeroed::<#nc>();
            #(#calls)*
            #alloc
            #fill(&mut #name, &c[..], &#table);
        },
    ))
}
