//! Recursive-descent parser: tokens to [`Stmt`]s.
//!
//! Statements end at a line end or `;`. Inside `( )` and `[ ]` line ends are ignored, and a
//! declaration list continues on the next line after a comma. Nesting (parentheses,
//! brackets, calls, unary minus, `for` blocks) deeper than [`MAX_DEPTH`] is an error, so the
//! parser's recursion is bounded whatever the input.

use super::ast::{AddOp, Decl, Expr, ExprKind, MulOp, Name, Postfix, Stmt};
use super::lexer::{Pos, Tok, Token};
use super::LangError;

/// Maximum nesting depth of expressions and of `for` blocks.
pub const MAX_DEPTH: usize = 64;

/// The largest exponent of `^` (the power is expanded into that many products).
pub const MAX_POWER: u32 = 32;

/// Words that cannot name a symbol.
pub const KEYWORDS: [&str; 10] = [
    "problem",
    "unknown",
    "data",
    "eliminate",
    "positive",
    "nonzero",
    "option",
    "let",
    "for",
    "in",
];

/// Parses a token stream (ending with [`Tok::Eof`]) into statements.
pub fn parse(tokens: &[Token]) -> Result<Vec<(Pos, Stmt)>, LangError> {
    let eof = match tokens.last() {
        Some(t) if t.tok == Tok::Eof => t.clone(),
        _ => Token {
            tok: Tok::Eof,
            pos: tokens
                .last()
                .map(|t| t.pos)
                .unwrap_or(Pos { line: 1, column: 1 }),
        },
    };
    let mut p = Parser {
        toks: tokens,
        i: 0,
        eof,
        depth: 0,
        group: 0,
    };
    let mut out = Vec::new();
    loop {
        p.skip_separators();
        if p.peek().tok == Tok::Eof {
            break;
        }
        let pos = p.peek().pos;
        out.push((pos, p.statement(0)?));
        p.end_of_statement(false)?;
    }
    Ok(out)
}

struct Parser<'a> {
    toks: &'a [Token],
    i: usize,
    eof: Token,
    depth: usize,
    /// Number of open `(`/`[` groups: inside one, line ends are skipped.
    group: usize,
}

impl<'a> Parser<'a> {
    fn raw(&self) -> &Token {
        self.toks.get(self.i).unwrap_or(&self.eof)
    }
    /// The current token (skipping line ends inside a group).
    fn peek(&mut self) -> Token {
        if self.group > 0 {
            while self.raw().tok == Tok::Newline {
                self.i += 1;
            }
        }
        self.raw().clone()
    }
    fn bump(&mut self) -> Token {
        let t = self.peek();
        if t.tok != Tok::Eof {
            self.i += 1;
        }
        t
    }
    fn skip_newlines(&mut self) {
        while self.raw().tok == Tok::Newline {
            self.i += 1;
        }
    }
    fn skip_separators(&mut self) {
        while matches!(self.raw().tok, Tok::Newline | Tok::Semi) {
            self.i += 1;
        }
    }
    fn error_here(&mut self, expected: &str) -> LangError {
        let t = self.peek();
        LangError::new(
            t.pos,
            format!("expected {expected}, found {}", t.tok.describe()),
        )
    }
    fn expect(&mut self, tok: Tok, expected: &str) -> Result<Token, LangError> {
        if self.peek().tok == tok {
            Ok(self.bump())
        } else {
            Err(self.error_here(expected))
        }
    }
    fn is_ident(&mut self, word: &str) -> bool {
        matches!(&self.peek().tok, Tok::Ident(s) if s == word)
    }
    fn ident(&mut self, expected: &str) -> Result<Name, LangError> {
        let t = self.peek();
        match t.tok {
            Tok::Ident(s) if !KEYWORDS.contains(&s.as_str()) => {
                self.bump();
                Ok(Name {
                    name: s,
                    pos: t.pos,
                })
            }
            Tok::Ident(s) => Err(LangError::new(
                t.pos,
                format!("expected {expected}, found the keyword '{s}'"),
            )),
            _ => Err(self.error_here(expected)),
        }
    }
    /// A problem name: adjacent identifier and number tokens with nothing between them
    /// (`8ptF_radial` lexes as `8` and `ptF_radial`), joined; the checker checks its
    /// characters (`names::check_problem_name`).
    fn problem_name(&mut self) -> Result<Name, LangError> {
        let first = self.peek();
        let mut text = match &first.tok {
            Tok::Number(s) => s.clone(),
            Tok::Ident(s) if !KEYWORDS.contains(&s.as_str()) => s.clone(),
            _ => {
                return Err(self.error_here("a problem name after 'problem'"));
            }
        };
        self.bump();
        loop {
            let t = self.raw().clone();
            let adjacent = t.pos.line == first.pos.line
                && t.pos.column == first.pos.column + text.chars().count();
            match &t.tok {
                Tok::Number(s) | Tok::Ident(s) if adjacent => {
                    text.push_str(s);
                    self.bump();
                }
                _ => break,
            }
        }
        Ok(Name {
            name: text,
            pos: first.pos,
        })
    }
    fn integer(&mut self, expected: &str) -> Result<(i64, Pos), LangError> {
        let t = self.peek();
        let negative = t.tok == Tok::Minus;
        if negative {
            self.bump();
        }
        let n = self.peek();
        match &n.tok {
            Tok::Number(s) if !s.contains('.') => {
                self.bump();
                match s.parse::<i64>() {
                    Ok(v) => Ok((if negative { -v } else { v }, t.pos)),
                    Err(_) => Err(LangError::new(n.pos, format!("integer {s} is too large"))),
                }
            }
            _ => Err(self.error_here(expected)),
        }
    }
    /// After a statement: a line end, `;`, end of file, or (inside a block) `}`.
    fn end_of_statement(&mut self, in_block: bool) -> Result<(), LangError> {
        match self.peek().tok {
            Tok::Newline | Tok::Semi | Tok::Eof => Ok(()),
            Tok::RBrace if in_block => Ok(()),
            _ => Err(self.error_here(if in_block {
                "end of line or '}' after the statement"
            } else {
                "end of line after the statement"
            })),
        }
    }

    /// `NAME, NAME, ...` after `keyword`.
    fn unknown_names(&mut self, keyword: &str) -> Result<Vec<Name>, LangError> {
        let mut names = vec![self.ident(&format!("an unknown's name after '{keyword}'"))?];
        while self.peek().tok == Tok::Comma {
            self.bump();
            self.skip_newlines();
            names.push(self.ident("an unknown's name after ','")?);
        }
        Ok(names)
    }

    fn statement(&mut self, block_depth: usize) -> Result<Stmt, LangError> {
        let t = self.peek();
        let word = match &t.tok {
            Tok::Ident(s) => s.clone(),
            _ => String::new(),
        };
        match word.as_str() {
            "problem" => {
                self.bump();
                let name = self.problem_name()?;
                Ok(Stmt::Problem { pos: t.pos, name })
            }
            "unknown" => {
                self.bump();
                Ok(Stmt::Unknown(self.decls(false)?))
            }
            "data" => {
                self.bump();
                Ok(Stmt::Data(self.decls(true)?))
            }
            "eliminate" => {
                self.bump();
                Ok(Stmt::Eliminate(self.unknown_names("eliminate")?))
            }
            "positive" => {
                self.bump();
                Ok(Stmt::Positive(self.unknown_names("positive")?))
            }
            "nonzero" => {
                self.bump();
                let expr = self.expr()?;
                Ok(Stmt::Nonzero { pos: t.pos, expr })
            }
            "option" => {
                self.bump();
                let name = self.ident("an option name after 'option'")?;
                self.expect(Tok::Eq, "'=' after the option name")?;
                let v = self.peek();
                let value = match v.tok {
                    Tok::Ident(s) | Tok::Number(s) => {
                        self.bump();
                        // `1/NAME`: the inverse of an unknown (a Laurent action).
                        let name = if s == "1" && self.peek().tok == Tok::Slash {
                            self.bump();
                            let n = self.ident("an unknown after '1/'")?;
                            format!("1/{}", n.name)
                        } else {
                            s
                        };
                        Name { name, pos: v.pos }
                    }
                    _ => return Err(self.error_here("an option value (a name or a number)")),
                };
                Ok(Stmt::Option { name, value })
            }
            "let" => {
                self.bump();
                let name = self.ident("a name after 'let'")?;
                self.expect(Tok::Eq, "'=' after the name in 'let'")?;
                let value = self.expr()?;
                Ok(Stmt::Let { name, value })
            }
            "for" => self.for_loop(block_depth),
            "in" => Err(LangError::new(
                t.pos,
                "expected a statement, found the keyword 'in'",
            )),
            _ => {
                if matches!(t.tok, Tok::RBrace) {
                    return Err(LangError::new(
                        t.pos,
                        "unexpected '}': no 'for' block is open",
                    ));
                }
                let lhs = self.expr()?;
                let eq = self.peek();
                if eq.tok != Tok::Eq {
                    return Err(self.error_here(
                        "'=' in an equation (an expression alone is not a statement)",
                    ));
                }
                self.bump();
                let rhs = self.expr()?;
                Ok(Stmt::Equation {
                    lhs,
                    eq: eq.pos,
                    rhs,
                })
            }
        }
    }

    fn decls(&mut self, with_kind: bool) -> Result<Vec<Decl>, LangError> {
        let mut out = Vec::new();
        loop {
            let name = self.ident(if with_kind {
                "a data name"
            } else {
                "an unknown's name"
            })?;
            let mut len = None;
            if self.peek().tok == Tok::LBracket {
                self.bump();
                let (n, pos) = self.integer("an array length (an integer)")?;
                if n < 1 {
                    return Err(LangError::new(
                        pos,
                        format!("array length must be at least 1, found {n}"),
                    ));
                }
                len = Some((n as usize, pos));
                self.expect(Tok::RBracket, "']' after the array length")?;
            }
            let mut kind = None;
            if with_kind {
                self.expect(
                    Tok::Colon,
                    "':' and a kind (scalar, point, rotation, vecN, matRxC)",
                )?;
                kind = Some(self.ident("a kind (scalar, point, rotation, vecN, matRxC)")?);
            } else if self.peek().tok == Tok::Colon {
                return Err(LangError::new(
                    self.peek().pos,
                    "unknowns have no kind: declare scalars or arrays of scalars (`unknown t[3]` \
                     is a 3-vector, `unknown q[4]` a quaternion's entries); kinds such as \
                     `: vec3` are for `data`",
                ));
            }
            out.push(Decl { name, len, kind });
            if self.peek().tok == Tok::Comma {
                self.bump();
                self.skip_newlines();
            } else {
                return Ok(out);
            }
        }
    }

    fn for_loop(&mut self, block_depth: usize) -> Result<Stmt, LangError> {
        let pos = self.bump().pos;
        if block_depth >= MAX_DEPTH {
            return Err(LangError::new(
                pos,
                format!("'for' blocks nested too deeply (more than {MAX_DEPTH} levels)"),
            ));
        }
        let var = self.ident("a loop variable after 'for'")?;
        if !self.is_ident("in") {
            return Err(self.error_here("'in' after the loop variable"));
        }
        self.bump();
        let start = self.integer("an integer range start (as in 0..5)")?;
        self.expect(Tok::DotDot, "'..' in the range (as in 0..5)")?;
        let end = self.integer("an integer range end (as in 0..5)")?;
        let brace = self.expect(Tok::LBrace, "'{' to open the loop body")?.pos;
        let mut body = Vec::new();
        loop {
            self.skip_separators();
            match self.peek().tok {
                Tok::RBrace => {
                    self.bump();
                    break;
                }
                Tok::Eof => {
                    return Err(LangError::new(
                        brace,
                        "unclosed '{': expected '}' before the end of the file",
                    ))
                }
                _ => {}
            }
            let pos = self.peek().pos;
            body.push((pos, self.statement(block_depth + 1)?));
            self.end_of_statement(true)?;
        }
        Ok(Stmt::For {
            pos,
            var,
            start,
            end,
            brace,
            body,
        })
    }

    fn expr(&mut self) -> Result<Expr, LangError> {
        let first = self.product()?;
        let mut rest = Vec::new();
        loop {
            let t = self.peek();
            let op = match t.tok {
                Tok::Plus => AddOp::Add,
                Tok::Minus => AddOp::Sub,
                _ => break,
            };
            self.bump();
            let e = self.operand(&t)?;
            rest.push((op, t.pos, e));
        }
        if rest.is_empty() {
            return Ok(first);
        }
        Ok(Expr {
            pos: first.pos,
            kind: ExprKind::Sum(Box::new(first), rest),
        })
    }

    /// The operand after a binary operator, with a message naming the operator.
    fn operand(&mut self, op: &Token) -> Result<Expr, LangError> {
        if self.starts_expression() {
            if matches!(op.tok, Tok::Plus | Tok::Minus) {
                self.product()
            } else {
                self.unary()
            }
        } else {
            Err(self.error_here(&format!("an expression after {}", op.tok.describe())))
        }
    }

    fn starts_expression(&mut self) -> bool {
        matches!(
            self.peek().tok,
            Tok::Ident(_) | Tok::Number(_) | Tok::Minus | Tok::Plus | Tok::LParen | Tok::LBracket
        )
    }

    fn product(&mut self) -> Result<Expr, LangError> {
        let first = self.unary()?;
        let mut rest = Vec::new();
        loop {
            let t = self.peek();
            let op = match t.tok {
                Tok::Star => MulOp::Mul,
                Tok::Slash => MulOp::Div,
                _ => break,
            };
            self.bump();
            let e = self.operand(&t)?;
            rest.push((op, t.pos, e));
        }
        if rest.is_empty() {
            return Ok(first);
        }
        Ok(Expr {
            pos: first.pos,
            kind: ExprKind::Product(Box::new(first), rest),
        })
    }

    fn unary(&mut self) -> Result<Expr, LangError> {
        let t = self.peek();
        if self.depth >= MAX_DEPTH {
            return Err(LangError::new(
                t.pos,
                format!("expression nested too deeply (more than {MAX_DEPTH} levels)"),
            ));
        }
        self.depth += 1;
        let r = match t.tok {
            Tok::Minus => {
                self.bump();
                self.operand(&t).map(|e| Expr {
                    pos: t.pos,
                    kind: ExprKind::Neg(Box::new(e)),
                })
            }
            Tok::Plus => {
                self.bump();
                self.operand(&t)
            }
            _ => self.postfix(),
        };
        self.depth -= 1;
        r
    }

    fn postfix(&mut self) -> Result<Expr, LangError> {
        let base = self.primary()?;
        let mut ops = Vec::new();
        loop {
            let t = self.peek();
            match t.tok {
                Tok::Quote => {
                    self.bump();
                    ops.push(Postfix::Transpose(t.pos));
                }
                Tok::LBracket => {
                    self.bump();
                    self.group += 1;
                    let idx = self.expr();
                    let close = idx.and_then(|idx| {
                        self.expect(
                            Tok::RBracket,
                            &format!(
                                "']' to close the index opened at {}:{}",
                                t.pos.line, t.pos.column
                            ),
                        )
                        .map(|_| idx)
                    });
                    self.group -= 1;
                    ops.push(Postfix::Index(Box::new(close?), t.pos));
                }
                _ => break,
            }
        }
        let operand = if ops.is_empty() {
            base
        } else {
            Expr {
                pos: base.pos,
                kind: ExprKind::Postfix(Box::new(base), ops),
            }
        };
        self.power(operand)
    }

    /// `operand ^ n` for an integer literal `1 <= n <= MAX_POWER`, as the product of `n`
    /// copies of the operand (so that shapes and kinds are checked as for `*`).
    fn power(&mut self, operand: Expr) -> Result<Expr, LangError> {
        let caret = self.peek();
        if caret.tok != Tok::Caret {
            return Ok(operand);
        }
        self.bump();
        let negative = self.peek().tok == Tok::Minus;
        if negative {
            self.bump();
        }
        let t = self.peek();
        let n = match &t.tok {
            Tok::Number(s) if !s.contains('.') => s.parse::<u32>().ok(),
            _ => return Err(self.error_here("an integer exponent after '^'")),
        };
        let Some(n) = n.filter(|n| (1..=MAX_POWER).contains(n)) else {
            return Err(LangError::new(
                t.pos,
                format!(
                    "the exponent after '^' must be an integer from 1 to {MAX_POWER} or from -{MAX_POWER} to -1"
                ),
            ));
        };
        self.bump();
        let pos = operand.pos;
        let power = if n == 1 {
            operand
        } else {
            let rest = (1..n)
                .map(|_| (MulOp::Mul, caret.pos, operand.clone()))
                .collect();
            Expr {
                pos,
                kind: ExprKind::Product(Box::new(operand), rest),
            }
        };
        if !negative {
            return Ok(power);
        }
        Ok(Expr {
            pos,
            kind: ExprKind::Recip(Box::new(power)),
        })
    }

    fn primary(&mut self) -> Result<Expr, LangError> {
        let t = self.peek();
        match &t.tok {
            Tok::Number(s) => {
                self.bump();
                Ok(Expr {
                    pos: t.pos,
                    kind: ExprKind::Number(s.clone()),
                })
            }
            Tok::Ident(s) if KEYWORDS.contains(&s.as_str()) => Err(LangError::new(
                t.pos,
                format!("expected an expression, found the keyword '{s}'"),
            )),
            Tok::Ident(s) => {
                self.bump();
                if self.raw().tok == Tok::LParen && (s == "cross" || s == "dot") {
                    let open = self.bump();
                    return self.vector_product(s, &t, &open);
                }
                if self.raw().tok == Tok::LParen && s == "diff" {
                    let open = self.bump();
                    let (e, x) = self.two_args(s, &open)?;
                    return Ok(Expr {
                        pos: t.pos,
                        kind: ExprKind::Diff(Box::new(e), Box::new(x)),
                    });
                }
                if self.raw().tok == Tok::LParen {
                    let open = self.bump();
                    let arg = self.group_expr(&open, Tok::RParen, "')'")?;
                    return Ok(Expr {
                        pos: t.pos,
                        kind: ExprKind::Call(
                            Name {
                                name: s.clone(),
                                pos: t.pos,
                            },
                            Box::new(arg),
                        ),
                    });
                }
                Ok(Expr {
                    pos: t.pos,
                    kind: ExprKind::Name(s.clone()),
                })
            }
            Tok::LParen => {
                self.bump();
                let e = self.group_expr(&t, Tok::RParen, "')'")?;
                Ok(Expr {
                    pos: t.pos,
                    kind: ExprKind::Paren(Box::new(e)),
                })
            }
            Tok::LBracket => {
                self.bump();
                self.group += 1;
                let r = self.list_items(&t);
                self.group -= 1;
                Ok(Expr {
                    pos: t.pos,
                    kind: ExprKind::List(r?),
                })
            }
            Tok::Quote => Err(LangError::new(
                t.pos,
                "expected an expression before ''' (transpose of nothing)",
            )),
            _ => Err(self.error_here("an expression")),
        }
    }

    /// `cross(a, b)` as `skew(a) * b` and `dot(a, b)` as `a' * b` (after the `(`), so that
    /// shapes are checked as for those forms.
    fn vector_product(&mut self, name: &str, at: &Token, open: &Token) -> Result<Expr, LangError> {
        let (a, b) = self.two_args(name, open)?;
        let left = if name == "cross" {
            Expr {
                pos: at.pos,
                kind: ExprKind::Call(
                    Name {
                        name: "skew".to_string(),
                        pos: at.pos,
                    },
                    Box::new(a),
                ),
            }
        } else {
            Expr {
                pos: a.pos,
                kind: ExprKind::Postfix(Box::new(a), vec![Postfix::Transpose(at.pos)]),
            }
        };
        Ok(Expr {
            pos: at.pos,
            kind: ExprKind::Paren(Box::new(Expr {
                pos: at.pos,
                kind: ExprKind::Product(Box::new(left), vec![(MulOp::Mul, at.pos, b)]),
            })),
        })
    }

    /// The two arguments of `name(a, b)` after the `(`, and the closing `)`.
    fn two_args(&mut self, name: &str, open: &Token) -> Result<(Expr, Expr), LangError> {
        self.group += 1;
        let args = self.expr().and_then(|a| {
            self.expect(
                Tok::Comma,
                &format!("',' between the two arguments of {name}"),
            )?;
            let b = self.expr()?;
            self.expect(
                Tok::RParen,
                &format!("')' to close '(' at {}:{}", open.pos.line, open.pos.column),
            )?;
            Ok((a, b))
        });
        self.group -= 1;
        args
    }

    fn group_expr(&mut self, open: &Token, close: Tok, what: &str) -> Result<Expr, LangError> {
        self.group += 1;
        let r = self.expr().and_then(|e| {
            self.expect(
                close,
                &format!(
                    "{what} to close {} at {}:{}",
                    open.tok.describe(),
                    open.pos.line,
                    open.pos.column
                ),
            )
            .map(|_| e)
        });
        self.group -= 1;
        r
    }

    fn list_items(&mut self, open: &Token) -> Result<Vec<Expr>, LangError> {
        let mut items = vec![self.expr()?];
        loop {
            match self.peek().tok {
                Tok::Comma => {
                    self.bump();
                    items.push(self.expr()?);
                }
                Tok::RBracket => {
                    self.bump();
                    return Ok(items);
                }
                _ => {
                    return Err(self.error_here(&format!(
                        "',' or ']' in the list opened at {}:{}",
                        open.pos.line, open.pos.column
                    )))
                }
            }
        }
    }
}
