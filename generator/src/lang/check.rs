//! Name resolution, loop unrolling and shape checking: statements to a [`Checked`] problem.
//!
//! The result is a tape of matrix-valued nodes (hash-consed, so a subexpression that occurs
//! several times, such as `skew(t)` in every loop iteration, is one node and is evaluated
//! once) plus the list of scalar equations, each an entry of a node.
//!
//! This file holds the statements (declarations, loops, equations, `nonzero`, `option`);
//! `expr` lowers expressions to tape nodes, and `ir` folds constants as nodes are added.

use super::ast::{Decl, Expr, Name, Stmt};
use super::ir::Tape;
pub use super::ir::{Checked, Node, NodeId, Op, ScalarEquation, Shape, MAX_DEGREE};
use super::lexer::Pos;
use super::names::{check_problem_name, FieldNames};
use super::LangError;
use crate::problem::{
    DataKind, DataSymbol, PolynomialSaturation, ProblemLayout, UnknownSymbol, MAX_WEIGHTED_ORDERS,
};
use expr::q_int;
use std::collections::HashMap;

mod diff;
mod expr;

/// Names that cannot be declared: the identity and the built-in functions.
pub const BUILTINS: [&str; 5] = ["I", "skew", "det", "trace", "diff"];

const MAX_ARRAY_LEN: usize = 100_000;
/// Most data slots of one declaration (array length times the kind's slots).
const MAX_DECL_SLOTS: usize = 1_000_000;
/// The most data slots a problem may declare in all: every slot is a field of the emitted
/// `Data` struct, a symbol of the expansion and of every coefficient the emitter traces,
/// so their number multiplies the memory of every later stage; minimal problems have at
/// most a few hundred.
pub const MAX_DATA_SLOTS: usize = 10_000;
/// Most Gauss-Newton steps `option newton` may ask for (polishing converges in one or two
/// from an eigenvector's solution; more only costs time).
pub const MAX_NEWTON_STEPS: u32 = 8;
const MAX_NODES: usize = 2_000_000;
const MAX_ITERATIONS: usize = 1_000_000;
const MAX_EQUATIONS: usize = 100_000;
#[derive(Clone, Copy, Debug)]
enum Sym {
    Unknown(usize),
    Data(usize),
}

#[derive(Clone, Debug)]
enum Binding {
    Value(Val),
    LoopVar(i64),
}

/// A checked value: a tape node, or an array symbol not yet indexed.
#[derive(Clone, Copy, Debug)]
enum Val {
    Node(NodeId),
    DataArray(usize),
    UnknownVec(usize),
}

struct Checker {
    layout: ProblemLayout,
    symbols: HashMap<String, Sym>,
    scopes: Vec<HashMap<String, Binding>>,
    tape: Tape,
    equations: Vec<ScalarEquation>,
    iterations: usize,
    fields: FieldNames,
    /// `nonzero` expressions: (node, position).
    nonzero: Vec<(NodeId, Pos)>,
    /// `option` statements: (name, value).
    options: Vec<(Name, Name)>,
}

/// Checks parsed statements.
pub fn check(stmts: &[(Pos, Stmt)]) -> Result<Checked, LangError> {
    let Some((first_pos, first)) = stmts.first() else {
        return Err(LangError::new(
            Pos { line: 1, column: 1 },
            "expected 'problem NAME' as the first statement, found end of file",
        ));
    };
    let (problem_pos, name) = match first {
        Stmt::Problem { pos, name } => {
            check_problem_name(name)?;
            (*pos, name.name.clone())
        }
        _ => {
            return Err(LangError::new(
                *first_pos,
                "expected 'problem NAME' as the first statement",
            ))
        }
    };
    let mut c = Checker {
        layout: ProblemLayout {
            name,
            unknowns: Vec::new(),
            data: Vec::new(),
            eliminate: Vec::new(),
            positive: Vec::new(),
            options: Default::default(),
        },
        symbols: HashMap::new(),
        scopes: vec![HashMap::new()],
        tape: Tape::default(),
        equations: Vec::new(),
        iterations: 0,
        fields: FieldNames::default(),
        nonzero: Vec::new(),
        options: Vec::new(),
    };
    for (pos, s) in stmts.iter().skip(1) {
        c.statement(*pos, s, true)?;
    }
    if c.layout.unknowns.is_empty() {
        return Err(LangError::new(
            problem_pos,
            "the problem declares no unknowns (add 'unknown NAME')",
        ));
    }
    if c.equations.is_empty() {
        return Err(LangError::new(
            problem_pos,
            "the problem has no equations (add 'lhs = rhs')",
        ));
    }
    c.saturate();
    c.check_options()?;
    Ok(Checked {
        layout: c.layout,
        nodes: c.tape.nodes,
        equations: c.equations,
    })
}

impl Checker {
    fn err(&self, pos: Pos, msg: impl Into<String>) -> LangError {
        LangError::new(pos, msg)
    }

    fn lookup(&self, name: &str) -> Option<Binding> {
        for s in self.scopes.iter().rev() {
            if let Some(b) = s.get(name) {
                return Some(b.clone());
            }
        }
        match self.symbols.get(name) {
            Some(Sym::Unknown(i)) => Some(Binding::Value(Val::UnknownVec(*i))),
            Some(Sym::Data(i)) => Some(Binding::Value(Val::DataArray(*i))),
            None => None,
        }
    }

    fn check_new_name(&self, n: &Name) -> Result<(), LangError> {
        if BUILTINS.contains(&n.name.as_str()) {
            return Err(self.err(
                n.pos,
                format!("'{}' is built in and cannot be declared", n.name),
            ));
        }
        if self.symbols.contains_key(&n.name) || self.scopes.iter().any(|s| s.contains_key(&n.name))
        {
            return Err(self.err(
                n.pos,
                format!("duplicate name '{}': it is already declared", n.name),
            ));
        }
        Ok(())
    }

    fn statement(&mut self, pos: Pos, s: &Stmt, top: bool) -> Result<(), LangError> {
        let only_top = |what: &str| {
            LangError::new(
                pos,
                format!("'{what}' must be at the top level, not inside a 'for' block"),
            )
        };
        match s {
            Stmt::Problem { pos, .. } => Err(self.err(
                *pos,
                "duplicate 'problem' statement: it must appear once, first",
            )),
            Stmt::Unknown(decls) => {
                if !top {
                    return Err(only_top("unknown"));
                }
                for d in decls {
                    self.declare_unknown(d)?;
                }
                Ok(())
            }
            Stmt::Data(decls) => {
                if !top {
                    return Err(only_top("data"));
                }
                for d in decls {
                    self.declare_data(d)?;
                }
                Ok(())
            }
            Stmt::Eliminate(names) => {
                if !top {
                    return Err(only_top("eliminate"));
                }
                self.name_unknowns(names, "eliminate", "eliminated", |l| &mut l.eliminate)
            }
            Stmt::Positive(names) => {
                if !top {
                    return Err(only_top("positive"));
                }
                self.name_unknowns(names, "positive", "declared positive", |l| &mut l.positive)
            }
            Stmt::Nonzero { pos, expr } => {
                if !top {
                    return Err(only_top("nonzero"));
                }
                let v = self.value(expr)?;
                let shape = self.tape.shape(v);
                if !shape.is_scalar() {
                    return Err(self.err(
                        expr.pos,
                        format!(
                            "'nonzero' needs a scalar expression, found {}",
                            shape.describe()
                        ),
                    ));
                }
                if self.tape.constant(v).is_some() {
                    return Err(self.err(
                        expr.pos,
                        "'nonzero' needs an expression in the unknowns, found a constant",
                    ));
                }
                if diff::reaches(&self.tape, v, |op| matches!(op, Op::Recip(_))) {
                    return Err(self.err(
                        expr.pos,
                        "'nonzero' needs a polynomial (no negative powers or division by unknowns)",
                    ));
                }
                self.nonzero.push((v, *pos));
                Ok(())
            }
            Stmt::Option { name, value } => {
                if !top {
                    return Err(only_top("option"));
                }
                self.options.push((name.clone(), value.clone()));
                Ok(())
            }
            Stmt::Let { name, value } => {
                self.check_new_name(name)?;
                let v = self.expr(value)?;
                if let Some(scope) = self.scopes.last_mut() {
                    scope.insert(name.name.clone(), Binding::Value(v));
                }
                Ok(())
            }
            Stmt::For {
                var,
                start,
                end,
                body,
                ..
            } => {
                self.check_new_name(var)?;
                if end.0 <= start.0 {
                    return Err(self.err(
                        end.1,
                        format!(
                            "empty range {}..{}: the end must be greater than the start",
                            start.0, end.0
                        ),
                    ));
                }
                let count = (end.0 as i128 - start.0 as i128) as u128;
                if count > MAX_ARRAY_LEN as u128 {
                    return Err(self.err(
                        end.1,
                        format!(
                            "range {}..{} is too long (at most {MAX_ARRAY_LEN} values)",
                            start.0, end.0
                        ),
                    ));
                }
                for k in start.0..end.0 {
                    self.iterations += 1;
                    if self.iterations > MAX_ITERATIONS {
                        return Err(self.err(
                            var.pos,
                            format!(
                                "too many loop iterations in total (more than {MAX_ITERATIONS})"
                            ),
                        ));
                    }
                    let mut scope = HashMap::new();
                    scope.insert(var.name.clone(), Binding::LoopVar(k));
                    self.scopes.push(scope);
                    let r = body
                        .iter()
                        .try_for_each(|(p, s)| self.statement(*p, s, false));
                    self.scopes.pop();
                    r?;
                }
                Ok(())
            }
            Stmt::Equation { lhs, eq, rhs } => self.equation(lhs, *eq, rhs),
        }
    }

    /// Saturation by the Rabinowitsch trick: for the k-th `nonzero EXPR`, a hidden unknown
    /// `nonzero#k` (after all declared unknowns) and the equation `nonzero#k * EXPR = 1`,
    /// which has exactly the solutions of the other equations where EXPR does not vanish.
    fn saturate(&mut self) {
        for (k, (node, pos)) in std::mem::take(&mut self.nonzero).into_iter().enumerate() {
            let var = self.layout.unknown_count();
            self.layout.unknowns.push(UnknownSymbol {
                name: format!("nonzero#{}", k + 1),
                len: None,
                first_var: var,
                hidden: true,
            });
            let z = self.tape.mk(Op::Unknown(var), Shape::SCALAR);
            let prod = self.tape.mk(Op::Mul(z, node), Shape::SCALAR);
            let one = self.tape.konst(q_int(1));
            let diff = self.tape.mk(Op::Sub(prod, one), Shape::SCALAR);
            self.equations.push(ScalarEquation {
                node: diff,
                row: 0,
                col: 0,
                line: pos.line,
            });
        }
    }

    /// Checks the `option` statements into `layout.options` (`newton` at most
    /// [`MAX_NEWTON_STEPS`]).
    fn check_options(&mut self) -> Result<(), LangError> {
        let names = self.layout.unknown_names();
        for (name, value) in std::mem::take(&mut self.options) {
            let o = &mut self.layout.options;
            let v = value.name.clone();
            let bad = |what: &str| Err(LangError::new(value.pos, what.to_string()));
            let seen = match name.name.as_str() {
                "action" => {
                    let unknown = |n: &str| names.iter().any(|m| m == n);
                    let inverse = v.strip_prefix("1/").is_some_and(unknown);
                    if v != "random" && !unknown(&v) && !inverse {
                        return bad(&format!(
                            "option action: expected an unknown scalar ({}), its inverse '1/NAME' or 'random', found '{v}'",
                            names
                                .iter()
                                .filter(|n| !n.contains('#'))
                                .cloned()
                                .collect::<Vec<_>>()
                                .join(", ")
                        ));
                    }
                    o.action.replace(v).is_some()
                }
                "extra_degree" => match v.parse::<u32>() {
                    Ok(d) if d <= 64 => o.extra_degree.replace(d).is_some(),
                    _ => {
                        return bad(&format!(
                            "option extra_degree: expected an integer from 0 to 64, found '{v}'"
                        ))
                    }
                },
                "basis" => {
                    if v != "standard" && v != "selected" {
                        return bad(&format!(
                            "option basis: expected 'standard' or 'selected', found '{v}'"
                        ));
                    }
                    o.basis.replace(v).is_some()
                }
                "newton" => match v.parse::<u32>() {
                    Ok(d) if d <= MAX_NEWTON_STEPS => o.newton.replace(d).is_some(),
                    _ => {
                        return bad(&format!(
                            "option newton: expected an integer from 0 to {MAX_NEWTON_STEPS}, found '{v}'"
                        ))
                    }
                },
                flag @ ("auto_eliminate" | "reduce_equations" | "sign_symmetry"
                | "redundant_basis") => {
                    let on = match v.as_str() {
                        "yes" => true,
                        "no" => false,
                        _ => {
                            return bad(&format!(
                                "option {flag}: expected 'yes' or 'no', found '{v}'"
                            ))
                        }
                    };
                    let slot = match flag {
                        "auto_eliminate" => &mut o.auto_eliminate,
                        "reduce_equations" => &mut o.reduce_equations,
                        "redundant_basis" => &mut o.redundant_basis,
                        _ => &mut o.sign_symmetry,
                    };
                    slot.replace(on).is_some()
                }
                "weighted_orders" => match v.parse::<usize>() {
                    Ok(n) if n <= MAX_WEIGHTED_ORDERS => o.weighted_orders.replace(n).is_some(),
                    _ => {
                        return bad(&format!(
                            "option weighted_orders: expected an integer from 0 to {MAX_WEIGHTED_ORDERS}, found '{v}'"
                        ))
                    }
                },
                "saturation" => match PolynomialSaturation::parse(&v) {
                    Some(s) => o.saturation.replace(s).is_some(),
                    None => {
                        return bad(&format!(
                            "option saturation: expected 'smaller', 'template' or 'unknown', found '{v}'"
                        ))
                    }
                },
                other => {
                    return Err(LangError::new(
                        name.pos,
                        format!(
                            "unknown option '{other}' (the options are action, extra_degree, basis, newton, auto_eliminate, reduce_equations, sign_symmetry, redundant_basis, weighted_orders, saturation)"
                        ),
                    ))
                }
            };
            if seen {
                return Err(LangError::new(
                    name.pos,
                    format!("option {} is given twice", name.name),
                ));
            }
        }
        Ok(())
    }

    fn declare_unknown(&mut self, d: &Decl) -> Result<(), LangError> {
        self.check_new_name(&d.name)?;
        let len = match d.len {
            Some((n, p)) if n > MAX_ARRAY_LEN => {
                return Err(self.err(
                    p,
                    format!("length {n} is too large (at most {MAX_ARRAY_LEN})"),
                ))
            }
            other => other.map(|(n, _)| n),
        };
        self.fields.unknown(&d.name, len)?;
        let first_var = self.layout.unknown_count();
        self.symbols.insert(
            d.name.name.clone(),
            Sym::Unknown(self.layout.unknowns.len()),
        );
        self.layout.unknowns.push(UnknownSymbol {
            name: d.name.name.clone(),
            len,
            first_var,
            hidden: false,
        });
        Ok(())
    }

    fn declare_data(&mut self, d: &Decl) -> Result<(), LangError> {
        self.check_new_name(&d.name)?;
        let len = match d.len {
            Some((n, p)) if n > MAX_ARRAY_LEN => {
                return Err(self.err(
                    p,
                    format!("length {n} is too large (at most {MAX_ARRAY_LEN})"),
                ))
            }
            other => other.map(|(n, _)| n),
        };
        self.fields.data(&d.name)?;
        let Some(k) = &d.kind else {
            return Err(self.err(d.name.pos, "missing kind"));
        };
        let kind = DataKind::parse(&k.name).map_err(|m| self.err(k.pos, m))?;
        let slots = kind.slots().saturating_mul(len.unwrap_or(1));
        if slots > MAX_DECL_SLOTS {
            return Err(self.err(
                d.name.pos,
                format!(
                    "data '{}' has too many slots ({slots}; at most {MAX_DECL_SLOTS} per declaration)",
                    d.name.name
                ),
            ));
        }
        let first_slot = self.layout.data_slot_count();
        if first_slot.saturating_add(slots) > MAX_DATA_SLOTS {
            return Err(self.err(
                d.name.pos,
                format!(
                    "data '{}' brings the problem to {} data slots (at most {MAX_DATA_SLOTS} in all)",
                    d.name.name,
                    first_slot.saturating_add(slots)
                ),
            ));
        }
        self.symbols
            .insert(d.name.name.clone(), Sym::Data(self.layout.data.len()));
        self.layout.data.push(DataSymbol {
            name: d.name.name.clone(),
            kind,
            len,
            first_slot,
        });
        Ok(())
    }

    /// Appends the variables of the unknowns `names` (after `keyword`) to the layout's
    /// list `list`; an unknown already there is an error ("'x' is already `done`").
    fn name_unknowns(
        &mut self,
        names: &[Name],
        keyword: &str,
        done: &str,
        list: fn(&mut ProblemLayout) -> &mut Vec<usize>,
    ) -> Result<(), LangError> {
        for n in names {
            let vars = self.unknown_vars(n, keyword)?;
            if vars.iter().any(|v| list(&mut self.layout).contains(v)) {
                return Err(self.err(n.pos, format!("'{}' is already {done}", n.name)));
            }
            list(&mut self.layout).extend(vars);
        }
        Ok(())
    }

    /// The variables of the unknown `n` names after `keyword` (`eliminate`, `positive`).
    fn unknown_vars(&self, n: &Name, keyword: &str) -> Result<Vec<usize>, LangError> {
        let u = match self.symbols.get(&n.name) {
            Some(Sym::Unknown(i)) => self.layout.unknowns.get(*i).cloned(),
            Some(Sym::Data(_)) => {
                return Err(self.err(
                    n.pos,
                    format!(
                        "'{}' is data, not an unknown: '{keyword}' names unknowns",
                        n.name
                    ),
                ))
            }
            None => None,
        };
        let Some(u) = u else {
            return Err(self.err(
                n.pos,
                format!("'{keyword}' names an undeclared unknown '{}'", n.name),
            ));
        };
        Ok((u.first_var..u.first_var + u.len.unwrap_or(1)).collect())
    }

    fn equation(&mut self, lhs: &Expr, eq: Pos, rhs: &Expr) -> Result<(), LangError> {
        let l = self.value(lhs)?;
        let r = self.value(rhs)?;
        let (ls, rs) = (self.tape.shape(l), self.tape.shape(r));
        let diff = if ls == rs {
            self.tape.mk(Op::Sub(l, r), ls)
        } else if rs.is_scalar() && self.tape.is_const_zero(r) {
            l
        } else if ls.is_scalar() && self.tape.is_const_zero(l) {
            r
        } else {
            return Err(self.err(
                eq,
                format!(
                    "the sides of '=' differ in shape: {} on the left, {} on the right (only 0 may stand for a zero matrix)",
                    ls.describe(),
                    rs.describe()
                ),
            ));
        };
        let shape = self.tape.shape(diff);
        let degree = self.tape.nodes.get(diff).map_or(0, |n| n.degree);
        if degree > MAX_DEGREE {
            return Err(self.err(
                eq,
                format!("equation degree too high (up to {degree} in unknowns and data; at most {MAX_DEGREE})"),
            ));
        }
        if self.equations.len() + shape.len() > MAX_EQUATIONS {
            return Err(self.err(
                eq,
                format!("too many scalar equations (more than {MAX_EQUATIONS})"),
            ));
        }
        for row in 0..shape.rows {
            for col in 0..shape.cols {
                self.equations.push(ScalarEquation {
                    node: diff,
                    row,
                    col,
                    line: eq.line,
                });
            }
        }
        Ok(())
    }
}
