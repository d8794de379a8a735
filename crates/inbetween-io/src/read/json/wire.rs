//! The document's wire types, read straight from the JSON text by hand-written visitors (no
//! `serde_json::Value` tree): syntax, types, field names and array lengths are checked here,
//! nothing is interpreted.
//!
//! Every object rejects unknown and repeated fields, as serde's derive with `deny_unknown_fields`
//! would; the visitors are hand-written because a message quotes at most `MAX_QUOTED_CHARS`
//! characters of the user's text, where the derive (and `Vec<T>`'s own impl) quote a wrong-typed
//! string or an unknown field name whole. Visitors ask for `deserialize_any`, so that serde_json
//! hands a wrong-typed string to them rather than quoting it in its own message.

use crate::document::shorten;
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, de::Error as _};
use serde_json::Value;
use std::fmt;

/// Field names of a document, a track and a key, in the order messages list them.
const DOC_FIELDS: &[&str] = &[
    "fps",
    "rotation",
    "angles",
    "scheme",
    "start_velocity",
    "end_velocity",
    "keys",
    "frames",
    "tracks",
];
const TRACK_FIELDS: &[&str] = &["name", "start_velocity", "end_velocity", "keys", "frames"];
pub(super) const KEY_FIELDS: &[&str] = &[
    "time",
    "frame",
    "quat",
    "euler",
    "matrix",
    "axis_angle",
    "rotvec",
    "rot6d",
    "angular_velocity",
    "velocity",
    "tension",
    "continuity",
    "bias",
    "translation",
];
/// Index in [`KEY_FIELDS`] of the first rotation field.
pub(super) const FIRST_ROTATION: usize = 2;

/// The JSON document as read: syntax, types, field names, array lengths checked; nothing
/// interpreted yet (key values need the document's `angles` and `rotation`, which may come last).
#[derive(Default)]
pub(super) struct DocWire {
    pub(super) fps: Option<FpsWire>,
    pub(super) rotation: Option<String>,
    pub(super) angles: Option<String>,
    pub(super) scheme: Option<String>,
    pub(super) start_velocity: Option<[f64; 3]>,
    pub(super) end_velocity: Option<[f64; 3]>,
    pub(super) keys: Option<Vec<KeyWire>>,
    pub(super) frames: Option<Vec<KeyWire>>,
    pub(super) tracks: Option<Vec<TrackWire>>,
}

pub(super) struct TrackWire {
    pub(super) name: Option<String>,
    pub(super) start_velocity: Option<[f64; 3]>,
    pub(super) end_velocity: Option<[f64; 3]>,
    pub(super) keys: Vec<KeyWire>,
    /// The keys were given as `frames` (interp's output).
    pub(super) frames: bool,
}

/// A key as read. `null` fields count as absent.
#[derive(Default)]
pub(super) struct KeyWire {
    pub(super) time: Option<f64>,
    pub(super) frame: Option<f64>,
    /// The rotation fields present, bit `i` for `KEY_FIELDS[FIRST_ROTATION + i]`.
    pub(super) rotations: u8,
    /// The values of the last rotation field read (the only one, when the key is valid).
    pub(super) values: [f64; 9],
    /// An `angular_velocity` was given (interp's frames).
    pub(super) angular_velocity: bool,
    /// The key's own angular velocity (`velocity`, or `angular_velocity` in frames), in the
    /// document's angle unit per second.
    pub(super) velocity: Option<[f64; 3]>,
    /// The key's own tension, continuity and bias.
    pub(super) tcb: [Option<f64>; 3],
    /// The key's position.
    pub(super) translation: Option<[f64; 3]>,
}

/// `fps` as read: a number, a string, or something else (shown in the message, cut).
pub(super) enum FpsWire {
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
                "rot6d" => rotation(
                    map.next_value::<Option<Fixed<Num, 6>>>()?
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
                "scheme" => doc.scheme = map.next_value::<Option<Text>>()?.map(|t| t.0),
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
