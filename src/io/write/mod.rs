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
//! - [`num`]: shortest round-trip and fixed-precision number formatting.

pub mod columns;
pub mod frames;
pub mod keyframes;
pub mod npy;
pub mod num;
mod worker;

pub use frames::FrameWriter;
pub use keyframes::write_keys;
pub use npy::NpyWriter;

use crate::clock::Fps;
use crate::rotation::{AngleUnit, QuatOrder, Repr};
use num::NumFormat;

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
