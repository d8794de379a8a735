//! The BVH hierarchy: whitespace-separated tokens (any indentation, line breaks where a writer
//! likes them, CRLF line ends), keywords case-sensitive as real files write them (`HIERARCHY`,
//! `ROOT`, `JOINT`, `End Site`, `OFFSET`, `CHANNELS`), a joint's name the rest of its
//! `ROOT`/`JOINT` line (so names with spaces work). Nesting is handled without recursion, so no
//! input can exhaust the stack. The motion section is [`super::read`]'s.

use super::{Channel, Joint};
use inbetween::error::{InputError, InputResult, shorten};

/// A token: its text, line (1-based) and byte offset in the text.
#[derive(Clone, Copy)]
pub(super) struct Tok<'a> {
    pub(super) s: &'a str,
    pub(super) line: usize,
    pub(super) start: usize,
}

/// Whitespace-separated tokens with their lines.
#[derive(Clone, Copy)]
pub(super) struct Tokens<'a> {
    pub(super) text: &'a str,
    pub(super) pos: usize,
    pub(super) line: usize,
}

impl<'a> Tokens<'a> {
    pub(super) fn skip_space(&mut self) {
        let bytes = self.text.as_bytes();
        while let Some(&b) = bytes.get(self.pos) {
            if b == b'\n' {
                self.line += 1;
            } else if !b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    pub(super) fn next(&mut self) -> Option<Tok<'a>> {
        self.skip_space();
        let bytes = self.text.as_bytes();
        let start = self.pos;
        while bytes
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        (self.pos > start).then(|| Tok {
            s: &self.text[start..self.pos],
            line: self.line,
            start,
        })
    }

    /// The rest of the current line (without its line end), trimmed; moves to the line end.
    pub(super) fn rest_of_line(&mut self) -> &'a str {
        let end = self.text[self.pos..]
            .find('\n')
            .map_or(self.text.len(), |i| self.pos + i);
        let rest = self.text[self.pos..end].trim();
        self.pos = end;
        rest
    }
}

/// What was found, for a message: the token quoted, or the end of the file.
pub(super) fn found(tok: Option<Tok>) -> String {
    match tok {
        Some(t) => format!("\"{}\"", shorten(t.s)),
        None => "the end of the file".to_string(),
    }
}

pub(super) struct Parser<'a> {
    pub(super) source: &'a str,
    pub(super) toks: Tokens<'a>,
    pub(super) joints: Vec<Joint>,
    pub(super) columns: usize,
}

impl<'a> Parser<'a> {
    /// `file:line: msg` at `tok`'s line, or `file: msg` at the end of the file.
    pub(super) fn err(&self, tok: Option<Tok>, msg: String) -> InputError {
        match tok {
            Some(t) => input_err!("{}:{}: {msg}", self.source, t.line),
            None => input_err!("{}: {msg}", self.source),
        }
    }

    pub(super) fn expect(&mut self, keyword: &str) -> InputResult<Tok<'a>> {
        let tok = self.toks.next();
        match tok {
            Some(t) if t.s == keyword => Ok(t),
            _ => Err(self.err(tok, format!("expected \"{keyword}\", found {}", found(tok)))),
        }
    }

    pub(super) fn number(&mut self, what: &str) -> InputResult<f64> {
        let tok = self.toks.next();
        match tok.map(|t| t.s.parse::<f64>()) {
            Some(Ok(x)) if x.is_finite() => Ok(x),
            Some(Ok(_)) => Err(self.err(
                tok,
                format!("expected a finite number for {what}, found {}", found(tok)),
            )),
            _ => Err(self.err(
                tok,
                format!("expected a number for {what}, found {}", found(tok)),
            )),
        }
    }

    pub(super) fn offset(&mut self) -> InputResult<[f64; 3]> {
        self.expect("OFFSET")?;
        Ok([
            self.number("OFFSET")?,
            self.number("OFFSET")?,
            self.number("OFFSET")?,
        ])
    }

    /// `ROOT`/`JOINT` (already read as `keyword`) up to and including its `CHANNELS`.
    pub(super) fn joint_header(
        &mut self,
        keyword: Tok<'a>,
        parent: Option<usize>,
    ) -> InputResult<()> {
        let line = self.toks.rest_of_line();
        // `ROOT Hips {` on one line: the brace is not part of the name.
        let (name, brace_on_line) = match line.strip_suffix('{') {
            Some(n) if n.is_empty() || n.ends_with(|c: char| c.is_ascii_whitespace()) => {
                (n.trim_end(), true)
            }
            _ => (line, false),
        };
        if name.is_empty() {
            return Err(self.err(
                Some(keyword),
                format!(
                    "expected a joint name after {}, found the end of the line",
                    keyword.s
                ),
            ));
        }
        if !brace_on_line {
            self.expect("{")?;
        }
        let offset = self.offset()?;
        let mut channels = Vec::new();
        let next = self.peek();
        if next.is_some_and(|t| t.s == "CHANNELS") {
            self.toks.next();
            let tok = self.toks.next();
            let n = match tok.map(|t| t.s.parse::<usize>()) {
                Some(Ok(n)) if n <= 6 => n,
                _ => {
                    return Err(self.err(
                        tok,
                        format!(
                            "expected a channel count from 0 to 6 for CHANNELS, found {}",
                            found(tok)
                        ),
                    ));
                }
            };
            for k in 0..n {
                let tok = self.toks.next();
                let Some(c) = tok.and_then(|t| Channel::parse(t.s)) else {
                    return Err(self.err(
                        tok,
                        format!(
                            "expected channel {} of {n} for CHANNELS (Xposition, Yposition, \
                             Zposition, Xrotation, Yrotation or Zrotation), found {}",
                            k + 1,
                            found(tok)
                        ),
                    ));
                };
                if channels.contains(&c) {
                    return Err(self.err(
                        tok,
                        format!("joint \"{}\" lists {c} twice in CHANNELS", shorten(name)),
                    ));
                }
                channels.push(c);
            }
        }
        let first_column = self.columns;
        self.columns += channels.len();
        self.joints.push(Joint {
            name: name.to_string(),
            parent,
            offset,
            channels,
            first_column,
            end_site: None,
            line: keyword.line,
            track_name: String::new(),
        });
        Ok(())
    }

    pub(super) fn peek(&self) -> Option<Tok<'a>> {
        let mut t = self.toks;
        t.next()
    }

    /// The hierarchy after `HIERARCHY`, up to `MOTION`; returns the `MOTION` token.
    pub(super) fn hierarchy(&mut self) -> InputResult<Tok<'a>> {
        // Open joints, innermost last.
        let mut open: Vec<usize> = Vec::new();
        loop {
            let tok = self.toks.next();
            let Some(t) = tok else {
                let msg = match open.last() {
                    Some(&j) => format!(
                        "expected \"}}\" closing joint \"{}\" (line {}), found the end of the file",
                        shorten(&self.joints[j].name),
                        self.joints[j].line
                    ),
                    None if self.joints.is_empty() => {
                        "expected \"ROOT\", found the end of the file".to_string()
                    }
                    None => "expected \"MOTION\", found the end of the file".to_string(),
                };
                return Err(self.err(None, msg));
            };
            match (open.last().copied(), t.s) {
                (None, "ROOT") => {
                    self.joint_header(t, None)?;
                    open.push(self.joints.len() - 1);
                }
                (None, "MOTION") if !self.joints.is_empty() => return Ok(t),
                (None, _) if self.joints.is_empty() => {
                    return Err(self.err(tok, format!("expected \"ROOT\", found {}", found(tok))));
                }
                (None, _) => {
                    return Err(self.err(
                        tok,
                        format!("expected \"ROOT\" or \"MOTION\", found {}", found(tok)),
                    ));
                }
                (Some(j), "JOINT") => {
                    self.joint_header(t, Some(j))?;
                    open.push(self.joints.len() - 1);
                }
                (Some(j), "End") => {
                    self.expect("Site")?;
                    self.expect("{")?;
                    let offset = self.offset()?;
                    self.expect("}")?;
                    if self.joints[j].end_site.is_some() {
                        return Err(self.err(
                            tok,
                            format!(
                                "joint \"{}\" has a second End Site",
                                shorten(&self.joints[j].name)
                            ),
                        ));
                    }
                    self.joints[j].end_site = Some(offset);
                }
                (Some(_), "}") => {
                    open.pop();
                }
                (Some(j), _) => {
                    return Err(self.err(
                        tok,
                        format!(
                            "expected \"JOINT\", \"End Site\" or \"}}\" in joint \"{}\", found {}",
                            shorten(&self.joints[j].name),
                            found(tok)
                        ),
                    ));
                }
            }
        }
    }
}

/// Which joint and channel column `c` belongs to, for messages.
pub(super) fn column_name(joints: &[Joint], c: usize) -> String {
    // Columns tile the row in file order: the joint is the last one starting at or before c
    // that has a channel there.
    let at = joints.partition_point(|j| j.first_column <= c);
    joints[..at]
        .last()
        .filter(|j| j.columns().contains(&c))
        .map_or_else(String::new, |j| {
            format!(
                " (joint \"{}\", {})",
                shorten(&j.name),
                j.channels[c - j.first_column]
            )
        })
}
