//! The emitted statements that build the action matrix from the reduced template (see the
//! template convention in [`crate::template`]).

use super::tokens::lit;
use crate::algebra::Monomial;
use crate::template::EliminationTemplate;
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use std::collections::HashMap;

/// The statements that fill the action matrix `a` (zeros) from the reduced template `m`
/// (see the template convention): `(unit entries, rows copied from the template)`. A
/// single-unknown action copies rows (negated); a linear form adds `c_i` times each. For
/// a pencil template these fill its relation matrix, which [`pencil_tokens`] turns into
/// the action matrix.
pub(super) fn action_matrix_tokens(
    t: &EliminationTemplate,
    column_of: &HashMap<Monomial, usize>,
    cols: usize,
    pivots: usize,
    nb: usize,
) -> (Vec<TokenStream>, TokenStream) {
    let nb_l = lit(nb);
    let mut units = Vec::new();
    if !t.action.is_monomial() {
        // Linear form: accumulate c * (unit or -T row) per product.
        let mut from_template = Vec::new();
        for (j, b) in t.basis.iter().enumerate() {
            for (p, coef) in t.action.products(b) {
                let c = t
                    .eliminated_column(column_of[&p])
                    .expect("action products are reducible or basis columns");
                let (jl, cl) = (lit(j), Literal::f64_unsuffixed(coef as f64));
                if c >= pivots {
                    let k = lit(c - pivots);
                    units.push(quote!(a[(#jl, #k)] += #cl;));
                } else {
                    let start = lit(c * cols + pivots);
                    from_template.push(quote!((#jl, #start, #cl)));
                }
            }
        }
        let lp = if from_template.is_empty() {
            quote!()
        } else {
            quote! {
                for (j, s, c) in [#(#from_template),*] {
                    for (k, x) in m[s..s + #nb_l].iter().enumerate() {
                        a[(j, k)] -= c * x;
                    }
                }
            }
        };
        return (units, lp);
    }
    let mut from_template = Vec::new();
    let mut single_source = None;
    for j in 0..t.basis.len() {
        let p = t
            .relation(j)
            .into_iter()
            .next()
            .map(|(p, _)| p)
            .expect("a monomial action relates each basis monomial to one monomial");
        let c = t
            .eliminated_column(column_of[&p])
            .expect("action products are reducible or basis columns");
        let jl = lit(j);
        if c >= pivots {
            let k = lit(c - pivots);
            units.push(quote!(a[(#jl, #k)] = 1.0;));
        } else {
            // Pivot row of column c holds c + sum_k T[c, k] b_k after Gauss-Jordan.
            let start = lit(c * cols + pivots);
            single_source = Some((jl.clone(), start.clone(), lit(c * cols + pivots + nb)));
            from_template.push(quote!((#jl, #start)));
        }
    }
    let from_template_loop = if from_template.is_empty() {
        quote!()
    } else if from_template.len() == 1 {
        let (jl, start, end) = single_source.expect("one row from the template");
        quote! {
            for (k, x) in m[#start..#end].iter().enumerate() {
                a[(#jl, k)] = -x;
            }
        }
    } else {
        quote! {
            for (j, s) in [#(#from_template),*] {
                for (k, x) in m[s..s + #nb_l].iter().enumerate() {
                    a[(j, k)] = -x;
                }
            }
        }
    };

    (units, from_template_loop)
}

/// The statements that turn the relation matrix `a` of a pencil template into its action
/// matrix (see the template convention; nothing for an ordinary template): the flipped rows
/// solve a small system on the stack, and the solver returns no solution when it is
/// singular.
pub(super) fn pencil_tokens(t: &EliminationTemplate, nb: usize) -> TokenStream {
    if t.flipped.is_empty() {
        return quote!();
    }
    let k = t.flipped.len();
    let rows = t.flipped.iter().map(|&j| lit(j));
    let (nb_l, scratch_l) = (lit(nb), lit(k * (k + nb)));
    let pencil = super::runtime_api::pencil_action_rows();
    quote! {
        let mut scratch = [0.0f64; #scratch_l];
        if !#pencil(a.as_mut_slice(), #nb_l, &[#(#rows),*], &mut scratch) {
            return out;
        }
    }
}
