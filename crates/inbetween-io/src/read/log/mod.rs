//! Timestamped logs (docs/formats.md, *Timestamped logs*): one orientation per row, read
//! through a [`ColumnMap`] rather than the CSV reader's column names. Lines starting with `#`
//! are comments; columns are separated by the delimiter of the first row (`,`, `;`, tab; the
//! one found most often), else by runs of spaces and tabs (TUM). Stamps become seconds from the
//! first stamp (or as written), exactly in integers first ([`stamp`]). One track, unnamed.
//!
//! The header, when the map names columns: the first line that is not a comment if it names
//! them all, else the last comment line before it that does (EuRoC's `#timestamp, p_RS_R_x
//! [m], …`, its `#` removed). Without names every line that is not a comment is a row (TUM).

pub mod columns;
pub mod stamp;

pub use columns::{Column, ColumnMap, Preset};
pub use stamp::{TimeOrigin, TimeUnit};

use crate::ReadOptions;
use crate::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use crate::read::csv::detect_delimiter;
use columns::{FIELD_NAMES, FIELDS};
use glam::DVec3;
use inbetween::error::{InputResult, shorten};
use inbetween::rotation::Repr;

/// How the fields of a line are separated.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Separator {
    /// One byte (`,`, `;`, tab), outside double quotes.
    Byte(u8),
    /// Runs of spaces and tabs.
    Blanks,
}

impl Separator {
    /// The separator of a row: `given` (`b' '` for runs of blanks), else the most frequent of
    /// `,`, `;` and tab, else blanks when the line has any.
    fn of(line: &str, given: Option<u8>) -> Separator {
        match given {
            Some(b' ') => Separator::Blanks,
            Some(b) => Separator::Byte(b),
            None if line.contains([',', ';', '\t']) => Separator::Byte(detect_delimiter(line)),
            None if line.contains(' ') => Separator::Blanks,
            None => Separator::Byte(b','),
        }
    }

    /// The trimmed fields of `line`, quotes around a field removed.
    fn split(self, line: &str) -> Vec<&str> {
        match self {
            Separator::Blanks => line.split_ascii_whitespace().collect(),
            Separator::Byte(d) => {
                let mut out = Vec::new();
                let (mut start, mut quoted) = (0, false);
                for (i, b) in line.bytes().enumerate() {
                    if b == b'"' {
                        quoted = !quoted;
                    } else if b == d && !quoted {
                        out.push(unquote(&line[start..i]));
                        start = i + 1;
                    }
                }
                out.push(unquote(&line[start..]));
                out
            }
        }
    }
}

fn unquote(field: &str) -> &str {
    let f = field.trim();
    f.strip_prefix('"')
        .and_then(|f| f.strip_suffix('"'))
        .unwrap_or(f)
}

/// Reads a timestamped log with the column map `map`.
pub fn read(
    text: &str,
    source: &str,
    map: &ColumnMap,
    opts: &ReadOptions,
) -> InputResult<Document> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // Numbered lines that hold something, comments marked.
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i as u64 + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty())
        .peekable();
    let mut comments = Vec::new();
    while let Some((n, l)) = lines.next_if(|(_, l)| l.starts_with('#')) {
        comments.push((n, &l[1..]));
    }
    let Some(&(first_line, first)) = lines.peek() else {
        return Err(input_err!("{source}: expected rows of a log, found none"));
    };
    let sep = Separator::of(first, opts.delimiter);
    // The header and each field's column.
    let (header, idx) = if map.needs_header() {
        let first_names = sep.split(first);
        match map.resolve(Some(&first_names)) {
            Ok(idx) => {
                lines.next();
                (Some((first_line, first_names)), idx)
            }
            Err(first_err) => {
                let found = comments.iter().rev().find_map(|&(n, c)| {
                    let names = sep.split(c);
                    map.resolve(Some(&names)).ok().map(|idx| ((n, names), idx))
                });
                match found {
                    Some((h, idx)) => (Some(h), idx),
                    None => return Err(input_err!("{source}:{first_line}: {first_err}")),
                }
            }
        }
    } else {
        (
            None,
            map.resolve(None).map_err(|e| input_err!("{source}: {e}"))?,
        )
    };
    let label = |f: usize| -> String {
        let c = idx[f].unwrap_or_default();
        match &header {
            Some((_, names)) => format!("column \"{}\" ({})", shorten(names[c]), FIELD_NAMES[f]),
            None => format!("column {} ({})", c + 1, FIELD_NAMES[f]),
        }
    };
    let needed = idx.iter().flatten().max().map_or(0, |m| m + 1);
    let translation = idx[5].is_some();
    let unit = map.unit();
    let mut track = DocTrack::new(Vec::new(), KeyOrigin::Lines(Vec::new()));
    let mut warnings = Vec::new();
    let mut stamps: Vec<i128> = Vec::new();
    let mut previous: Option<(i128, u64, &str)> = None;
    for (line, text) in lines {
        if text.starts_with('#') {
            continue;
        }
        let fields = sep.split(text);
        match &header {
            Some((h, names)) if fields.len() != names.len() => {
                return Err(input_err!(
                    "{source}:{line}: expected {} fields as in the header (line {h}), found {}",
                    names.len(),
                    fields.len()
                ));
            }
            None if fields.len() < needed => {
                return Err(input_err!(
                    "{source}:{line}: expected at least {needed} fields, found {}",
                    fields.len()
                ));
            }
            _ => {}
        }
        let field = |f: usize| fields[idx[f].unwrap_or_default()];
        let ns = stamp::parse(field(0), unit)
            .map_err(|e| input_err!("{source}:{line}: {}: {e}", label(0)))?;
        if let Some((before, at, written)) = previous
            && ns <= before
        {
            return Err(input_err!(
                "{source}:{line}: {}: expected stamps that increase, found {} after {} \
                 (line {at})",
                label(0),
                shorten(field(0)),
                shorten(written)
            ));
        }
        previous = Some((ns, line, field(0)));
        let number = |f: usize| -> InputResult<f64> {
            let raw = field(f);
            match raw.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(input_err!(
                    "{source}:{line}: {}: expected a finite number, found \"{}\"",
                    label(f),
                    shorten(raw)
                )),
            }
        };
        let q = [number(1)?, number(2)?, number(3)?, number(4)?];
        let (rot, warning) = Repr::Quat
            .to_quat(&q, opts.undeclared_angles())
            .map_err(|e| e.at(format!("{source}:{line}: columns w,x,y,z")))?;
        if let Some(w) = warning {
            warnings.push(format!("{source}:{line}: {w}"));
        }
        let position = if translation {
            Some(DVec3::new(number(5)?, number(6)?, number(7)?))
        } else {
            None
        };
        stamps.push(ns);
        track.keys.push(Key {
            when: KeyTime::Seconds(0.0),
            rot,
        });
        if let KeyOrigin::Lines(l) = &mut track.origin {
            l.push(line);
        }
        track.push_translation(position);
    }
    let Some(&first_stamp) = stamps.first() else {
        return Err(input_err!(
            "{source}: expected at least 1 row, found only a header"
        ));
    };
    for (key, &ns) in track.keys.iter_mut().zip(&stamps) {
        key.when = KeyTime::Seconds(stamp::seconds(ns, first_stamp, map.times));
    }
    debug_assert_eq!(FIELD_NAMES.len(), FIELDS);
    Ok(Document {
        rotation: Some(Repr::Quat),
        tracks: vec![track],
        warnings,
        ..Document::new(source)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_with(text: &str, map: &str) -> InputResult<Document> {
        let map = ColumnMap::parse(map).unwrap();
        read(text, "log.txt", &map, &ReadOptions::default())
    }

    fn times(doc: &Document) -> Vec<f64> {
        doc.tracks[0]
            .keys
            .iter()
            .map(|k| match k.when {
                KeyTime::Seconds(t) => t,
                KeyTime::Frame(_) => unreachable!(),
            })
            .collect()
    }

    #[test]
    fn euroc_header_in_a_comment_and_exact_nanoseconds() {
        let text = "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], \
                    q_RS_y [], q_RS_z []\n\
                    1403636579758555392,1,2,3,1,0,0,0\n\
                    1403636579758555393,1,2,3,0,0,0,1\n";
        let doc = read_with(text, "euroc").unwrap();
        assert_eq!(times(&doc), [0.0, 1e-9]);
        assert_eq!(
            doc.tracks[0].translations[1],
            Some(DVec3::new(1.0, 2.0, 3.0))
        );
        assert_eq!(doc.tracks[0].loc(1), crate::document::Loc::Line(3));
    }

    #[test]
    fn tum_blanks_and_comments() {
        let text = "# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n\
                    1305031098.6659 1 2 3 0 0 0 1\n1305031098.6759  1 2 3 0 0 1 0\n";
        let doc = read_with(text, "tum").unwrap();
        let t = times(&doc);
        assert_eq!(t[0], 0.0);
        assert_eq!(t[1], 0.01);
        assert!((doc.tracks[0].keys[1].rot.z - 1.0).abs() < 1e-15);
        // Names from the comment header work too, in any case.
        let doc = read_with(text, "time=TIMESTAMP,w=qw,x=qx,y=qy,z=qz").unwrap();
        assert_eq!(times(&doc), t);
    }

    #[test]
    fn located_errors() {
        let msg = |text: &str, map: &str| read_with(text, map).unwrap_err().message().to_string();
        let rost = "%time,field.x,field.y,field.z,field.w\n";
        assert_eq!(
            msg(&format!("{rost}100,0,0,0,1\n100,0,0,0,1\n"), "rostopic"),
            "log.txt:3: column \"%time\" (time): expected stamps that increase, found 100 after \
             100 (line 2)"
        );
        assert_eq!(
            msg(&format!("{rost}100.5,0,0,0,1\n"), "rostopic"),
            "log.txt:2: column \"%time\" (time): expected a whole number of nanoseconds, found \
             \"100.5\""
        );
        assert_eq!(
            msg(&format!("{rost}100,0,0,x,1\n"), "rostopic"),
            "log.txt:2: column \"field.z\" (z): expected a finite number, found \"x\""
        );
        assert_eq!(
            msg("%time,field.x,field.y,field.z\n1,0,0,0\n", "rostopic"),
            "log.txt:1: no quaternion columns (…x, …y, …z, …w of one prefix such as \
             field.pose.orientation.) among the columns: %time,field.x,field.y,field.z"
        );
        assert_eq!(
            msg("1 0 0 0\n", "tum"),
            "log.txt:1: expected at least 8 fields, found 4"
        );
        assert_eq!(
            msg("# only\n", "tum"),
            "log.txt: expected rows of a log, found none"
        );
        assert_eq!(
            msg("1 0 0 0 0 0 0 0\n", "tum"),
            "log.txt:1: columns w,x,y,z: expected a quaternion of non-zero length, found norm 0e0"
        );
    }

    #[test]
    fn absolute_times_keep_the_stamps() {
        let text = "t w x y z\n2.5 1 0 0 0\n3 1 0 0 0\n";
        let mut map = ColumnMap::parse("time=t,w=w,x=x,y=y,z=z").unwrap();
        assert_eq!(
            times(&read(text, "k", &map, &ReadOptions::default()).unwrap()),
            [0.0, 0.5]
        );
        map.times = TimeOrigin::Absolute;
        assert_eq!(
            times(&read(text, "k", &map, &ReadOptions::default()).unwrap()),
            [2.5, 3.0]
        );
    }
}
