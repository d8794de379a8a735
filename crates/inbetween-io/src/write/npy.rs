//! Frames as a NumPy `.npy` file (format version 1.0): one float64 row per frame,
//!
//! ```text
//! [track_index,] frame, time, <rotation values>, [wx, wy, wz], [tx, ty, tz]
//! ```
//!
//! with the rotation values in the order of the CSV columns (`w,x,y,z`; Euler angles in SEQ
//! order; the matrix row-major; …) and angles in `--angles` units; `track_index` (0-based, in the
//! order tracks appear) only when the CSV output would have a `track` column; the translation
//! last, as in the CSV ([`NpyWriter::with_positions`]; zeros for a track without, where the CSV
//! has empty cells). `np.load(path)`
//! returns an `(n_frames, n_columns)` array. The header must state the shape, so the writer is
//! given the exact number of frames; it checks it at the end.

use super::{Bad, Style, internal_error, is_rotation, rotation_fault, velocity_fault};
use glam::{DQuat, DVec3};
use inbetween::bake::FrameSink;
use inbetween::rotation::{MAX_WIDTH, Repr};
use std::io::{self, Write};

/// Streams frames as `.npy` rows.
pub struct NpyWriter<W: Write> {
    w: W,
    buf: Vec<u8>,
    style: Style,
    track_index: Option<f64>,
    /// The current track's name and index, for error messages.
    track: (Option<String>, usize),
    tracks: usize,
    velocity: bool,
    /// Write `tx, ty, tz` (zeros for a frame without a position).
    positions: bool,
    rows_expected: u64,
    rows: u64,
    vals: [f64; MAX_WIDTH],
    /// Continuous Euler angles along the current track.
    unwrap: Option<inbetween::rotation::unwrap::EulerUnwrap>,
}

/// Number of columns of a frame row (`positions`: the three translation columns).
pub fn columns(repr: Repr, track_column: bool, velocity: bool, positions: bool) -> usize {
    usize::from(track_column)
        + 2
        + repr.width()
        + 3 * usize::from(velocity)
        + 3 * usize::from(positions)
}

/// The `.npy` v1.0 header for a `rows × cols` little-endian float64 C-order array.
pub fn header(rows: u64, cols: usize) -> Vec<u8> {
    array_header("<f8", &[rows, cols as u64])
}

/// The `.npy` v1.0 header for a C-order array of dtype `descr` (`<f8`, `<i8`, `|b1`, `<U12`) and
/// `shape` (empty: a 0-d array), padded to a multiple of 64 bytes.
pub(crate) fn array_header(descr: &str, shape: &[u64]) -> Vec<u8> {
    let shape = match shape {
        [n] => format!("({n},)"),
        _ => {
            let dims: Vec<String> = shape.iter().map(u64::to_string).collect();
            format!("({})", dims.join(", "))
        }
    };
    let dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
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
        buf.extend_from_slice(&header(
            rows,
            columns(style.repr, track_column, velocity, false),
        ));
        NpyWriter {
            w,
            buf,
            style,
            track_index: track_column.then_some(-1.0),
            track: (None, 0),
            tracks: 0,
            velocity,
            positions: false,
            rows_expected: rows,
            rows: 0,
            vals: [0.0; MAX_WIDTH],
            unwrap: None,
        }
    }

    /// Writes positions too (tracks with translations): `tx, ty, tz` after the other columns,
    /// zeros for a track without (the CSV's empty cells). Call before the first track.
    pub fn with_positions(mut self) -> Self {
        debug_assert_eq!(self.rows, 0, "called before any row");
        let cols = columns(
            self.style.repr,
            self.track_index.is_some(),
            self.velocity,
            true,
        );
        self.buf = header(self.rows_expected, cols);
        self.positions = true;
        self
    }

    /// The writer, after [`FrameSink::finish`].
    pub fn into_inner(self) -> W {
        self.w
    }

    #[inline]
    fn push(&mut self, x: f64) {
        self.buf.extend_from_slice(&x.to_le_bytes());
    }

    /// What is wrong with a frame whose checks failed (the cold path of `frame`).
    #[cold]
    fn refuse(
        &self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<[f64; 3]>,
        position: DVec3,
    ) -> io::Error {
        let repr = self.style.repr;
        let bad_position = position.to_array().into_iter().find(|x| !x.is_finite());
        let bad = if !time.is_finite() {
            Bad::NonFinite("time", time)
        } else if let Some(x) = bad_position.filter(|_| self.positions) {
            Bad::NonFinite("translation", x)
        } else if let Some(bad) = rotation_fault(repr, q, &self.vals[..repr.width()]) {
            bad
        } else {
            velocity_fault(omega)
        };
        internal_error(
            &format!("frame {k}"),
            self.track.0.as_deref(),
            self.track.1,
            bad,
        )
    }
}

impl<W: Write> FrameSink for NpyWriter<W> {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()> {
        if let Some(i) = &mut self.track_index {
            *i += 1.0;
        }
        self.track = (name.map(str::to_string), self.tracks);
        self.unwrap = self.style.unwrapper();
        self.tracks += 1;
        Ok(())
    }

    fn euler_start(&mut self, seq: crate::EulerSeq, angles: [f64; 3]) {
        self.unwrap = self.style.unwrapper_from(seq, angles);
    }

    #[inline]
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        self.row(k, time, q, omega, DVec3::ZERO)
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
        self.row(k, time, q, omega, position)
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

impl<W: Write> NpyWriter<W> {
    /// One row: the frame, and its position when the writer has position columns.
    #[inline]
    fn row(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: DVec3,
    ) -> io::Result<()> {
        let row_start = self.buf.len();
        if let Some(i) = self.track_index {
            self.push(i);
        }
        self.push(k as f64);
        self.push(time);
        let repr = self.style.repr;
        let euler = self.unwrap.as_mut().map(|u| u.next(q));
        self.style.fill(q, euler, &mut self.vals);
        // One `is_finite` per written value and one norm per rotation.
        let mut ok = time.is_finite() && is_rotation(q);
        for i in 0..repr.width() {
            ok &= self.vals[i].is_finite();
            self.buf.extend_from_slice(&self.vals[i].to_le_bytes());
        }
        let unit = self.style.angles;
        let w = omega.map(|o| o.to_array().map(|x| unit.from_rad(x)));
        if self.velocity {
            match w {
                Some(w) => {
                    for x in w {
                        ok &= x.is_finite();
                        self.push(x);
                    }
                }
                None => ok = false,
            }
        }
        if self.positions {
            for x in position.to_array() {
                ok &= x.is_finite();
                self.push(x);
            }
        }
        if !ok {
            self.buf.truncate(row_start);
            return Err(self.refuse(k, time, q, w, position));
        }
        self.rows += 1;
        if self.buf.len() >= 1 << 16 {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::NumFormat;
    use inbetween::rotation::{AngleUnit, QuatOrder};

    fn writer(velocity: bool) -> NpyWriter<Vec<u8>> {
        let style = Style {
            repr: Repr::RotVec,
            angles: AngleUnit::Deg,
            quat_order: QuatOrder::Wxyz,
            num: NumFormat::Shortest,
            euler: Default::default(),
        };
        NpyWriter::new(Vec::new(), style, 3, true, velocity)
    }

    #[test]
    fn non_finite_values_are_refused_not_written() {
        let cases = [
            (
                (f64::NAN, DQuat::IDENTITY, Some(DVec3::ZERO)),
                "internal error: non-finite value in frame 1 of track \"arm\" (\"time\" = NaN)",
            ),
            (
                (
                    0.1,
                    DQuat::from_xyzw(0.0, 0.0, f64::INFINITY, 1.0),
                    Some(DVec3::ZERO),
                ),
                "internal error: non-finite value in frame 1 of track \"arm\" (\"rz\" = NaN)",
            ),
            (
                (0.1, DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0), Some(DVec3::ZERO)),
                "internal error: zero or non-unit quaternion in frame 1 of track \"arm\" (norm 0)",
            ),
            (
                (0.1, DQuat::IDENTITY, Some(DVec3::new(0.0, 0.0, -1e307))),
                "internal error: non-finite value in frame 1 of track \"arm\" (\"wz\" = -inf)",
            ),
            (
                // It used to write NaN for a missing velocity.
                (0.1, DQuat::IDENTITY, None),
                "internal error: no angular velocity in frame 1 of track \"arm\"",
            ),
        ];
        for ((t, q, omega), want) in cases {
            let mut w = writer(true);
            w.begin_track(Some("arm")).unwrap();
            w.frame(0, 0.0, DQuat::IDENTITY, Some(DVec3::ZERO)).unwrap();
            let err = w.frame(1, t, q, omega).unwrap_err();
            assert_eq!(err.kind(), io::ErrorKind::InvalidData);
            assert_eq!(err.to_string(), want);
            // The refused row is not in the buffer: the header, then one row of 9 values
            // (track, frame, time, rx, ry, rz, wx, wy, wz).
            assert_eq!(w.buf.len(), header(3, 9).len() + 9 * 8);
        }
    }

    #[test]
    fn positions_are_the_last_three_columns() {
        let mut w = writer(false).with_positions();
        w.begin_track(Some("arm")).unwrap();
        w.frame_at(0, 0.0, DQuat::IDENTITY, None, DVec3::new(1.0, 2.0, 3.0))
            .unwrap();
        // A track without positions: zeros.
        w.frame(1, 0.5, DQuat::IDENTITY, None).unwrap();
        let err = w
            .frame_at(
                2,
                1.0,
                DQuat::IDENTITY,
                None,
                DVec3::new(0.0, f64::NAN, 0.0),
            )
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "internal error: non-finite value in frame 2 of track \"arm\" (\"translation\" = NaN)"
        );
        // track, frame, time, rx, ry, rz, tx, ty, tz.
        let h = header(3, 9);
        assert_eq!(&w.buf[..h.len()], h.as_slice());
        let vals: Vec<f64> = w.buf[h.len()..]
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(vals.len(), 18);
        assert_eq!(vals[6..9], [1.0, 2.0, 3.0]);
        assert_eq!(vals[15..18], [0.0, 0.0, 0.0]);
    }

    #[test]
    fn headers_of_every_rank() {
        let dict = |h: Vec<u8>| String::from_utf8(h[10..].to_vec()).unwrap();
        assert!(dict(array_header("<U3", &[])).contains("'shape': (), "));
        assert!(
            dict(array_header("|b1", &[7]))
                .contains("'descr': '|b1', 'fortran_order': False, 'shape': (7,), ")
        );
        assert!(dict(array_header("<f8", &[2, 3, 4])).contains("'shape': (2, 3, 4), "));
    }

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
