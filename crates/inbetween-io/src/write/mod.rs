//! Writers: frames (from `interp`) and keys (from `convert`) as CSV or JSON bytes, and NumPy
//! `.npy` arrays of frames.
//!
//! Writers only turn values into bytes on a [`Write`](std::io::Write); they stream (a frame is
//! formatted and handed on as it comes, through a small buffer) and never look at the file system.
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
//!
//! - [`columns`]: one rotation's values in the chosen representation, CSV cells or a JSON array.
//! - [`frames`]: [`FrameWriter`], the CSV/JSON frame writer (a [`crate::FrameSink`]).
//! - `worker`: the order-preserving formatting thread behind [`FrameWriter`].
//! - [`keyframes`]: [`write_keys`], a document's keys for `convert`.
//! - [`npy`]: [`NpyWriter`], frames as a NumPy array.
//! - [`npz`]: [`NpzWriter`], frames as named NumPy arrays in a [`zip`] archive.
//!
//! Last line of defence (docs/spec.md, *Exit codes*): output never holds NaN, infinity or a zero
//! quaternion. Every writer checks each value it writes (one `is_finite` per value, one norm
//! per rotation) and, instead of writing a bad one, fails with an [`io::Error`] of kind
//! `InvalidData`, `internal error: …`, naming the frame or key and the track. Inputs are
//! validated and the curves are finite, so this only ever reports a bug.

pub mod columns;
pub mod frames;
pub mod keyframes;
pub mod npy;
pub mod npz;
mod rows;
mod worker;
pub mod zip;

pub use frames::FrameWriter;
pub use keyframes::write_keys;
pub use npy::NpyWriter;
pub use npz::{NpzShape, NpzWriter};

use crate::num::NumFormat;
use glam::DQuat;
use inbetween::clock::Fps;
use inbetween::rotation::{AngleUnit, MAX_WIDTH, QuatOrder, Repr};
use std::io;

/// How rotations and numbers are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Style {
    /// The representation written.
    pub repr: Repr,
    /// The unit of written angles (Euler angles, axis-angle angles, angular velocities).
    pub angles: AngleUnit,
    /// The component order of quaternions in JSON arrays (CSV columns are named `w,x,y,z`).
    pub quat_order: QuatOrder,
    /// Shortest round-trip or fixed precision.
    pub num: NumFormat,
    /// Euler angles continuous along a track, or each triple in scipy's ranges.
    pub euler: EulerMode,
}

/// How Euler angles are written along a track (`--euler`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EulerMode {
    /// Each triple is the one of its rotation nearest the previous triple (both solutions of
    /// the sequence, any multiple of 360°): no ±180° wrap, no flip near gimbal lock
    /// ([`inbetween::rotation::unwrap`]). A track starts from its first key's own triple when the
    /// keys were given as Euler angles in the same sequence, else from the canonical triple.
    #[default]
    Continuous,
    /// Each triple in scipy's ranges, independently.
    Wrapped,
    /// Keys given as Euler angles in the output's sequence are written with their own triples,
    /// exactly as given ([`crate::write::write_keys`]; `reduce --path euler`, whose keys'
    /// turns are in their angles). Anything else (frames, other keys) as `Continuous`.
    AsGiven,
}

impl Style {
    /// `q`'s values in this style's representation into `out` (the angle unit applied); Euler
    /// angles taken from `euler` (radians, continuous along the track) when given.
    #[inline]
    pub(crate) fn fill(&self, q: glam::DQuat, euler: Option<[f64; 3]>, out: &mut [f64; MAX_WIDTH]) {
        match euler {
            Some(e) => out[..3].copy_from_slice(&e.map(|x| self.angles.from_rad(x))),
            None => self.repr.from_quat(q, self.angles, out),
        }
    }

    /// A new per-track state for continuous Euler angles, when this style writes them.
    pub(crate) fn unwrapper(&self) -> Option<inbetween::rotation::unwrap::EulerUnwrap> {
        match (self.repr, self.euler) {
            (Repr::Euler(seq), EulerMode::Continuous | EulerMode::AsGiven) => {
                Some(inbetween::rotation::unwrap::EulerUnwrap::new(seq))
            }
            _ => None,
        }
    }

    /// [`Style::unwrapper`] for a track whose first key was given as `angles` (radians) in `seq`:
    /// when this style writes continuous Euler angles in that same sequence, the track starts
    /// from the key's own triple.
    pub(crate) fn unwrapper_from(
        &self,
        seq: crate::EulerSeq,
        angles: [f64; 3],
    ) -> Option<inbetween::rotation::unwrap::EulerUnwrap> {
        match (self.repr, self.euler) {
            (Repr::Euler(out), EulerMode::Continuous | EulerMode::AsGiven) if out == seq => Some(
                inbetween::rotation::unwrap::EulerUnwrap::with_start(seq, angles),
            ),
            _ => self.unwrapper(),
        }
    }
}

pub(crate) fn json_string(s: &str) -> String {
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

/// CSV field quoting for track names (RFC 4180: quote when needed, double inner quotes).
pub(crate) fn csv_field(s: &str) -> Vec<u8> {
    if s.contains([',', '"', '\n', '\r']) || s.trim() != s {
        format!("\"{}\"", s.replace('"', "\"\"")).into_bytes()
    } else {
        s.as_bytes().to_vec()
    }
}

/// A value a writer refused to write (a bug upstream), with the field it was for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Bad {
    /// A NaN or infinite value for the named field (`time`, a rotation column, `wx`, …).
    NonFinite(&'static str, f64),
    /// A rotation whose quaternion is zero or far from unit, with its norm.
    NotRotation(f64),
    /// A frame without the angular velocity the output has columns for.
    NoVelocity,
}

/// Whether `q` can be written as a rotation: its squared norm is in `[0.5, 2]` (the curves'
/// points are unit to 1e-13; this catches a zero, NaN or wildly wrong quaternion, cheaply).
#[inline]
pub(crate) fn is_rotation(q: DQuat) -> bool {
    (0.5..=2.0).contains(&q.length_squared())
}

/// The first problem among a rotation's written `values` (named by `repr`'s CSV columns) and
/// its quaternion `q`, if any.
pub(crate) fn rotation_fault(repr: Repr, q: DQuat, values: &[f64]) -> Option<Bad> {
    if let Some((i, &x)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Some(Bad::NonFinite(repr.columns()[i], x));
    }
    (!is_rotation(q)).then(|| Bad::NotRotation(q.length()))
}

/// The problem with a frame's written angular velocity `w` (`None`: missing).
pub(crate) fn velocity_fault(w: Option<[f64; 3]>) -> Bad {
    match w {
        None => Bad::NoVelocity,
        Some(w) => {
            let i = w.iter().position(|x| !x.is_finite()).unwrap_or(0);
            Bad::NonFinite(["wx", "wy", "wz"][i], w[i])
        }
    }
}

/// The error for `bad` in `item` (`frame 12`, `key 3`) of a track, named or by index:
/// `internal error: non-finite value in frame 12 of track "hip" ("wx" = NaN)`.
pub(crate) fn internal_error(
    item: &str,
    track: Option<&str>,
    track_index: usize,
    bad: Bad,
) -> io::Error {
    let track = match track {
        Some(name) => format!("track \"{name}\""),
        None => format!("track {track_index}"),
    };
    let msg = match bad {
        Bad::NonFinite(field, x) => {
            format!("internal error: non-finite value in {item} of {track} (\"{field}\" = {x})")
        }
        Bad::NotRotation(n) => format!(
            "internal error: zero or non-unit quaternion in {item} of {track} (norm {})",
            inbetween::error::num(n)
        ),
        Bad::NoVelocity => {
            format!("internal error: no angular velocity in {item} of {track}")
        }
    };
    io::Error::new(io::ErrorKind::InvalidData, msg)
}
