//! JSON keyframe documents (docs/spec.md §3).
//!
//! ```json
//! {"fps": 30, "rotation": "euler:ZYX", "angles": "deg",
//!  "start_velocity": [0, 0, 0], "end_velocity": [0, 0, 0],
//!  "keys": [{"time": 0.0, "euler": [0, 0, 0]}, {"frame": 24, "quat": [1, 0, 0, 0]}]}
//! ```
//! or `"tracks": [{"name": "hip", "keys": [...], "start_velocity": ...}, ...]`. A bare array is
//! taken as `keys`; `frames` (interp's output) is a synonym of `keys`, in a document and in a
//! track. Unknown fields, and a field given twice in one object, are errors. Each key has one of
//! `time`/`frame` (or both, as interp writes them: the time is used, the frame checked against
//! it when the rate is known) and one rotation field. A document's declarations (`fps`,
//! `rotation`, `angles`) describe its own values; the flags (`--key-fps`, `--from`,
//! `--input-angles`) only what it leaves undeclared, and contradicting one is an error
//! ([`settle`]).

use crate::document::{
    DocTrack, Document, EulerKeys, Key, KeyOrigin, KeyTime, Loc, push_shape, push_sparse, shorten,
};
use crate::{ReadOptions, settle};
use glam::DVec3;
use inbetween::clock::Fps;
use inbetween::error::{InputError, InputResult};
use inbetween::rotation::{AngleUnit, Repr};
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, de::Error as _};
use serde_json::Value;
use serde_path_to_error::Segment;
use std::collections::HashSet;
use std::fmt;

// The wire types below are read straight from the text by hand-written visitors (no
// `serde_json::Value` tree, no derive): every object rejects unknown and repeated fields (serde's
// derive keeps the last of two), and a message quotes at most `MAX_QUOTED_CHARS` characters of
// the user's text. Visitors ask for `deserialize_any`, so that serde_json hands a wrong-typed
// string to them rather than quoting it whole in its own message.

/// Field names of a document, a track and a key, in the order messages list them.
const DOC_FIELDS: &[&str] = &[
    "fps",
    "rotation",
    "angles",
    "start_velocity",
    "end_velocity",
    "keys",
    "frames",
    "tracks",
];
const TRACK_FIELDS: &[&str] = &["name", "start_velocity", "end_velocity", "keys", "frames"];
const KEY_FIELDS: &[&str] = &[
    "time",
    "frame",
    "quat",
    "euler",
    "matrix",
    "axis_angle",
    "rotvec",
    "angular_velocity",
    "velocity",
    "tension",
    "continuity",
    "bias",
    "translation",
];
/// Index in [`KEY_FIELDS`] of the first rotation field.
const FIRST_ROTATION: usize = 2;

/// The JSON document as read: syntax, types, field names, array lengths checked; nothing
/// interpreted yet (key values need the document's `angles` and `rotation`, which may come last).
#[derive(Default)]
struct DocWire {
    fps: Option<FpsWire>,
    rotation: Option<String>,
    angles: Option<String>,
    start_velocity: Option<[f64; 3]>,
    end_velocity: Option<[f64; 3]>,
    keys: Option<Vec<KeyWire>>,
    frames: Option<Vec<KeyWire>>,
    tracks: Option<Vec<TrackWire>>,
}

struct TrackWire {
    name: Option<String>,
    start_velocity: Option<[f64; 3]>,
    end_velocity: Option<[f64; 3]>,
    keys: Vec<KeyWire>,
    /// The keys were given as `frames` (interp's output).
    frames: bool,
}

/// A key as read. `null` fields count as absent.
#[derive(Default)]
struct KeyWire {
    time: Option<f64>,
    frame: Option<f64>,
    /// The rotation fields present, bit `i` for `KEY_FIELDS[FIRST_ROTATION + i]`.
    rotations: u8,
    /// The values of the last rotation field read (the only one, when the key is valid).
    values: [f64; 9],
    /// An `angular_velocity` was given (interp's frames).
    angular_velocity: bool,
    /// The key's own angular velocity (`velocity`, or `angular_velocity` in frames), in the
    /// document's angle unit per second.
    velocity: Option<[f64; 3]>,
    /// The key's own tension, continuity and bias.
    tcb: [Option<f64>; 3],
    /// The key's position.
    translation: Option<[f64; 3]>,
}

/// `fps` as read: a number, a string, or something else (shown in the message, cut).
enum FpsWire {
    Number(f64),
    Text(String),
    Other(String),
}

/// A wrong-typed string, cut, for `invalid type` messages.
fn bad_str<E: de::Error>(v: &str, exp: &dyn de::Expected) -> E {
    E::invalid_type(de::Unexpected::Str(&shorten(v)), exp)
}

/// A JSON number as f64 (serde_json has already refused anything out of f64 range).
#[derive(Clone, Copy, Default)]
struct Num(f64);

struct NumVisitor;

impl<'de> Visitor<'de> for NumVisitor {
    type Value = Num;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("f64")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Num, E> {
        Ok(Num(v))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Num, E> {
        Ok(Num(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Num, E> {
        Ok(Num(v as f64))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Num, E> {
        Err(bad_str(v, &self))
    }
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Num, D::Error> {
        d.deserialize_any(NumVisitor)
    }
}

/// An array of exactly `N` values.
struct Fixed<T, const N: usize>([T; N]);

struct FixedVisitor<T, const N: usize>(std::marker::PhantomData<T>);

impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Visitor<'de>
    for FixedVisitor<T, N>
{
    type Value = Fixed<T, N>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "an array of length {N}")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Fixed<T, N>, A::Error> {
        let mut out = [T::default(); N];
        for (i, slot) in out.iter_mut().enumerate() {
            *slot = seq
                .next_element()?
                .ok_or_else(|| A::Error::invalid_length(i, &self))?;
        }
        let mut extra = 0;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            extra += 1;
        }
        if extra > 0 {
            return Err(A::Error::invalid_length(N + extra, &self));
        }
        Ok(Fixed(out))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Fixed<T, N>, E> {
        Err(bad_str(v, &self))
    }
}

impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Deserialize<'de> for Fixed<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(FixedVisitor(std::marker::PhantomData))
    }
}

impl<T: Copy + Default, const N: usize> Clone for Fixed<T, N> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T: Copy + Default, const N: usize> Copy for Fixed<T, N> {}
impl<T: Copy + Default, const N: usize> Default for Fixed<T, N> {
    fn default() -> Self {
        Fixed([T::default(); N])
    }
}

fn nums<const N: usize>(a: Fixed<Num, N>) -> [f64; N] {
    a.0.map(|n| n.0)
}

/// A string (`rotation`, `angles`, a track's `name`).
struct Text(String);

struct TextVisitor;

impl Visitor<'_> for TextVisitor {
    type Value = Text;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a string")
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Text, E> {
        Ok(Text(v.to_owned()))
    }
    fn visit_string<E: de::Error>(self, v: String) -> Result<Text, E> {
        Ok(Text(v))
    }
}

impl<'de> Deserialize<'de> for Text {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Text, D::Error> {
        d.deserialize_any(TextVisitor)
    }
}

struct FpsVisitor;

impl<'de> Visitor<'de> for FpsVisitor {
    type Value = FpsWire;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number or a string")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<FpsWire, E> {
        Ok(FpsWire::Number(v))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<FpsWire, E> {
        Ok(FpsWire::Number(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<FpsWire, E> {
        Ok(FpsWire::Number(v as f64))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<FpsWire, E> {
        Ok(FpsWire::Text(v.to_owned()))
    }
    fn visit_bool<E: de::Error>(self, v: bool) -> Result<FpsWire, E> {
        Ok(FpsWire::Other(v.to_string()))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<FpsWire, A::Error> {
        let v = Value::deserialize(de::value::SeqAccessDeserializer::new(seq))?;
        Ok(FpsWire::Other(shorten(&v.to_string()).into_owned()))
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<FpsWire, A::Error> {
        let v = Value::deserialize(de::value::MapAccessDeserializer::new(map))?;
        Ok(FpsWire::Other(shorten(&v.to_string()).into_owned()))
    }
}

impl<'de> Deserialize<'de> for FpsWire {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<FpsWire, D::Error> {
        d.deserialize_any(FpsVisitor)
    }
}

/// A field name: its index in `self.0`, or the unknown name (cut).
struct FieldSeed(&'static [&'static str]);

impl<'de> DeserializeSeed<'de> for FieldSeed {
    type Value = Result<usize, String>;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_identifier(self)
    }
}

impl Visitor<'_> for FieldSeed {
    type Value = Result<usize, String>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a field name")
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
        Ok(self
            .0
            .iter()
            .position(|f| *f == v)
            .ok_or_else(|| shorten(v).into_owned()))
    }
}

/// The next field of an object whose fields are `fields`: its index, once. An unknown field
/// (serde's message, the name cut) and a field given twice are errors at the object's path.
fn next_field<'de, A: MapAccess<'de>>(
    map: &mut A,
    fields: &'static [&'static str],
    seen: &mut u32,
) -> Result<Option<usize>, A::Error> {
    let Some(field) = map.next_key_seed(FieldSeed(fields))? else {
        return Ok(None);
    };
    let i = field.map_err(|name| {
        let expected: Vec<String> = fields.iter().map(|f| format!("`{f}`")).collect();
        A::Error::custom(format_args!(
            "unknown field `{name}`, expected one of {}",
            expected.join(", ")
        ))
    })?;
    if *seen & (1 << i) != 0 {
        return Err(A::Error::custom(format_args!(
            "duplicate field \"{}\"",
            fields[i]
        )));
    }
    *seen |= 1 << i;
    Ok(Some(i))
}

/// `[T]` read element by element (`Vec<T>`'s own impl would quote a wrong-typed string whole).
struct List<T>(Vec<T>);

struct ListVisitor<T>(&'static str, std::marker::PhantomData<T>);

impl<'de, T: Deserialize<'de>> Visitor<'de> for ListVisitor<T> {
    type Value = List<T>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.0)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<List<T>, A::Error> {
        let mut out = Vec::new();
        while let Some(x) = seq.next_element()? {
            out.push(x);
        }
        Ok(List(out))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<List<T>, E> {
        Err(bad_str(v, &self))
    }
}

/// What a list holds, for its `expecting` message.
trait Listed {
    const LIST: &'static str;
}
impl Listed for KeyWire {
    const LIST: &'static str = "an array of keys";
}
impl Listed for TrackWire {
    const LIST: &'static str = "an array of tracks";
}

impl<'de, T: Deserialize<'de> + Listed> Deserialize<'de> for List<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<List<T>, D::Error> {
        d.deserialize_any(ListVisitor(T::LIST, std::marker::PhantomData))
    }
}

struct KeyVisitor;

impl<'de> Visitor<'de> for KeyVisitor {
    type Value = KeyWire;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a key object")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<KeyWire, A::Error> {
        let mut key = KeyWire::default();
        let mut seen = 0;
        while let Some(i) = next_field(&mut map, KEY_FIELDS, &mut seen)? {
            let mut rotation = |values: Option<&[f64]>| {
                if let Some(v) = values {
                    key.rotations |= 1 << (i - FIRST_ROTATION);
                    key.values[..v.len()].copy_from_slice(v);
                }
            };
            match KEY_FIELDS[i] {
                "time" => key.time = map.next_value::<Option<Num>>()?.map(|n| n.0),
                "frame" => key.frame = map.next_value::<Option<Num>>()?.map(|n| n.0),
                "quat" | "axis_angle" => rotation(
                    map.next_value::<Option<Fixed<Num, 4>>>()?
                        .map(nums)
                        .as_ref()
                        .map(|a| &a[..]),
                ),
                "euler" | "rotvec" => rotation(
                    map.next_value::<Option<Fixed<Num, 3>>>()?
                        .map(nums)
                        .as_ref()
                        .map(|a| &a[..]),
                ),
                "angular_velocity" | "velocity" => {
                    let v = map.next_value::<Option<Fixed<Num, 3>>>()?.map(nums);
                    if v.is_some() {
                        if key.velocity.is_some() {
                            return Err(A::Error::custom(
                                "expected one of `velocity` and `angular_velocity`, found both",
                            ));
                        }
                        key.angular_velocity |= KEY_FIELDS[i] == "angular_velocity";
                        key.velocity = v;
                    }
                }
                "tension" => key.tcb[0] = map.next_value::<Option<Num>>()?.map(|n| n.0),
                "continuity" => key.tcb[1] = map.next_value::<Option<Num>>()?.map(|n| n.0),
                "bias" => key.tcb[2] = map.next_value::<Option<Num>>()?.map(|n| n.0),
                "translation" => {
                    key.translation = map.next_value::<Option<Fixed<Num, 3>>>()?.map(nums);
                }
                _ => {
                    let m = map.next_value::<Option<Fixed<Fixed<Num, 3>, 3>>>()?;
                    let flat = m.map(|m| {
                        let mut v = [0.0; 9];
                        v.copy_from_slice(m.0.map(nums).as_flattened());
                        v
                    });
                    rotation(flat.as_ref().map(|a| &a[..]))
                }
            }
        }
        Ok(key)
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<KeyWire, E> {
        Err(bad_str(v, &self))
    }
}

impl<'de> Deserialize<'de> for KeyWire {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<KeyWire, D::Error> {
        d.deserialize_any(KeyVisitor)
    }
}

fn velocity<'de, A: MapAccess<'de>>(map: &mut A) -> Result<Option<[f64; 3]>, A::Error> {
    Ok(map.next_value::<Option<Fixed<Num, 3>>>()?.map(nums))
}

struct TrackVisitor;

impl<'de> Visitor<'de> for TrackVisitor {
    type Value = TrackWire;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a track object")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<TrackWire, A::Error> {
        let (mut name, mut start_velocity, mut end_velocity) = (None, None, None);
        let (mut keys, mut frames) = (None, None);
        let mut seen = 0;
        while let Some(i) = next_field(&mut map, TRACK_FIELDS, &mut seen)? {
            match TRACK_FIELDS[i] {
                "name" => name = map.next_value::<Option<Text>>()?.map(|t| t.0),
                "start_velocity" => start_velocity = velocity(&mut map)?,
                "end_velocity" => end_velocity = velocity(&mut map)?,
                "keys" => keys = Some(map.next_value::<List<KeyWire>>()?.0),
                _ => frames = Some(map.next_value::<List<KeyWire>>()?.0),
            }
        }
        let (keys, frames) = match (keys, frames) {
            (Some(k), None) => (k, false),
            (None, Some(f)) => (f, true),
            (Some(_), Some(_)) => {
                return Err(A::Error::custom(
                    "expected \"keys\" or \"frames\", found both",
                ));
            }
            (None, None) => return Err(A::Error::missing_field("keys")),
        };
        Ok(TrackWire {
            name,
            start_velocity,
            end_velocity,
            keys,
            frames,
        })
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<TrackWire, E> {
        Err(bad_str(v, &self))
    }
}

impl<'de> Deserialize<'de> for TrackWire {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<TrackWire, D::Error> {
        d.deserialize_any(TrackVisitor)
    }
}

/// The document: an object, or a bare array of keys.
struct DocVisitor;

impl DocVisitor {
    fn not_a_document<E: de::Error>(kind: &str) -> E {
        E::custom(format_args!(
            "expected an object with \"keys\" or \"tracks\" (or an array of keys), found {kind}"
        ))
    }
}

impl<'de> Visitor<'de> for DocVisitor {
    type Value = DocWire;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an object with \"keys\" or \"tracks\" (or an array of keys)")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<DocWire, A::Error> {
        let mut doc = DocWire::default();
        let mut seen = 0;
        while let Some(i) = next_field(&mut map, DOC_FIELDS, &mut seen)? {
            match DOC_FIELDS[i] {
                "fps" => doc.fps = map.next_value()?,
                "rotation" => doc.rotation = map.next_value::<Option<Text>>()?.map(|t| t.0),
                "angles" => doc.angles = map.next_value::<Option<Text>>()?.map(|t| t.0),
                "start_velocity" => doc.start_velocity = velocity(&mut map)?,
                "end_velocity" => doc.end_velocity = velocity(&mut map)?,
                "keys" => doc.keys = map.next_value::<Option<List<KeyWire>>>()?.map(|l| l.0),
                "frames" => doc.frames = map.next_value::<Option<List<KeyWire>>>()?.map(|l| l.0),
                _ => doc.tracks = map.next_value::<Option<List<TrackWire>>>()?.map(|l| l.0),
            }
        }
        Ok(doc)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<DocWire, A::Error> {
        let keys = ListVisitor::<KeyWire>("", std::marker::PhantomData).visit_seq(seq)?;
        Ok(DocWire {
            keys: Some(keys.0),
            ..DocWire::default()
        })
    }
    fn visit_unit<E: de::Error>(self) -> Result<DocWire, E> {
        Err(Self::not_a_document("null"))
    }
    fn visit_bool<E: de::Error>(self, _: bool) -> Result<DocWire, E> {
        Err(Self::not_a_document("a boolean"))
    }
    fn visit_i64<E: de::Error>(self, _: i64) -> Result<DocWire, E> {
        Err(Self::not_a_document("a number"))
    }
    fn visit_u64<E: de::Error>(self, _: u64) -> Result<DocWire, E> {
        Err(Self::not_a_document("a number"))
    }
    fn visit_f64<E: de::Error>(self, _: f64) -> Result<DocWire, E> {
        Err(Self::not_a_document("a number"))
    }
    fn visit_str<E: de::Error>(self, _: &str) -> Result<DocWire, E> {
        Err(Self::not_a_document("a string"))
    }
}

impl<'de> Deserialize<'de> for DocWire {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<DocWire, D::Error> {
        d.deserialize_any(DocVisitor)
    }
}

/// serde_json's message without the " at line L column C" it appends.
fn serde_message(e: &serde_json::Error) -> String {
    let msg = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    match msg.strip_suffix(&suffix) {
        Some(m) if e.line() != 0 => m.to_string(),
        _ => msg,
    }
}

/// A reading error, located: `source:line:column` for syntax, else the key or track it is in
/// (`source: keys[3]`, `source: tracks[1].keys[0]`, `source: tracks[1]`), then the field within
/// it, quoted (`"quat[1]"`).
fn located(source: &str, e: serde_path_to_error::Error<serde_json::Error>) -> InputError {
    let inner = e.inner();
    if inner.classify() != serde_json::error::Category::Data {
        return input_err!(
            "{source}:{}:{}: {}",
            inner.line(),
            inner.column(),
            serde_message(inner)
        );
    }
    let msg = serde_message(inner);
    let segments: Vec<&Segment> = e.path().iter().collect();
    let map = |s: &Segment, name: &str| matches!(s, Segment::Map { key } if key == name);
    let seq = |s: &Segment| match s {
        Segment::Seq { index } => Some(*index),
        _ => None,
    };
    // A list of keys: `keys`, or `frames` (interp's output).
    let list = |s: &Segment| ["keys", "frames"].into_iter().find(|n| map(s, n));
    let (place, field) = match segments.as_slice() {
        // A bare array of keys.
        [s, rest @ ..] if seq(s).is_some() => (format!("keys[{}]", seq(s).unwrap()), rest),
        [k, s, rest @ ..] if list(k).is_some() && seq(s).is_some() => {
            (format!("{}[{}]", list(k).unwrap(), seq(s).unwrap()), rest)
        }
        [t, ts, k, s, rest @ ..] if map(t, "tracks") && list(k).is_some() && seq(s).is_some() => (
            format!(
                "tracks[{}].{}[{}]",
                seq(ts).unwrap_or(0),
                list(k).unwrap(),
                seq(s).unwrap()
            ),
            rest,
        ),
        [t, ts, rest @ ..] if map(t, "tracks") && seq(ts).is_some() => {
            (format!("tracks[{}]", seq(ts).unwrap()), rest)
        }
        rest => (String::new(), rest),
    };
    let mut path = String::new();
    for s in field {
        match s {
            Segment::Seq { index } => path.push_str(&format!("[{index}]")),
            Segment::Map { key } => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(&shorten(key));
            }
            _ => path.push('?'),
        }
    }
    let mut out = format!("{source}:");
    if !place.is_empty() {
        out.push_str(&format!(" {place}:"));
    }
    if !path.is_empty() {
        out.push_str(&format!(" \"{path}\":"));
    }
    input_err!("{out} {msg}")
}

/// An error of parsing the user's string `raw` (for `"angles"`, `"fps"`, `"rotation"`): the
/// message quotes `quoted` (all of `raw` or the part that failed), which is cut here.
fn cut_quote(e: InputError, quoted: &str) -> InputError {
    match shorten(quoted) {
        std::borrow::Cow::Borrowed(_) => e,
        std::borrow::Cow::Owned(short) => InputError::new(e.message().replacen(
            &format!("\"{quoted}\""),
            &format!("\"{short}\""),
            1,
        )),
    }
}

/// Reads a JSON keyframe document.
pub fn read(text: &str, source: &str, opts: &ReadOptions) -> InputResult<Document> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.trim().is_empty() {
        return Err(input_err!(
            "{source}: expected a JSON document, found an empty input"
        ));
    }
    let mut de = serde_json::Deserializer::from_str(text);
    let wire: DocWire =
        serde_path_to_error::deserialize(&mut de).map_err(|e| located(source, e))?;
    de.end().map_err(|e| {
        input_err!(
            "{source}:{}:{}: {}",
            e.line(),
            e.column(),
            serde_message(&e)
        )
    })?;
    // The document's declarations, each settled against its flag by the one precedence rule.
    let declared_angles = match &wire.angles {
        Some(a) => Some((
            AngleUnit::parse(a).map_err(|e| cut_quote(e, a).at(format!("{source}: \"angles\"")))?,
            format!("\"{a}\""),
        )),
        None => None,
    };
    let angles = settle(
        source,
        "angles",
        declared_angles
            .as_ref()
            .map(|(u, w)| (Unit(*u), w.as_str())),
        "--input-angles",
        opts.input_angles.map(Unit),
    )?
    .map_or(opts.undeclared_angles(), |u| u.0);
    let declared_fps = match &wire.fps {
        None => None,
        Some(FpsWire::Number(n)) => Some((
            Fps::from_f64(*n).map_err(|e| e.at(format!("{source}: \"fps\"")))?,
            inbetween::error::num(*n),
        )),
        Some(FpsWire::Text(s)) => Some((
            Fps::parse(s).map_err(|e| cut_quote(e, s.trim()).at(format!("{source}: \"fps\"")))?,
            format!("\"{s}\""),
        )),
        Some(FpsWire::Other(other)) => {
            return Err(input_err!(
                "{source}: \"fps\": expected a number or a string such as \"30000/1001\", found {other}"
            ));
        }
    };
    let fps = settle(
        source,
        "fps",
        declared_fps.as_ref().map(|(f, w)| (*f, w.as_str())),
        "--key-fps",
        opts.key_fps,
    )?;
    // Where the rate of `frame` values comes from, for messages.
    let rate_from = if declared_fps.is_some() {
        "\"fps\""
    } else {
        "--key-fps"
    };
    let doc_rotation = match &wire.rotation {
        Some(r) => Some(Repr::parse(r).map_err(|e| {
            let quoted = r.strip_prefix("euler:").unwrap_or(r);
            cut_quote(cut_quote(e, r), quoted).at(format!("{source}: \"rotation\""))
        })?),
        None => None,
    };
    let rotation_written = format!("\"{}\"", wire.rotation.as_deref().unwrap_or(""));
    let rotation = settle(
        source,
        "rotation",
        doc_rotation.map(|r| (r, rotation_written.as_str())),
        "--from",
        opts.from,
    )?;
    let euler_seq = match rotation {
        Some(Repr::Euler(seq)) => Some(seq),
        _ => None,
    };
    let velocity =
        |v: Option<[f64; 3]>, field: &dyn Fn() -> String| -> InputResult<Option<DVec3>> {
            match v {
                None => Ok(None),
                Some(a) => {
                    let v = DVec3::from_array(a.map(|x| angles.to_rad(x)));
                    if !v.is_finite() {
                        return Err(input_err!(
                            "{source}: \"{}\": expected finite numbers",
                            field()
                        ));
                    }
                    Ok(Some(v))
                }
            }
        };
    let doc_start = velocity(wire.start_velocity, &|| "start_velocity".into())?;
    let doc_end = velocity(wire.end_velocity, &|| "end_velocity".into())?;
    let mut doc = Document {
        source: source.to_string(),
        fps,
        rotation: doc_rotation,
        tracks: Vec::new(),
        named_tracks: wire.tracks.is_some(),
        warnings: Vec::new(),
        skeleton: None,
    };
    let ctx = KeyContext {
        source,
        angles,
        euler_seq,
        rate: fps.map(|f| (f, rate_from)),
        opts,
    };
    let keys = match (wire.keys, wire.frames) {
        (Some(k), None) => Some((k, false)),
        (None, Some(f)) => Some((f, true)),
        (None, None) => None,
        (Some(_), Some(_)) => {
            return Err(input_err!(
                "{source}: expected \"keys\" or \"frames\", found both"
            ));
        }
    };
    match (keys, wire.tracks) {
        (Some((keys, frames)), None) => {
            let read = ctx.keys(keys, None, frames, &mut doc)?;
            doc.tracks.push(DocTrack {
                name: None,
                keys: read.keys,
                euler: read.euler,
                velocities: read.velocities,
                tcb: read.tcb,
                translations: read.translations,
                start_velocity: doc_start,
                end_velocity: doc_end,
                origin: KeyOrigin::Json {
                    track: None,
                    frames,
                },
            });
        }
        (None, Some(tracks)) => {
            // Names seen so far: a set, so that reading is linear in the number of tracks.
            let mut names = HashSet::with_capacity(tracks.len());
            doc.tracks.reserve_exact(tracks.len());
            for (ti, t) in tracks.into_iter().enumerate() {
                let start = velocity(t.start_velocity, &|| format!("tracks[{ti}].start_velocity"))?;
                let end = velocity(t.end_velocity, &|| format!("tracks[{ti}].end_velocity"))?;
                let read = ctx.keys(t.keys, Some(ti), t.frames, &mut doc)?;
                let name = t.name.unwrap_or_else(|| format!("track{ti}"));
                if !names.insert(name.clone()) {
                    return Err(input_err!(
                        "{source}: tracks[{ti}].name: track \"{}\" appears twice",
                        shorten(&name)
                    ));
                }
                doc.tracks.push(DocTrack {
                    name: Some(name),
                    keys: read.keys,
                    euler: read.euler,
                    velocities: read.velocities,
                    tcb: read.tcb,
                    translations: read.translations,
                    start_velocity: start.or(doc_start),
                    end_velocity: end.or(doc_end),
                    origin: KeyOrigin::Json {
                        track: Some(ti),
                        frames: t.frames,
                    },
                });
            }
        }
        (Some(_), Some(_)) => {
            return Err(input_err!(
                "{source}: expected \"keys\" or \"tracks\", found both"
            ));
        }
        (None, None) => {
            return Err(input_err!(
                "{source}: expected \"keys\" or \"tracks\", found neither"
            ));
        }
    }
    Ok(doc)
}

struct KeyContext<'a> {
    source: &'a str,
    angles: AngleUnit,
    euler_seq: Option<inbetween::rotation::EulerSeq>,
    /// The rate of `frame` values, declared (`"fps"`) or given (`--key-fps`), and which.
    rate: Option<(Fps, &'static str)>,
    opts: &'a ReadOptions,
}

/// An angle unit shown as the flag's value (`deg`), for [`settle`]'s message.
#[derive(Clone, Copy, PartialEq)]
struct Unit(AngleUnit);

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0.as_str())
    }
}

/// A key with both `time` and `frame` (interp's output) is at its `time`; when the rate of its
/// frame numbers is known, the two must agree within this many seconds.
pub const FRAME_TIME_AGREEMENT: f64 = 1e-9;

/// Checks that frame `frame` at `rate` is at `time` (within [`FRAME_TIME_AGREEMENT`]), for a key
/// that gives both; `rate_from` names where the rate comes from (`"fps"`, `--key-fps`).
pub fn check_frame_time(frame: f64, time: f64, rate: Fps, rate_from: &str) -> InputResult<()> {
    let at = rate.frame_to_time(frame);
    if (at - time).abs() <= FRAME_TIME_AGREEMENT {
        return Ok(());
    }
    Err(input_err!(
        "expected frame {} at {rate} fps ({rate_from}) to be at time {} s (within 1e-9 s), found {} s",
        inbetween::error::num(frame),
        inbetween::error::num(time),
        inbetween::error::num(at)
    ))
}

/// A track's keys as read, with their Euler angles and their own velocities and TCB values
/// (see [`DocTrack`]).
struct KeysRead {
    translations: Vec<Option<DVec3>>,
    keys: Vec<Key>,
    euler: Option<EulerKeys>,
    velocities: Vec<Option<DVec3>>,
    tcb: Vec<[Option<f64>; 3]>,
}

impl KeyContext<'_> {
    fn keys(
        &self,
        wires: Vec<KeyWire>,
        track: Option<usize>,
        frames: bool,
        doc: &mut Document,
    ) -> InputResult<KeysRead> {
        let mut keys = Vec::with_capacity(wires.len());
        let (mut velocities, mut tcbs, mut translations) = (Vec::new(), Vec::new(), Vec::new());
        // The keys' Euler angles as written, while every key so far is Euler in one sequence.
        let mut euler: Option<EulerKeys> = None;
        let mut all_euler = true;
        for (i, w) in wires.into_iter().enumerate() {
            let loc = Loc::Json {
                track,
                key: i,
                frames,
            };
            let here = |e: InputError| e.at(format!("{}:{loc}", self.source));
            if w.angular_velocity && !frames {
                return Err(here(input_err!(
                    "\"angular_velocity\": expected only in \"frames\" (interp's output), \
                     found in \"keys\""
                )));
            }
            let when = match (w.time, w.frame) {
                (Some(t), None) => KeyTime::Seconds(t),
                (None, Some(f)) => KeyTime::Frame(f),
                // interp's frames: the time is used, the frame number checked against it.
                (Some(t), Some(f)) => {
                    if let Some((rate, from)) = self.rate
                        && t.is_finite()
                        && f.is_finite()
                    {
                        check_frame_time(f, t, rate, from)
                            .map_err(|e| here(e.at("\"frame\" and \"time\"")))?;
                    }
                    KeyTime::Seconds(t)
                }
                (None, None) => {
                    return Err(here(input_err!(
                        "expected \"time\" or \"frame\", found neither"
                    )));
                }
            };
            let present = |r: usize| w.rotations & (1 << r) != 0;
            let seq = match self.euler_seq {
                Some(seq) => seq,
                None if present(1) => {
                    return Err(here(input_err!(
                        "\"euler\": the sequence is unknown: set the document's \"rotation\" \
                         (e.g. \"euler:ZYX\") or pass --from euler:SEQ"
                    )));
                }
                // Unused: there is no euler key.
                None => inbetween::rotation::EulerSeq::parse("XYZ").expect("valid"),
            };
            let repr = match w.rotations.count_ones() {
                1 => match w.rotations.trailing_zeros() {
                    0 => Repr::Quat,
                    1 => Repr::Euler(seq),
                    2 => Repr::Matrix,
                    3 => Repr::AxisAngle,
                    _ => Repr::RotVec,
                },
                0 => {
                    return Err(here(input_err!(
                        "expected a rotation (\"quat\", \"euler\", \"matrix\", \"axis_angle\" \
                         or \"rotvec\"), found none"
                    )));
                }
                _ => {
                    return Err(here(input_err!(
                        "expected one rotation, found {}",
                        KEY_FIELDS[FIRST_ROTATION..FIRST_ROTATION + 5]
                            .iter()
                            .enumerate()
                            .filter(|&(r, _)| present(r))
                            .map(|(_, f)| format!("\"{f}\""))
                            .collect::<Vec<_>>()
                            .join(" and ")
                    )));
                }
            };
            let mut values = w.values;
            if repr == Repr::Quat {
                let q = [values[0], values[1], values[2], values[3]];
                values[..4].copy_from_slice(&self.opts.quat_order.to_wxyz(q));
            }
            let (rot, warning) = repr
                .to_quat(&values[..repr.width()], self.angles)
                .map_err(|e| here(e.at(format!("\"{}\"", repr.json_key()))))?;
            if let Some(w) = warning {
                doc.warnings.push(format!("{}:{loc}: {w}", self.source));
            }
            if doc.rotation.is_none() {
                doc.rotation = Some(repr);
            }
            match (repr, &mut euler) {
                (Repr::Euler(seq), None) if all_euler => {
                    euler = Some((seq, Vec::with_capacity(keys.capacity())));
                }
                (Repr::Euler(seq), Some((s, _))) if *s == seq => {}
                _ => all_euler = false,
            }
            if let (true, Some((_, angles))) = (all_euler, &mut euler) {
                let r = |x: f64| self.angles.to_rad(x);
                angles.push(DVec3::new(r(values[0]), r(values[1]), r(values[2])));
            }
            keys.push(Key { when, rot });
            let velocity = w
                .velocity
                .map(|v| DVec3::from_array(v.map(|x| self.angles.to_rad(x))));
            push_shape(&mut velocities, &mut tcbs, keys.len(), velocity, w.tcb);
            push_sparse(
                &mut translations,
                keys.len(),
                w.translation.map(DVec3::from_array),
            );
        }
        Ok(KeysRead {
            translations,
            keys,
            euler: euler.filter(|_| all_euler),
            velocities,
            tcb: tcbs,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_single_and_multi_track() {
        let text = r#"{"fps": "30000/1001", "rotation": "euler:ZYX",
            "keys": [{"time": 0, "euler": [0, 0, 0]}, {"frame": 24, "quat": [1, 0, 0, 0]}]}"#;
        let doc = read(text, "k.json", &ReadOptions::default()).unwrap();
        assert_eq!(doc.fps.unwrap().to_string(), "30000/1001");
        assert_eq!(doc.tracks[0].keys[1].when, KeyTime::Frame(24.0));
        let text = r#"{"tracks": [{"name": "hip", "keys": []}, {"keys": []}]}"#;
        let doc = read(text, "k.json", &ReadOptions::default()).unwrap();
        assert_eq!(doc.tracks[1].name.as_deref(), Some("track1"));
    }

    #[test]
    fn unknown_field_names_key_index() {
        let text =
            r#"{"keys": [{"time": 0, "quat": [1,0,0,0]}, {"time": 1, "quaternion": [1,0,0,0]}]}"#;
        let err = read(text, "k.json", &ReadOptions::default()).unwrap_err();
        assert!(
            err.message()
                .starts_with("k.json: keys[1]: unknown field `quaternion`"),
            "{err}"
        );
    }

    fn err(text: &str) -> String {
        read(text, "k.json", &ReadOptions::default())
            .unwrap_err()
            .message()
            .to_string()
    }

    #[test]
    fn a_field_given_twice_is_an_error_in_every_object() {
        let key = r#"{"time": 0, "quat": [1, 0, 0, 0]}"#;
        assert_eq!(
            err(&format!(
                r#"{{"keys": [{key}, {{"time": 1, "quat": [1, 0, 0, 0], "quat": [0, 1, 0, 0]}}]}}"#
            )),
            "k.json: keys[1]: duplicate field \"quat\""
        );
        assert_eq!(
            err(&format!(
                r#"[{key}, {{"time": 1, "time": 2, "rotvec": [0, 0, 0]}}]"#
            )),
            "k.json: keys[1]: duplicate field \"time\""
        );
        assert_eq!(
            err(&format!(r#"{{"fps": 24, "keys": [{key}], "fps": 30}}"#)),
            "k.json: duplicate field \"fps\""
        );
        assert_eq!(
            err(&format!(
                r#"{{"rotation": "quat", "rotation": "euler:ZYX", "keys": [{key}]}}"#
            )),
            "k.json: duplicate field \"rotation\""
        );
        assert_eq!(
            err(&format!(
                r#"{{"tracks": [{{"keys": [{key}]}}, {{"name": "a", "keys": [{key}], "name": "b"}}]}}"#
            )),
            "k.json: tracks[1]: duplicate field \"name\""
        );
        assert_eq!(
            err(&format!(
                r#"{{"tracks": [{{"keys": [{key}, {{"frame": 1, "frame": 1, "quat": [1, 0, 0, 0]}}]}}]}}"#
            )),
            "k.json: tracks[0].keys[1]: duplicate field \"frame\""
        );
        // Two null values are still two fields.
        assert_eq!(
            err(r#"{"keys": [{"time": 0, "euler": null, "euler": null, "quat": [1, 0, 0, 0]}]}"#),
            "k.json: keys[0]: duplicate field \"euler\""
        );
    }

    #[test]
    fn messages_quote_at_most_60_characters() {
        let long = "é".repeat(1000);
        let cut = format!("{}…", "é".repeat(60));
        assert_eq!(
            err(&format!(
                r#"{{"keys": [{{"time": "{long}", "quat": [1, 0, 0, 0]}}]}}"#
            )),
            format!("k.json: keys[0]: \"time\": invalid type: string \"{cut}\", expected f64")
        );
        assert_eq!(
            err(&format!(r#"{{"keys": "{long}"}}"#)),
            format!("k.json: \"keys\": invalid type: string \"{cut}\", expected an array of keys")
        );
        assert!(
            err(&format!(r#"{{"keys": [{{"{long}": 1}}]}}"#)).starts_with(&format!(
                "k.json: keys[0]: unknown field `{cut}`, expected one of"
            ))
        );
        assert_eq!(
            err(&format!(r#"{{"angles": "{long}", "keys": []}}"#)),
            format!("k.json: \"angles\": expected \"deg\" or \"rad\", found \"{cut}\"")
        );
        assert_eq!(
            err(&format!(r#"{{"rotation": "euler:{long}", "keys": []}}"#)),
            format!(
                "k.json: \"rotation\": expected an Euler sequence of three letters from xyz \
                 (extrinsic) or XYZ (intrinsic) with no axis twice in a row, such as ZYX or zxz, \
                 found \"{cut}\""
            )
        );
        assert!(
            err(&format!(r#"{{"fps": " {long} ", "keys": []}}"#))
                .ends_with(&format!("found \"{cut}\""))
        );
        assert_eq!(
            err(&format!(
                r#"{{"fps": [{}], "keys": []}}"#,
                vec!["1"; 100].join(",")
            )),
            format!(
                "k.json: \"fps\": expected a number or a string such as \"30000/1001\", found [{}…",
                &vec!["1"; 30].join(",")[..59]
            )
        );
        let t = r#"{"time": 0, "quat": [1, 0, 0, 0]}"#;
        assert_eq!(
            err(&format!(
                r#"{{"tracks": [{{"name": "{long}", "keys": [{t}]}}, {{"name": "{long}", "keys": [{t}]}}]}}"#
            )),
            format!("k.json: tracks[1].name: track \"{cut}\" appears twice")
        );
    }

    #[test]
    fn arrays_of_the_wrong_length_and_misplaced_values_name_the_field() {
        assert_eq!(
            err(r#"{"keys": [{"time": 0, "quat": [1, 0, 0, 0, 0]}]}"#),
            "k.json: keys[0]: \"quat\": invalid length 5, expected an array of length 4"
        );
        assert_eq!(
            err(r#"{"keys": [{"time": 0, "matrix": [[1, 0, 0], [0, 1], [0, 0, 1]]}]}"#),
            "k.json: keys[0]: \"matrix[1]\": invalid length 2, expected an array of length 3"
        );
        assert_eq!(
            err(r#"{"tracks": [{"name": 5, "keys": []}]}"#),
            "k.json: tracks[0]: \"name\": invalid type: integer `5`, expected a string"
        );
        assert_eq!(
            err(r#"{"tracks": [{"name": "a"}]}"#),
            "k.json: tracks[0]: missing field `keys`"
        );
        // A key is an object (serde's derive also took an array of the fields in order).
        assert_eq!(
            err(r#"{"keys": [[0, null, [1, 0, 0, 0], null, null, null, null]]}"#),
            "k.json: keys[0]: invalid type: sequence, expected a key object"
        );
    }

    #[test]
    fn syntax_error_has_line_and_column() {
        let err = read("{\n \"keys\": [,]}", "k.json", &ReadOptions::default()).unwrap_err();
        assert!(err.message().starts_with("k.json:2:"), "{err}");
    }
}
