//! Building the template of one action: candidate rows up to a degree (see
//! `candidates`), shrinking ([`super::shrink`]), the standard basis against bases
//! selected among the template's columns ([`super::select`]), and the final ordering of
//! rows and columns into an [`EliminationTemplate`].
//!
//! Public: [`BuiltTemplate`], and [`EliminationTemplate::fill`], the template matrix of an
//! instance over any ring. The search over actions and degrees that builds templates is
//! [`super::search`].

use super::candidates::{candidate_bytes, candidates, pool_size, Blocks, Candidate, ShrinkStep};
use super::exclude::exclude_and_shrink;
use super::linalg::gauss_jordan;
use super::select::{self, SelectedTemplate};
use super::shift::{row_coordinates, shifted_coordinates, ColumnShift};
use super::shrink::shrink;
use super::{Action, EliminationTemplate, TemplateError, TemplateOptions};
use crate::algebra::{Field, Fp, Monomial, MonomialOrder, Poly};
use crate::budget::Deadline;
use std::collections::{BTreeMap, BTreeSet};

/// A template with how it was obtained.
#[derive(Clone, Debug)]
pub struct BuiltTemplate {
    /// The template.
    pub template: EliminationTemplate,
    /// Size after each construction/shrinking step, first the raw candidate set.
    pub history: Vec<ShrinkStep>,
    /// Whether the action matrix has distinct eigenvalues on the build instance.
    pub distinct_eigenvalues: bool,
    /// How the basis was obtained: `"standard monomials (grevlex)"` or the column order of
    /// the basis selection.
    pub basis_choice: String,
    /// The weights grading its candidate pool (empty: total degree).
    pub pool_weights: Vec<u32>,
    /// How many rows its fold would take ([`super::fold::foldable_rows`]), where the
    /// search knows the equations' constants (0 otherwise): the search compares templates
    /// by their area after the fold ([`BuiltTemplate::folded_area`]).
    pub foldable_rows: usize,
    /// For a template with a redundant basis
    /// ([`EliminationTemplate::spurious_eigenvalues`]), the template with a quotient basis
    /// it was grown from, for the plan to measure one against the other; `None` otherwise.
    pub quotient_basis: Option<Box<BuiltTemplate>>,
    /// Other templates with a redundant basis for the same action, larger than this one,
    /// smallest first: the plan measures each in turn, against this one's
    /// `quotient_basis`, when it drops this one (`crate::redundancy`); empty otherwise (and
    /// their own `quotient_basis` is `None`).
    pub redundant_alternatives: Vec<BuiltTemplate>,
}

impl BuiltTemplate {
    /// The template's elimination area after its fold: the folded size when the template
    /// has been folded, else as [`BuiltTemplate::foldable_rows`] predicts.
    pub fn folded_area(&self) -> usize {
        let t = &self.template;
        if t.fold.is_some() || self.foldable_rows == 0 {
            return t.elimination_area();
        }
        let (r, c) = t.eliminated_size();
        let k = self.foldable_rows.min(r).min(c);
        (r - k) * (c - k) + t.reduction_size().map_or(0, |(n, m)| n * m)
    }
}

/// The candidate degrees [`build_template`] tries, and its limits.
pub(crate) struct DegreeSearch<'a> {
    /// Candidate degrees, tried in increasing order until one reduces.
    pub(crate) degrees: std::ops::RangeInclusive<u32>,
    /// Whether to also try bases selected among the template's columns.
    pub(crate) basis_selection: bool,
    /// Time and memory budget.
    pub(crate) deadline: Option<&'a Deadline>,
    /// Whether to run the greedy exclusion ([`super::exclude`]) on the shrunk template.
    pub(crate) exclude: bool,
    /// The weights grading the candidate pools and `degrees` (empty: total degree).
    pub(crate) weights: &'a [u32],
    /// The most candidate rows a pool may have: larger degrees are not tried (none:
    /// unbounded but for the budget).
    pub(crate) max_pool: Option<u64>,
    /// The polynomial the reducible and basis columns stand for multiples of (a template
    /// saturated by a polynomial, [`super::shift`]); `None`: columns are monomials.
    pub(crate) shift: Option<&'a ColumnShift>,
}

/// The shrunk elimination template for `action` from the equations of one random instance
/// mod P and the quotient basis `basis` (the standard monomials of some monomial order,
/// described by `label`), with the distinct-eigenvalue flag computed by the caller.
///
/// Candidate rows are all multiples of the equations up to total degree `d`, for `d` in
/// `search.degrees` in increasing order, until every reducible monomial is reducible; then
/// shrinking removes rows and columns (and with `search.exclude`, the greedy exclusion
/// searches further), and with `search.basis_selection` a selected basis replaces the
/// standard one when its template is smaller. Deterministic.
pub(crate) fn build_template<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    label: &str,
    action: &Action,
    search: &DegreeSearch,
    distinct: bool,
    opts: &TemplateOptions,
) -> Result<BuiltTemplate, TemplateError> {
    let nvars = basis.first().map(|b| b.nvars()).unwrap_or(0);
    let visible = nvars - opts.hidden_vars.min(nvars);
    // A Laurent action's basis is the quotient basis times its unknown.
    let shifted = action.basis_for(basis);
    let basis = &shifted[..];
    let blocks = Blocks::new(basis, action, visible);
    let shift: Option<Vec<(Monomial, Fp<P>)>> = search.shift.and_then(|s| s.terms_in());
    // Candidate families: all multiples up to degree d, optionally with every exponent of
    // the products capped; each family that reduces is shrunk, the smallest result kept.
    let maxdeg = eqs.iter().filter_map(|f| f.degree()).max().unwrap_or(0);
    let mut best: Option<(usize, Vec<Candidate>, Vec<ShrinkStep>)> = None;
    let mut full_ok = false;
    let mut exhausted = None;
    let mut reached = *search.degrees.start();
    let weights = search.weights;
    // A weighted grading raises the pool by steps much smaller than a whole degree: a
    // degree is tried once its pool is half again as large as the last one tried.
    let mut previous_pool = None;
    'degrees: for d in search.degrees.clone() {
        if let Some(dl) = search.deadline {
            if let Err(e) = dl.check(candidate_bytes(eqs, d, weights)) {
                exhausted = Some(e);
                break;
            }
        }
        let size = pool_size(eqs, d, weights);
        if search.max_pool.is_some_and(|m| size > m) {
            break;
        }
        reached = d;
        if !weights.is_empty() {
            if previous_pool.is_some_and(|p| 2 * size < 3 * p) {
                continue;
            }
            previous_pool = Some(size);
        }
        for cap in (maxdeg.max(1)..=d).rev().take(opts.exponent_caps + 1) {
            let cands: Vec<Candidate> = candidates(eqs, d, weights)
                .into_iter()
                .filter(|c| {
                    c.terms
                        .iter()
                        .all(|(m, _)| m.0.iter().all(|&e| e as u32 <= cap))
                })
                .map(|c| match &shift {
                    Some(s) => shifted_candidate(c, s, &blocks),
                    None => c,
                })
                .collect();
            let refs: Vec<&Candidate> = cands.iter().collect();
            match blocks.reducible_within::<P>(&refs, search.deadline) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => {
                    exhausted = Some(e);
                    break 'degrees;
                }
            }
            full_ok = true;
            let ne = blocks.excess_of(cands.iter()).len();
            let mut history = vec![(
                if !weights.is_empty() {
                    format!("all multiples up to weighted degree {d} (weights {weights:?})")
                } else if cap < d {
                    format!("all multiples up to degree {d}, exponents <= {cap}")
                } else {
                    format!("all multiples up to degree {d}")
                },
                cands.len(),
                ne + blocks.reducible.len() + basis.len(),
            )];
            let pool = search.exclude.then(|| cands.clone());
            let Some(mut kept) = shrink::<P>(&blocks, cands, &mut history, search.deadline) else {
                exhausted = search.deadline.and_then(|d| d.check_time().err());
                break 'degrees;
            };
            if let Some(pool) = pool {
                kept = exclude_and_shrink::<P>(&blocks, pool, kept, search.deadline, &mut history);
            }
            let score = kept.len()
                * (blocks.excess_of(kept.iter()).len() + blocks.reducible.len() + basis.len());
            if best.as_ref().map_or(true, |b| score < b.0) {
                best = Some((score, kept, history));
            }
        }
        if full_ok {
            break;
        }
    }
    let mut best: Option<SelectedTemplate> = best.map(|(score, kept, history)| SelectedTemplate {
        score,
        blocks,
        kept,
        history,
        label: label.to_string(),
    });
    // Selected bases contain 1 and every variable. A variable outside the standard
    // (grevlex) basis is a leading term of the ideal, so the ideal holds a linear
    // polynomial in it: 1 and the variables are dependent, and no selected basis exists.
    let every_variable = (0..nvars).all(|v| basis.contains(&Monomial::var(nvars, v)));
    // Selected bases contain 1, which a Laurent action cannot divide.
    let selectable = every_variable && action.inverse_of().is_none();
    if search.basis_selection && exhausted.is_none() && selectable {
        let maxeq = eqs.iter().filter_map(|f| f.degree()).max().unwrap_or(0);
        if let Some(sel) = select::best_selected::<P>(
            eqs,
            nvars,
            action,
            basis.len(),
            maxeq,
            &opts.var_names,
            search.deadline,
        ) {
            if best.as_ref().map_or(true, |b| sel.score < b.score) {
                best = Some(sel);
            }
        }
    }
    let Some(SelectedTemplate {
        blocks,
        kept,
        history,
        label: basis_choice,
        ..
    }) = best
    else {
        return Err(TemplateError::NotReducible {
            action: action.display_with(&opts.var_names),
            max_degree: reached,
            exhausted,
        });
    };
    let mut template = assemble::<P>(nvars, &blocks, &kept, action, opts.hidden_vars);
    template.shift = search.shift.cloned();
    debug_assert!(blocks.reducible_by::<P>(&kept.iter().collect::<Vec<_>>()));
    template.check_emittable(&opts.var_names)?;
    Ok(BuiltTemplate {
        template,
        history,
        distinct_eigenvalues: distinct,
        basis_choice,
        pool_weights: weights.to_vec(),
        foldable_rows: 0,
        quotient_basis: None,
        redundant_alternatives: Vec::new(),
    })
}

/// `c` with its terms in the coordinates of a template whose reducible and basis columns
/// stand for multiples of `shift` ([`super::shift`]).
fn shifted_candidate<const P: u32>(
    c: Candidate,
    shift: &[(Monomial, Fp<P>)],
    blocks: &Blocks,
) -> Candidate {
    let terms = shifted_coordinates(
        c.terms.into_iter().map(|(m, x)| (m, Fp::<P>(x))),
        shift,
        |l| blocks.red_set.contains(l) || blocks.basis_set.contains(l),
    );
    Candidate {
        terms: terms.into_iter().map(|(m, x)| (m, x.0)).collect(),
        ..c
    }
}

/// Orders the final rows and columns into an [`EliminationTemplate`]: columns
/// `excess (descending grevlex) | reducible (descending grevlex) | basis (given order)`,
/// except that excess columns that are not pivot columns of the excess block on this
/// instance (linear combinations of earlier ones) move to the end of the excess block as
/// its dependent columns; rows by their first non-zero column (then equation and
/// multiplier), so that the left block is close to triangular.
pub(crate) fn assemble<const P: u32>(
    nvars: usize,
    blocks: &Blocks,
    kept: &[Candidate],
    action: &Action,
    n_hidden: usize,
) -> EliminationTemplate {
    let excess = blocks.excess_of(kept.iter());
    let refs: Vec<&Candidate> = kept.iter().collect();
    let mut dense = blocks.dense_er(&refs, &excess);
    let pivots: BTreeSet<usize> = gauss_jordan::<P>(&mut dense, excess.len(), false)
        .into_iter()
        .collect();
    let (independent, dependent): (Vec<_>, Vec<_>) = excess
        .into_iter()
        .enumerate()
        .partition(|(i, _)| pivots.contains(i));
    let n_dependent = dependent.len();
    let excess: Vec<Monomial> = independent
        .into_iter()
        .chain(dependent)
        .map(|(_, m)| m)
        .collect();
    let columns: Vec<Monomial> = excess
        .iter()
        .chain(blocks.reducible.iter())
        .chain(blocks.basis.iter())
        .cloned()
        .collect();
    let idx: BTreeMap<&Monomial, usize> = columns.iter().enumerate().map(|(i, m)| (m, i)).collect();
    let mut rows: Vec<(usize, &Candidate)> = kept
        .iter()
        .map(|c| {
            let first = c
                .terms
                .iter()
                .map(|(m, _)| idx[m])
                .min()
                .unwrap_or(usize::MAX);
            (first, c)
        })
        .collect();
    rows.sort_by(|a, b| {
        (a.0, a.1.row.equation)
            .cmp(&(b.0, b.1.row.equation))
            .then_with(|| MonomialOrder::Grevlex.cmp(&b.1.row.multiplier, &a.1.row.multiplier))
    });
    EliminationTemplate {
        nvars,
        rows: rows.into_iter().map(|(_, c)| c.row.clone()).collect(),
        n_excess: excess.len(),
        n_reducible: blocks.reducible.len(),
        n_dependent,
        columns,
        basis: blocks.basis.clone(),
        n_hidden,
        action: action.clone(),
        sparse: None,
        unrolled: None,
        reduction: None,
        fold: None,
        shift: None,
        spurious_eigenvalues: 0,
        flipped: blocks.flipped.clone(),
    }
}

impl EliminationTemplate {
    /// The template matrix (rows x columns, see the module convention) of the instance
    /// with equations `eqs`, over any field: row i holds the coefficients of
    /// `rows[i].multiplier * eqs[rows[i].equation]`, after the template's
    /// [`EliminationTemplate::reduction`] if it has one (exactly, over the field).
    ///
    /// Errors with [`TemplateError::MissingColumn`] if a product has a monomial that is not
    /// a column, or [`TemplateError::Reduction`] if the equations cannot be reduced as
    /// planned (the instance is not of the family the template was built for).
    /// `names` renders the unknowns in the error (template variables in order).
    pub fn fill<C: Field>(
        &self,
        eqs: &[Poly<C>],
        names: &[String],
    ) -> Result<Vec<Vec<C>>, TemplateError> {
        let reduced;
        let eqs = match &self.reduction {
            Some(r) => {
                reduced = r.reduce(eqs)?;
                &reduced[..]
            }
            None => eqs,
        };
        let idx: BTreeMap<&Monomial, usize> = self
            .columns
            .iter()
            .enumerate()
            .map(|(i, m)| (m, i))
            .collect();
        let shift: Option<Vec<(Monomial, C)>> = match &self.shift {
            Some(s) => Some(s.terms_in().ok_or(TemplateError::ShiftNotInField)?),
            None => None,
        };
        self.rows
            .iter()
            .map(|r| {
                let mut v = vec![C::zero(); self.columns.len()];
                let terms = row_coordinates(
                    &r.multiplier,
                    &eqs[r.equation],
                    shift.as_deref(),
                    self.n_excess,
                    |m| idx.get(m).copied(),
                );
                for (p, c) in terms {
                    match idx.get(&p) {
                        Some(&k) => v[k] = c,
                        None => {
                            return Err(TemplateError::MissingColumn {
                                equation: r.equation,
                                multiplier: r.multiplier.display_with(names),
                                monomial: p.display_with(names),
                            })
                        }
                    }
                }
                Ok(v)
            })
            .collect()
    }
}
