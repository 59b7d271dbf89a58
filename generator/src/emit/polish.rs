//! Emission of `option newton`: the original equations' coefficients (computed with the
//! template's, from the same shared intermediates), their terms as a constant table, and
//! the call of `mingen_runtime::newton_polish` on each solution.

use super::coefficients::{Expr, VarStyle};
use super::runtime_api as rt;
use super::tokens::lit;
use super::{EmitError, PolishSpec, Traced};
use crate::algebra::{Monomial, Poly, Ring};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// One equation's terms: (index among the polishing coefficients, exponents of the declared
/// unknowns).
pub(super) type EquationTerms = Vec<(usize, Vec<u8>)>;

/// Whether a solver can polish solutions on `equations` in their first `unknowns` unknowns
/// (`option newton`): at most `mingen_runtime::MAX_NEWTON_UNKNOWNS` unknowns, at least as
/// many equations, no exponent above 255 (the term tables store `u8`).
pub(crate) fn check_polishable<C: Ring>(
    unknowns: usize,
    equations: &[Poly<C>],
) -> Result<(), EmitError> {
    if unknowns > mingen_runtime::MAX_NEWTON_UNKNOWNS || equations.len() < unknowns {
        return Err(EmitError::Unsupported(format!(
            "option newton needs at most {} unknowns and as many equations ({} unknowns, {} equations)",
            mingen_runtime::MAX_NEWTON_UNKNOWNS,
            unknowns,
            equations.len()
        )));
    }
    let small = |m: &Monomial| m.0[..unknowns].iter().all(|&d| d <= u8::MAX.into());
    if !equations.iter().all(|e| e.terms().all(|(m, _)| small(m))) {
        return Err(EmitError::Unsupported(
            "option newton with an exponent above 255".into(),
        ));
    }
    Ok(())
}

/// Appends the coefficients of `p`'s equations to `values` and returns each equation's
/// terms: (index among the appended coefficients, exponents of the declared unknowns).
pub(super) fn coefficients(
    p: &PolishSpec,
    values: &mut Vec<Traced>,
) -> Result<Vec<EquationTerms>, EmitError> {
    check_polishable(p.unknowns, &p.equations)?;
    let first = values.len();
    let mut out = Vec::with_capacity(p.equations.len());
    for eq in &p.equations {
        let mut terms = Vec::new();
        for (m, c) in eq.terms() {
            // Exponents fit in `u8`: checked above.
            let e = m.0[..p.unknowns].iter().map(|&d| d as u8).collect();
            terms.push((values.len() - first, e));
            values.push(c.clone());
        }
        out.push(terms);
    }
    Ok(out)
}

/// `(before the solution loop, inside it)`: the coefficient array `newton_c` and the term
/// table `NEWTON_TERMS`; then `x`, the solution in declared-unknown order (`values`), and
/// its polishing. `outputs` are the program outputs of the coefficients of
/// [`coefficients`], in order.
pub(super) fn tokens(
    p: &PolishSpec,
    terms: &[EquationTerms],
    outputs: &[Expr],
    values: Vec<TokenStream>,
    style: VarStyle,
) -> (TokenStream, TokenStream) {
    let coeffs: Vec<TokenStream> = outputs.iter().map(|e| e.tokens(style)).collect();
    let nc = lit(coeffs.len());
    let neq = lit(terms.len());
    let eqs: Vec<TokenStream> = terms
        .iter()
        .map(|terms| {
            let ts = terms.iter().map(|(c, e)| {
                let c = lit(*c);
                let e = e.iter().map(|&x| Literal::u8_unsuffixed(x));
                quote!((#c, &[#(#e),*]))
            });
            quote!(&[#(#ts),*])
        })
        .collect();
    let (check, seen_setup, seen_check) = if p.reject_spurious {
        let (screen, distinct) = (rt::screen_redundant_readout(), rt::distinct_solutions());
        let n = lit(p.unknowns);
        (
            quote! {
                if !#screen(&mut x, &NEWTON_TERMS, &newton_c) {
                    continue;
                }
            },
            quote! {
                let mut seen = #distinct::<#n, MAX_SOLUTIONS>::new();
            },
            quote! {
                if !seen.insert(&x) {
                    continue;
                }
            },
        )
    } else {
        (quote!(), quote!(), quote!())
    };
    let polish = if p.steps > 0 {
        let (steps, polish) = (lit(p.steps), rt::newton_polish());
        quote!(#polish(&mut x, &NEWTON_TERMS, &newton_c, #steps);)
    } else {
        quote!()
    };
    let binding = if p.steps > 0 || p.reject_spurious {
        quote!(let mut x)
    } else {
        quote!(let x)
    };
    (
        quote! {
            let newton_c: [f64; #nc] = [#(#coeffs),*];
            const NEWTON_TERMS: [&[(usize, &[u8])]; #neq] = [#(#eqs),*];
            #seen_setup
        },
        quote! {
            #binding = [#(#values),*];
            #check
            #polish
            #seen_check
        },
    )
}
