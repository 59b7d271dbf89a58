//! Expressions to tape nodes: names, literals, arithmetic with shape rules, indexing and
//! the built-in functions. Every value the checker builds goes through here, so the node
//! budget and the shape errors live in one place.

use super::{Binding, Checker, Val, BUILTINS, MAX_NODES};
use crate::algebra::Q;
use crate::lang::ast::{AddOp, Expr, ExprKind, MulOp, Name, Postfix};
use crate::lang::ir::{NodeId, Op, Shape};
use crate::lang::lexer::Pos;
use crate::lang::LangError;
use crate::problem::{DataKind, DataSymbol};
use num_bigint::BigInt;
use num_traits::{One, ToPrimitive, Zero};

/// The largest matrix `det` expands (by cofactors: `n!` products).
pub const MAX_DET: usize = 6;

/// An integer as a rational constant.
pub(super) fn q_int(n: i64) -> Q {
    Q::from_integer(BigInt::from(n))
}

/// Parses a literal such as `2`, `0.5`, `12.250` or `1.5e-3` exactly.
fn parse_number(s: &str, pos: Pos) -> Result<Q, LangError> {
    let bad = || LangError::new(pos, format!("malformed number {s}"));
    if let Some((mantissa, exponent)) = s.split_once(['e', 'E']) {
        let e: i32 = exponent.parse().map_err(|_| bad())?;
        if e.unsigned_abs() > 1000 {
            return Err(LangError::new(
                pos,
                format!("the exponent of {s} is out of range (at most 1000 in magnitude)"),
            ));
        }
        let m = parse_number(mantissa, pos)?;
        let p = Q::from_integer(num_traits::pow(BigInt::from(10), e.unsigned_abs() as usize));
        return Ok(if e >= 0 { m * p } else { m / p });
    }
    let (int, frac) = match s.split_once('.') {
        Some((a, b)) => (a, b),
        None => (s, ""),
    };
    let digits = format!("{int}{frac}");
    let n: BigInt = digits.parse().map_err(|_| bad())?;
    if frac.len() > 1000 {
        return Err(bad());
    }
    let d = num_traits::pow(BigInt::from(10), frac.len());
    Ok(Q::new(n, d))
}

impl Checker {
    fn budget(&self, pos: Pos) -> Result<(), LangError> {
        if self.tape.nodes.len() > MAX_NODES {
            return Err(self.err(
                pos,
                format!("problem too large (more than {MAX_NODES} expression nodes)"),
            ));
        }
        Ok(())
    }

    /// The node of a value, or an error for an unindexed array.
    pub(super) fn value(&mut self, e: &Expr) -> Result<NodeId, LangError> {
        let v = self.expr(e)?;
        self.node_of(v, e.pos)
    }

    fn node_of(&mut self, v: Val, pos: Pos) -> Result<NodeId, LangError> {
        match v {
            Val::Node(n) => Ok(n),
            Val::DataArray(i) => {
                let Some(d) = self.layout.data.get(i).cloned() else {
                    return Err(self.err(pos, "internal error: bad data symbol"));
                };
                match d.len {
                    None => Ok(self.data_element(&d, 0)),
                    Some(n) => Err(self.err(
                        pos,
                        format!(
                            "'{}' is an array of {n} {}s: index it, as in {}[k]",
                            d.name,
                            d.kind.keyword(),
                            d.name
                        ),
                    )),
                }
            }
            Val::UnknownVec(i) => {
                let Some(u) = self.layout.unknowns.get(i).cloned() else {
                    return Err(self.err(pos, "internal error: bad unknown symbol"));
                };
                match u.len {
                    None | Some(1) => Ok(self.tape.mk(Op::Unknown(u.first_var), Shape::SCALAR)),
                    Some(n) => {
                        let e: Vec<NodeId> = (0..n)
                            .map(|k| self.tape.mk(Op::Unknown(u.first_var + k), Shape::SCALAR))
                            .collect();
                        let s = Shape { rows: n, cols: 1 };
                        Ok(self.tape.mk(Op::Build(s, e), s))
                    }
                }
            }
        }
    }

    fn data_element(&mut self, d: &DataSymbol, elem: usize) -> NodeId {
        let base = d.first_slot + elem * d.kind.slots();
        let slot = |c: &mut Checker, k: usize| c.tape.mk(Op::Data(base + k), Shape::SCALAR);
        let (rows, cols) = d.kind.shape();
        if rows * cols == 1 {
            return slot(self, 0);
        }
        let mut e: Vec<NodeId> = (0..d.kind.slots()).map(|k| slot(self, k)).collect();
        if d.kind == DataKind::Point {
            e.push(self.tape.konst(Q::one()));
        }
        let s = Shape { rows, cols };
        self.tape.mk(Op::Build(s, e), s)
    }

    /// An index expression's value, checked against `len`.
    fn index(&mut self, e: &Expr, len: usize, what: &str) -> Result<usize, LangError> {
        let n = self.value(e)?;
        let Some(q) = self.tape.constant(n).cloned() else {
            return Err(self.err(
                e.pos,
                format!("the index of {what} must be an integer constant or loop variable"),
            ));
        };
        if !q.is_integer() {
            return Err(self.err(
                e.pos,
                format!("the index of {what} must be an integer, found {q}"),
            ));
        }
        let i = q.to_integer();
        match i.to_usize() {
            Some(i) if i < len => Ok(i),
            _ => Err(self.err(
                e.pos,
                format!(
                    "index {i} out of range for {what} (valid indices 0..{})",
                    len.saturating_sub(1)
                ),
            )),
        }
    }

    pub(super) fn expr(&mut self, e: &Expr) -> Result<Val, LangError> {
        self.budget(e.pos)?;
        match &e.kind {
            ExprKind::Number(s) => {
                let q = parse_number(s, e.pos)?;
                Ok(Val::Node(self.tape.konst(q)))
            }
            ExprKind::Name(name) => match self.lookup(name) {
                Some(Binding::Value(v)) => Ok(v),
                Some(Binding::LoopVar(k)) => Ok(Val::Node(self.tape.konst(q_int(k)))),
                None if name == "I" => Ok(Val::Node(self.tape.mk(Op::Identity, Shape::MAT))),
                None if BUILTINS.contains(&name.as_str()) => Err(self.err(
                    e.pos,
                    format!("'{name}' is a function: call it, as in {name}(...)"),
                )),
                None => Err(self.err(e.pos, format!("unknown symbol '{name}'"))),
            },
            ExprKind::Paren(inner) => self.expr(inner),
            ExprKind::Neg(inner) => {
                let n = self.value(inner)?;
                let s = self.tape.shape(n);
                Ok(Val::Node(self.tape.mk(Op::Neg(n), s)))
            }
            ExprKind::Call(f, arg) => self.call(f, arg),
            ExprKind::Sum(first, rest) => {
                let mut acc = self.value(first)?;
                for (op, pos, t) in rest {
                    let n = self.value(t)?;
                    let (a, b) = (self.tape.shape(acc), self.tape.shape(n));
                    if a != b {
                        return Err(self.err(
                            *pos,
                            format!(
                                "cannot {} {} and {}: shapes differ",
                                if *op == AddOp::Add { "add" } else { "subtract" },
                                a.describe(),
                                b.describe()
                            ),
                        ));
                    }
                    acc = match op {
                        AddOp::Add => self.tape.mk(Op::Add(acc, n), a),
                        AddOp::Sub => self.tape.mk(Op::Sub(acc, n), a),
                    };
                }
                Ok(Val::Node(acc))
            }
            ExprKind::Product(first, rest) => {
                let mut acc = self.value(first)?;
                for (op, pos, t) in rest {
                    let n = self.value(t)?;
                    let (a, b) = (self.tape.shape(acc), self.tape.shape(n));
                    match op {
                        MulOp::Mul => {
                            let s = if a.is_scalar() {
                                b
                            } else if b.is_scalar() {
                                a
                            } else if a.cols == b.rows {
                                Shape {
                                    rows: a.rows,
                                    cols: b.cols,
                                }
                            } else {
                                return Err(self.err(
                                    *pos,
                                    format!(
                                        "cannot multiply {} by {}: inner dimensions {} and {} differ",
                                        a.describe(),
                                        b.describe(),
                                        a.cols,
                                        b.rows
                                    ),
                                ));
                            };
                            acc = self.tape.mk(Op::Mul(acc, n), s);
                        }
                        MulOp::Div => {
                            let inv = self.reciprocal(n, t.pos)?;
                            acc = self.tape.mk(Op::Mul(acc, inv), a);
                        }
                    }
                }
                Ok(Val::Node(acc))
            }
            ExprKind::Postfix(base, ops) => {
                let mut v = self.expr(base)?;
                for p in ops {
                    v = match p {
                        Postfix::Transpose(_) => {
                            let n = self.node_of(v, base.pos)?;
                            let s = self.tape.shape(n);
                            Val::Node(self.tape.mk(
                                Op::Transpose(n),
                                Shape {
                                    rows: s.cols,
                                    cols: s.rows,
                                },
                            ))
                        }
                        Postfix::Index(idx, pos) => self.indexed(v, idx, *pos)?,
                    };
                }
                Ok(v)
            }
            ExprKind::List(items) => self.list(items, e.pos),
            ExprKind::Recip(inner) => {
                let n = self.value(inner)?;
                Ok(Val::Node(self.reciprocal(n, inner.pos)?))
            }
            ExprKind::Diff(inner, var) => {
                let n = self.value(inner)?;
                let x = self.value(var)?;
                let Some(&Op::Unknown(v)) = self.tape.op(x) else {
                    return Err(self.err(
                        var.pos,
                        "diff(EXPR, x) differentiates by an unknown scalar (such as x or q[0])",
                    ));
                };
                let mut memo = std::collections::HashMap::new();
                let d = super::diff::derivative(&mut self.tape, n, v, &mut memo);
                let s = self.tape.shape(n);
                let zero = self.tape.konst(q_int(0));
                let out = match d {
                    Some(d) => d,
                    None if s.is_scalar() => zero,
                    None => self.tape.mk(Op::Build(s, vec![zero; s.len()]), s),
                };
                self.budget(e.pos)?;
                Ok(Val::Node(out))
            }
        }
    }

    /// The reciprocal of a divisor: a non-zero constant, or a monomial in the unknowns (a
    /// product of unknowns, their reciprocals and a non-zero constant), whose reciprocal
    /// is a Laurent monomial (`Op::Recip` leaves).
    fn reciprocal(&mut self, n: NodeId, pos: Pos) -> Result<NodeId, LangError> {
        let in_unknowns = super::diff::reaches(&self.tape, n, |op| {
            matches!(op, Op::Unknown(_) | Op::Recip(_))
        });
        if !in_unknowns {
            let Some(q) = self.tape.constant(n).cloned() else {
                return Err(self.err(
                    pos,
                    "the divisor must be a constant (numbers and loop variables only)",
                ));
            };
            if q.is_zero() {
                return Err(self.err(pos, "division by zero"));
            }
            return Ok(self.tape.konst(q.recip()));
        }
        let s = self.tape.shape(n);
        if !s.is_scalar() {
            return Err(self.err(
                pos,
                format!(
                    "the divisor must be a scalar monomial in the unknowns, found {}",
                    s.describe()
                ),
            ));
        }
        self.monomial_reciprocal(n, pos, 0)
    }

    fn monomial_reciprocal(
        &mut self,
        n: NodeId,
        pos: Pos,
        depth: usize,
    ) -> Result<NodeId, LangError> {
        let not_monomial = |c: &Checker| {
            c.err(
                pos,
                "the divisor must be a monomial in the unknowns (a product of unknowns and a non-zero constant, as in 2*x*y^2)",
            )
        };
        if depth > 4 * crate::lang::parser::MAX_DEPTH {
            return Err(not_monomial(self));
        }
        match self.tape.op(n).cloned() {
            Some(Op::Unknown(i)) => Ok(self.tape.mk(Op::Recip(i), Shape::SCALAR)),
            Some(Op::Recip(i)) => Ok(self.tape.mk(Op::Unknown(i), Shape::SCALAR)),
            Some(Op::Const(q)) if !q.is_zero() => Ok(self.tape.konst(q.recip())),
            Some(Op::Neg(a)) => {
                let r = self.monomial_reciprocal(a, pos, depth + 1)?;
                Ok(self.tape.mk(Op::Neg(r), Shape::SCALAR))
            }
            Some(Op::Mul(a, b))
                if self.tape.shape(a).is_scalar() && self.tape.shape(b).is_scalar() =>
            {
                let ra = self.monomial_reciprocal(a, pos, depth + 1)?;
                let rb = self.monomial_reciprocal(b, pos, depth + 1)?;
                Ok(self.tape.mk(Op::Mul(ra, rb), Shape::SCALAR))
            }
            _ => Err(not_monomial(self)),
        }
    }

    fn indexed(&mut self, v: Val, idx: &Expr, pos: Pos) -> Result<Val, LangError> {
        match v {
            Val::DataArray(i) => {
                let Some(d) = self.layout.data.get(i).cloned() else {
                    return Err(self.err(pos, "internal error: bad data symbol"));
                };
                if let Some(len) = d.len {
                    let k = self.index(idx, len, &format!("'{}'", d.name))?;
                    return Ok(Val::Node(self.data_element(&d, k)));
                }
                let n = self.data_element(&d, 0);
                self.index_node(n, idx, &format!("'{}'", d.name))
            }
            Val::UnknownVec(i) => {
                let Some(u) = self.layout.unknowns.get(i).cloned() else {
                    return Err(self.err(pos, "internal error: bad unknown symbol"));
                };
                let Some(len) = u.len else {
                    return Err(
                        self.err(pos, format!("cannot index the scalar unknown '{}'", u.name))
                    );
                };
                let k = self.index(idx, len, &format!("'{}'", u.name))?;
                Ok(Val::Node(
                    self.tape.mk(Op::Unknown(u.first_var + k), Shape::SCALAR),
                ))
            }
            Val::Node(n) => self.index_node(n, idx, "this value"),
        }
    }

    fn index_node(&mut self, n: NodeId, idx: &Expr, what: &str) -> Result<Val, LangError> {
        let s = self.tape.shape(n);
        if s.is_scalar() {
            return Err(self.err(idx.pos, format!("cannot index a scalar ({what})")));
        }
        let len = if s.rows == 1 { s.cols } else { s.rows };
        let k = self.index(idx, len, what)?;
        if s.rows == 1 {
            Ok(Val::Node(self.tape.mk(Op::Entry(n, 0, k), Shape::SCALAR)))
        } else if s.cols == 1 {
            Ok(Val::Node(self.tape.mk(Op::Entry(n, k, 0), Shape::SCALAR)))
        } else {
            // A matrix row, 1x3.
            let e: Vec<NodeId> = (0..s.cols)
                .map(|j| self.tape.mk(Op::Entry(n, k, j), Shape::SCALAR))
                .collect();
            let row = Shape {
                rows: 1,
                cols: s.cols,
            };
            Ok(Val::Node(self.tape.mk(Op::Build(row, e), row)))
        }
    }

    fn scalar_items(&mut self, items: &[Expr]) -> Result<Vec<NodeId>, LangError> {
        let mut out = Vec::new();
        for it in items {
            let n = self.value(it)?;
            let s = self.tape.shape(n);
            if !s.is_scalar() {
                return Err(self.err(
                    it.pos,
                    format!(
                        "entries of a vector or matrix literal must be scalars, found {}",
                        s.describe()
                    ),
                ));
            }
            out.push(n);
        }
        Ok(out)
    }

    fn list(&mut self, items: &[Expr], pos: Pos) -> Result<Val, LangError> {
        let rows: Vec<&Vec<Expr>> = items
            .iter()
            .filter_map(|i| match &i.kind {
                ExprKind::List(r) => Some(r),
                _ => None,
            })
            .collect();
        if !rows.is_empty() {
            if rows.len() != items.len() {
                return Err(self.err(
                    pos,
                    format!(
                        "a matrix literal needs rows only, each a list [a, b, ...]; found {} rows among {} items",
                        rows.len(),
                        items.len()
                    ),
                ));
            }
            let cols = rows.first().map_or(0, |r| r.len());
            let mut entries = Vec::new();
            for (r, item) in rows.iter().zip(items) {
                if r.len() != cols {
                    return Err(self.err(
                        item.pos,
                        format!(
                            "the rows of a matrix literal differ in length: {cols} entries in the first, {} in this one",
                            r.len()
                        ),
                    ));
                }
                entries.extend(self.scalar_items(r)?);
            }
            let s = Shape {
                rows: rows.len(),
                cols,
            };
            if let [one] = entries[..] {
                return Ok(Val::Node(one));
            }
            return Ok(Val::Node(self.tape.mk(Op::Build(s, entries), s)));
        }
        let e = self.scalar_items(items)?;
        if e.len() == 1 {
            return Ok(Val::Node(e[0]));
        }
        let s = Shape {
            rows: e.len(),
            cols: 1,
        };
        Ok(Val::Node(self.tape.mk(Op::Build(s, e), s)))
    }

    fn call(&mut self, f: &Name, arg: &Expr) -> Result<Val, LangError> {
        let fname = f.name.as_str();
        if !BUILTINS.contains(&fname) || fname == "I" || fname == "diff" {
            let msg = if self.lookup(fname).is_some() {
                format!("'{fname}' is not a function (write '*' for a product)")
            } else {
                format!("unknown function '{fname}' (the functions are skew, det, trace, diff(EXPR, x), and cross and dot of two vectors)")
            };
            return Err(self.err(f.pos, msg));
        }
        let n = self.value(arg)?;
        let s = self.tape.shape(n);
        match fname {
            "skew" => {
                if s != Shape::COL && s != Shape::ROW {
                    return Err(self.err(
                        arg.pos,
                        format!("skew() takes a 3-vector, found {}", s.describe()),
                    ));
                }
                Ok(Val::Node(self.tape.mk(Op::Skew(n), Shape::MAT)))
            }
            _ => {
                if s.rows != s.cols {
                    return Err(self.err(
                        arg.pos,
                        format!("{fname}() takes a square matrix, found {}", s.describe()),
                    ));
                }
                if fname == "det" && s.rows > MAX_DET {
                    return Err(self.err(
                        arg.pos,
                        format!(
                            "det() of {} is not supported (cofactor expansion up to {MAX_DET}x{MAX_DET})",
                            s.describe()
                        ),
                    ));
                }
                let op = if fname == "det" {
                    Op::Det(n)
                } else {
                    Op::Trace(n)
                };
                Ok(Val::Node(self.tape.mk(op, Shape::SCALAR)))
            }
        }
    }
}
