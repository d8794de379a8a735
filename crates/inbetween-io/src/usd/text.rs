//! The `.usda` text syntax, as far as a skeletal animation needs it: a lexer and a parser into
//! prims, their properties and values (docs/formats.md, *USD*). Anything else a layer may hold
//! — other prims, dictionaries, variant sets, metadata — is read and kept or skipped as values,
//! never interpreted.

use super::lex::{Lexer, Tok};
use inbetween::error::{InputError, InputResult};
use std::collections::{HashMap, VecDeque};

/// A value as written.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Value {
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
    /// `(a, b, …)` or `[a, b, …]` of numbers only: 8 bytes a number.
    Numbers(Vec<f64>),
    /// `{ code: value, … }` (time samples), or a dictionary (kept as its entries' values).
    Samples(Vec<(f64, Value)>),
    /// A dictionary or anything in braces that is not time samples.
    Other,
}

/// A property of a prim: `[uniform] type name = value`, `name.timeSamples = {…}` or `rel`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Property {
    /// The name, without `.timeSamples`.
    pub(crate) name: String,
    /// The type as written (`quatf[]`, `rel`).
    pub(crate) type_name: String,
    /// The default value, if any.
    pub(crate) value: Option<Value>,
    /// The time samples, if any.
    pub(crate) samples: Option<Vec<(f64, Value)>>,
    /// The line where it starts.
    pub(crate) line: usize,
}

/// A prim: `def Type "name" (…) { … }`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Prim {
    /// Its name, `Skeleton`.
    pub(crate) name: String,
    /// Its parent's index in [`Layer::prims`], `None` at the root.
    pub(crate) parent: Option<usize>,
    /// Its type (`Skeleton`), empty for none.
    pub(crate) type_name: String,
    /// Its properties in order.
    pub(crate) properties: Vec<Property>,
    /// The line where it starts.
    pub(crate) line: usize,
}

impl Prim {
    /// The property called `name`.
    pub(crate) fn property(&self, name: &str) -> Option<&Property> {
        self.properties.iter().find(|p| p.name == name)
    }
}

/// A parsed layer: its metadata (`key = value`) and every prim, depth first.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Layer {
    /// The layer's metadata values by key.
    pub(crate) metadata: Vec<(String, Value)>,
    /// Every prim, parents before children.
    pub(crate) prims: Vec<Prim>,
}

impl Layer {
    /// The path of prim `i`, `/Clip/Skeleton` (as long as its nesting: built on demand, so that
    /// nested prims cost memory linear in the text, not quadratic in depth).
    pub(crate) fn path(&self, i: usize) -> String {
        let mut names = Vec::new();
        let mut at = Some(i);
        while let Some(k) = at {
            names.push(self.prims[k].name.as_str());
            at = self.prims[k].parent;
        }
        let mut path = String::new();
        for n in names.iter().rev() {
            path.push('/');
            path.push_str(n);
        }
        path
    }

    /// The index of the prim at the absolute `path` (`/Clip/Skeleton`), the first where two
    /// define it; one pass over the prims.
    pub(crate) fn find(&self, path: &str) -> Option<usize> {
        let mut parent: Option<usize> = None;
        let mut from = 0;
        for name in path.split('/').filter(|n| !n.is_empty()) {
            let k = (from..self.prims.len())
                .find(|&k| self.prims[k].parent == parent && self.prims[k].name == name)?;
            parent = Some(k);
            from = k + 1;
        }
        parent
    }

    /// A word or string of the layer's metadata (`upAxis = "Z"`).
    pub(crate) fn word(&self, key: &str) -> Option<&str> {
        self.metadata
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| match v {
                Value::Str(s) | Value::Word(s) => Some(s.as_str()),
                _ => None,
            })
    }

    /// A number of the layer's metadata.
    pub(crate) fn number(&self, key: &str) -> Option<f64> {
        self.metadata
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| match v {
                Value::Num(x) => Some(*x),
                _ => None,
            })
    }
}

/// Parses `.usda` text (`source` names it in messages, with the line).
pub(crate) fn parse(text: &str, source: &str) -> InputResult<Layer> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    if !body.starts_with("#usda ") {
        return Err(InputError::new(format!(
            "{source}:1: expected \"#usda 1.0\", the first line of a USD text layer"
        )));
    }
    let lexer = Lexer {
        src: body.as_bytes(),
        at: 0,
        line: 1,
        source,
    };
    let mut p = Parser {
        lexer,
        ahead: VecDeque::new(),
        lex_error: None,
        last_line: 1,
        depth: 0,
        source,
    };
    let parsed = p.layer();
    // A lexing error ends the tokens early: it, not what the parser made of the early end, is
    // the error.
    match (parsed, p.lex_error) {
        (_, Some(e)) => Err(e),
        (result, None) => result,
    }
}

/// The properties a skeletal animation is read from; the parser keeps only these (the others
/// are parsed, checked and dropped, so a layer's meshes and shaders cost no memory).
pub(crate) const KEPT_PROPERTIES: [&str; 5] = [
    "joints",
    "restTransforms",
    "rotations",
    "translations",
    "skel:animationSource",
];

/// How deep prims, lists, tuples and metadata may nest: real layers nest a few dozen levels;
/// the parser recurses once per level, so the bound is what keeps a hostile file from
/// overflowing the stack (on a batch worker's 2 MiB thread too).
pub(crate) const MAX_NESTING: usize = 256;

/// The parser: tokens are lexed as they are needed (at most two ahead), so no token list is
/// held beside the text.
struct Parser<'a> {
    lexer: Lexer<'a>,
    ahead: VecDeque<(Tok, usize)>,
    lex_error: Option<InputError>,
    last_line: usize,
    depth: usize,
    source: &'a str,
}

impl Parser<'_> {
    fn layer(&mut self) -> InputResult<Layer> {
        let mut layer = Layer::default();
        if self.peek() == Some(&Tok::Punct('(')) {
            layer.metadata = self.metadata()?;
        }
        while self.peek().is_some() {
            self.prim(None, &mut layer.prims)?;
        }
        Ok(layer)
    }

    /// Lexes until `n` tokens are ahead (fewer at the end or at a lexing error, kept).
    fn fill(&mut self, n: usize) {
        while self.ahead.len() < n && self.lex_error.is_none() {
            match self.lexer.next() {
                Ok(Some(t)) => self.ahead.push_back(t),
                Ok(None) => break,
                Err(e) => self.lex_error = Some(e),
            }
        }
    }

    fn peek(&mut self) -> Option<&Tok> {
        self.fill(1);
        self.ahead.front().map(|t| &t.0)
    }

    /// The token after the next.
    fn peek2(&mut self) -> Option<&Tok> {
        self.fill(2);
        self.ahead.get(1).map(|t| &t.0)
    }

    /// The line of the next token (of the last one at the end).
    fn line(&mut self) -> usize {
        self.fill(1);
        self.ahead.front().map_or(self.last_line, |t| t.1)
    }

    fn err(&mut self, what: &str) -> InputError {
        let line = self.line();
        InputError::new(format!("{}:{line}: {what}", self.source))
    }

    /// An error at the token just taken.
    fn err_last(&self, what: &str) -> InputError {
        InputError::new(format!("{}:{}: {what}", self.source, self.last_line))
    }

    fn bump(&mut self) -> Option<Tok> {
        self.fill(1);
        let (t, line) = self.ahead.pop_front()?;
        self.last_line = line;
        Some(t)
    }

    /// One level deeper (a prim, a list, a tuple, metadata): an error past [`MAX_NESTING`].
    fn enter(&mut self) -> InputResult<()> {
        self.depth += 1;
        if self.depth > MAX_NESTING {
            return Err(self.err(&format!(
                "nested deeper than {MAX_NESTING} levels (prims, lists, tuples or metadata)"
            )));
        }
        Ok(())
    }

    fn expect(&mut self, c: char) -> InputResult<()> {
        match self.bump() {
            Some(Tok::Punct(p)) if p == c => Ok(()),
            other => {
                Err(self.err_last(&format!("expected '{c}', found {}", shown(other.as_ref()))))
            }
        }
    }

    /// `( key = value … )`: metadata, its keys and values (list edits and docs kept as values).
    fn metadata(&mut self) -> InputResult<Vec<(String, Value)>> {
        self.expect('(')?;
        self.enter()?;
        let mut out = Vec::new();
        loop {
            match self.bump() {
                Some(Tok::Punct(')')) => {
                    self.depth -= 1;
                    return Ok(out);
                }
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
                    return Err(self.err_last(&format!(
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
                self.enter()?;
                let close = if open == '[' { ']' } else { ')' };
                // Numbers are gathered as numbers (8 bytes each) until an item is not one.
                let mut numbers: Vec<f64> = Vec::new();
                let mut items: Option<Vec<Value>> = None;
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
                        _ => match (self.value()?, &mut items) {
                            (Value::Num(x), None) => numbers.push(x),
                            (v, Some(items)) => items.push(v),
                            (v, None) => {
                                let mut all: Vec<Value> =
                                    numbers.drain(..).map(Value::Num).collect();
                                all.push(v);
                                items = Some(all);
                            }
                        },
                    }
                }
                self.depth -= 1;
                Ok(match items {
                    // A list or tuple of numbers (a quaternion, a vector, a matrix row, an
                    // array of floats) as numbers alone.
                    None if !numbers.is_empty() => Value::Numbers(numbers),
                    None if open == '[' => Value::List(Vec::new()),
                    None => Value::Tuple(Vec::new()),
                    Some(items) if open == '[' => Value::List(items),
                    Some(items) => Value::Tuple(items),
                })
            }
            Some(Tok::Punct('{')) => {
                let samples = matches!(self.peek(), Some(Tok::Num(_)))
                    && self.peek2() == Some(&Tok::Punct(':'));
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
                            return Err(self.err_last(&format!(
                                "expected a time code or '}}', found {}",
                                shown(other.as_ref())
                            )));
                        }
                    }
                }
            }
            other => Err(self.err_last(&format!(
                "expected a value, found {}",
                shown(other.as_ref())
            ))),
        }
    }

    /// A prim (`def|over|class [Type] "name" [(…)] { … }`) and its children, under `parent`.
    fn prim(&mut self, parent: Option<usize>, prims: &mut Vec<Prim>) -> InputResult<()> {
        let line = self.line();
        self.enter()?;
        match self.bump() {
            Some(Tok::Word(w)) if matches!(w.as_str(), "def" | "over" | "class") => {}
            other => {
                return Err(self.err_last(&format!(
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
                return Err(self.err_last(&format!(
                    "expected the prim's name in quotes, found {}",
                    shown(other.as_ref())
                )));
            }
        };
        if self.peek() == Some(&Tok::Punct('(')) {
            self.metadata()?;
        }
        self.expect('{')?;
        let index = prims.len();
        prims.push(Prim {
            name,
            parent,
            type_name,
            properties: Vec::new(),
            line,
        });
        // Properties by name, for a property given twice (a default and its time samples).
        let mut by_name: HashMap<String, usize> = HashMap::new();
        loop {
            match self.peek() {
                Some(Tok::Punct('}')) => {
                    self.bump();
                    self.depth -= 1;
                    // A prim that is no skeleton or animation, keeps no property and has no
                    // such prim below it is not kept: a layer's other prims cost no memory.
                    let prim = &prims[index];
                    let kept = matches!(prim.type_name.as_str(), "Skeleton" | "SkelAnimation")
                        || !prim.properties.is_empty()
                        || prims.len() > index + 1;
                    if !kept {
                        prims.truncate(index);
                    }
                    return Ok(());
                }
                Some(Tok::Punct(';')) => {
                    self.bump();
                }
                Some(Tok::Word(w)) if matches!(w.as_str(), "def" | "over" | "class") => {
                    self.prim(Some(index), prims)?;
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
                    if !KEPT_PROPERTIES.contains(&p.name.as_str()) {
                        // Read and dropped: a layer's other properties cost no memory.
                        continue;
                    }
                    let props = &mut prims[index].properties;
                    match by_name.get(&p.name) {
                        Some(&k) => {
                            let q = &mut props[k];
                            q.value = p.value.or(q.value.take());
                            q.samples = p.samples.or(q.samples.take());
                        }
                        None => {
                            by_name.insert(p.name.clone(), props.len());
                            props.push(p);
                        }
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
        let paths: Vec<String> = (0..layer.prims.len()).map(|i| layer.path(i)).collect();
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

    /// Prims, lists and tuples nested deeper than [`MAX_NESTING`]: a located error, never a
    /// stack overflow, on a thread with a batch worker's 2 MiB stack (a debug build's frames).
    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let run = |text: String| {
            std::thread::Builder::new()
                .stack_size(2 << 20)
                .spawn(move || parse(&text, "deep.usda").map(|l| l.prims.len()))
                .unwrap()
                .join()
                .expect("no stack overflow")
        };
        let prims = |n: usize| {
            format!(
                "#usda 1.0\n{}def Skeleton \"s\" {{\n{}",
                "def \"a\" {\n".repeat(n - 1),
                "}\n".repeat(n)
            )
        };
        assert_eq!(run(prims(MAX_NESTING)).unwrap(), MAX_NESTING);
        let e = run(prims(MAX_NESTING + 1)).unwrap_err();
        assert_eq!(
            e.message(),
            format!(
                "deep.usda:{}: nested deeper than {MAX_NESTING} levels (prims, lists, tuples or \
                 metadata)",
                MAX_NESTING + 2
            )
        );
        assert!(run(prims(100_000)).is_err());
        for (open, close) in [("[", "]"), ("(", ")")] {
            let values = |n: usize| {
                format!(
                    "#usda 1.0\ndef \"a\" {{\n float x = {}1{}\n}}\n",
                    open.repeat(n),
                    close.repeat(n)
                )
            };
            assert!(run(values(MAX_NESTING - 1)).is_ok());
            assert!(run(values(MAX_NESTING)).is_err());
            assert!(run(values(1_000_000)).is_err());
        }
        let meta = format!("#usda 1.0\n{}", "( doc = ".repeat(100_000));
        assert!(run(meta).is_err());
    }

    /// A 100 000-character number is quoted cut to 60 characters.
    #[test]
    fn long_tokens_are_quoted_shortened() {
        let long = "1".repeat(50_000) + "x" + &"2".repeat(50_000);
        let e = parse(&format!("#usda 1.0\n( a = {long} )\n"), "l.usda").unwrap_err();
        assert!(e.message().len() < 200, "{}", e.message());
    }

    /// Blender's export writes asset paths: read as values, skipped.
    #[test]
    fn asset_paths_are_values() {
        let text = "#usda 1.0\ndef Shader \"s\" {\n asset inputs:file = @./textures/x.jpg@\n asset b = @@@a@b\nc@@@\n asset joints = @j@\n}\n";
        let layer = parse(text, "a.usda").unwrap();
        let p = layer.prims[0].property("joints").unwrap();
        assert_eq!(p.value, Some(Value::Str("j".into())));
        assert_eq!(p.line, 6);
        // Properties no skeleton is read from are not kept.
        assert!(layer.prims[0].property("inputs:file").is_none());
        assert!(parse("#usda 1.0\ndef \"s\" {\n asset a = @x\n}\n", "b.usda").is_err());
    }

    /// Paths are built from parents, found in one pass; the first of two definitions wins.
    #[test]
    fn prims_are_found_by_path() {
        let text = "#usda 1.0\ndef \"A\" {\n def \"B\" {\n def Skeleton \"C\" {\n }\n def \"D\" {\n float x = 1\n }\n }\n def SkelAnimation \"C\" {\n }\n}\nover \"A\" {\n}\n";
        let layer = parse(text, "p.usda").unwrap();
        assert_eq!(layer.find("/A/B/C"), Some(2));
        assert_eq!(layer.find("/A/C"), Some(3));
        assert_eq!(layer.find("/A"), Some(0));
        assert_eq!(layer.find("/B"), None);
        assert_eq!(layer.path(2), "/A/B/C");
        // D (no kept property) and the last `over` (nothing in it) are not kept.
        assert_eq!(layer.prims.len(), 4);
    }
}
