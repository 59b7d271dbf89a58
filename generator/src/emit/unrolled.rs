//! The straight-line elimination of a small template (`EliminationTemplate::unrolled`):
//! one emitted function that runs the LU with partial pivoting of the runtime's
//! `lu_solve_template_sparse` along the plan of the template's own order, every index a
//! constant. Rows outside a step's candidates are zero in its column, so the pivots and
//! the numbers are the dense LU's (`mingen_runtime::lu_solve_template`); the entries that
//! are zero for every instance are not touched, and nothing is left to loops or index
//! arithmetic but the exchange of the pivot row.

use super::runtime_api as rt;
use super::tokens::lit;
use crate::template::{EliminationTemplate, SparseElimination};
use proc_macro2::TokenStream;
use quote::quote;

/// `fn eliminate_template(m: &mut [f64]) -> bool`: the forward elimination of every step
/// and the back substitution of the rows from the first reduced one, as the runtime's
/// sparse LU does them (the same pivot choice, the same operations on the entries the
/// plan says may be non-zero; a zero multiplier is not skipped, which changes no value).
pub(super) fn eliminate_template_fn(t: &EliminationTemplate, e: &SparseElimination) -> TokenStream {
    let (rows, cols) = t.eliminated_size();
    let pivots = t.pivot_columns();
    let first = t.first_reduced_row();
    let span = |start: &[u32], k: usize| start[k] as usize..start[k + 1] as usize;
    let at = |r: usize, c: usize| lit(r * cols + c);
    let mut steps = Vec::with_capacity(pivots);
    for k in 0..pivots {
        let pattern: Vec<usize> = e.pattern[span(&e.pattern_start, k)]
            .iter()
            .map(|&c| usize::from(c))
            .collect();
        let targets: Vec<usize> = e.targets[span(&e.target_start, k)]
            .iter()
            .map(|&i| usize::from(i))
            .collect();
        // The columns a step updates: its pattern, then the right-hand side.
        let updated: Vec<usize> = pattern.iter().copied().chain(pivots..cols).collect();
        let (kk, k_l) = (at(k, k), lit(k));
        let choose = targets.iter().map(|&i| {
            let (ik, i_l) = (at(i, k), lit(i));
            quote! {
                let a = m[#ik].abs();
                if a > best {
                    best = a;
                    p = #i_l;
                }
            }
        });
        let exchange = if targets.is_empty() {
            quote!()
        } else {
            let swapped = std::iter::once(k).chain(updated.iter().copied()).map(lit);
            let cols_l = lit(cols);
            // Row k's entry of column c (`c` itself in the first row: no `0 + c`).
            let in_row_k = if k == 0 {
                quote!(c)
            } else {
                let row_k = lit(k * cols);
                quote!(#row_k + c)
            };
            quote! {
                if p != #k_l {
                    for c in [#(#swapped),*] {
                        m.swap(#in_row_k, p * #cols_l + c);
                    }
                }
            }
        };
        let scale = updated.iter().map(|&c| {
            let kc = at(k, c);
            quote!(m[#kc] *= inv;)
        });
        let eliminate = targets.iter().map(|&i| {
            let columns = updated.iter().map(|&c| (i * cols + c, k * cols + c));
            subtract_multiple(i * cols + k, columns)
        });
        let mut_p = if targets.is_empty() {
            quote!(let best = m[#kk].abs();)
        } else {
            quote!(let (mut p, mut best) = (#k_l, m[#kk].abs());)
        };
        steps.push(quote! {
            #mut_p
            #(#choose)*
            if !(best > tol[#k_l] && best <= f64::MAX) {
                return false;
            }
            #exchange
            let inv = 1.0 / m[#kk];
            m[#kk] = 1.0;
            #(#scale)*
            #(#eliminate)*
        });
    }
    let back = (first..pivots).rev().map(|k| {
        let clears = e.pattern[span(&e.pattern_start, k)].iter().map(|&l| {
            let l = usize::from(l);
            let columns = (pivots..cols).map(|j| (k * cols + j, l * cols + j));
            subtract_multiple(k * cols + l, columns)
        });
        quote!(#(#clears)*)
    });
    let (size, pivots_l) = (lit(rows * cols), lit(pivots));
    // The dense LU's tolerances (`PIVOT_TOL` times each pivot column's largest magnitude)
    // and finiteness check (the magnitudes' sum, in four lanes), over the entries the fill
    // may set: the others are zero.
    let filled: Vec<usize> = e.filled.iter().map(|&i| i as usize).collect();
    let tolerances = (0..pivots).map(|j| {
        let mut entries = filled.iter().filter(|&&i| i % cols == j).map(|&i| lit(i));
        let j_l = lit(j);
        match entries.next() {
            Some(first) => {
                quote!(tol[#j_l] = pivot_tol * m[#first].abs()#(.max(m[#entries].abs()))*;)
            }
            None => quote!(),
        }
    });
    let lanes = (0..4).map(|lane| {
        let entries: Vec<_> = filled
            .iter()
            .skip(lane)
            .step_by(4)
            .map(|&i| lit(i))
            .collect();
        if entries.is_empty() {
            quote!(0.0f64)
        } else {
            quote!(#(m[#entries].abs())+*)
        }
    });
    let pivot_tol = rt::pivot_tol();
    quote! {
        /// The elimination of the filled template (row-major, in place), written out along
        /// its structure: LU with partial pivoting among each step's candidate rows (those
        /// that may be non-zero in its column; the others are zero there), then back
        /// substitution of the rows from the first reduced one. The dense LU's pivots and
        /// numbers. False if an entry is not finite or a pivot is below its column's
        /// tolerance.
        #[inline]
        #[rustfmt::skip]
        #[allow(clippy::too_many_lines)]
        fn eliminate_template(m: &mut [f64]) -> bool {
            let m: &mut [f64; #size] = match ::core::convert::TryFrom::try_from(m) {
                Ok(m) => m,
                Err(_) => return false,
            };
            let sums = [#(#lanes),*];
            if !((sums[0] + sums[1]) + (sums[2] + sums[3])).is_finite() {
                return false;
            }
            let pivot_tol = #pivot_tol;
            let mut tol = [0.0f64; #pivots_l];
            #(#tolerances)*
            #(#steps)*
            #(#back)*
            true
        }
    }
}

/// `f = m[entry]; m[entry] = 0; m[a] -= f * m[b]` for each `(a, b)`: a row loses the
/// multiple of another that clears `entry`.
fn subtract_multiple(entry: usize, columns: impl Iterator<Item = (usize, usize)>) -> TokenStream {
    let entry = lit(entry);
    let updates = columns.map(|(a, b)| {
        let (a, b) = (lit(a), lit(b));
        quote!(m[#a] -= f * m[#b];)
    });
    quote! {
        let f = m[#entry];
        m[#entry] = 0.0;
        #(#updates)*
    }
}
