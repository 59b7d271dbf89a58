//! The options of the template search, read by every stage of it.

use crate::budget::Budget;
use crate::problem::{PolynomialSaturation, ProblemOptions};

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
    /// Number of fresh instances [`crate::pipeline::find_template`] validates the chosen
    /// template on.
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
    /// Also try the standard bases of grevlex under other variable orders (the orders of
    /// [`super::select::basis_orders`]; one Gröbner basis each on the analysis instance),
    /// keeping, for each action, the smallest template. On by default; off with
    /// `basis = standard`.
    pub alternative_bases: bool,
    /// How many weighted monomial orders with new standard bases to also try, beyond the
    /// grid of weights 1 and 2 that small problems get (their standard bases, with candidate
    /// pools graded by the same weights; see [`super::search`]); 32 by default, 0 turns
    /// weighted orders off.
    pub weighted_orders: usize,
    /// Weight vectors whose weighted orders are tried before all others (one weight from 1
    /// to [`crate::groebner::MAX_WEIGHT`] per unknown of the system the template is built
    /// for, in variable order, as `inspect` lists them; others are an error): an order
    /// known to be good, from a paper say. Their templates
    /// are built even where their standard basis is one seen before, since the candidate
    /// pools are graded by the weights. Empty by default.
    pub weights: Vec<Vec<u32>>,
    /// Rebuild the chosen template with the greedy exclusion of candidate rows
    /// (`super::exclude`) and keep it when it has fewer rows. On by default.
    pub exclude_monomials: bool,
    /// Let the chosen template's basis grow past the solution count when that makes the
    /// template smaller (see `super::redundant`; the solver then drops the spurious
    /// eigenvalues by their residual, and the plan keeps the basis only where it measures
    /// no lost solution). Off by default: the larger eigenvalue problem makes the emitted
    /// solvers slower than the smaller template makes them faster.
    pub redundant_bases: bool,
    /// Also try the Laurent actions `1 / x_v` of the unknowns tried as actions, each on
    /// the quotient basis times `x_v` (see [`super::Action::inverse_of_var`]); the
    /// template of an unknown and of its inverse are compared like any two actions'. Off
    /// by default: on a quotient basis the inverse's template has not been smaller than the
    /// unknown's on any problem measured (docs/BENCHMARK.md), and it doubles the actions
    /// searched. `option action = 1/x` asks for one alone. With
    /// [`TemplateOptions::redundant_bases`] they are searched whatever this says: a
    /// redundant basis grown on an inverse's template can be smaller than any grown on an
    /// unknown's.
    pub laurent_actions: bool,
    /// Also build templates from the equations row-reduced on their data (see
    /// [`super::reduction`]; every action and basis again) and keep the smaller. On by
    /// default.
    pub reduce_equations: bool,
    /// Only templates of the equations row-reduced on their data (with
    /// [`TemplateOptions::reduce_equations`]): the pipeline sets it for systems whose
    /// equations differ in scale by construction (the minors of an eliminated block whose
    /// rows were reduced fraction-free, `crate::eliminate::BlockReduction::rest_pivots`,
    /// carry products of the reduction's pivots in their coefficients); the solver's
    /// reduction brings every equation to a unit pivot first. Off by default.
    pub reduced_equations_only: bool,
    /// How a `nonzero` polynomial with constant coefficients is saturated (see
    /// [`PolynomialSaturation`]); both ways, the smaller kept, by default.
    pub polynomial_saturation: PolynomialSaturation,
    /// Seed of all random choices (instances).
    pub seed: u64,
    /// Options that override those of the problem file (`option NAME = VALUE`) when the
    /// pipeline applies them (`crate::pipeline::plan`); set by the command line.
    pub overrides: ProblemOptions,
    /// Number of hidden variables (the last ones, from `nonzero`), which the template need
    /// not read off; [`crate::pipeline::find_template`] fills it from its source.
    pub hidden_vars: usize,
    /// Names of the unknowns, in variable order, for messages; empty renders them as
    /// `x0, x1, ...`. [`crate::pipeline::find_template`] fills them from its source.
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
            alternative_bases: true,
            weighted_orders: 32,
            weights: Vec::new(),
            exclude_monomials: true,
            redundant_bases: false,
            laurent_actions: false,
            reduce_equations: true,
            reduced_equations_only: false,
            polynomial_saturation: PolynomialSaturation::Smaller,
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
    /// eigenvalues, also a random linear combination of the unknowns ([`super::Action::random`]).
    #[default]
    Auto,
    /// These unknowns (variable indices) only, and their inverses when
    /// [`TemplateOptions::laurent_actions`].
    Unknowns(Vec<usize>),
    /// The Laurent action `1 / x_v` of this unknown (variable index) only.
    Inverse(usize),
    /// A random linear combination of the unknowns only.
    Random,
}
