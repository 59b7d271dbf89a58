//! `diff(EXPR, x)`: exact partial derivatives on the tape. Every operation is
//! differentiated symbolically into new tape nodes (sums, the product rule, transposes,
//! entries, `skew` and `trace` as linear maps, `det` by the rows of its argument), so the
//! derivative is a polynomial expression like any other; data and constants have
//! derivative zero.

use crate::lang::ir::{NodeId, Op, Shape, Tape};
use std::collections::HashMap;

/// The derivative of node `n` with respect to unknown variable `var`, as a node of the
/// same shape; `memo` holds the derivatives computed so far (`None`: identically zero).
pub(super) fn derivative(
    tape: &mut Tape,
    n: NodeId,
    var: usize,
    memo: &mut HashMap<NodeId, Option<NodeId>>,
) -> Option<NodeId> {
    // Iterative post-order, so that long chains cannot overflow the stack.
    let mut stack = vec![(n, false)];
    while let Some((id, ready)) = stack.pop() {
        if memo.contains_key(&id) {
            continue;
        }
        let Some(op) = tape.op(id).cloned() else {
            memo.insert(id, None);
            continue;
        };
        let operands = operands(&op);
        if !ready {
            stack.push((id, true));
            stack.extend(
                operands
                    .iter()
                    .filter(|o| !memo.contains_key(o))
                    .map(|&o| (o, false)),
            );
            continue;
        }
        let d = |o: &NodeId| memo.get(o).copied().flatten();
        let shape = tape.shape(id);
        let result = match op {
            Op::Const(_) | Op::Data(_) | Op::Identity => None,
            Op::Unknown(i) => (i == var).then(|| tape.konst(super::q_int(1))),
            // d(1/x)/dx = -1/x^2.
            Op::Recip(i) => (i == var).then(|| {
                let sq = tape.mk(Op::Mul(id, id), Shape::SCALAR);
                tape.mk(Op::Neg(sq), Shape::SCALAR)
            }),
            Op::Build(s, entries) => {
                let ds: Vec<Option<NodeId>> = entries.iter().map(d).collect();
                if ds.iter().all(Option::is_none) {
                    None
                } else {
                    let zero = tape.konst(super::q_int(0));
                    let e = ds.into_iter().map(|x| x.unwrap_or(zero)).collect();
                    Some(tape.mk(Op::Build(s, e), s))
                }
            }
            Op::Add(a, b) | Op::Sub(a, b) => {
                let sub = matches!(op, Op::Sub(..));
                match (d(&a), d(&b)) {
                    (None, None) => None,
                    (Some(x), None) => Some(x),
                    (None, Some(y)) if sub => Some(tape.mk(Op::Neg(y), shape)),
                    (None, Some(y)) => Some(y),
                    (Some(x), Some(y)) => {
                        Some(tape.mk(if sub { Op::Sub(x, y) } else { Op::Add(x, y) }, shape))
                    }
                }
            }
            Op::Neg(a) => d(&a).map(|x| tape.mk(Op::Neg(x), shape)),
            Op::Mul(a, b) => {
                let left = d(&a).map(|x| tape.mk(Op::Mul(x, b), shape));
                let right = d(&b).map(|y| tape.mk(Op::Mul(a, y), shape));
                match (left, right) {
                    (Some(l), Some(r)) => Some(tape.mk(Op::Add(l, r), shape)),
                    (l, r) => l.or(r),
                }
            }
            Op::Transpose(a) => d(&a).map(|x| tape.mk(Op::Transpose(x), shape)),
            Op::Skew(a) => d(&a).map(|x| tape.mk(Op::Skew(x), shape)),
            Op::Trace(a) => d(&a).map(|x| tape.mk(Op::Trace(x), shape)),
            Op::Entry(a, i, j) => d(&a).map(|x| tape.mk(Op::Entry(x, i, j), shape)),
            Op::Det(a) => d(&a).map(|x| det_derivative(tape, a, x)),
        };
        memo.insert(id, result);
    }
    memo.get(&n).copied().flatten()
}

/// `d det(A) = sum_i det(A with row i replaced by row i of dA)`.
fn det_derivative(tape: &mut Tape, a: NodeId, da: NodeId) -> NodeId {
    let s = tape.shape(a);
    let mut acc: Option<NodeId> = None;
    for i in 0..s.rows {
        let mut e = Vec::with_capacity(s.len());
        for r in 0..s.rows {
            for c in 0..s.cols {
                let src = if r == i { da } else { a };
                e.push(tape.mk(Op::Entry(src, r, c), Shape::SCALAR));
            }
        }
        let m = tape.mk(Op::Build(s, e), s);
        let term = tape.mk(Op::Det(m), Shape::SCALAR);
        acc = Some(match acc {
            None => term,
            Some(x) => tape.mk(Op::Add(x, term), Shape::SCALAR),
        });
    }
    acc.unwrap_or_else(|| tape.konst(super::q_int(0)))
}

/// Whether node `n` or one of its operands satisfies `pred`.
pub(super) fn reaches(tape: &Tape, n: NodeId, pred: impl Fn(&Op) -> bool) -> bool {
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![n];
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        let Some(op) = tape.op(id) else { continue };
        if pred(op) {
            return true;
        }
        stack.extend(operands(op));
    }
    false
}

/// The operand nodes of an operation.
fn operands(op: &Op) -> Vec<NodeId> {
    match op {
        Op::Const(_) | Op::Unknown(_) | Op::Data(_) | Op::Recip(_) | Op::Identity => Vec::new(),
        Op::Build(_, e) => e.clone(),
        Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => vec![*a, *b],
        Op::Neg(a)
        | Op::Transpose(a)
        | Op::Skew(a)
        | Op::Det(a)
        | Op::Trace(a)
        | Op::Entry(a, _, _) => vec![*a],
    }
}
