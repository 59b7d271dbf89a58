//! The emitted `Data` and `Solution` structs: one field per problem symbol, the slot
//! order shared with `solve` and `mingen::instance`, and the slot/unknown conversions.

use super::runtime_api as rt;
use super::tokens::{doc, lit};
use super::EmitError;
use crate::lang::names::is_raw_keyword;
use crate::problem::{DataKind, DataSymbol, ProblemLayout};
use proc_macro2::{Ident, TokenStream};
use quote::quote;
use std::collections::BTreeSet;

/// The Rust field identifiers of one struct's symbols, in order: each name lowercased,
/// except names that lowercase to the same word (`x` and `X`), which keep their spelling
/// (the struct then allows non-snake-case fields), keywords as raw identifiers. The rule
/// depends on the set of names, not their order, and never maps two names to one field.
pub(super) fn field_idents<'a>(
    names: impl Iterator<Item = &'a str>,
    what: &str,
) -> Result<Vec<Ident>, EmitError> {
    let names: Vec<&str> = names.collect();
    let lower: Vec<String> = names.iter().map(|n| n.to_lowercase()).collect();
    let idents = names
        .iter()
        .zip(&lower)
        .map(|(name, l)| {
            let shared = lower.iter().filter(|m| *m == l).count() > 1;
            let field = if shared { name } else { l.as_str() };
            if is_raw_keyword(field) {
                return Ok(Ident::new_raw(field, proc_macro2::Span::call_site()));
            }
            syn::parse_str::<Ident>(field).map_err(|_| {
                EmitError::Unsupported(format!(
                    "{what} `{name}` does not give a Rust field name (`{field}` is not an identifier or is a keyword)"
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut seen = BTreeSet::new();
    for i in &idents {
        if !seen.insert(i.to_string()) {
            return Err(EmitError::Unsupported(format!(
                "two {what} symbols map to the field name `{i}`"
            )));
        }
    }
    Ok(idents)
}

/// The struct attribute and the documentation's naming note for `idents`: all lowercase
/// (the usual case), or some names kept as spelled.
fn naming(idents: &[Ident]) -> (TokenStream, &'static str) {
    if idents
        .iter()
        .all(|i| !i.to_string().chars().any(char::is_uppercase))
    {
        (quote!(), "lowercased")
    } else {
        (
            quote!(#[allow(non_snake_case)]),
            "lowercased, except names that differ only in case, which keep their spelling",
        )
    }
}

/// The element's Rust type (`scalar` → `T`, a vector kind → `[T; N]`, a matrix kind →
/// `[[T; C]; R]`) for an entry type `scalar` (`f64`) or its zero (`0.0`).
fn element_tokens(kind: DataKind, scalar: TokenStream) -> TokenStream {
    let vector = |n: usize| {
        let n = lit(n);
        quote!([#scalar; #n])
    };
    match kind {
        DataKind::Scalar => scalar,
        DataKind::Point => vector(2),
        DataKind::Vec3 => vector(3),
        DataKind::Vector(n) => vector(n),
        DataKind::Mat3 | DataKind::Rotation | DataKind::Matrix(..) => {
            let (r, c) = kind.shape();
            let (r, c) = (lit(r), lit(c));
            quote!([[#scalar; #c]; #r])
        }
    }
}

pub(super) fn element_type(kind: DataKind) -> TokenStream {
    element_tokens(kind, quote!(f64))
}

pub(super) fn element_zero(kind: DataKind) -> TokenStream {
    element_tokens(kind, quote!(0.0))
}

/// Whether the element's array type has a dimension above 32 (no `Default` to derive).
fn element_is_big(kind: DataKind) -> bool {
    let (r, c) = kind.shape();
    r > 32 || c > 32
}

pub(super) fn kind_doc(kind: DataKind) -> String {
    match kind {
        DataKind::Scalar => "a real number".into(),
        DataKind::Vec3 => "a 3-vector".into(),
        DataKind::Point => {
            "an image point in normalised coordinates `[x, y]`; the third coordinate is 1".into()
        }
        DataKind::Mat3 => "a 3x3 matrix, row-major (`[row][column]`)".into(),
        DataKind::Rotation => "a 3x3 rotation matrix, row-major (`[row][column]`)".into(),
        DataKind::Vector(n) => format!("a {n}-vector"),
        DataKind::Matrix(r, c) => format!("a {r}x{c} matrix, row-major (`[row][column]`)"),
    }
}

/// Access tokens for slot `k` of element `e` of a data symbol.
pub(super) fn slot_access(field: &Ident, ds: &DataSymbol, e: usize, k: usize) -> TokenStream {
    let elem = match ds.len {
        Some(_) => {
            let e = lit(e);
            quote!(data.#field[#e])
        }
        None => quote!(data.#field),
    };
    match ds.kind {
        DataKind::Scalar => elem,
        DataKind::Vec3 | DataKind::Point | DataKind::Vector(_) => {
            let k = lit(k);
            quote!(#elem[#k])
        }
        DataKind::Mat3 | DataKind::Rotation | DataKind::Matrix(..) => {
            let cols = ds.kind.shape().1;
            let (r, c) = (lit(k / cols), lit(k % cols));
            quote!(#elem[#r][#c])
        }
    }
}

/// The `Data` struct's field identifiers, in the layout's data order.
pub(super) fn data_field_idents(layout: &ProblemLayout) -> Result<Vec<Ident>, EmitError> {
    field_idents(layout.data.iter().map(|d| d.name.as_str()), "data")
}

/// The `Solution` struct's field identifiers, in declaration order.
pub(super) fn solution_field_idents(layout: &ProblemLayout) -> Result<Vec<Ident>, EmitError> {
    field_idents(
        layout.declared_unknowns().map(|u| u.name.as_str()),
        "unknown",
    )
}

pub(super) fn emit_data(layout: &ProblemLayout) -> Result<TokenStream, EmitError> {
    let idents = data_field_idents(layout)?;
    let mut fields = Vec::new();
    let mut zeros = Vec::new();
    let mut big = false;
    for (d, id) in layout.data.iter().zip(&idents) {
        let el = element_type(d.kind);
        let z = element_zero(d.kind);
        big |= element_is_big(d.kind);
        let (ty, zero, what) = match d.len {
            Some(n) => {
                big |= n > 32;
                let nl = lit(n);
                (
                    quote!([#el; #nl]),
                    quote!([#z; #nl]),
                    format!(
                        "`{}[{}]: {}` — {} elements, each {}.",
                        d.name,
                        n,
                        d.kind.keyword(),
                        n,
                        kind_doc(d.kind)
                    ),
                )
            }
            None => (
                el,
                z,
                format!("`{}: {}` — {}.", d.name, d.kind.keyword(), kind_doc(d.kind)),
            ),
        };
        let dc = doc(what);
        fields.push(quote!(#dc pub #id: #ty,));
        zeros.push(quote!(#id: #zero,));
    }
    let (derive, default_impl) = if big {
        (
            quote!(#[derive(Clone, Copy, Debug, PartialEq)]),
            quote! {
                impl Default for Data {
                    fn default() -> Self {
                        Data { #(#zeros)* }
                    }
                }
            },
        )
    } else {
        (
            quote!(#[derive(Clone, Copy, Debug, PartialEq, Default)]),
            quote!(),
        )
    };
    let (allow, note) = naming(&idents);
    let d = doc(format!(
        "Input data of `{}`: one field per data symbol of the problem file ({note}).",
        layout.name
    ));
    let slot_impl = emit_data_slots(layout, &idents)?;
    Ok(quote! {
        #d
        #derive
        #allow
        pub struct Data { #(#fields)* }
        #default_impl
        #slot_impl
    })
}

/// `impl Data { SLOTS, from_slots, to_slots }`: the data as a flat array in slot order
/// (the order `solve` flattens it in and `mingen::instance::random_data_f64` draws it in).
fn emit_data_slots(layout: &ProblemLayout, idents: &[Ident]) -> Result<TokenStream, EmitError> {
    let n_slots = layout.data_slot_count();
    let mut reads: Vec<Option<TokenStream>> = vec![None; n_slots];
    let mut inits = Vec::new();
    for (ds, field) in layout.data.iter().zip(idents) {
        let per = ds.kind.slots();
        let mut elements = Vec::new();
        for e in 0..ds.len.unwrap_or(1) {
            let mut slot = |k: usize| -> Result<TokenStream, EmitError> {
                let s = ds.first_slot + e * per + k;
                match reads.get_mut(s) {
                    Some(x @ None) => *x = Some(slot_access(field, ds, e, k)),
                    _ => {
                        return Err(EmitError::Invalid(format!(
                            "data slot {s} of `{}` is out of range or used twice",
                            ds.name
                        )))
                    }
                }
                let s = lit(s);
                Ok(quote!(slots[#s]))
            };
            elements.push(match ds.kind {
                DataKind::Scalar => slot(0)?,
                DataKind::Vec3 | DataKind::Point | DataKind::Vector(_) => {
                    let xs = (0..per).map(&mut slot).collect::<Result<Vec<_>, _>>()?;
                    quote!([#(#xs),*])
                }
                DataKind::Mat3 | DataKind::Rotation | DataKind::Matrix(..) => {
                    let (nr, nc) = ds.kind.shape();
                    let mut rows = Vec::new();
                    for r in 0..nr {
                        let xs = (nc * r..nc * r + nc)
                            .map(&mut slot)
                            .collect::<Result<Vec<_>, _>>()?;
                        rows.push(quote!([#(#xs),*]));
                    }
                    quote!([#(#rows),*])
                }
            });
        }
        let value = match ds.len {
            Some(_) => quote!([#(#elements),*]),
            None => elements.pop().expect("one element"),
        };
        inits.push(quote!(#field: #value,));
    }
    let reads = reads
        .into_iter()
        .enumerate()
        .map(|(s, x)| {
            x.ok_or_else(|| EmitError::Invalid(format!("data slot {s} belongs to no symbol")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let n = lit(n_slots);
    let names = layout.data_slot_names();
    // In code spans: `x1[0]` would otherwise be read as an intra-doc link.
    let quoted = |ns: &[String]| {
        ns.iter()
            .map(|n| format!("`{n}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let order = if names.len() <= 12 {
        quoted(&names)
    } else {
        format!(
            "{}, ..., {}",
            quoted(&names[..6]),
            quoted(&names[names.len() - 3..])
        )
    };
    let d_slots = doc(
        "Number of scalar data slots: the length of the flat form of \
         [`from_slots`](Self::from_slots) / [`to_slots`](Self::to_slots).",
    );
    let d_from = [
        doc("The data from its flat form, in the problem's slot order: symbols in declaration order, arrays element by element, a point as `x, y`, a matrix row-major."),
        doc(""),
        doc(format!("Slot order: {order}.")),
    ];
    let d_to = doc("The flat form of the data (inverse of [`from_slots`](Self::from_slots)).");
    let flat_impl = flat_values_impl(&quote!(Data), &n, &quote!(from_slots), &quote!(to_slots));
    Ok(quote! {
        #flat_impl
        impl Data {
            #d_slots
            pub const SLOTS: usize = #n;
            #(#d_from)*
            #[must_use]
            pub fn from_slots(slots: &[f64; #n]) -> Data {
                Data { #(#inits)* }
            }
            #d_to
            #[must_use]
            pub fn to_slots(&self) -> [f64; #n] {
                let data = self;
                [#(#reads),*]
            }
        }
    })
}

pub(super) fn emit_solution(layout: &ProblemLayout) -> Result<TokenStream, EmitError> {
    let idents = solution_field_idents(layout)?;
    let mut fields = Vec::new();
    let mut zeros = Vec::new();
    let mut big = false;
    for (u, id) in layout.declared_unknowns().zip(&idents) {
        let (ty, zero, what) = match u.len {
            Some(n) => {
                big |= n > 32;
                let nl = lit(n);
                (
                    quote!([f64; #nl]),
                    quote!([0.0; #nl]),
                    format!(
                        "Unknown `{}[{}]` (`{}1` .. `{}{}`).",
                        u.name, n, u.name, u.name, n
                    ),
                )
            }
            None => (quote!(f64), quote!(0.0), format!("Unknown `{}`.", u.name)),
        };
        let dc = doc(what);
        fields.push(quote!(#dc pub #id: #ty,));
        zeros.push(quote!(#id: #zero,));
    }
    let (derive, default_impl) = if big {
        (
            quote!(#[derive(Clone, Copy, Debug, PartialEq)]),
            quote! {
                impl Default for Solution {
                    fn default() -> Self {
                        Solution { #(#zeros)* }
                    }
                }
            },
        )
    } else {
        (
            quote!(#[derive(Clone, Copy, Debug, PartialEq, Default)]),
            quote!(),
        )
    };
    let (allow, note) = naming(&idents);
    let d = doc(format!(
        "One real solution of `{}`: one field per unknown symbol ({note}).",
        layout.name
    ));
    let unknowns_impl = emit_solution_unknowns(layout, &idents);
    Ok(quote! {
        #d
        #derive
        #allow
        pub struct Solution { #(#fields)* }
        #default_impl
        #unknowns_impl
    })
}

/// `impl Solution { UNKNOWNS, to_unknowns }`: the solution as a flat array in the problem's
/// unknown order (`ProblemLayout::unknown_names`, eliminated unknowns included).
fn emit_solution_unknowns(layout: &ProblemLayout, idents: &[Ident]) -> TokenStream {
    let mut values = Vec::new();
    let mut inits = Vec::new();
    for (u, id) in layout.declared_unknowns().zip(idents) {
        match u.len {
            None => {
                let k = lit(values.len());
                values.push(quote!(self.#id));
                inits.push(quote!(#id: unknowns[#k],));
            }
            Some(n) => {
                let ks: Vec<_> = (values.len()..values.len() + n).map(lit).collect();
                values.extend((0..n).map(|e| {
                    let e = lit(e);
                    quote!(self.#id[#e])
                }));
                inits.push(quote!(#id: [#(unknowns[#ks]),*],));
            }
        }
    }
    let n = lit(values.len());
    let d_n = doc("Number of scalar unknowns (eliminated ones included).");
    let d_to = doc(format!(
        "The solution as a flat array in the problem's unknown order: {}.",
        layout.unknown_names().join(", ")
    ));
    let d_from =
        doc("The solution from its flat form (inverse of [`to_unknowns`](Self::to_unknowns)).");
    let flat_impl = flat_values_impl(
        &quote!(Solution),
        &n,
        &quote!(from_unknowns),
        &quote!(to_unknowns),
    );
    quote! {
        impl Solution {
            #d_n
            pub const UNKNOWNS: usize = #n;
            #d_to
            #[must_use]
            pub fn to_unknowns(&self) -> [f64; #n] {
                [#(#values),*]
            }
            #d_from
            #[must_use]
            pub fn from_unknowns(unknowns: &[f64; #n]) -> Solution {
                Solution { #(#inits)* }
            }
        }
        #flat_impl
    }
}

/// `impl FlatValues for TY` through its inherent array conversions `from(&[f64; N]) -> TY`
/// and `to(&self) -> [f64; N]`.
fn flat_values_impl(
    ty: &TokenStream,
    n: &proc_macro2::Literal,
    from: &TokenStream,
    to: &TokenStream,
) -> TokenStream {
    let flat = rt::flat_values();
    quote! {
        impl #flat for #ty {
            const LEN: usize = #n;
            fn from_flat(values: &[f64]) -> Option<Self> {
                // Fully qualified: `TryFrom` is not in the 2018 edition's prelude, and the
                // module may be included in a crate of any edition.
                let values = <&[f64; #n] as ::core::convert::TryFrom<&[f64]>>::try_from(values).ok()?;
                Some(#ty::#from(values))
            }
            fn write_flat(&self, out: &mut [f64]) -> bool {
                match out.get_mut(..#n) {
                    Some(out) => {
                        out.copy_from_slice(&self.#to());
                        true
                    }
                    None => false,
                }
            }
        }
    }
}
