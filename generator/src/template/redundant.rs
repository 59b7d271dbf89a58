//! Redundant solving bases (Martyushev, Bhayani and Pajdla 2023): a basis B with more
//! monomials than solutions.
//!
//! The reducibility test of `candidates` never asks B to be independent modulo the ideal:
//! every reducible monomial r needs a row `r + sum_k c_k b_k` in the rows' span, zero on
//! the excess columns, and then, for every solution s, the vector `v = (b(s))` still
//! satisfies `M v = action(s) v` (module documentation of `crate::template`). When B is
//! a quotient basis the rows must also prove every relation among its monomials; a larger
//! B needs no such proof, and its template can be smaller. The price: M has |B|
//! eigenvalues, `|B| - count` of them spurious, which the solver tells apart by the
//! residual of the equations at the read-out solution.
//!
//! [`grow_basis`] moves columns into B one at a time, greedily: a column joins B when
//! shrinking the rows with the larger B ([`shrink_quick`]) gives the smallest template,
//! and the growth stops when no column makes the template smaller or B has
//! [`max_redundant_basis`] monomials.

use super::build::{assemble, BuiltTemplate};
use super::candidates::{Blocks, Candidate};
use super::fold::{foldable_rows, EquationConstants};
use super::linalg::{charpoly_within, derivative, poly_gcd};
use super::shrink::shrink_quick;
use super::validate::template_action_matrix;
use super::{Action, EliminationTemplate, TemplateOptions};
use crate::algebra::{Fp, Monomial, MonomialOrder, Poly};
use crate::budget::Deadline;
use std::collections::BTreeSet;

/// The most monomials a redundant basis may have for `count` solutions: half again as
/// many (the eigenvalue problem grows with the cube of |B|, the template only shrinks).
pub fn max_redundant_basis(count: usize) -> usize {
    count + count.div_ceil(2)
}

/// Rows times columns of the rows with the blocks' basis.
fn area(blocks: &Blocks, rows: &[Candidate]) -> usize {
    rows.len() * (blocks.excess_of(rows.iter()).len() + blocks.reducible.len() + blocks.basis.len())
}

/// The columns that may join B: monomials of the rows, outside B, whose products with the
/// action are all columns (so that `action * m` can be reduced or is in B).
fn permissible(blocks: &Blocks, rows: &[Candidate], action: &Action) -> Vec<Monomial> {
    let cols: BTreeSet<&Monomial> = rows
        .iter()
        .flat_map(|c| c.terms.iter().map(|(m, _)| m))
        .collect();
    cols.iter()
        .filter(|m| !blocks.basis_set.contains(**m))
        .filter(|m| action.products(m).all(|(p, _)| cols.contains(&p)))
        .map(|m| (*m).clone())
        .collect()
}

/// Grows the basis of a reducing row set greedily (module documentation); returns the
/// blocks and rows of the smallest template found, or `None` when no larger basis gives a
/// smaller template (or the budget runs out before one does).
pub(crate) fn grow_basis<const P: u32>(
    blocks: &Blocks,
    rows: &[Candidate],
    action: &Action,
    visible: usize,
    count: usize,
    deadline: Option<&Deadline>,
) -> Option<(Blocks, Vec<Candidate>)> {
    let mut best: Option<(Blocks, Vec<Candidate>)> = None;
    let mut current_area = area(blocks, rows);
    loop {
        let (cur_blocks, cur_rows) = match &best {
            Some((b, r)) => (b, r.as_slice()),
            None => (blocks, rows),
        };
        if cur_blocks.basis.len() >= max_redundant_basis(count) {
            break;
        }
        let mut step: Option<(usize, Blocks, Vec<Candidate>)> = None;
        for m in permissible(cur_blocks, cur_rows, action) {
            if deadline.is_some_and(|d| d.check_time().is_err()) {
                return best;
            }
            let mut basis = cur_blocks.basis.clone();
            basis.push(m);
            let grown = Blocks::new(&basis, action, visible);
            let refs: Vec<&Candidate> = cur_rows.iter().collect();
            if !grown.reducible_by::<P>(&refs) {
                continue;
            }
            let kept = shrink_quick::<P>(&grown, cur_rows.to_vec());
            let a = area(&grown, &kept);
            if a < current_area && step.as_ref().map_or(true, |s| a < s.0) {
                step = Some((a, grown, kept));
            }
        }
        let Some((a, grown, kept)) = step else {
            break;
        };
        current_area = a;
        best = Some((grown, kept));
    }
    best
}

/// The chosen template with a redundant basis ([`super::redundant`]) when that is
/// smaller; otherwise the template itself.
pub(super) fn with_redundant_basis<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Option<&[EquationConstants]>,
    best: BuiltTemplate,
    visible: usize,
    count: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> BuiltTemplate {
    if !opts.redundant_bases {
        return best;
    }
    let t = &best.template;
    let rows: Vec<Candidate> = t
        .rows
        .iter()
        .map(|r| {
            let f = &eqs[r.equation];
            let degree = f.degree().unwrap_or(0) + r.multiplier.degree();
            Candidate::multiple(r.equation, f, r.multiplier.clone(), degree)
        })
        .collect();
    let blocks = Blocks::new(&t.basis, &t.action, visible);
    let Some((grown, kept)) =
        grow_basis::<P>(&blocks, &rows, &t.action, visible, count, Some(deadline))
    else {
        return best;
    };
    // The basis in descending grevlex, as every other template's.
    let mut basis = grown.basis;
    basis.sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
    let grown = Blocks::new(&basis, &t.action, visible);
    let mut template = assemble::<P>(t.nvars, &grown, &kept, &t.action, t.n_hidden);
    let nb = template.basis.len();
    template.spurious_eigenvalues = nb - count;
    if template.check_emittable(&opts.var_names).is_err() {
        return best;
    }
    // A spurious eigenvalue equal to a solution's would make the eigenvectors of both
    // undefined: where the quotient's eigenvalues are distinct, no root of its
    // characteristic polynomial may be a repeated root of the template's (spurious ones
    // may repeat among themselves).
    if best.distinct_eigenvalues {
        let charpoly = |t: &EliminationTemplate| {
            template_action_matrix::<P>(t, eqs, &opts.var_names)
                .ok()
                .and_then(|m| charpoly_within::<P>(&m, Some(deadline)).ok())
        };
        let separate = match (charpoly(&template), charpoly(&best.template)) {
            (Some(grown), Some(quotient)) => {
                let repeated = poly_gcd::<P>(&grown, &derivative::<P>(&grown));
                poly_gcd::<P>(&repeated, &quotient).len() == 1
            }
            _ => false,
        };
        if !separate {
            return best;
        }
    }
    let mut history = best.history.clone();
    let (r, c) = template.size();
    history.push((
        format!("redundant basis: {nb} monomials for {count} solutions"),
        r,
        c,
    ));
    let foldable_rows = constants.map_or(0, |c| foldable_rows(&template, c));
    let grown = BuiltTemplate {
        template,
        history,
        basis_choice: format!("{}, redundant basis", best.basis_choice),
        foldable_rows,
        quotient_basis: Some(Box::new(best.clone())),
        ..best.clone()
    };
    if grown.folded_area() < best.folded_area() {
        grown
    } else {
        best
    }
}
