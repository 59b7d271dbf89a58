//! The one test of whether a template can be solved as the emitted solvers solve it, and
//! the shape of the matrix they eliminate.
//!
//! The emitted solver, the interpreter behind `audit` and the validation mod p all
//! eliminate the same matrix: the template without its dependent excess columns (see
//! [`EliminationTemplate::n_dependent`]), whose first [`EliminationTemplate::pivot_columns`]
//! columns must all become pivots. [`EliminationTemplate::check_emittable`] is the
//! predicate `inspect`, `audit` and `generate` share.

use super::EliminationTemplate;
use crate::algebra::Monomial;
use std::collections::{BTreeSet, HashMap};
use thiserror::Error;

/// Why a template cannot be solved by elimination and eigenvectors (its fields disagree
/// with the convention of `crate::template`). Monomials are rendered with the given names.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ShapeError {
    /// The column blocks do not add up or the last block is not the basis.
    #[error("malformed template: {0}")]
    Malformed(String),
    /// `action * b` is neither a basis monomial nor a reducible column.
    #[error("action * {basis} = {product} is neither in the basis nor a reducible column")]
    ActionNotCovered {
        /// The basis monomial b.
        basis: String,
        /// The product.
        product: String,
    },
    /// Fewer rows than columns to eliminate.
    #[error(
        "{rows} rows cannot eliminate {excess} independent excess + {reducible} reducible columns"
    )]
    TooFewRows {
        /// Template rows.
        rows: usize,
        /// Excess columns that are eliminated (dependent ones excluded).
        excess: usize,
        /// Reducible columns.
        reducible: usize,
    },
    /// The basis lacks 1, so solutions cannot be read off eigenvectors.
    #[error(
        "the quotient basis does not contain {0}: solutions cannot be read off the eigenvectors"
    )]
    BasisLacks(String),
    /// An unknown outside the basis is not a reducible column, so it cannot be read off
    /// through its reduced row.
    #[error("the unknown {0} is neither in the quotient basis nor a reducible column: it cannot be read off the eigenvectors")]
    ReadoutNotReducible(String),
}

impl EliminationTemplate {
    /// Number of columns the elimination turns into pivots: the independent excess columns
    /// and the reducible ones, less the columns of a [`EliminationTemplate::fold`].
    pub fn pivot_columns(&self) -> usize {
        self.filled_pivot_columns() - self.folded_rows()
    }

    /// `(rows, cols)` of the matrix that is eliminated: the template without its dependent
    /// excess columns and, when it has a [`EliminationTemplate::fold`], without its constant
    /// rows and their pivot columns (the Schur complement). This is the size of the emitted
    /// solver's template.
    pub fn eliminated_size(&self) -> (usize, usize) {
        let (r, c) = self.filled_size();
        let k = self.folded_rows();
        (r - k, c - k)
    }

    /// The column of the eliminated matrix that template column `col` becomes, or `None`
    /// for a dependent excess column (left out) or a folded constant row's pivot column.
    pub fn eliminated_column(&self, col: usize) -> Option<usize> {
        self.filled_column(col)
            .and_then(|c| c.checked_sub(self.folded_rows()))
    }

    /// The first row of the eliminated matrix that is not an excess row: the number of its
    /// independent excess columns.
    pub fn first_reduced_row(&self) -> usize {
        self.n_excess - self.n_dependent - self.folded_rows()
    }

    /// How many rows [`EliminationTemplate::fold`] eliminates, its constant block's and
    /// its pivot rows (0 without one).
    pub fn folded_rows(&self) -> usize {
        self.fold.as_ref().map_or(0, |f| f.rows + f.pivot_inv.len())
    }

    /// `(rows, cols)` of the matrix the solver fills, before a fold: the template without
    /// its dependent excess columns (every row, the constant ones included).
    pub fn filled_size(&self) -> (usize, usize) {
        (
            self.rows.len(),
            self.columns.len().saturating_sub(self.n_dependent),
        )
    }

    /// The column of the filled matrix ([`EliminationTemplate::filled_size`]) that template
    /// column `col` becomes, or `None` for a dependent excess column.
    pub fn filled_column(&self, col: usize) -> Option<usize> {
        let first_dependent = self.n_excess.saturating_sub(self.n_dependent);
        if col < first_dependent {
            Some(col)
        } else if col < self.n_excess {
            None
        } else {
            Some(col - self.n_dependent)
        }
    }

    /// [`EliminationTemplate::pivot_columns`] of the filled matrix (before a fold).
    pub fn filled_pivot_columns(&self) -> usize {
        (self.n_excess + self.n_reducible).saturating_sub(self.n_dependent)
    }

    /// Whether the elimination, the action matrix and the read-out of the solutions are
    /// well defined: the column blocks are consistent, the reducible block is exactly the
    /// products `action * b` outside the basis and the unknowns outside it, there are at
    /// least as many rows as columns to eliminate, and the basis contains 1. `names`
    /// renders monomials in messages (template variables in order).
    pub fn check_emittable(&self, names: &[String]) -> Result<(), ShapeError> {
        let bad = |s: String| Err(ShapeError::Malformed(s));
        let show = |m: &Monomial| m.display_with(names);
        let nb = self.basis.len();
        let npiv = self.n_excess + self.n_reducible;
        if nb == 0 {
            return bad("the quotient basis is empty".into());
        }
        if self.columns.len() != npiv + nb {
            return bad(format!(
                "{} columns but {} excess + {} reducible + {} basis",
                self.columns.len(),
                self.n_excess,
                self.n_reducible,
                nb
            ));
        }
        if self.n_dependent > self.n_excess {
            return bad(format!(
                "{} dependent columns but {} excess columns",
                self.n_dependent, self.n_excess
            ));
        }
        if self.columns[npiv..] != self.basis[..] {
            return bad("the last block of columns is not the basis (in basis order)".into());
        }
        let monomials = self
            .columns
            .iter()
            .chain(self.rows.iter().map(|r| &r.multiplier));
        if self.action.nvars() != self.nvars {
            return bad(format!(
                "the action has {} variables, the template {}",
                self.action.nvars(),
                self.nvars
            ));
        }
        if let Some(m) = monomials.clone().find(|m| m.nvars() != self.nvars) {
            return bad(format!(
                "monomial {m:?} has {} variables, the template {}",
                m.nvars(),
                self.nvars
            ));
        }
        let mut column_of = HashMap::new();
        for (i, m) in self.columns.iter().enumerate() {
            if column_of.insert(m, i).is_some() {
                return bad(format!("column {} appears twice", show(m)));
            }
        }
        if !self.basis.contains(&self.unit()) {
            return Err(ShapeError::BasisLacks("1".into()));
        }
        let mut needed = BTreeSet::new();
        // Unknowns outside the basis: the linear read-out from their reduced rows.
        for m in self.linear_readouts() {
            match column_of.get(&m) {
                Some(&c) if c >= self.n_excess && c < npiv => {
                    needed.insert(c);
                }
                _ => return Err(ShapeError::ReadoutNotReducible(show(&m))),
            }
        }
        if !self.flipped.is_empty() {
            let increasing = self.flipped.windows(2).all(|w| w[0] < w[1]);
            if !increasing || self.flipped.last().is_some_and(|&j| j >= self.basis.len()) {
                return bad("flipped relations are not increasing basis indices".into());
            }
        }
        for (j, b) in self.basis.iter().enumerate() {
            let flipped = self.flipped.binary_search(&j).is_ok();
            if flipped && self.action.inverse_product(b).is_none() {
                return Err(ShapeError::ActionNotCovered {
                    basis: show(b),
                    product: format!("{} / ({})", show(b), self.action.display_with(names)),
                });
            }
            if !flipped && !self.action.applies_to(b) {
                return Err(ShapeError::ActionNotCovered {
                    basis: show(b),
                    product: format!("{} / {}", show(b), show(&self.unit())),
                });
            }
            for (p, _) in self.relation(j) {
                match column_of.get(&p) {
                    Some(&c) if c >= npiv => {}
                    Some(&c) if c >= self.n_excess => {
                        needed.insert(c);
                    }
                    _ => {
                        return Err(ShapeError::ActionNotCovered {
                            basis: show(b),
                            product: show(&p),
                        })
                    }
                }
            }
        }
        if needed.len() != self.n_reducible {
            return bad(format!(
                "{} reducible columns but {} products action * b and unknowns fall outside the basis",
                self.n_reducible,
                needed.len()
            ));
        }
        if self.rows.len() < self.pivot_columns() {
            return Err(ShapeError::TooFewRows {
                rows: self.rows.len(),
                excess: self.n_excess - self.n_dependent,
                reducible: self.n_reducible,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::template::TemplateRow;

    /// A hand-built template in x, y with basis (y, x, 1) and action x, so that each
    /// failure mode can be produced by editing a field.
    fn toy() -> EliminationTemplate {
        let m = |e: [u16; 2]| Monomial(e.to_vec());
        EliminationTemplate {
            nvars: 2,
            rows: vec![
                TemplateRow {
                    equation: 0,
                    multiplier: m([0, 0]),
                },
                TemplateRow {
                    equation: 1,
                    multiplier: m([0, 0]),
                },
            ],
            columns: vec![
                m([0, 2]),
                m([2, 0]),
                m([1, 1]),
                m([0, 1]),
                m([1, 0]),
                m([0, 0]),
            ],
            n_excess: 1,
            n_reducible: 2,
            n_dependent: 0,
            n_hidden: 0,
            basis: vec![m([0, 1]), m([1, 0]), m([0, 0])],
            action: super::super::Action::var(2, 0),
            sparse: None,
            unrolled: None,
            reduction: None,
            fold: None,
            shift: None,
            spurious_eigenvalues: 0,
            flipped: Vec::new(),
        }
    }

    fn names() -> Vec<String> {
        vec!["x".into(), "y".into()]
    }

    #[test]
    fn rows_are_counted_without_dependent_columns() {
        let mut t = toy();
        assert_eq!(
            t.check_emittable(&names()),
            Err(ShapeError::TooFewRows {
                rows: 2,
                excess: 1,
                reducible: 2
            })
        );
        t.n_dependent = 1;
        assert_eq!(t.check_emittable(&names()), Ok(()));
        assert_eq!(t.pivot_columns(), 2);
        assert_eq!(t.eliminated_size(), (2, 5));
        assert_eq!(t.eliminated_column(0), None);
        assert_eq!(t.eliminated_column(1), Some(0));
        assert_eq!(t.eliminated_column(5), Some(4));
    }

    #[test]
    fn failures_name_the_monomials() {
        let mut t = toy();
        t.n_dependent = 1;
        t.basis[0] = Monomial(vec![0, 2]);
        let n = t.columns.len();
        t.columns[n - 3] = Monomial(vec![0, 2]);
        t.columns[0] = Monomial(vec![0, 3]);
        assert_eq!(
            t.check_emittable(&names()),
            Err(ShapeError::ReadoutNotReducible("y".into()))
        );
        t.basis[0] = Monomial(vec![0, 1]);
        t.columns[n - 3] = Monomial(vec![0, 1]);
        t.action = super::super::Action::var(2, 1);
        let e = t.check_emittable(&names()).unwrap_err();
        assert!(e.to_string().contains("y^2"), "{e}");
        let mut t = toy();
        t.n_dependent = 2;
        assert!(matches!(
            t.check_emittable(&names()),
            Err(ShapeError::Malformed(_))
        ));
    }
}
