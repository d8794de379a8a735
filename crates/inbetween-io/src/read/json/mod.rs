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
//! ([`settle`]). `"scheme"` names the scheme the keys were made for (`reduce` writes it), which
//! plays them unless the command line names another.

use crate::document::{DocTrack, Document, KeyOrigin, shorten};
use crate::{ReadOptions, settle};
use glam::DVec3;
use inbetween::clock::Fps;
use inbetween::error::{InputError, InputResult, Setting};
use inbetween::rotation::{AngleUnit, Repr};
use keys::{KeyContext, Unit};
use serde_path_to_error::Segment;
use std::collections::HashSet;
use wire::{DocWire, FpsWire};

mod keys;
mod wire;

pub(crate) use keys::{RateFrom, check_frame_time};

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
        Setting::InputAngles,
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
        Setting::KeyRate,
        opts.key_fps,
    )?;
    // Where the rate of `frame` values comes from, for messages.
    let rate_from = if declared_fps.is_some() {
        RateFrom::Declared
    } else {
        RateFrom::Given
    };
    let doc_rotation = match &wire.rotation {
        Some(r) => Some(Repr::parse(r).map_err(|e| {
            let quoted = r.strip_prefix("euler:").unwrap_or(r);
            cut_quote(cut_quote(e, r), quoted).at(format!("{source}: \"rotation\""))
        })?),
        None => None,
    };
    // The scheme the keys were made for (reduce writes it): how they play unless --scheme says.
    let scheme = match &wire.scheme {
        Some(s) => Some(
            s.parse::<inbetween::Scheme>()
                .map_err(|e| cut_quote(e, s).at(format!("{source}: \"scheme\"")))?,
        ),
        None => None,
    };
    let rotation_written = format!("\"{}\"", wire.rotation.as_deref().unwrap_or(""));
    let rotation = settle(
        source,
        "rotation",
        doc_rotation.map(|r| (r, rotation_written.as_str())),
        Setting::Rotation,
        opts.from,
    )?;
    let euler_seq = match rotation {
        Some(Repr::Euler(seq)) => Some(seq),
        _ => None,
    };
    let rot6d = rotation.filter(|r| matches!(r, Repr::Rot6dRows | Repr::Rot6dColumns));
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
        fps,
        rotation: doc_rotation,
        scheme,
        named_tracks: wire.tracks.is_some(),
        ..Document::new(source.to_string())
    };
    let ctx = KeyContext {
        source,
        angles,
        euler_seq,
        rot6d,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::KeyTime;

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

    /// `"scheme"` is the scheme the keys were made for; an unknown one is refused by name.
    #[test]
    fn a_recorded_scheme_is_read_and_checked() {
        let keys = r#""keys": [{"time": 0, "quat": [1, 0, 0, 0]}]"#;
        let doc = read(
            &format!(r#"{{"scheme": "nlerp", {keys}}}"#),
            "k.json",
            &ReadOptions::default(),
        )
        .unwrap();
        assert_eq!(doc.scheme, Some(inbetween::Scheme::Nlerp));
        let doc = read(&format!("{{{keys}}}"), "k.json", &ReadOptions::default()).unwrap();
        assert_eq!(doc.scheme, None);
        assert_eq!(
            err(&format!(r#"{{"scheme": "linear", {keys}}}"#)),
            "k.json: \"scheme\": expected a scheme from hermite, squad, bezier, slerp, nlerp, \
             minaccel, found \"linear\""
        );
        assert!(err(&format!(r#"{{"scheme": 3, {keys}}}"#)).contains("scheme"));
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
