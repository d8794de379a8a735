//! The `.usda` text syntax, as far as a skeletal animation needs it: a lexer and a parser into
//! prims, their properties and values (docs/formats.md, *USD*). Anything else a layer may hold
//! — other prims, dictionaries, variant sets, metadata — is read and kept or skipped as values,
//! never interpreted.

use inbetween::error::{InputError, InputResult};

/// A value as written.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number.
    Num(f64),
    /// A quoted string.
    Str(String),
    /// A bare word (`true`, a token, a type name).
    Word(String),
    /// A path, `</Clip/Skeleton>`.
    Path(String),
    /// `[a, b, …]`.
    List(Vec<Value>),
    /// `(a, b, …)`.
    Tuple(Vec<Value>),
    /// `{ code: value, … }` (time samples), or a dictionary (kept as its entries' values).
    Samples(Vec<(f64, Value)>),
    /// A dictionary or anything in braces that is not time samples.
    Other,
}

/// A property of a prim: `[uniform] type name = value`, `name.timeSamples = {…}` or `rel`.
#[derive(Debug, Clone, PartialEq)]
pub struct Property {
    /// The name, without `.timeSamples`.
    pub name: String,
    /// The type as written (`quatf[]`, `rel`).
    pub type_name: String,
    /// The default value, if any.
    pub value: Option<Value>,
    /// The time samples, if any.
    pub samples: Option<Vec<(f64, Value)>>,
    /// The line where it starts.
    pub line: usize,
}

/// A prim: `def Type "name" (…) { … }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Prim {
    /// Its path, `/Clip/Skeleton`.
    pub path: String,
    /// Its type (`Skeleton`), empty for none.
    pub type_name: String,
    /// Its properties in order.
    pub properties: Vec<Property>,
    /// The line where it starts.
    pub line: usize,
}

impl Prim {
    /// The property called `name`.
    pub fn property(&self, name: &str) -> Option<&Property> {
        self.properties.iter().find(|p| p.name == name)
    }
}

/// A parsed layer: its metadata (`key = value`) and every prim, depth first.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Layer {
    /// The layer's metadata values by key.
    pub metadata: Vec<(String, Value)>,
    /// Every prim, parents before children.
    pub prims: Vec<Prim>,
}

impl Layer {
    /// A word or string of the layer's metadata (`upAxis = "Z"`).
    pub fn word(&self, key: &str) -> Option<&str> {
        self.metadata
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| match v {
                Value::Str(s) | Value::Word(s) => Some(s.as_str()),
                _ => None,
            })
    }

    /// A number of the layer's metadata.
    pub fn number(&self, key: &str) -> Option<f64> {
        self.metadata
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| match v {
                Value::Num(x) => Some(*x),
                _ => None,
            })
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Num(f64),
    Str(String),
    Word(String),
    Path(String),
    Punct(char),
}

struct Lexer<'a> {
    src: &'a [u8],
    at: usize,
    line: usize,
    source: &'a str,
}

impl Lexer<'_> {
    fn err(&self, what: &str) -> InputError {
        InputError::new(format!("{}:{}: {what}", self.source, self.line))
    }

    /// The next token and its line, or `None` at the end.
    fn next(&mut self) -> InputResult<Option<(Tok, usize)>> {
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
                    _ => text
                        .parse::<f64>()
                        .map_err(|_| self.err(&format!("expected a number, found \"{text}\"")))?,
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

/// Parses `.usda` text (`source` names it in messages, with the line).
pub fn parse(text: &str, source: &str) -> InputResult<Layer> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    if !body.starts_with("#usda ") {
        return Err(InputError::new(format!(
            "{source}:1: expected \"#usda 1.0\", the first line of a USD text layer"
        )));
    }
    let mut lexer = Lexer {
        src: body.as_bytes(),
        at: 0,
        line: 1,
        source,
    };
    let mut toks = Vec::new();
    while let Some(t) = lexer.next()? {
        toks.push(t);
    }
    let mut p = Parser {
        toks,
        at: 0,
        source,
    };
    let mut layer = Layer::default();
    if p.peek() == Some(&Tok::Punct('(')) {
        layer.metadata = p.metadata()?;
    }
    while p.peek().is_some() {
        p.prim("", &mut layer.prims)?;
    }
    Ok(layer)
}

struct Parser<'a> {
    toks: Vec<(Tok, usize)>,
    at: usize,
    source: &'a str,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.at).map(|t| &t.0)
    }

    fn line(&self) -> usize {
        self.toks
            .get(self.at)
            .or(self.toks.last())
            .map_or(1, |t| t.1)
    }

    fn err(&self, what: &str) -> InputError {
        InputError::new(format!("{}:{}: {what}", self.source, self.line()))
    }

    fn bump(&mut self) -> Option<Tok> {
        let t = self.toks.get(self.at).map(|t| t.0.clone());
        self.at += 1;
        t
    }

    fn expect(&mut self, c: char) -> InputResult<()> {
        match self.bump() {
            Some(Tok::Punct(p)) if p == c => Ok(()),
            other => {
                self.at -= 1;
                Err(self.err(&format!("expected '{c}', found {}", shown(other.as_ref()))))
            }
        }
    }

    /// `( key = value … )`: metadata, its keys and values (list edits and docs kept as values).
    fn metadata(&mut self) -> InputResult<Vec<(String, Value)>> {
        self.expect('(')?;
        let mut out = Vec::new();
        loop {
            match self.bump() {
                Some(Tok::Punct(')')) => return Ok(out),
                Some(Tok::Punct(';')) => {}
                Some(Tok::Str(_)) => {}
                Some(Tok::Word(w)) => {
                    let key = match w.as_str() {
                        "prepend" | "append" | "add" | "delete" | "reorder" => match self.bump() {
                            Some(Tok::Word(k)) => k,
                            other => {
                                return Err(self.err(&format!(
                                    "expected a metadata key, found {}",
                                    shown(other.as_ref())
                                )));
                            }
                        },
                        _ => w,
                    };
                    // A typed dictionary entry (`string key = …`) has its name next.
                    let key = match self.peek() {
                        Some(Tok::Word(_)) | Some(Tok::Str(_)) => match self.bump() {
                            Some(Tok::Word(k) | Tok::Str(k)) => k,
                            _ => key,
                        },
                        _ => key,
                    };
                    if self.peek() == Some(&Tok::Punct('=')) {
                        self.bump();
                        let v = self.value()?;
                        out.push((key, v));
                    }
                }
                other => {
                    self.at -= 1;
                    return Err(self.err(&format!(
                        "expected metadata or ')', found {}",
                        shown(other.as_ref())
                    )));
                }
            }
        }
    }

    /// A value: number, string, word, path, list, tuple, or braces (time samples or a
    /// dictionary).
    fn value(&mut self) -> InputResult<Value> {
        match self.bump() {
            Some(Tok::Num(x)) => Ok(Value::Num(x)),
            Some(Tok::Str(s)) => Ok(Value::Str(s)),
            Some(Tok::Word(w)) => Ok(Value::Word(w)),
            Some(Tok::Path(p)) => Ok(Value::Path(p)),
            Some(Tok::Punct(open @ ('[' | '('))) => {
                let close = if open == '[' { ']' } else { ')' };
                let mut items = Vec::new();
                loop {
                    match self.peek() {
                        Some(Tok::Punct(c)) if *c == close => {
                            self.bump();
                            break;
                        }
                        Some(Tok::Punct(',')) => {
                            self.bump();
                        }
                        None => return Err(self.err(&format!("expected '{close}', found the end"))),
                        _ => items.push(self.value()?),
                    }
                }
                Ok(if open == '[' {
                    Value::List(items)
                } else {
                    Value::Tuple(items)
                })
            }
            Some(Tok::Punct('{')) => {
                let samples = matches!(self.peek(), Some(Tok::Num(_)))
                    && matches!(self.toks.get(self.at + 1), Some((Tok::Punct(':'), _)));
                if !samples {
                    let mut depth = 1;
                    while depth > 0 {
                        match self.bump() {
                            Some(Tok::Punct('{')) => depth += 1,
                            Some(Tok::Punct('}')) => depth -= 1,
                            None => return Err(self.err("expected '}', found the end")),
                            _ => {}
                        }
                    }
                    return Ok(Value::Other);
                }
                let mut out = Vec::new();
                loop {
                    match self.bump() {
                        Some(Tok::Punct('}')) => return Ok(Value::Samples(out)),
                        Some(Tok::Punct(',')) => {}
                        Some(Tok::Num(code)) => {
                            self.expect(':')?;
                            out.push((code, self.value()?));
                        }
                        other => {
                            self.at -= 1;
                            return Err(self.err(&format!(
                                "expected a time code or '}}', found {}",
                                shown(other.as_ref())
                            )));
                        }
                    }
                }
            }
            other => {
                self.at -= 1;
                Err(self.err(&format!(
                    "expected a value, found {}",
                    shown(other.as_ref())
                )))
            }
        }
    }

    /// A prim (`def|over|class [Type] "name" [(…)] { … }`) and its children, under `parent`.
    fn prim(&mut self, parent: &str, prims: &mut Vec<Prim>) -> InputResult<()> {
        let line = self.line();
        match self.bump() {
            Some(Tok::Word(w)) if matches!(w.as_str(), "def" | "over" | "class") => {}
            other => {
                self.at -= 1;
                return Err(self.err(&format!(
                    "expected a prim (def, over or class), found {}",
                    shown(other.as_ref())
                )));
            }
        }
        let type_name = match self.peek() {
            Some(Tok::Word(_)) => match self.bump() {
                Some(Tok::Word(t)) => t,
                _ => String::new(),
            },
            _ => String::new(),
        };
        let name = match self.bump() {
            Some(Tok::Str(n)) => n,
            other => {
                self.at -= 1;
                return Err(self.err(&format!(
                    "expected the prim's name in quotes, found {}",
                    shown(other.as_ref())
                )));
            }
        };
        if self.peek() == Some(&Tok::Punct('(')) {
            self.metadata()?;
        }
        self.expect('{')?;
        let path = format!("{parent}/{name}");
        let index = prims.len();
        prims.push(Prim {
            path: path.clone(),
            type_name,
            properties: Vec::new(),
            line,
        });
        loop {
            match self.peek() {
                Some(Tok::Punct('}')) => {
                    self.bump();
                    return Ok(());
                }
                Some(Tok::Punct(';')) => {
                    self.bump();
                }
                Some(Tok::Word(w)) if matches!(w.as_str(), "def" | "over" | "class") => {
                    self.prim(&path, prims)?;
                }
                Some(Tok::Word(w)) if w == "variantSet" => {
                    // `variantSet "name" = { … }`: skipped.
                    self.bump();
                    self.bump();
                    self.expect('=')?;
                    self.value()?;
                }
                Some(Tok::Word(_)) => {
                    let p = self.property()?;
                    let props = &mut prims[index].properties;
                    match props.iter_mut().find(|q| q.name == p.name) {
                        Some(q) => {
                            q.value = p.value.or(q.value.take());
                            q.samples = p.samples.or(q.samples.take());
                        }
                        None => props.push(p),
                    }
                }
                other => {
                    let other = other.cloned();
                    return Err(self.err(&format!(
                        "expected a property, a prim or '}}', found {}",
                        shown(other.as_ref())
                    )));
                }
            }
        }
    }

    /// A property: qualifiers, a type (or `rel`), a name, an optional value and metadata.
    fn property(&mut self) -> InputResult<Property> {
        let line = self.line();
        let mut type_name = String::new();
        let mut name = None;
        while let Some(Tok::Word(w)) = self.peek().cloned() {
            self.bump();
            match w.as_str() {
                "custom" | "uniform" | "varying" | "prepend" | "append" | "add" | "delete"
                | "reorder" => {}
                _ if type_name.is_empty() => {
                    type_name = w;
                    if self.peek() == Some(&Tok::Punct('[')) {
                        self.bump();
                        self.expect(']')?;
                        type_name.push_str("[]");
                    }
                }
                _ => {
                    name = Some(w);
                    break;
                }
            }
        }
        let Some(mut name) = name else {
            return Err(self.err("expected a property's type and name"));
        };
        let mut prop = Property {
            name: String::new(),
            type_name,
            value: None,
            samples: None,
            line,
        };
        if self.peek() == Some(&Tok::Punct('=')) {
            self.bump();
            let v = self.value()?;
            if let Some(base) = name.strip_suffix(".timeSamples") {
                let Value::Samples(s) = v else {
                    return Err(
                        self.err(&format!("{name}: expected time samples {{ code: value }}"))
                    );
                };
                prop.samples = Some(s);
                name = base.to_string();
            } else {
                prop.value = Some(v);
            }
        }
        if self.peek() == Some(&Tok::Punct('(')) {
            self.metadata()?;
        }
        prop.name = name;
        Ok(prop)
    }
}

fn shown(t: Option<&Tok>) -> String {
    match t {
        None => "the end".into(),
        Some(Tok::Num(x)) => format!("{x}"),
        Some(Tok::Str(s)) => format!("\"{}\"", inbetween::error::shorten(s)),
        Some(Tok::Word(w)) => format!("\"{}\"", inbetween::error::shorten(w)),
        Some(Tok::Path(p)) => format!("<{}>", inbetween::error::shorten(p)),
        Some(Tok::Punct(c)) => format!("'{c}'"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_prims_properties_samples_and_metadata() {
        let text = "#usda 1.0\n(\n    doc = \"\"\"a\n\"b\"\"\"\n    timeCodesPerSecond = 29.97002997002997\n    customLayerData = {\n        string creator = \"x\"\n    }\n)\n\ndef SkelRoot \"Clip\" (kind = \"component\")\n{\n    def Skeleton \"Skel\" (\n        prepend apiSchemas = [\"SkelBindingAPI\"]\n    )\n    {\n        uniform token[] joints = [\"A\", \"A/B\"]\n        rel skel:animationSource = </Clip/Skel/Anim>\n        def SkelAnimation \"Anim\"\n        {\n            quatf[] rotations.timeSamples = {\n                0: [(1, 0, 0, -0), (0.70710677, 0, 0, 0.70710677)],\n                2.5: [(1, 0, 0, 0), (1, 0, 0, 0)],\n            }\n        }\n    }\n}\n";
        let layer = parse(text, "a.usda").unwrap();
        assert_eq!(layer.number("timeCodesPerSecond"), Some(29.97002997002997));
        let paths: Vec<&str> = layer.prims.iter().map(|p| p.path.as_str()).collect();
        assert_eq!(paths, ["/Clip", "/Clip/Skel", "/Clip/Skel/Anim"]);
        let skel = &layer.prims[1];
        assert_eq!(skel.type_name, "Skeleton");
        assert_eq!(
            skel.property("skel:animationSource").unwrap().value,
            Some(Value::Path("/Clip/Skel/Anim".into()))
        );
        let rot = layer.prims[2].property("rotations").unwrap();
        assert_eq!(rot.type_name, "quatf[]");
        let s = rot.samples.as_ref().unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s[1].0, 2.5);
        assert_eq!(rot.line, 21);
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse(
            "#usda 1.0\ndef Xform \"a\"\n{\n    float x = (1, 2\n}\n",
            "b.usda",
        )
        .unwrap_err();
        assert_eq!(e.message(), "b.usda:5: expected a value, found '}'");
        let e = parse("hello", "c.usda").unwrap_err();
        assert!(e.message().starts_with("c.usda:1: expected \"#usda 1.0\""));
        let e = parse("#usda 1.0\ndef \"a\" { float x = \"open\n}", "d.usda").unwrap_err();
        assert_eq!(e.message(), "d.usda:2: a string without its closing quote");
    }
}
