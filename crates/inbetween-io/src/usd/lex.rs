//! The `.usda` lexer: numbers, strings (single, double, triple quoted), words, paths
//! (`</a/b>`), asset paths (`@x@`, skipped as strings) and punctuation, one token at a time
//! with its line.

use inbetween::error::{InputError, InputResult};

#[derive(Debug, Clone, PartialEq)]
pub(super) enum Tok {
    Num(f64),
    Str(String),
    Word(String),
    Path(String),
    Punct(char),
}

pub(super) struct Lexer<'a> {
    pub(super) src: &'a [u8],
    pub(super) at: usize,
    pub(super) line: usize,
    pub(super) source: &'a str,
}

impl Lexer<'_> {
    fn err(&self, what: &str) -> InputError {
        InputError::new(format!("{}:{}: {what}", self.source, self.line))
    }

    /// The next token and its line, or `None` at the end.
    pub(super) fn next(&mut self) -> InputResult<Option<(Tok, usize)>> {
        let s = self.src;
        loop {
            match s.get(self.at) {
                None => return Ok(None),
                Some(b'\n') => {
                    self.line += 1;
                    self.at += 1;
                }
                Some(c) if c.is_ascii_whitespace() => self.at += 1,
                Some(b'#') => {
                    while self.at < s.len() && s[self.at] != b'\n' {
                        self.at += 1;
                    }
                }
                Some(_) => break,
            }
        }
        let line = self.line;
        let c = s[self.at];
        let tok = match c {
            b'"' | b'\'' => Tok::Str(self.string(c)?),
            b'<' => {
                let start = self.at + 1;
                let end = s[start..]
                    .iter()
                    .position(|&b| b == b'>' || b == b'\n')
                    .map(|e| start + e)
                    .filter(|&e| s[e] == b'>')
                    .ok_or_else(|| self.err("a path without its closing '>'"))?;
                self.at = end + 1;
                Tok::Path(String::from_utf8_lossy(&s[start..end]).into_owned())
            }
            b'@' => {
                // An asset path, `@./textures/x.jpg@` or `@@@…@@@`: a value the reader skips.
                let triple = s[self.at..].starts_with(b"@@@");
                let (open, close): (usize, &[u8]) = if triple { (3, b"@@@") } else { (1, b"@") };
                let start = self.at + open;
                let end = s[start..]
                    .windows(close.len())
                    .position(|w| w == close)
                    .map(|e| start + e)
                    .filter(|&e| triple || !s[start..e].contains(&b'\n'))
                    .ok_or_else(|| self.err("an asset path without its closing '@'"))?;
                self.line += s[start..end].iter().filter(|&&b| b == b'\n').count();
                self.at = end + close.len();
                Tok::Str(String::from_utf8_lossy(&s[start..end]).into_owned())
            }
            b'(' | b')' | b'[' | b']' | b'{' | b'}' | b'=' | b',' | b':' | b';' => {
                self.at += 1;
                Tok::Punct(c as char)
            }
            b'-' | b'+' | b'.' | b'0'..=b'9' => {
                let start = self.at;
                self.at += 1;
                while self.at < s.len()
                    && (s[self.at].is_ascii_alphanumeric()
                        || matches!(s[self.at], b'.' | b'-' | b'+'))
                {
                    self.at += 1;
                }
                let text = std::str::from_utf8(&s[start..self.at]).unwrap_or("");
                let x = match text {
                    "-inf" => f64::NEG_INFINITY,
                    "+inf" => f64::INFINITY,
                    _ => text.parse::<f64>().map_err(|_| {
                        self.err(&format!(
                            "expected a number, found \"{}\"",
                            inbetween::error::shorten(text)
                        ))
                    })?,
                };
                Tok::Num(x)
            }
            c if c.is_ascii_alphabetic() || c == b'_' || c >= 0x80 => {
                let start = self.at;
                while self.at < s.len() {
                    let b = s[self.at];
                    let colon_word = b == b':'
                        && s.get(self.at + 1)
                            .is_some_and(|n| n.is_ascii_alphabetic() || *n == b'_');
                    if b.is_ascii_alphanumeric()
                        || b == b'_'
                        || b == b'.'
                        || b >= 0x80
                        || colon_word
                    {
                        self.at += 1;
                    } else {
                        break;
                    }
                }
                let word = String::from_utf8_lossy(&s[start..self.at]).into_owned();
                match word.as_str() {
                    "inf" => Tok::Num(f64::INFINITY),
                    "nan" => Tok::Num(f64::NAN),
                    _ => Tok::Word(word),
                }
            }
            other => return Err(self.err(&format!("unexpected character '{}'", other as char))),
        };
        Ok(Some((tok, line)))
    }

    /// A quoted string (single, double or triple quotes) from `self.at`.
    fn string(&mut self, quote: u8) -> InputResult<String> {
        let s = self.src;
        let triple = s[self.at..].starts_with(&[quote; 3]);
        self.at += if triple { 3 } else { 1 };
        let mut out = Vec::new();
        loop {
            let Some(&b) = s.get(self.at) else {
                return Err(self.err("a string without its closing quote"));
            };
            if b == b'\\' {
                let e = s.get(self.at + 1).copied().unwrap_or(b'\\');
                out.push(match e {
                    b'n' => b'\n',
                    b't' => b'\t',
                    other => other,
                });
                self.at += 2;
                continue;
            }
            if b == quote && (!triple || s[self.at..].starts_with(&[quote; 3])) {
                self.at += if triple { 3 } else { 1 };
                return Ok(String::from_utf8_lossy(&out).into_owned());
            }
            if b == b'\n' {
                if !triple {
                    return Err(self.err("a string without its closing quote"));
                }
                self.line += 1;
            }
            out.push(b);
            self.at += 1;
        }
    }
}
