//! The BVH parser: text → [`Clip`] and located warnings.
//!
//! The hierarchy is read as a stream of whitespace-separated tokens (any indentation, line
//! breaks where a writer likes them, CRLF line ends), with keywords case-sensitive as real
//! files write them (`HIERARCHY`, `ROOT`, `JOINT`, `End Site`, `OFFSET`, `CHANNELS`, `MOTION`,
//! `Frames:`, `Frame Time:`). A joint's name is the rest of its `ROOT`/`JOINT` line, so names
//! with spaces work. After the `Frame Time:` line, each non-blank line is one frame.
//!
//! Errors are [`InputError`](inbetween::InputError)s naming `file:line`, what was expected and what was found
//! (`clip.bvh:12: expected a number for OFFSET, found "abc"`); a non-finite number (`nan`,
//! `inf`, `1e999`) is an error, never a value. Nesting is handled without recursion, so no
//! input can exhaust the stack.

use super::chosen::Choose;
use super::hierarchy::{Parser, Tokens, column_name, found};
use super::rate::rate_from_frame_time;
use super::{Clip, Joint};
use inbetween::clock::Fps;
use inbetween::error::{InputResult, shorten};
use std::io::Read;

/// Everything before the rows, parsed.
struct Head {
    joints: Vec<Joint>,
    hierarchy: String,
    declared: u64,
    frames_line: usize,
    frame_time_text: String,
    frame_time: f64,
    fps: Fps,
    channels: usize,
    /// Byte offset (in the text without its byte-order mark) of the line end of the `Frame
    /// Time` line: the rows are the lines after it.
    body_start: usize,
    /// The line number of the `Frame Time` line.
    time_line: usize,
}

/// Parses the hierarchy and the `MOTION` header of `text` (without a byte-order mark).
fn parse_head(text: &str, source: &str) -> InputResult<Head> {
    let mut p = Parser {
        source,
        toks: Tokens {
            text,
            pos: 0,
            line: 1,
        },
        joints: Vec::new(),
        columns: 0,
    };
    let first = p.toks.next();
    let start = match first {
        Some(t) if t.s == "HIERARCHY" => t.start,
        Some(_) => {
            return Err(p.err(
                first,
                format!("expected \"HIERARCHY\", found {}", found(first)),
            ));
        }
        None => {
            return Err(input_err!(
                "{source}: expected a BVH file starting with \"HIERARCHY\", found an empty input"
            ));
        }
    };
    let motion = p.hierarchy()?;
    let hierarchy = text[start..motion.start].to_string();
    if p.columns == 0 {
        return Err(p.err(
            Some(motion),
            "expected at least one channel in the hierarchy, found none".to_string(),
        ));
    }

    let frames_tok = p.expect("Frames:")?;
    let tok = p.toks.next();
    let declared: u64 = match tok.map(|t| t.s.parse::<u64>()) {
        Some(Ok(n)) => n,
        _ => {
            return Err(p.err(
                tok,
                format!(
                    "expected a whole number of frames after \"Frames:\", found {}",
                    found(tok)
                ),
            ));
        }
    };
    let frame = p.toks.next();
    let time = p.toks.next();
    let (Some(frame), Some(time)) = (frame, time) else {
        return Err(p.err(
            frame,
            format!("expected \"Frame Time:\", found {}", found(frame)),
        ));
    };
    if frame.s != "Frame" || time.s != "Time:" || frame.line != time.line {
        return Err(p.err(
            Some(frame),
            format!(
                "expected \"Frame Time:\", found \"{}\"",
                shorten(&p.toks.text[frame.start..time.start + time.s.len()])
            ),
        ));
    }
    let value = p.toks.next();
    let Some(value) = value.filter(|v| v.line == time.line) else {
        return Err(p.err(
            Some(time),
            "expected a frame time after \"Frame Time:\", found the end of the line".to_string(),
        ));
    };
    let fps =
        rate_from_frame_time(value.s).map_err(|e| e.at(format!("{source}:{}", value.line)))?;
    // The text the rate was read from: trimmed as `rate_from_frame_time` trims it (a vertical
    // tab is Unicode white space but part of a token here; found by the bvh_reader fuzz
    // target, it panicked). Never a panic.
    let frame_time: f64 = value.s.trim().parse().map_err(|_| {
        p.err(
            Some(value),
            format!(
                "expected a frame time in seconds, found \"{}\"",
                shorten(value.s)
            ),
        )
    })?;
    let rest = p.toks.rest_of_line();
    if !rest.is_empty() {
        return Err(p.err(
            Some(value),
            format!(
                "expected the end of the line after the frame time, found \"{}\"",
                shorten(rest)
            ),
        ));
    }
    Ok(Head {
        channels: p.columns,
        joints: p.joints,
        hierarchy,
        declared,
        frames_line: frames_tok.line,
        frame_time_text: value.s.to_string(),
        frame_time,
        fps,
        body_start: p.toks.pos,
        time_line: value.line,
    })
}

/// Powers of ten that are exact as `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// A motion value: `Ok` for a finite number, `Err(true)` for a number that is not finite,
/// `Err(false)` for anything else. Exactly what `str::parse::<f64>` reads (the same grammar and
/// the same correctly rounded value); the common `-12.345678` (at most 15 digits, no exponent)
/// is read directly — its digits are an exact integer `m` and `m / 10^k` of two exact values is
/// correctly rounded — and everything else by `str::parse`.
#[inline]
fn motion_value(cell: &str) -> Result<f64, bool> {
    let b = cell.as_bytes();
    let (neg, digits) = match b.first() {
        Some(b'-') => (true, &b[1..]),
        Some(b'+') => (false, &b[1..]),
        _ => (false, b),
    };
    let (mut m, mut n, mut frac, mut dot, mut plain) = (0u64, 0usize, 0usize, false, true);
    for &c in digits {
        match c {
            b'0'..=b'9' => {
                m = m.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
                n += 1;
                frac += usize::from(dot);
            }
            b'.' if !dot => dot = true,
            _ => {
                plain = false;
                break;
            }
        }
    }
    if plain && (1..=15).contains(&n) {
        // m < 10^15 < 2^53 and frac ≤ 15: both exact.
        let x = m as f64 / POW10[frac];
        return Ok(if neg { -x } else { x });
    }
    match cell.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(true),
        Err(_) => Err(false),
    }
}

/// The motion rows, one line at a time.
struct Rows<'a> {
    source: &'a str,
    joints: &'a [Joint],
    channels: usize,
    /// The columns whose values are kept ([`super::chosen`]); `None`: all.
    keep: Option<&'a [bool]>,
    /// The number of the last line read.
    line_no: usize,
    values: Vec<f64>,
}

impl Rows<'_> {
    /// The next line (without its `\n`): a row of `channels` values, or blank.
    fn line(&mut self, line: &str) -> InputResult<()> {
        self.line_no += 1;
        let (source, line_no, channels) = (self.source, self.line_no, self.channels);
        let (mut n, mut pushed) = (0, 0);
        for cell in line.split_ascii_whitespace() {
            if n == channels {
                let found = n + 1 + line.split_ascii_whitespace().skip(n + 1).count();
                self.values.truncate(self.values.len() - pushed);
                return Err(input_err!(
                    "{source}:{line_no}: expected {channels} values (one per channel), found {found}"
                ));
            }
            match motion_value(cell) {
                Ok(x) => {
                    if self.keep.is_none_or(|k| k[n]) {
                        self.values.push(x);
                        pushed += 1;
                    }
                }
                Err(parsed) => {
                    let what = if parsed {
                        "a finite number"
                    } else {
                        "a number"
                    };
                    return Err(input_err!(
                        "{source}:{line_no}: value {}{}: expected {what}, found \"{}\"",
                        n + 1,
                        column_name(self.joints, n),
                        shorten(cell)
                    ));
                }
            }
            n += 1;
        }
        if n != 0 && n != channels {
            return Err(input_err!(
                "{source}:{line_no}: expected {channels} values (one per channel), found {n}"
            ));
        }
        Ok(())
    }
}

/// The clip of `head` and `values`, and the warning when `Frames:` disagrees with the rows.
fn finish(head: Head, values: Vec<f64>, source: &str) -> (Clip, Vec<String>) {
    let rows = values.len() / head.channels;
    let mut warnings = Vec::new();
    if rows as u64 != head.declared {
        warnings.push(format!(
            "{source}:{}: \"Frames: {}\" but the motion has {rows} rows; the {rows} rows are used",
            head.frames_line, head.declared
        ));
    }
    let mut joints = head.joints;
    let given: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
    let ids: Vec<usize> = (0..joints.len()).collect();
    let names = crate::names::unique_names(&given, &ids);
    let by_track_name = names
        .iter()
        .enumerate()
        .map(|(j, n)| (n.clone(), j))
        .collect();
    for (joint, name) in joints.iter_mut().zip(names) {
        joint.track_name = name;
    }
    let clip = Clip {
        joints,
        by_track_name,
        hierarchy: head.hierarchy,
        declared_frames: head.declared,
        frame_time_text: head.frame_time_text,
        frame_time: head.frame_time,
        fps: head.fps,
        channels: head.channels,
        values,
    };
    (clip, warnings)
}

/// Room for the rows: `Frames:` as declared, but never more than `body_len` bytes can hold.
/// `width` values a row are kept (the chosen joints' columns, or every one).
fn values_for(head: &Head, body_len: u64, width: usize) -> Vec<f64> {
    let most = body_len / (2 * head.channels as u64) + 1;
    let hint = usize::try_from(head.declared.min(most)).unwrap_or(usize::MAX);
    Vec::with_capacity(hint.saturating_mul(width))
}

/// Parses a BVH file. `source` names it in messages (`clip.bvh`). Returns the clip and the
/// warnings, each located (`clip.bvh:40: "Frames: 100" but the motion has 99 rows; …`).
///
/// Accepted as files are written: a byte-order mark, CRLF line ends, tabs or spaces, blank
/// lines between rows and at the end, several `ROOT`s, joints without channels, 3- and
/// 6-channel joints, each joint's own channel order, a `Frame Time` of `.0083333`. Errors: a
/// missing or misplaced keyword, a number that is not one or not finite, a channel count
/// outside 0–6 or a channel listed twice, a hierarchy without channels, a row with the wrong
/// number of values, a frame time that is not a positive finite number. When `Frames:`
/// disagrees with the number of rows, the rows win and a warning says so.
pub fn parse(text: &str, source: &str) -> InputResult<(Clip, Vec<String>)> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // Lines that end in CR alone (classic Mac OS) would read as one line: say so.
    if !text.contains('\n') && text.contains('\r') {
        return Err(input_err!(
            "{source}: its lines end in CR alone (classic Mac OS); convert the line ends to LF \
             or CRLF (e.g. tr '\\r' '\\n' < in.bvh > out.bvh)"
        ));
    }
    let head = parse_head(text, source)?;
    // The line after the Frame Time line (`body` starts at its line end).
    let body = &text[head.body_start..];
    let mut rows = Rows {
        source,
        joints: &head.joints,
        channels: head.channels,
        line_no: head.time_line - 1,
        keep: None,
        values: values_for(&head, body.len() as u64, head.channels),
    };
    for line in body.split('\n') {
        rows.line(line)?;
    }
    let values = rows.values;
    Ok(finish(head, values, source))
}

/// How much [`parse_reader`] reads at a time.
const CHUNK: usize = 1 << 20;

/// [`parse`] reading from `reader` in pieces of about 1 MiB, never holding the file's text:
/// the rows go straight into the clip's values. `len`, when known (a file's size), bounds the
/// room made for the rows as [`parse`] does; otherwise rows beyond 1 Mi values at a time are
/// made room for as they come. The clip and warnings are [`parse`]'s for the same text; an
/// invalid file is an input error (when a file has several faults, the first met reading
/// forward, which is not always the one [`parse`] reports: [`parse`] needs the whole text as
/// UTF-8 first, while this reads rows as they come).
pub fn parse_reader<R: Read>(
    reader: R,
    source: &str,
    len: Option<u64>,
) -> InputResult<(Clip, Vec<String>)> {
    read_clip(reader, source, len, None)
}

/// [`parse_reader`] keeping the motion values of the joints `choose` chooses only
/// ([`super::chosen`]): every row is read and checked as there (the same errors and
/// warnings), and `choose`'s error, given the track names once the hierarchy is read, is the
/// read's.
pub fn parse_reader_chosen<R: Read>(
    reader: R,
    source: &str,
    len: Option<u64>,
    choose: Choose,
) -> InputResult<(Clip, Vec<String>)> {
    read_clip(reader, source, len, Some(choose))
}

fn read_clip<R: Read>(
    mut reader: R,
    source: &str,
    len: Option<u64>,
    choose: Option<Choose>,
) -> InputResult<(Clip, Vec<String>)> {
    let cannot = |e: std::io::Error| input_err!("{source}: cannot read: {e}");
    let not_utf8 = |at: usize| {
        input_err!("{source}: expected UTF-8 text, found an invalid byte at offset {at}")
    };
    let mut buf: Vec<u8> = Vec::with_capacity(CHUNK);
    // Up to CHUNK more bytes at the end of `buf`; false at the end of the input.
    let mut more = |buf: &mut Vec<u8>| -> InputResult<bool> {
        let n = (&mut reader)
            .take(CHUNK as u64)
            .read_to_end(buf)
            .map_err(cannot)?;
        Ok(n > 0)
    };
    // The header: up to the line end after the first "Frame Time:".
    const MARK: &[u8] = b"Frame Time:";
    let (mut searched, mut mark) = (0usize, None);
    let head_end = loop {
        if mark.is_none() {
            let from = searched.saturating_sub(MARK.len());
            mark = buf[from..]
                .windows(MARK.len())
                .position(|w| w == MARK)
                .map(|i| from + i);
        }
        if let Some(m) = mark
            && let Some(j) = buf[m..].iter().position(|&b| b == b'\n')
        {
            break Some(m + j + 1);
        }
        searched = buf.len();
        if !more(&mut buf)? {
            break None;
        }
    };
    let bom = if buf.starts_with("\u{feff}".as_bytes()) {
        3
    } else {
        0
    };
    let whole = |mut buf: Vec<u8>, more: &mut dyn FnMut(&mut Vec<u8>) -> InputResult<bool>| {
        while more(&mut buf)? {}
        let text = String::from_utf8(buf).map_err(|e| not_utf8(e.utf8_error().valid_up_to()))?;
        let (clip, warnings) = parse(&text, source)?;
        match choose {
            Some(choose) => Ok((super::chosen::of_clip(clip, choose)?, warnings)),
            None => Ok((clip, warnings)),
        }
    };
    let Some(head_end) = head_end else {
        return whole(buf, &mut more);
    };
    let head = match std::str::from_utf8(&buf[bom..head_end]).map(|t| parse_head(t, source)) {
        Ok(Ok(head)) => head,
        // Whatever is wrong, it is reported as parse reports it.
        _ => return whole(buf, &mut more),
    };
    let (keep, keep_joint) = match choose {
        Some(choose) => {
            let (columns, joints) = super::chosen::columns(&head.joints, choose)?;
            (Some(columns), Some(joints))
        }
        None => (None, None),
    };
    let width = keep
        .as_ref()
        .map_or(head.channels, |k| k.iter().filter(|&&k| k).count());
    let body_len = len.map_or(CHUNK as u64, |n| n.saturating_sub(head_end as u64));
    let values = values_for(&head, body_len, width);
    let mut rows = Rows {
        source,
        joints: &head.joints,
        channels: head.channels,
        keep: keep.as_deref(),
        line_no: head.time_line - 1,
        values,
    };
    // The body starts at the line end of the Frame Time line, as in `parse`; every piece
    // of it before a `\n` is a line, and so is the piece after the last one.
    let mut start = bom + head.body_start;
    // Bytes of the file before buf[0].
    let mut offset = 0;
    loop {
        if let Some(i) = buf[start..].iter().rposition(|&b| b == b'\n') {
            let end = start + i;
            let text = std::str::from_utf8(&buf[start..end])
                .map_err(|e| not_utf8(offset + start + e.valid_up_to()))?;
            for line in text.split('\n') {
                rows.line(line)?;
            }
            start = end + 1;
        }
        // Keep the unfinished line.
        buf.drain(..start);
        offset += start;
        start = 0;
        if !more(&mut buf)? {
            let text = std::str::from_utf8(&buf).map_err(|e| not_utf8(offset + e.valid_up_to()))?;
            rows.line(text)?;
            break;
        }
    }
    let values = rows.values;
    let mut head = head;
    if let Some(keep_joint) = keep_joint {
        head.channels = super::chosen::narrow(&mut head.joints, &keep_joint);
    }
    Ok(finish(head, values, source))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::clip::Channel;

    /// Two roots; End Sites; a 6-channel root in ZXY; joints in ZYX and XYZ; a joint with
    /// no channels; a joint with position channels interleaved with rotations; tabs; a name
    /// with spaces; a brace on the ROOT line.
    pub(crate) const SMALL: &str = "HIERARCHY
ROOT Hips
{
\tOFFSET 0.0 0.0 0.0
\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
\tJOINT Chest
\t{
\t\tOFFSET 0 5.21 0
\t\tCHANNELS 3 Zrotation Yrotation Xrotation
\t\tJOINT Bip01 L Hand
\t\t{
\t\t\tOFFSET 1.5 -2 .25
\t\t\tCHANNELS 3 Xrotation Yrotation Zrotation
\t\t\tEnd Site
\t\t\t{
\t\t\t\tOFFSET 0 -7 0
\t\t\t}
\t\t}
\t}
\tJOINT Marker
\t{
\t\tOFFSET 1 1 1
\t\tCHANNELS 0
\t\tEnd Site
\t\t{
\t\t\tOFFSET 0 1 0
\t\t}
\t}
}
ROOT Prop {
  OFFSET 10 0 0
  CHANNELS 6 Zrotation Xposition Yrotation Yposition Xrotation Zposition
}
MOTION
Frames: 3
Frame Time: 0.0333333
0 35 0 0 0 0 0 0 0 0 0 0 1 2 3 4 5 6
1.5 35.25 -2 10 20 30 -5 0 5 90 -90 180 7 8 9 10 11 12
-0.0000 1e2 2.5E-1 -179.99 0.001 359 1 2 3 4 5 6 7 8 9 10 11 12

";

    /// A BVH file of `n` three-channel roots whose names are `pad` bytes of `x` and then the
    /// joint's index in six digits (all of one length: comparing two costs the whole name),
    /// with two rows.
    pub(crate) fn many_joints(n: usize, pad: usize) -> String {
        let x = "x".repeat(pad);
        let mut text = String::from("HIERARCHY\n");
        for j in 0..n {
            text += &format!(
                "ROOT {x}{j:06}\n{{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n}}\n"
            );
        }
        text += "MOTION\nFrames: 2\nFrame Time: 0.04\n";
        for i in 0..2 {
            text += &vec![format!("{} 0 0", 3 * i); n].join(" ");
            text.push('\n');
        }
        text
    }

    /// Runs a timing takes the least of: the work takes milliseconds in an optimised test build,
    /// and tests on the other threads preempt some runs (three were too few: 8.7× for 4× the
    /// joints once in CI, beside the other tests).
    const TIMED_RUNS: usize = 9;

    /// The least of [`TIMED_RUNS`] timings of `f`, seconds (the least is the one other
    /// processes and threads disturbed least).
    pub(crate) fn least_of_runs(mut f: impl FnMut()) -> f64 {
        (0..TIMED_RUNS)
            .map(|_| {
                let start = std::time::Instant::now();
                f();
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn parse_ok(text: &str) -> (Clip, Vec<String>) {
        parse(text, "clip.bvh").unwrap()
    }

    fn parse_err(text: &str) -> String {
        parse(text, "clip.bvh").unwrap_err().to_string()
    }

    #[test]
    fn parses_a_small_hand_written_file() {
        let (clip, warnings) = parse_ok(SMALL);
        assert!(warnings.is_empty(), "{warnings:?}");
        let names: Vec<&str> = clip.joints().iter().map(|j| j.name()).collect();
        assert_eq!(names, ["Hips", "Chest", "Bip01 L Hand", "Marker", "Prop"]);
        let parents: Vec<Option<usize>> = clip.joints().iter().map(|j| j.parent()).collect();
        assert_eq!(parents, [None, Some(0), Some(1), Some(0), None]);
        let lines: Vec<usize> = clip.joints().iter().map(|j| j.line()).collect();
        assert_eq!(lines, [2, 6, 10, 20, 30]);
        let hand = clip.joint("Bip01 L Hand").unwrap();
        assert_eq!(hand.offset(), [1.5, -2.0, 0.25]);
        assert_eq!(hand.end_site(), Some([0.0, -7.0, 0.0]));
        assert_eq!(clip.joints()[0].end_site(), None);
        assert_eq!(clip.channel_count(), 18);
        assert_eq!(clip.frame_count(), 3);
        assert_eq!(clip.declared_frames(), 3);
        assert_eq!(clip.frame_time_text(), "0.0333333");
        assert_eq!(clip.frame_time(), 0.0333333);
        assert_eq!((clip.fps().num(), clip.fps().den()), (30, 1));
        assert_eq!(clip.time_of(2), 2.0 / 30.0);
        assert_eq!(clip.row(2)[..6], [-0.0, 100.0, 0.25, -179.99, 0.001, 359.0]);
        assert_eq!(clip.rows().count(), 3);
        assert_eq!(clip.values().len(), 54);
        // The hierarchy text: from HIERARCHY to the start of MOTION, byte for byte.
        let end = SMALL.find("MOTION").unwrap();
        assert_eq!(clip.hierarchy(), &SMALL[..end]);
    }

    #[test]
    fn each_joint_has_its_own_rotation_order_and_columns() {
        let (clip, _) = parse_ok(SMALL);
        let rot = |name: &str| {
            clip.joint(name)
                .unwrap()
                .rotation()
                .map(|(s, c)| (s.as_str().to_string(), c))
        };
        assert_eq!(
            rot("Hips"),
            Some(("ZXY".to_string(), [Some(3), Some(4), Some(5)]))
        );
        assert_eq!(
            rot("Chest"),
            Some(("ZYX".to_string(), [Some(6), Some(7), Some(8)]))
        );
        assert_eq!(
            rot("Bip01 L Hand"),
            Some(("XYZ".to_string(), [Some(9), Some(10), Some(11)]))
        );
        assert_eq!(rot("Marker"), None);
        // Interleaved: Zrotation Xposition Yrotation Yposition Xrotation Zposition.
        assert_eq!(
            rot("Prop"),
            Some(("ZYX".to_string(), [Some(12), Some(14), Some(16)]))
        );
        let pos = |name: &str| clip.joint(name).unwrap().position();
        assert_eq!(pos("Hips"), Some([Some(0), Some(1), Some(2)]));
        assert_eq!(pos("Chest"), None);
        assert_eq!(pos("Prop"), Some([Some(13), Some(15), Some(17)]));
        assert_eq!(clip.joint("Marker").unwrap().columns(), 12..12);
        assert_eq!(clip.joint("Prop").unwrap().columns(), 12..18);
        let chest = clip.joint("Chest").unwrap();
        assert_eq!(
            chest.channels(),
            [Channel::Zrotation, Channel::Yrotation, Channel::Xrotation]
        );
    }

    #[test]
    fn the_listed_order_is_the_intrinsic_product() {
        // Zrotation Xrotation Yrotation = 30, 20, 10 degrees: R = Rz(30)·Rx(20)·Ry(10).
        use glam::DQuat;
        let (clip, _) = parse_ok(SMALL);
        let (seq, cols) = clip.joint("Hips").unwrap().rotation().unwrap();
        let row = clip.row(1);
        let angles = cols.map(|c| row[c.unwrap()].to_radians());
        let q = seq.to_quat(angles);
        let want = DQuat::from_rotation_z(angles[0])
            * DQuat::from_rotation_x(angles[1])
            * DQuat::from_rotation_y(angles[2]);
        assert!(q.dot(want).abs() > 1.0 - 1e-15, "{q} vs {want}");
    }

    #[test]
    fn crlf_bom_and_odd_spacing_read_the_same() {
        let (clip, _) = parse_ok(SMALL);
        let messy = format!(
            "\u{feff}\r\n  {}",
            SMALL.replace('\n', "\r\n").replace('\t', "   ")
        );
        let (other, warnings) = parse_ok(&messy);
        assert!(warnings.is_empty());
        assert_eq!(other.values(), clip.values());
        assert_eq!(other.joints().len(), clip.joints().len());
        for (a, b) in other.joints().iter().zip(clip.joints()) {
            assert_eq!(
                (a.name(), a.offset(), a.channels()),
                (b.name(), b.offset(), b.channels())
            );
            assert_eq!(a.line(), b.line() + 1);
        }
        // The hierarchy text keeps the CRLF line ends and starts at HIERARCHY.
        assert!(other.hierarchy().starts_with("HIERARCHY\r\nROOT Hips\r\n"));
        assert!(other.hierarchy().ends_with("}\r\n"));
    }

    #[test]
    fn frames_disagreeing_with_the_rows_is_a_warning_and_the_rows_win() {
        let text = SMALL.replace("Frames: 3", "Frames: 5");
        let (clip, warnings) = parse_ok(&text);
        assert_eq!(clip.frame_count(), 3);
        assert_eq!(clip.declared_frames(), 5);
        assert_eq!(
            warnings,
            ["clip.bvh:35: \"Frames: 5\" but the motion has 3 rows; the 3 rows are used"]
        );
        let text = SMALL.replace("Frames: 3", "Frames: 2");
        let (clip, warnings) = parse_ok(&text);
        assert_eq!(clip.frame_count(), 3);
        assert_eq!(warnings.len(), 1);
    }

    #[test]
    fn zero_frames_is_a_clip_without_rows() {
        let end = SMALL.find("0 35 0").unwrap();
        let text = SMALL[..end].replace("Frames: 3", "Frames: 0");
        let (clip, warnings) = parse_ok(&text);
        assert!(warnings.is_empty());
        assert_eq!(clip.frame_count(), 0);
        assert!(clip.values().is_empty());
    }

    /// SMALL with `from` replaced by `to` (which must occur exactly once).
    fn small_with(from: &str, to: &str) -> String {
        assert_eq!(SMALL.matches(from).count(), 1, "{from}");
        SMALL.replace(from, to)
    }

    #[test]
    fn every_error_names_the_line_what_was_expected_and_what_was_found() {
        let cases: Vec<(String, &str)> = vec![
            (
                String::new(),
                "clip.bvh: expected a BVH file starting with \"HIERARCHY\", found an empty input",
            ),
            (
                "\u{feff} \n\r\n".to_string(),
                "clip.bvh: expected a BVH file starting with \"HIERARCHY\", found an empty input",
            ),
            (
                small_with("HIERARCHY", "hierarchy"),
                "clip.bvh:1: expected \"HIERARCHY\", found \"hierarchy\"",
            ),
            (
                small_with("ROOT Hips", "JOINT Hips"),
                "clip.bvh:2: expected \"ROOT\", found \"JOINT\"",
            ),
            (
                "HIERARCHY\nMOTION\n".to_string(),
                "clip.bvh:2: expected \"ROOT\", found \"MOTION\"",
            ),
            (
                "HIERARCHY\n".to_string(),
                "clip.bvh: expected \"ROOT\", found the end of the file",
            ),
            (
                small_with("ROOT Hips", "ROOT"),
                "clip.bvh:2: expected a joint name after ROOT, found the end of the line",
            ),
            (
                small_with("ROOT Hips\n{", "ROOT Hips\n("),
                "clip.bvh:3: expected \"{\", found \"(\"",
            ),
            (
                small_with("OFFSET 0.0 0.0 0.0", "OFFSET 0.0 abc 0.0"),
                "clip.bvh:4: expected a number for OFFSET, found \"abc\"",
            ),
            (
                small_with("OFFSET 0.0 0.0 0.0", "OFFSET 0.0 nan 0.0"),
                "clip.bvh:4: expected a finite number for OFFSET, found \"nan\"",
            ),
            (
                small_with("OFFSET 0.0 0.0 0.0", "OFFSET 0.0 1e999 0.0"),
                "clip.bvh:4: expected a finite number for OFFSET, found \"1e999\"",
            ),
            (
                small_with("OFFSET 0.0 0.0 0.0", "OFFSET 0.0 0.0"),
                "clip.bvh:5: expected a number for OFFSET, found \"CHANNELS\"",
            ),
            (
                small_with("\tOFFSET 0.0 0.0 0.0\n", ""),
                "clip.bvh:4: expected \"OFFSET\", found \"CHANNELS\"",
            ),
            (
                small_with("CHANNELS 0", "CHANNELS none"),
                "clip.bvh:23: expected a channel count from 0 to 6 for CHANNELS, found \"none\"",
            ),
            (
                small_with("CHANNELS 0", "CHANNELS 7"),
                "clip.bvh:23: expected a channel count from 0 to 6 for CHANNELS, found \"7\"",
            ),
            (
                small_with(
                    "CHANNELS 3 Zrotation Yrotation Xrotation",
                    "CHANNELS 3 Zrotation Yrotation xrotation",
                ),
                "clip.bvh:9: expected channel 3 of 3 for CHANNELS (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation), found \"xrotation\"",
            ),
            (
                small_with(
                    "CHANNELS 3 Zrotation Yrotation Xrotation",
                    "CHANNELS 4 Zrotation Yrotation Xrotation",
                ),
                "clip.bvh:10: expected channel 4 of 4 for CHANNELS (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation), found \"JOINT\"",
            ),
            (
                small_with(
                    "CHANNELS 3 Xrotation Yrotation Zrotation",
                    "CHANNELS 3 Xrotation Yrotation Xrotation",
                ),
                "clip.bvh:13: joint \"Bip01 L Hand\" lists Xrotation twice in CHANNELS",
            ),
            (
                small_with(
                    "\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 1 0\n\t\t}\n",
                    "\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 1 0\n\t\t}\n\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 1 0\n\t\t}\n",
                ),
                "clip.bvh:28: joint \"Marker\" has a second End Site",
            ),
            (
                small_with("\t\t\tEnd Site\n", "\t\t\tEnd site\n"),
                "clip.bvh:14: expected \"Site\", found \"site\"",
            ),
            (
                small_with("\t\tJOINT Bip01", "\t\tJoint Bip01"),
                "clip.bvh:10: expected \"JOINT\", \"End Site\" or \"}\" in joint \"Chest\", found \"Joint\"",
            ),
            (
                small_with("}\nROOT Prop {", "ROOT Prop {"),
                "clip.bvh:29: expected \"JOINT\", \"End Site\" or \"}\" in joint \"Hips\", found \"ROOT\"",
            ),
            (
                small_with("}\nMOTION", "}\nmotion"),
                "clip.bvh:34: expected \"ROOT\" or \"MOTION\", found \"motion\"",
            ),
            (
                SMALL[..SMALL.find("\t}\n\tJOINT Marker").unwrap()].to_string(),
                "clip.bvh: expected \"}\" closing joint \"Chest\" (line 6), found the end of the file",
            ),
            (
                SMALL[..SMALL.find("MOTION").unwrap()].to_string(),
                "clip.bvh: expected \"MOTION\", found the end of the file",
            ),
            (
                small_with("Frames: 3", "Frames 3"),
                "clip.bvh:35: expected \"Frames:\", found \"Frames\"",
            ),
            (
                small_with("Frames: 3", "Frames: three"),
                "clip.bvh:35: expected a whole number of frames after \"Frames:\", found \"three\"",
            ),
            (
                small_with("Frames: 3", "Frames: -3"),
                "clip.bvh:35: expected a whole number of frames after \"Frames:\", found \"-3\"",
            ),
            (
                small_with("Frame Time: 0.0333333", "FrameTime: 0.0333333"),
                "clip.bvh:36: expected \"Frame Time:\", found \"FrameTime: 0.0333333\"",
            ),
            (
                small_with("Frame Time: 0.0333333", "Frame Time:\n0.0333333"),
                "clip.bvh:36: expected a frame time after \"Frame Time:\", found the end of the line",
            ),
            (
                small_with("Frame Time: 0.0333333", "Frame Time: 0"),
                "clip.bvh:36: expected a positive frame time, found 0",
            ),
            (
                small_with("Frame Time: 0.0333333", "Frame Time: -0.01"),
                "clip.bvh:36: expected a positive frame time, found -0.01",
            ),
            (
                small_with("Frame Time: 0.0333333", "Frame Time: NaN"),
                "clip.bvh:36: expected a finite frame time, found \"NaN\"",
            ),
            (
                small_with("Frame Time: 0.0333333", "Frame Time: 30fps"),
                "clip.bvh:36: expected a frame time in seconds such as 0.0333333, found \"30fps\"",
            ),
            (
                small_with("Frame Time: 0.0333333", "Frame Time: 0.0333333 s"),
                "clip.bvh:36: expected the end of the line after the frame time, found \"s\"",
            ),
            (
                small_with("1.5 35.25 -2 10", "1.5 35.25 abc 10"),
                "clip.bvh:38: value 3 (joint \"Hips\", Zposition): expected a number, found \"abc\"",
            ),
            (
                small_with("1.5 35.25 -2 10 20 30 -5", "1.5 35.25 -2 10 20 30 inf"),
                "clip.bvh:38: value 7 (joint \"Chest\", Zrotation): expected a finite number, found \"inf\"",
            ),
            (
                small_with(" 11 12\n-0.0000", " 11\n-0.0000"),
                "clip.bvh:38: expected 18 values (one per channel), found 17",
            ),
            (
                small_with(" 11 12\n-0.0000", " 11 12 13 14\n-0.0000"),
                "clip.bvh:38: expected 18 values (one per channel), found 20",
            ),
            (
                SMALL
                    .replace(
                        "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation",
                        "CHANNELS 0",
                    )
                    .replace("CHANNELS 3 Zrotation Yrotation Xrotation", "CHANNELS 0")
                    .replace("CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 0")
                    .replace(
                        "CHANNELS 6 Zrotation Xposition Yrotation Yposition Xrotation Zposition",
                        "CHANNELS 0",
                    ),
                "clip.bvh:34: expected at least one channel in the hierarchy, found none",
            ),
        ];
        let wrong: Vec<String> = cases
            .iter()
            .filter(|(text, want)| parse_err(text) != *want)
            .map(|(text, want)| format!("want {want}\ngot  {}", parse_err(text)))
            .collect();
        assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    }

    #[test]
    fn long_or_control_text_in_messages_is_shortened_and_escaped() {
        let long = "x".repeat(100);
        let text = small_with("OFFSET 0.0 0.0 0.0", &format!("OFFSET 0.0 {long} 0.0"));
        assert_eq!(
            parse_err(&text),
            format!(
                "clip.bvh:4: expected a number for OFFSET, found \"{}…\"",
                "x".repeat(60)
            )
        );
        let text = small_with("OFFSET 0.0 0.0 0.0", "OFFSET 0.0 \u{1b}[31m 0.0");
        assert_eq!(
            parse_err(&text),
            "clip.bvh:4: expected a number for OFFSET, found \"\\u{1b}[31m\""
        );
    }

    #[test]
    fn deep_nesting_does_not_exhaust_the_stack() {
        let depth = 200_000;
        let mut text = String::from("HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n");
        for i in 0..depth {
            text.push_str(&format!("JOINT j{i}\n{{\nOFFSET 0 0 0\n"));
        }
        text.push_str(&"}\n".repeat(depth + 1));
        text.push_str("MOTION\nFrames: 1\nFrame Time: 0.01\n5\n");
        let (clip, _) = parse_ok(&text);
        assert_eq!(clip.joints().len(), depth + 1);
        assert_eq!(clip.joints()[depth].parent(), Some(depth - 1));
        // Unclosed: an error, not a crash.
        let cut = text.find("}\n").unwrap();
        assert!(parse_err(&text[..cut]).ends_with("found the end of the file"));
    }

    /// A batch worker's small stack (256 KiB) reads a 20 000-deep chain and writes it back.
    #[test]
    fn a_deep_chain_reads_and_writes_on_a_small_stack() {
        let depth = 20_000;
        let mut text = String::from("HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n");
        for i in 0..depth {
            text.push_str(&format!(
                "JOINT j{i}\n{{\nOFFSET 0 1 0\nCHANNELS 1 Zrotation\n"
            ));
        }
        text.push_str(&"}\n".repeat(depth + 1));
        text.push_str("MOTION\nFrames: 1\nFrame Time: 0.01\n");
        text.push_str(&"5 ".repeat(depth + 1));
        text.push('\n');
        let joints = std::thread::Builder::new()
            .stack_size(256 << 10)
            .spawn(move || {
                let (clip, _) = parse_ok(&text);
                let mut out = Vec::new();
                crate::bvh::write(
                    &mut out,
                    clip.hierarchy(),
                    clip.fps(),
                    clip.channel_count(),
                    clip.values(),
                )
                .unwrap();
                let (back, _) = parse_ok(std::str::from_utf8(&out).unwrap());
                assert_eq!(back.values(), clip.values());
                back.joints().len()
            })
            .unwrap()
            .join()
            .unwrap();
        assert_eq!(joints, depth + 1);
    }

    /// A reader that hands out at most `n` bytes at a time.
    struct Trickle<'a>(&'a [u8], usize);

    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let n = self.1.min(buf.len()).min(self.0.len());
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    #[test]
    fn reading_in_pieces_is_parsing_the_text() {
        // Read at run time from the repository (not include_str!: the crate's package has no
        // fixtures/, and its build must not need them).
        let fixture = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../fixtures/bvh/mixed_orders.bvh"
        ))
        .unwrap();
        let fixture = fixture.as_str();
        let texts = [
            SMALL.to_string(),
            format!("\u{feff}{}", SMALL.replace('\n', "\r\n")),
            SMALL.replace("Frames: 3", "Frames: 7") + "\n\n",
            SMALL.trim_end().to_string(),
            fixture.to_string(),
            // "Frame Time:" in a joint's name, and spaced apart for the parser.
            SMALL
                .replace("JOINT Marker", "JOINT Frame Time: x")
                .replace("Frame Time: 0.0333333", "Frame   Time: 0.0333333"),
        ];
        for text in &texts {
            let want = parse(text, "clip.bvh").unwrap();
            for n in [1, 2, 7, 64, 1 << 20] {
                let got = parse_reader(Trickle(text.as_bytes(), n), "clip.bvh", None).unwrap();
                assert_eq!(got, want, "pieces of {n}");
                let len = Some(text.len() as u64);
                let got = parse_reader(Trickle(text.as_bytes(), n), "clip.bvh", len).unwrap();
                assert_eq!(got, want, "pieces of {n}");
            }
        }
        // Errors name the same line.
        for (from, to) in [
            ("1.5 35.25 -2 10", "1.5 35.25 abc 10"),
            (" 11 12\n-0.0000", " 11\n-0.0000"),
            ("OFFSET 0.0 0.0 0.0", "OFFSET 0.0 abc 0.0"),
            ("Frame Time: 0.0333333", "Frame Time: 0"),
        ] {
            let text = small_with(from, to);
            let want = parse_err(&text);
            for n in [1, 5, 1 << 20] {
                let got = parse_reader(Trickle(text.as_bytes(), n), "clip.bvh", None)
                    .unwrap_err()
                    .to_string();
                assert_eq!(got, want);
            }
        }
        let mut bad = SMALL.as_bytes().to_vec();
        let at = SMALL.find("-0.0000").unwrap();
        bad[at] = 0xff;
        let got = parse_reader(Trickle(&bad, 3), "clip.bvh", None).unwrap_err();
        assert_eq!(
            got.to_string(),
            format!("clip.bvh: expected UTF-8 text, found an invalid byte at offset {at}")
        );
    }

    #[test]
    fn motion_values_are_read_as_str_parse_reads_them() {
        for s in [
            "0",
            "-0",
            "-0.000000",
            "+5",
            "5.",
            ".5",
            "-.5",
            "12.345678",
            "-179.999999",
            "123456789012345",
            "1234567890123456",
            "0.1",
            "0.3",
            "1e5",
            "-2.5E-3",
            "007.5",
            "99999999999999.9",
            "0.000000000000001",
        ] {
            let want: f64 = s.parse().unwrap();
            let got = motion_value(s).unwrap();
            assert_eq!(got.to_bits(), want.to_bits(), "{s}");
        }
        for s in ["", "-", ".", "+", "1.2.3", "1e", "abc", "1,5", "--1"] {
            assert_eq!(motion_value(s), Err(false), "{s}");
        }
        for s in ["inf", "-inf", "NaN", "1e999"] {
            assert_eq!(motion_value(s), Err(true), "{s}");
        }
    }

    #[test]
    fn a_huge_declared_frame_count_does_not_allocate_for_it() {
        let text = small_with("Frames: 3", "Frames: 18446744073709551615");
        let (clip, warnings) = parse_ok(&text);
        assert_eq!(clip.frame_count(), 3);
        assert_eq!(warnings.len(), 1);
    }

    /// Found by the `bvh_reader` fuzz target: a frame time with a vertical tab after it (part of
    /// the token, trimmed by the rate's reader) panicked on a second parse.
    #[test]
    fn a_frame_time_followed_by_a_vertical_tab_is_read() {
        let text = SMALL.replacen("Frame Time: 0.0333333", "Frame Time: 0.0333333\u{b}", 1);
        assert!(text.contains('\u{b}'));
        let (clip, _) = parse_ok(&text);
        assert_eq!(clip.frame_time(), 0.0333333);
    }
}
