//! The checker's output: a hash-consed tape of matrix and scalar operations (operands
//! before users, identical operations shared, constants folded as nodes are added) and the
//! scalar equations read off it. `expand` turns the tape into polynomials.

use crate::algebra::Q;
use crate::problem::ProblemLayout;
use num_traits::{One, Zero};
use std::collections::HashMap;

/// Bound on the total degree (unknowns and data) of an equation, far above any minimal
/// problem and far below the exponent range of [`crate::algebra::Exponent`].
pub const MAX_DEGREE: u32 = 255;

/// Index of a node in [`Checked::nodes`].
pub type NodeId = usize;

/// A shape: 1x1 (scalar), Nx1 (column vector), 1xN (row vector) or RxC (matrix).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shape {
    /// Number of rows.
    pub rows: usize,
    /// Number of columns.
    pub cols: usize,
}

impl Shape {
    /// 1x1.
    pub const SCALAR: Shape = Shape { rows: 1, cols: 1 };
    /// 3x1.
    pub const COL: Shape = Shape { rows: 3, cols: 1 };
    /// 1x3.
    pub const ROW: Shape = Shape { rows: 1, cols: 3 };
    /// 3x3.
    pub const MAT: Shape = Shape { rows: 3, cols: 3 };
    /// Whether 1x1.
    pub fn is_scalar(self) -> bool {
        self == Shape::SCALAR
    }
    /// Number of entries.
    pub fn len(self) -> usize {
        self.rows * self.cols
    }
    /// Always false (shapes have at least one entry); for clippy's `len` convention.
    pub fn is_empty(self) -> bool {
        false
    }
    pub(crate) fn describe(self) -> String {
        match (self.rows, self.cols) {
            (1, 1) => "a scalar".into(),
            (r, 1) => format!("a {r}x1 column vector"),
            (1, c) => format!("a 1x{c} row vector"),
            (r, c) => format!("a {r}x{c} matrix"),
        }
    }
}

/// One operation of the tape; operands are earlier nodes.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// A rational constant (1x1).
    Const(Q),
    /// Unknown scalar number i (1x1).
    Unknown(usize),
    /// Data slot number s (1x1).
    Data(usize),
    /// The reciprocal `1 / x_i` of unknown scalar number i (1x1): a Laurent monomial. The
    /// expansion multiplies each equation by the smallest monomial that clears the
    /// negative exponents (`Problem::expand`).
    Recip(usize),
    /// A matrix from 1x1 nodes, row-major.
    Build(Shape, Vec<NodeId>),
    /// The 3x3 identity.
    Identity,
    /// Entrywise sum of equal shapes.
    Add(NodeId, NodeId),
    /// Entrywise difference of equal shapes.
    Sub(NodeId, NodeId),
    /// Negation.
    Neg(NodeId),
    /// Matrix product, or scaling when one side is 1x1.
    Mul(NodeId, NodeId),
    /// Transpose.
    Transpose(NodeId),
    /// The cross-product matrix of a 3-vector.
    Skew(NodeId),
    /// Determinant of a square matrix (at most 6x6).
    Det(NodeId),
    /// Trace of a square matrix.
    Trace(NodeId),
    /// Entry (row, col) of a node (1x1).
    Entry(NodeId, usize, usize),
}

/// A tape node: operation and result shape.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Node {
    /// The operation.
    pub op: Op,
    /// The shape of its value.
    pub shape: Shape,
    /// An upper bound on the total degree of its entries in unknowns and data together.
    pub degree: u32,
}

/// One scalar equation: entry (row, col) of node `node`, which is `lhs - rhs`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScalarEquation {
    /// The node holding `lhs - rhs`.
    pub node: NodeId,
    /// Row of the entry.
    pub row: usize,
    /// Column of the entry.
    pub col: usize,
    /// Source line of the equation.
    pub line: usize,
}

/// A checked problem: layout, tape and scalar equations.
#[derive(Clone, Debug)]
pub struct Checked {
    /// Symbols of the problem.
    pub layout: ProblemLayout,
    /// The tape, operands before users.
    pub nodes: Vec<Node>,
    /// The scalar equations, in source order (matrix equations row-major).
    pub equations: Vec<ScalarEquation>,
}

/// The tape under construction: nodes and the index that shares identical operations.
#[derive(Debug, Default)]
pub(crate) struct Tape {
    /// The nodes, operands before users.
    pub(crate) nodes: Vec<Node>,
    intern: HashMap<Op, NodeId>,
}

impl Tape {
    pub(crate) fn shape(&self, n: NodeId) -> Shape {
        self.nodes.get(n).map(|n| n.shape).unwrap_or(Shape::SCALAR)
    }

    pub(crate) fn op(&self, n: NodeId) -> Option<&Op> {
        self.nodes.get(n).map(|n| &n.op)
    }

    pub(crate) fn constant(&self, n: NodeId) -> Option<&Q> {
        match self.op(n) {
            Some(Op::Const(q)) => Some(q),
            _ => None,
        }
    }

    pub(crate) fn is_const_zero(&self, n: NodeId) -> bool {
        self.constant(n).is_some_and(|q| q.is_zero())
    }

    /// Adds a node (or finds the identical one), folding constants.
    pub(crate) fn mk(&mut self, op: Op, shape: Shape) -> NodeId {
        let folded = match &op {
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => {
                match (self.constant(*a), self.constant(*b)) {
                    (Some(x), Some(y)) => Some(Op::Const(match op {
                        Op::Add(..) => x + y,
                        Op::Sub(..) => x - y,
                        _ => x * y,
                    })),
                    (_, Some(y)) if y.is_zero() && !matches!(op, Op::Mul(..)) => {
                        return *a;
                    }
                    (Some(x), _) if x.is_zero() && matches!(op, Op::Add(..)) => return *b,
                    (Some(x), _) if x.is_one() && matches!(op, Op::Mul(..)) => return *b,
                    (_, Some(y)) if y.is_one() && matches!(op, Op::Mul(..)) => return *a,
                    _ => None,
                }
            }
            Op::Neg(a) => self.constant(*a).map(|x| Op::Const(-x)),
            Op::Transpose(a) => {
                if self.shape(*a).is_scalar() {
                    return *a;
                }
                if let Some(Op::Transpose(inner)) = self.op(*a) {
                    return *inner;
                }
                None
            }
            Op::Entry(a, i, j) => {
                if let Some(Op::Build(s, entries)) = self.op(*a) {
                    if let Some(e) = entries.get(i * s.cols + j) {
                        return *e;
                    }
                }
                if self.shape(*a).is_scalar() {
                    return *a;
                }
                None
            }
            _ => None,
        };
        let op = folded.unwrap_or(op);
        if let Some(&id) = self.intern.get(&op) {
            return id;
        }
        let deg = |n: &NodeId| self.nodes.get(*n).map_or(0, |n| n.degree);
        let degree = match &op {
            Op::Const(_) | Op::Identity => 0,
            Op::Unknown(_) | Op::Data(_) | Op::Recip(_) => 1,
            Op::Build(_, e) => e.iter().map(deg).max().unwrap_or(0),
            Op::Add(a, b) | Op::Sub(a, b) => deg(a).max(deg(b)),
            Op::Mul(a, b) => deg(a).saturating_add(deg(b)),
            Op::Det(a) => {
                let n = self.shape(*a).rows;
                deg(a).saturating_mul(u32::try_from(n).unwrap_or(u32::MAX))
            }
            Op::Neg(a) | Op::Transpose(a) | Op::Skew(a) | Op::Trace(a) | Op::Entry(a, _, _) => {
                deg(a)
            }
        };
        let id = self.nodes.len();
        self.intern.insert(op.clone(), id);
        self.nodes.push(Node { op, shape, degree });
        id
    }

    pub(crate) fn konst(&mut self, q: Q) -> NodeId {
        self.mk(Op::Const(q), Shape::SCALAR)
    }
}
