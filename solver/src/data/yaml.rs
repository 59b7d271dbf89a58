//! The subset of YAML that calibration files use: Kalibr's `camchain-imucam.yaml`, OpenCV's
//! `cv::FileStorage` YAML (`%YAML:1.0`, `!!opencv-matrix`) and ROS `camera_info` files.
//!
//! Supported: block mappings by indentation, block sequences (`- item`, also at the
//! indentation of their key as Kalibr writes `T_cam_imu`), flow sequences `[a, b]` and flow
//! mappings `{k: v}` (nested, spanning lines), plain, single- and double-quoted scalars
//! (without escapes beyond `\"` and `''`), `#` comments, directives (`%YAML:1.0`),
//! document markers (`---`, `...`) and tags (`!!opencv-matrix`, ignored: the value is read
//! as it stands). Not supported, and refused with the line: anchors and aliases, block
//! scalars (`|`, `>`), several documents, mapping items inside block sequences. No YAML
//! crate is in the workspace, and these files need nothing more.

use thiserror::Error;

/// A parsed YAML value. Scalars stay text; [`Yaml::as_f64`] and friends convert them.
#[derive(Debug, Clone, PartialEq)]
pub enum Yaml {
    /// A scalar as written (quotes removed), with its 1-based line.
    Scalar(String, usize),
    /// A sequence.
    Seq(Vec<Yaml>),
    /// A mapping, keys in file order.
    Map(Vec<(String, Yaml)>),
    /// An empty value (`key:` with nothing under it).
    Null,
}

/// Why a text is not in the supported subset; `line` is 1-based.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("line {line}: {reason}")]
pub struct YamlError {
    /// The line.
    pub line: usize,
    /// What is wrong.
    pub reason: String,
}

impl Yaml {
    /// The value under `key` of a mapping (`None` for a missing key or a non-mapping).
    pub fn get(&self, key: &str) -> Option<&Yaml> {
        match self {
            Yaml::Map(items) => items.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }

    /// The keys of a mapping, in file order (empty for anything else).
    pub fn keys(&self) -> Vec<&str> {
        match self {
            Yaml::Map(items) => items.iter().map(|(k, _)| k.as_str()).collect(),
            _ => Vec::new(),
        }
    }

    /// A scalar's text.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Yaml::Scalar(s, _) => Some(s),
            _ => None,
        }
    }

    /// A scalar as a finite number (YAML's and OpenCV's spellings: `1`, `-2.5e-3`, `0.`).
    pub fn as_f64(&self) -> Option<f64> {
        self.as_str()
            .and_then(|s| s.trim().parse::<f64>().ok())
            .filter(|x| x.is_finite())
    }

    /// A sequence of finite numbers.
    pub fn as_f64_vec(&self) -> Option<Vec<f64>> {
        match self {
            Yaml::Seq(items) => items.iter().map(Yaml::as_f64).collect(),
            _ => None,
        }
    }
}

/// One significant line: indentation, text without comment, 1-based number.
struct Line {
    indent: usize,
    text: String,
    number: usize,
}

/// The text up to an unquoted `#` that starts a comment (at the start or after a space).
fn strip_comment(s: &str) -> &str {
    let (mut single, mut double) = (false, false);
    let mut prev = ' ';
    for (i, c) in s.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '#' if !single && !double && prev.is_whitespace() => return &s[..i],
            _ => {}
        }
        prev = c;
    }
    s
}

/// Depth change of flow brackets in `s` (outside quotes).
fn bracket_balance(s: &str) -> i64 {
    let (mut single, mut double, mut depth) = (false, false, 0i64);
    for c in s.chars() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '[' | '{' if !single && !double => depth += 1,
            ']' | '}' if !single && !double => depth -= 1,
            _ => {}
        }
    }
    depth
}

/// The significant lines, flow collections that span lines joined into one.
fn lines_of(text: &str) -> Result<Vec<Line>, YamlError> {
    let mut out: Vec<Line> = Vec::new();
    let mut open = 0i64;
    let mut documents = 0;
    for (i, raw) in text.lines().enumerate() {
        let number = i + 1;
        let content = strip_comment(raw).trim_end();
        if open > 0 {
            let last = out.last_mut().expect("an open flow collection has a line");
            last.text.push(' ');
            last.text.push_str(content.trim());
            open += bracket_balance(content);
            continue;
        }
        let trimmed = content.trim_start();
        if trimmed.is_empty() || trimmed.starts_with('%') || trimmed == "..." {
            continue;
        }
        if trimmed == "---" || trimmed.starts_with("--- ") {
            documents += 1;
            if documents > 1 {
                return Err(YamlError {
                    line: number,
                    reason: "several documents in one file".into(),
                });
            }
            continue;
        }
        if content.starts_with('\t') {
            return Err(YamlError {
                line: number,
                reason: "a tab in the indentation".into(),
            });
        }
        open = bracket_balance(content);
        out.push(Line {
            indent: content.len() - trimmed.len(),
            text: trimmed.to_string(),
            number,
        });
    }
    if open > 0 {
        let line = out.last().map_or(0, |l| l.number);
        return Err(YamlError {
            line,
            reason: "unclosed `[` or `{`".into(),
        });
    }
    Ok(out)
}

/// Parses `text` (see the module documentation for the subset).
pub fn parse(text: &str) -> Result<Yaml, YamlError> {
    let lines = lines_of(text)?;
    if lines.is_empty() {
        return Ok(Yaml::Null);
    }
    let mut i = 0;
    let value = block(&lines, &mut i, lines[0].indent)?;
    if let Some(l) = lines.get(i) {
        return Err(YamlError {
            line: l.number,
            reason: "unexpected indentation".into(),
        });
    }
    Ok(value)
}

fn is_item(text: &str) -> bool {
    text == "-" || text.starts_with("- ")
}

/// The block (mapping or sequence) whose lines start at `lines[*i]` with indentation
/// `indent`.
fn block(lines: &[Line], i: &mut usize, indent: usize) -> Result<Yaml, YamlError> {
    if is_item(&lines[*i].text) {
        return sequence(lines, i, indent);
    }
    let mut items: Vec<(String, Yaml)> = Vec::new();
    while let Some(l) = lines.get(*i) {
        if l.indent < indent {
            break;
        }
        if l.indent > indent || is_item(&l.text) {
            return Err(YamlError {
                line: l.number,
                reason: "unexpected indentation".into(),
            });
        }
        let (key, rest) = split_key(&l.text).ok_or_else(|| YamlError {
            line: l.number,
            reason: format!("expected `key: value`, got `{}`", l.text),
        })?;
        if items.iter().any(|(k, _)| *k == key) {
            return Err(YamlError {
                line: l.number,
                reason: format!("duplicate key `{key}`"),
            });
        }
        *i += 1;
        let rest = strip_tag(rest);
        let value = if !rest.is_empty() {
            inline(rest, l.number)?
        } else {
            match lines.get(*i) {
                Some(n) if n.indent > indent => block(lines, i, n.indent)?,
                Some(n) if n.indent == indent && is_item(&n.text) => sequence(lines, i, indent)?,
                _ => Yaml::Null,
            }
        };
        items.push((key, value));
    }
    Ok(Yaml::Map(items))
}

/// A block sequence at `indent`.
fn sequence(lines: &[Line], i: &mut usize, indent: usize) -> Result<Yaml, YamlError> {
    let mut items = Vec::new();
    while let Some(l) = lines.get(*i) {
        if l.indent != indent || !is_item(&l.text) {
            break;
        }
        *i += 1;
        let rest = strip_tag(l.text[1..].trim());
        if rest.is_empty() {
            match lines.get(*i) {
                Some(n) if n.indent > indent => items.push(block(lines, i, n.indent)?),
                _ => items.push(Yaml::Null),
            }
        } else if split_key(rest).is_some() && !rest.starts_with(['[', '{', '"', '\'']) {
            return Err(YamlError {
                line: l.number,
                reason: "mappings inside block sequences are not supported".into(),
            });
        } else {
            items.push(inline(rest, l.number)?);
        }
    }
    Ok(Yaml::Seq(items))
}

/// `key: rest` or `key:` (the key unquoted).
fn split_key(text: &str) -> Option<(String, &str)> {
    let (key, rest) = if let Some(k) = text.strip_suffix(':') {
        (k, "")
    } else {
        let at = text.find(": ")?;
        (&text[..at], text[at + 2..].trim())
    };
    let key = key.trim();
    if key.is_empty() || key.starts_with(['[', '{', '-']) {
        return None;
    }
    Some((unquote(key).to_string(), rest))
}

/// The value without a leading tag (`!!opencv-matrix`, `!<...>`).
fn strip_tag(s: &str) -> &str {
    if s.starts_with('!') {
        s.split_once(char::is_whitespace)
            .map_or("", |(_, rest)| rest.trim())
    } else {
        s
    }
}

fn unquote(s: &str) -> &str {
    let s = s.trim();
    if s.len() >= 2
        && ((s.starts_with('"') && s.ends_with('"')) || (s.starts_with('\'') && s.ends_with('\'')))
    {
        &s[1..s.len() - 1]
    } else {
        s
    }
}

/// A value on one (joined) line: a flow collection or a scalar.
fn inline(s: &str, line: usize) -> Result<Yaml, YamlError> {
    let s = s.trim();
    let err = |reason: &str| YamlError {
        line,
        reason: reason.into(),
    };
    if s.starts_with('&') || s.starts_with('*') {
        return Err(err("anchors and aliases are not supported"));
    }
    if s.starts_with('|') || s.starts_with('>') {
        return Err(err("block scalars are not supported"));
    }
    if let Some(body) = s.strip_prefix('[') {
        let body = body
            .strip_suffix(']')
            .ok_or_else(|| err("text after a flow sequence's `]`"))?;
        let items = split_flow(body)
            .into_iter()
            .map(|p| inline(p, line))
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(Yaml::Seq(items));
    }
    if let Some(body) = s.strip_prefix('{') {
        let body = body
            .strip_suffix('}')
            .ok_or_else(|| err("text after a flow mapping's `}`"))?;
        let mut items = Vec::new();
        for part in split_flow(body) {
            let (k, v) = split_key(part).ok_or_else(|| err("expected `key: value` in `{}`"))?;
            items.push((k, inline(strip_tag(v), line)?));
        }
        return Ok(Yaml::Map(items));
    }
    Ok(Yaml::Scalar(unquote(s).to_string(), line))
}

/// The comma-separated parts of a flow collection's body, at depth 0 and outside quotes
/// (a trailing comma allowed).
fn split_flow(body: &str) -> Vec<&str> {
    let (mut single, mut double, mut depth, mut start) = (false, false, 0i64, 0);
    let mut parts = Vec::new();
    for (i, c) in body.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '[' | '{' if !single && !double => depth += 1,
            ']' | '}' if !single && !double => depth -= 1,
            ',' if !single && !double && depth == 0 => {
                parts.push(body[start..i].trim());
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(body[start..].trim());
    parts.into_iter().filter(|p| !p.is_empty()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kalibr_and_opencv_shapes_parse() {
        let text = "cam0:\n  T_cam_imu:\n  - [1, 0, 0, 0.1]\n  - [0, 1, 0, 0]  # row 2\n  intrinsics: [458.6, 457.3,\n     367.2, 248.4]\n  name: 'a # b'\n  empty:\ncam1: {x: 1, y: [2, 3]}\n";
        let y = parse(text).unwrap();
        let cam0 = y.get("cam0").unwrap();
        let t = cam0.get("T_cam_imu").unwrap();
        assert_eq!(
            t,
            &Yaml::Seq(vec![
                Yaml::Seq(
                    ["1", "0", "0", "0.1"]
                        .map(|s| Yaml::Scalar(s.into(), 3))
                        .to_vec()
                ),
                Yaml::Seq(
                    ["0", "1", "0", "0"]
                        .map(|s| Yaml::Scalar(s.into(), 4))
                        .to_vec()
                ),
            ])
        );
        assert_eq!(
            cam0.get("intrinsics").unwrap().as_f64_vec(),
            Some(vec![458.6, 457.3, 367.2, 248.4])
        );
        assert_eq!(cam0.get("name").unwrap().as_str(), Some("a # b"));
        assert_eq!(cam0.get("empty"), Some(&Yaml::Null));
        assert_eq!(
            y.get("cam1").unwrap().get("y").unwrap().as_f64_vec(),
            Some(vec![2.0, 3.0])
        );
        assert_eq!(y.keys(), vec!["cam0", "cam1"]);

        let cv = "%YAML:1.0\n---\nimage_width: 640\nK: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 5.0e+02, 0., 3.2e+02, 0., 5.0e+02,\n       2.4e+02, 0., 0., 1. ]\n";
        let y = parse(cv).unwrap();
        assert_eq!(y.get("image_width").unwrap().as_f64(), Some(640.0));
        let k = y.get("K").unwrap();
        assert_eq!(k.get("rows").unwrap().as_f64(), Some(3.0));
        assert_eq!(k.get("data").unwrap().as_f64_vec().unwrap().len(), 9);
    }

    #[test]
    fn unsupported_or_broken_text_names_the_line() {
        for (text, line) in [
            ("a: 1\n  b: 2\n", 2),
            ("a: [1, 2\n", 1),
            ("a: 1\na: 2\n", 2),
            ("a: *x\n", 1),
            ("a: |\n  text\n", 1),
            ("a:\n- b: 1\n", 2),
            ("a: 1\n---\nb: 2\n---\nc: 3\n", 4),
            ("just text\n", 1),
        ] {
            let e = parse(text).unwrap_err();
            assert_eq!(e.line, line, "{text:?}: {e}");
        }
    }
}
