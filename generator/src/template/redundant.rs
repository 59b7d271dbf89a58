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
//! Two constructions, both from the chosen template's rows. [`grow_basis`] moves columns
//! into B one at a time, greedily: a column joins B when shrinking the rows with the
//! larger B ([`shrink_quick`]) gives the smallest template, and the growth stops when no
//! column makes the template smaller or B has [`max_redundant_basis`] monomials.
//! [`reduce_permissible`] is Martyushev et al.'s: B is the whole permissible set of a
//! pool (the rows closed under their columns, [`closed_rows`]), and monomials are excluded
//! from the pool while the template shrinks. [`with_redundant_basis`] keeps every result
//! smaller than the quotient template, smallest first, for the plan to measure.

use super::build::{assemble, BuiltTemplate};
use super::candidates::{Blocks, Candidate};
use super::deflate::deflate;
use super::fold::{foldable_rows, EquationConstants};
use super::linalg::{charpoly_within, derivative, poly_gcd};
use super::pools::pools;
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

/// How the searches size a template of rows with the blocks' basis: its area, or its area
/// after the fold where the equations have constants to fold (`with_redundant_basis`).
pub(crate) type Measure<'a> = dyn Fn(&Blocks, &[Candidate]) -> usize + 'a;

/// Rows times columns of the rows with the blocks' basis.
fn area(blocks: &Blocks, rows: &[Candidate]) -> usize {
    rows.len() * (blocks.excess_of(rows.iter()).len() + blocks.reducible.len() + blocks.basis.len())
}

/// The monomials of the rows: the template's columns.
fn columns(rows: &[Candidate]) -> BTreeSet<&Monomial> {
    rows.iter()
        .flat_map(|c| c.terms.iter().map(|(m, _)| m))
        .collect()
}

/// The columns that may join B: monomials of the rows, outside B, whose products with the
/// action are all columns (so that `action * m` can be reduced or is in B).
fn permissible(blocks: &Blocks, rows: &[Candidate], action: &Action) -> Vec<Monomial> {
    permissible_columns(rows, action)
        .into_iter()
        .filter(|m| !blocks.basis_set.contains(m))
        .collect()
}

/// Every monomial of the rows whose products with the action are all monomials of the
/// rows, in the monomials' own order.
fn permissible_columns(rows: &[Candidate], action: &Action) -> Vec<Monomial> {
    let cols = columns(rows);
    cols.iter()
        .filter(|m| action.applies_to(m) && action.products(m).all(|(p, _)| cols.contains(&p)))
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
    (visible, count): (usize, usize),
    measure: &Measure<'_>,
    deadline: Option<&Deadline>,
) -> Option<(Blocks, Vec<Candidate>)> {
    let mut best: Option<(Blocks, Vec<Candidate>)> = None;
    let mut current_area = measure(blocks, rows);
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
            let a = measure(&grown, &kept);
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

/// The largest redundant solving set of a row set (Martyushev, Bhayani and Pajdla's
/// permissible monomials): every monomial of the rows whose products with the action are
/// all monomials of the rows.
fn permissible_set(rows: &[Candidate], action: &Action) -> Vec<Monomial> {
    let mut basis = permissible_columns(rows, action);
    basis.sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
    basis
}

/// The rows with their permissible set as the basis, shrunk, and then with the shrunk
/// rows' own (smaller) permissible set while they reduce it; `None` when the rows do not
/// reduce their permissible set.
fn settle_permissible<const P: u32>(
    rows: Vec<Candidate>,
    action: &Action,
    visible: usize,
) -> Option<(Blocks, Vec<Candidate>)> {
    let basis = permissible_set(&rows, action);
    if basis.is_empty() {
        return None;
    }
    let blocks = Blocks::new(&basis, action, visible);
    let refs: Vec<&Candidate> = rows.iter().collect();
    if !blocks.reducible_by::<P>(&refs) {
        return None;
    }
    let mut kept = shrink_quick::<P>(&blocks, rows);
    let mut blocks = blocks;
    // The shrunk rows' own permissible set is smaller; it is the basis when they reduce it.
    loop {
        let basis = permissible_set(&kept, action);
        if basis.len() >= blocks.basis.len() || basis.is_empty() {
            break;
        }
        let smaller = Blocks::new(&basis, action, visible);
        let refs: Vec<&Candidate> = kept.iter().collect();
        if !smaller.reducible_by::<P>(&refs) {
            break;
        }
        kept = shrink_quick::<P>(&smaller, kept);
        blocks = smaller;
    }
    Some((blocks, kept))
}

/// Every multiple `m f` of the equations whose monomials are all monomials of `rows`:
/// more rows over the same columns, so more ways to reduce a permissible set.
fn closed_rows<const P: u32>(eqs: &[Poly<Fp<P>>], rows: &[Candidate]) -> Vec<Candidate> {
    let cols = columns(rows);
    let mut seen: BTreeSet<(usize, Monomial)> = BTreeSet::new();
    let mut out = Vec::new();
    for c in rows {
        seen.insert((c.row.equation, c.row.multiplier.clone()));
        out.push(c.clone());
    }
    for (e, f) in eqs.iter().enumerate() {
        let Some((lead, _)) = f.terms().next() else {
            continue;
        };
        for t in &cols {
            let Some(m) = lead.divide_into(t) else {
                continue;
            };
            if seen.contains(&(e, m.clone())) {
                continue;
            }
            if f.terms().all(|(s, _)| cols.contains(&s.mul(&m))) {
                let degree = f.degree().unwrap_or(0) + m.degree();
                seen.insert((e, m.clone()));
                out.push(Candidate::multiple(e, f, m, degree));
            }
        }
    }
    out
}

/// The bound on the summed `rows x columns` of the row sets [`reduce_permissible`] tries
/// from a chosen template's rows.
const MAX_PERMISSIBLE_WORK: u64 = 1 << 27;

/// The same bound for all the pools and actions of [`from_pools`] together (of both
/// equation sets, the equations as given and row-reduced).
pub(super) const MAX_POOL_WORK: u64 = 1 << 26;

/// Martyushev, Bhayani and Pajdla's reduction of a redundant template: the basis is the
/// permissible set of the rows ([`permissible_set`]); monomials of the template are
/// excluded from the pool one at a time (every row containing one leaves), highest first,
/// and a move is kept when the pool still reduces its permissible set and the template
/// shrinks (or, while the set has more than `max_basis` monomials, the set does). Returns
/// the basis's blocks and the template's rows, `None` when the pool does not reduce its
/// permissible set or the result has more than `max_basis` monomials.
pub(crate) fn reduce_permissible<const P: u32>(
    pool: &[Candidate],
    action: &Action,
    (visible, max_basis): (usize, usize),
    measure: &Measure<'_>,
    (work, deadline): (&mut u64, Option<&Deadline>),
) -> Option<(Blocks, Vec<Candidate>)> {
    let mut pool = pool.to_vec();
    let mut best = settle_permissible::<P>(pool.clone(), action, visible)?;
    // Monomials above the cap first, then the area: a basis over the cap is no result.
    let key = |b: &(Blocks, Vec<Candidate>)| {
        (
            b.0.basis.len().saturating_sub(max_basis),
            measure(&b.0, &b.1),
        )
    };
    let mut best_key = key(&best);
    let mut tried: BTreeSet<Monomial> = BTreeSet::new();
    let mut pool_columns = columns(&pool).len();
    let within = |b: (Blocks, Vec<Candidate>)| (b.0.basis.len() <= max_basis).then_some(b);
    loop {
        let mut improved = false;
        let mut order: Vec<Monomial> = best
            .1
            .iter()
            .flat_map(|c| c.terms.iter().map(|(m, _)| m.clone()))
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        order.sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
        for m in order {
            if tried.contains(&m) {
                continue;
            }
            // Bounded by work (the summed size of the pools eliminated), so that the result
            // does not depend on the machine's speed; the deadline only guards the budget.
            let cost = pool.len() as u64 * pool_columns as u64;
            if cost > *work || deadline.is_some_and(|d| d.check_time().is_err()) {
                return within(best);
            }
            *work -= cost;
            tried.insert(m.clone());
            let smaller: Vec<Candidate> = pool
                .iter()
                .filter(|c| !c.terms.iter().any(|(t, _)| *t == m))
                .cloned()
                .collect();
            if smaller.is_empty() || smaller.len() == pool.len() {
                continue;
            }
            if let Some(s) = settle_permissible::<P>(smaller.clone(), action, visible) {
                let k = key(&s);
                if k < best_key {
                    best_key = k;
                    best = s;
                    pool = smaller;
                    pool_columns = columns(&pool).len();
                    improved = true;
                }
            }
        }
        if !improved {
            return within(best);
        }
    }
}

/// The chosen template with a redundant basis ([`super::redundant`]) when that is
/// smaller; otherwise the template itself. Two constructions compete: the quotient basis
/// grown column by column ([`grow_basis`]) and the permissible set of the rows reduced
/// greedily ([`reduce_permissible`]); the smallest becomes the template, the others, in
/// increasing size, its [`BuiltTemplate::redundant_alternatives`], which the plan measures
/// in turn when it drops the smaller one.
pub(super) fn with_redundant_basis<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Option<&[EquationConstants]>,
    best: BuiltTemplate,
    visible: usize,
    count: usize,
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> BuiltTemplate {
    // A shifted template's rows are not its products' monomials, which the constructions
    // below grow from.
    if !opts.redundant_bases || best.template.shift.is_some() {
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
    let measure = folded_measure::<P>(constants, t, &t.action);
    let dims = (visible, count);
    let grown = grow_basis::<P>(&blocks, &rows, &t.action, dims, &measure, Some(deadline));
    let closed = closed_rows::<P>(eqs, &rows);
    let dims = (visible, max_redundant_basis(count));
    let mut work = MAX_PERMISSIBLE_WORK;
    let bounds = (&mut work, Some(deadline));
    let reduced = reduce_permissible::<P>(&closed, &t.action, dims, &measure, bounds);
    // Where the quotient's eigenvalues are distinct, no spurious one may meet them.
    let quotient = best
        .distinct_eigenvalues
        .then(|| template_charpoly::<P>(t, eqs, opts, deadline))
        .flatten();
    let action = t.action.clone();
    let which = (&action, quotient.as_deref());
    let mut built: Vec<BuiltTemplate> = grown
        .into_iter()
        .chain(reduced)
        .flat_map(|(b, kept)| {
            let parts = (b, kept.as_slice(), visible, count);
            redundant_templates::<P>(eqs, constants, &best, which, parts, opts, deadline)
        })
        .filter(|g| g.folded_area() < best.folded_area())
        .collect();
    // The measure borrows `best`'s template, which moves below.
    drop(measure);
    built.sort_by_key(BuiltTemplate::folded_area);
    built.dedup_by_key(|g| g.template.eliminated_size());
    if built.is_empty() {
        return best;
    }
    let mut chosen = built.remove(0);
    chosen.quotient_basis = Some(Box::new(best));
    chosen.redundant_alternatives = built;
    chosen
}

/// The templates of `best`'s action on a redundant basis `blocks` with rows `kept`: deflated
/// as far as the rows allow ([`deflate`]: fewer spurious eigenvalues, none when the basis
/// reaches the solution count), then as grown; none that cannot be emitted or whose spurious
/// eigenvalue may meet a solution's.
fn redundant_templates<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Option<&[EquationConstants]>,
    best: &BuiltTemplate,
    (action, quotient): (&Action, Option<&[u32]>),
    (blocks, kept, visible, count): (Blocks, &[Candidate], usize, usize),
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> Vec<BuiltTemplate> {
    let t = &best.template;
    // The basis in descending grevlex, as every other template's.
    let mut basis = blocks.basis;
    basis.sort_by(|x, y| MonomialOrder::Grevlex.cmp(y, x));
    let grown = Blocks::new(&basis, action, visible);
    let closed = closed_rows::<P>(eqs, kept);
    let deflated = deflate::<P>(&grown, &closed, action, (visible, count), Some(deadline));
    // Without distinct eigenvalues the quotient's characteristic polynomial still tells
    // whether a deflated basis spans the quotient.
    let own = match quotient {
        None if deflated.is_some() && t.action == *action && t.flipped.is_empty() => {
            template_charpoly::<P>(t, eqs, opts, deadline)
        }
        _ => None,
    };
    let reference = quotient.or(own.as_deref());
    let check = |b: &Blocks, rows: &[Candidate]| {
        let mut template = assemble::<P>(t.nvars, b, rows, action, t.n_hidden);
        template.spurious_eigenvalues = template.basis.len() - count;
        template.check_emittable(&opts.var_names).ok()?;
        if template.spurious_eigenvalues == 0 {
            // A basis of the solution count must span the quotient: the same eigenvalues.
            let charpoly = template_charpoly::<P>(&template, eqs, opts, deadline);
            return (charpoly.is_some() && charpoly.as_deref() == reference).then_some(template);
        }
        // A spurious eigenvalue equal to a solution's would make the eigenvectors of both
        // undefined: where the quotient's eigenvalues are distinct, no root of its
        // characteristic polynomial may be a repeated root of the template's (spurious
        // ones may repeat among themselves).
        if let Some(quotient) = quotient {
            let grown = template_charpoly::<P>(&template, eqs, opts, deadline)?;
            let repeated = poly_gcd::<P>(&grown, &derivative::<P>(&grown));
            if poly_gcd::<P>(&repeated, quotient).len() != 1 {
                return None;
            }
        }
        Some(template)
    };
    let templates = deflated
        .and_then(|(b, rows)| check(&b, &rows))
        .into_iter()
        .chain(check(&grown, kept));
    let full = grown.basis.len();
    templates
        .map(|template| {
            built_redundant(constants, best, template, (count, full), quotient.is_some())
        })
        .collect()
}

/// `best` with a redundant (possibly deflated) template of `full` monomials for `count`
/// solutions, its history extended.
fn built_redundant(
    constants: Option<&[EquationConstants]>,
    best: &BuiltTemplate,
    template: EliminationTemplate,
    (count, full): (usize, usize),
    separated: bool,
) -> BuiltTemplate {
    let nb = template.basis.len();
    let mut history = best.history.clone();
    let (r, c) = template.size();
    history.push((
        format!("redundant basis: {full} monomials for {count} solutions"),
        r,
        c,
    ));
    if nb < full {
        history.push((
            format!(
                "deflated to {nb} monomials, {} relations flipped",
                template.flipped.len()
            ),
            r,
            c,
        ));
    }
    let foldable_rows = constants.map_or(0, |c| foldable_rows(&template, c));
    let basis_choice = if template.flipped.is_empty() {
        format!("{}, redundant basis", best.basis_choice)
    } else {
        format!(
            "{}, redundant basis deflated to a pencil",
            best.basis_choice
        )
    };
    BuiltTemplate {
        template,
        history,
        basis_choice,
        distinct_eigenvalues: best.distinct_eigenvalues || separated,
        foldable_rows,
        quotient_basis: None,
        redundant_alternatives: Vec::new(),
        ..best.clone()
    }
}

/// How the constructions compare templates of `action` on the rows of `t`'s problem: by
/// their area after the fold (step 5 of the search), as the search compares its own.
fn folded_measure<'a, const P: u32>(
    constants: Option<&'a [EquationConstants]>,
    t: &'a EliminationTemplate,
    action: &'a Action,
) -> impl Fn(&Blocks, &[Candidate]) -> usize + 'a {
    move |b: &Blocks, r: &[Candidate]| match constants {
        None => area(b, r),
        Some(cs) => {
            let candidate = assemble::<P>(t.nvars, b, r, action, t.n_hidden);
            let (rows, cols) = candidate.eliminated_size();
            let k = foldable_rows(&candidate, cs).min(rows).min(cols);
            (rows - k) * (cols - k)
        }
    }
}

/// The characteristic polynomial, on the build instance, of a template's action matrix;
/// `None` when the template does not reduce there or the budget runs out.
fn template_charpoly<const P: u32>(
    t: &EliminationTemplate,
    eqs: &[Poly<Fp<P>>],
    opts: &TemplateOptions,
    deadline: &Deadline,
) -> Option<Vec<u32>> {
    template_action_matrix::<P>(t, eqs, &opts.var_names)
        .ok()
        .and_then(|m| charpoly_within::<P>(&m, Some(deadline)).ok())
}

/// How many times the quotient template's rows a pool of [`from_pools`] may have: the
/// redundant templates sought are smaller than the quotient's, and Martyushev et al.'s
/// greedy exclusion starts near their size.
const POOL_ROWS_FACTOR: u64 = 2;

/// The fewest rows a pool of [`from_pools`] may always have, however small the quotient
/// template.
const MIN_POOL_ROWS: u64 = 64;

/// Redundant templates built from the candidate pools of basis selection
/// ([`super::pools::pools`]: boxes of the unknowns' degrees, the Newton polytope, total
/// degrees), for every action of `actions`, with no quotient template of that action to
/// start from: each pool's permissible set reduced greedily ([`reduce_permissible`]), as
/// Martyushev, Bhayani and Pajdla reduce their shift sets. The quotient template of one
/// action may be far larger than the smallest redundant one of another (the Laurent
/// action `1/x` of a system whose quotient templates all act by an unknown). `actions`
/// are those whose characteristic polynomial on the quotient (given beside each, on the
/// build instance) has distinct roots; a template qualifies when no spurious eigenvalue
/// meets them. Every template is smaller than `quotient`, which it names as its
/// [`BuiltTemplate::quotient_basis`]; smallest first. The pools' eliminations draw on
/// `work` (summed rows x columns), so that the result does not depend on the machine.
pub(super) fn from_pools<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    constants: Option<&[EquationConstants]>,
    quotient: &BuiltTemplate,
    actions: &[(Action, Vec<u32>)],
    (visible, count): (usize, usize),
    opts: &TemplateOptions,
    (work, deadline): (&mut u64, &Deadline),
) -> Vec<BuiltTemplate> {
    if !opts.redundant_bases || quotient.template.shift.is_some() {
        return Vec::new();
    }
    let t = &quotient.template;
    let maxeq = eqs.iter().filter_map(|f| f.degree()).max().unwrap_or(0);
    let limit = (POOL_ROWS_FACTOR * t.rows.len() as u64).max(MIN_POOL_ROWS);
    // Smallest first: the work bound ends with the largest.
    let mut pools: Vec<(String, Vec<Candidate>)> = pools(eqs, t.nvars, maxeq)
        .into_iter()
        .filter(|p| p.rows(eqs) <= limit)
        .map(|p| (p.describe(&opts.var_names), p.candidates::<P>(eqs)))
        .collect();
    pools.sort_by_key(|(_, rows)| rows.len());
    let mut built = Vec::new();
    for (action, charpoly) in actions {
        if deadline.check_time().is_err() {
            break;
        }
        let measure = folded_measure::<P>(constants, t, action);
        let dims = (visible, max_redundant_basis(count));
        for (label, pool) in &pools {
            let bounds = (&mut *work, Some(deadline));
            let Some((b, kept)) = reduce_permissible::<P>(pool, action, dims, &measure, bounds)
            else {
                continue;
            };
            let parts = (b, kept.as_slice(), visible, count);
            let which = (action, Some(charpoly.as_slice()));
            let found =
                redundant_templates::<P>(eqs, constants, quotient, which, parts, opts, deadline);
            for mut g in found {
                if g.folded_area() >= quotient.folded_area() {
                    continue;
                }
                // The steps of `redundant_templates` (the basis, its deflation) after the pool.
                let steps = g
                    .history
                    .split_off(quotient.history.len().min(g.history.len()));
                g.history = std::iter::once((label.clone(), pool.len(), columns(pool).len()))
                    .chain(steps)
                    .collect();
                let deflated = if g.template.flipped.is_empty() {
                    ""
                } else {
                    ", deflated to a pencil"
                };
                g.basis_choice = format!(
                "the permissible set of {label} for the action {}, reduced greedily (redundant basis{deflated})",
                action.display_with(&opts.var_names)
            );
                built.push(g);
            }
        }
    }
    built.sort_by_key(BuiltTemplate::folded_area);
    built.dedup_by_key(|g| g.template.eliminated_size());
    for g in &mut built {
        g.quotient_basis = Some(Box::new(quotient.clone()));
    }
    built
}
