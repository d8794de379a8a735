//! One frame's row: the frame waiting to be formatted and the formatter that writes it (CSV
//! or JSON), shared by the writer and its worker thread.

use super::columns::RotationFormatter;
use super::{Bad, is_rotation, velocity_fault};
use crate::Format;
use crate::num::NumWriter;
use glam::{DQuat, DVec3};
use inbetween::rotation::AngleUnit;

/// One frame waiting to be formatted.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub(super) k: i64,
    pub(super) time: f64,
    pub(super) q: DQuat,
    pub(super) omega: Option<DVec3>,
    /// Continuous Euler angles (radians), computed in order on the writer's thread.
    pub(super) euler: Option<[f64; 3]>,
    /// The frame's position (tracks with translations).
    pub(super) position: Option<DVec3>,
}

/// Turns frames into CSV rows or JSON objects (one per line). Owned by the writer and cloned
/// into the worker thread.
#[derive(Clone)]
pub(super) struct RowFormatter {
    pub(super) format: Format,
    pub(super) rot: RotationFormatter,
    pub(super) nums: NumWriter,
    pub(super) track_column: bool,
    pub(super) velocity: bool,
    pub(super) angles: AngleUnit,
    /// Write `tx,ty,tz` columns (CSV; empty for a track without translations) and
    /// `"translation"` fields (JSON, where a frame has one).
    pub(super) positions: bool,
}

/// A frame [`RowFormatter::rows`] refused: its number and what was wrong.
pub(super) type Fault = (i64, Bad);

impl RowFormatter {
    /// Appends `frames`, the first being frame number `start` of its track; `track` is the CSV
    /// row prefix (`name,`). Stops at the first frame with a value that must not be written
    /// (NaN, infinity, a quaternion that is not a rotation: a bug upstream); the bytes appended
    /// are then to be discarded.
    pub(super) fn rows(
        &mut self,
        out: &mut Vec<u8>,
        track: &[u8],
        start: usize,
        frames: &[Frame],
    ) -> Result<(), Fault> {
        for (i, f) in frames.iter().enumerate() {
            let omega = if self.velocity {
                f.omega
                    .map(|w| w.to_array().map(|x| self.angles.from_rad(x)))
            } else {
                None
            };
            // One `is_finite` per written value and one norm per rotation.
            let mut ok = f.time.is_finite() && is_rotation(f.q);
            match self.format {
                Format::Json => {
                    out.extend_from_slice(if start + i == 0 {
                        b"\n{\"frame\": "
                    } else {
                        b",\n{\"frame\": "
                    });
                    self.nums.int(out, f.k);
                    out.extend_from_slice(b", \"time\": ");
                    self.nums.shortest(out, f.time);
                    out.extend_from_slice(b", ");
                    ok &= self.rot.json(out, f.q, f.euler);
                    if let Some(w) = omega {
                        out.extend_from_slice(b", \"angular_velocity\": [");
                        for (j, x) in w.iter().enumerate() {
                            if j > 0 {
                                out.extend_from_slice(b", ");
                            }
                            ok &= x.is_finite();
                            self.nums.float(out, *x);
                        }
                        out.push(b']');
                    }
                    if let Some(p) = f.position.filter(|_| self.positions) {
                        out.extend_from_slice(b", \"translation\": [");
                        for (j, x) in p.to_array().iter().enumerate() {
                            if j > 0 {
                                out.extend_from_slice(b", ");
                            }
                            ok &= x.is_finite();
                            self.nums.float(out, *x);
                        }
                        out.push(b']');
                    }
                    out.push(b'}');
                }
                // Every other format is written here as CSV (the writers write CSV or JSON).
                _ => {
                    if self.track_column {
                        out.extend_from_slice(track);
                    }
                    self.nums.int(out, f.k);
                    out.push(b',');
                    self.nums.shortest(out, f.time);
                    ok &= self.rot.csv(out, f.q, f.euler);
                    if let Some(w) = omega {
                        for x in w {
                            out.push(b',');
                            ok &= x.is_finite();
                            self.nums.float(out, x);
                        }
                    }
                    if self.positions {
                        match f.position {
                            Some(p) => {
                                for x in p.to_array() {
                                    out.push(b',');
                                    ok &= x.is_finite();
                                    self.nums.float(out, x);
                                }
                            }
                            None => out.extend_from_slice(b",,,"),
                        }
                    }
                    out.push(b'\n');
                }
            }
            if !ok || (self.velocity && omega.is_none()) {
                return Err((f.k, self.fault(f, omega)));
            }
        }
        Ok(())
    }

    /// What is wrong with frame `f` (the cold path of [`Self::rows`]).
    #[cold]
    fn fault(&mut self, f: &Frame, omega: Option<[f64; 3]>) -> Bad {
        if !f.time.is_finite() {
            return Bad::NonFinite("time", f.time);
        }
        if let Some(x) = f
            .position
            .and_then(|p| p.to_array().into_iter().find(|x| !x.is_finite()))
        {
            return Bad::NonFinite("translation", x);
        }
        if let Some(bad) = self.rot.fault(f.q) {
            return bad;
        }
        velocity_fault(omega)
    }
}
