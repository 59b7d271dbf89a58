//! A checked problem and its evaluation: over any [`Ring`] (the equations as polynomials in
//! the unknowns with coefficients in the ring), symbolically ([`Problem::expand`]: exact
//! polynomial coefficients in the data), and directly in `f64` matrices (an independent
//! check).
//!
//! Evaluation walks the checked tape (see [`crate::lang::check`]) with small matrices whose
//! entries are polynomials: no strings, no parsing, each shared subexpression computed once.

use crate::algebra::{Monomial, Poly, Ring, Q};
use crate::lang::check::{Checked, Node, NodeId, Op, Shape};
use crate::lang::{self, LangError};
use crate::problem::ProblemLayout;
use std::collections::BTreeMap;
use std::path::Path;

/// A parsed and checked problem.
#[derive(Clone, Debug)]
pub struct Problem {
    /// Its symbols (unknowns, typed data, eliminated unknowns).
    pub layout: ProblemLayout,
    checked: Checked,
    /// Whether each tape node is needed by some equation.
    needed: Vec<bool>,
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
}

/// A small dense matrix (1x1, 3x1, 1x3 or 3x3) over a ring, row-major.
#[derive(Clone, Debug)]
struct Mat<T> {
    shape: Shape,
    e: Vec<T>,
}

impl<T: Ring> Mat<T> {
    fn scalar(x: T) -> Self {
        Mat {
            shape: Shape::SCALAR,
            e: vec![x],
        }
    }
    fn at(&self, i: usize, j: usize) -> &T {
        &self.e[i * self.shape.cols + j]
    }
    fn zip(&self, o: &Self, f: impl Fn(&T, &T) -> T) -> Self {
        Mat {
            shape: self.shape,
            e: self.e.iter().zip(&o.e).map(|(a, b)| f(a, b)).collect(),
        }
    }
    fn map(&self, f: impl Fn(&T) -> T) -> Self {
        Mat {
            shape: self.shape,
            e: self.e.iter().map(f).collect(),
        }
    }
    fn mul(&self, o: &Self) -> Self {
        if self.shape.is_scalar() {
            let s = &self.e[0];
            return o.map(|x| mul_skip(s, x));
        }
        if o.shape.is_scalar() {
            let s = &o.e[0];
            return self.map(|x| mul_skip(x, s));
        }
        let (r, n, c) = (self.shape.rows, self.shape.cols, o.shape.cols);
        let mut e = Vec::with_capacity(r * c);
        for i in 0..r {
            for j in 0..c {
                let mut acc: Option<T> = None;
                for k in 0..n {
                    let (a, b) = (self.at(i, k), o.at(k, j));
                    if a.is_zero() || b.is_zero() {
                        continue;
                    }
                    let p = a.mul(b);
                    acc = Some(match acc {
                        None => p,
                        Some(s) => s.add(&p),
                    });
                }
                e.push(acc.unwrap_or_else(T::zero));
            }
        }
        Mat {
            shape: Shape { rows: r, cols: c },
            e,
        }
    }
    fn transpose(&self) -> Self {
        let s = self.shape;
        let mut e = Vec::with_capacity(s.len());
        for j in 0..s.cols {
            for i in 0..s.rows {
                e.push(self.at(i, j).clone());
            }
        }
        Mat {
            shape: Shape {
                rows: s.cols,
                cols: s.rows,
            },
            e,
        }
    }
    fn skew(&self) -> Self {
        let (x, y, z) = (&self.e[0], &self.e[1], &self.e[2]);
        Mat {
            shape: Shape::MAT,
            e: vec![
                T::zero(),
                z.neg(),
                y.clone(),
                z.clone(),
                T::zero(),
                x.neg(),
                y.neg(),
                x.clone(),
                T::zero(),
            ],
        }
    }
    fn det(&self) -> T {
        let m = |i, j| self.at(i, j);
        let minor = |a: usize, b: usize| {
            // Columns other than the first of the 2x2 minor on rows 1, 2.
            sub_skip(&mul_skip(m(1, a), m(2, b)), &mul_skip(m(1, b), m(2, a)))
        };
        let t0 = mul_skip(m(0, 0), &minor(1, 2));
        let t1 = mul_skip(m(0, 1), &minor(0, 2));
        let t2 = mul_skip(m(0, 2), &minor(0, 1));
        t0.sub(&t1).add(&t2)
    }
    fn trace(&self) -> T {
        self.at(0, 0).add(self.at(1, 1)).add(self.at(2, 2))
    }
}

fn mul_skip<T: Ring>(a: &T, b: &T) -> T {
    if a.is_zero() || b.is_zero() {
        T::zero()
    } else {
        a.mul(b)
    }
}

fn sub_skip<T: Ring>(a: &T, b: &T) -> T {
    if b.is_zero() {
        a.clone()
    } else {
        a.sub(b)
    }
}

/// Runs the tape over `T`, with leaves (constants, unknowns, data slots) from `leaf`.
fn run_tape<T: Ring>(
    nodes: &[Node],
    needed: &[bool],
    identity: (&T, &T),
    mut leaf: impl FnMut(&Op) -> Result<T, EvalError>,
) -> Result<Vec<Option<Mat<T>>>, EvalError> {
    let mut vals: Vec<Option<Mat<T>>> = Vec::with_capacity(nodes.len());
    for (id, node) in nodes.iter().enumerate() {
        if !needed.get(id).copied().unwrap_or(false) {
            vals.push(None);
            continue;
        }
        let get = |n: &NodeId| -> &Mat<T> {
            vals[*n]
                .as_ref()
                .expect("operands precede their users and are needed")
        };
        let v = match &node.op {
            Op::Const(_) | Op::Unknown(_) | Op::Data(_) => Mat::scalar(leaf(&node.op)?),
            Op::Build(shape, entries) => Mat {
                shape: *shape,
                e: entries.iter().map(|n| get(n).e[0].clone()).collect(),
            },
            Op::Identity => Mat {
                shape: Shape::MAT,
                e: (0..9)
                    .map(|k| {
                        if k % 4 == 0 {
                            identity.1.clone()
                        } else {
                            identity.0.clone()
                        }
                    })
                    .collect(),
            },
            Op::Add(a, b) => get(a).zip(get(b), |x, y| x.add(y)),
            Op::Sub(a, b) => get(a).zip(get(b), sub_skip),
            Op::Neg(a) => get(a).map(T::neg),
            Op::Mul(a, b) => get(a).mul(get(b)),
            Op::Transpose(a) => get(a).transpose(),
            Op::Skew(a) => get(a).skew(),
            Op::Det(a) => Mat::scalar(get(a).det()),
            Op::Trace(a) => Mat::scalar(get(a).trace()),
            Op::Entry(a, i, j) => Mat::scalar(get(a).at(*i, *j).clone()),
        };
        vals.push(Some(v));
    }
    Ok(vals)
}

impl Problem {
    /// Parses and checks a problem's source; errors carry `file_name`.
    pub fn parse(source: &str, file_name: &str) -> Result<Problem, LangError> {
        let checked = lang::compile(source).map_err(|e| e.in_file(file_name))?;
        Ok(Problem::from_checked(checked))
    }

    /// Reads, parses and checks a problem file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Problem, ProblemError> {
        let path = path.as_ref();
        let shown = path.display().to_string();
        let source = std::fs::read_to_string(path).map_err(|source| ProblemError::Io {
            path: shown.clone(),
            source,
        })?;
        Ok(Problem::parse(&source, &shown)?)
    }

    fn from_checked(checked: Checked) -> Problem {
        let mut needed = vec![false; checked.nodes.len()];
        let mut stack: Vec<NodeId> = checked.equations.iter().map(|e| e.node).collect();
        while let Some(n) = stack.pop() {
            if needed[n] {
                continue;
            }
            needed[n] = true;
            match &checked.nodes[n].op {
                Op::Const(_) | Op::Unknown(_) | Op::Data(_) | Op::Identity => {}
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
        }
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
        let expected = self.layout.data_slot_count();
        if data.len() != expected {
            return Err(EvalError::DataLength {
                expected,
                found: data.len(),
            });
        }
        let n = self.layout.unknown_count();
        let zero = Poly::zero(n);
        let one = Poly::constant(n, C::one());
        let vals = run_tape(&self.checked.nodes, &self.needed, (&zero, &one), |op| {
            Ok(match op {
                Op::Const(q) => Poly::constant(
                    n,
                    C::from_rational(q).ok_or(EvalError::Constant(q.clone()))?,
                ),
                Op::Unknown(i) => Poly::var(n, *i),
                Op::Data(s) => Poly::constant(n, data[*s].clone()),
                _ => unreachable!("only leaves are passed to the leaf function"),
            })
        })?;
        Ok(self
            .checked
            .equations
            .iter()
            .map(|eq| {
                let p = vals[eq.node]
                    .as_ref()
                    .map(|m| m.at(eq.row, eq.col).clone())
                    .unwrap_or_else(|| Poly::zero(n));
                if p.nvars() < n {
                    p.widen(n)
                } else {
                    p
                }
            })
            .collect())
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
        let nu = self.layout.unknown_count();
        let nd = self.layout.data_slot_count();
        let n = nu + nd;
        let zero = Poly::zero(n);
        let one = Poly::constant(n, Q::from_integer(1.into()));
        let vals = run_tape(&self.checked.nodes, &self.needed, (&zero, &one), |op| {
            Ok(match op {
                Op::Const(q) => Poly::constant(n, q.clone()),
                Op::Unknown(i) => Poly::var(n, *i),
                Op::Data(s) => Poly::var(n, nu + *s),
                _ => unreachable!("only leaves are passed to the leaf function"),
            })
        })
        .expect("rational evaluation cannot fail");
        self.checked
            .equations
            .iter()
            .map(|eq| {
                let flat = vals[eq.node]
                    .as_ref()
                    .map(|m| m.at(eq.row, eq.col).clone())
                    .unwrap_or_else(|| Poly::zero(n));
                split(&flat, nu, nd)
            })
            .collect()
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
            .map(|eq| vals[eq.node].as_ref().map_or(0.0, |m| m[(eq.row, eq.col)]))
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
        let vals = run_tape(
            &self.checked.nodes,
            &self.needed,
            (&C::zero(), &C::one()),
            |op| {
                Ok(match op {
                    Op::Const(q) => C::from_rational(q).ok_or(EvalError::Constant(q.clone()))?,
                    Op::Unknown(i) => unknowns[*i].clone(),
                    Op::Data(s) => data[*s].clone(),
                    _ => unreachable!("only leaves are passed to the leaf function"),
                })
            },
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
