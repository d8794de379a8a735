//! An AMASS file written back at another rate: the same keys in the same order, shapes and
//! dtypes, with the frames of the new rate over the same span.
//!
//! - `poses` and the split rotation arrays (`root_orient`, `pose_body`, `pose_hand`, SMPL-X's
//!   `pose_jaw` and `pose_eye`, when their width is their joints') from the curves: rotation
//!   vectors of the shortest form (angle at most π);
//! - every other float array of two or more dimensions whose first dimension is the frame count
//!   (`trans`, `dmpls`, …): interpolated linearly between the two frames around each new time
//!   (exactly a source row where the new frame falls on one: the position is a rational);
//! - the rate key: the new rate, in its dtype (a float64 where an integer dtype cannot say it);
//! - everything else (`betas`, `gender`, `num_betas`, …): copied byte for byte.
//!
//! The archive is stored (as `np.savez` writes it), every entry and the whole at most
//! [`MAX_BYTES`](crate::write::zip::MAX_BYTES) (no ZIP64).

use super::npy::{Array, Kind};
use super::{Amass, RATE_KEYS};
use crate::write::npy::array_header;
use crate::write::zip::{MAX_BYTES, ZipWriter, archive_size};
use glam::DQuat;
use inbetween::clock::Fps;
use inbetween::error::InputResult;
use inbetween::rotation::quat;
use std::io::{self, Write};

/// An AMASS archive at a new rate, built in memory and checked before anything is written.
#[derive(Debug, Clone)]
pub struct Resampled {
    entries: Vec<(String, Vec<u8>)>,
    frames: u64,
}

impl Resampled {
    /// The number of frames written.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The archive's size in bytes.
    pub fn size(&self) -> u64 {
        let sizes: Vec<(usize, u64)> = self
            .entries
            .iter()
            .map(|(n, b)| (n.len(), b.len() as u64))
            .collect();
        archive_size(&sizes)
    }

    /// Writes the archive to `w`; returns it.
    pub fn write<W: Write>(&self, w: W) -> io::Result<W> {
        let mut zip = ZipWriter::new(w);
        for (name, bytes) in &self.entries {
            zip.entry(name, &[bytes])?;
        }
        zip.finish()
    }
}

/// `values` in the float encoding of `a` (its width and byte order; a half float's array is
/// written as float32), with its header for `shape`.
fn encode(a: &Array, shape: &[u64], values: &[f64]) -> Vec<u8> {
    let (wide, big) = (a.item == 8, a.big_endian);
    let descr = format!(
        "{}f{}",
        if big { '>' } else { '<' },
        if wide { 8 } else { 4 }
    );
    let mut out = array_header(&descr, shape);
    out.reserve(values.len() * if wide { 8 } else { 4 });
    for &x in values {
        match (wide, big) {
            (true, false) => out.extend_from_slice(&x.to_le_bytes()),
            (true, true) => out.extend_from_slice(&x.to_be_bytes()),
            (false, false) => out.extend_from_slice(&(x as f32).to_le_bytes()),
            (false, true) => out.extend_from_slice(&(x as f32).to_be_bytes()),
        }
    }
    out
}

/// The rotation vector of `q` (radians): `2·log q` of its canonical sign, angle in [0, π].
fn rotvec(q: DQuat) -> [f64; 3] {
    (quat::log(quat::canonical(q)) * 2.0).to_array()
}

impl Amass {
    /// The span of the frames in seconds: frame 0 to the last at [`Amass::fps`].
    pub fn span(&self) -> (f64, f64) {
        (0.0, self.fps.time_of(self.frames as i64 - 1))
    }

    /// The frame numbers at `fps` within [`Amass::span`] (ends kept when they are frames).
    pub fn frames_at(&self, fps: Fps) -> (i64, i64) {
        let (t0, t1) = self.span();
        fps.frames_between(t0, t1)
    }

    /// The archive at `fps` (see the module documentation): `rotation(joint, time)` is the
    /// curve of each joint (its rotation at a time in seconds). Input errors when an array
    /// cannot be written at the new frame count or the archive would pass what a zip without
    /// ZIP64 holds, before anything is written.
    pub fn resample(
        &self,
        fps: Fps,
        rotation: &(dyn Fn(usize, f64) -> DQuat + Sync),
    ) -> InputResult<Resampled> {
        let (a, b) = self.frames_at(fps);
        let out_frames = (b - a + 1).max(0) as u64;
        let joints = self.model.joint_count();
        // Every joint's rotation vector at every new frame, frame-major (the rows of poses).
        let mut rotvecs = vec![0.0; out_frames as usize * 3 * joints];
        for (k, row) in (a..=b).zip(rotvecs.chunks_exact_mut(3 * joints)) {
            let t = fps.time_of(k);
            for (j, v) in row.chunks_exact_mut(3).enumerate() {
                v.copy_from_slice(&rotvec(rotation(j, t)));
            }
        }
        // Where each new frame falls among the source frames: row i0 and the fraction toward
        // i0 + 1, from the exact rational k·den'·num / (num'·den).
        let (src, dst) = (self.fps, fps);
        let places: Vec<(usize, f64)> = (a..=b)
            .map(|k| {
                let p = k.max(0) as u128 * u128::from(dst.den()) * u128::from(src.num());
                let q = u128::from(dst.num()) * u128::from(src.den());
                let i0 = ((p / q) as usize).min(self.frames - 1);
                let frac = if i0 + 1 < self.frames {
                    (p % q) as f64 / q as f64
                } else {
                    0.0
                };
                (i0, frac)
            })
            .collect();
        let mut entries = Vec::with_capacity(self.arrays.len());
        for (key, array) in &self.arrays {
            // A per-frame array of another kind (integers, flags) is taken at the nearest
            // source frame; in Fortran order its rows are not contiguous, and it is refused.
            if array.kind != Kind::Float
                && array.shape.len() >= 2
                && array.shape[0] == self.frames as u64
                && array.fortran
            {
                return Err(input_err!(
                    "{}: \"{key}\": a per-frame {} array in Fortran order cannot be resampled",
                    self.source,
                    array.descr
                ));
            }
            let bytes = self.entry(key, array, fps, out_frames, &rotvecs, &places);
            entries.push((format!("{key}.npy"), bytes));
        }
        let out = Resampled {
            entries,
            frames: out_frames,
        };
        if let Some((name, bytes)) = out.entries.iter().find(|(_, b)| b.len() as u64 > MAX_BYTES) {
            return Err(input_err!(
                "{}: \"{name}\" at {fps} fps would take {} bytes, more than a zip without ZIP64 \
                 holds ({MAX_BYTES} bytes)",
                self.source,
                bytes.len()
            ));
        }
        if out.size() > MAX_BYTES {
            return Err(input_err!(
                "{}: the archive at {fps} fps would take {} bytes, more than a zip without ZIP64 \
                 holds ({MAX_BYTES} bytes)",
                self.source,
                out.size()
            ));
        }
        Ok(out)
    }

    /// One entry's `.npy` bytes at the new rate.
    fn entry(
        &self,
        key: &str,
        array: &Array,
        fps: Fps,
        out_frames: u64,
        rotvecs: &[f64],
        places: &[(usize, f64)],
    ) -> Vec<u8> {
        let joints = self.model.joint_count();
        let per_frame = array.shape.len() >= 2 && array.shape[0] == self.frames as u64;
        let mut shape = array.shape.clone();
        if RATE_KEYS.contains(&key) && self.rate_key.is_some() {
            let x = fps.as_f64();
            let int = matches!(array.kind, Kind::Int | Kind::Uint) && fps.den() == 1;
            return match array.kind {
                Kind::Float => encode(array, &shape, &[x]),
                _ if int => {
                    let mut out = array_header(&array.descr, &shape);
                    let mut b = fps.num().to_le_bytes()[..array.item].to_vec();
                    if array.big_endian {
                        b.reverse();
                    }
                    out.extend_from_slice(&b);
                    out
                }
                _ => {
                    let mut out = array_header("<f8", &shape);
                    out.extend_from_slice(&x.to_le_bytes());
                    out
                }
            };
        }
        if !per_frame {
            return array.bytes.clone();
        }
        shape[0] = out_frames;
        let width: usize = array.shape[1..].iter().map(|&d| d as usize).product();
        if array.kind != Kind::Float {
            // Rows of integers or flags cannot be blended: each new frame takes the nearest
            // source frame's row (C order, checked by the caller), bytes as they are.
            let row = width * array.item;
            let data = &array.bytes[array.data_at..];
            let mut out = array_header(&array.descr, &shape);
            for &(i0, frac) in places {
                let i = if frac > 0.5 { i0 + 1 } else { i0 };
                out.extend_from_slice(&data[i * row..(i + 1) * row]);
            }
            return out;
        }
        // The rotation arrays: their joints' columns of the new poses.
        let joints_of = match key {
            "poses" => Some(0..joints),
            _ => self.model.split_key(key),
        };
        if let Some(range) = joints_of.filter(|r| 3 * r.len() == width) {
            let cols = 3 * range.start..3 * range.end;
            let values: Vec<f64> = rotvecs
                .chunks_exact(3 * joints)
                .flat_map(|row| row[cols.clone()].iter().copied())
                .collect();
            return encode(array, &shape, &values);
        }
        let src = array.floats().unwrap_or_default();
        let mut values = Vec::with_capacity(out_frames as usize * width);
        for &(i0, frac) in places {
            let r0 = &src[i0 * width..(i0 + 1) * width];
            if frac == 0.0 {
                values.extend_from_slice(r0);
            } else {
                let r1 = &src[(i0 + 1) * width..(i0 + 2) * width];
                values.extend(r0.iter().zip(r1).map(|(x, y)| x + (y - x) * frac));
            }
        }
        encode(array, &shape, &values)
    }
}
