//! The error of every template stage (search, build, validation, fill), in a module of
//! its own so that each stage can return it without depending on another.

use super::reduction::ReductionError;
use super::ShapeError;
use crate::budget::Exhausted;
use crate::groebner::GroebnerError;
use crate::quotient::AnalysisError;
use thiserror::Error;

/// Failures of template construction and validation.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum TemplateError {
    /// Counting solutions failed.
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    /// A Gröbner basis computation failed (during validation), or a weighted order of
    /// [`super::TemplateOptions::weights`] is not one the computation takes.
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
    /// The quotient basis lacks 1, or an unknown is neither in it nor a reducible column:
    /// solutions cannot be read off eigenvectors.
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
    /// The polynomial a template's columns are shifted by has a denominator that vanishes
    /// in the field of the instance.
    #[error("the template's shift polynomial has a denominator divisible by the field's prime")]
    ShiftNotInField,
    /// On some validation instance, a reducible column is not a pivot column.
    #[error("validation instance {instance}: reducible monomial {monomial} is not reducible by the template")]
    Singular {
        /// Instance number.
        instance: usize,
        /// Rendered monomial.
        monomial: String,
    },
    /// The template's linear read-out of an unknown disagrees with its Gröbner normal form.
    #[error("validation instance {instance}: the template's read-out of {unknown} differs from its Gröbner normal form")]
    ReadoutMismatch {
        /// Instance number.
        instance: usize,
        /// The unknown (rendered).
        unknown: String,
    },
    /// Template and Gröbner action matrices disagree.
    #[error("validation instance {instance}: characteristic polynomials of the template and Gröbner action matrices differ")]
    CharpolyMismatch {
        /// Instance number.
        instance: usize,
    },
    /// An instance's equations cannot be row-reduced as the template's
    /// [`super::EquationReduction`] plans.
    #[error("equation reduction: {0}")]
    Reduction(#[from] ReductionError),
    /// No action variable was given or none works.
    #[error("no usable action variable: {reasons}")]
    NoAction {
        /// Why each action failed, one clause per distinct reason.
        reasons: String,
        /// The budget that stopped the first action stopped by one, if any did.
        exhausted: Option<Exhausted>,
    },
    /// A Laurent action `1 / x` where `x` is zero on a solution (its multiplication
    /// matrix on the quotient is singular): no template can reduce by it.
    #[error("the unknown of {action} is zero on a solution, where {action} is undefined")]
    NotInvertible {
        /// The action (rendered).
        action: String,
    },
    /// The template cannot be solved by elimination and eigenvectors.
    #[error(transparent)]
    Shape(#[from] ShapeError),
    /// The budget ran out in a step that has no degree to report (the characteristic
    /// polynomial of an action matrix, the memory of the action matrices).
    #[error("{step}: {exhausted}")]
    Budget {
        /// The step that was stopped.
        step: String,
        /// Which limit ran out.
        exhausted: Exhausted,
    },
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

    /// The budget that stopped the search, if a budget did.
    pub fn exhausted(&self) -> Option<Exhausted> {
        match self {
            TemplateError::Budget { exhausted, .. } => Some(*exhausted),
            TemplateError::NotReducible { exhausted, .. }
            | TemplateError::NoAction { exhausted, .. } => *exhausted,
            TemplateError::Groebner(GroebnerError::Budget { exhausted, .. })
            | TemplateError::Analysis(AnalysisError::Groebner {
                source: GroebnerError::Budget { exhausted, .. },
                ..
            }) => Some(*exhausted),
            TemplateError::Counted { source, .. } => source.exhausted(),
            _ => None,
        }
    }
}
