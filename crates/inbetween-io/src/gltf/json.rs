//! The glTF JSON as read: parsed once into a `serde_json::Value` with every object's keys
//! checked unique, the channels this crate does not process set aside, and the rest parsed into
//! the `gltf` crate's types with errors located by JSON path.
//!
//! - Duplicate keys: the JSON data format glTF 2.0 uses (§3.2, RFC 8259 with unique names)
//!   requires every name in an object to be unique; `serde_json::Value` would keep the last
//!   silently, so the parse here refuses the second with its path (`animations[0].channels[1]:
//!   duplicate key "sampler"`).
//! - Channels that target something other than a node's `translation`, `rotation`, `scale` or
//!   `weights` (`KHR_animation_pointer`'s `"pointer"`, any other path), or that name no node
//!   (§3.11: the target is then defined by an extension), are not for this crate: they are left
//!   out of the typed document (they stay in the JSON the writer copies) and reported once.
//! - Errors of the typed parse name the JSON path (`accessors[4].count: invalid type: …`) and
//!   quote at most [`inbetween::error::MAX_QUOTED_CHARS`] characters of the input.

use inbetween::error::shorten;
use serde::de::{self, DeserializeSeed, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};
use std::fmt;

/// The JSON of an asset and its typed document.
pub(super) struct Parsed {
    /// The JSON as written (every channel in it).
    pub json: Value,
    /// The typed document, without the channels set aside.
    pub root: gltf::json::Root,
    /// Per animation, the JSON index of each channel kept in `root` (in order).
    pub channels: Vec<Vec<usize>>,
    /// The channels set aside: `(animation, channel, what it targets)`.
    pub ignored: Vec<(usize, usize, String)>,
}

/// The paths a channel of this crate may target (glTF 2.0 §3.11).
const PATHS: [&str; 4] = ["translation", "rotation", "scale", "weights"];

/// Parses the JSON of an asset (see the module documentation). Errors are messages without
/// the file name.
pub(super) fn parse(bytes: &[u8]) -> Result<Parsed, String> {
    let json = unique_keys_value(bytes)?;
    let mut typed = json.clone();
    let mut channels = Vec::new();
    let mut ignored = Vec::new();
    if let Some(anims) = typed.get_mut("animations").and_then(Value::as_array_mut) {
        for (a, anim) in anims.iter_mut().enumerate() {
            let Some(list) = anim.get_mut("channels").and_then(Value::as_array_mut) else {
                channels.push(Vec::new());
                continue;
            };
            let mut kept = Vec::new();
            let mut c = 0;
            list.retain(|ch| {
                let why = set_aside(ch);
                if let Some(why) = &why {
                    ignored.push((a, c, why.clone()));
                } else {
                    kept.push(c);
                }
                c += 1;
                why.is_none()
            });
            channels.push(kept);
        }
    }
    let root: gltf::json::Root = serde_path_to_error::deserialize(&typed).map_err(|e| {
        let path = e.path().to_string();
        let msg = cut_quotes(&e.inner().to_string());
        if path == "." || path.is_empty() {
            format!("invalid glTF: {msg}")
        } else {
            format!("{path}: {msg}")
        }
    })?;
    Ok(Parsed {
        json,
        root,
        channels,
        ignored,
    })
}

/// Why a channel is set aside (what it targets, for the warning), or `None` to keep it. A
/// channel whose `target` or `path` is malformed is kept, for the typed parse to report.
fn set_aside(ch: &Value) -> Option<String> {
    let target = ch.get("target")?.as_object()?;
    let path = target.get("path")?.as_str()?;
    if !PATHS.contains(&path) {
        return Some(format!("path \"{}\"", shorten(path)));
    }
    if !target.contains_key("node") {
        return Some(format!("path \"{path}\" without a node"));
    }
    None
}

/// serde's message with every quoted string longer than the quoting limit cut
/// ([`shorten`]): serde quotes a whole value it did not expect (`invalid type: string
/// "…1 MB…", expected u64`).
fn cut_quotes(msg: &str) -> String {
    let mut out = String::new();
    let mut rest = msg;
    while let Some(start) = rest.find('"') {
        out.push_str(&rest[..start]);
        let body = &rest[start + 1..];
        // The closing quote: the first not escaped by a backslash.
        let mut end = None;
        let mut escaped = false;
        for (k, c) in body.char_indices() {
            match c {
                '\\' if !escaped => escaped = true,
                '"' if !escaped => {
                    end = Some(k);
                    break;
                }
                _ => escaped = false,
            }
        }
        let Some(end) = end else {
            out.push('"');
            out.push_str(&shorten(body));
            return out;
        };
        out.push('"');
        out.push_str(&shorten(&body[..end]));
        out.push('"');
        rest = &body[end + 1..];
    }
    out.push_str(&shorten_tail(rest));
    out
}

/// The unquoted rest of a message: short in practice (serde's words), cut if not.
fn shorten_tail(s: &str) -> String {
    if s.chars().count() > 200 {
        shorten(s).into_owned()
    } else {
        s.to_string()
    }
}

/// One step of a JSON path.
enum Step {
    Key(String),
    Index(usize),
}

fn path_text(path: &[Step]) -> String {
    let mut out = String::new();
    for s in path {
        match s {
            Step::Key(k) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(&shorten(k));
            }
            Step::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// The JSON in `bytes` as a `Value`, refusing an object with a key twice.
fn unique_keys_value(bytes: &[u8]) -> Result<Value, String> {
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let mut path = Vec::new();
    let value = UniqueKeys { path: &mut path }
        .deserialize(&mut de)
        .and_then(|v| de.end().map(|()| v))
        .map_err(|e| format!("invalid glTF JSON: {}", cut_quotes(&e.to_string())))?;
    Ok(value)
}

/// A `Value` deserialized with a check for duplicate keys; `path` is where it is.
struct UniqueKeys<'p> {
    path: &'p mut Vec<Step>,
}

impl<'de> DeserializeSeed<'de> for UniqueKeys<'_> {
    type Value = Value;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for UniqueKeys<'_> {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(Value::from(v))
    }
    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        // JSON has no NaN or infinity: every f64 serde_json produces is finite.
        Ok(serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number))
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_string()))
    }
    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_none<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut out = Vec::new();
        loop {
            self.path.push(Step::Index(out.len()));
            let next = seq.next_element_seed(UniqueKeys {
                path: &mut *self.path,
            })?;
            self.path.pop();
            match next {
                Some(v) => out.push(v),
                None => return Ok(Value::Array(out)),
            }
        }
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut out = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if out.contains_key(&key) {
                let at = path_text(self.path);
                let at = if at.is_empty() {
                    "the top-level object".to_string()
                } else {
                    at
                };
                return Err(de::Error::custom(format!(
                    "{at}: duplicate key \"{}\" (glTF requires unique keys)",
                    shorten(&key)
                )));
            }
            self.path.push(Step::Key(key.clone()));
            let v = map.next_value_seed(UniqueKeys {
                path: &mut *self.path,
            })?;
            self.path.pop();
            out.insert(key, v);
        }
        Ok(Value::Object(out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicate_keys_are_refused_with_their_path() {
        let e = unique_keys_value(br#"{"a": [{"b": 1}, {"c": 2, "c": 3}]}"#).unwrap_err();
        assert!(e.contains("a[1]: duplicate key \"c\""), "{e}");
        let e = unique_keys_value(br#"{"x": 1, "x": 1}"#).unwrap_err();
        assert!(
            e.contains("the top-level object: duplicate key \"x\""),
            "{e}"
        );
        let v = unique_keys_value(br#"{"a": {"b": [1, 2.5, "s", null, true]}}"#).unwrap();
        assert_eq!(
            v,
            serde_json::json!({"a": {"b": [1, 2.5, "s", null, true]}})
        );
    }

    #[test]
    fn long_quotes_are_cut() {
        let long = "x".repeat(1000);
        let msg = format!("invalid type: string \"{long}\", expected u64");
        let cut = cut_quotes(&msg);
        assert_eq!(
            cut,
            format!("invalid type: string \"{}…\", expected u64", "x".repeat(60))
        );
        assert_eq!(cut_quotes("a \"b\\\"c\" d"), "a \"b\\\"c\" d");
    }
}

/// Whether `bytes` are a JSON object with a top-level member `"asset"`: every glTF asset has one
/// (glTF 2.0 §5.1), a keyframe document never does. How a `.gltf` without a name (on standard
/// input) is told from a keyframe document: one pass over the bytes, no parsing; text that is
/// not JSON is not glTF.
pub(crate) fn has_asset_member(bytes: &[u8]) -> bool {
    let b = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let Some(open) = b.iter().position(|c| !c.is_ascii_whitespace()) else {
        return false;
    };
    if b[open] != b'{' {
        return false;
    }
    let (mut depth, mut key_next, mut i) = (1usize, true, open + 1);
    while i < b.len() {
        match b[i] {
            b'"' => {
                let start = i + 1;
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                if depth == 1 && key_next && b.get(start..i) == Some(b"asset") {
                    return true;
                }
            }
            b'{' | b'[' => depth += 1,
            b'}' | b']' => {
                depth -= 1;
                if depth == 0 {
                    return false;
                }
            }
            b':' if depth == 1 => key_next = false,
            b',' if depth == 1 => key_next = true,
            _ => {}
        }
        i += 1;
    }
    false
}

#[cfg(test)]
mod sniff_tests {
    use super::has_asset_member;

    #[test]
    fn a_gltf_is_told_from_a_keyframe_document() {
        let gltf = br#" {"scenes": [{"nodes": [0]}], "asset": {"version": "2.0"}}"#;
        assert!(has_asset_member(gltf));
        assert!(has_asset_member(b"\xef\xbb\xbf{\"asset\":{}}"));
        for not in [
            &br#"{"keys": [{"time": 0, "quat": [1, 0, 0, 0]}], "name": "asset"}"#[..],
            br#"{"tracks": [{"name": "x", "keys": [], "asset": 1}]}"#,
            br#"{"name": "a\"asset", "keys": []}"#,
            br#"[{"asset": 1}]"#,
            b"time,w,x,y,z\n0,1,0,0,0\n",
            b"",
            b"{\"ass",
        ] {
            assert!(!has_asset_member(not), "{}", String::from_utf8_lossy(not));
        }
    }
}
