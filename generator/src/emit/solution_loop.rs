//! The emitted solver's loop over the real eigenpairs of the action matrix: per eigenvector,
//! the read-out of the template variables, both signs of a sign-folded system, the
//! recovery of eliminated unknowns, polishing, the `positive` filter and the push of the
//! solution (ARCHITECTURE §2, emission).

use super::coefficients::{Expr, VarStyle};
use super::fill::Coefficients;
use super::runtime_api as rt;
use super::solver::{entry_tokens, Plan};
use super::structs::solution_field_idents;
use super::tokens::lit;
use super::EmitError;
use crate::algebra::Monomial;
use crate::eliminate::has_data_only_columns;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// The code of `solve` after `let pairs = ...` (the real eigenpairs): the constants the
/// loop reads (the elimination's factorisation, the polishing equations, the read-out
/// pairs) and the loop, which pushes each solution into `out`.
pub(super) fn solution_loop(
    plan: &Plan,
    coefficients: &Coefficients,
    style: VarStyle,
) -> Result<TokenStream, EmitError> {
    let spec = plan.spec;
    let readout = Readout::new(plan);
    let (elim_setup, elim_block) = eliminated_unknowns_tokens(plan, coefficients, style);
    let (polish_consts, polish_block) = polish_tokens(plan, coefficients, style);
    let field_inits = solution_fields(plan)?;
    let (prefilter, filter) = positive_filter(plan);
    let Readout {
        one_l,
        nvars_l,
        pairs: readout_pairs,
        unknown_idents,
        linear_reads,
    } = &readout;
    // An action that is one unknown: that unknown is the eigenvalue where its pairs cannot
    // be read (`read_unknowns_with_eigenvalue`).
    let (lambda, read_call) = match spec.template.action.single() {
        Some(i) => {
            let (read, il) = (rt::read_unknowns_with_eigenvalue(), lit(i));
            (
                quote!(lambda),
                quote!(#read(v.as_slice(), #one_l, &READOUT, Some((#il, *lambda)), &mut u)),
            )
        }
        None => {
            let read = rt::read_unknowns();
            (
                quote!(_),
                quote!(#read(v.as_slice(), #one_l, &READOUT, &mut u)),
            )
        }
    };
    let solution_loop = if spec.sign_folds.is_empty() {
        quote! {
            for (#lambda, v) in pairs.iter() {
                let mut u = [0.0f64; #nvars_l];
                if !#read_call {
                    continue;
                }
                #(#linear_reads)*
                let [#(#unknown_idents),*] = u;
                #elim_block
                #prefilter
                #polish_block
                #filter
                if !out.push(Solution { #(#field_inits)* }) {
                    break;
                }
            }
        }
    } else {
        // Each eigenvector gives a solution of the folded system and up to 2^k of the
        // problem's (both signs per fold).
        let nvars = plan.readout.len();
        let folds = spec.sign_folds.iter().map(|f| {
            let pivot = lit(f.pivot);
            let scaled = f.scaled.iter().filter(|&&j| j < nvars).map(|&j| lit(j));
            quote!((#pivot, &[#(#scaled),*]))
        });
        let (kl, ml) = (
            lit(spec.sign_folds.len()),
            lit(1usize << spec.sign_folds.len()),
        );
        let (unfold, fold_type) = (rt::unfold_signs(), rt::sign_fold());
        quote! {
            const SIGN_FOLDS: [#fold_type<'static>; #kl] = [#(#folds),*];
            'pairs: for (#lambda, v) in pairs.iter() {
                let mut u = [0.0f64; #nvars_l];
                if !#read_call {
                    continue;
                }
                #(#linear_reads)*
                let mut signs = [[0.0f64; #nvars_l]; #ml];
                let found = #unfold(&u, &SIGN_FOLDS, &mut signs);
                for &[#(#unknown_idents),*] in &signs[..found] {
                    #elim_block
                    #prefilter
                    #polish_block
                    #filter
                    if !out.push(Solution { #(#field_inits)* }) {
                        break 'pairs;
                    }
                }
            }
        }
    };
    Ok(quote! {
        #elim_setup
        #polish_consts
        const READOUT: [&[(usize, usize)]; #nvars_l] = [#(#readout_pairs),*];
        #solution_loop
    })
}

/// The read-out of the template variables from an eigenvector `v`.
struct Readout {
    /// The position of the basis's unit (the monomial 1, or the shift of a saturated
    /// template) in the basis.
    one_l: Literal,
    /// The number of template variables.
    nvars_l: Literal,
    /// The read-out pairs of each variable, the runtime's `read_unknowns` constant.
    pairs: Vec<TokenStream>,
    /// `u0, u1, ...`, the variables' names.
    unknown_idents: Vec<Ident>,
    /// The linear read-out of the variables outside the basis.
    linear_reads: Vec<TokenStream>,
}

impl Readout {
    fn new(plan: &Plan) -> Self {
        let t = &plan.spec.template;
        let cols = t.eliminated_size().1;
        let (pivots, nb) = (t.pivot_columns(), t.basis.len());
        let one_l = lit(plan.basis_one);
        // The unknown of a companion action is its eigenvalue (no read-out pairs).
        let companion = t.companion_unknown();
        let pairs: Vec<TokenStream> = plan
            .readout
            .iter()
            .map(|pairs| {
                let ps = pairs.iter().map(|&(j, k)| {
                    let (jl, kl) = (lit(j), lit(k));
                    quote!((#jl, #kl))
                });
                quote!(&[#(#ps),*])
            })
            .collect();
        let unknown_idents: Vec<Ident> = (0..plan.readout.len())
            .map(|k| format_ident!("u{}", k))
            .collect();
        // Unknowns outside the basis: `x_i = -T[s x_i, :] v / v[s]` from the reduced row of
        // their (reducible) column `s x_i` (`s` the basis's unit, usually 1), which starts
        // at `c * cols + pivots` as the action rows do.
        let read_linear = rt::read_linear();
        let linear_reads: Vec<TokenStream> = plan
            .readout
            .iter()
            .enumerate()
            .filter(|&(i, pairs)| pairs.is_empty() && Some(i) != companion)
            .map(|(i, _)| {
                let c = t
                    .eliminated_column(plan.column_of[&Monomial::var(t.nvars, i).mul(&t.unit())])
                    .expect("an unknown outside the basis is a reducible column");
                let (il, start, end) =
                    (lit(i), lit(c * cols + pivots), lit(c * cols + pivots + nb));
                quote! {
                    match #read_linear(v.as_slice(), #one_l, &m[#start..#end]) {
                        Some(x) => u[#il] = x,
                        None => continue,
                    }
                }
            })
            .collect();
        let linear_reads = companion
            .map(|x| {
                let xl = lit(x);
                quote!(u[#xl] = *lambda;)
            })
            .into_iter()
            .chain(linear_reads)
            .collect();
        Readout {
            nvars_l: lit(plan.readout.len()),
            one_l,
            pairs,
            unknown_idents,
            linear_reads,
        }
    }
}

/// The eliminated unknowns `n` of one solution, `(before the solution loop, in it)`: the
/// null vector of the elimination coefficient matrix at the template variables; when the
/// equations are inhomogeneous and the eliminated unknowns' coefficients are data only
/// (`A n + b(u) = 0`), `A` is factored once before the loop
/// (`mingen_runtime::LeastSquares`) and each solution solves with its `b`. Nothing without
/// an elimination.
fn eliminated_unknowns_tokens(
    plan: &Plan,
    coefficients: &Coefficients,
    style: VarStyle,
) -> (TokenStream, TokenStream) {
    let Some(el) = &plan.spec.elimination else {
        return (quote!(), quote!());
    };
    let mut outs = coefficients.program.outputs[coefficients.n_fill..].iter();
    let mut rows: Vec<Vec<TokenStream>> = Vec::new();
    for row in &coefficients.elim_terms {
        let mut entries = Vec::new();
        for support in row {
            let terms: Vec<(Monomial, Expr)> = support
                .iter()
                .map(|m| (m.clone(), outs.next().expect("one output per term").clone()))
                .collect();
            entries.push(entry_tokens(&terms, style));
        }
        rows.push(entries);
    }
    let nr = lit(el.coefficient_matrix.len());
    let k = el.eliminated.len();
    if el.inhomogeneous && has_data_only_columns(&el.coefficient_matrix, k) {
        let ls = rt::least_squares();
        let kl = lit(k);
        let a_rows = rows.iter().map(|r| {
            let a = &r[..k];
            quote!([#(#a),*])
        });
        let b = rows.iter().map(|r| &r[k]);
        return (
            quote! {
                if pairs.is_empty() {
                    return out;
                }
                let Some(elim_ls) = #ls::<#nr, #kl>::new(&[#(#a_rows),*]) else {
                    return out;
                };
            },
            quote! {
                let Some(n) = elim_ls.solve(&[#(#b),*]) else {
                    continue;
                };
            },
        );
    }
    let row_tokens: Vec<TokenStream> = rows.iter().map(|r| quote!([#(#r),*])).collect();
    let in_loop = if el.inhomogeneous {
        let (width, kl) = (lit(k + 1), lit(k));
        let (nv, dh) = (rt::null_vector(), rt::dehomogenize());
        quote! {
            let rows: [[f64; #width]; #nr] = [#(#row_tokens),*];
            let Some(h) = #nv(&rows) else {
                continue;
            };
            let mut n = [0.0; #kl];
            if !#dh(&h, &mut n) {
                continue;
            }
        }
    } else if k == 3 {
        let nv = rt::null_vector3();
        quote! {
            let rows: [[f64; 3]; #nr] = [#(#row_tokens),*];
            let Some(n) = #nv(&rows) else {
                continue;
            };
        }
    } else {
        let (width, nv) = (lit(k), rt::null_vector());
        quote! {
            let rows: [[f64; #width]; #nr] = [#(#row_tokens),*];
            let Some(n) = #nv(&rows) else {
                continue;
            };
        }
    };
    (quote!(), in_loop)
}

/// The value of the problem's unknown scalar `i` in one solution: a template variable
/// `u_k` or an eliminated unknown `n[j]`.
fn source_value(plan: &Plan, i: usize) -> TokenStream {
    match plan.source[i] {
        Ok(k) => {
            let u = format_ident!("u{}", k);
            quote!(#u)
        }
        Err(j) => {
            let j = lit(j);
            quote!(n[#j])
        }
    }
}

/// Newton polishing of one solution into `x`: its constants (before the solution loop)
/// and its code (in the loop); both empty without `option newton`.
fn polish_tokens(
    plan: &Plan,
    coefficients: &Coefficients,
    style: VarStyle,
) -> (TokenStream, TokenStream) {
    match &plan.spec.polish {
        Some(p) => super::polish::tokens(
            p,
            &coefficients.polish_terms,
            &coefficients.program.outputs[coefficients.n_fill + coefficients.n_elim..],
            (0..p.unknowns).map(|i| source_value(plan, i)).collect(),
            style,
        ),
        None => (quote!(), quote!()),
    }
}

/// The value of unknown scalar `i` (flat index) in the solution loop: polished, or read
/// out (or recovered, for an eliminated unknown).
fn solution_value(plan: &Plan, i: usize) -> TokenStream {
    if plan.spec.polish.is_some() {
        let i = lit(i);
        quote!(x[#i])
    } else {
        source_value(plan, i)
    }
}

/// The checks that drop a solution whose unknowns declared `positive` are not positive
/// (`NaN` included), in the solution loop: `(before polishing, before the push)`. With
/// polishing, a solution is checked before it (none is polished only to be dropped) and
/// again on its polished values; without, once.
fn positive_filter(plan: &Plan) -> (TokenStream, TokenStream) {
    let after = positive_checks(plan, solution_value);
    if plan.spec.polish.is_none() {
        return (quote!(), after);
    }
    (positive_checks(plan, source_value), after)
}

/// One check per `positive` unknown of the values `value` gives.
fn positive_checks(plan: &Plan, value: fn(&Plan, usize) -> TokenStream) -> TokenStream {
    let checks = plan.spec.layout.positive.iter().map(|&i| {
        let v = value(plan, i);
        quote! {
            if #v.is_nan() || #v <= 0.0 {
                continue;
            }
        }
    });
    quote!(#(#checks)*)
}

/// The fields of the `Solution` pushed for one solution: the read-out (or polished) values
/// of the declared unknowns.
fn solution_fields(plan: &Plan) -> Result<Vec<TokenStream>, EmitError> {
    let spec = plan.spec;
    let layout = &spec.layout;
    let mut field_inits = Vec::new();
    for (u, id) in layout
        .declared_unknowns()
        .zip(solution_field_idents(layout)?)
    {
        let val = |i: usize| solution_value(plan, i);
        match u.len {
            None => {
                let v = val(u.first_var);
                field_inits.push(quote!(#id: #v,));
            }
            Some(len) => {
                let vs: Vec<TokenStream> = (0..len).map(|e| val(u.first_var + e)).collect();
                field_inits.push(quote!(#id: [#(#vs),*],));
            }
        }
    }
    Ok(field_inits)
}
