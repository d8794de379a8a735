//! JSON keyframe documents (docs/spec.md §3).
//!
//! ```json
//! {"fps": 30, "rotation": "euler:ZYX", "angles": "deg",
//!  "start_velocity": [0, 0, 0], "end_velocity": [0, 0, 0],
//!  "keys": [{"time": 0.0, "euler": [0, 0, 0]}, {"frame": 24, "quat": [1, 0, 0, 0]}]}
//! ```
//! or `"tracks": [{"name": "hip", "keys": [...], "start_velocity": ...}, ...]`. A bare array is
//! taken as `keys`. Unknown fields are errors. Each key has exactly one of `time`/`frame` and one
//! rotation field; `euler` keys take their sequence from `--from euler:SEQ` or the document's
//! `rotation`. A document's `angles` describes its own values; `fps` is the rate its `frame`
//! values are numbered at.

use crate::clock::Fps;
use crate::error::input_err;
use crate::error::{InputError, InputResult};
use crate::io::ReadOptions;
use crate::io::document::{DocTrack, Document, Key, KeyTime, Loc};
use crate::rotation::{AngleUnit, Repr};
use glam::DVec3;
use serde::Deserialize;
use serde_json::Value;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DocWire {
    fps: Option<Value>,
    rotation: Option<String>,
    angles: Option<String>,
    start_velocity: Option<[f64; 3]>,
    end_velocity: Option<[f64; 3]>,
    keys: Option<Vec<Value>>,
    tracks: Option<Vec<TrackWire>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TrackWire {
    name: Option<String>,
    start_velocity: Option<[f64; 3]>,
    end_velocity: Option<[f64; 3]>,
    keys: Vec<Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct KeyWire {
    time: Option<f64>,
    frame: Option<f64>,
    quat: Option<[f64; 4]>,
    euler: Option<[f64; 3]>,
    matrix: Option<[[f64; 3]; 3]>,
    axis_angle: Option<[f64; 4]>,
    rotvec: Option<[f64; 3]>,
}

/// serde_json's message without its trailing " at line L column C".
fn serde_message(e: &serde_json::Error) -> String {
    let msg = e.to_string();
    match msg.rfind(" at line ") {
        Some(i) => msg[..i].to_string(),
        None => msg,
    }
}

/// Deserialises `value`, naming the field that failed (`quat: invalid length 3, …`).
fn from_value<T: serde::de::DeserializeOwned>(value: Value) -> Result<T, String> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        let msg = serde_message(e.inner());
        // An unknown field's message names it already.
        if path == "." || path.is_empty() || msg.starts_with("unknown field") {
            msg
        } else {
            format!("\"{path}\": {msg}")
        }
    })
}

/// Reads a JSON keyframe document.
pub fn read(text: &str, source: &str, opts: &ReadOptions) -> InputResult<Document> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.trim().is_empty() {
        return Err(input_err!(
            "{source}: expected a JSON document, found an empty input"
        ));
    }
    let value: Value = serde_json::from_str(text).map_err(|e| {
        input_err!(
            "{source}:{}:{}: {}",
            e.line(),
            e.column(),
            serde_message(&e)
        )
    })?;
    let wire: DocWire = match value {
        Value::Array(keys) => DocWire {
            fps: None,
            rotation: None,
            angles: None,
            start_velocity: None,
            end_velocity: None,
            keys: Some(keys),
            tracks: None,
        },
        Value::Object(map) => {
            from_value(Value::Object(map)).map_err(|e| input_err!("{source}: {e}"))?
        }
        other => {
            let kind = match other {
                Value::Null => "null",
                Value::Bool(_) => "a boolean",
                Value::Number(_) => "a number",
                _ => "a string",
            };
            return Err(input_err!(
                "{source}: expected an object with \"keys\" or \"tracks\" (or an array of keys), \
                 found {kind}"
            ));
        }
    };
    let angles = match &wire.angles {
        Some(a) => AngleUnit::parse(a).map_err(|e| e.at(format!("{source}: \"angles\"")))?,
        None => opts.angles,
    };
    let fps = match &wire.fps {
        None => None,
        Some(Value::Number(n)) => Some(
            Fps::from_f64(n.as_f64().unwrap_or(f64::NAN))
                .map_err(|e| e.at(format!("{source}: \"fps\"")))?,
        ),
        Some(Value::String(s)) => {
            Some(Fps::parse(s).map_err(|e| e.at(format!("{source}: \"fps\"")))?)
        }
        Some(other) => {
            return Err(input_err!(
                "{source}: \"fps\": expected a number or a string such as \"30000/1001\", found {other}"
            ));
        }
    };
    let doc_rotation = match &wire.rotation {
        Some(r) => Some(Repr::parse(r).map_err(|e| e.at(format!("{source}: \"rotation\"")))?),
        None => None,
    };
    let euler_seq = match (opts.from, doc_rotation) {
        (Some(Repr::Euler(seq)), _) | (_, Some(Repr::Euler(seq))) => Some(seq),
        _ => None,
    };
    let velocity = |v: Option<[f64; 3]>, field: &str| -> InputResult<Option<DVec3>> {
        match v {
            None => Ok(None),
            Some(a) => {
                let v = DVec3::from_array(a.map(|x| angles.to_rad(x)));
                if !v.is_finite() {
                    return Err(input_err!("{source}: \"{field}\": expected finite numbers"));
                }
                Ok(Some(v))
            }
        }
    };
    let doc_start = velocity(wire.start_velocity, "start_velocity")?;
    let doc_end = velocity(wire.end_velocity, "end_velocity")?;
    let mut doc = Document {
        source: source.to_string(),
        fps,
        rotation: doc_rotation,
        tracks: Vec::new(),
        named_tracks: wire.tracks.is_some(),
        warnings: Vec::new(),
    };
    let ctx = KeyContext {
        source,
        angles,
        euler_seq,
        opts,
    };
    match (wire.keys, wire.tracks) {
        (Some(keys), None) => {
            let keys = ctx.keys(keys, None, &mut doc)?;
            doc.tracks.push(DocTrack {
                name: None,
                keys,
                start_velocity: doc_start,
                end_velocity: doc_end,
            });
        }
        (None, Some(tracks)) => {
            for (ti, t) in tracks.into_iter().enumerate() {
                let start = velocity(t.start_velocity, &format!("tracks[{ti}].start_velocity"))?;
                let end = velocity(t.end_velocity, &format!("tracks[{ti}].end_velocity"))?;
                let keys = ctx.keys(t.keys, Some(ti), &mut doc)?;
                let name = t.name.unwrap_or_else(|| format!("track{ti}"));
                if doc.tracks.iter().any(|t| t.name.as_deref() == Some(&name)) {
                    return Err(input_err!(
                        "{source}: tracks[{ti}].name: track \"{name}\" appears twice"
                    ));
                }
                doc.tracks.push(DocTrack {
                    name: Some(name),
                    keys,
                    start_velocity: start.or(doc_start),
                    end_velocity: end.or(doc_end),
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
    euler_seq: Option<crate::rotation::EulerSeq>,
    opts: &'a ReadOptions,
}

impl KeyContext<'_> {
    fn keys(
        &self,
        values: Vec<Value>,
        track: Option<usize>,
        doc: &mut Document,
    ) -> InputResult<Vec<Key>> {
        let mut keys = Vec::with_capacity(values.len());
        for (i, v) in values.into_iter().enumerate() {
            let loc = Loc::Json { track, key: i };
            let here = |e: InputError| e.at(format!("{}:{loc}", self.source));
            let w: KeyWire = from_value(v).map_err(|e| here(input_err!("{e}")))?;
            let when = match (w.time, w.frame) {
                (Some(t), None) => KeyTime::Seconds(t),
                (None, Some(f)) => KeyTime::Frame(f),
                (Some(_), Some(_)) => {
                    return Err(here(input_err!(
                        "expected \"time\" or \"frame\", found both"
                    )));
                }
                (None, None) => {
                    return Err(here(input_err!(
                        "expected \"time\" or \"frame\", found neither"
                    )));
                }
            };
            let (repr, values): (Repr, Vec<f64>) = {
                let mut found: Vec<(Repr, Vec<f64>)> = Vec::new();
                if let Some(q) = w.quat {
                    found.push((Repr::Quat, self.opts.quat_order.to_wxyz(q).to_vec()));
                }
                if let Some(e) = w.euler {
                    let seq = self.euler_seq.ok_or_else(|| {
                        here(input_err!(
                            "\"euler\": the sequence is unknown: set the document's \"rotation\" \
                             (e.g. \"euler:ZYX\") or pass --from euler:SEQ"
                        ))
                    })?;
                    found.push((Repr::Euler(seq), e.to_vec()));
                }
                if let Some(m) = w.matrix {
                    found.push((Repr::Matrix, m.concat()));
                }
                if let Some(a) = w.axis_angle {
                    found.push((Repr::AxisAngle, a.to_vec()));
                }
                if let Some(r) = w.rotvec {
                    found.push((Repr::RotVec, r.to_vec()));
                }
                match found.len() {
                    1 => found.pop().expect("one"),
                    0 => {
                        return Err(here(input_err!(
                            "expected a rotation (\"quat\", \"euler\", \"matrix\", \"axis_angle\" \
                             or \"rotvec\"), found none"
                        )));
                    }
                    _ => {
                        return Err(here(input_err!(
                            "expected one rotation, found {}",
                            found
                                .iter()
                                .map(|(r, _)| format!("\"{}\"", r.json_key()))
                                .collect::<Vec<_>>()
                                .join(" and ")
                        )));
                    }
                }
            };
            let (rot, warning) = repr
                .to_quat(&values, self.angles)
                .map_err(|e| here(e.at(format!("\"{}\"", repr.json_key()))))?;
            if let Some(w) = warning {
                doc.warnings.push(format!("{}:{loc}: {w}", self.source));
            }
            if doc.rotation.is_none() {
                doc.rotation = Some(repr);
            }
            keys.push(Key { when, rot, loc });
        }
        Ok(keys)
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

    #[test]
    fn syntax_error_has_line_and_column() {
        let err = read("{\n \"keys\": [,]}", "k.json", &ReadOptions::default()).unwrap_err();
        assert!(err.message().starts_with("k.json:2:"), "{err}");
    }
}
