//! [`write_keys`]: a document's keys in the input shape, so that `convert`'s output reads back.

use super::columns::RotationFormatter;
use super::num::NumWriter;
use super::{Style, csv_field, json_head, json_string};
use crate::clock::Fps;
use crate::io::Format;
use crate::io::document::{Document, KeyTime};
use std::io::{self, Write};

/// Writes a key's time, or its frame number (as an integer when it is whole).
fn when_value(nums: &mut NumWriter, buf: &mut Vec<u8>, x: f64, frame: bool) {
    if frame && x.fract() == 0.0 && x.abs() < 9.007_199_254_740_992e15 {
        nums.int(buf, x as i64);
    } else {
        nums.float(buf, x);
    }
}

/// Writes a document's keys (for `convert`) in the input shape of docs/spec.md §3, so that the output is
/// valid input: CSV `[track,]time|frame,<columns>`; JSON `keys` or `tracks`, with `fps` when
/// keys are frames, `rotation`, `angles` and the tracks' end velocities.
///
/// Keys are written with `frame` when every key of the document has one, otherwise with `time`
/// (frames converted at `frame_fps`).
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
    match format {
        Format::Csv => {
            if named {
                buf.extend_from_slice(b"track,");
            }
            buf.extend_from_slice(when_name.as_bytes());
            for c in style.repr.columns() {
                buf.push(b',');
                buf.extend_from_slice(c.as_bytes());
            }
            buf.push(b'\n');
            for track in &doc.tracks {
                for key in &track.keys {
                    if named {
                        buf.extend_from_slice(&csv_field(track.name.as_deref().unwrap_or("")));
                        buf.push(b',');
                    }
                    when_value(&mut nums, &mut buf, when(key.when), all_frames);
                    rot.csv(&mut buf, key.rot);
                    buf.push(b'\n');
                }
            }
        }
        Format::Json => {
            let velocities = doc
                .tracks
                .iter()
                .any(|t| t.start_velocity.is_some() || t.end_velocity.is_some());
            json_head(
                &mut buf,
                all_frames.then_some(frame_fps),
                &style,
                velocities,
            );
            let vel = |buf: &mut Vec<u8>, nums: &mut NumWriter, name: &str, v: glam::DVec3| {
                buf.extend_from_slice(format!(", \"{name}\": [").as_bytes());
                for (i, x) in v.to_array().iter().enumerate() {
                    if i > 0 {
                        buf.extend_from_slice(b", ");
                    }
                    nums.float(buf, style.angles.from_rad(*x));
                }
                buf.push(b']');
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
                    vel(&mut buf, &mut nums, "start_velocity", v);
                }
                if let Some(v) = track.end_velocity {
                    vel(&mut buf, &mut nums, "end_velocity", v);
                }
                buf.extend_from_slice(b", \"keys\": [");
                for (i, key) in track.keys.iter().enumerate() {
                    buf.extend_from_slice(if i == 0 { b"\n{\"" } else { b",\n{\"" });
                    buf.extend_from_slice(when_name.as_bytes());
                    buf.extend_from_slice(b"\": ");
                    when_value(&mut nums, &mut buf, when(key.when), all_frames);
                    buf.extend_from_slice(b", ");
                    rot.json(&mut buf, key.rot);
                    buf.push(b'}');
                }
                buf.extend_from_slice(b"\n]");
                if named {
                    buf.push(b'}');
                }
            }
            buf.extend_from_slice(if named { b"\n]}\n".as_slice() } else { b"}\n" });
        }
    }
    w.write_all(&buf)?;
    w.flush()
}
