//! Rotation representations (docs/spec.md §2) and their conversions to and from unit quaternions.
//!
//! Every representation converts to a unit [`DQuat`]; only quaternion input keeps its sign
//! (which `--path as-given` honours), the others give `w ≥ 0`. On output, quaternions are written
//! as they are; every other representation describes the rotation, so the sign does not matter.

pub(crate) mod arc;
mod euler;
pub mod magnitude;
mod matrix;
pub mod quat;
pub(crate) mod quat4;
pub mod spin;
mod unit;
pub mod unwrap;

use crate::error::InputResult;
use crate::error::input_err;
use crate::error::num;
pub use euler::EulerSeq;
use glam::{DMat3, DQuat, DVec3};
use std::fmt;
pub use unit::AngleUnit;

/// A rotation representation, as named by `--from`/`--to`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Repr {
    /// A unit quaternion `w, x, y, z` (`quat`).
    Quat,
    /// Euler angles in a sequence (`euler:ZYX` intrinsic, `euler:zyx` extrinsic).
    Euler(EulerSeq),
    /// A 3×3 rotation matrix, row-major (`matrix`).
    Matrix,
    /// A unit axis and an angle (`axis-angle`).
    AxisAngle,
    /// A rotation vector, axis × angle (`rotvec`).
    RotVec,
    /// The 6D representation of networks as pytorch3d's `matrix_to_rotation_6d` takes it: the
    /// first two *rows* of the rotation matrix, `m00, m01, m02, m10, m11, m12` (`rot6d:rows`).
    Rot6dRows,
    /// The 6D representation of Zhou et al. (2019): the first two *columns* of the rotation
    /// matrix, `m00, m10, m20, m01, m11, m21` (`rot6d:columns`).
    Rot6dColumns,
}

/// Component order of quaternions written as JSON arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum QuatOrder {
    /// Scalar first: `[w, x, y, z]` (scipy's `scalar_first=True`).
    #[default]
    Wxyz,
    /// Scalar last: `[x, y, z, w]` (scipy's default, glTF).
    Xyzw,
}

impl QuatOrder {
    /// `wxyz` or `xyzw`.
    pub fn parse(s: &str) -> InputResult<QuatOrder> {
        match s {
            "wxyz" => Ok(QuatOrder::Wxyz),
            "xyzw" => Ok(QuatOrder::Xyzw),
            _ => Err(input_err!("expected \"wxyz\" or \"xyzw\", found \"{s}\"")),
        }
    }

    /// `[w, x, y, z]` from an array in this order.
    pub fn to_wxyz(self, a: [f64; 4]) -> [f64; 4] {
        match self {
            QuatOrder::Wxyz => a,
            QuatOrder::Xyzw => [a[3], a[0], a[1], a[2]],
        }
    }

    /// An array in this order from `[w, x, y, z]`.
    pub fn from_wxyz(self, a: [f64; 4]) -> [f64; 4] {
        match self {
            QuatOrder::Wxyz => a,
            QuatOrder::Xyzw => [a[1], a[2], a[3], a[0]],
        }
    }
}

/// Smallest accepted quaternion norm.
pub(crate) const MIN_QUAT_NORM: f64 = 1e-6;
/// Norm deviation from 1 above which a quaternion draws a warning.
pub const QUAT_NORM_WARN: f64 = 1e-3;

/// Largest number of values any representation has (a matrix).
pub const MAX_WIDTH: usize = 9;

impl Repr {
    /// Parses `quat`, `euler:SEQ`, `matrix`, `axis-angle`, `rotvec`, `rot6d:rows`,
    /// `rot6d:columns`.
    pub fn parse(s: &str) -> InputResult<Repr> {
        match s {
            "quat" => Ok(Repr::Quat),
            "matrix" => Ok(Repr::Matrix),
            "axis-angle" => Ok(Repr::AxisAngle),
            "rotvec" => Ok(Repr::RotVec),
            "rot6d:rows" => Ok(Repr::Rot6dRows),
            "rot6d:columns" => Ok(Repr::Rot6dColumns),
            "rot6d" => Err(input_err!(
                "expected rot6d:rows (pytorch3d's matrix_to_rotation_6d: the matrix's first two \
                 rows) or rot6d:columns (Zhou et al.: its first two columns), found \"rot6d\""
            )),
            _ => match s.strip_prefix("euler:") {
                Some(seq) => Ok(Repr::Euler(EulerSeq::parse(seq)?)),
                None => Err(input_err!(
                    "expected one of quat, euler:SEQ (e.g. euler:ZYX), matrix, axis-angle, \
                     rotvec, rot6d:rows, rot6d:columns, found \"{s}\""
                )),
            },
        }
    }

    /// CSV column names, in order.
    pub fn columns(&self) -> &'static [&'static str] {
        match self {
            Repr::Quat => &["w", "x", "y", "z"],
            Repr::Euler(_) => &["e1", "e2", "e3"],
            Repr::Matrix => &[
                "m00", "m01", "m02", "m10", "m11", "m12", "m20", "m21", "m22",
            ],
            Repr::AxisAngle => &["ax", "ay", "az", "angle"],
            Repr::RotVec => &["rx", "ry", "rz"],
            Repr::Rot6dRows => &["r0x", "r0y", "r0z", "r1x", "r1y", "r1z"],
            Repr::Rot6dColumns => &["c0x", "c0y", "c0z", "c1x", "c1y", "c1z"],
        }
    }

    /// Number of values.
    pub fn width(&self) -> usize {
        self.columns().len()
    }

    /// JSON key of a keyframe or frame.
    pub fn json_key(&self) -> &'static str {
        match self {
            Repr::Quat => "quat",
            Repr::Euler(_) => "euler",
            Repr::Matrix => "matrix",
            Repr::AxisAngle => "axis_angle",
            Repr::RotVec => "rotvec",
            Repr::Rot6dRows | Repr::Rot6dColumns => "rot6d",
        }
    }

    /// True when the values contain angles (so `--angles` applies).
    pub fn has_angles(&self) -> bool {
        matches!(self, Repr::Euler(_) | Repr::AxisAngle | Repr::RotVec)
    }

    /// Converts values (quaternions as `[w, x, y, z]`, matrices row-major) to a unit quaternion.
    /// Returns a warning when a quaternion's norm is off 1 by more than 1e-3.
    ///
    /// Lengths are computed without overflow or underflow ([`magnitude`]): a quaternion or axis
    /// of any finite non-zero scale is normalised. Angles in degrees are reduced exactly modulo
    /// 360 first, so any finite value works (1e200° is 128°); in radians an angle, Euler angle or
    /// rotation vector beyond 1e15 rad is an error, and so is a rotation vector longer than 1e15
    /// degrees (its length is rounded, so its fraction of a turn is lost beyond that).
    pub fn to_quat(&self, v: &[f64], unit: AngleUnit) -> InputResult<(DQuat, Option<String>)> {
        debug_assert_eq!(v.len(), self.width());
        if let Some(bad) = v.iter().find(|x| !x.is_finite()) {
            return Err(input_err!("expected a finite number, found {bad}"));
        }
        let q = match *self {
            Repr::Quat => {
                // q = s·w with w safe to square; s = 1 for ordinary values.
                let (s, w) = magnitude::split([v[1], v[2], v[3], v[0]]);
                let q = DQuat::from_array(w);
                let r = q.length();
                let n = s * r;
                if n < MIN_QUAT_NORM {
                    return Err(input_err!(
                        "expected a quaternion of non-zero length, found norm {n:e}"
                    ));
                }
                let warning = ((n - 1.0).abs() > QUAT_NORM_WARN).then(|| {
                    format!(
                        "quaternion norm {} is off 1 by more than 1e-3; normalized",
                        magnitude::product_num(&[r, s], None)
                    )
                });
                return Ok((q / r, warning));
            }
            Repr::Euler(seq) => {
                let mut rad = [0.0; 3];
                for (i, (r, &a)) in rad.iter_mut().zip(v).enumerate() {
                    *r = magnitude::angle_to_rad(a, unit).ok_or_else(|| {
                        input_err!(
                            "expected Euler angles within ±{:e} rad, found e{} = {}",
                            magnitude::MAX_ANGLE,
                            i + 1,
                            num(a)
                        )
                    })?;
                }
                seq.to_quat(rad)
            }
            Repr::Matrix => {
                let rows = [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]];
                matrix::to_quat(rows)?
            }
            Repr::AxisAngle => {
                let (_, w) = magnitude::split([v[0], v[1], v[2]]);
                let axis = DVec3::from_array(w);
                let n = axis.length();
                if n == 0.0 {
                    if v[3] != 0.0 {
                        return Err(input_err!(
                            "expected a non-zero axis for a non-zero angle, found axis (0, 0, 0)"
                        ));
                    }
                    DQuat::IDENTITY
                } else {
                    let angle = magnitude::angle_to_rad(v[3], unit).ok_or_else(|| {
                        input_err!(
                            "expected an angle within ±{:e} rad, found {}",
                            magnitude::MAX_ANGLE,
                            num(v[3])
                        )
                    })?;
                    from_unit_axis(axis / n, angle)
                }
            }
            Repr::Rot6dRows | Repr::Rot6dColumns => {
                let (b1, b2, b3) = gram_schmidt(v)?;
                // b1, b2 (and b3) are the matrix's rows, or its columns.
                let rows = match *self {
                    Repr::Rot6dRows => [b1, b2, b3],
                    _ => [
                        [b1[0], b2[0], b3[0]],
                        [b1[1], b2[1], b3[1]],
                        [b1[2], b2[2], b3[2]],
                    ],
                };
                matrix::to_quat(rows)?
            }
            Repr::RotVec => {
                let (s, w) = magnitude::split([v[0], v[1], v[2]]);
                let dir = DVec3::from_array(w);
                let r = dir.length();
                if r == 0.0 {
                    DQuat::IDENTITY
                } else {
                    // The length in the vector's own unit; rounded, so not reduced exactly.
                    let len = s * r;
                    if len > magnitude::MAX_ANGLE {
                        return Err(input_err!(
                            "expected a rotation vector no longer than {:e} {}, found length {}",
                            magnitude::MAX_ANGLE,
                            unit.as_str(),
                            magnitude::product_num(&[r, s], None)
                        ));
                    }
                    let angle = match unit {
                        AngleUnit::Deg => (len % 360.0).to_radians(),
                        AngleUnit::Rad => len,
                    };
                    from_unit_axis(dir / r, angle)
                }
            }
        };
        Ok((quat::canonical(q.normalize()), None))
    }

    /// Writes the values of `q` into `out[..width]` (quaternion `[w, x, y, z]` with its sign,
    /// matrix row-major, angles in `unit`).
    pub fn from_quat(&self, q: DQuat, unit: AngleUnit, out: &mut [f64; MAX_WIDTH]) {
        match *self {
            Repr::Quat => out[..4].copy_from_slice(&[q.w, q.x, q.y, q.z]),
            Repr::Euler(seq) => {
                let a = seq.from_quat(q);
                out[..3].copy_from_slice(&a.map(|x| unit.from_rad(x)));
            }
            Repr::Matrix => {
                let rows = matrix::to_rows(&DMat3::from_quat(q));
                for (r, row) in rows.iter().enumerate() {
                    out[3 * r..3 * r + 3].copy_from_slice(row);
                }
            }
            Repr::AxisAngle => {
                let l = quat::log(quat::canonical(q));
                let half = l.length();
                let axis = if half > 0.0 { l / half } else { DVec3::X };
                out[..4].copy_from_slice(&[axis.x, axis.y, axis.z, unit.from_rad(2.0 * half)]);
            }
            Repr::RotVec => {
                let r = quat::log(quat::canonical(q)) * 2.0;
                out[..3].copy_from_slice(&r.to_array().map(|x| unit.from_rad(x)));
            }
            Repr::Rot6dRows => {
                let rows = matrix::to_rows(&DMat3::from_quat(q));
                out[..3].copy_from_slice(&rows[0]);
                out[3..6].copy_from_slice(&rows[1]);
            }
            Repr::Rot6dColumns => {
                let m = DMat3::from_quat(q);
                out[..3].copy_from_slice(&m.x_axis.to_array());
                out[3..6].copy_from_slice(&m.y_axis.to_array());
            }
        }
    }
}

/// pytorch3d's `rotation_6d_to_matrix` (Zhou et al. 2019, §B): `b1 = a1/‖a1‖`,
/// `b2 = (a2 − (b1·a2) b1)/‖…‖`, `b3 = b1 × b2`, for `v = [a1, a2]`. Two vectors that are
/// (nearly) zero or parallel span no frame: an error, never NaN.
fn gram_schmidt(v: &[f64]) -> InputResult<([f64; 3], [f64; 3], [f64; 3])> {
    let a1 = DVec3::new(v[0], v[1], v[2]);
    let a2 = DVec3::new(v[3], v[4], v[5]);
    // Scale-free: both vectors brought to unit-ish size before any product (no overflow).
    let unit = |a: DVec3| {
        let (_, w) = magnitude::split(a.to_array());
        let w = DVec3::from_array(w);
        let n = w.length();
        (n > 0.0).then(|| w / n)
    };
    let (Some(b1), Some(u2)) = (unit(a1), unit(a2)) else {
        return Err(input_err!(
            "expected two non-zero vectors (6D rotation), found a zero vector"
        ));
    };
    let e2 = u2 - b1 * b1.dot(u2);
    // sin of the angle between a1 and a2: below 1e-6 they are parallel for this purpose.
    let s = e2.length();
    if s < 1e-6 {
        return Err(input_err!(
            "expected two non-parallel vectors (6D rotation), found vectors {}° apart",
            num(b1.dot(u2).clamp(-1.0, 1.0).acos().to_degrees())
        ));
    }
    let b2 = e2 / s;
    let b3 = b1.cross(b2);
    Ok((b1.to_array(), b2.to_array(), b3.to_array()))
}

/// The rotation by `angle` (radians) about the unit `axis`: `(cos ½angle, sin ½angle·axis)`.
/// (Not `exp(axis·½angle)`: that would recompute the angle as a rounded length.)
fn from_unit_axis(axis: DVec3, angle: f64) -> DQuat {
    let (s, c) = (0.5 * angle).sin_cos();
    DQuat::from_xyzw(axis.x * s, axis.y * s, axis.z * s, c)
}

impl fmt::Display for Repr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Repr::Quat => f.write_str("quat"),
            Repr::Euler(seq) => write!(f, "euler:{}", seq.as_str()),
            Repr::Matrix => f.write_str("matrix"),
            Repr::AxisAngle => f.write_str("axis-angle"),
            Repr::RotVec => f.write_str("rotvec"),
            Repr::Rot6dRows => f.write_str("rot6d:rows"),
            Repr::Rot6dColumns => f.write_str("rot6d:columns"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(repr: Repr, q: DQuat, unit: AngleUnit) -> DQuat {
        let mut buf = [0.0; MAX_WIDTH];
        repr.from_quat(q, unit, &mut buf);
        repr.to_quat(&buf[..repr.width()], unit).unwrap().0
    }

    #[test]
    fn every_repr_round_trips() {
        let q = DQuat::from_euler(glam::EulerRot::ZYX, 0.3, 1.2, -2.5);
        let reprs = [
            Repr::Quat,
            Repr::Matrix,
            Repr::AxisAngle,
            Repr::RotVec,
            Repr::Rot6dRows,
            Repr::Rot6dColumns,
            Repr::parse("euler:zxz").unwrap(),
        ];
        for repr in reprs {
            for unit in [AngleUnit::Deg, AngleUnit::Rad] {
                let back = round_trip(repr, q, unit);
                assert!(quat::rotation_angle_between(q, back) < 1e-12, "{repr}");
            }
        }
    }

    #[test]
    fn quaternion_input_keeps_sign_others_canonical() {
        let v = [-0.5, 0.5, 0.5, 0.5];
        let (q, w) = Repr::Quat.to_quat(&v, AngleUnit::Deg).unwrap();
        assert_eq!(q.w, -0.5);
        assert!(w.is_none());
        let (q, _) = Repr::RotVec
            .to_quat(&[0.0, 0.0, 350.0], AngleUnit::Deg)
            .unwrap();
        assert!(q.w >= 0.0);
    }

    #[test]
    fn quaternion_validation() {
        assert!(Repr::Quat.to_quat(&[0.0; 4], AngleUnit::Deg).is_err());
        assert!(
            Repr::Quat
                .to_quat(&[f64::NAN, 0.0, 0.0, 0.0], AngleUnit::Deg)
                .is_err()
        );
        let (_, w) = Repr::Quat
            .to_quat(&[1.01, 0.0, 0.0, 0.0], AngleUnit::Deg)
            .unwrap();
        assert!(w.unwrap().contains("norm"));
    }

    #[test]
    fn zero_axis() {
        assert!(
            Repr::AxisAngle
                .to_quat(&[0.0, 0.0, 0.0, 10.0], AngleUnit::Deg)
                .is_err()
        );
        let (q, _) = Repr::AxisAngle
            .to_quat(&[0.0, 0.0, 0.0, 0.0], AngleUnit::Deg)
            .unwrap();
        assert_eq!(q, DQuat::IDENTITY);
    }

    /// The rotation by `deg` degrees about the unit `axis`, by the closed form, `w ≥ 0`.
    fn closed_form(axis: DVec3, deg: f64) -> DQuat {
        let h = deg.to_radians() / 2.0;
        quat::canonical(DQuat::from_xyzw(
            axis.x * h.sin(),
            axis.y * h.sin(),
            axis.z * h.sin(),
            h.cos(),
        ))
    }

    fn message(repr: Repr, v: &[f64], unit: AngleUnit) -> String {
        repr.to_quat(v, unit).unwrap_err().message().to_string()
    }

    #[test]
    fn large_quaternions_are_normalised() {
        // Their norm overflowed to inf (the result was 0, 0, 0, 0).
        let (q, w) = Repr::Quat
            .to_quat(&[1e200, 0.0, 0.0, 0.0], AngleUnit::Deg)
            .unwrap();
        assert_eq!(q, DQuat::IDENTITY);
        assert_eq!(
            w.as_deref(),
            Some("quaternion norm 1e200 is off 1 by more than 1e-3; normalized")
        );
        // A norm beyond f64 itself (2e308): each component is half the norm.
        let (q, w) = Repr::Quat
            .to_quat(&[-1e308, 1e308, 1e308, 1e308], AngleUnit::Deg)
            .unwrap();
        assert_eq!(q, DQuat::from_xyzw(0.5, 0.5, 0.5, -0.5));
        assert_eq!(
            w.as_deref(),
            Some("quaternion norm 2e308 is off 1 by more than 1e-3; normalized")
        );
    }

    #[test]
    fn tiny_quaternions_keep_their_norm_in_the_message() {
        // The norm underflowed to 0 and was printed as 0e0.
        assert_eq!(
            message(Repr::Quat, &[1e-300, 0.0, 0.0, 0.0], AngleUnit::Deg),
            "expected a quaternion of non-zero length, found norm 1e-300"
        );
        assert_eq!(
            message(Repr::Quat, &[0.0, 3e-200, 0.0, 4e-200], AngleUnit::Deg),
            "expected a quaternion of non-zero length, found norm 5e-200"
        );
        assert_eq!(
            message(Repr::Quat, &[0.0; 4], AngleUnit::Deg),
            "expected a quaternion of non-zero length, found norm 0e0"
        );
    }

    #[test]
    fn axes_of_any_scale_are_normalised() {
        // (1e200, 0, 0) silently became the identity; (1e-320, 0, 0) an error "axis (0, 0, 0)".
        let want = closed_form(DVec3::X, 90.0);
        for scale in [1e200, 1e-320, f64::MAX] {
            let (q, _) = Repr::AxisAngle
                .to_quat(&[scale, 0.0, 0.0, 90.0], AngleUnit::Deg)
                .unwrap();
            assert!((q - want).length() < 1e-15, "{scale:e}: {q}");
        }
        let (q, _) = Repr::AxisAngle
            .to_quat(&[0.0, 3e250, -4e250, 60.0], AngleUnit::Deg)
            .unwrap();
        assert!((q - closed_form(DVec3::new(0.0, 0.6, -0.8), 60.0)).length() < 1e-15);
    }

    #[test]
    fn degrees_are_reduced_exactly_before_conversion() {
        // int(1e200) mod 360 = 128, int(-1e200) mod 360 = 232 ≡ −128, int(1e15) mod 360 = 280
        // (Python's exact integers).
        let (q, _) = Repr::AxisAngle
            .to_quat(&[0.0, 0.0, 2.0, 1e200], AngleUnit::Deg)
            .unwrap();
        assert!((q - closed_form(DVec3::Z, 128.0)).length() < 1e-15, "{q}");
        let (q, _) = Repr::AxisAngle
            .to_quat(&[0.0, 0.0, 2.0, -1e200], AngleUnit::Deg)
            .unwrap();
        assert!((q - closed_form(DVec3::Z, -128.0)).length() < 1e-15, "{q}");
        let zyx = Repr::parse("euler:ZYX").unwrap();
        let (q, _) = zyx.to_quat(&[0.0, 1e200, 0.0], AngleUnit::Deg).unwrap();
        assert!((q - closed_form(DVec3::Y, 128.0)).length() < 1e-15, "{q}");
        // A rotation vector along an axis has an exact length: 1e15° ≡ 280° ≡ −80°.
        let (q, _) = Repr::RotVec
            .to_quat(&[0.0, 0.0, 1e15], AngleUnit::Deg)
            .unwrap();
        assert!((q - closed_form(DVec3::Z, -80.0)).length() < 1e-15, "{q}");
    }

    #[test]
    fn radians_that_lose_the_turn_are_refused() {
        assert_eq!(
            message(Repr::AxisAngle, &[1.0, 0.0, 0.0, 1e300], AngleUnit::Rad),
            "expected an angle within ±1e15 rad, found 1e300"
        );
        assert_eq!(
            message(
                Repr::parse("euler:zxz").unwrap(),
                &[0.0, -2e15, 0.0],
                AngleUnit::Rad
            ),
            "expected Euler angles within ±1e15 rad, found e2 = -2e15"
        );
        assert_eq!(
            message(Repr::RotVec, &[1e300, 0.0, 0.0], AngleUnit::Rad),
            "expected a rotation vector no longer than 1e15 rad, found length 1e300"
        );
        // A length beyond f64 keeps its digits: √3·1e308.
        assert_eq!(
            message(Repr::RotVec, &[1e308, -1e308, 1e308], AngleUnit::Rad),
            "expected a rotation vector no longer than 1e15 rad, found length 1.7320508075688772e308"
        );
        // Rotation vectors in degrees too: their length is rounded, so not reduced exactly.
        assert_eq!(
            message(Repr::RotVec, &[0.0, 1e200, 0.0], AngleUnit::Deg),
            "expected a rotation vector no longer than 1e15 deg, found length 1e200"
        );
        // At the limit: accepted, and sin/cos reduce the exact binary value.
        let (q, _) = Repr::RotVec
            .to_quat(&[1e15, 0.0, 0.0], AngleUnit::Rad)
            .unwrap();
        let h: f64 = 0.5e15;
        let want = quat::canonical(DQuat::from_xyzw(h.sin(), 0.0, 0.0, h.cos()));
        assert!((q - want).length() < 1e-15);
        assert!(
            Repr::AxisAngle
                .to_quat(&[1.0, 0.0, 0.0, -1e15], AngleUnit::Rad)
                .is_ok()
        );
    }

    #[test]
    fn huge_and_tiny_matrices_report_their_numbers() {
        let diag = |a: f64, b: f64| [a, 0.0, 0.0, 0.0, b, 0.0, 0.0, 0.0, b];
        // 1e200·I: RᵀR − I = (1e400 − 1)·I, Frobenius norm √3·1e400.
        assert_eq!(
            message(Repr::Matrix, &diag(1e200, 1e200), AngleUnit::Deg),
            "expected an orthonormal rotation matrix (‖RᵀR − I‖ ≤ 1e-3), found ‖RᵀR − I‖ = 1.732e400"
        );
        // diag(−1e200, 1e200, 1e200): determinant −1e600.
        assert_eq!(
            message(Repr::Matrix, &diag(-1e200, 1e200), AngleUnit::Deg),
            "expected a rotation matrix, found a reflection (determinant -1e600)"
        );
        assert_eq!(
            message(Repr::Matrix, &diag(-1e-200, 1e-200), AngleUnit::Deg),
            "expected a rotation matrix, found a reflection (determinant -1e-600)"
        );
        // 1e-200·I: RᵀR ≈ 0, so ‖RᵀR − I‖ = √3.
        assert_eq!(
            message(Repr::Matrix, &diag(1e-200, 1e-200), AngleUnit::Deg),
            "expected an orthonormal rotation matrix (‖RᵀR − I‖ ≤ 1e-3), found ‖RᵀR − I‖ = 1.732e0"
        );
    }

    #[test]
    fn axis_angle_output_is_in_0_pi() {
        let q = -DQuat::from_rotation_x(0.4);
        let mut buf = [0.0; MAX_WIDTH];
        Repr::AxisAngle.from_quat(q, AngleUnit::Rad, &mut buf);
        assert!((buf[3] - 0.4).abs() < 1e-15);
        assert!((buf[0] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn repr_names_round_trip() {
        for s in [
            "quat",
            "matrix",
            "axis-angle",
            "rotvec",
            "euler:ZYX",
            "euler:xyx",
        ] {
            assert_eq!(Repr::parse(s).unwrap().to_string(), s);
        }
        assert!(Repr::parse("euler").is_err());
        assert!(Repr::parse("quaternion").is_err());
    }
}
