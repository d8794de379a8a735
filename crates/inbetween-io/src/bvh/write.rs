//! The BVH writer: a hierarchy text, a rate and rows of values → a BVH file.
//!
//! ```text
//! <the hierarchy text exactly as given>      (a line end is added only if it lacks one)
//! MOTION
//! Frames: <rows>
//! Frame Time: <rate::frame_time_text(fps)>    0.01, 0.0125, 0.0333333333
//! <values of row 0, one space apart>          rounded (see below), then shortest digits
//! ...
//! ```
//!
//! Each number is first rounded to 12 significant digits and to at most 10 decimals
//! (`bvh_round`), then written as the shortest decimal that reads back as that f64 (integers
//! without `.0`, −0 as `0`); lines end as the hierarchy's do: `\r\n` when its first line ends
//! so (a file written on Windows comes back with one line ending throughout), else `\n`. The rounding is far above the noise of an angle
//! that went through a quaternion (about 1e-13 degrees) and far below anything a skeleton can
//! show (1e-10 degrees), so an angle the source wrote as `10` or `-11.725488` is written so again
//! rather than `9.99999999999999` or `-11.725488000000004`. The writer streams: `BvhWriter` takes one row at a time
//! and buffers at most about 64 KiB. Like the other writers, it never writes a non-finite
//! value: it fails with an [`io::Error`] of kind `InvalidData` (`internal error: …`) instead.

use super::rate::frame_time_text;
use crate::num::NumWriter;
use inbetween::clock::Fps;
use std::io::{self, Write};

const FLUSH_AT: usize = 64 * 1024;

/// Powers of ten that are exact as `f64`.
const POW10: [f64; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// `x` (finite) rounded to 12 significant digits and to at most 10 decimals: the f64 nearest to
/// that decimal, so that the shortest round-trip digits of the result are that decimal's.
/// Values of 10^12 and more are left as they are.
///
/// (Its example is a unit test: `bvh_round_example`.)
pub(crate) fn bvh_round(x: f64) -> f64 {
    let a = x.abs();
    if a >= 1e12 {
        // No decimals are left to round (and no such value is an angle or a skeleton's length).
        return x;
    }
    // Decimals kept: 10 below 100, then one fewer per digit before the point (12 significant).
    let mut d = 10;
    let mut lim = 100.0;
    while a >= lim {
        d -= 1;
        lim *= 10.0;
    }
    // |x|·10^d < 10^12: the product is within one rounding of the exact one, and dividing two
    // exact values rounds once, to the f64 nearest the decimal.
    let p = POW10[d];
    (x * p).round() / p
}

/// Writes a BVH file row by row: the header when made, then [`BvhWriter::row`] for each of the
/// `frames` rows announced in it, then [`BvhWriter::finish`] (which flushes; dropping the
/// writer without it loses the buffered rows).
///
/// (Its example is a unit test: `bvhwriter_example`.)
pub(crate) struct BvhWriter<W: Write> {
    out: W,
    buf: Vec<u8>,
    num: NumWriter,
    channels: usize,
    frames: u64,
    written: u64,
    /// The line end: the hierarchy's (`\r\n` or `\n`).
    eol: &'static str,
}

/// The line end of `hierarchy`: `\r\n` when its first line ends so, else `\n`.
fn line_end(hierarchy: &str) -> &'static str {
    match hierarchy.find('\n') {
        Some(i) if hierarchy[..i].ends_with('\r') => "\r\n",
        _ => "\n",
    }
}

fn invalid(kind: io::ErrorKind, msg: String) -> io::Error {
    io::Error::new(kind, msg)
}

impl<W: Write> BvhWriter<W> {
    /// Writes the header: `hierarchy` as given (followed by a line end if it has none),
    /// `MOTION`, `Frames: <frames>` and the `Frame Time` of `fps`. Each row must then have
    /// `channels` values (at least one).
    pub(crate) fn new(
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
        let eol = line_end(hierarchy);
        let mut buf = Vec::with_capacity(FLUSH_AT + 4096);
        buf.extend_from_slice(hierarchy.as_bytes());
        if !hierarchy.is_empty() && !hierarchy.ends_with('\n') {
            buf.extend_from_slice(eol.as_bytes());
        }
        buf.extend_from_slice(
            format!(
                "MOTION{eol}Frames: {frames}{eol}Frame Time: {}{eol}",
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
            eol,
        })
    }

    /// Writes one row: `channels` finite values.
    pub(crate) fn row(&mut self, values: &[f64]) -> io::Result<()> {
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
            self.num.shortest(&mut self.buf, bvh_round(x));
            // Integers as BVH files write them: `-21`, not `-21.0`.
            if self.buf.ends_with(b".0") {
                self.buf.truncate(self.buf.len() - 2);
            }
        }
        self.buf.extend_from_slice(self.eol.as_bytes());
        self.written += 1;
        if self.buf.len() >= FLUSH_AT {
            self.out.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    /// Writes what is buffered, flushes, and returns the destination. An error if fewer rows
    /// were written than announced in `Frames:`.
    pub(crate) fn finish(mut self) -> io::Result<W> {
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
/// `fps`. See `BvhWriter` for the layout.
pub fn write<W: Write>(
    out: W,
    hierarchy: &str,
    fps: Fps,
    channels: usize,
    values: &[f64],
) -> io::Result<()> {
    if channels == 0 || !values.len().is_multiple_of(channels) {
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

#[cfg(test)]
mod tests {
    use super::*;

    const H: &str =
        "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n}\n";

    fn fps(n: u64, d: u64) -> Fps {
        Fps::new(n, d).unwrap()
    }

    fn written(hierarchy: &str, fps: Fps, channels: usize, values: &[f64]) -> String {
        let mut out = Vec::new();
        write(&mut out, hierarchy, fps, channels, values).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn writes_the_hierarchy_then_the_motion() {
        let values = [0.0, -0.0, 21.0, 0.1, -179.99, 1e-7, 1.0 / 3.0, 1e21, -2.5];
        assert_eq!(
            written(H, fps(30, 1), 3, &values),
            format!(
                "{H}MOTION\nFrames: 3\nFrame Time: 0.0333333333\n0 0 21\n0.1 -179.99 1e-7\n\
                 0.3333333333 1e+21 -2.5\n"
            )
        );
        assert_eq!(
            written(H, fps(120, 1), 3, &[]),
            format!("{H}MOTION\nFrames: 0\nFrame Time: 0.00833333333\n")
        );
    }

    #[test]
    fn every_written_number_reads_back_as_its_rounded_value() {
        let mut state = 0x9E3779B97F4A7C15u64;
        let mut values = Vec::new();
        for _ in 0..30_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
            values.push((unit - 0.5) * 10f64.powi((state % 12) as i32 - 4));
        }
        let text = written(H, fps(24, 1), 3, &values);
        let body = text.split_once("Frame Time: 0.0416666667\n").unwrap().1;
        let back: Vec<f64> = body
            .split_ascii_whitespace()
            .map(|s| s.parse().unwrap())
            .collect();
        let rounded: Vec<f64> = values.iter().map(|&x| bvh_round(x)).collect();
        assert_eq!(back, rounded);
        // Within half a unit of the 12th significant digit or the 10th decimal.
        for (x, r) in values.iter().zip(&rounded) {
            assert!(
                (x - r).abs() <= (x.abs() * 5e-12).max(5e-11) * (1.0 + 1e-9),
                "{x} {r}"
            );
        }
    }

    #[test]
    fn numbers_written_with_few_digits_come_back_through_noise() {
        for s in [
            "10",
            "-11.725488",
            "179.999999",
            "0.000001",
            "-0.5",
            "123456.789012",
            "0",
        ] {
            let x: f64 = s.parse().unwrap();
            for noisy in [x, x + x.abs() * 3e-15 + 1e-14, x - x.abs() * 3e-15 - 1e-14] {
                let mut out = Vec::new();
                write(&mut out, H, fps(30, 1), 3, &[noisy, 0.0, 0.0]).unwrap();
                let text = String::from_utf8(out).unwrap();
                let row = text.lines().last().unwrap();
                let first = row.split(' ').next().unwrap();
                // The number as written (in its shortest form: `1e-6` for `0.000001`).
                assert_eq!(first.parse::<f64>().unwrap(), x + 0.0, "{noisy}: {row}");
                assert!(first.len() <= s.len(), "{noisy}: {row}");
            }
        }
        assert_eq!(bvh_round(1e300), 1e300);
        assert_eq!(bvh_round(-2.5e-17), 0.0);
    }

    #[test]
    fn a_hierarchy_without_a_final_line_end_gets_one() {
        let h = H.trim_end();
        assert_eq!(
            written(h, fps(100, 1), 3, &[1.0, 2.0, 3.0]),
            format!("{h}\nMOTION\nFrames: 1\nFrame Time: 0.01\n1 2 3\n")
        );
    }

    #[test]
    fn the_streaming_writer_equals_the_whole_file_writer() {
        let values: Vec<f64> = (0..60_000).map(|i| i as f64 * 0.37 - 999.5).collect();
        let whole = written(H, fps(60, 1), 3, &values);
        let mut w = BvhWriter::new(Vec::new(), H, fps(60, 1), 3, 20_000).unwrap();
        for row in values.chunks(3) {
            w.row(row).unwrap();
        }
        assert_eq!(String::from_utf8(w.finish().unwrap()).unwrap(), whole);
    }

    #[test]
    fn bad_rows_are_internal_errors() {
        let err = |e: io::Error| (e.kind(), e.to_string());
        let mut w = BvhWriter::new(Vec::new(), H, fps(30, 1), 3, 1).unwrap();
        assert_eq!(
            err(w.row(&[1.0, f64::NAN, 0.0]).unwrap_err()),
            (
                io::ErrorKind::InvalidData,
                "internal error: non-finite value in frame 0, column 2 (NaN)".to_string()
            )
        );
        assert_eq!(
            err(w.row(&[1.0, 2.0]).unwrap_err()),
            (
                io::ErrorKind::InvalidInput,
                "internal error: a row of 2 values for 3 channels".to_string()
            )
        );
        w.row(&[1.0, 2.0, 3.0]).unwrap();
        assert_eq!(
            err(w.row(&[1.0, 2.0, 3.0]).unwrap_err()).1,
            "internal error: more rows than the 1 announced in \"Frames:\""
        );
        let w = BvhWriter::new(Vec::new(), H, fps(30, 1), 3, 2).unwrap();
        assert_eq!(
            err(w.finish().unwrap_err()).1,
            "internal error: 0 rows written after \"Frames: 2\""
        );
        assert_eq!(
            err(write(Vec::new(), H, fps(30, 1), 3, &[1.0; 4]).unwrap_err()).1,
            "internal error: 4 values do not make rows of 3 channels"
        );
        assert!(BvhWriter::new(Vec::new(), H, fps(30, 1), 0, 0).is_err());
    }

    #[test]
    fn a_failing_destination_is_an_io_error() {
        struct Broken;
        impl Write for Broken {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::Error::from(io::ErrorKind::BrokenPipe))
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let e = write(Broken, H, fps(30, 1), 3, &[0.0; 3]).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::BrokenPipe);
    }
}

#[cfg(test)]
mod examples {
    #[test]
    fn bvhwriter_example() -> Result<(), Box<dyn std::error::Error>> {
        use crate::bvh::write::BvhWriter;
        use inbetween::Fps;

        let hierarchy = "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Zrotation\n}\n";
        let mut w = BvhWriter::new(Vec::new(), hierarchy, Fps::new(100, 1)?, 1, 2)?;
        w.row(&[0.5])?;
        w.row(&[-90.0])?;
        let bytes = w.finish()?;
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            format!("{hierarchy}MOTION\nFrames: 2\nFrame Time: 0.01\n0.5\n-90\n")
        );
        Ok(())
    }

    #[test]
    fn bvh_round_example() {
        use crate::bvh::write::bvh_round;

        assert_eq!(bvh_round(9.999999999999998), 10.0);
        assert_eq!(bvh_round(-11.725488000000004), -11.725488);
        assert_eq!(bvh_round(1.4e-15), 0.0);
        assert_eq!(bvh_round(123456.78901234567), 123456.789012);
        assert_eq!(bvh_round(1.0 / 3.0), 0.3333333333);
    }
}
