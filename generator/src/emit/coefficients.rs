//! From traced coefficients to straight-line code.
//!
//! A [`Program`] is the part of a [`Tracer`]'s DAG needed by a list
//! of outputs (dead nodes dropped), as a sequence of `let cK = <expr>;` statements plus one
//! expression per output. A node becomes a named statement when it is used more than once
//! (the shared subexpressions), when it is an output that must be computed up front, or
//! when inlining it would make an expression too large; every other node is inlined into
//! its single user, so the code stays compact and reads like hand-written arithmetic.
//!
//! The operation order of every node is kept exactly (parentheses are emitted wherever
//! floating-point associativity matters), so [`Program::eval`] — the f64 interpreter of
//! the program — computes bit for bit what the emitted code computes.
//! Statements are numbered in node-creation order: the same traced computation always
//! gives the same program.

use super::traced::{q_to_f64, NodeId, Op, Traced, TracedValue, Tracer};
use super::EmitError;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// Largest number of arithmetic operations inlined into one expression.
pub const MAX_INLINE_OPS: usize = 12;

/// An expression of a [`Program`].
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// Data slot `d[i]`.
    Input(usize),
    /// A literal.
    Const(f64),
    /// The value of statement `k` (`cK`).
    Var(usize),
    /// `a + b`.
    Add(Box<Expr>, Box<Expr>),
    /// `a - b`.
    Sub(Box<Expr>, Box<Expr>),
    /// `a * b`.
    Mul(Box<Expr>, Box<Expr>),
    /// `-a`.
    Neg(Box<Expr>),
}

impl Expr {
    /// Evaluates with data slots and statement values.
    pub fn eval(&self, data: &[f64], vars: &[f64]) -> f64 {
        match self {
            Expr::Input(i) => data[*i],
            Expr::Const(c) => *c,
            Expr::Var(k) => vars[*k],
            Expr::Add(a, b) => a.eval(data, vars) + b.eval(data, vars),
            Expr::Sub(a, b) => a.eval(data, vars) - b.eval(data, vars),
            Expr::Mul(a, b) => a.eval(data, vars) * b.eval(data, vars),
            Expr::Neg(a) => -a.eval(data, vars),
        }
    }
    /// Number of binary arithmetic operations.
    pub fn op_count(&self) -> usize {
        match self {
            Expr::Input(_) | Expr::Const(_) | Expr::Var(_) => 0,
            Expr::Neg(a) => a.op_count(),
            Expr::Add(a, b) | Expr::Sub(a, b) | Expr::Mul(a, b) => 1 + a.op_count() + b.op_count(),
        }
    }
    fn is_sum(&self) -> bool {
        matches!(self, Expr::Add(..) | Expr::Sub(..))
    }
    fn is_atom(&self) -> bool {
        matches!(self, Expr::Input(_) | Expr::Const(_) | Expr::Var(_))
    }
    /// Rust tokens (statement `k` is the identifier `cK`, data slot `i` is `d[i]`).
    pub fn to_tokens(&self) -> TokenStream {
        self.tokens(VarStyle::Locals)
    }
    /// Rust tokens with statement values spelled as `style` says (data slot `i` is `d[i]`).
    pub fn tokens(&self, style: VarStyle) -> TokenStream {
        let paren = |e: &Expr, needed: bool| {
            let t = e.tokens(style);
            if needed {
                quote!((#t))
            } else {
                t
            }
        };
        match self {
            Expr::Input(i) => {
                let i = Literal::usize_unsuffixed(*i);
                quote!(d[#i])
            }
            Expr::Const(c) => signed_f64_literal(*c),
            Expr::Var(k) => style.var(*k),
            // Left operands of + and - never need parentheses (left associativity); right
            // operands that are sums do, to keep the evaluation order.
            Expr::Add(a, b) => {
                let (a, b) = (paren(a, false), paren(b, b.is_sum()));
                quote!(#a + #b)
            }
            Expr::Sub(a, b) => {
                let (a, b) = (paren(a, false), paren(b, b.is_sum()));
                quote!(#a - #b)
            }
            Expr::Mul(a, b) => {
                let (a, b) = (paren(a, a.is_sum()), paren(b, !b.is_atom()));
                quote!(#a * #b)
            }
            Expr::Neg(a) => {
                let a = paren(a, !a.is_atom());
                quote!(-#a)
            }
        }
    }
}

/// How emitted code names the value of statement `k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarStyle {
    /// A local `let cK` (straight-line code inside `solve`).
    Locals,
    /// The array entry `c[K]` (the table form of large solvers: statements are spread over
    /// several functions that write one coefficient array, so no function grows without
    /// bound and compile time stays linear).
    Array,
}

impl VarStyle {
    /// The tokens naming statement `k`'s value.
    pub fn var(self, k: usize) -> TokenStream {
        match self {
            VarStyle::Locals => {
                let id = format_ident!("c{}", k);
                quote!(#id)
            }
            VarStyle::Array => {
                let k = Literal::usize_unsuffixed(k);
                quote!(c[#k])
            }
        }
    }
}

/// `v` as tokens: [`f64_literal`] of its magnitude, negated when its sign is.
pub fn signed_f64_literal(v: f64) -> TokenStream {
    let l = f64_literal(v.abs());
    if v.is_sign_negative() {
        quote!(-#l)
    } else {
        quote!(#l)
    }
}

/// An f64 literal token (finite, non-negative expected; shortest round-trip digits).
pub fn f64_literal(v: f64) -> Literal {
    Literal::f64_unsuffixed(v)
}

/// Straight-line code for a list of traced outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// Statement `k` binds `cK` to this expression (in terms of data and earlier statements).
    pub stmts: Vec<Expr>,
    /// One expression per output, in the order given to [`Program::build`].
    pub outputs: Vec<Expr>,
}

impl Program {
    /// Builds the program for `inline_outputs` (whose expressions may be inlined where they
    /// are used) followed by `bound_outputs` (always computed by a statement of their own,
    /// or a literal/data slot, so that using them later is free). Data slots must be below
    /// `slot_count`.
    pub fn build(
        inline_outputs: &[Traced],
        bound_outputs: &[Traced],
        slot_count: usize,
    ) -> Result<Program, EmitError> {
        let all: Vec<&Traced> = inline_outputs.iter().chain(bound_outputs).collect();
        let mut tracer: Option<&Tracer> = None;
        for t in &all {
            if let Some(tr) = t.tracer() {
                match tracer {
                    None => tracer = Some(tr),
                    Some(t0) if !t0.same_graph(tr) => return Err(EmitError::MixedTracers),
                    Some(_) => {}
                }
            }
        }
        let ops = tracer.map(Tracer::ops).unwrap_or_default();
        let n = ops.len();
        let node_of = |t: &Traced| match t.value() {
            TracedValue::Node { id, .. } => Some(id as usize),
            TracedValue::Const(_) => None,
        };

        // Liveness (children have smaller ids than parents) and use counts.
        let mut live = vec![false; n];
        let mut uses = vec![0usize; n];
        let mut forced = vec![false; n];
        for (k, t) in all.iter().enumerate() {
            if let Some(id) = node_of(t) {
                live[id] = true;
                uses[id] += 1;
                if k >= inline_outputs.len() {
                    forced[id] = true;
                }
            }
        }
        for id in (0..n).rev() {
            if !live[id] {
                continue;
            }
            match &ops[id] {
                Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => {
                    for c in [*a, *b] {
                        live[c as usize] = true;
                        uses[c as usize] += 1;
                    }
                }
                Op::Input(s) => {
                    if *s >= slot_count {
                        return Err(EmitError::Invalid(format!(
                            "traced data slot {s} out of range (the layout has {slot_count} slots)"
                        )));
                    }
                }
                Op::Const(q) => {
                    if !q_to_f64(q).is_finite() {
                        return Err(EmitError::Invalid(format!(
                            "constant {q} has no finite f64 value"
                        )));
                    }
                }
            }
        }

        // Which arithmetic nodes get a statement.
        let mut bound = vec![false; n];
        let mut size = vec![0usize; n]; // ops of the inlined expression
        for id in 0..n {
            if !live[id] {
                continue;
            }
            if let Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) = &ops[id] {
                let s = 1 + size[*a as usize] + size[*b as usize];
                if forced[id] || uses[id] >= 2 || s > MAX_INLINE_OPS {
                    bound[id] = true;
                    size[id] = 0;
                } else {
                    size[id] = s;
                }
            }
        }
        let mut var_of = vec![usize::MAX; n];
        let mut next = 0;
        for id in 0..n {
            if bound[id] {
                var_of[id] = next;
                next += 1;
            }
        }

        // Expression of node `id` as seen by a user (`Var` if bound).
        fn render(id: usize, ops: &[Op], bound: &[bool], var_of: &[usize], top: bool) -> Expr {
            if bound[id] && !top {
                return Expr::Var(var_of[id]);
            }
            let r = |c: NodeId| Box::new(render(c as usize, ops, bound, var_of, false));
            match &ops[id] {
                Op::Input(s) => Expr::Input(*s),
                Op::Const(q) => Expr::Const(q_to_f64(q)),
                Op::Add(a, b) => Expr::Add(r(*a), r(*b)),
                Op::Sub(a, b) => Expr::Sub(r(*a), r(*b)),
                // A constant factor reads best in front (same value: * commutes exactly).
                Op::Mul(a, b) if matches!(ops[*b as usize], Op::Const(_)) => {
                    Expr::Mul(r(*b), r(*a))
                }
                Op::Mul(a, b) => Expr::Mul(r(*a), r(*b)),
            }
        }
        let stmts = (0..n)
            .filter(|&id| bound[id])
            .map(|id| render(id, &ops, &bound, &var_of, true))
            .collect();
        let outputs = all
            .iter()
            .map(|t| match t.value() {
                TracedValue::Const(q) => Expr::Const(q_to_f64(&q)),
                TracedValue::Node { id, neg } => {
                    let e = render(id as usize, &ops, &bound, &var_of, false);
                    if neg {
                        Expr::Neg(Box::new(e))
                    } else {
                        e
                    }
                }
            })
            .collect::<Vec<_>>();
        for e in &outputs {
            if let Expr::Const(c) = e {
                if !c.is_finite() {
                    return Err(EmitError::Invalid(format!(
                        "constant coefficient {c} is not finite"
                    )));
                }
            }
        }
        Ok(Program { stmts, outputs })
    }

    /// Runs the program in f64: the values of all outputs.
    pub fn eval(&self, data: &[f64]) -> Vec<f64> {
        let mut vars = Vec::with_capacity(self.stmts.len());
        for s in &self.stmts {
            let v = s.eval(data, &vars);
            vars.push(v);
        }
        self.outputs.iter().map(|e| e.eval(data, &vars)).collect()
    }

    /// Number of arithmetic operations (additions, subtractions, multiplications) the code
    /// performs: the live DAG nodes.
    pub fn op_count(&self) -> usize {
        self.stmts
            .iter()
            .chain(&self.outputs)
            .map(Expr::op_count)
            .sum()
    }

    /// Makes every output in `range` a statement's value (or its negation): an output that
    /// is not already `Var(k)` or `-Var(k)` gets a statement of its own. Returns each
    /// output's `(statement, negated)`. The values [`Program::eval`] computes are unchanged.
    pub fn bind_outputs(&mut self, range: std::ops::Range<usize>) -> Vec<(usize, bool)> {
        let mut out = Vec::with_capacity(range.len());
        for i in range {
            let (inner, neg) = match &self.outputs[i] {
                Expr::Neg(inner) => ((**inner).clone(), true),
                other => (other.clone(), false),
            };
            let k = match inner {
                Expr::Var(k) => k,
                other => {
                    self.stmts.push(other);
                    let k = self.stmts.len() - 1;
                    self.outputs[i] = if neg {
                        Expr::Neg(Box::new(Expr::Var(k)))
                    } else {
                        Expr::Var(k)
                    };
                    k
                }
            };
            out.push((k, neg));
        }
        out
    }

    /// The statements as assignments `c[K] = ...;` (table form, [`VarStyle::Array`]).
    pub fn stmt_tokens_array(&self) -> Vec<TokenStream> {
        self.stmts
            .iter()
            .enumerate()
            .map(|(k, e)| {
                let k = Literal::usize_unsuffixed(k);
                let e = e.tokens(VarStyle::Array);
                quote!(c[#k] = #e;)
            })
            .collect()
    }

    /// The statements as Rust tokens, `let cK = ...;` each.
    pub fn stmt_tokens(&self) -> Vec<TokenStream> {
        self.stmts
            .iter()
            .enumerate()
            .map(|(k, e)| {
                let id = format_ident!("c{}", k);
                let e = e.to_tokens();
                quote!(let #id = #e;)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::Ring;

    #[test]
    fn shared_nodes_become_statements_and_the_rest_is_inlined() {
        let t = Tracer::new();
        let d = t.inputs(4);
        let ab = d[0].mul(&d[1]); // used twice -> statement
        let o1 = ab.sub(&d[2].mul(&d[3])); // inlined
        let o2 = ab.add(&d[2]);
        let dead = d[3].mul(&d[3]).add(&d[0]); // not an output
        let _ = dead;
        let p = Program::build(&[o1.clone(), o2.clone(), o1.neg()], &[], 4).unwrap();
        // o1 is used twice (as o1 and -o1): bound too.
        assert_eq!(p.stmts.len(), 2);
        assert_eq!(p.op_count(), 4);
        let data = [1.5, -2.0, 0.25, 3.0];
        let v = p.eval(&data);
        assert_eq!(v[0], 1.5 * -2.0 - 0.25 * 3.0);
        assert_eq!(v[1], 1.5 * -2.0 + 0.25);
        assert_eq!(v[2], -(1.5 * -2.0 - 0.25 * 3.0));
        let code: Vec<String> = p.stmt_tokens().iter().map(|s| s.to_string()).collect();
        assert_eq!(code[0], "let c0 = d [0] * d [1] ;");
        assert_eq!(code[1], "let c1 = c0 - d [2] * d [3] ;");
        assert_eq!(p.outputs[1].to_tokens().to_string(), "d [2] + c0");
        assert_eq!(p.outputs[2].to_tokens().to_string(), "- c1");
    }

    #[test]
    fn bound_outputs_keep_their_values_and_array_style_names_entries() {
        let t = Tracer::new();
        let d = t.inputs(3);
        let ab = d[0].mul(&d[1]);
        let outs = [
            ab.sub(&d[2]),
            ab.neg(),
            ab.add(&d[2]).neg(),
            Traced::from_i64(-3),
            d[2].clone(),
        ];
        let mut p = Program::build(&outs, &[], 3).unwrap();
        let data = [1.5, -2.0, 0.25];
        let before = p.eval(&data);
        let refs = p.bind_outputs(0..outs.len());
        assert_eq!(p.eval(&data), before, "same values after binding");
        let vars = {
            let mut v = Vec::new();
            for s in &p.stmts {
                let x = s.eval(&data, &v);
                v.push(x);
            }
            v
        };
        for (&(k, neg), want) in refs.iter().zip(&before) {
            let got = if neg { -vars[k] } else { vars[k] };
            assert_eq!(got.to_bits(), want.to_bits());
        }
        assert_eq!(refs[1], (0, true), "-ab is the negation of ab's statement");
        let code: Vec<String> = p
            .stmt_tokens_array()
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_eq!(code[0], "c [0] = d [0] * d [1] ;");
        for (k, line) in code.iter().enumerate() {
            assert!(line.starts_with(&format!("c [{k}] = ")), "{line}");
        }
        assert!(code[1..].iter().any(|l| l.contains("c [0]")), "{code:?}");
    }

    #[test]
    fn parentheses_keep_the_evaluation_order() {
        let a = Box::new(Expr::Var(0));
        let b = Box::new(Expr::Var(1));
        let c = Box::new(Expr::Var(2));
        let e = Expr::Sub(a.clone(), Box::new(Expr::Add(b.clone(), c.clone())));
        assert_eq!(e.to_tokens().to_string(), "c0 - (c1 + c2)");
        let e = Expr::Mul(Box::new(Expr::Add(a.clone(), b.clone())), c.clone());
        assert_eq!(e.to_tokens().to_string(), "(c0 + c1) * c2");
        let e = Expr::Mul(a, Box::new(Expr::Mul(b, c)));
        assert_eq!(e.to_tokens().to_string(), "c0 * (c1 * c2)");
    }

    #[test]
    fn constant_outputs_and_bound_outputs() {
        let t = Tracer::new();
        let d = t.inputs(2);
        let x = d[0].mul(&d[1]);
        let p = Program::build(&[Traced::from_i64(-3)], std::slice::from_ref(&x), 2).unwrap();
        assert_eq!(p.stmts.len(), 1);
        assert_eq!(p.outputs[0], Expr::Const(-3.0));
        assert_eq!(p.outputs[1], Expr::Var(0));
        assert!(Program::build(&[x], &[], 1).is_err(), "slot 1 out of range");
    }
}
