//! Token helpers shared by the solver and struct emitters, so that neither depends on the
//! other.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// An unsuffixed integer literal (`3`, not `3usize`).
pub(super) fn lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

/// A `#[doc = " ..."]` attribute.
pub(super) fn doc(s: impl AsRef<str>) -> TokenStream {
    let s = format!(" {}", s.as_ref());
    quote!(#[doc = #s])
}
