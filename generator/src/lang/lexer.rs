//! Tokens of the problem language, with 1-based line and column positions.

use super::LangError;

/// The most digits a number literal may have (its exponent aside): far beyond any measured
/// or exact constant, while a literal of a million digits costs seconds to convert and
/// more in every product it enters.
pub const MAX_NUMBER_DIGITS: usize = 1000;

/// The most characters of a name: messages repeat names, and stay one short line.
pub const MAX_NAME_CHARS: usize = 256;

/// A position in the source: 1-based line and column (columns count characters).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Pos {
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
}

/// A token kind.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Tok {
    /// An identifier or keyword (keywords are resolved by the parser).
    Ident(String),
    /// A numeric literal as written: digits with an optional fractional part.
    Number(String),
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `'` (transpose)
    Quote,
    /// `^` (integer power)
    Caret,
    /// `=`
    Eq,
    /// `,`
    Comma,
    /// `:`
    Colon,
    /// `;`
    Semi,
    /// `..`
    DotDot,
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `[`
    LBracket,
    /// `]`
    RBracket,
    /// `{`
    LBrace,
    /// `}`
    RBrace,
    /// End of a line (statements end at line ends).
    Newline,
    /// End of the input.
    Eof,
}

impl Tok {
    /// How the token is named in error messages.
    pub fn describe(&self) -> String {
        match self {
            Tok::Ident(s) => format!("'{s}'"),
            Tok::Number(s) => format!("number {s}"),
            Tok::Plus => "'+'".into(),
            Tok::Minus => "'-'".into(),
            Tok::Star => "'*'".into(),
            Tok::Slash => "'/'".into(),
            Tok::Quote => "'''".into(),
            Tok::Caret => "'^'".into(),
            Tok::Eq => "'='".into(),
            Tok::Comma => "','".into(),
            Tok::Colon => "':'".into(),
            Tok::Semi => "';'".into(),
            Tok::DotDot => "'..'".into(),
            Tok::LParen => "'('".into(),
            Tok::RParen => "')'".into(),
            Tok::LBracket => "'['".into(),
            Tok::RBracket => "']'".into(),
            Tok::LBrace => "'{'".into(),
            Tok::RBrace => "'}'".into(),
            Tok::Newline => "end of line".into(),
            Tok::Eof => "end of file".into(),
        }
    }
}

/// A token with its position.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Where it starts.
    pub pos: Pos,
}

/// Splits the source into tokens; `#` starts a comment running to the end of the line.
/// A leading byte-order mark (as some editors write) is skipped. The result always ends
/// with [`Tok::Eof`].
pub fn lex(src: &str) -> Result<Vec<Token>, LangError> {
    let chars: Vec<char> = src
        .strip_prefix('\u{feff}')
        .unwrap_or(src)
        .chars()
        .collect();
    let mut out = Vec::new();
    let (mut i, mut line, mut col) = (0usize, 1usize, 1usize);
    while let Some(&c) = chars.get(i) {
        let pos = Pos { line, column: col };
        let peek = chars.get(i + 1).copied();
        let single = |t: Tok| Some((t, 1usize));
        let simple = match c {
            '\n' => single(Tok::Newline),
            '+' => single(Tok::Plus),
            '-' => single(Tok::Minus),
            '*' => single(Tok::Star),
            '/' => single(Tok::Slash),
            '^' => single(Tok::Caret),
            '\'' => single(Tok::Quote),
            '=' => single(Tok::Eq),
            ',' => single(Tok::Comma),
            ':' => single(Tok::Colon),
            ';' => single(Tok::Semi),
            '(' => single(Tok::LParen),
            ')' => single(Tok::RParen),
            '[' => single(Tok::LBracket),
            ']' => single(Tok::RBracket),
            '{' => single(Tok::LBrace),
            '}' => single(Tok::RBrace),
            '.' if peek == Some('.') => Some((Tok::DotDot, 2)),
            _ => None,
        };
        if let Some((tok, n)) = simple {
            out.push(Token { tok, pos });
            i += n;
            if c == '\n' {
                line += 1;
                col = 1;
            } else {
                col += n;
            }
            continue;
        }
        if c == '#' {
            while chars.get(i).is_some_and(|&c| c != '\n') {
                i += 1;
                col += 1;
            }
            continue;
        }
        if c == ' ' || c == '\t' || c == '\r' {
            i += 1;
            col += 1;
            continue;
        }
        let start = i;
        if c.is_ascii_alphabetic() || c == '_' {
            while chars
                .get(i)
                .is_some_and(|c| c.is_ascii_alphanumeric() || *c == '_')
            {
                i += 1;
            }
        } else if c.is_ascii_digit() {
            while chars.get(i).is_some_and(char::is_ascii_digit) {
                i += 1;
            }
            // A fractional part needs a digit after the dot (so that `0..5` is a range).
            if chars.get(i) == Some(&'.') && chars.get(i + 1).is_some_and(char::is_ascii_digit) {
                i += 1;
                while chars.get(i).is_some_and(char::is_ascii_digit) {
                    i += 1;
                }
            }
            // A decimal exponent: `1e-3`, `2.5E4` (a letter e not followed by digits starts
            // a name, as in `2e` → `2` `e`).
            if chars.get(i).is_some_and(|c| *c == 'e' || *c == 'E') {
                let sign = usize::from(chars.get(i + 1).is_some_and(|c| *c == '+' || *c == '-'));
                if chars.get(i + 1 + sign).is_some_and(char::is_ascii_digit) {
                    i += 1 + sign;
                    while chars.get(i).is_some_and(char::is_ascii_digit) {
                        i += 1;
                    }
                }
            }
        } else if c == '.' {
            return Err(LangError::new(
                pos,
                "unexpected '.': expected '..' in a range or a digit before a decimal point",
            ));
        } else {
            return Err(LangError::new(
                pos,
                format!("unexpected character {c:?}: not part of the problem language"),
            ));
        }
        if c.is_ascii_digit() {
            let digits = chars[start..i]
                .iter()
                .take_while(|c| **c != 'e' && **c != 'E')
                .filter(|c| c.is_ascii_digit())
                .count();
            if digits > MAX_NUMBER_DIGITS {
                // Not repeated in the message: it may be a megabyte long.
                return Err(LangError::new(
                    pos,
                    format!("a number of {digits} digits (at most {MAX_NUMBER_DIGITS})"),
                ));
            }
        } else if i - start > MAX_NAME_CHARS {
            return Err(LangError::new(
                pos,
                format!(
                    "a name of {} characters (at most {MAX_NAME_CHARS})",
                    i - start
                ),
            ));
        }
        let text: String = chars[start..i].iter().collect();
        col += i - start;
        let tok = if c.is_ascii_digit() {
            Tok::Number(text)
        } else {
            Tok::Ident(text)
        };
        out.push(Token { tok, pos });
    }
    out.push(Token {
        tok: Tok::Eof,
        pos: Pos { line, column: col },
    });
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_and_ranges() {
        let t = lex("for k in 0..5 { x2[k]' }\n# c\n 0.25").unwrap();
        let kinds: Vec<&Tok> = t.iter().map(|t| &t.tok).collect();
        assert_eq!(kinds[3], &Tok::Number("0".into()));
        assert_eq!(kinds[4], &Tok::DotDot);
        assert_eq!(kinds[5], &Tok::Number("5".into()));
        let last = &t[t.len() - 2];
        assert_eq!(last.tok, Tok::Number("0.25".into()));
        assert_eq!(last.pos, Pos { line: 3, column: 2 });
        assert!(lex("a $ b").is_err());
    }
}
