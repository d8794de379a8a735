//! [`write_keys`]: a document's keys in the input shape, so that `convert`'s output reads back.

use super::columns::RotationFormatter;
use super::{
    Bad, EulerMode, Style, csv_field, internal_error, is_rotation, json_head, json_string,
};
use crate::Format;
use crate::document::{DocTrack, Document, KeyTime};
use crate::num::NumWriter;
use inbetween::clock::Fps;
use inbetween::rotation::Repr;
use std::io::{self, Write};

/// The Euler triples of a track's keys: their own, as given ([`EulerMode::AsGiven`] with keys
/// given in the output's sequence), or continuous along the track from the first key's own
/// triple when the keys were given as Euler angles ([`Style::unwrapper_from`]).
enum KeyEuler<'a> {
    Given(&'a [glam::DVec3]),
    Continuous(Option<inbetween::rotation::unwrap::EulerUnwrap>),
}

impl<'a> KeyEuler<'a> {
    fn of(style: &Style, track: &'a DocTrack) -> KeyEuler<'a> {
        match &track.euler {
            Some((seq, angles))
                if style.euler == EulerMode::AsGiven && style.repr == Repr::Euler(*seq) =>
            {
                KeyEuler::Given(angles)
            }
            Some((seq, angles)) => {
                KeyEuler::Continuous(style.unwrapper_from(*seq, angles[0].to_array()))
            }
            None => KeyEuler::Continuous(style.unwrapper()),
        }
    }

    /// Key `i`'s triple (radians), rotation `q`, when Euler angles are written.
    fn next(&mut self, i: usize, q: glam::DQuat) -> Option<[f64; 3]> {
        match self {
            KeyEuler::Given(a) => Some(a[i].to_array()),
            KeyEuler::Continuous(u) => u.as_mut().map(|u| u.next(q)),
        }
    }
}

/// Writes a key's time, or its frame number (as an integer when it is whole), with the
/// shortest round-trip digits whatever the precision (it is a time, not a rotation).
fn when_value(nums: &mut NumWriter, buf: &mut Vec<u8>, x: f64, frame: bool) {
    if frame && x.fract() == 0.0 && x.abs() < 9.007_199_254_740_992e15 {
        nums.int(buf, x as i64);
    } else {
        nums.shortest(buf, x);
    }
}

/// Writes a document's keys (for `convert`) in the input shape of docs/spec.md §3, so that the output is
/// valid input: CSV `[track,]time|frame,<columns>`; JSON `keys` or `tracks`, with `fps` when
/// keys are frames, `rotation`, `angles` and the tracks' end velocities.
///
/// Keys are written with `frame` when every key of the document has one, otherwise with `time`
/// (frames converted at `frame_fps`).
///
/// A NaN or infinite value, or a key rotation that is not a unit quaternion, is never written:
/// the error is `internal error: non-finite value in key 3 of track "hip" ("time" = inf)`
/// (kind `InvalidData`), and nothing is written.
pub fn write_keys<W: Write>(
    mut w: W,
    doc: &Document,
    format: Format,
    style: Style,
    frame_fps: Fps,
) -> io::Result<()> {
    let all_frames = doc
        .tracks
        .iter()
        .flat_map(|t| &t.keys)
        .all(|k| matches!(k.when, KeyTime::Frame(_)));
    let when = |t: KeyTime| match t {
        KeyTime::Frame(f) if all_frames => f,
        KeyTime::Frame(f) => frame_fps.frame_to_time(f),
        KeyTime::Seconds(s) => s,
    };
    let when_name = if all_frames { "frame" } else { "time" };
    let mut rot = RotationFormatter::new(style);
    let mut nums = NumWriter::new(style.num);
    let mut buf = Vec::new();
    let named = doc.named_tracks || doc.tracks.len() > 1;
    // Translations are finite by construction (readers refuse anything else).
    let positions = doc.tracks.iter().any(|t| !t.translations.is_empty());
    // A key's own angular velocity, in the output angle unit per second.
    let key_velocities = doc.tracks.iter().any(|t| !t.velocities.is_empty());
    let key_velocity = |track: &crate::document::DocTrack, i: usize| {
        track
            .velocities
            .get(i)
            .copied()
            .flatten()
            .map(|w| w.to_array().map(|x| style.angles.from_rad(x)))
    };
    // The last line of defence: one check per written value (see the module `write`).
    let refuse = |ti: usize, item: &str, bad: Bad| {
        internal_error(item, doc.tracks[ti].name.as_deref(), ti, bad)
    };
    let check_key = |rot: &mut RotationFormatter, ti: usize, i: usize, t: f64, ok: bool| {
        let q = doc.tracks[ti].keys[i].rot;
        if ok && t.is_finite() && is_rotation(q) {
            return Ok(());
        }
        let bad = if t.is_finite() {
            rot.fault(q).unwrap_or(Bad::NotRotation(q.length()))
        } else {
            Bad::NonFinite(when_name, t)
        };
        Err(refuse(ti, &format!("key {i}"), bad))
    };
    // BVH keys are written by `io::bvh` on its skeleton; the commands never route them here.
    debug_assert!(format != Format::Bvh, "write_keys writes CSV or JSON");
    match format {
        Format::Json => {
            let velocities = doc
                .tracks
                .iter()
                .any(|t| t.start_velocity.is_some() || t.end_velocity.is_some())
                || key_velocities;
            json_head(
                &mut buf,
                all_frames.then_some(frame_fps),
                &style,
                velocities,
            );
            if let Some(s) = doc.scheme {
                buf.extend_from_slice(format!(", \"scheme\": \"{s}\"").as_bytes());
            }
            let vel = |buf: &mut Vec<u8>,
                       nums: &mut NumWriter,
                       ti: usize,
                       name: &'static str,
                       v: glam::DVec3| {
                buf.extend_from_slice(format!(", \"{name}\": [").as_bytes());
                for (i, x) in v.to_array().iter().enumerate() {
                    if i > 0 {
                        buf.extend_from_slice(b", ");
                    }
                    let x = style.angles.from_rad(*x);
                    if !x.is_finite() {
                        let item = name.replace('_', " ");
                        return Err(refuse(ti, &format!("the {item}"), Bad::NonFinite(name, x)));
                    }
                    nums.float(buf, x);
                }
                buf.push(b']');
                Ok(())
            };
            buf.extend_from_slice(if named {
                b", \"tracks\": [\n".as_slice()
            } else {
                b"".as_slice()
            });
            for (ti, track) in doc.tracks.iter().enumerate() {
                if named {
                    if ti > 0 {
                        buf.extend_from_slice(b",\n");
                    }
                    buf.push(b'{');
                    let name = track.name.clone().unwrap_or_else(|| format!("track{ti}"));
                    buf.extend_from_slice(format!("\"name\": {}", json_string(&name)).as_bytes());
                }
                if let Some(v) = track.start_velocity {
                    vel(&mut buf, &mut nums, ti, "start_velocity", v)?;
                }
                if let Some(v) = track.end_velocity {
                    vel(&mut buf, &mut nums, ti, "end_velocity", v)?;
                }
                buf.extend_from_slice(b", \"keys\": [");
                let mut key_euler = KeyEuler::of(&style, track);
                for (i, key) in track.keys.iter().enumerate() {
                    buf.extend_from_slice(if i == 0 { b"\n{\"" } else { b",\n{\"" });
                    buf.extend_from_slice(when_name.as_bytes());
                    buf.extend_from_slice(b"\": ");
                    let t = when(key.when);
                    when_value(&mut nums, &mut buf, t, all_frames);
                    buf.extend_from_slice(b", ");
                    let euler = key_euler.next(i, key.rot);
                    let ok = rot.json(&mut buf, key.rot, euler);
                    check_key(&mut rot, ti, i, t, ok)?;
                    if let Some(w) = key_velocity(track, i) {
                        buf.extend_from_slice(b", \"velocity\": [");
                        for (j, x) in w.iter().enumerate() {
                            if j > 0 {
                                buf.extend_from_slice(b", ");
                            }
                            nums.float(&mut buf, *x);
                        }
                        buf.push(b']');
                    }
                    if let Some(p) = track.translations.get(i).copied().flatten() {
                        buf.extend_from_slice(b", \"translation\": [");
                        for (j, x) in p.to_array().iter().enumerate() {
                            if j > 0 {
                                buf.extend_from_slice(b", ");
                            }
                            nums.shortest(&mut buf, *x);
                        }
                        buf.push(b']');
                    }
                    buf.push(b'}');
                }
                buf.extend_from_slice(b"\n]");
                if named {
                    buf.push(b'}');
                }
            }
            buf.extend_from_slice(if named { b"\n]}\n".as_slice() } else { b"}\n" });
        }
        // Every other format is written here as CSV (the writers write CSV or JSON).
        _ => {
            if named {
                buf.extend_from_slice(b"track,");
            }
            buf.extend_from_slice(when_name.as_bytes());
            for c in style.repr.columns() {
                buf.push(b',');
                buf.extend_from_slice(c.as_bytes());
            }
            if key_velocities {
                buf.extend_from_slice(b",wx,wy,wz");
            }
            if positions {
                buf.extend_from_slice(b",tx,ty,tz");
            }
            buf.push(b'\n');
            for (ti, track) in doc.tracks.iter().enumerate() {
                let mut key_euler = KeyEuler::of(&style, track);
                for (i, key) in track.keys.iter().enumerate() {
                    if named {
                        buf.extend_from_slice(&csv_field(track.name.as_deref().unwrap_or("")));
                        buf.push(b',');
                    }
                    let t = when(key.when);
                    when_value(&mut nums, &mut buf, t, all_frames);
                    let euler = key_euler.next(i, key.rot);
                    let ok = rot.csv(&mut buf, key.rot, euler);
                    check_key(&mut rot, ti, i, t, ok)?;
                    if key_velocities {
                        match key_velocity(track, i) {
                            Some(w) => {
                                for x in w {
                                    buf.push(b',');
                                    nums.float(&mut buf, x);
                                }
                            }
                            None => buf.extend_from_slice(b",,,"),
                        }
                    }
                    if positions {
                        match track.translations.get(i).copied().flatten() {
                            Some(p) => {
                                for x in p.to_array() {
                                    buf.push(b',');
                                    nums.shortest(&mut buf, x);
                                }
                            }
                            None => buf.extend_from_slice(b",,,"),
                        }
                    }
                    buf.push(b'\n');
                }
            }
        }
    }
    w.write_all(&buf)?;
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::{DocTrack, Key, KeyOrigin};
    use crate::num::NumFormat;
    use glam::{DQuat, DVec3};
    use inbetween::rotation::{AngleUnit, QuatOrder, Repr};

    fn doc(second: (f64, DQuat), start_velocity: Option<DVec3>) -> Document {
        let key = |t: f64, rot: DQuat| Key {
            when: KeyTime::Seconds(t),
            rot,
        };
        Document {
            rotation: Some(Repr::Quat),
            tracks: vec![DocTrack {
                name: Some("hip".into()),
                keys: vec![key(0.0, DQuat::IDENTITY), key(second.0, second.1)],
                start_velocity,
                end_velocity: None,
                origin: KeyOrigin::Lines(vec![2, 3]),
                euler: None,
                velocities: Vec::new(),
                tcb: Vec::new(),
                translations: Vec::new(),
            }],
            named_tracks: true,
            ..Document::new("k.csv")
        }
    }

    fn write(doc: &Document, format: Format, num: NumFormat) -> (Vec<u8>, io::Result<()>) {
        let style = Style {
            repr: Repr::Quat,
            angles: AngleUnit::Deg,
            quat_order: QuatOrder::Wxyz,
            num,
            euler: Default::default(),
        };
        let mut out = Vec::new();
        let r = write_keys(&mut out, doc, format, style, Fps::DEFAULT);
        (out, r)
    }

    #[test]
    fn non_finite_keys_are_refused_not_written() {
        let cases = [
            (
                doc((f64::INFINITY, DQuat::IDENTITY), None),
                "internal error: non-finite value in key 1 of track \"hip\" (\"time\" = inf)",
            ),
            (
                doc((1.0, DQuat::from_xyzw(0.0, f64::NAN, 0.0, 1.0)), None),
                "internal error: non-finite value in key 1 of track \"hip\" (\"y\" = NaN)",
            ),
            (
                doc((1.0, DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0)), None),
                "internal error: zero or non-unit quaternion in key 1 of track \"hip\" (norm 0)",
            ),
        ];
        for format in [Format::Csv, Format::Json] {
            for (doc, want) in &cases {
                let (out, r) = write(doc, format, NumFormat::Shortest);
                let err = r.unwrap_err();
                assert_eq!(err.kind(), io::ErrorKind::InvalidData);
                assert_eq!(err.to_string(), *want, "{format:?}");
                assert!(out.is_empty());
            }
        }
        // 1e307 rad/s is finite, but infinite in deg/s.
        let doc = doc((1.0, DQuat::IDENTITY), Some(DVec3::new(1e307, 0.0, 0.0)));
        let (out, r) = write(&doc, Format::Json, NumFormat::Shortest);
        assert_eq!(
            r.unwrap_err().to_string(),
            "internal error: non-finite value in the start velocity of track \"hip\" \
             (\"start_velocity\" = inf)"
        );
        assert!(out.is_empty());
    }

    #[test]
    fn key_times_are_shortest_whatever_the_precision() {
        let doc = doc((1.0 / 3.0, DQuat::from_xyzw(0.0, 0.0, -1e-9, 1.0)), None);
        let (out, r) = write(&doc, Format::Csv, NumFormat::Fixed(2));
        r.unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "track,time,w,x,y,z\nhip,0.0,1.00,0.00,0.00,0.00\nhip,0.3333333333333333,1.00,0.00,0.00,0.00\n"
        );
    }
}
