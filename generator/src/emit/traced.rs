//! Traced expressions: a [`Ring`] whose values record how they were computed from data.
//!
//! A [`Traced`] value is either an exact rational constant (so structural zeros and ones
//! fold away while the problem is expanded) or a signed reference to a node of a shared,
//! hash-consed expression DAG owned by a [`Tracer`]. Evaluating a problem's equations with
//! traced data (`problem.evaluate::<Traced>(&tracer.inputs(n))`) yields, for every
//! equation and monomial in the unknowns, a DAG node computing that coefficient from the
//! data slots; [`super::coefficients::Program`] turns the needed part of the DAG into
//! straight-line code.
//!
//! ## Canonical form (what makes sharing effective and output deterministic)
//! - Graph nodes are `Input(slot)`, `Const(q)` with `q > 0`, `Add(a, b)` and `Mul(a, b)`
//!   with `a <= b` (commutative operands sorted by node id), and `Sub(a, b)` with `a < b`.
//!   There is no negation node: a sign lives in the [`Traced`] value, so `x - y` and
//!   `y - x` are the same node with opposite signs, and `(-x) * y` is `-(x * y)`.
//! - Identical nodes are created once (hash-consing), which is common-subexpression
//!   elimination for free: the products of matrices are traced entry by entry and every
//!   repeated intermediate is shared.
//! - Node ids are assigned in order of first creation, so a deterministic evaluation order
//!   gives a deterministic graph; children always have smaller ids than their parents.

use crate::algebra::{Ring, Q};
use num_traits::Signed;
use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt;
use std::rc::Rc;

/// Id of a node in a [`Tracer`]'s graph (creation order).
pub type NodeId = u32;

/// One node of the expression DAG (see the module documentation for its canonical form).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// The data slot with this index.
    Input(usize),
    /// A positive rational constant (only created when a constant meets a node).
    Const(Q),
    /// `a + b`, `a <= b`.
    Add(NodeId, NodeId),
    /// `a - b`, `a < b`.
    Sub(NodeId, NodeId),
    /// `a * b`, `a <= b`.
    Mul(NodeId, NodeId),
}

#[derive(Default)]
struct Graph {
    ops: Vec<Op>,
    index: HashMap<Op, NodeId>,
}

impl Graph {
    fn intern(&mut self, op: Op) -> NodeId {
        if let Some(&id) = self.index.get(&op) {
            return id;
        }
        let id = NodeId::try_from(self.ops.len()).expect("fewer than 2^32 traced nodes");
        self.ops.push(op.clone());
        self.index.insert(op, id);
        id
    }
}

/// Owner of an expression DAG; cheap to clone (shared handle).
///
/// Use one tracer per emitted solver: node ids, and therefore the emitted code, depend only
/// on the operations performed through it.
#[derive(Clone, Default)]
pub struct Tracer(Rc<RefCell<Graph>>);

impl fmt::Debug for Tracer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Tracer({} nodes)", self.node_count())
    }
}

impl Tracer {
    /// A tracer with an empty graph.
    pub fn new() -> Self {
        Tracer::default()
    }
    /// The traced value of data slot `slot`.
    pub fn input(&self, slot: usize) -> Traced {
        let id = self.0.borrow_mut().intern(Op::Input(slot));
        self.node(id, false)
    }
    /// The traced values of data slots `0..n`, in order.
    pub fn inputs(&self, n: usize) -> Vec<Traced> {
        (0..n).map(|i| self.input(i)).collect()
    }
    /// Number of nodes created so far (inputs and constants included).
    pub fn node_count(&self) -> usize {
        self.0.borrow().ops.len()
    }
    /// The operation of node `id`.
    pub fn op(&self, id: NodeId) -> Op {
        self.0.borrow().ops[id as usize].clone()
    }
    /// A snapshot of all node operations, indexed by id.
    pub fn ops(&self) -> Vec<Op> {
        self.0.borrow().ops.clone()
    }
    /// Whether two handles refer to the same graph.
    pub fn same_graph(&self, other: &Tracer) -> bool {
        Rc::ptr_eq(&self.0, &other.0)
    }
    /// Evaluates every node in f64 from the data slots (the reference interpreter).
    pub fn eval_all(&self, data: &[f64]) -> Vec<f64> {
        let g = self.0.borrow();
        let mut v: Vec<f64> = Vec::with_capacity(g.ops.len());
        for op in &g.ops {
            let x = match op {
                Op::Input(s) => data[*s],
                Op::Const(q) => q_to_f64(q),
                Op::Add(a, b) => v[*a as usize] + v[*b as usize],
                Op::Sub(a, b) => v[*a as usize] - v[*b as usize],
                Op::Mul(a, b) => v[*a as usize] * v[*b as usize],
            };
            v.push(x);
        }
        v
    }

    fn node(&self, id: NodeId, neg: bool) -> Traced {
        Traced(Repr::Node {
            tracer: self.clone(),
            id,
            neg,
        })
    }
    fn intern(&self, op: Op) -> NodeId {
        self.0.borrow_mut().intern(op)
    }
    fn const_node(&self, q: &Q) -> NodeId {
        debug_assert!(q.is_positive());
        self.intern(Op::Const(q.clone()))
    }
}

/// The nearest f64 to a rational (as used for emitted literals).
pub fn q_to_f64(q: &Q) -> f64 {
    <f64 as Ring>::from_rational(q).unwrap_or(f64::NAN)
}

#[derive(Clone)]
enum Repr {
    Const(Q),
    Node {
        tracer: Tracer,
        id: NodeId,
        neg: bool,
    },
}

/// A traced scalar: an exact constant or `±node` of a [`Tracer`]'s graph.
#[derive(Clone)]
pub struct Traced(Repr);

/// A traced value taken apart.
#[derive(Clone, Debug, PartialEq)]
pub enum TracedValue {
    /// An exact constant.
    Const(Q),
    /// `-node` if `neg`, else `node`.
    Node {
        /// The node id.
        id: NodeId,
        /// Whether the value is the negated node.
        neg: bool,
    },
}

impl Traced {
    /// The constant `q`.
    pub fn constant(q: Q) -> Self {
        Traced(Repr::Const(q))
    }
    /// The value as a constant or signed node id.
    pub fn value(&self) -> TracedValue {
        match &self.0 {
            Repr::Const(q) => TracedValue::Const(q.clone()),
            Repr::Node { id, neg, .. } => TracedValue::Node { id: *id, neg: *neg },
        }
    }
    /// The graph this value refers to (`None` for constants).
    pub fn tracer(&self) -> Option<&Tracer> {
        match &self.0 {
            Repr::Const(_) => None,
            Repr::Node { tracer, .. } => Some(tracer),
        }
    }
    /// Evaluates the value in f64 from the data slots (through [`Tracer::eval_all`]).
    pub fn eval_f64(&self, data: &[f64]) -> f64 {
        match &self.0 {
            Repr::Const(q) => q_to_f64(q),
            Repr::Node { tracer, id, neg } => {
                let v = tracer.eval_all(data)[*id as usize];
                if *neg {
                    -v
                } else {
                    v
                }
            }
        }
    }

    /// Splits into sign and magnitude base.
    fn parts(&self) -> (bool, Base) {
        match &self.0 {
            Repr::Const(q) => (q.is_negative(), Base::Const(q.abs())),
            Repr::Node { tracer, id, neg } => (*neg, Base::Node(tracer.clone(), *id)),
        }
    }

    fn from_parts(neg: bool, tracer: &Tracer, id: NodeId) -> Self {
        tracer.node(id, neg)
    }

    fn signed_const(neg: bool, q: Q) -> Self {
        Traced(Repr::Const(if neg { -q } else { q }))
    }
}

enum Base {
    Const(Q),
    Node(Tracer, NodeId),
}

impl Base {
    /// Node id of this base in `tracer` (constants become `Const` nodes).
    fn id_in(&self, tracer: &Tracer) -> NodeId {
        match self {
            Base::Const(q) => tracer.const_node(q),
            Base::Node(t, id) => {
                assert!(
                    t.same_graph(tracer),
                    "traced values from different tracers combined"
                );
                *id
            }
        }
    }
    fn tracer(&self) -> Option<&Tracer> {
        match self {
            Base::Const(_) => None,
            Base::Node(t, _) => Some(t),
        }
    }
}

fn sorted(a: NodeId, b: NodeId) -> (NodeId, NodeId) {
    if a <= b {
        (a, b)
    } else {
        (b, a)
    }
}

/// `sa*a + sb*b` for magnitudes `a`, `b` and signs `sa`, `sb`, in canonical form.
fn signed_add(sa: bool, a: Base, sb: bool, b: Base) -> Traced {
    if let (Base::Const(p), Base::Const(q)) = (&a, &b) {
        let p = if sa { -p.clone() } else { p.clone() };
        let q = if sb { -q.clone() } else { q.clone() };
        return Traced::constant(p + q);
    }
    if let Base::Const(p) = &a {
        if p.is_zero() {
            let t = b.tracer().expect("b is a node").clone();
            return Traced::from_parts(sb, &t, b.id_in(&t));
        }
    }
    if let Base::Const(q) = &b {
        if q.is_zero() {
            let t = a.tracer().expect("a is a node").clone();
            return Traced::from_parts(sa, &t, a.id_in(&t));
        }
    }
    let tracer = a.tracer().or(b.tracer()).expect("one is a node").clone();
    let (ia, ib) = (a.id_in(&tracer), b.id_in(&tracer));
    if sa == sb {
        // ±(a + b)
        let (x, y) = sorted(ia, ib);
        let id = tracer.intern(Op::Add(x, y));
        Traced::from_parts(sa, &tracer, id)
    } else {
        // a - b (sa = +) or b - a (sa = -); canonical Sub has the smaller id first.
        let (p, m) = if sa { (ib, ia) } else { (ia, ib) };
        if p == m {
            return Traced::constant(Q::zero());
        }
        if p < m {
            let id = tracer.intern(Op::Sub(p, m));
            Traced::from_parts(false, &tracer, id)
        } else {
            let id = tracer.intern(Op::Sub(m, p));
            Traced::from_parts(true, &tracer, id)
        }
    }
}

impl Ring for Traced {
    fn zero() -> Self {
        Traced::constant(Q::zero())
    }
    fn one() -> Self {
        Traced::constant(Q::one())
    }
    fn is_zero(&self) -> bool {
        matches!(&self.0, Repr::Const(q) if q.is_zero())
    }
    fn is_one(&self) -> bool {
        matches!(&self.0, Repr::Const(q) if q.is_one())
    }
    fn add(&self, other: &Self) -> Self {
        let (sa, a) = self.parts();
        let (sb, b) = other.parts();
        signed_add(sa, a, sb, b)
    }
    fn sub(&self, other: &Self) -> Self {
        let (sa, a) = self.parts();
        let (sb, b) = other.parts();
        signed_add(sa, a, !sb, b)
    }
    fn mul(&self, other: &Self) -> Self {
        let (sa, a) = self.parts();
        let (sb, b) = other.parts();
        let neg = sa != sb;
        match (a, b) {
            (Base::Const(p), Base::Const(q)) => Traced::signed_const(neg, p * q),
            (Base::Const(q), n @ Base::Node(..)) | (n @ Base::Node(..), Base::Const(q)) => {
                if q.is_zero() {
                    return Traced::zero();
                }
                let tracer = n.tracer().expect("node").clone();
                let idn = n.id_in(&tracer);
                if q.is_one() {
                    return Traced::from_parts(neg, &tracer, idn);
                }
                let idq = tracer.const_node(&q);
                let (x, y) = sorted(idq, idn);
                let id = tracer.intern(Op::Mul(x, y));
                Traced::from_parts(neg, &tracer, id)
            }
            (a @ Base::Node(..), b @ Base::Node(..)) => {
                let tracer = a.tracer().expect("node").clone();
                let (x, y) = sorted(a.id_in(&tracer), b.id_in(&tracer));
                let id = tracer.intern(Op::Mul(x, y));
                Traced::from_parts(neg, &tracer, id)
            }
        }
    }
    fn neg(&self) -> Self {
        match &self.0 {
            Repr::Const(q) => Traced::constant(-q.clone()),
            Repr::Node { tracer, id, neg } => tracer.node(*id, !*neg),
        }
    }
    fn from_rational(q: &Q) -> Option<Self> {
        Some(Traced::constant(q.clone()))
    }
}

impl fmt::Debug for Traced {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Const(q) => write!(f, "{q}"),
            Repr::Node { id, neg, .. } => write!(f, "{}n{id}", if *neg { "-" } else { "" }),
        }
    }
}

impl fmt::Display for Traced {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    fn q(n: i64, d: i64) -> Q {
        Q::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn constants_fold_and_structural_identities() {
        let t = Tracer::new();
        let x = t.input(0);
        let y = t.input(1);
        assert!(x.mul(&Traced::zero()).is_zero());
        assert_eq!(x.mul(&Traced::one()).value(), x.value());
        assert_eq!(x.add(&Traced::zero()).value(), x.value());
        assert!(x.sub(&x).is_zero());
        // x*y and y*x are one node; y - x is -(x - y).
        assert_eq!(x.mul(&y).value(), y.mul(&x).value());
        assert_eq!(y.sub(&x).value(), x.sub(&y).neg().value());
        // (-x) * y = -(x * y); (-x) + (-y) = -(x + y).
        assert_eq!(x.neg().mul(&y).value(), x.mul(&y).neg().value());
        assert_eq!(x.neg().add(&y.neg()).value(), x.add(&y).neg().value());
        // 2/3 * x, then -(2/3) * x shares the node.
        let c = Traced::constant(q(2, 3));
        assert_eq!(
            c.neg().mul(&x).value(),
            c.mul(&x).neg().value(),
            "negative constants factor out"
        );
        let n = t.node_count();
        let _ = x.mul(&y).add(&y.mul(&x)); // one new Add node
        assert_eq!(t.node_count(), n + 1);
    }

    #[test]
    fn interpreter_matches_f64() {
        let t = Tracer::new();
        let v = t.inputs(3);
        let e = v[0]
            .mul(&v[1])
            .sub(&v[2].mul(&Traced::constant(q(-5, 2))))
            .mul(&v[2].sub(&v[0]))
            .add(&Traced::constant(q(7, 1)));
        let d = [0.3, -1.7, 2.9];
        let direct = (d[0] * d[1] + 2.5 * d[2]) * (d[2] - d[0]) + 7.0;
        assert!((e.eval_f64(&d) - direct).abs() < 1e-12);
    }
}
