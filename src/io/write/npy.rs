//! Frames as a NumPy `.npy` file (format version 1.0): one float64 row per frame,
//!
//! ```text
//! [track_index,] frame, time, <rotation values>, [wx, wy, wz]
//! ```
//!
//! with the rotation values in the order of the CSV columns (`w,x,y,z`; Euler angles in SEQ
//! order; the matrix row-major; …) and angles in `--angles` units; `track_index` (0-based, in the
//! order tracks appear) only when the CSV output would have a `track` column. `np.load(path)`
//! returns an `(n_frames, n_columns)` array. The header must state the shape, so the writer is
//! given the exact number of frames; it checks it at the end.

use super::Style;
use crate::bake::FrameSink;
use crate::rotation::{MAX_WIDTH, Repr};
use glam::{DQuat, DVec3};
use std::io::{self, Write};

/// Streams frames as `.npy` rows.
pub struct NpyWriter<W: Write> {
    w: W,
    buf: Vec<u8>,
    style: Style,
    track_index: Option<f64>,
    velocity: bool,
    rows_expected: u64,
    rows: u64,
    vals: [f64; MAX_WIDTH],
}

/// Number of columns of a frame row.
pub fn columns(repr: Repr, track_column: bool, velocity: bool) -> usize {
    usize::from(track_column) + 2 + repr.width() + if velocity { 3 } else { 0 }
}

/// The `.npy` v1.0 header for a `rows × cols` little-endian float64 C-order array.
pub fn header(rows: u64, cols: usize) -> Vec<u8> {
    let dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows}, {cols}), }}");
    // magic (6) + version (2) + header length (2) + dict + padding + '\n', a multiple of 64.
    let unpadded = 10 + dict.len() + 1;
    let total = unpadded.div_ceil(64) * 64;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&((total - 10) as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out.extend(std::iter::repeat_n(b' ', total - unpadded));
    out.push(b'\n');
    out
}

impl<W: Write> NpyWriter<W> {
    /// A writer of exactly `rows` frames (checked at the end); `track_column` adds the track
    /// index column, `velocity` the angular velocity columns.
    pub fn new(w: W, style: Style, rows: u64, track_column: bool, velocity: bool) -> Self {
        let mut buf = Vec::with_capacity(1 << 16);
        buf.extend_from_slice(&header(rows, columns(style.repr, track_column, velocity)));
        NpyWriter {
            w,
            buf,
            style,
            track_index: track_column.then_some(-1.0),
            velocity,
            rows_expected: rows,
            rows: 0,
            vals: [0.0; MAX_WIDTH],
        }
    }

    /// The writer, after [`FrameSink::finish`].
    pub fn into_inner(self) -> W {
        self.w
    }

    #[inline]
    fn push(&mut self, x: f64) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }
}

impl<W: Write> FrameSink for NpyWriter<W> {
    fn begin_track(&mut self, _name: Option<&str>) -> io::Result<()> {
        if let Some(i) = &mut self.track_index {
            *i += 1.0;
        }
        Ok(())
    }

    #[inline]
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        if let Some(i) = self.track_index {
            self.push(i);
        }
        self.push(k as f64);
        self.push(time);
        let repr = self.style.repr;
        repr.from_quat(q, self.style.angles, &mut self.vals);
        for i in 0..repr.width() {
            self.buf.extend_from_slice(&self.vals[i].to_le_bytes());
        }
        if self.velocity {
            let w = omega.unwrap_or(DVec3::NAN);
            for x in w.to_array() {
                self.push(self.style.angles.from_rad(x));
            }
        }
        self.rows += 1;
        if self.buf.len() >= 1 << 16 {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    fn end_track(&mut self) -> io::Result<()> {
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        if self.rows != self.rows_expected {
            return Err(io::Error::other(format!(
                "npy writer: {} rows written, {} announced",
                self.rows, self.rows_expected
            )));
        }
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        self.w.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_is_aligned_and_parsable() {
        let h = header(1_000_000, 6);
        assert_eq!(h.len() % 64, 0);
        assert_eq!(&h[..8], b"\x93NUMPY\x01\x00");
        let len = u16::from_le_bytes([h[8], h[9]]) as usize;
        assert_eq!(len + 10, h.len());
        let dict = std::str::from_utf8(&h[10..]).unwrap();
        assert!(
            dict.starts_with("{'descr': '<f8', 'fortran_order': False, 'shape': (1000000, 6), }")
        );
        assert!(dict.ends_with('\n'));
    }
}
