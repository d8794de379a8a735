//! Writers: frames (from `interp`) and keys (from `convert`) as CSV or JSON bytes.
//!
//! Writers only turn values into bytes on a [`Write`]; they stream (a frame is formatted and
//! handed on as it comes, through a small buffer) and never look at the file system.
//!
//! ```text
//! CSV frames:  [track,]frame,time,<rotation columns>
//! JSON frames: {"fps": 30, "rotation": "quat", "tracks": [
//!              {"name": "hip", "frames": [
//!              {"frame": 0, "time": 0.0, "quat": [1.0, 0.0, 0.0, 0.0]},
//!              ...]}]}
//! ```
//! One frame per line in JSON too, so that outputs diff well. `"angles"` is written when the
//! representation has angles; `"name"` when the track has one.

use super::Format;
use super::num::{NumFormat, NumWriter};
use crate::clock::Fps;
use crate::keys::{Document, KeyTime};
use crate::rotation::{AngleUnit, MAX_WIDTH, QuatOrder, Repr};
use glam::{DQuat, DVec3};
use std::io::{self, Write};

/// How rotations and numbers are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Style {
    pub repr: Repr,
    pub angles: AngleUnit,
    pub quat_order: QuatOrder,
    pub num: NumFormat,
}

/// Formats one rotation's values (CSV: comma-separated; JSON: an array) into `out`.
#[derive(Clone)]
struct RotationFormatter {
    style: Style,
    nums: NumWriter,
    vals: [f64; MAX_WIDTH],
}

impl RotationFormatter {
    fn new(style: Style) -> Self {
        RotationFormatter {
            style,
            nums: NumWriter::new(style.num),
            vals: [0.0; MAX_WIDTH],
        }
    }

    #[inline]
    fn values(&mut self, q: DQuat) -> &[f64] {
        let repr = self.style.repr;
        repr.from_quat(q, self.style.angles, &mut self.vals);
        let w = repr.width();
        if repr == Repr::Quat {
            let o = self.style.quat_order.from_wxyz([
                self.vals[0],
                self.vals[1],
                self.vals[2],
                self.vals[3],
            ]);
            self.vals[..4].copy_from_slice(&o);
        }
        &self.vals[..w]
    }

    #[inline]
    fn csv(&mut self, out: &mut Vec<u8>, q: DQuat) {
        // CSV columns are named, so quaternions are always w,x,y,z.
        let repr = self.style.repr;
        repr.from_quat(q, self.style.angles, &mut self.vals);
        for i in 0..repr.width() {
            out.push(b',');
            self.nums.float(out, self.vals[i]);
        }
    }

    fn json(&mut self, out: &mut Vec<u8>, q: DQuat) {
        let key = self.style.repr.json_key();
        let mut vals = [0.0; MAX_WIDTH];
        let n = {
            let v = self.values(q);
            vals[..v.len()].copy_from_slice(v);
            v.len()
        };
        out.extend_from_slice(b"\"");
        out.extend_from_slice(key.as_bytes());
        out.extend_from_slice(b"\": [");
        if self.style.repr == Repr::Matrix {
            for r in 0..3 {
                out.extend_from_slice(if r == 0 { b"[" } else { b", [" });
                for c in 0..3 {
                    if c > 0 {
                        out.extend_from_slice(b", ");
                    }
                    self.nums.float(out, vals[3 * r + c]);
                }
                out.push(b']');
            }
        } else {
            for (i, v) in vals[..n].iter().enumerate() {
                if i > 0 {
                    out.extend_from_slice(b", ");
                }
                self.nums.float(out, *v);
            }
        }
        out.push(b']');
    }
}

fn json_string(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".to_string())
}

/// Document-level JSON header fields shared by frames and keys output. `"angles"` is written
/// when any angle is (an angle representation, or velocities when `velocity`).
fn json_head(out: &mut Vec<u8>, fps: Option<Fps>, style: &Style, velocity: bool) {
    out.push(b'{');
    if let Some(fps) = fps {
        if fps.den() == 1 {
            out.extend_from_slice(format!("\"fps\": {}, ", fps.num()).as_bytes());
        } else {
            out.extend_from_slice(format!("\"fps\": \"{fps}\", ").as_bytes());
        }
    }
    out.extend_from_slice(format!("\"rotation\": \"{}\"", style.repr).as_bytes());
    if style.repr.has_angles() || velocity {
        out.extend_from_slice(format!(", \"angles\": \"{}\"", style.angles.as_str()).as_bytes());
    }
}

const FLUSH_AT: usize = 1 << 15;

/// Receives the frames of `interp`, track by track.
pub trait FrameSink {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()>;
    /// One frame; `omega` is the world-frame angular velocity in rad/s when it was asked for.
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()>;
    fn end_track(&mut self) -> io::Result<()>;
    /// Writes what closes the document and flushes the buffer to the writer.
    fn finish(&mut self) -> io::Result<()>;
}

/// One frame waiting to be formatted.
#[derive(Debug, Clone, Copy)]
struct Frame {
    k: i64,
    time: f64,
    q: DQuat,
    omega: Option<DVec3>,
}

/// Frames per block; blocks alternate between this thread and the formatting worker.
const BLOCK: usize = 4096;

/// Turns frames into CSV rows or JSON objects (one per line). Owned by the writer and cloned
/// into the worker thread.
#[derive(Clone)]
struct RowFormatter {
    format: Format,
    rot: RotationFormatter,
    nums: NumWriter,
    track_column: bool,
    velocity: bool,
    angles: AngleUnit,
}

impl RowFormatter {
    /// Appends `frames`, the first being frame number `start` of its track; `track` is the CSV
    /// row prefix (`name,`).
    fn rows(&mut self, out: &mut Vec<u8>, track: &[u8], start: usize, frames: &[Frame]) {
        for (i, f) in frames.iter().enumerate() {
            let omega = if self.velocity {
                f.omega
                    .map(|w| w.to_array().map(|x| self.angles.from_rad(x)))
            } else {
                None
            };
            match self.format {
                Format::Csv => {
                    if self.track_column {
                        out.extend_from_slice(track);
                    }
                    self.nums.int(out, f.k);
                    out.push(b',');
                    self.nums.float(out, f.time);
                    self.rot.csv(out, f.q);
                    if let Some(w) = omega {
                        for x in w {
                            out.push(b',');
                            self.nums.float(out, x);
                        }
                    }
                    out.push(b'\n');
                }
                Format::Json => {
                    out.extend_from_slice(if start + i == 0 {
                        b"\n{\"frame\": "
                    } else {
                        b",\n{\"frame\": "
                    });
                    self.nums.int(out, f.k);
                    out.extend_from_slice(b", \"time\": ");
                    self.nums.float(out, f.time);
                    out.extend_from_slice(b", ");
                    self.rot.json(out, f.q);
                    if let Some(w) = omega {
                        out.extend_from_slice(b", \"angular_velocity\": [");
                        for (j, x) in w.iter().enumerate() {
                            if j > 0 {
                                out.extend_from_slice(b", ");
                            }
                            self.nums.float(out, *x);
                        }
                        out.push(b']');
                    }
                    out.push(b'}');
                }
            }
        }
    }
}

/// A block sent to the worker: frames, CSV track prefix, index of the first frame in its track;
/// a buffer to format into comes along and goes back with the result.
type Job = (Vec<Frame>, Vec<u8>, usize, Vec<u8>);

/// The formatting thread: formats the blocks it is sent, in order.
struct Worker {
    jobs: std::sync::mpsc::Sender<Job>,
    done: std::sync::mpsc::Receiver<(Vec<u8>, Vec<Frame>)>,
    handle: Option<std::thread::JoinHandle<()>>,
}

impl Worker {
    fn spawn(mut rows: RowFormatter) -> Worker {
        let (jobs, inbox) = std::sync::mpsc::channel::<Job>();
        let (outbox, done) = std::sync::mpsc::channel();
        let handle = std::thread::spawn(move || {
            for (frames, track, start, mut out) in inbox {
                out.clear();
                rows.rows(&mut out, &track, start, &frames);
                if outbox.send((out, frames)).is_err() {
                    break;
                }
            }
        });
        Worker {
            jobs,
            done,
            handle: Some(handle),
        }
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // Closing the job channel ends the thread.
        let (closed, _) = std::sync::mpsc::channel();
        drop(std::mem::replace(&mut self.jobs, closed));
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

fn worker_gone() -> io::Error {
    io::Error::other("the formatting thread stopped")
}

/// Writes frames as CSV or JSON.
///
/// With two or more cores, once a track has more than one block of frames, alternate blocks of
/// 4096 frames are formatted by a second thread while this one computes and formats the next;
/// blocks are written in order, so the bytes are those of the sequential writer (tested).
pub struct FrameWriter<W: Write> {
    w: W,
    buf: Vec<u8>,
    format: Format,
    rows: RowFormatter,
    track: Vec<u8>,
    tracks_written: usize,
    /// Frames of the current track formatted or queued so far.
    frames_in_track: usize,
    block: Vec<Frame>,
    parallel: bool,
    worker: Option<Worker>,
    /// The worker holds a block whose bytes are not written yet.
    in_flight: bool,
    /// Buffers kept for reuse: blocks are large, and a fresh allocation each time costs page
    /// faults (they are above malloc's mmap threshold).
    spare: Vec<u8>,
    scratch: Vec<u8>,
    recycled: Vec<Frame>,
}

impl<W: Write> FrameWriter<W> {
    /// `track_column`: write the CSV `track` column (several tracks, or the input named them);
    /// `velocity`: write angular velocity columns `wx,wy,wz` (JSON `"angular_velocity"`).
    pub fn new(
        w: W,
        format: Format,
        style: Style,
        fps: Fps,
        track_column: bool,
        velocity: bool,
    ) -> Self {
        let mut buf = Vec::with_capacity(FLUSH_AT + 1024);
        match format {
            Format::Csv => {
                if track_column {
                    buf.extend_from_slice(b"track,");
                }
                buf.extend_from_slice(b"frame,time");
                for c in style.repr.columns() {
                    buf.push(b',');
                    buf.extend_from_slice(c.as_bytes());
                }
                if velocity {
                    buf.extend_from_slice(b",wx,wy,wz");
                }
                buf.push(b'\n');
            }
            Format::Json => {
                json_head(&mut buf, Some(fps), &style, velocity);
                buf.extend_from_slice(b", \"tracks\": [\n");
            }
        }
        let parallel = std::thread::available_parallelism().is_ok_and(|n| n.get() >= 2);
        FrameWriter {
            w,
            buf,
            format,
            rows: RowFormatter {
                format,
                rot: RotationFormatter::new(style),
                nums: NumWriter::new(style.num),
                track_column,
                velocity,
                angles: style.angles,
            },
            track: Vec::new(),
            tracks_written: 0,
            frames_in_track: 0,
            block: Vec::with_capacity(BLOCK),
            parallel,
            worker: None,
            in_flight: false,
            spare: Vec::new(),
            scratch: Vec::new(),
            recycled: Vec::new(),
        }
    }

    /// Formats everything in this thread (for comparison with the parallel writer).
    pub fn sequential(mut self) -> Self {
        self.parallel = false;
        self
    }

    #[inline]
    fn maybe_flush(&mut self) -> io::Result<()> {
        if self.buf.len() >= FLUSH_AT {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    /// Writes the worker's block, if it holds one.
    fn collect(&mut self) -> io::Result<()> {
        if self.in_flight {
            let worker = self.worker.as_ref().ok_or_else(worker_gone)?;
            let (bytes, mut frames) = worker.done.recv().map_err(|_| worker_gone())?;
            self.in_flight = false;
            self.w.write_all(&self.buf)?;
            self.buf.clear();
            self.w.write_all(&bytes)?;
            self.spare = bytes;
            frames.clear();
            self.recycled = frames;
        }
        Ok(())
    }

    /// Formats the pending block: hands it to the worker when it is free, else formats it here
    /// and writes it after the worker's.
    fn flush_block(&mut self, full: bool) -> io::Result<()> {
        if self.block.is_empty() {
            return self.collect();
        }
        let start = self.frames_in_track;
        self.frames_in_track += self.block.len();
        if full && self.parallel && !self.in_flight {
            if self.worker.is_none() {
                self.worker = Some(Worker::spawn(self.rows.clone()));
            }
            let worker = self.worker.as_ref().ok_or_else(worker_gone)?;
            let mut next = std::mem::take(&mut self.recycled);
            next.reserve(BLOCK);
            let frames = std::mem::replace(&mut self.block, next);
            let out = std::mem::take(&mut self.spare);
            worker
                .jobs
                .send((frames, self.track.clone(), start, out))
                .map_err(|_| worker_gone())?;
            self.in_flight = true;
            // Everything before the worker's block must reach the writer first.
            self.w.write_all(&self.buf)?;
            self.buf.clear();
            return Ok(());
        }
        if !self.in_flight {
            // Nothing to overlap with: format straight into the output buffer.
            self.rows
                .rows(&mut self.buf, &self.track, start, &self.block);
            self.block.clear();
            return self.maybe_flush();
        }
        // Format this block while the worker formats the previous one, then write both in order.
        self.scratch.clear();
        self.rows
            .rows(&mut self.scratch, &self.track, start, &self.block);
        self.block.clear();
        self.collect()?;
        self.w.write_all(&self.scratch)?;
        Ok(())
    }

    /// The writer, after [`FrameSink::finish`] (the worker thread, if any, ends).
    pub fn into_inner(self) -> W {
        self.w
    }
}

/// CSV field quoting for track names (RFC 4180: quote when needed, double inner quotes).
fn csv_field(s: &str) -> Vec<u8> {
    if s.contains([',', '"', '\n', '\r']) || s.trim() != s {
        format!("\"{}\"", s.replace('"', "\"\"")).into_bytes()
    } else {
        s.as_bytes().to_vec()
    }
}

impl<W: Write> FrameSink for FrameWriter<W> {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()> {
        self.frames_in_track = 0;
        match self.format {
            Format::Csv => {
                self.track = csv_field(name.unwrap_or(""));
                self.track.push(b',');
            }
            Format::Json => {
                if self.tracks_written > 0 {
                    self.buf.extend_from_slice(b",\n");
                }
                self.buf.push(b'{');
                if let Some(n) = name {
                    self.buf
                        .extend_from_slice(format!("\"name\": {}, ", json_string(n)).as_bytes());
                }
                self.buf.extend_from_slice(b"\"frames\": [");
            }
        }
        self.tracks_written += 1;
        Ok(())
    }

    #[inline]
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        self.block.push(Frame { k, time, q, omega });
        if self.block.len() == BLOCK {
            self.flush_block(true)?;
        }
        Ok(())
    }

    fn end_track(&mut self) -> io::Result<()> {
        self.flush_block(false)?;
        self.collect()?;
        if self.format == Format::Json {
            self.buf.extend_from_slice(b"\n]}");
        }
        self.maybe_flush()
    }

    fn finish(&mut self) -> io::Result<()> {
        self.flush_block(false)?;
        self.collect()?;
        if self.format == Format::Json {
            self.buf.extend_from_slice(b"\n]}\n");
        }
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        self.w.flush()
    }
}

/// Writes a key's time, or its frame number (as an integer when it is whole).
fn when_value(nums: &mut NumWriter, buf: &mut Vec<u8>, x: f64, frame: bool) {
    if frame && x.fract() == 0.0 && x.abs() < 9.007_199_254_740_992e15 {
        nums.int(buf, x as i64);
    } else {
        nums.float(buf, x);
    }
}

/// Writes a document's keys (for `convert`) in the input shape of SPEC §3, so that the output is
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::num::NumFormat;
    use crate::rotation::{EulerSeq, QuatOrder};

    /// Writes tracks of the given lengths with both writers.
    fn both(format: Format, style: Style, lengths: &[usize], velocity: bool) -> (Vec<u8>, Vec<u8>) {
        let fps = Fps::new(30, 1).unwrap();
        let write = |w: &mut FrameWriter<Vec<u8>>| {
            for (ti, &n) in lengths.iter().enumerate() {
                w.begin_track(Some(&format!("t{ti}"))).unwrap();
                for k in 0..n as i64 {
                    let t = k as f64 / 30.0;
                    let q = DQuat::from_euler(glam::EulerRot::ZYX, t, 0.3 * t + ti as f64, -t);
                    w.frame(k, t, q, Some(DVec3::new(t, -t, 0.5))).unwrap();
                }
                w.end_track().unwrap();
            }
            w.finish().unwrap();
        };
        let mut par = FrameWriter::new(Vec::new(), format, style, fps, true, velocity);
        assert!(par.parallel || std::thread::available_parallelism().map_or(1, |n| n.get()) < 2);
        write(&mut par);
        let mut seq = FrameWriter::new(Vec::new(), format, style, fps, true, velocity).sequential();
        write(&mut seq);
        (par.into_inner(), seq.into_inner())
    }

    #[test]
    fn parallel_formatting_gives_the_sequential_bytes() {
        let lengths = [0, 1, BLOCK - 1, BLOCK, BLOCK + 1, 3 * BLOCK + 17, 2 * BLOCK];
        let styles = [
            Style {
                repr: Repr::Quat,
                angles: AngleUnit::Deg,
                quat_order: QuatOrder::Wxyz,
                num: NumFormat::Shortest,
            },
            Style {
                repr: Repr::Euler(EulerSeq::parse("zyx").unwrap()),
                angles: AngleUnit::Rad,
                quat_order: QuatOrder::Xyzw,
                num: NumFormat::Fixed(9),
            },
        ];
        for format in [Format::Csv, Format::Json] {
            for style in styles {
                for velocity in [false, true] {
                    let (par, seq) = both(format, style, &lengths, velocity);
                    assert!(par.len() > 100_000);
                    assert!(
                        par == seq,
                        "{format:?} {:?} velocity {velocity}",
                        style.repr
                    );
                }
            }
        }
    }
}
