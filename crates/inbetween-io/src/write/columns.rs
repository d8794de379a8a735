//! One rotation's values in the representation of a [`Style`]: CSV cells or a JSON array.

use super::Style;
use crate::num::NumWriter;
use glam::DQuat;
use inbetween::rotation::{MAX_WIDTH, Repr};

/// Formats one rotation's values (CSV: comma-separated; JSON: an array) into `out`.
#[derive(Clone)]
pub(crate) struct RotationFormatter {
    style: Style,
    nums: NumWriter,
    vals: [f64; MAX_WIDTH],
}

impl RotationFormatter {
    /// A formatter for `style`.
    pub(crate) fn new(style: Style) -> Self {
        RotationFormatter {
            style,
            nums: NumWriter::new(style.num),
            vals: [0.0; MAX_WIDTH],
        }
    }

    /// `q` in the style's representation into `vals`; Euler angles from `euler` (radians,
    /// continuous along the track) when given.
    #[inline]
    fn fill(&mut self, q: DQuat, euler: Option<[f64; 3]>) {
        self.style.fill(q, euler, &mut self.vals);
    }

    /// The values of `q` in the style's representation (JSON component order for quaternions);
    /// Euler angles from `euler` when given.
    #[inline]
    pub(crate) fn values(&mut self, q: DQuat, euler: Option<[f64; 3]>) -> &[f64] {
        let repr = self.style.repr;
        self.fill(q, euler);
        let w = repr.width();
        if repr == Repr::Quat {
            let o = self.style.quat_order.from_wxyz([
                self.vals[0],
                self.vals[1],
                self.vals[2],
                self.vals[3],
            ]);
            self.vals[..4].copy_from_slice(&o);
        }
        &self.vals[..w]
    }

    /// Appends `q` as CSV cells, each preceded by a comma (quaternions always `w,x,y,z`).
    /// Returns whether every value was finite (the caller discards the bytes otherwise).
    #[inline]
    pub(crate) fn csv(&mut self, out: &mut Vec<u8>, q: DQuat, euler: Option<[f64; 3]>) -> bool {
        // CSV columns are named, so quaternions are always w,x,y,z.
        let repr = self.style.repr;
        self.fill(q, euler);
        let mut finite = true;
        for i in 0..repr.width() {
            out.push(b',');
            finite &= self.vals[i].is_finite();
            self.nums.float(out, self.vals[i]);
        }
        finite
    }

    /// The first problem with writing `q` (a non-finite value, or a quaternion that is not a
    /// rotation), computed again for the message (the cold path after [`Self::csv`] or
    /// [`Self::json`] returned `false`, or the caller's norm check failed).
    pub(crate) fn fault(&mut self, q: DQuat) -> Option<super::Bad> {
        let repr = self.style.repr;
        repr.from_quat(q, self.style.angles, &mut self.vals);
        super::rotation_fault(repr, q, &self.vals[..repr.width()])
    }

    /// Appends `q` as a JSON member: `"quat": [w, x, y, z]`, a matrix as rows, etc. Returns
    /// whether every value was finite (the caller discards the bytes otherwise).
    pub(crate) fn json(&mut self, out: &mut Vec<u8>, q: DQuat, euler: Option<[f64; 3]>) -> bool {
        let key = self.style.repr.json_key();
        let mut vals = [0.0; MAX_WIDTH];
        let n = {
            let v = self.values(q, euler);
            vals[..v.len()].copy_from_slice(v);
            v.len()
        };
        out.extend_from_slice(b"\"");
        out.extend_from_slice(key.as_bytes());
        out.extend_from_slice(b"\": [");
        let finite = vals[..n].iter().all(|x| x.is_finite());
        if self.style.repr == Repr::Matrix {
            for r in 0..3 {
                out.extend_from_slice(if r == 0 { b"[" } else { b", [" });
                for c in 0..3 {
                    if c > 0 {
                        out.extend_from_slice(b", ");
                    }
                    self.nums.float(out, vals[3 * r + c]);
                }
                out.push(b']');
            }
        } else {
            for (i, v) in vals[..n].iter().enumerate() {
                if i > 0 {
                    out.extend_from_slice(b", ");
                }
                self.nums.float(out, *v);
            }
        }
        out.push(b']');
        finite
    }
}
