//! Validation of a template mod p against Gröbner normal forms.
//!
//! ## Public API
//! - [`template_action_matrix`]: fill the template from an instance mod P, Gauss-Jordan,
//!   and read the action matrix off per the convention of `crate::template`.
//! - [`gb_action_matrix`]: the action matrix from normal forms (row j: coefficients of
//!   `NF(action * b_j)` on the basis).
//! - [`validate`]: on fresh random instances (alternately mod P1 and P2) checks that both
//!   action matrices have the same characteristic polynomial and that the linear read-out
//!   of every unknown outside the basis is its normal form, after [`check_readoff`] (the
//!   basis must contain 1, every unknown must be in it or a reducible column).

use super::linalg::{addmod, charpoly_within, gauss_jordan, inverse, mulmod, poly_gcd, submod};
use super::{Action, EliminationTemplate, TemplateError};
use crate::algebra::{Fp, Monomial, Poly, Ring, P1, P2};
use crate::budget::{Deadline, Exhausted};
use crate::groebner::{groebner_with, GroebnerBasis, GroebnerOptions};
use crate::quotient::{standard_monomials, InstanceSource};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;

/// Outcome of a successful [`validate`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ValidationReport {
    /// Number of instances checked (all passed).
    pub instances: usize,
}

/// Checks that the template's basis contains 1 and that every unknown is in it or a
/// reducible column (read off its reduced row), as needed to read the solutions off the
/// eigenvectors. `names` renders the unknowns in the message (template variables in order).
pub fn check_readoff(t: &EliminationTemplate, names: &[String]) -> Result<(), TemplateError> {
    let mut missing = Vec::new();
    if !t.basis.contains(&t.unit()) {
        missing.push("1".to_string());
    }
    let reducible = t
        .columns
        .get(t.n_excess..t.n_excess + t.n_reducible)
        .unwrap_or_default();
    for m in t.linear_readouts() {
        if !reducible.contains(&m) {
            missing.push(m.display_with(names));
        }
    }
    if missing.is_empty() {
        Ok(())
    } else {
        Err(TemplateError::BasisLacks {
            missing: missing.join(", "),
        })
    }
}

/// The action matrix (|B| x |B|, raw residues) of the template on an instance mod P, or
/// the first column that the elimination does not turn into a pivot. The matrix is
/// eliminated as the emitted solvers eliminate it: without the dependent excess columns,
/// every other excess and every reducible column a pivot, in order.
/// `names` renders the unknowns in errors (template variables in order).
pub fn template_action_matrix<const P: u32>(
    t: &EliminationTemplate,
    eqs: &[Poly<Fp<P>>],
    names: &[String],
) -> Result<Vec<Vec<u32>>, TemplateError> {
    template_matrices::<P>(t, eqs, names).map(|(a, _)| a)
}

/// [`template_action_matrix`] and the linear read-out of each unknown outside the basis
/// ([`EliminationTemplate::linear_readouts`], same order): the coefficients of its normal form on the basis,
/// `-T[x_i, :]` from its reduced row.
#[allow(clippy::type_complexity)]
fn template_matrices<const P: u32>(
    t: &EliminationTemplate,
    eqs: &[Poly<Fp<P>>],
    names: &[String],
) -> Result<(Vec<Vec<u32>>, Vec<Vec<u32>>), TemplateError> {
    let show = |m: &Monomial| m.display_with(names);
    let filled = t.fill(eqs, names)?;
    let mut m: Vec<Vec<u32>> = filled
        .into_iter()
        .map(|r| {
            r.into_iter()
                .enumerate()
                .filter(|(j, _)| t.filled_column(*j).is_some())
                .map(|(_, c)| c.0)
                .collect()
        })
        .collect();
    // The whole template, constant rows included: a fold is an exact rewriting of this
    // elimination (see `fold.rs`).
    let (_, nc) = t.filled_size();
    let npiv = t.filled_pivot_columns();
    let piv = gauss_jordan::<P>(&mut m, npiv, true);
    if let Some(j) = (0..npiv).find(|&j| piv.get(j) != Some(&j)) {
        let col = (0..t.columns.len())
            .find(|&c| t.filled_column(c) == Some(j))
            .unwrap_or(j);
        return Err(TemplateError::Singular {
            instance: 0,
            monomial: show(&t.columns[col]),
        });
    }
    let nb = t.basis.len();
    let red0 = t.n_excess - t.n_dependent;
    // Row of each reducible column's pivot (template column numbering).
    let mut red_row: BTreeMap<usize, usize> = BTreeMap::new();
    for (r, &c) in piv.iter().enumerate() {
        if c >= red0 && c < npiv {
            red_row.insert(c + t.n_dependent, r);
        }
    }
    let col_of: BTreeMap<&Monomial, usize> =
        t.columns.iter().enumerate().map(|(i, m)| (m, i)).collect();
    let basis_idx: BTreeMap<&Monomial, usize> =
        t.basis.iter().enumerate().map(|(i, m)| (m, i)).collect();
    let mut out = vec![vec![0u32; nb]; nb];
    for (j, row) in out.iter_mut().enumerate() {
        for (ab, coef) in t.relation(j) {
            let c = Action::residue::<P>(coef);
            if let Some(&k) = basis_idx.get(&ab) {
                row[k] = addmod::<P>(row[k], c);
                continue;
            }
            let col = col_of[&ab];
            let Some(&r) = red_row.get(&col) else {
                return Err(TemplateError::Singular {
                    instance: 0,
                    monomial: show(&ab),
                });
            };
            for (k, x) in row.iter_mut().enumerate() {
                *x = submod::<P>(*x, mulmod::<P>(c, m[r][nc - nb + k]));
            }
        }
    }
    if !t.flipped.is_empty() {
        out =
            pencil_action_matrix::<P>(&out, &t.flipped).ok_or_else(|| TemplateError::Singular {
                instance: 0,
                monomial: format!(
                    "the flipped relations of {}",
                    t.flipped
                        .iter()
                        .map(|&j| show(&t.basis[j]))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            })?;
    }
    let mut readouts = Vec::new();
    for x in t.linear_readouts() {
        let r =
            col_of
                .get(&x)
                .and_then(|c| red_row.get(c))
                .ok_or_else(|| TemplateError::Singular {
                    instance: 0,
                    monomial: show(&x),
                })?;
        readouts.push(
            (0..nb)
                .map(|k| submod::<P>(0, m[*r][nc - nb + k]))
                .collect(),
        );
    }
    Ok((out, readouts))
}

/// The action matrix `M = T1^-1 T0` of a pencil template (see the template convention)
/// from its relation matrix `rel` (row j: the basis coordinates of `action * b_j`, or of
/// `b_j / action` for `j` in `flipped`): unflipped rows are `rel`'s, the flipped rows `F`
/// solve `rel_FF M_F = E_F - rel_FU rel_U`. `None` when `rel_FF` is singular.
fn pencil_action_matrix<const P: u32>(
    rel: &[Vec<u32>],
    flipped: &[usize],
) -> Option<Vec<Vec<u32>>> {
    let n = rel.len();
    let is_flipped = |j: usize| flipped.binary_search(&j).is_ok();
    let square: Vec<Vec<u32>> = flipped
        .iter()
        .map(|&i| flipped.iter().map(|&l| rel[i][l]).collect())
        .collect();
    let inv = inverse::<P>(&square)?;
    // rhs_F = E_F - rel_FU rel_U.
    let rhs: Vec<Vec<u32>> = flipped
        .iter()
        .map(|&i| {
            let mut row = vec![0u32; n];
            row[i] = 1;
            for (l, &c) in rel[i].iter().enumerate() {
                if c != 0 && !is_flipped(l) {
                    for k in 0..n {
                        row[k] = submod::<P>(row[k], mulmod::<P>(c, rel[l][k]));
                    }
                }
            }
            row
        })
        .collect();
    let mut out = rel.to_vec();
    for (a, &i) in flipped.iter().enumerate() {
        out[i] = (0..n)
            .map(|k| {
                (0..flipped.len()).fold(0u32, |acc, b| {
                    addmod::<P>(acc, mulmod::<P>(inv[a][b], rhs[b][k]))
                })
            })
            .collect();
    }
    Some(out)
}

/// The action matrix of multiplication by `action` on the quotient ring, in the basis
/// `basis` (standard monomials of `gb`): row j holds the coefficients of
/// `NF(action * basis[j])` (for a Laurent action `1 / x_v`, the inverse of `x_v`'s matrix). Checks `deadline` between rows (each is a normal form).
pub fn gb_action_matrix<const P: u32>(
    gb: &GroebnerBasis<P>,
    basis: &[Monomial],
    action: &Action,
    deadline: Option<&Deadline>,
) -> Result<Vec<Vec<u32>>, TemplateError> {
    let form = action.poly::<P>();
    let idx: BTreeMap<&Monomial, usize> = basis.iter().enumerate().map(|(i, m)| (m, i)).collect();
    // The matrix is `count x count`: its size is known before it is filled.
    if let Some(d) = deadline {
        let n = basis.len() as u64;
        d.check_memory(n.saturating_mul(n).saturating_mul(2 * 4))
            .map_err(budget_error)?;
    }
    let mut rows = Vec::with_capacity(basis.len());
    for (j, b) in basis.iter().enumerate() {
        if let (Some(d), 0) = (deadline, j % 16) {
            d.check_time().map_err(budget_error)?;
        }
        let nf = gb.normal_form(&form.mul(&Poly::term(b.clone(), Fp::<P>::one())))?;
        rows.push(coordinates(&nf, &idx));
    }
    // A Laurent action `1 / x_v`: the inverse of multiplication by `x_v`, which exists
    // where `x_v` is non-zero on every solution.
    if let Some(v) = action.inverse_of() {
        return inverse::<P>(&rows).ok_or_else(|| TemplateError::Singular {
            instance: 0,
            monomial: format!("1 / x{v} (x{v} is zero on a solution)"),
        });
    }
    Ok(rows)
}

/// The coordinates of a normal form on the standard monomials indexed by `idx` (a term
/// outside them, which a normal form does not have, is left out).
fn coordinates<const P: u32>(p: &Poly<Fp<P>>, idx: &BTreeMap<&Monomial, usize>) -> Vec<u32> {
    let mut row = vec![0u32; idx.len()];
    for (m, c) in p.terms() {
        if let Some(&i) = idx.get(m) {
            row[i] = c.0;
        }
    }
    row
}

/// A budget that ran out during a check of the action matrices.
fn budget_error(exhausted: Exhausted) -> TemplateError {
    TemplateError::Budget {
        step: "the characteristic polynomial of an action matrix".into(),
        exhausted,
    }
}

/// Characteristic polynomial of [`gb_action_matrix`], within `deadline`.
pub(crate) fn nf_action_charpoly<const P: u32>(
    gb: &GroebnerBasis<P>,
    basis: &[Monomial],
    action: &Action,
    deadline: Option<&Deadline>,
) -> Result<Vec<u32>, TemplateError> {
    let m = gb_action_matrix(gb, basis, action, deadline)?;
    charpoly_within::<P>(&m, deadline).map_err(budget_error)
}

fn check_one<const P: u32, S: InstanceSource>(
    t: &EliminationTemplate,
    src: &S,
    rng: &mut ChaCha8Rng,
    instance: usize,
    deadline: Option<&Deadline>,
) -> Result<(), TemplateError> {
    let eqs = src.instance::<P>(rng);
    let names = src.var_names();
    let (tm, readouts) = template_matrices::<P>(t, &eqs, &names).map_err(|e| match e {
        TemplateError::Singular { monomial, .. } => TemplateError::Singular { instance, monomial },
        e => e,
    })?;
    let gopts = GroebnerOptions {
        deadline: deadline.copied(),
        ..GroebnerOptions::default()
    };
    let gb = groebner_with(t.nvars, &eqs, &gopts)?;
    let b = standard_monomials(&gb)?;
    let gm = gb_action_matrix(&gb, &b, &t.action, deadline)?;
    let charpoly_of = |m: &[Vec<u32>]| charpoly_within::<P>(m, deadline).map_err(budget_error);
    let (template_cp, quotient_cp) = (charpoly_of(&tm)?, charpoly_of(&gm)?);
    // A redundant basis (more monomials than solutions, `redundant.rs`) adds spurious
    // eigenvalues: the quotient's characteristic polynomial must divide the template's.
    let agrees = if tm.len() > gm.len() {
        poly_gcd::<P>(&template_cp, &quotient_cp) == quotient_cp
    } else {
        template_cp == quotient_cp
    };
    if !agrees {
        return Err(TemplateError::CharpolyMismatch { instance });
    }
    // The linear read-outs, from the template's basis to the Gröbner basis's: NF(x_i) must
    // be sum_k r_k NF(basis_k).
    if !readouts.is_empty() {
        let gb_idx: BTreeMap<&Monomial, usize> =
            b.iter().enumerate().map(|(i, m)| (m, i)).collect();
        let nf = |m: &Monomial| {
            gb.normal_form(&Poly::term(m.clone(), Fp::<P>::one()))
                .map(|p| coordinates(&p, &gb_idx))
        };
        let change: Vec<Vec<u32>> = t.basis.iter().map(nf).collect::<Result<_, _>>()?;
        for (x, r) in t.linear_readouts().iter().zip(&readouts) {
            let mut via_template = vec![0u32; b.len()];
            for (rk, row) in r.iter().zip(&change) {
                for (acc, &c) in via_template.iter_mut().zip(row) {
                    *acc = addmod::<P>(*acc, mulmod::<P>(*rk, c));
                }
            }
            if via_template != nf(x)? {
                return Err(TemplateError::ReadoutMismatch {
                    instance,
                    unknown: x.display_with(&names),
                });
            }
        }
    }
    Ok(())
}

/// Validates a template on `n` fresh random instances (even-numbered mod P1, odd mod P2,
/// all drawn from `seed`): the characteristic polynomial of the template's action matrix
/// must equal that of the Gröbner normal-form action matrix. Also runs [`check_readoff`].
pub fn validate<S: InstanceSource>(
    t: &EliminationTemplate,
    src: &S,
    n: usize,
    seed: u64,
) -> Result<ValidationReport, TemplateError> {
    validate_within(t, src, n, seed, None)
}

/// [`validate`] within a budget: at least two instances (one per prime) are always
/// checked, whatever the budget; further ones only while less than half the time budget
/// has been spent (the report gives the number checked).
pub fn validate_within<S: InstanceSource>(
    t: &EliminationTemplate,
    src: &S,
    n: usize,
    seed: u64,
    deadline: Option<&Deadline>,
) -> Result<ValidationReport, TemplateError> {
    check_readoff(t, &src.var_names())?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut done = 0;
    for i in 0..n {
        if i >= 2 {
            if let Some(d) = deadline {
                if d.elapsed() > d.budget().max_seconds / 2.0 {
                    break;
                }
            }
        }
        let limit = if i < 2 { None } else { deadline };
        if i % 2 == 0 {
            check_one::<P1, S>(t, src, &mut rng, i, limit)?;
        } else {
            check_one::<P2, S>(t, src, &mut rng, i, limit)?;
        }
        done += 1;
    }
    Ok(ValidationReport { instances: done })
}
