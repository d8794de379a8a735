//! [`FrameWriter`]: frames as CSV rows or JSON objects, one per line.

use super::columns::RotationFormatter;
use super::rows::{Fault, Frame, RowFormatter};
use super::worker::{Worker, worker_gone};
use super::{Style, csv_field, internal_error, json_head, json_string};
use crate::Format;
use crate::num::NumWriter;
use glam::{DQuat, DVec3};
use inbetween::bake::FrameSink;
use inbetween::clock::Fps;
use std::io::{self, Write};

const FLUSH_AT: usize = 1 << 15;

/// Frames per block; blocks alternate between this thread and the formatting worker.
const BLOCK: usize = 4096;

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
    /// The current track's name, for error messages.
    track_name: Option<String>,
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
    /// The style, for a new track's continuous-Euler state.
    style: Style,
    /// Continuous Euler angles along the current track (Euler output, `EulerMode::Continuous`).
    unwrap: Option<inbetween::rotation::unwrap::EulerUnwrap>,
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
        // BVH is written by `io::bvh` on its skeleton; the commands never route it here.
        debug_assert!(format != Format::Bvh, "FrameWriter writes CSV or JSON");
        let format = if format == Format::Json {
            Format::Json
        } else {
            Format::Csv
        };
        let mut buf = Vec::with_capacity(FLUSH_AT + 1024);
        match format {
            Format::Json => {
                json_head(&mut buf, Some(fps), &style, velocity);
                buf.extend_from_slice(b", \"tracks\": [\n");
            }
            // Every other format is written here as CSV (the writers write CSV or JSON).
            _ => {
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
                positions: false,
            },
            track: Vec::new(),
            track_name: None,
            tracks_written: 0,
            frames_in_track: 0,
            block: Vec::with_capacity(BLOCK),
            parallel,
            worker: None,
            in_flight: false,
            spare: Vec::new(),
            scratch: Vec::new(),
            recycled: Vec::new(),
            style,
            unwrap: None,
        }
    }

    /// Writes positions too (tracks with translations): CSV columns `tx,ty,tz` after the others
    /// (empty cells for a track without), JSON `"translation": [x, y, z]`. Call before the first
    /// track.
    pub fn with_positions(mut self) -> Self {
        if self.format == Format::Csv && !self.rows.positions {
            let nl = self.buf.len() - 1;
            debug_assert_eq!(self.buf[nl], b'\n', "called before any row");
            self.buf.truncate(nl);
            self.buf.extend_from_slice(b",tx,ty,tz\n");
        }
        self.rows.positions = true;
        self
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

    /// The error for a frame of the current track that must not be written.
    #[cold]
    fn refuse(&self, (k, bad): Fault) -> io::Error {
        let index = self.tracks_written.saturating_sub(1);
        internal_error(
            &format!("frame {k}"),
            self.track_name.as_deref(),
            index,
            bad,
        )
    }

    /// Writes the worker's block, if it holds one.
    fn collect(&mut self) -> io::Result<()> {
        if self.in_flight {
            let worker = self.worker.as_ref().ok_or_else(worker_gone)?;
            let (bytes, mut frames, result) = worker.done.recv().map_err(|_| worker_gone())?;
            self.in_flight = false;
            if let Err(fault) = result {
                return Err(self.refuse(fault));
            }
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
            let before = self.buf.len();
            let result = self
                .rows
                .rows(&mut self.buf, &self.track, start, &self.block);
            self.block.clear();
            if let Err(fault) = result {
                self.buf.truncate(before);
                return Err(self.refuse(fault));
            }
            return self.maybe_flush();
        }
        // Format this block while the worker formats the previous one, then write both in order.
        self.scratch.clear();
        let result = self
            .rows
            .rows(&mut self.scratch, &self.track, start, &self.block);
        self.block.clear();
        self.collect()?;
        if let Err(fault) = result {
            self.scratch.clear();
            return Err(self.refuse(fault));
        }
        self.w.write_all(&self.scratch)?;
        Ok(())
    }

    /// The writer, after [`FrameSink::finish`] (the worker thread, if any, ends).
    pub fn into_inner(self) -> W {
        self.w
    }
}

impl<W: Write> FrameWriter<W> {
    #[inline]
    fn push(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: Option<DVec3>,
    ) -> io::Result<()> {
        let euler = self.unwrap.as_mut().map(|u| u.next(q));
        self.block.push(Frame {
            k,
            time,
            q,
            omega,
            euler,
            position,
        });
        if self.block.len() == BLOCK {
            self.flush_block(true)?;
        }
        Ok(())
    }
}

impl<W: Write> FrameSink for FrameWriter<W> {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()> {
        self.unwrap = self.style.unwrapper();
        self.frames_in_track = 0;
        self.track_name = name.map(str::to_string);
        match self.format {
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
            // Every other format is written here as CSV (the writers write CSV or JSON).
            _ => {
                self.track = csv_field(name.unwrap_or(""));
                self.track.push(b',');
            }
        }
        self.tracks_written += 1;
        Ok(())
    }

    fn euler_start(&mut self, seq: crate::EulerSeq, angles: [f64; 3]) {
        self.unwrap = self.style.unwrapper_from(seq, angles);
    }

    #[inline]
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        self.push(k, time, q, omega, None)
    }

    #[inline]
    fn frame_at(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: DVec3,
    ) -> io::Result<()> {
        self.push(k, time, q, omega, Some(position))
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
    use crate::num::NumFormat;
    use inbetween::rotation::{AngleUnit, Repr};
    use inbetween::rotation::{EulerSeq, QuatOrder};

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

    fn quat_style(num: NumFormat) -> Style {
        Style {
            repr: Repr::Quat,
            angles: AngleUnit::Deg,
            quat_order: QuatOrder::Wxyz,
            num,
            euler: Default::default(),
        }
    }

    /// Writes one track named `name` of `n` frames at 30 fps, frame `bad` replaced by `frame`;
    /// returns the bytes that reached the output and the error.
    fn write_with_bad_frame(
        format: Format,
        parallel: bool,
        name: Option<&str>,
        n: usize,
        bad: usize,
        frame: (f64, DQuat, Option<DVec3>),
    ) -> (Vec<u8>, io::Error) {
        let fps = Fps::new(30, 1).unwrap();
        let style = quat_style(NumFormat::Shortest);
        let mut w = FrameWriter::new(Vec::new(), format, style, fps, false, true);
        if !parallel {
            w = w.sequential();
        }
        let mut result = w.begin_track(name);
        for k in 0..n {
            if result.is_err() {
                break;
            }
            let (t, q, omega) = if k == bad {
                frame
            } else {
                (k as f64 / 30.0, DQuat::IDENTITY, Some(DVec3::ZERO))
            };
            result = w.frame(k as i64, t, q, omega);
        }
        let result = result
            .and_then(|()| w.end_track())
            .and_then(|()| w.finish());
        let err = result.expect_err("a bad frame is an error");
        (w.into_inner(), err)
    }

    #[test]
    fn non_finite_values_are_refused_not_written() {
        let nan_q = DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0);
        let cases = [
            (
                (f64::NAN, DQuat::IDENTITY, Some(DVec3::ZERO)),
                "internal error: non-finite value in frame 7 of track \"hip\" (\"time\" = NaN)",
            ),
            (
                (0.2, nan_q, Some(DVec3::ZERO)),
                "internal error: non-finite value in frame 7 of track \"hip\" (\"x\" = NaN)",
            ),
            (
                (0.2, DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0), Some(DVec3::ZERO)),
                "internal error: zero or non-unit quaternion in frame 7 of track \"hip\" (norm 0)",
            ),
            (
                // Finite in rad/s, infinite in deg/s.
                (0.2, DQuat::IDENTITY, Some(DVec3::new(0.0, 1e307, 0.0))),
                "internal error: non-finite value in frame 7 of track \"hip\" (\"wy\" = inf)",
            ),
            (
                (0.2, DQuat::IDENTITY, None),
                "internal error: no angular velocity in frame 7 of track \"hip\"",
            ),
        ];
        for format in [Format::Csv, Format::Json] {
            for (frame, want) in cases {
                let (out, err) = write_with_bad_frame(format, false, Some("hip"), 10, 7, frame);
                assert_eq!(err.kind(), io::ErrorKind::InvalidData);
                assert_eq!(err.to_string(), want, "{format:?}");
                let text = String::from_utf8(out).unwrap();
                assert!(!text.contains("NaN") && !text.contains("inf"), "{text}");
            }
        }
        // An unnamed track is named by its index.
        let (_, err) = write_with_bad_frame(
            Format::Csv,
            false,
            None,
            3,
            0,
            (0.0, nan_q, Some(DVec3::ZERO)),
        );
        assert_eq!(
            err.to_string(),
            "internal error: non-finite value in frame 0 of track 0 (\"x\" = NaN)"
        );
    }

    #[test]
    fn a_bad_frame_in_a_block_of_the_formatting_thread_is_refused() {
        // Frame 2·BLOCK + 5 is in the third block: formatted by the worker thread when there are
        // two cores, here otherwise.
        let bad = 2 * BLOCK + 5;
        for format in [Format::Csv, Format::Json] {
            let (out, err) = write_with_bad_frame(
                format,
                true,
                Some("arm"),
                4 * BLOCK,
                bad,
                (f64::INFINITY, DQuat::IDENTITY, Some(DVec3::ZERO)),
            );
            assert_eq!(
                err.to_string(),
                format!(
                    "internal error: non-finite value in frame {bad} of track \"arm\" (\"time\" = inf)"
                )
            );
            let text = String::from_utf8(out).unwrap();
            assert!(!text.contains("inf"));
        }
    }

    #[test]
    fn times_are_shortest_whatever_the_precision() {
        let fps = Fps::new(30, 1).unwrap();
        // `--precision 1` used to write the time 1/30 as 0.0, and x = −1e-9 as -0.0.
        for (format, want) in [
            (Format::Csv, "1,0.03333333333333333,-1.0,0.0,0.0,0.0\n"),
            (
                Format::Json,
                "{\"frame\": 1, \"time\": 0.03333333333333333, \"quat\": [-1.0, 0.0, 0.0, 0.0]}",
            ),
        ] {
            let style = quat_style(NumFormat::Fixed(1));
            let mut w = FrameWriter::new(Vec::new(), format, style, fps, false, false);
            w.begin_track(None).unwrap();
            w.frame(1, 1.0 / 30.0, DQuat::from_xyzw(-1e-9, 0.0, 0.0, -1.0), None)
                .unwrap();
            w.end_track().unwrap();
            w.finish().unwrap();
            let text = String::from_utf8(w.into_inner()).unwrap();
            assert!(text.contains(want), "{format:?}: {text}");
        }
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
                euler: Default::default(),
            },
            Style {
                repr: Repr::Euler(EulerSeq::parse("zyx").unwrap()),
                angles: AngleUnit::Rad,
                quat_order: QuatOrder::Xyzw,
                num: NumFormat::Fixed(9),
                euler: Default::default(),
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
