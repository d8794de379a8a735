//! CSV keyframes (docs/spec.md §3): a header row, one key per row, columns found by name in any order.
//!
//! ```text
//! track,time,w,x,y,z          track optional; time (seconds) or frame; rotation columns of one
//! hip,0.0,1,0,0,0             representation (docs/spec.md §2). Rows of several tracks may interleave;
//! hip,0.5,0.7071,0,0.7071,0   each track keeps its row order.
//! ```
//! Accepted as a user would expect: a UTF-8 BOM, CRLF line ends, blank lines, spaces around
//! fields and header names, quoted fields, comment lines starting with `#`, columns separated by
//! runs of spaces (a header without `,`, `;` or tab). Errors: an unknown or duplicated column, a missing
//! rotation column, a row with a different number of fields than the header, a field that is
//! not a finite number.

use crate::ReadOptions;
use crate::document::{DocTrack, Document, Key, KeyOrigin, KeyTime, shorten};
use crate::read::json::{RateFrom, check_frame_time};
use glam::DVec3;
use inbetween::error::{InputError, InputResult, Setting};
use inbetween::message;
use inbetween::rotation::{MAX_WIDTH, Repr};
use std::collections::{HashMap, HashSet};

/// A key's own angular velocity (the columns `interp --velocity` writes): all three or none;
/// a key without one leaves its cells empty.
const VELOCITY_COLUMNS: [&str; 3] = ["wx", "wy", "wz"];

/// A key's position (BVH and glTF translations): all three columns or none; a track without
/// positions leaves its cells empty.
const TRANSLATION_COLUMNS: [&str; 3] = ["tx", "ty", "tz"];

/// A key's own Kochanek–Bartels values: any of them; an empty cell takes the flag's value.
const TCB_COLUMNS: [&str; 3] = ["tension", "continuity", "bias"];

/// Column sets that name a representation, with their aliases.
const QUAT_ALIASES: [&str; 4] = ["qw", "qx", "qy", "qz"];

fn rotation_candidates() -> Vec<(Repr, Vec<&'static str>)> {
    let seq = inbetween::rotation::EulerSeq::parse("XYZ").expect("valid");
    vec![
        (Repr::Quat, Repr::Quat.columns().to_vec()),
        (Repr::Quat, QUAT_ALIASES.to_vec()),
        (Repr::Euler(seq), Repr::Euler(seq).columns().to_vec()),
        (Repr::Matrix, Repr::Matrix.columns().to_vec()),
        (Repr::AxisAngle, Repr::AxisAngle.columns().to_vec()),
        (Repr::RotVec, Repr::RotVec.columns().to_vec()),
        (Repr::Rot6dRows, Repr::Rot6dRows.columns().to_vec()),
        (Repr::Rot6dColumns, Repr::Rot6dColumns.columns().to_vec()),
    ]
}

/// Reads a CSV keyframe document.
pub fn read(text: &str, source: &str, opts: &ReadOptions) -> InputResult<Document> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.trim().is_empty() {
        return Err(input_err!(
            "{source}: expected a CSV header row, found an empty input"
        ));
    }
    let delimiter = opts.delimiter.unwrap_or_else(|| detect_delimiter(text));
    // Comment lines become blank and runs of blanks one tab, line by line (line numbers kept),
    // for the csv crate (whose own comments lose count of lines).
    let blanks = delimiter == b' ';
    let cleaned = (blanks || text.contains('#')).then(|| clean(text, blanks));
    let (text, delimiter) = match &cleaned {
        Some(t) => (t.as_str(), if blanks { b'\t' } else { delimiter }),
        None => (text, delimiter),
    };
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .from_reader(text.as_bytes());
    let mut records = rdr.records();
    let mut record = csv::StringRecord::new();
    let header = match records.next() {
        Some(Ok(h)) => h,
        Some(Err(e)) => return Err(csv_error(source, &e)),
        None => {
            return Err(input_err!(
                "{source}: expected a CSV header row, found none"
            ));
        }
    };
    // Lines counted from the records' byte offsets: the csv crate's own count skips blank lines.
    let mut lines = LineCounter::default();
    let header_line = lines.at(text, header.position());
    // Fields are trimmed here rather than by the csv crate, whose trimming copies every record.
    // Header names match case-insensitively (ASCII): `Time, W, X, Y, Z` as a spreadsheet writes
    // them. Messages quote them as written.
    let written: Vec<&str> = header.iter().map(str::trim).collect();
    let lower: Vec<String> = written.iter().map(|n| n.to_ascii_lowercase()).collect();
    let names: Vec<&str> = lower.iter().map(String::as_str).collect();
    let hloc = format!("{source}:{header_line}");
    let mut seen = HashSet::with_capacity(names.len());
    for (n, w) in names.iter().zip(&written) {
        if !seen.insert(*n) {
            return Err(input_err!(
                "{hloc}: column \"{}\" appears twice",
                shorten(w)
            ));
        }
    }
    let col = |n: &str| names.iter().position(|c| *c == n);
    let (repr, rot_cols) = choose_rotation(&written, &seen, opts, &hloc)?;
    let track_col = col("track");
    // Per-key angular velocities: all three columns or none.
    let velocity = VELOCITY_COLUMNS.iter().all(|c| seen.contains(c));
    let translation = TRANSLATION_COLUMNS.iter().all(|c| seen.contains(c));
    for (n, w) in names.iter().zip(&written) {
        let known = *n == "track"
            || *n == "time"
            || *n == "frame"
            || rot_cols.contains(n)
            || (velocity && VELOCITY_COLUMNS.contains(n))
            || (translation && TRANSLATION_COLUMNS.contains(n))
            || TCB_COLUMNS.contains(n);
        if !known {
            let mut expected = vec!["track", "time", "frame"];
            expected.extend(&rot_cols);
            if TRANSLATION_COLUMNS.contains(n) {
                return Err(input_err!(
                    "{hloc}: column \"{}\": a key's translation needs all three columns tx, ty, tz",
                    shorten(w)
                ));
            }
            if VELOCITY_COLUMNS.contains(n) {
                return Err(input_err!(
                    "{hloc}: column \"{}\": a key's angular velocity needs all three columns \
                     wx, wy, wz",
                    shorten(w)
                ));
            }
            let mut all = expected.clone();
            all.extend(VELOCITY_COLUMNS);
            all.extend(TCB_COLUMNS);
            all.extend(TRANSLATION_COLUMNS);
            return Err(input_err!(
                "{hloc}: unknown column \"{}\": expected {} (optional: {}, {}, {}){}",
                shorten(w),
                expected.join(", "),
                VELOCITY_COLUMNS.join(", "),
                TCB_COLUMNS.join(", "),
                TRANSLATION_COLUMNS.join(", "),
                suggestion(n, &all)
            ));
        }
    }
    let time_col = col("time");
    let frame_col = col("frame");
    // With both (interp's output), the time is used and the frame number is checked against it
    // when `--key-fps` gives its rate.
    let (when_col, is_frame, frame_check) = match (time_col, frame_col) {
        (Some(t), None) => (t, false, None),
        (None, Some(f)) => (f, true, None),
        (Some(t), Some(f)) => (t, false, Some(f)),
        (None, None) => {
            return Err(input_err!(
                "{hloc}: expected a \"time\" or a \"frame\" column, found neither (columns: {})",
                joined(&written)
            ));
        }
    };
    let rot_idx: Vec<usize> = rot_cols.iter().filter_map(|n| col(n)).collect();
    let vel_idx: Option<Vec<usize>> =
        velocity.then(|| VELOCITY_COLUMNS.iter().filter_map(|n| col(n)).collect());
    let tcb_idx: [Option<usize>; 3] = TCB_COLUMNS.map(col);
    let pos_idx: Option<Vec<usize>> =
        translation.then(|| TRANSLATION_COLUMNS.iter().filter_map(|n| col(n)).collect());

    let mut doc = Document {
        // CSV declares no rate: `--key-fps` gives it.
        fps: opts.key_fps,
        rotation: Some(repr),
        named_tracks: track_col.is_some(),
        ..Document::new(source)
    };
    let mut values = [0.0; MAX_WIDTH];
    let mut track_index: HashMap<String, usize> = HashMap::new();
    let (mut last, mut last_name) = (None, String::new());
    loop {
        match rdr.read_record(&mut record) {
            Ok(false) => break,
            Ok(true) => {}
            Err(e) => return Err(csv_error(source, &e)),
        }
        let line = lines.at(text, record.position());
        // Built only for a message: formatting it for every row would cost as much as the row.
        let loc = || format!("{source}:{line}");
        if record.len() != names.len() {
            return Err(input_err!(
                "{}: expected {} fields as in the header, found {}",
                loc(),
                names.len(),
                record.len()
            ));
        }
        let number = |i: usize| -> InputResult<f64> {
            let raw = record[i].trim();
            match raw.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                Ok(_) => Err(input_err!(
                    "{}: column \"{}\": expected a finite number, found \"{}\"",
                    loc(),
                    written[i],
                    shorten(raw)
                )),
                Err(_) => Err(input_err!(
                    "{}: column \"{}\": expected a number, found \"{}\"",
                    loc(),
                    written[i],
                    shorten(raw)
                )),
            }
        };
        let t = number(when_col)?;
        if let Some(f) = frame_check {
            let frame = number(f)?;
            if let Some(rate) = opts.key_fps {
                check_frame_time(frame, t, rate, RateFrom::Given)
                    .map_err(|e| e.at(format!("{}: columns \"frame\" and \"time\"", loc())))?;
            }
        }
        for (slot, &i) in values.iter_mut().zip(&rot_idx) {
            *slot = number(i)?;
        }
        let (rot, warning) = repr
            .to_quat(&values[..repr.width()], opts.undeclared_angles())
            .map_err(|e| e.at(format!("{}: columns {}", loc(), rot_cols.join(","))))?;
        // Optional cells: empty is "none".
        let optional = |i: usize| -> InputResult<Option<f64>> {
            if record[i].trim().is_empty() {
                Ok(None)
            } else {
                number(i).map(Some)
            }
        };
        // Three optional cells that are filled together or not at all.
        let triple = |idx: &Option<Vec<usize>>, names: &str| -> InputResult<Option<DVec3>> {
            let Some(idx) = idx else { return Ok(None) };
            match [optional(idx[0])?, optional(idx[1])?, optional(idx[2])?] {
                [Some(x), Some(y), Some(z)] => Ok(Some(DVec3::new(x, y, z))),
                [None, None, None] => Ok(None),
                _ => Err(input_err!(
                    "{}: columns {names}: expected three numbers or three empty cells",
                    loc()
                )),
            }
        };
        let unit = opts.undeclared_angles();
        let key_velocity = triple(&vel_idx, "wx,wy,wz")?
            .map(|v| DVec3::from_array(v.to_array().map(|x| unit.to_rad(x))));
        let key_translation = triple(&pos_idx, "tx,ty,tz")?;
        let mut key_tcb = [None; 3];
        for (slot, i) in key_tcb.iter_mut().zip(tcb_idx) {
            if let Some(i) = i {
                *slot = optional(i)?;
            }
        }
        if let Some(w) = warning {
            doc.warnings.push(format!("{}: {w}", loc()));
        }
        // The track of this row: the previous row's, else found by name in a map (tracks in
        // order of first appearance), so that reading is linear in the number of tracks. Each
        // name is kept once, as a key of the map, and handed to its track at the end.
        let index = match track_col.map(|c| record[c].trim()) {
            None => 0,
            Some(name) => match last {
                Some(i) if last_name == name => i,
                _ => {
                    let i = match track_index.get(name) {
                        Some(&i) => i,
                        None => {
                            track_index.insert(name.to_string(), doc.tracks.len());
                            doc.tracks.len()
                        }
                    };
                    last = Some(i);
                    last_name.clear();
                    last_name.push_str(name);
                    i
                }
            },
        };
        if index == doc.tracks.len() {
            doc.tracks.push(DocTrack {
                name: None,
                keys: Vec::new(),
                start_velocity: None,
                end_velocity: None,
                origin: KeyOrigin::Lines(Vec::new()),
                euler: match repr {
                    Repr::Euler(seq) => Some((seq, Vec::new())),
                    _ => None,
                },
                velocities: Vec::new(),
                tcb: Vec::new(),
                translations: Vec::new(),
            });
        }
        let track = &mut doc.tracks[index];
        track.keys.push(Key {
            when: if is_frame {
                KeyTime::Frame(t)
            } else {
                KeyTime::Seconds(t)
            },
            rot,
        });
        if let KeyOrigin::Lines(lines) = &mut track.origin {
            lines.push(line);
        }
        track.push_shape(key_velocity, key_tcb);
        track.push_translation(key_translation);
        if let Some((_, angles)) = &mut track.euler {
            let unit = opts.undeclared_angles();
            angles.push(DVec3::new(
                unit.to_rad(values[0]),
                unit.to_rad(values[1]),
                unit.to_rad(values[2]),
            ));
        }
    }
    for (name, i) in track_index {
        doc.tracks[i].name = Some(name);
    }
    if doc.tracks.is_empty() {
        return Err(input_err!(
            "{source}: expected at least 1 key, found only a header"
        ));
    }
    Ok(doc)
}

/// The delimiter of a CSV document without `--delimiter`: of `,`, `;` and tab, the one that
/// occurs most often outside double quotes in the header line (the first line that is neither
/// blank nor a `#` comment); ties go to the first of `,`, `;`, tab; none at all is `b' '` (runs
/// of blanks) when the line has a space, else `,`.
pub(crate) fn detect_delimiter(text: &str) -> u8 {
    let header = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))
        .unwrap_or_default();
    let mut counts = [0usize; 3];
    let mut quoted = false;
    for b in header.bytes() {
        match b {
            b'"' => quoted = !quoted,
            b',' if !quoted => counts[0] += 1,
            b';' if !quoted => counts[1] += 1,
            b'\t' if !quoted => counts[2] += 1,
            _ => {}
        }
    }
    if counts == [0; 3] && header.contains(' ') {
        return b' ';
    }
    let best = (0..3).fold(0, |best, i| if counts[i] > counts[best] { i } else { best });
    [b',', b';', b'\t'][best]
}

/// `text` with its comment lines (first non-blank character `#`) made empty and, with
/// `blanks`, each line trimmed and its runs of spaces and tabs made one tab (lines and their
/// numbers kept).
fn clean(text: &str, blanks: bool) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let comment = line.trim_start().starts_with('#');
        if comment {
            // Nothing of the line but its end.
        } else if blanks {
            let mut words = line.split_ascii_whitespace();
            if let Some(w) = words.next() {
                out.push_str(w);
                for w in words {
                    out.push('\t');
                    out.push_str(w);
                }
            }
        } else {
            out.push_str(line.strip_suffix('\n').unwrap_or(line));
        }
        if line.ends_with('\n') {
            out.push('\n');
        }
    }
    out
}

/// The line of a byte offset, counted forward from the last offset asked (records come in
/// order, so reading stays linear).
#[derive(Default)]
struct LineCounter {
    byte: usize,
    line: u64,
}

impl LineCounter {
    /// The 1-based line where a record starts: the csv crate's position is where it started
    /// reading, before the empty lines it skipped.
    fn at(&mut self, text: &str, pos: Option<&csv::Position>) -> u64 {
        let mut byte = pos.map_or(0, |p| p.byte() as usize).min(text.len());
        while matches!(text.as_bytes().get(byte), Some(b'\r' | b'\n')) {
            byte += 1;
        }
        if byte < self.byte {
            *self = LineCounter::default();
        }
        let newlines = text.as_bytes()[self.byte..byte]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.line += newlines as u64;
        self.byte = byte;
        self.line + 1
    }
}

/// Levenshtein distance between two short names (in characters).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let here = (prev + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            prev = row[j + 1];
            row[j + 1] = here;
        }
    }
    row[b.len()]
}

/// `; did you mean "time"?` for the expected name nearest `name` (lowercased) by edit distance,
/// when that distance is at most 2 (the first such name on a tie); else nothing.
fn suggestion(name: &str, expected: &[&str]) -> String {
    // A name far longer than any column cannot be within 2 edits: skip the work.
    if name.len() > 64 {
        return String::new();
    }
    expected
        .iter()
        .map(|e| (edit_distance(name, e), e))
        .filter(|(d, _)| *d <= 2)
        .min_by_key(|(d, _)| *d)
        .map_or(String::new(), |(_, e)| format!("; did you mean \"{e}\"?"))
}

/// The header's names joined by commas for a message, cut like a quoted value ([`shorten`]),
/// without building the whole list.
fn joined(names: &[&str]) -> String {
    let mut list = String::new();
    for (i, n) in names.iter().enumerate() {
        if i > 0 {
            list.push(',');
        }
        list.push_str(&shorten(n));
        if list.chars().count() > crate::document::MAX_QUOTED_CHARS {
            break;
        }
    }
    shorten(&list).into_owned()
}

fn csv_error(source: &str, e: &csv::Error) -> inbetween::error::InputError {
    match e.position() {
        Some(p) => input_err!("{source}:{}: {}", p.line(), e),
        None => input_err!("{source}: {e}"),
    }
}

/// The representation named by the header (or forced by `--from`), and its column names as they
/// appear in the header.
fn choose_rotation(
    names: &[&str],
    set: &HashSet<&str>,
    opts: &ReadOptions,
    hloc: &str,
) -> InputResult<(Repr, Vec<&'static str>)> {
    let has = |c: &&str| set.contains(c);
    let candidates = rotation_candidates();
    if let Some(from) = opts.from {
        let sets: Vec<_> = candidates
            .iter()
            .filter(|(r, _)| std::mem::discriminant(r) == std::mem::discriminant(&from))
            .collect();
        if let Some((_, cols)) = sets.iter().find(|(_, cols)| cols.iter().all(has)) {
            return Ok((from, cols.clone()));
        }
        let cols = &sets[0].1;
        let missing: Vec<_> = cols.iter().filter(|c| !has(c)).collect();
        return Err(InputError::new(message![
            format!("{hloc}: "),
            Setting::Rotation,
            format!(
                " {from} needs columns {}, missing \"{}\"",
                cols.join(","),
                missing[0]
            )
        ]));
    }
    let full: Vec<_> = candidates
        .iter()
        .filter(|(_, cols)| cols.iter().all(has))
        .collect();
    match full.as_slice() {
        [(Repr::Euler(_), _)] => Err(InputError::new(message![
            format!(
                "{hloc}: columns e1,e2,e3 hold Euler angles but the sequence is unknown: pass "
            ),
            Setting::Rotation,
            " euler:SEQ (e.g. ",
            Setting::Rotation,
            " euler:ZYX)"
        ])),
        [(repr, cols)] => Ok((*repr, cols.clone())),
        [] => {
            // Name the first missing column of the best partial match.
            let best = candidates
                .iter()
                .max_by_key(|(_, cols)| cols.iter().filter(|c| has(c)).count())
                .expect("non-empty");
            if best.1.iter().any(has) {
                let missing = best.1.iter().find(|c| !has(c)).expect("partial");
                Err(input_err!(
                    "{hloc}: missing column \"{missing}\" (rotation columns {})",
                    best.1.join(",")
                ))
            } else {
                Err(input_err!(
                    "{hloc}: expected rotation columns (w,x,y,z or e1,e2,e3 or m00..m22 or \
                     ax,ay,az,angle or rx,ry,rz or r0x..r1z or c0x..c1z), found {}",
                    joined(names)
                ))
            }
        }
        several => Err(InputError::new(message![
            format!(
                "{hloc}: found columns of several rotations ({}); keep one or pass ",
                several
                    .iter()
                    .map(|(r, _)| r.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Setting::Rotation
        ])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inbetween::rotation::AngleUnit;

    fn opts() -> ReadOptions {
        ReadOptions::default()
    }

    #[test]
    fn reads_two_tracks_interleaved() {
        let text = "track,time,w,x,y,z\na,0,1,0,0,0\nb,0,1,0,0,0\na,1,0,1,0,0\nb,2,0,0,1,0\n";
        let doc = read(text, "k.csv", &opts()).unwrap();
        assert_eq!(doc.tracks.len(), 2);
        assert_eq!(doc.tracks[0].name.as_deref(), Some("a"));
        assert_eq!(doc.tracks[1].keys[1].when, KeyTime::Seconds(2.0));
        assert_eq!(doc.tracks[1].loc(1), crate::document::Loc::Line(5));
    }

    #[test]
    fn bom_crlf_spaces_and_aliases() {
        let text = "\u{feff} time , qw,qx ,qy,qz\r\n0, 1,0,0,0\r\n\r\n1,0,0,0,1\r\n";
        let doc = read(text, "k.csv", &opts()).unwrap();
        assert_eq!(doc.tracks[0].keys.len(), 2);
        assert!(!doc.named_tracks);
        // Lines are counted across blank lines and CRLF ends.
        assert_eq!(doc.tracks[0].loc(1), crate::document::Loc::Line(4));
    }

    #[test]
    fn euler_needs_a_sequence() {
        let text = "time,e1,e2,e3\n0,0,0,0\n1,90,0,0\n";
        let err = read(text, "k.csv", &opts()).unwrap_err();
        assert!(
            err.message()
                .contains("pass rotation representation euler:SEQ"),
            "{err}"
        );
        assert!(err.parts().settings().all(|s| s == Setting::Rotation));
        let o = ReadOptions {
            from: Some(Repr::parse("euler:ZYX").unwrap()),
            angles: AngleUnit::Deg,
            ..opts()
        };
        let doc = read(text, "k.csv", &o).unwrap();
        let q = doc.tracks[0].keys[1].rot;
        assert!((q.z - (std::f64::consts::FRAC_PI_4).sin()).abs() < 1e-15);
    }

    #[test]
    fn messages_quote_at_most_60_characters() {
        let long = "ж".repeat(500);
        let cut = format!("{}…", "ж".repeat(60));
        let err = |text: &str| {
            read(text, "k.csv", &opts())
                .unwrap_err()
                .message()
                .to_string()
        };
        assert_eq!(
            err(&format!("time,w,x,y,z\n0,{long},0,0,0\n")),
            format!("k.csv:2: column \"w\": expected a number, found \"{cut}\"")
        );
        assert_eq!(
            err(&format!("time,w,x,y,z,{long}\n")),
            format!(
                "k.csv:1: unknown column \"{cut}\": expected track, time, frame, w, x, y, z (optional: wx, wy, wz, tension, continuity, bias, tx, ty, tz)"
            )
        );
        assert_eq!(
            err(&format!("time,w,x,y,z,{long},{long}\n")),
            format!("k.csv:1: column \"{cut}\" appears twice")
        );
        // An unknown column is reported before a missing time, so the list of columns holds
        // known names only.
        assert_eq!(
            err(&format!("w,x,y,z,{long}\n")),
            format!(
                "k.csv:1: unknown column \"{cut}\": expected track, time, frame, w, x, y, z (optional: wx, wy, wz, tension, continuity, bias, tx, ty, tz)"
            )
        );
        assert_eq!(
            err("W,X,Y,Z,Track\n"),
            "k.csv:1: expected a \"time\" or a \"frame\" column, found neither (columns: \
             W,X,Y,Z,Track)"
        );
    }

    #[test]
    fn the_delimiter_is_the_most_frequent_of_three_in_the_header() {
        assert_eq!(detect_delimiter("time,w,x,y,z\n"), b',');
        assert_eq!(detect_delimiter("\n\ntime;w;x;y;z\n0,5;1;0;0;0\n"), b';');
        assert_eq!(detect_delimiter("time\tw\tx\ty\tz\n"), b'\t');
        // Inside quotes a delimiter does not count; ties and none go to the comma.
        assert_eq!(detect_delimiter("\"a,b,c\";time;w\n"), b';');
        assert_eq!(detect_delimiter("a;b,c\n"), b',');
        assert_eq!(detect_delimiter("a\tb;c\n"), b';');
        assert_eq!(detect_delimiter("time\n"), b',');
        // Comment lines are not the header; a header of words between blanks is blanks.
        assert_eq!(detect_delimiter("# a;b;c\ntime,w,x,y,z\n"), b',');
        assert_eq!(detect_delimiter("# a,b\ntime  w x\ty z\n"), b'\t');
        assert_eq!(detect_delimiter("time  w x y z\n"), b' ');
    }

    #[test]
    fn comments_and_blank_separated_columns() {
        let text =
            "# exported by hand\n  time   w x y z\n# a comment row\n0 1 0 0 0\n\n1\t0 0 0 1\r\n";
        let doc = read(text, "k.csv", &opts()).unwrap();
        assert_eq!(doc.tracks[0].keys.len(), 2);
        assert_eq!(doc.tracks[0].keys[1].when, KeyTime::Seconds(1.0));
        assert_eq!(doc.tracks[0].loc(1), crate::document::Loc::Line(6));
        let err = read("time w x y z\n0 1 0 0\n", "k.csv", &opts()).unwrap_err();
        assert_eq!(
            err.message(),
            "k.csv:2: expected 5 fields as in the header, found 4"
        );
        assert_eq!(clean(" a  b\t c \r\n #x\nd", true), "a\tb\tc\n\nd");
        assert_eq!(clean("a,b\r\n#x,y\nd", false), "a,b\r\n\nd");
    }

    #[test]
    fn spreadsheet_headers_and_suggestions() {
        let text = "Time ; W ; X ; Y ; Z\r\n0;1;0;0;0\r\n1;0;0;0;1\r\n";
        let doc = read(text, "k.csv", &opts()).unwrap();
        assert_eq!(doc.tracks[0].keys.len(), 2);
        let err = |text: &str| {
            read(text, "k.csv", &opts())
                .unwrap_err()
                .message()
                .to_string()
        };
        assert_eq!(
            err("TIME,w,x,y,z,Trak\n"),
            "k.csv:1: unknown column \"Trak\": expected track, time, frame, w, x, y, z (optional: wx, \
             wy, wz, tension, continuity, bias, tx, ty, tz); did you \
             mean \"track\"?"
        );
        assert_eq!(
            err("time,W,x,y,z,w\n"),
            "k.csv:1: column \"w\" appears twice"
        );
        assert_eq!(
            err("time,W,x,y,z\n0,a,0,0,0\n"),
            "k.csv:2: column \"W\": expected a number, found \"a\""
        );
        assert_eq!(suggestion("qw", &["w", "x"]), "; did you mean \"w\"?");
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        let tabs = ReadOptions {
            delimiter: Some(b'\t'),
            ..opts()
        };
        assert!(read("time,w,x,y,z\n0,1,0,0,0\n", "k.csv", &tabs).is_err());
        assert!(read("time\tw\tx\ty\tz\n0\t1\t0\t0\t0\n", "k.csv", &tabs).is_ok());
    }

    #[test]
    fn errors_name_line_and_column() {
        let text = "time,w,x,y,z\n0,1,0,0,0\n1,abc,0,0,0\n";
        let err = read(text, "k.csv", &opts()).unwrap_err();
        assert_eq!(
            err.message(),
            "k.csv:3: column \"w\": expected a number, found \"abc\""
        );
    }
}
