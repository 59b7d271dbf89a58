//! Syntax tree of a problem file, as parsed (before name resolution and shape checks).
//!
//! Sums and products are n-ary and postfix operators are lists, so the tree depth is the
//! nesting depth of the source (bounded by the parser), never the length of a chain.

use super::lexer::Pos;

/// An identifier with its position.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Name {
    /// The identifier.
    pub name: String,
    /// Where it is written.
    pub pos: Pos,
}

/// `name` or `name[len]` in an `unknown` or `data` declaration.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decl {
    /// The declared name.
    pub name: Name,
    /// The array length, with the position of the literal.
    pub len: Option<(usize, Pos)>,
    /// The kind keyword (data declarations only), with its position.
    pub kind: Option<Name>,
}

/// A statement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Stmt {
    /// `problem NAME`
    Problem {
        /// Position of the keyword.
        pos: Pos,
        /// The problem's name.
        name: Name,
    },
    /// `unknown a[3], t[3]`
    Unknown(Vec<Decl>),
    /// `data x1[5]: point, ...`
    Data(Vec<Decl>),
    /// `eliminate t`
    Eliminate(Vec<Name>),
    /// `positive f, d`: solutions where a named unknown is not positive are dropped.
    Positive(Vec<Name>),
    /// `nonzero EXPR`: only solutions where the scalar `EXPR` does not vanish count.
    Nonzero {
        /// Position of the keyword.
        pos: Pos,
        /// The expression.
        expr: Expr,
    },
    /// `option NAME = VALUE`: a template-search option of the problem.
    Option {
        /// The option's name.
        name: Name,
        /// The value as written (a name or an integer), with its position.
        value: Name,
    },
    /// `let NAME = expr`
    Let {
        /// The bound name.
        name: Name,
        /// The bound expression.
        value: Expr,
    },
    /// `for VAR in START..END { body }`
    For {
        /// Position of the keyword.
        pos: Pos,
        /// The loop variable.
        var: Name,
        /// First value, inclusive.
        start: (i64, Pos),
        /// Last value, exclusive.
        end: (i64, Pos),
        /// Position of the opening brace.
        brace: Pos,
        /// Statements of the body, each with the position of its first token.
        body: Vec<(Pos, Stmt)>,
    },
    /// `lhs = rhs`
    Equation {
        /// Left side.
        lhs: Expr,
        /// Position of `=`.
        eq: Pos,
        /// Right side.
        rhs: Expr,
    },
}

/// A binary operator of a sum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AddOp {
    /// `+`
    Add,
    /// `-`
    Sub,
}

/// A binary operator of a product.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MulOp {
    /// `*`
    Mul,
    /// `/` (the divisor must be a non-zero constant)
    Div,
}

/// A postfix operator.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Postfix {
    /// `'` at a position.
    Transpose(Pos),
    /// `[index]` with the position of `[`.
    Index(Box<Expr>, Pos),
}

/// An expression with the position of its first token.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where it starts.
    pub pos: Pos,
}

/// The expression forms.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ExprKind {
    /// A numeric literal as written (`2`, `0.5`).
    Number(String),
    /// A name: unknown, data, `let` binding, loop variable or `I`.
    Name(String),
    /// `f(arg)` for the built-in functions.
    Call(Name, Box<Expr>),
    /// `-e`
    Neg(Box<Expr>),
    /// `first op e op e ...` with `+`/`-`, operator positions kept.
    Sum(Box<Expr>, Vec<(AddOp, Pos, Expr)>),
    /// `first op e op e ...` with `*`/`/`, operator positions kept.
    Product(Box<Expr>, Vec<(MulOp, Pos, Expr)>),
    /// A primary followed by postfix operators.
    Postfix(Box<Expr>, Vec<Postfix>),
    /// `[e0, e1, ...]`: a column vector of scalars, or a matrix whose rows are such lists.
    List(Vec<Expr>),
    /// `( e )`
    Paren(Box<Expr>),
    /// `e^-n`: the reciprocal of `e` (`e^n` as a product), a monomial in the unknowns.
    Recip(Box<Expr>),
    /// `diff(e, x)`: the partial derivative of `e` by the unknown scalar `x`.
    Diff(Box<Expr>, Box<Expr>),
}
