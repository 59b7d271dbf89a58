//! Emission of `option newton` and of the polishing of poor solutions: the original
//! equations' coefficients (computed with the template's, from the same shared
//! intermediates), the equations written out as code (their values, magnitudes and
//! Jacobian, for `mingen_runtime::newton_polish_with`, `polish_poor_solution_with` and
//! `screen_redundant_readout_with`) or, past [`MAX_CODE_FORM_PRODUCTS`], as a constant
//! table of terms (for `newton_polish`, `polish_poor_solution` and
//! `screen_redundant_readout`), and the screening and polishing of each solution.

use super::coefficients::{Expr, VarStyle};
use super::runtime_api as rt;
use super::tokens::lit;
use super::{EmitError, PolishSpec, Traced};
use crate::algebra::{Monomial, Poly, Ring};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// Equations with at most this many factor products (terms and gradient entries) are
/// written out as code; larger ones are polished from the table of their terms, so that
/// no closure grows past what a debug build compiles comfortably.
pub(super) const MAX_CODE_FORM_PRODUCTS: usize = 4000;

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
    let code_form = (p.steps > 0 || p.reject_spurious)
        .then(|| code_form(terms, p.unknowns))
        .flatten();
    let (check, seen_setup, seen_check) = if p.reject_spurious {
        let distinct = rt::distinct_solutions();
        let n = lit(p.unknowns);
        let screen = if code_form.is_some() {
            let screen = rt::screen_redundant_readout_with();
            quote!(#screen(&mut x, newton_values, newton_jacobian))
        } else {
            let screen = rt::screen_redundant_readout();
            quote!(#screen(&mut x, &NEWTON_TERMS, &newton_c))
        };
        (
            quote! {
                if !#screen {
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
    let polish = match &code_form {
        Some(_) if p.poor_only => {
            let polish = rt::polish_poor_solution_with();
            quote!(#polish(&mut x, newton_values, newton_jacobian);)
        }
        None if p.poor_only => {
            let polish = rt::polish_poor_solution();
            quote!(#polish(&mut x, &NEWTON_TERMS, &newton_c);)
        }
        Some(_) if p.steps > 0 => {
            let (steps, polish) = (lit(p.steps), rt::newton_polish_with());
            quote!(#polish(&mut x, #steps, newton_values, newton_jacobian);)
        }
        None if p.steps > 0 => {
            let (steps, polish) = (lit(p.steps), rt::newton_polish());
            quote!(#polish(&mut x, &NEWTON_TERMS, &newton_c, #steps);)
        }
        _ => quote!(),
    };
    // The term table serves equations too large to write out.
    let table = if (p.reject_spurious || p.steps > 0) && code_form.is_none() {
        quote!(const NEWTON_TERMS: [&[(usize, &[u8])]; #neq] = [#(#eqs),*];)
    } else {
        quote!()
    };
    let closures = code_form.unwrap_or_default();
    let binding = if p.steps > 0 || p.reject_spurious {
        quote!(let mut x)
    } else {
        quote!(let x)
    };
    (
        quote! {
            let newton_c: [f64; #nc] = [#(#coeffs),*];
            #table
            #closures
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

/// The name of `x_k^p` (`p` from 2 up to `mingen_runtime::MAX_TABULATED_POWER`) in the
/// written-out equations.
fn power_name(k: usize, p: u8) -> Ident {
    format_ident!("x{k}_{p}")
}

/// `x_k^e` as the runtime's power table computes it: `x_k` itself, a product of the chain
/// `x_k^p = x_k^(p-1) x_k` up to the table's last power, `powi` past it.
fn power(k: usize, e: u8) -> TokenStream {
    let x = format_ident!("x{k}");
    if e == 1 {
        quote!(#x)
    } else if usize::from(e) <= mingen_runtime::MAX_TABULATED_POWER {
        let p = power_name(k, e);
        quote!(#p)
    } else {
        let e = Literal::i32_unsuffixed(i32::from(e));
        quote!(#x.powi(#e))
    }
}

/// `a * b * c` (left to right), or `None` for no factor.
fn left_product(factors: &[TokenStream]) -> Option<TokenStream> {
    let (first, rest) = factors.split_first()?;
    Some(rest.iter().fold(first.clone(), |acc, f| quote!(#acc * #f)))
}

/// `a * (b * c)` (right to left), or `None` for no factor.
fn right_product(factors: &[TokenStream]) -> Option<TokenStream> {
    let (last, rest) = factors.split_last()?;
    Some(
        rest.iter()
            .rev()
            .fold(last.clone(), |acc, f| quote!((#f * #acc))),
    )
}

/// The closures `newton_values` and `newton_jacobian` of `mingen_runtime::newton_polish_with`
/// for equations with `terms` in `n` unknowns, or `None` past [`MAX_CODE_FORM_PRODUCTS`].
///
/// Each product is formed in the order the runtime's table form forms it (`newton.rs`:
/// `value`, `value_and_gradient`), leaving out the factors `x^0 = 1` and `e = 1`, whose
/// products are exact; so both forms compute the same bits.
fn code_form(terms: &[EquationTerms], n: usize) -> Option<TokenStream> {
    let products: usize = terms
        .iter()
        .flatten()
        .map(|(_, e)| 1 + e.iter().filter(|&&d| d > 0).count())
        .sum();
    if products > MAX_CODE_FORM_PRODUCTS || n == 0 {
        return None;
    }
    // Unknowns used, and the highest tabulated power of each that a product reads.
    let mut highest = vec![0u8; n];
    for (_, e) in terms.iter().flatten() {
        for (h, &d) in highest.iter_mut().zip(e) {
            // A gradient reads x^(d - 1) as well; powers past the table are `powi`.
            for p in [d, d.saturating_sub(1)] {
                if usize::from(p) <= mingen_runtime::MAX_TABULATED_POWER {
                    *h = (*h).max(p);
                }
            }
            if d > 0 {
                *h = (*h).max(1);
            }
        }
    }
    let mut setup = Vec::new();
    for (k, &h) in highest.iter().enumerate() {
        if h == 0 {
            continue;
        }
        let x = format_ident!("x{k}");
        let i = lit(k);
        setup.push(quote!(let #x = x[#i];));
        for p in 2..=h {
            let (this, before) = (power_name(k, p), power(k, p - 1));
            setup.push(quote!(let #this = #before * #x;));
        }
    }
    let factors = |e: &[u8]| -> Vec<(usize, TokenStream)> {
        e.iter()
            .enumerate()
            .filter(|(_, &d)| d > 0)
            .map(|(k, &d)| (k, power(k, d)))
            .collect()
    };
    let mut values = Vec::new();
    let mut jacobian = Vec::new();
    for (i, eq) in terms.iter().enumerate() {
        let i = lit(i);
        let mut value_terms = Vec::new();
        let mut jacobian_terms = Vec::new();
        for (c, e) in eq {
            let c = lit(*c);
            let coefficient = quote!(newton_c[#c]);
            let fs = factors(e);
            let all: Vec<TokenStream> = fs.iter().map(|(_, f)| f.clone()).collect();
            // `value`: c (x^e_0 x^e_1 ...), the factors' product left to right.
            value_terms.push(match left_product(&all) {
                Some(p) => quote!(let t = #coefficient * (#p); v += t; a += t.abs();),
                None => quote!(let t = #coefficient; v += t; a += t.abs();),
            });
            // `value_and_gradient`: c (x^e_0 (x^e_1 (...))), and per unknown k in the
            // term, ((c x^e_0 ... x^e_(k-1)) e_k x_k^(e_k - 1)) (x^e_(k+1) (...)).
            jacobian_terms.push(match right_product(&all) {
                Some(p) => quote!(v += #coefficient * #p;),
                None => quote!(v += #coefficient;),
            });
            for (pos, (k, _)) in fs.iter().enumerate() {
                let d = e[*k];
                let mut chain = vec![coefficient.clone()];
                chain.extend(all[..pos].iter().cloned());
                if d > 1 {
                    let d_lit = Literal::f64_unsuffixed(f64::from(d));
                    chain.push(quote!(#d_lit));
                    chain.push(power(*k, d - 1));
                }
                if let Some(after) = right_product(&all[pos + 1..]) {
                    chain.push(after);
                }
                let product = left_product(&chain).unwrap_or_default();
                let k = lit(*k);
                jacobian_terms.push(quote!(g[#k] += #product;));
            }
        }
        values.push(quote! {
            let (mut v, mut a) = (0.0f64, 0.0f64);
            #(#value_terms)*
            f[#i] = v;
            m[#i] = a;
        });
        jacobian.push(quote! {
            let mut v = 0.0f64;
            let mut g = [0.0f64; NEWTON_N];
            #(#jacobian_terms)*
            f[#i] = v;
            j[#i] = g;
        });
    }
    let (nn, ne) = (lit(n), lit(terms.len()));
    Some(quote! {
        const NEWTON_N: usize = #nn;
        const NEWTON_E: usize = #ne;
        // A power that only a gradient reads is unused in the values.
        #[allow(unused_variables)]
        let newton_values = |x: &[f64; NEWTON_N], f: &mut [f64; NEWTON_E], m: &mut [f64; NEWTON_E]| {
            #(#setup)*
            #(#values)*
        };
        let newton_jacobian = |x: &[f64; NEWTON_N], f: &mut [f64; NEWTON_E], j: &mut [[f64; NEWTON_N]; NEWTON_E]| {
            #(#setup)*
            #(#jacobian)*
        };
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The written-out products associate as the runtime's table form does (`newton.rs`:
    /// `value` left to right, `value_and_gradient` right to left with a left-to-right
    /// prefix per gradient entry), so that both forms give the same bits.
    #[test]
    fn code_form_associates_as_the_table_form() {
        // c0 x0^2 x1 x2^16 + c1 in (x0, x1, x2): x2^16 is past the power table, x2^15
        // (its gradient's) the table's last entry.
        let terms = vec![vec![(0, vec![2, 1, 16]), (1, vec![0, 0, 0])]];
        let code = code_form(&terms, 3).unwrap().to_string().replace(' ', "");
        for want in [
            "letx0_2=x0*x0;",
            "letx2_15=x2_14*x2;",
            "lett=newton_c[0]*(x0_2*x1*x2.powi(16));v+=t;a+=t.abs();",
            "lett=newton_c[1];v+=t;a+=t.abs();",
            "v+=newton_c[0]*(x0_2*(x1*x2.powi(16)));",
            "g[0]+=newton_c[0]*2.0*x0*(x1*x2.powi(16));",
            "g[1]+=newton_c[0]*x0_2*x2.powi(16);",
            "g[2]+=newton_c[0]*x0_2*x1*16.0*x2_15;",
        ] {
            assert!(code.contains(want), "{want} not in {code}");
        }
        let big = vec![vec![(0, vec![1; 8]); MAX_CODE_FORM_PRODUCTS / 8]];
        assert!(code_form(&big, 8).is_none());
    }
}
