//! Building elimination templates: candidate rows as monomial multiples of the equations
//! (Macaulay-style, by increasing total degree), shrinking (see [`super::shrink`]), and the
//! choice of the action variable.
//!
//! ## Public API
//! - [`build_template`]`(&equations, &basis, action_var, &opts)`: the shrunk template for
//!   one action variable, from the equations of one random instance mod P.
//!   Besides the given (standard-monomial) basis it tries bases selected among the
//!   template's columns ([`super::select`], `opts.basis_selection`) and keeps the smallest.
//! - [`best_template`]: tries every unknown as action variable and keeps the best.
//! - [`generate`]`(&source, &opts)`: the whole algebra pipeline from an
//!   [`InstanceSource`]: [`analyse`] (count and basis, confirmed), [`best_template`],
//!   [`super::validate::validate`]; returns a [`Generated`].
//! - [`EliminationTemplate::fill`]: the template matrix of an instance, over any ring.
//!
//! The reducibility test used everywhere: with the template's columns ordered
//! `excess | reducible | basis`, Gauss-Jordan elimination makes every reducible column a
//! pivot column iff `rank([E | R]) - rank(E) = |R|` (E, R: the excess and reducible column
//! blocks); the basis block does not enter the test.

use super::linalg::{gauss_jordan, gauss_jordan_within, is_squarefree};
use super::select::{self, SelectedTemplate};
use super::shrink::shrink;
use super::validate::nf_action_charpoly;
use super::{Action, EliminationTemplate, ShapeError, TemplateRow};
use crate::algebra::{Fp, Monomial, MonomialOrder, Poly, Ring};
use crate::budget::{Budget, Deadline, Exhausted};
use crate::groebner::{groebner, GroebnerError};
use crate::problem::ProblemOptions;
use crate::quotient::AnalysisError;
use std::collections::{BTreeMap, BTreeSet};
use thiserror::Error;

/// Failures of template construction and validation.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum TemplateError {
    /// Counting solutions failed.
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    /// A Gröbner basis computation failed (during validation).
    #[error(transparent)]
    Groebner(#[from] GroebnerError),
    /// No candidate set up to the degree bound makes every reducible monomial reducible.
    #[error(
        "reducible monomials still not reducible with all multiples up to degree {max_degree}{}",
        .exhausted.map(|e| format!(" ({e})")).unwrap_or_default()
    )]
    NotReducible {
        /// The action (rendered).
        action: String,
        /// The largest total degree tried.
        max_degree: u32,
        /// The budget that stopped the search, if one did (otherwise the degree bound of
        /// the options did).
        exhausted: Option<Exhausted>,
    },
    /// The quotient basis lacks 1 or an unknown: solutions cannot be read off eigenvectors.
    #[error("the quotient basis does not contain {missing}: solutions cannot be read off the eigenvectors")]
    BasisLacks {
        /// Rendered missing monomials (e.g. `1`, `t3`).
        missing: String,
    },
    /// An instance has a monomial the template has no column for.
    #[error("instance equation {equation} times {multiplier} has monomial {monomial}, which is not a template column")]
    MissingColumn {
        /// Equation index.
        equation: usize,
        /// Rendered multiplier.
        multiplier: String,
        /// Rendered monomial.
        monomial: String,
    },
    /// On some validation instance, a reducible column is not a pivot column.
    #[error("validation instance {instance}: reducible monomial {monomial} is not reducible by the template")]
    Singular {
        /// Instance number.
        instance: usize,
        /// Rendered monomial.
        monomial: String,
    },
    /// Template and Gröbner action matrices disagree.
    #[error("validation instance {instance}: characteristic polynomials of the template and Gröbner action matrices differ")]
    CharpolyMismatch {
        /// Instance number.
        instance: usize,
    },
    /// No action variable was given or none works.
    #[error("no usable action variable: {0}")]
    NoAction(String),
    /// The template cannot be solved by elimination and eigenvectors.
    #[error(transparent)]
    Shape(#[from] ShapeError),
    /// The solutions were counted, but no solver could be made: the count is kept so
    /// that every report can still state it.
    #[error("{count} solutions, but no template: {source}")]
    Counted {
        /// The number of solutions (confirmed on two primes).
        count: usize,
        /// Why no template was found or accepted.
        source: Box<TemplateError>,
    },
}

impl TemplateError {
    /// The number of solutions, if it was found before the failure.
    pub fn solution_count(&self) -> Option<usize> {
        match self {
            TemplateError::Counted { count, .. } => Some(*count),
            _ => None,
        }
    }
}

/// Options of template construction.
#[derive(Clone, Debug)]
pub struct TemplateOptions {
    /// How many degrees above the largest of the equations and the reducible monomials
    /// every action is tried at first (4 by default).
    pub max_extra_degree: u32,
    /// When no action works within `max_extra_degree`, raise the candidate degree further
    /// until one does or the budget runs out (on by default; off means `max_extra_degree`
    /// is a hard bound).
    pub adaptive_degree: bool,
    /// Time and memory budget of the whole algebra (count, templates, validation).
    pub budget: Budget,
    /// Which actions to try.
    pub actions: ActionChoice,
    /// Prefer actions whose action matrix has distinct eigenvalues (a squarefree
    /// characteristic polynomial on the build instance), since the solutions are read off
    /// its eigenvectors. On by default.
    pub require_distinct_eigenvalues: bool,
    /// Number of fresh instances [`generate`] validates the chosen template on.
    pub validate_instances: usize,
    /// How many exponent caps below the degree to try as extra candidate families
    /// (products with every exponent `<= d - 1, d - 2, ...`); 0 by default (no gain seen
    /// on the shipped problems).
    pub exponent_caps: usize,
    /// Also choose the quotient basis among the template's columns (see
    /// [`super::select`]): for each of a few column orders (grevlex under the variable
    /// permutations of [`super::select::basis_orders`]), the basis B is read off a Gaussian
    /// elimination of all multiples up to a low degree, and the smallest template over the
    /// standard basis and these bases is kept (ties to the standard basis). On by default.
    pub basis_selection: bool,
    /// Seed of all random choices (instances).
    pub seed: u64,
    /// Options that override those of the problem file (`option NAME = VALUE`) when the
    /// pipeline applies them (`crate::pipeline::plan`); set by the command line.
    pub overrides: ProblemOptions,
    /// Number of hidden variables (the last ones, from `nonzero`), which the template need
    /// not read off; [`super::generate`] fills it from its source.
    pub hidden_vars: usize,
    /// Names of the unknowns, in variable order, for messages; empty renders them as
    /// `x0, x1, ...`. [`generate`] fills them from its source.
    pub var_names: Vec<String>,
}

impl Default for TemplateOptions {
    fn default() -> Self {
        TemplateOptions {
            max_extra_degree: 4,
            adaptive_degree: true,
            budget: Budget::default(),
            actions: ActionChoice::Auto,
            require_distinct_eigenvalues: true,
            validate_instances: 10,
            exponent_caps: 0,
            basis_selection: true,
            seed: 2024,
            hidden_vars: 0,
            overrides: ProblemOptions::default(),
            var_names: Vec::new(),
        }
    }
}

/// Which actions the template search tries.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub enum ActionChoice {
    /// Every unknown; when none gives a template whose action matrix has distinct
    /// eigenvalues, also a random linear combination of the unknowns ([`Action::random`]).
    #[default]
    Auto,
    /// These unknowns (variable indices) only.
    Unknowns(Vec<usize>),
    /// A random linear combination of the unknowns only.
    Random,
}

/// One shrinking step: `(description, rows, cols)` after the step.
pub type ShrinkStep = (String, usize, usize);

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
}

/// The candidate rows and their monomials, as used by build and shrink.
#[derive(Clone, Debug)]
pub(crate) struct Candidate {
    pub(crate) row: TemplateRow,
    /// Total degree of `multiplier * equation`.
    pub(crate) degree: u32,
    /// Terms of the product (monomial, raw residue).
    pub(crate) terms: Vec<(Monomial, u32)>,
}

/// Classification of monomials into the reducible and basis blocks.
pub(crate) struct Blocks {
    pub(crate) reducible: Vec<Monomial>,
    pub(crate) basis: Vec<Monomial>,
    pub(crate) red_set: BTreeSet<Monomial>,
    pub(crate) basis_set: BTreeSet<Monomial>,
}

impl Blocks {
    pub(crate) fn new(basis: &[Monomial], action: &Action) -> Blocks {
        let basis_set: BTreeSet<Monomial> = basis.iter().cloned().collect();
        let red_set: BTreeSet<Monomial> = basis
            .iter()
            .flat_map(|b| action.products(b).map(|(m, _)| m).collect::<Vec<_>>())
            .filter(|m| !basis_set.contains(m))
            .collect();
        let mut reducible: Vec<Monomial> = red_set.iter().cloned().collect();
        reducible.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
        Blocks {
            reducible,
            basis: basis.to_vec(),
            red_set,
            basis_set,
        }
    }
    /// The excess monomials of a set of rows, descending grevlex.
    pub(crate) fn excess_of<'a>(&self, rows: impl Iterator<Item = &'a Candidate>) -> Vec<Monomial> {
        let mut s: BTreeSet<Monomial> = BTreeSet::new();
        for c in rows {
            for (m, _) in &c.terms {
                if !self.red_set.contains(m) && !self.basis_set.contains(m) {
                    s.insert(m.clone());
                }
            }
        }
        let mut v: Vec<Monomial> = s.into_iter().collect();
        v.sort_by(|a, b| MonomialOrder::Grevlex.cmp(b, a));
        v
    }
    /// Dense `[E | R]` rows (raw residues) of the candidates, with the given excess order.
    pub(crate) fn dense_er(&self, rows: &[&Candidate], excess: &[Monomial]) -> Vec<Vec<u32>> {
        let idx: BTreeMap<&Monomial, usize> = excess
            .iter()
            .chain(self.reducible.iter())
            .enumerate()
            .map(|(i, m)| (m, i))
            .collect();
        let n = excess.len() + self.reducible.len();
        rows.iter()
            .map(|c| {
                let mut v = vec![0u32; n];
                for (m, x) in &c.terms {
                    if let Some(&k) = idx.get(m) {
                        v[k] = *x;
                    }
                }
                v
            })
            .collect()
    }
    /// The reducibility test `rank([E|R]) - rank(E) == |R|` for a row set.
    pub(crate) fn reducible_by<const P: u32>(&self, rows: &[&Candidate]) -> bool {
        self.reducible_within::<P>(rows, None)
            .expect("no budget, never exhausted")
    }
    /// [`Self::reducible_by`] within a budget.
    pub(crate) fn reducible_within<const P: u32>(
        &self,
        rows: &[&Candidate],
        deadline: Option<&Deadline>,
    ) -> Result<bool, Exhausted> {
        let excess = self.excess_of(rows.iter().copied());
        let mut m = self.dense_er(rows, &excess);
        let piv =
            gauss_jordan_within::<P>(&mut m, excess.len() + self.reducible.len(), false, deadline)?;
        Ok(piv.iter().filter(|&&c| c >= excess.len()).count() == self.reducible.len())
    }
}

/// All multiples `m * f_i` with `deg(m * f_i) <= d`.
pub(crate) fn candidates<const P: u32>(eqs: &[Poly<Fp<P>>], d: u32) -> Vec<Candidate> {
    let mut out = Vec::new();
    for (i, f) in eqs.iter().enumerate() {
        let Some(df) = f.degree() else { continue };
        if df > d {
            continue;
        }
        let n = f.nvars();
        for m in Monomial::all_up_to_degree(n, d - df, MonomialOrder::Grevlex) {
            let terms = f.terms().map(|(t, c)| (t.mul(&m), c.0)).collect();
            out.push(Candidate {
                row: TemplateRow {
                    equation: i,
                    multiplier: m.clone(),
                },
                degree: df + m.degree(),
                terms,
            });
        }
    }
    out
}

/// The shrunk elimination template for action variable `action_var` from the equations of
/// one random instance mod P and the quotient basis `basis` (descending grevlex, as from
/// [`crate::quotient::standard_monomials`]).
///
/// Candidate rows are all multiples of the equations up to total degree `d`, for `d` from
/// the largest degree among the equations and the reducible monomials upward (at most
/// `opts.max_extra_degree` more), until every reducible monomial is reducible; then
/// Shrinking (`shrink.rs`) removes rows and columns. Deterministic. (The adaptive search
/// beyond `opts.max_extra_degree` is [`super::best_template`]'s.)
pub fn build_template<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    action_var: usize,
    opts: &TemplateOptions,
) -> Result<BuiltTemplate, TemplateError> {
    let nvars = basis.first().map(|b| b.nvars()).unwrap_or(0);
    let action = Action::var(nvars, action_var);
    let d0 = start_degree(eqs, basis, &action);
    let distinct = match groebner(nvars, eqs) {
        Ok(gb) => is_squarefree::<P>(&nf_action_charpoly::<P>(&gb, basis, &action)),
        Err(_) => false,
    };
    let search = DegreeSearch {
        degrees: d0..=d0 + opts.max_extra_degree,
        basis_selection: opts.basis_selection,
        deadline: None,
    };
    build_in_range::<P>(eqs, basis, &action, &search, distinct, opts)
}

/// The smallest candidate degree worth trying for `action`: the largest degree among the
/// equations and the reducible monomials.
pub(crate) fn start_degree<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    action: &Action,
) -> u32 {
    let blocks = Blocks::new(basis, action);
    eqs.iter()
        .filter_map(|f| f.degree())
        .chain(blocks.reducible.iter().map(|m| m.degree()))
        .max()
        .unwrap_or(0)
}

/// Estimated bytes of the candidate rows of degree `d` and of their dense `[E|R]` matrix.
pub(crate) fn candidate_bytes<const P: u32>(eqs: &[Poly<Fp<P>>], d: u32) -> u64 {
    let n = eqs.first().map_or(0, |f| f.nvars()) as u64;
    let binom =
        |a: u64, b: u64| -> u64 { (1..=b).fold(1u64, |acc, i| acc.saturating_mul(a + 1 - i) / i) };
    let cols = binom(n + d as u64, n);
    let (mut rows, mut terms) = (0u64, 0u64);
    for f in eqs {
        let Some(df) = f.degree() else { continue };
        if df <= d {
            let r = binom(n + (d - df) as u64, n);
            rows = rows.saturating_add(r);
            terms = terms.saturating_add(r.saturating_mul(f.len() as u64));
        }
    }
    rows.saturating_mul(cols)
        .saturating_mul(4)
        .saturating_add(terms.saturating_mul(48 + 2 * n))
}

/// The candidate degrees [`build_in_range`] tries, and its limits.
pub(crate) struct DegreeSearch<'a> {
    /// Candidate degrees, tried in increasing order until one reduces.
    pub(crate) degrees: std::ops::RangeInclusive<u32>,
    /// Whether to also try bases selected among the template's columns.
    pub(crate) basis_selection: bool,
    /// Time and memory budget.
    pub(crate) deadline: Option<&'a Deadline>,
}

/// [`build_template`] for the candidate degrees of `search`, with the distinct-eigenvalue
/// flag computed by the caller.
pub(crate) fn build_in_range<const P: u32>(
    eqs: &[Poly<Fp<P>>],
    basis: &[Monomial],
    action: &Action,
    search: &DegreeSearch,
    distinct: bool,
    opts: &TemplateOptions,
) -> Result<BuiltTemplate, TemplateError> {
    let nvars = basis.first().map(|b| b.nvars()).unwrap_or(0);
    let blocks = Blocks::new(basis, action);
    // Candidate families: all multiples up to degree d, optionally with every exponent of
    // the products capped; each family that reduces is shrunk, the smallest result kept.
    let maxdeg = eqs.iter().filter_map(|f| f.degree()).max().unwrap_or(0);
    let mut best: Option<(usize, Vec<Candidate>, Vec<ShrinkStep>)> = None;
    let mut full_ok = false;
    let mut exhausted = None;
    let mut reached = *search.degrees.start();
    'degrees: for d in search.degrees.clone() {
        if let Some(dl) = search.deadline {
            if let Err(e) = dl.check(candidate_bytes(eqs, d)) {
                exhausted = Some(e);
                break;
            }
        }
        reached = d;
        for cap in (maxdeg.max(1)..=d).rev().take(opts.exponent_caps + 1) {
            let cands: Vec<Candidate> = candidates(eqs, d)
                .into_iter()
                .filter(|c| {
                    c.terms
                        .iter()
                        .all(|(m, _)| m.0.iter().all(|&e| e as u32 <= cap))
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
                if cap < d {
                    format!("all multiples up to degree {d}, exponents <= {cap}")
                } else {
                    format!("all multiples up to degree {d}")
                },
                cands.len(),
                ne + blocks.reducible.len() + basis.len(),
            )];
            let kept = shrink::<P>(&blocks, cands, &mut history);
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
        label: "standard monomials (grevlex)".to_string(),
    });
    // Basis selection is unbudgeted work: skipped once the budget has run out.
    if search.basis_selection && exhausted.is_none() {
        let maxeq = eqs.iter().filter_map(|f| f.degree()).max().unwrap_or(0);
        if let Some(sel) =
            select::best_selected::<P>(eqs, nvars, action, basis.len(), maxeq, &opts.var_names)
        {
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
    let template = assemble::<P>(nvars, &blocks, &kept, action, opts.hidden_vars);
    debug_assert!(blocks.reducible_by::<P>(&kept.iter().collect::<Vec<_>>()));
    template.check_emittable(&opts.var_names)?;
    Ok(BuiltTemplate {
        template,
        history,
        distinct_eigenvalues: distinct,
        basis_choice,
    })
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
    }
}

impl EliminationTemplate {
    /// The template matrix (rows x columns, see the module convention) of the instance
    /// with equations `eqs`, over any ring: row i holds the coefficients of
    /// `rows[i].multiplier * eqs[rows[i].equation]`.
    ///
    /// Errors with [`TemplateError::MissingColumn`] if a product has a monomial that is not
    /// a column (the instance is not of the family the template was built for).
    /// `names` renders the unknowns in the error (template variables in order).
    pub fn fill<C: Ring>(
        &self,
        eqs: &[Poly<C>],
        names: &[String],
    ) -> Result<Vec<Vec<C>>, TemplateError> {
        let idx: BTreeMap<&Monomial, usize> = self
            .columns
            .iter()
            .enumerate()
            .map(|(i, m)| (m, i))
            .collect();
        self.rows
            .iter()
            .map(|r| {
                let mut v = vec![C::zero(); self.columns.len()];
                for (m, c) in eqs[r.equation].terms() {
                    let p = m.mul(&r.multiplier);
                    match idx.get(&p) {
                        Some(&k) => v[k] = c.clone(),
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
