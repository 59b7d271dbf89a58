//! The problem language: lexer, parser, and checker (name resolution, loop unrolling,
//! shape checking). See `templates/README.md` for the language itself.
//!
//! Every error is a [`LangError`] naming a line and column; no input makes the parser
//! panic (there is no indexing or unwrapping on user-controlled data, and nesting deeper
//! than [`parser::MAX_DEPTH`] is an error).

pub mod ast;
pub mod check;
pub mod ir;
pub mod lexer;
pub mod names;
pub mod parser;

pub use lexer::Pos;

/// An error in a problem file, displayed as `FILE:LINE:COL: message`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{column}: {message}")]
pub struct LangError {
    /// The file name as given to the parser (`<input>` if none).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column (in characters).
    pub column: usize,
    /// What was expected and what was found.
    pub message: String,
}

impl LangError {
    /// An error at a position, with no file name yet.
    pub fn new(pos: Pos, message: impl Into<String>) -> Self {
        LangError {
            file: "<input>".into(),
            line: pos.line,
            column: pos.column,
            message: message.into(),
        }
    }
    /// The same error attributed to `file`.
    pub fn in_file(mut self, file: &str) -> Self {
        self.file = file.to_string();
        self
    }
}

/// Lexes, parses and checks a problem's source.
pub fn compile(source: &str) -> Result<check::Checked, LangError> {
    let tokens = lexer::lex(source)?;
    let stmts = parser::parse(&tokens)?;
    check::check(&stmts)
}
