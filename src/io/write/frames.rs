//! [`FrameWriter`]: frames as CSV rows or JSON objects, one per line.

use super::columns::RotationFormatter;
use super::num::NumWriter;
use super::worker::{Worker, worker_gone};
use super::{Style, csv_field, json_head, json_string};
use crate::bake::FrameSink;
use crate::clock::Fps;
use crate::io::Format;
use crate::rotation::AngleUnit;
use glam::{DQuat, DVec3};
use std::io::{self, Write};

const FLUSH_AT: usize = 1 << 15;

/// One frame waiting to be formatted.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
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
pub(super) struct RowFormatter {
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
    pub(super) fn rows(&mut self, out: &mut Vec<u8>, track: &[u8], start: usize, frames: &[Frame]) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::write::num::NumFormat;
    use crate::rotation::Repr;
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
