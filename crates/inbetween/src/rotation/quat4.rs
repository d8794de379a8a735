//! Four quaternions as SIMD lanes (`wide::f64x4`), structure-of-arrays: the curves' blends
//! (`curve/blend4.rs`), the Bézier segments built four at a time and the tangents' logarithms
//! (`tangent/logs.rs`) share it.

use glam::DQuat;
use wide::f64x4;

/// Four quaternions as lanes: `[w, x, y, z]` each an `f64x4`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Quat4 {
    pub w: f64x4,
    pub x: f64x4,
    pub y: f64x4,
    pub z: f64x4,
}

impl Quat4 {
    /// The 4D dot product `((w·w′ + x·x′) + y·y′) + z·z′` in each lane.
    #[inline]
    pub(crate) fn dot(self, b: Quat4) -> f64x4 {
        self.w * b.w + self.x * b.x + self.y * b.y + self.z * b.z
    }

    /// `self·ca + b·cb` in every component.
    #[inline]
    pub(crate) fn combine(self, ca: f64x4, b: Quat4, cb: f64x4) -> Quat4 {
        Quat4 {
            w: self.w * ca + b.w * cb,
            x: self.x * ca + b.x * cb,
            y: self.y * ca + b.y * cb,
            z: self.z * ca + b.z * cb,
        }
    }

    /// `self/k` in every component.
    #[inline]
    pub(crate) fn over(self, k: f64x4) -> Quat4 {
        Quat4 {
            w: self.w / k,
            x: self.x / k,
            y: self.y / k,
            z: self.z / k,
        }
    }

    /// The quaternion product `self·rhs` in each lane: glam's `DQuat * DQuat`, operation for
    /// operation, so a lane is the scalar product's bits.
    #[inline]
    pub(crate) fn mul(self, rhs: Quat4) -> Quat4 {
        let (x0, y0, z0, w0) = (self.x, self.y, self.z, self.w);
        let (x1, y1, z1, w1) = (rhs.x, rhs.y, rhs.z, rhs.w);
        Quat4 {
            x: w0 * x1 + x0 * w1 + y0 * z1 - z0 * y1,
            y: w0 * y1 - x0 * z1 + y0 * w1 + z0 * x1,
            z: w0 * z1 + x0 * y1 - y0 * x1 + z0 * w1,
            w: w0 * w1 - x0 * x1 - y0 * y1 - z0 * z1,
        }
    }

    /// The conjugate `(w, −x, −y, −z)` in each lane.
    #[inline]
    pub(crate) fn conjugate(self) -> Quat4 {
        Quat4 {
            w: self.w,
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }

    /// The same quaternion in every lane.
    #[inline]
    pub(crate) fn splat(q: DQuat) -> Quat4 {
        Quat4 {
            w: f64x4::splat(q.w),
            x: f64x4::splat(q.x),
            y: f64x4::splat(q.y),
            z: f64x4::splat(q.z),
        }
    }

    #[inline]
    pub(crate) fn from_quats(q: &[DQuat; 4]) -> Quat4 {
        Quat4 {
            w: f64x4::new([q[0].w, q[1].w, q[2].w, q[3].w]),
            x: f64x4::new([q[0].x, q[1].x, q[2].x, q[3].x]),
            y: f64x4::new([q[0].y, q[1].y, q[2].y, q[3].y]),
            z: f64x4::new([q[0].z, q[1].z, q[2].z, q[3].z]),
        }
    }

    #[inline]
    pub(crate) fn to_quats(self) -> [DQuat; 4] {
        let (w, x, y, z) = (
            self.w.to_array(),
            self.x.to_array(),
            self.y.to_array(),
            self.z.to_array(),
        );
        std::array::from_fn(|i| DQuat::from_xyzw(x[i], y[i], z[i], w[i]))
    }
}

/// Below this `|x|` (2²⁶) `wide`'s `sin_cos` is within an ulp or so of libm's: its Cody–Waite
/// reduction by π/2 in three parts is exact while the quadrant count stays below 2²⁹
/// (measured: 1.1e-16 up to 5e8, 6e-8 at 1e9, 8e-3 at 1e14).
pub(crate) const LANE_TRIG_MAX: f64 = 67_108_864.0;

/// `(sin x, cos x)` in lanes, the lanes with `|x|` beyond [`LANE_TRIG_MAX`] by the scalar
/// (libm) functions, so an arc of many turns (a tangent of 10⁹ rad/s) is as accurate as
/// libm's while every other lane keeps the vector polynomials' bits.
#[inline]
pub(crate) fn sin_cos4(x: f64x4) -> (f64x4, f64x4) {
    let (s, c) = x.sin_cos();
    if !x.abs().simd_gt(f64x4::splat(LANE_TRIG_MAX)).any() {
        return (s, c);
    }
    let (mut s, mut c, x) = (s.to_array(), c.to_array(), x.to_array());
    for l in 0..4 {
        if x[l].abs() > LANE_TRIG_MAX {
            (s[l], c[l]) = x[l].sin_cos();
        }
    }
    (f64x4::new(s), f64x4::new(c))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Within 2 ulp of libm's at every size, the far lanes libm's exactly; inf and NaN give NaN.
    #[test]
    fn sin_cos4_is_libms_at_every_size() {
        for e in 0..=15 {
            for k in 0..200 {
                let x =
                    10f64.powi(e) * (1.0 + k as f64 * 1e-3) * if k % 2 == 0 { 1.0 } else { -1.0 };
                let lanes = f64x4::new([x, 0.5, -x, 1e12]);
                let (s, c) = sin_cos4(lanes);
                for (l, v) in lanes.to_array().into_iter().enumerate() {
                    let (s0, c0) = v.sin_cos();
                    let (s1, c1) = (s.to_array()[l], c.to_array()[l]);
                    assert!(
                        (s1 - s0).abs() <= 2.3e-16 && (c1 - c0).abs() <= 2.3e-16,
                        "{v:e}"
                    );
                    if v.abs() > LANE_TRIG_MAX {
                        assert_eq!((s1.to_bits(), c1.to_bits()), (s0.to_bits(), c0.to_bits()));
                    }
                }
            }
        }
        let (s, c) = sin_cos4(f64x4::new([f64::INFINITY, f64::NAN, 0.0, -0.0]));
        assert!(
            s.to_array()[..2]
                .iter()
                .chain(&c.to_array()[..2])
                .all(|v| v.is_nan())
        );
        assert_eq!(s.to_array()[2..], [0.0, -0.0]);
    }
}
