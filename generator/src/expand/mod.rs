//! A checked problem and its evaluation: over any [`Ring`] (the equations as polynomials in
//! the unknowns with coefficients in the ring), symbolically ([`Problem::expand`]: exact
//! polynomial coefficients in the data), and directly in `f64` matrices (an independent
//! check).
//!
//! Evaluation walks the checked tape (see [`crate::lang::check`]) with small matrices whose
//! entries are polynomials: no strings, no parsing, each shared subexpression computed once.
//! `tape.rs` is that walk (matrices, the budget guard); `laurent.rs` the reciprocals of
//! unknowns and the shifts that clear them.

use crate::algebra::{Exponent, Fp, Monomial, Poly, Ring, P1, Q};
use crate::budget::{Budget, Deadline, Exhausted, DEFAULT_MAX_MEMORY_MB, DEFAULT_MAX_SECONDS};

/// The budget of the evaluations [`Problem::parse`] makes: the command line's defaults.
fn default_parse_budget() -> Budget {
    Budget::new(DEFAULT_MAX_SECONDS, DEFAULT_MAX_MEMORY_MB)
}
use crate::lang::check::{Checked, Node, NodeId, Op, Shape};
use crate::lang::{self, LangError};
use crate::problem::ProblemLayout;
use std::collections::BTreeMap;
use std::path::Path;

mod laurent;
mod tape;

use laurent::Laurent;
use tape::*;

/// A parsed and checked problem.
#[derive(Clone, Debug)]
pub struct Problem {
    /// Its symbols (unknowns, typed data, eliminated unknowns).
    pub layout: ProblemLayout,
    checked: Checked,
    /// Whether each tape node is needed by some equation or `nonzero` expression.
    needed: Vec<bool>,
    /// The expression of each `nonzero` statement (its tape node), in source order.
    nonzero: Vec<NodeId>,
    /// `divisions[i][k]`: how many times equation `i` of the system (after elimination) is
    /// divided by the k-th `nonzero` expression (see [`Problem::with_divisions`]).
    divisions: Vec<Vec<u32>>,
    /// The equations of the system (after elimination and division) that are kept, in
    /// order; `None`: all (see [`Problem::with_independent`]).
    independent: Option<Vec<usize>>,
    /// The affine equations whose unknowns `layout.eliminate` are substituted into the
    /// others (see [`Problem::with_substitution`]); `None`: `eliminate` takes minors.
    substitution: Option<(Vec<usize>, Vec<usize>)>,
    /// The data row reduction that `eliminate` uses instead of the block's maximal minors
    /// (see [`Problem::with_block_reduction`]); `None`: the minors.
    block_reduction: Option<crate::eliminate::BlockReduction>,
    /// Sign folds applied to the system, in order (see [`Problem::with_sign_fold`]).
    sign_folds: Vec<crate::symmetry::SignFold>,
    /// Laurent equations (`x^-1`, `e / x`): see [`Laurent`]; empty when there are none.
    laurent: Laurent,
}

/// Failure to load a problem file.
#[derive(Debug, thiserror::Error)]
pub enum ProblemError {
    /// The file could not be read.
    #[error("{path}: cannot read the problem file: {source}")]
    Io {
        /// The path as given.
        path: String,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The file is malformed.
    #[error(transparent)]
    Lang(#[from] LangError),
}

/// Failure to evaluate a problem over a ring.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EvalError {
    /// The data vector has the wrong length.
    #[error("expected {expected} data values (one per slot), found {found}")]
    DataLength {
        /// `layout.data_slot_count()`.
        expected: usize,
        /// What was given.
        found: usize,
    },
    /// The unknowns vector has the wrong length.
    #[error("expected {expected} unknown values, found {found}")]
    UnknownLength {
        /// `layout.unknown_count()`.
        expected: usize,
        /// What was given.
        found: usize,
    },
    /// A literal has no image in the ring (a denominator divisible by p in Z_p).
    #[error("the constant {0} has no image in this ring")]
    Constant(Q),
    /// The expansion would pass the time or memory budget.
    #[error("expanding the equations: {0}")]
    Budget(Exhausted),
}

/// The largest problem file read, in bytes: far above any minimal problem, small enough to
/// hold in memory.
pub const MAX_PROBLEM_FILE_BYTES: u64 = 16 << 20;

/// A problem file's text: a regular file (a FIFO or device is refused, since reading one
/// may wait forever for a writer) of at most [`MAX_PROBLEM_FILE_BYTES`].
pub(crate) fn read_problem_text(path: &Path) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind, Read};
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "not a regular file (a directory, FIFO or device); give the problem file itself",
        ));
    }
    let too_large = || {
        Error::new(
            ErrorKind::InvalidData,
            format!(
                "larger than {} MiB, the most a problem file may have",
                MAX_PROBLEM_FILE_BYTES >> 20
            ),
        )
    };
    if meta.len() > MAX_PROBLEM_FILE_BYTES {
        return Err(too_large());
    }
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(MAX_PROBLEM_FILE_BYTES + 1)
        .read_to_string(&mut text)?;
    if text.len() as u64 > MAX_PROBLEM_FILE_BYTES {
        return Err(too_large());
    }
    Ok(text)
}

impl Problem {
    /// Parses and checks a problem's source; errors carry `file_name`. Equations with
    /// reciprocals of unknowns are evaluated twice to find their shifts, within the
    /// command line's default budget ([`Problem::parse_within`] takes another).
    pub fn parse(source: &str, file_name: &str) -> Result<Problem, LangError> {
        Problem::parse_within(source, file_name, default_parse_budget())
    }

    /// [`Problem::parse`] with the evaluations of Laurent equations within `budget`.
    pub fn parse_within(
        source: &str,
        file_name: &str,
        budget: Budget,
    ) -> Result<Problem, LangError> {
        let checked = lang::compile(source).map_err(|e| e.in_file(file_name))?;
        Problem::from_checked(checked, budget).map_err(|e| e.in_file(file_name))
    }

    /// Reads, parses and checks a problem file: a regular file of at most
    /// [`MAX_PROBLEM_FILE_BYTES`] (a FIFO, device or directory is an `Io` error).
    pub fn from_file(path: impl AsRef<Path>) -> Result<Problem, ProblemError> {
        Problem::from_file_within(path, default_parse_budget())
    }

    /// [`Problem::from_file`] with the evaluations of Laurent equations within `budget`.
    pub fn from_file_within(
        path: impl AsRef<Path>,
        budget: Budget,
    ) -> Result<Problem, ProblemError> {
        let path = path.as_ref();
        let shown = path.display().to_string();
        let source = read_problem_text(path).map_err(|source| ProblemError::Io {
            path: shown.clone(),
            source,
        })?;
        Ok(Problem::parse_within(&source, &shown, budget)?)
    }

    fn from_checked(checked: Checked, budget: Budget) -> Result<Problem, LangError> {
        // `nonzero EXPR` is the equation `u * EXPR - 1` of a hidden unknown u, one per
        // statement, after all others (see `lang::check`).
        let hidden = checked.layout.hidden_count();
        let first = checked.equations.len().saturating_sub(hidden);
        let nonzero = checked.equations[first..]
            .iter()
            .filter_map(|eq| saturated_expression(&checked.nodes, eq.node))
            .collect();
        Problem::with_needed(checked, nonzero, Vec::new()).with_laurent(budget)
    }

    fn with_needed(checked: Checked, nonzero: Vec<NodeId>, divisions: Vec<Vec<u32>>) -> Problem {
        let mut needed = vec![false; checked.nodes.len()];
        let mut stack: Vec<NodeId> = checked.equations.iter().map(|e| e.node).collect();
        stack.extend(&nonzero);
        while let Some(n) = stack.pop() {
            if needed[n] {
                continue;
            }
            needed[n] = true;
            match &checked.nodes[n].op {
                Op::Const(_) | Op::Unknown(_) | Op::Data(_) | Op::Recip(_) | Op::Identity => {}
                Op::Build(_, e) => stack.extend(e),
                Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => stack.extend([*a, *b]),
                Op::Neg(a)
                | Op::Transpose(a)
                | Op::Skew(a)
                | Op::Det(a)
                | Op::Trace(a)
                | Op::Entry(a, _, _) => stack.push(*a),
            }
        }
        Problem {
            layout: checked.layout.clone(),
            checked,
            needed,
            nonzero,
            divisions,
            independent: None,
            substitution: None,
            block_reduction: None,
            sign_folds: Vec::new(),
            laurent: Laurent::default(),
        }
    }

    /// Finds the reciprocals of unknowns in the needed tape and each equation's shift
    /// ([`Laurent`]); nothing when there are none. The shifts come from two evaluations
    /// within `budget`, and an expansion past it is an error of the file.
    fn with_laurent(mut self, budget: Budget) -> Result<Problem, LangError> {
        let mut inverted: Vec<usize> = self
            .checked
            .nodes
            .iter()
            .zip(&self.needed)
            .filter_map(|(node, &needed)| match node.op {
                Op::Recip(i) if needed => Some(i),
                _ => None,
            })
            .collect();
        inverted.sort_unstable();
        inverted.dedup();
        if inverted.is_empty() {
            return Ok(self);
        }
        self.laurent.inverted = inverted;
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(0x1au64);
        let deadline = budget.start();
        let mut instances: Vec<Vec<Poly<Fp<P1>>>> = Vec::new();
        for _ in 0..2 {
            let data = crate::instance::random_data_fp::<P1>(&self.layout, &mut rng);
            match self.tape_values_within(&data, Some(&deadline)) {
                Ok((n, vals)) => instances.push(
                    self.checked
                        .equations
                        .iter()
                        .map(|eq| entry_poly(&vals, eq.node, eq.row, eq.col, n))
                        .collect(),
                ),
                Err(e @ EvalError::Budget(_)) => {
                    let line = self.checked.equations.first().map_or(1, |eq| eq.line);
                    return Err(LangError::new(
                        lang::Pos { line, column: 1 },
                        format!("the equations with reciprocals of unknowns: {e}"),
                    ));
                }
                // Planning reports the constant on the instances it evaluates.
                Err(_) => {}
            }
        }
        let nu = self.layout.unknown_count();
        self.laurent.shifts_from(nu, &instances);
        Ok(self)
    }

    /// The number of `nonzero` statements.
    pub fn nonzero_count(&self) -> usize {
        self.nonzero.len()
    }

    /// Whether `nonzero` is imposed by saturation (a hidden unknown per statement); false
    /// after [`Problem::without_saturation`].
    pub fn is_saturated(&self) -> bool {
        self.layout.hidden_count() > 0
    }

    /// The same problem without the saturating equations and their hidden unknowns: the
    /// `nonzero` expressions are kept only as divisors ([`Problem::with_divisions`]). Its
    /// solutions include those where an expression vanishes, unless dividing removed them.
    pub fn without_saturation(&self) -> Problem {
        let hidden = self.layout.hidden_count();
        let mut checked = self.checked.clone();
        let keep = checked.equations.len().saturating_sub(hidden);
        checked.equations.truncate(keep);
        checked.layout.unknowns.retain(|u| !u.hidden);
        let mut p = Problem::with_needed(checked, self.nonzero.clone(), self.divisions.clone());
        p.laurent = self.laurent.clone();
        p.laurent.shifts.truncate(keep);
        p.layout = self.layout.clone();
        p.layout.unknowns.retain(|u| !u.hidden);
        // Hidden unknowns come last and never enter the block of an elimination.
        let n = p.layout.unknown_count();
        p.block_reduction = self.block_reduction.clone().map(|mut b| {
            for m in &mut b.columns {
                m.0.truncate(n);
            }
            b
        });
        p
    }

    /// The same problem with equation `i` of its system (after elimination) divided
    /// `divisions[i][k]` times by the k-th `nonzero` expression. Planning chooses the counts
    /// where the division is exact on the whole data family (`rewrite::nonzero_divisions`):
    /// the expression does not vanish at a solution, so the divided system has the same
    /// solutions with smaller degrees.
    pub fn with_divisions(&self, divisions: Vec<Vec<u32>>) -> Problem {
        let mut p = self.clone();
        p.divisions = divisions;
        p
    }

    /// See [`Problem::with_divisions`] (empty when nothing is divided).
    pub fn divisions(&self) -> &[Vec<u32>] {
        &self.divisions
    }

    /// The same problem keeping only equations `kept` (indices, increasing) of its system
    /// after elimination and division: planning drops those that are linear combinations
    /// of the others on the whole data family (`crate::independent`), which changes
    /// neither the ideal nor the solutions.
    pub fn with_independent(&self, kept: Vec<usize>) -> Problem {
        let mut p = self.clone();
        p.independent = Some(kept);
        p
    }

    /// The same problem with the unknowns `pivots` (flat indices) solved from the affine
    /// equations `linear` (indices into the problem's equations) by Cramer's rule and
    /// substituted into the others but `implied` (affine equations that are combinations
    /// of `linear`; [`crate::eliminate::substitute_linear`]); the solver recovers them as
    /// the null vector of the affine equations at each solution. Planning chooses them
    /// where the solution count stays the same.
    pub fn with_substitution(
        &self,
        pivots: Vec<usize>,
        linear: Vec<usize>,
        implied: Vec<usize>,
    ) -> Problem {
        let mut p = self.clone();
        p.layout.eliminate = pivots;
        p.substitution = Some((linear, implied));
        p
    }

    /// The same problem with `eliminate` reducing the block of equations linear in the
    /// eliminated unknowns by `reduction` (a pivot block of its data coefficient matrix,
    /// [`crate::eliminate::reduce_block`]) instead of taking the block's maximal minors.
    /// Planning chooses it where those minors have a spurious component or the eliminated
    /// unknowns enter other equations non-linearly.
    pub fn with_block_reduction(&self, reduction: crate::eliminate::BlockReduction) -> Problem {
        let mut p = self.clone();
        p.block_reduction = Some(reduction);
        p
    }

    /// See [`Problem::with_block_reduction`].
    pub fn block_reduction(&self) -> Option<&crate::eliminate::BlockReduction> {
        self.block_reduction.as_ref()
    }

    /// The same problem with its system folded by `fold` after the folds it has
    /// (`crate::symmetry`): the system's variables keep their positions, the pivot standing
    /// for its square and the scaled ones for their ratios to it. Planning chooses folds
    /// where every equation is even or odd in the fold's variables and the count halves.
    pub fn with_sign_fold(&self, fold: crate::symmetry::SignFold) -> Problem {
        let mut p = self.clone();
        p.sign_folds.push(fold);
        p
    }

    /// See [`Problem::with_sign_fold`] (empty: the system as evaluated).
    pub fn sign_folds(&self) -> &[crate::symmetry::SignFold] {
        &self.sign_folds
    }

    /// See [`Problem::with_substitution`]: the solved and the implied affine equations.
    pub fn substitution(&self) -> Option<(&[usize], &[usize])> {
        self.substitution
            .as_ref()
            .map(|(l, i)| (l.as_slice(), i.as_slice()))
    }

    /// See [`Problem::with_independent`] (`None`: every equation is kept).
    pub fn independent(&self) -> Option<&[usize]> {
        self.independent.as_deref()
    }

    /// Each `nonzero` expression as a polynomial in the declared (not hidden) unknowns,
    /// the data slots replaced by `data`.
    pub fn nonzero_expressions<C: Ring>(&self, data: &[C]) -> Result<Vec<Poly<C>>, EvalError> {
        let (n, vals) = self.tape_values(data)?;
        Ok(self.nonzero_from(&vals, n))
    }

    /// [`Problem::try_evaluate`] and [`Problem::nonzero_expressions`] from one evaluation
    /// of the tape.
    pub fn try_evaluate_with_nonzero<C: Ring>(
        &self,
        data: &[C],
    ) -> Result<EquationsAndNonzero<C>, EvalError> {
        let (n, vals) = self.tape_values(data)?;
        Ok((self.equations_from(&vals, n), self.nonzero_from(&vals, n)))
    }

    fn equations_from<C: Ring>(&self, vals: &TapeValues<C>, n: usize) -> Vec<Poly<C>> {
        let nu = self.layout.unknown_count();
        self.checked
            .equations
            .iter()
            .enumerate()
            .map(|(k, eq)| {
                self.laurent
                    .fold(entry_poly(vals, eq.node, eq.row, eq.col, n), nu, k)
            })
            .collect()
    }

    fn nonzero_from<C: Ring>(&self, vals: &TapeValues<C>, n: usize) -> Vec<Poly<C>> {
        let visible = n - self.laurent.inverted.len() - self.layout.hidden_count();
        self.nonzero
            .iter()
            .map(|&node| {
                // `nonzero` expressions are checked to be in the declared unknowns.
                entry_poly(vals, node, 0, 0, n)
                    .narrow(visible)
                    .unwrap_or_else(|| Poly::zero(visible))
            })
            .collect()
    }

    /// The values of the needed tape nodes at `data`, with the unknowns as the variables of
    /// polynomials in `layout.unknown_count()` variables (returned first).
    fn tape_values<C: Ring>(&self, data: &[C]) -> Result<(usize, TapeValues<C>), EvalError> {
        self.tape_values_within(data, None)
    }

    /// [`Problem::tape_values`] within `deadline`, if any (see [`Guard`]).
    fn tape_values_within<C: Ring>(
        &self,
        data: &[C],
        deadline: Option<&Deadline>,
    ) -> Result<(usize, TapeValues<C>), EvalError> {
        let expected = self.layout.data_slot_count();
        if data.len() != expected {
            return Err(EvalError::DataLength {
                expected,
                found: data.len(),
            });
        }
        let inverted = &self.laurent.inverted;
        let n = self.layout.unknown_count() + inverted.len();
        let guard = deadline.map(|d| Guard::new::<C>(d, n));
        Ok((
            n,
            run_mixed(
                &self.checked.nodes,
                &self.needed,
                n,
                inverted,
                data,
                guard.as_ref(),
            )?,
        ))
    }

    /// The problem's name.
    pub fn name(&self) -> &str {
        &self.layout.name
    }

    /// Number of scalar equations (a matrix equation counts one per entry).
    pub fn equation_count(&self) -> usize {
        self.checked.equations.len()
    }

    /// The source line of each scalar equation.
    pub fn equation_lines(&self) -> Vec<usize> {
        self.checked.equations.iter().map(|e| e.line).collect()
    }

    /// Names of the unknown scalars (`a1 a2 a3 t1 t2 t3`), see [`ProblemLayout::unknown_names`].
    pub fn unknown_names(&self) -> Vec<String> {
        self.layout.unknown_names()
    }

    /// Names of the data slots (`x1[0].x`, `R0[2][1]`), see
    /// [`ProblemLayout::data_slot_names`].
    pub fn data_slot_names(&self) -> Vec<String> {
        self.layout.data_slot_names()
    }

    /// Number of nodes of the checked tape (after sharing of common subexpressions).
    pub fn tape_len(&self) -> usize {
        self.checked.nodes.len()
    }

    /// Each scalar equation `lhs - rhs` as a polynomial in the unknown scalars
    /// (`layout.unknown_count()` variables), the data slots replaced by `data` (one value
    /// per slot in layout order; a point's third entry is the constant 1).
    pub fn try_evaluate<C: Ring>(&self, data: &[C]) -> Result<Vec<Poly<C>>, EvalError> {
        self.try_evaluate_within(data, None)
    }

    /// [`EvalError::Constant`] for the first literal the equations need that has no image
    /// in `C` (a denominator divisible by its characteristic): evaluation over `C` would
    /// fail on it.
    pub fn check_constants<C: Ring>(&self) -> Result<(), EvalError> {
        for (node, &needed) in self.checked.nodes.iter().zip(&self.needed) {
            if let (Op::Const(q), true) = (&node.op, needed) {
                if C::from_rational(q).is_none() {
                    return Err(EvalError::Constant(q.clone()));
                }
            }
        }
        Ok(())
    }

    /// [`Problem::try_evaluate`] within `deadline`, if any: [`EvalError::Budget`] once the
    /// time runs out or the polynomials' estimated memory would pass the budget (checked
    /// before each product of polynomials, so a product too large is never started).
    pub fn try_evaluate_within<C: Ring>(
        &self,
        data: &[C],
        deadline: Option<&Deadline>,
    ) -> Result<Vec<Poly<C>>, EvalError> {
        let (n, vals) = self.tape_values_within(data, deadline)?;
        Ok(self.equations_from(&vals, n))
    }

    /// [`Problem::try_evaluate`], panicking on a data vector of the wrong length or a
    /// literal with no image in `C` (a denominator divisible by p).
    pub fn evaluate<C: Ring>(&self, data: &[C]) -> Vec<Poly<C>> {
        self.try_evaluate(data)
            .unwrap_or_else(|e| panic!("evaluating problem {}: {e}", self.layout.name))
    }

    /// The exact symbolic expansion: each scalar equation as a polynomial in the unknowns
    /// whose coefficients are polynomials in the data slots (`layout.data_slot_count()`
    /// variables, numbered as in the layout) with rational coefficients.
    ///
    /// Equal to `evaluate::<Poly<Q>>` with `Poly::var(data_slot_count, i)` as data, but
    /// computed with flat polynomials in unknowns and data together (much faster) and then
    /// split.
    pub fn expand(&self) -> Vec<Poly<Poly<Q>>> {
        // Without a deadline nothing can run out, and rational constants always have an
        // image.
        self.expand_within(None).unwrap_or_default()
    }

    /// [`Problem::expand`] within `deadline`, if any ([`EvalError::Budget`] as for
    /// [`Problem::try_evaluate_within`]; with the data symbols as variables an expansion
    /// can be far larger than any instance's).
    pub fn expand_within(
        &self,
        deadline: Option<&Deadline>,
    ) -> Result<Vec<Poly<Poly<Q>>>, EvalError> {
        let nu = self.layout.unknown_count();
        let nd = self.layout.data_slot_count();
        let inverted = &self.laurent.inverted;
        let nr = inverted.len();
        let n = nu + nr + nd;
        let zero = Poly::zero(n);
        let one = Poly::constant(n, Q::from_integer(1.into()));
        let leaf = |op: &Op| {
            Ok(match op {
                Op::Const(q) => Poly::constant(n, q.clone()),
                Op::Unknown(i) => Poly::var(n, *i),
                Op::Recip(i) => {
                    Poly::var(n, nu + inverted.iter().position(|v| v == i).unwrap_or(0))
                }
                Op::Data(s) => Poly::var(n, nu + nr + *s),
                _ => unreachable!("only leaves are passed to the leaf function"),
            })
        };
        let guard = deadline.map(|d| Guard::new::<Q>(d, n));
        let vals = run_tape(
            &self.checked.nodes,
            &self.needed,
            (&zero, &one),
            leaf,
            guard.as_ref().map(|g| g.hooks(n)),
        )?;
        Ok(self
            .checked
            .equations
            .iter()
            .enumerate()
            .map(|(k, eq)| {
                let flat = vals[eq.node]
                    .as_ref()
                    .map(|m| m.at(eq.row, eq.col).clone())
                    .unwrap_or_else(|| Poly::zero(n));
                split(&self.laurent.fold(flat, nu, k), nu, nd)
            })
            .collect())
    }

    /// Direct numeric evaluation of every scalar equation `lhs - rhs` at `data` and
    /// `unknowns`, with plain `f64` matrices (nalgebra; determinant by LU): a path
    /// independent of the polynomial arithmetic, for tests.
    ///
    /// # Panics
    /// If the slices do not have `data_slot_count()` and `unknown_count()` entries.
    pub fn evaluate_direct(&self, data: &[f64], unknowns: &[f64]) -> Vec<f64> {
        use nalgebra::DMatrix;
        assert_eq!(data.len(), self.layout.data_slot_count(), "data length");
        assert_eq!(
            unknowns.len(),
            self.layout.unknown_count(),
            "unknowns length"
        );
        let mut vals: Vec<Option<DMatrix<f64>>> = Vec::with_capacity(self.checked.nodes.len());
        for (id, node) in self.checked.nodes.iter().enumerate() {
            if !self.needed[id] {
                vals.push(None);
                continue;
            }
            let get = |n: &NodeId| vals[*n].as_ref().expect("operand evaluated");
            let s = |x: f64| DMatrix::from_element(1, 1, x);
            let v = match &node.op {
                Op::Const(q) => s(<f64 as Ring>::from_rational(q).unwrap_or(f64::NAN)),
                Op::Unknown(i) => s(unknowns[*i]),
                Op::Recip(i) => s(1.0 / unknowns[*i]),
                Op::Data(k) => s(data[*k]),
                Op::Build(shape, e) => DMatrix::from_row_iterator(
                    shape.rows,
                    shape.cols,
                    e.iter().map(|n| get(n)[(0, 0)]),
                ),
                Op::Identity => DMatrix::identity(3, 3),
                Op::Add(a, b) => get(a) + get(b),
                Op::Sub(a, b) => get(a) - get(b),
                Op::Neg(a) => -get(a),
                Op::Mul(a, b) => {
                    let (x, y) = (get(a), get(b));
                    if x.nrows() == 1 && x.ncols() == 1 {
                        y * x[(0, 0)]
                    } else if y.nrows() == 1 && y.ncols() == 1 {
                        x * y[(0, 0)]
                    } else {
                        x * y
                    }
                }
                Op::Transpose(a) => get(a).transpose(),
                Op::Skew(a) => {
                    let v = get(a);
                    let (x, y, z) = (v[0], v[1], v[2]);
                    DMatrix::from_row_slice(3, 3, &[0.0, -z, y, z, 0.0, -x, -y, x, 0.0])
                }
                Op::Det(a) => s(get(a).clone().determinant()),
                Op::Trace(a) => s(get(a).trace()),
                Op::Entry(a, i, j) => s(get(a)[(*i, *j)]),
            };
            vals.push(Some(v));
        }
        self.checked
            .equations
            .iter()
            .enumerate()
            .map(|(k, eq)| {
                let v = vals[eq.node].as_ref().map_or(0.0, |m| m[(eq.row, eq.col)]);
                // The Laurent shift monomial (see `Laurent`).
                let shift = self.laurent.shifts.get(k).map_or(1.0, |s| {
                    s.iter()
                        .zip(unknowns)
                        .map(|(&e, x)| x.powi(i32::from(e)))
                        .product()
                });
                v * shift
            })
            .collect()
    }

    /// Direct evaluation of every scalar equation over any ring (e.g. `Fp`), with small
    /// matrices of ring elements: no polynomials.
    pub fn evaluate_direct_ring<C: Ring>(
        &self,
        data: &[C],
        unknowns: &[C],
    ) -> Result<Vec<C>, EvalError> {
        let (nd, nu) = (self.layout.data_slot_count(), self.layout.unknown_count());
        if data.len() != nd {
            return Err(EvalError::DataLength {
                expected: nd,
                found: data.len(),
            });
        }
        if unknowns.len() != nu {
            return Err(EvalError::UnknownLength {
                expected: nu,
                found: unknowns.len(),
            });
        }
        if !self.laurent.inverted.is_empty() {
            // A ring has no reciprocals: evaluate the shifted polynomials instead.
            let polys = self.try_evaluate(data)?;
            return Ok(polys.iter().map(|p| p.eval(unknowns)).collect());
        }
        let vals = run_tape(
            &self.checked.nodes,
            &self.needed,
            (&C::zero(), &C::one()),
            |op| {
                Ok(match op {
                    Op::Const(q) => C::from_rational(q).ok_or(EvalError::Constant(q.clone()))?,
                    Op::Unknown(i) | Op::Recip(i) => unknowns[*i].clone(),
                    Op::Data(s) => data[*s].clone(),
                    _ => unreachable!("only leaves are passed to the leaf function"),
                })
            },
            None,
        )?;
        Ok(self
            .checked
            .equations
            .iter()
            .map(|eq| {
                vals[eq.node]
                    .as_ref()
                    .map_or_else(C::zero, |m| m.at(eq.row, eq.col).clone())
            })
            .collect())
    }
}

/// The equations and the `nonzero` expressions of one evaluation
/// ([`Problem::try_evaluate_with_nonzero`]).
pub type EquationsAndNonzero<C> = (Vec<Poly<C>>, Vec<Poly<C>>);

/// The value of each tape node (`None` where not needed).
type TapeValues<C> = Vec<Option<Mixed<C>>>;

/// Entry `(row, col)` of node `node`'s value as a polynomial in `n` variables (zero if the
/// node was not evaluated).
fn entry_poly<C: Ring>(
    vals: &TapeValues<C>,
    node: NodeId,
    row: usize,
    col: usize,
    n: usize,
) -> Poly<C> {
    let p = match vals[node].as_ref() {
        Some(Mixed::K(m)) => Poly::constant(n, m.at(row, col).clone()),
        Some(Mixed::P(m)) => m.at(row, col).clone(),
        None => Poly::zero(n),
    };
    if p.nvars() < n {
        p.widen(n)
    } else {
        p
    }
}

/// The expression `e` of a saturating equation `u * e - 1` (see `lang::check::saturate`).
fn saturated_expression(nodes: &[Node], eq: NodeId) -> Option<NodeId> {
    let Op::Sub(prod, _) = nodes.get(eq)?.op else {
        return None;
    };
    match nodes.get(prod)?.op {
        Op::Mul(a, b) if matches!(nodes.get(a)?.op, Op::Unknown(_)) => Some(b),
        Op::Mul(a, b) if matches!(nodes.get(b)?.op, Op::Unknown(_)) => Some(a),
        _ => None,
    }
}

/// Splits a polynomial in `nu + nd` variables (unknowns first) into a polynomial in the
/// `nu` unknowns with coefficients polynomials in the `nd` data variables.
fn split(flat: &Poly<Q>, nu: usize, nd: usize) -> Poly<Poly<Q>> {
    let mut groups: BTreeMap<Monomial, Poly<Q>> = BTreeMap::new();
    for (m, c) in flat.terms() {
        let outer = Monomial(m.0[..nu].to_vec());
        let inner = Monomial(m.0[nu..].to_vec());
        groups
            .entry(outer)
            .or_insert_with(|| Poly::zero(nd))
            .add_term(inner, c.clone());
    }
    Poly::from_terms(nu, groups)
}
