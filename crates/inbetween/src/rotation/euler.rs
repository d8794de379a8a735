//! Euler sequences in scipy's notation, mapped onto glam's 24 [`EulerRot`] variants.
//!
//! ```text
//! SEQ  = three letters from xyzXYZ, all upper or all lower case, no letter twice in a row
//! "XYZ" (upper case)  intrinsic, rotating axes:  R = Rx(a) · Ry(b) · Rz(c)
//! "xyz" (lower case)  extrinsic, fixed axes:     R = Rz(c) · Ry(b) · Rx(a)
//! ```
//! (a, b, c) are the angles in the order the letters are written; `R` rotates column vectors.
//! This is scipy's `Rotation.from_euler(seq, [a, b, c])`, and glam's `EulerRot::XYZ` (intrinsic)
//! and `EulerRot::XYZEx` (extrinsic) with the same angle order.

use crate::error::InputResult;
use crate::error::input_err;
use glam::{DQuat, EulerRot};

/// A validated Euler sequence.
///
/// The convention, pinned: intrinsic `ZYX` is `Rz(a)·Ry(b)·Rx(c)`, extrinsic `xyz` is the same
/// matrix product read from the right, and the decomposition returns the angles in the order
/// the letters are written.
///
/// ```
/// use inbetween::EulerSeq;
/// use glam::DQuat;
///
/// let (a, b, c) = (0.3, -0.2, 1.1);
/// let zyx = EulerSeq::parse("ZYX")?;
/// let q = zyx.to_quat([a, b, c]);
/// let product = DQuat::from_rotation_z(a) * DQuat::from_rotation_y(b) * DQuat::from_rotation_x(c);
/// assert!((q - product).length() < 1e-15 || (q + product).length() < 1e-15);
/// // Extrinsic x-y-z with the angles reversed is the same rotation.
/// let xyz = EulerSeq::parse("xyz")?.to_quat([c, b, a]);
/// assert!((q - xyz).length() < 1e-15 || (q + xyz).length() < 1e-15);
/// let back = zyx.from_quat(q);
/// assert!((back[0] - a).abs() < 1e-14 && (back[1] - b).abs() < 1e-14 && (back[2] - c).abs() < 1e-14);
/// assert!(EulerSeq::parse("ZYx").is_err());
/// # Ok::<(), inbetween::InputError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EulerSeq {
    /// The three letters as the user writes them (case carries intrinsic/extrinsic).
    letters: [u8; 3],
    rot: EulerRot,
}

impl EulerSeq {
    /// Parses a scipy-style sequence such as `ZYX` (intrinsic) or `zxz` (extrinsic).
    pub fn parse(s: &str) -> InputResult<EulerSeq> {
        let b = s.as_bytes();
        let valid_letters = b.len() == 3 && b.iter().all(|c| b"xyzXYZ".contains(c));
        let same_case = valid_letters
            && (b.iter().all(u8::is_ascii_uppercase) || b.iter().all(u8::is_ascii_lowercase));
        if !same_case || b[0].eq_ignore_ascii_case(&b[1]) || b[1].eq_ignore_ascii_case(&b[2]) {
            return Err(input_err!(
                "expected an Euler sequence of three letters from xyz (extrinsic) or XYZ \
                 (intrinsic) with no axis twice in a row, such as ZYX or zxz, found \"{s}\""
            ));
        }
        let intrinsic = b[0].is_ascii_uppercase();
        let up = [
            b[0].to_ascii_uppercase(),
            b[1].to_ascii_uppercase(),
            b[2].to_ascii_uppercase(),
        ];
        use EulerRot::*;
        let rot = match (&up, intrinsic) {
            (b"XYZ", true) => XYZ,
            (b"XZY", true) => XZY,
            (b"YXZ", true) => YXZ,
            (b"YZX", true) => YZX,
            (b"ZXY", true) => ZXY,
            (b"ZYX", true) => ZYX,
            (b"XYX", true) => XYX,
            (b"XZX", true) => XZX,
            (b"YXY", true) => YXY,
            (b"YZY", true) => YZY,
            (b"ZXZ", true) => ZXZ,
            (b"ZYZ", true) => ZYZ,
            (b"XYZ", false) => XYZEx,
            (b"XZY", false) => XZYEx,
            (b"YXZ", false) => YXZEx,
            (b"YZX", false) => YZXEx,
            (b"ZXY", false) => ZXYEx,
            (b"ZYX", false) => ZYXEx,
            (b"XYX", false) => XYXEx,
            (b"XZX", false) => XZXEx,
            (b"YXY", false) => YXYEx,
            (b"YZY", false) => YZYEx,
            (b"ZXZ", false) => ZXZEx,
            (b"ZYZ", false) => ZYZEx,
            _ => unreachable!("validated above: 3 axis letters, no repeats in a row"),
        };
        Ok(EulerSeq {
            letters: [b[0], b[1], b[2]],
            rot,
        })
    }

    /// All 24 sequences: 12 intrinsic then 12 extrinsic.
    pub fn all() -> Vec<EulerSeq> {
        let names = [
            "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
        ];
        let upper = names.iter().map(|n| n.to_string());
        let lower = names.iter().map(|n| n.to_ascii_lowercase());
        upper
            .chain(lower)
            .map(|n| EulerSeq::parse(&n).expect("the 24 names are valid"))
            .collect()
    }

    /// The sequence as written, e.g. `ZYX`.
    pub fn as_str(&self) -> &str {
        std::str::from_utf8(&self.letters).unwrap_or("???")
    }

    /// The glam variant this sequence maps to.
    pub fn euler_rot(&self) -> EulerRot {
        self.rot
    }

    /// The rotation for angles (radians) in the order of the letters.
    pub fn to_quat(&self, angles: [f64; 3]) -> DQuat {
        DQuat::from_euler(self.rot, angles[0], angles[1], angles[2])
    }

    /// Angles (radians) in the order of the letters. Ranges as scipy: first and third in
    /// [−π, π); the middle in [−π/2, π/2] (Tait–Bryan) or [0, π] (proper Euler).
    ///
    /// Computed directly from the quaternion by the method of Bernardes & Viollet (2022,
    /// "Quaternion to Euler angles conversion: a direct, general and computationally efficient
    /// method", PLOS ONE 17(11)), as scipy's `as_euler` does. glam's `to_euler` goes through the
    /// matrix and loses up to 2e-5 rad near gimbal lock (measured: the round-trip test in
    /// `tests/cli/conventions.rs` fails with it); this stays within 1e-12 rad everywhere.
    ///
    /// At gimbal lock scipy sets the third angle to zero once the middle angle is within 1e-7 of
    /// its singular value, which moves the rebuilt rotation by up to ~1e-7 rad. We do that only
    /// at an exact singularity; near it the regular formula is still exact for the rotation
    /// (only the split between first and third angle is ill-conditioned), so every triple
    /// rebuilds the rotation to 1e-12.
    pub fn from_quat(&self, q: DQuat) -> [f64; 3] {
        use std::f64::consts::{FRAC_PI_2, PI, TAU};
        let quat = [q.x, q.y, q.z, q.w];
        let extrinsic = self.letters[0].is_ascii_lowercase();
        let idx = |c: u8| (c.to_ascii_lowercase() - b'x') as usize;
        let mut axes = [
            idx(self.letters[0]),
            idx(self.letters[1]),
            idx(self.letters[2]),
        ];
        if !extrinsic {
            axes.reverse();
        }
        let [i, j, mut k] = axes;
        let symmetric = i == k;
        if symmetric {
            k = 3 - i - j;
        }
        let sign =
            ((i as i64 - j as i64) * (j as i64 - k as i64) * (k as i64 - i as i64) / 2) as f64;
        let (a, b, c, d) = if symmetric {
            (quat[3], quat[i], quat[j], quat[k] * sign)
        } else {
            (
                quat[3] - quat[j],
                quat[i] + quat[k] * sign,
                quat[j] + quat[3],
                quat[k] * sign - quat[i],
            )
        };
        let half_sum = b.atan2(a);
        let half_diff = d.atan2(c);
        let cd = c.hypot(d);
        let ab = a.hypot(b);
        let mut angles = [0.0; 3];
        angles[1] = 2.0 * cd.atan2(ab);
        let (first, third) = if extrinsic { (0, 2) } else { (2, 0) };
        let tb_sign = if symmetric { 1.0 } else { sign };
        if cd == 0.0 || ab == 0.0 {
            // Exact gimbal lock: scipy's choice, the angle goes to index 0 and the other is 0.
            angles[0] = if cd == 0.0 {
                2.0 * half_sum
            } else {
                2.0 * half_diff * if extrinsic { -1.0 } else { 1.0 }
            };
            if third == 0 {
                angles[0] *= tb_sign;
            }
        } else {
            angles[first] = half_sum - half_diff;
            angles[third] = (half_sum + half_diff) * tb_sign;
        }
        if !symmetric {
            angles[1] -= FRAC_PI_2;
        }
        // Only the first and third angles wrap (as scipy): the middle one is already in its range,
        // and wrapping it would turn a proper Euler sequence's 180° into −180°.
        let wrap = |x: f64| (x + PI).rem_euclid(TAU) - PI;
        [wrap(angles[0]), angles[1], wrap(angles[2])]
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn proper_euler_middle_angle_at_half_turn_is_plus_180() {
        // ZXZ with the middle angle exactly 180°: scipy's range for it is [0°, 180°].
        let seq = EulerSeq::parse("ZXZ").unwrap();
        let q = seq.to_quat([0.3, std::f64::consts::PI, 0.2]);
        let e = seq.from_quat(q);
        assert!(e[1] >= 0.0, "{e:?}");
        assert!((e[1] - std::f64::consts::PI).abs() < 1e-15, "{e:?}");
    }

    use super::*;
    use glam::DMat3;

    #[test]
    fn intrinsic_and_extrinsic_matrix_products() {
        let (a, b, c) = (0.3, -0.7, 1.1);
        let rx = DMat3::from_rotation_x(a);
        let ry = DMat3::from_rotation_y(b);
        let rz = DMat3::from_rotation_z(c);
        let intrinsic = DMat3::from_quat(EulerSeq::parse("XYZ").unwrap().to_quat([a, b, c]));
        assert!(intrinsic.abs_diff_eq(rx * ry * rz, 1e-14));
        let extrinsic = DMat3::from_quat(EulerSeq::parse("xyz").unwrap().to_quat([a, b, c]));
        assert!(extrinsic.abs_diff_eq(rz * ry * rx, 1e-14));
    }

    #[test]
    fn rejects_bad_sequences() {
        for s in ["XXY", "xYz", "XY", "ABC", "XYZX", "zzx"] {
            assert!(EulerSeq::parse(s).is_err(), "{s}");
        }
    }

    #[test]
    fn all_has_24_distinct() {
        let all = EulerSeq::all();
        assert_eq!(all.len(), 24);
        let mut rots: Vec<_> = all.iter().map(|s| format!("{:?}", s.euler_rot())).collect();
        rots.sort();
        rots.dedup();
        assert_eq!(rots.len(), 24);
    }
}
