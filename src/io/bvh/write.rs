//! The BVH writer: a hierarchy text, a rate and rows of values → a BVH file.
//!
//! ```text
//! <the hierarchy text exactly as given>      (a line end is added only if it lacks one)
//! MOTION
//! Frames: <rows>
//! Frame Time: <rate::frame_time_text(fps)>    0.01, 0.0125, 0.0333333333
//! <values of row 0, one space apart>          shortest digits that read back to the same f64
//! ...
//! ```
//!
//! Numbers are the shortest decimal that reads back as the same f64 (integers without `.0`,
//! −0 as `0`); lines end in `\n`. The writer streams: [`BvhWriter`] takes one row at a time
//! and buffers at most about 64 KiB. Like the other writers, it never writes a non-finite
//! value: it fails with an [`io::Error`] of kind `InvalidData` (`internal error: …`) instead.

use super::rate::frame_time_text;
use crate::clock::Fps;
use crate::io::write::num::NumWriter;
use std::io::{self, Write};

const FLUSH_AT: usize = 64 * 1024;

/// Writes a BVH file row by row: the header when made, then [`BvhWriter::row`] for each of the
/// `frames` rows announced in it, then [`BvhWriter::finish`] (which flushes; dropping the
/// writer without it loses the buffered rows).
///
/// ```
/// use inbetween::Fps;
/// use inbetween::io::bvh::BvhWriter;
///
/// let hierarchy = "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Zrotation\n}\n";
/// let mut w = BvhWriter::new(Vec::new(), hierarchy, Fps::new(100, 1)?, 1, 2)?;
/// w.row(&[0.5])?;
/// w.row(&[-90.0])?;
/// let bytes = w.finish()?;
/// assert_eq!(
///     String::from_utf8(bytes).unwrap(),
///     format!("{hierarchy}MOTION\nFrames: 2\nFrame Time: 0.01\n0.5\n-90\n")
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct BvhWriter<W: Write> {
    out: W,
    buf: Vec<u8>,
    num: NumWriter,
    channels: usize,
    frames: u64,
    written: u64,
}

fn invalid(kind: io::ErrorKind, msg: String) -> io::Error {
    io::Error::new(kind, msg)
}

impl<W: Write> BvhWriter<W> {
    /// Writes the header: `hierarchy` as given (followed by a line end if it has none),
    /// `MOTION`, `Frames: <frames>` and the `Frame Time` of `fps`. Each row must then have
    /// `channels` values (at least one).
    pub fn new(
        out: W,
        hierarchy: &str,
        fps: Fps,
        channels: usize,
        frames: u64,
    ) -> io::Result<BvhWriter<W>> {
        if channels == 0 {
            return Err(invalid(
                io::ErrorKind::InvalidInput,
                "internal error: a BVH file needs at least one channel".to_string(),
            ));
        }
        let mut buf = Vec::with_capacity(FLUSH_AT + 4096);
        buf.extend_from_slice(hierarchy.as_bytes());
        if !hierarchy.is_empty() && !hierarchy.ends_with('\n') {
            buf.push(b'\n');
        }
        buf.extend_from_slice(
            format!(
                "MOTION\nFrames: {frames}\nFrame Time: {}\n",
                frame_time_text(fps)
            )
            .as_bytes(),
        );
        Ok(BvhWriter {
            out,
            buf,
            num: NumWriter::default(),
            channels,
            frames,
            written: 0,
        })
    }

    /// Writes one row: `channels` finite values.
    pub fn row(&mut self, values: &[f64]) -> io::Result<()> {
        if values.len() != self.channels {
            return Err(invalid(
                io::ErrorKind::InvalidInput,
                format!(
                    "internal error: a row of {} values for {} channels",
                    values.len(),
                    self.channels
                ),
            ));
        }
        if self.written == self.frames {
            return Err(invalid(
                io::ErrorKind::InvalidInput,
                format!(
                    "internal error: more rows than the {} announced in \"Frames:\"",
                    self.frames
                ),
            ));
        }
        if let Some(c) = values.iter().position(|x| !x.is_finite()) {
            return Err(invalid(
                io::ErrorKind::InvalidData,
                format!(
                    "internal error: non-finite value in frame {}, column {} ({})",
                    self.written,
                    c + 1,
                    values[c]
                ),
            ));
        }
        for (i, &x) in values.iter().enumerate() {
            if i > 0 {
                self.buf.push(b' ');
            }
            self.num.shortest(&mut self.buf, x);
            // Integers as BVH files write them: `-21`, not `-21.0`.
            if self.buf.ends_with(b".0") {
                self.buf.truncate(self.buf.len() - 2);
            }
        }
        self.buf.push(b'\n');
        self.written += 1;
        if self.buf.len() >= FLUSH_AT {
            self.out.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    /// Writes what is buffered, flushes, and returns the destination. An error if fewer rows
    /// were written than announced in `Frames:`.
    pub fn finish(mut self) -> io::Result<W> {
        if self.written != self.frames {
            return Err(invalid(
                io::ErrorKind::InvalidInput,
                format!(
                    "internal error: {} rows written after \"Frames: {}\"",
                    self.written, self.frames
                ),
            ));
        }
        self.out.write_all(&self.buf)?;
        self.out.flush()?;
        Ok(self.out)
    }
}

/// Writes a whole BVH file: `hierarchy`, then `values` (row-major, `channels` per row) at
/// `fps`. See [`BvhWriter`] for the layout.
pub fn write<W: Write>(
    out: W,
    hierarchy: &str,
    fps: Fps,
    channels: usize,
    values: &[f64],
) -> io::Result<()> {
    if channels == 0 || values.len() % channels != 0 {
        return Err(invalid(
            io::ErrorKind::InvalidInput,
            format!(
                "internal error: {} values do not make rows of {channels} channels",
                values.len()
            ),
        ));
    }
    let rows = values.len() / channels;
    let mut w = BvhWriter::new(out, hierarchy, fps, channels, rows as u64)?;
    for row in values.chunks_exact(channels) {
        w.row(row)?;
    }
    w.finish().map(drop)
}
