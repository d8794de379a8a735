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

    /// `self − k·a` in every component: `b − (a·b)·a`, the part of `b` across `a`.
    #[inline]
    pub(crate) fn less(self, k: f64x4, a: Quat4) -> Quat4 {
        Quat4 {
            w: self.w - k * a.w,
            x: self.x - k * a.x,
            y: self.y - k * a.y,
            z: self.z - k * a.z,
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

/// `atan2(y, x)` in lanes for `y ≥ 0` (a sine's magnitude: every angle the curves take, in
/// `[0, π]`), as libm's on the edges (`y = 0` with `x = ±0` or `x < 0`, `x = ±0`, infinite
/// `x` or `y` but not both); NaN in, NaN out. Cephes' `atan` rational function as the vector
/// class library writes it (the coefficients of `wide`'s `atan2`), shortened for the upper
/// half-plane: the octant reduction leaves `t = min/max ≤ 1`, so its `t > 1 + √2` branch never
/// runs, and `z` comes from one division of the two numbers rather than two (`t`, then
/// `(t − 1)/(t + 1)`). The result is `n·π/4 ± atan z` with `n` a whole number, added as
/// `n·hi + (n·lo ± atan z)` (`π/4 = hi + lo`), so the one large rounding is the last.
/// Within 2 ulp of libm's (measured below; `wide`'s within 2). Not for `y < 0` or `y = −0`
/// (the sign of a zero `y` is not carried to the result), nor for both magnitudes above about
/// 9e307, where `x + y` overflows and a ratio near 1 reads as exactly 1: the curves pass
/// lengths and cosines of unit quaternions (at most about 1), and `y` from a square root.
#[inline]
pub(crate) fn atan2_upper4(y: f64x4, x: f64x4) -> f64x4 {
    // π/4 = PI4_HI + PI4_LO; `n·PI4_HI` is exact for n = 0..4.
    const PI4_HI: f64 = std::f64::consts::FRAC_PI_4;
    const PI4_LO: f64 = 3.061_616_997_868_383e-17;
    // The coefficients of `wide`'s `atan2` (Cephes' P4/Q5 in z²), as `f64` rounds them.
    let (p0, p1, p2, p3, p4) = (
        f64x4::splat(-64.850_219_049_420_25),
        f64x4::splat(-122.886_668_449_013_61),
        f64x4::splat(-75.008_557_923_147_05),
        f64x4::splat(-16.157_537_187_333_652),
        f64x4::splat(-0.875_060_860_003_190_4),
    );
    let (q0, q1, q2, q3, q4) = (
        f64x4::splat(194.550_657_148_261_4),
        f64x4::splat(485.390_399_635_913_7),
        f64x4::splat(432.881_060_491_290_27),
        f64x4::splat(165.027_009_831_698_85),
        f64x4::splat(24.858_464_901_423_062),
    );
    let x1 = x.abs();
    let swap = y.simd_gt(x1);
    let (big, small) = (swap.select(y, x1), swap.select(x1, y));
    // `t = small/big` at or above 0.66: atan t = π/4 + atan((t − 1)/(t + 1)) (t = 0/0 is not).
    let medium = small.simd_ge(big * f64x4::splat(0.66)) & big.simd_gt(f64x4::ZERO);
    let z = medium.select(small - big, small) / medium.select(small + big, big);
    let zz = z * z;
    let zz2 = zz * zz;
    let px = (p3 * zz + p2) * zz2 + (p1 * zz + p0) + p4 * (zz2 * zz2);
    let qx = zz2 * (zz * q3 + q2) + (zz2 * zz2 * (q4 + zz) + (zz * q1 + q0));
    let core = (px / qx) * (z * zz) + z;
    // y = x = 0 (z = 0/0): an angle of 0, turned to π when x is −0.
    let core = (x | y).simd_eq(f64x4::ZERO).select(f64x4::ZERO, core);
    // The octant back in place: t (n = 0, +), π/2 − t (2, −), π − t (4, −), π/2 + t (2, +),
    // with π/4 added to t in the medium range.
    let neg = x.is_sign_negative();
    let flip = swap ^ neg;
    let base = swap.select(f64x4::splat(2.0), neg & f64x4::splat(4.0));
    let m = medium & f64x4::ONE;
    let n = base + flip.select(-m, m);
    n * f64x4::splat(PI4_HI) + (n * f64x4::splat(PI4_LO) + flip.select(-core, core))
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
    /// The distance of `got` from `want` in units of `want`'s last place.
    fn ulps(got: f64, want: f64) -> f64 {
        let ulp = f64::from_bits(want.abs().to_bits() + 1) - want.abs();
        (got - want).abs() / ulp
    }

    /// Within 2 ulp of libm's over the upper half-plane — angles near 0, π/2 and π, tiny and
    /// large magnitudes — as `wide`'s `atan2` (also 2), and libm's bits on the edges.
    #[test]
    fn atan2_upper4_is_libms_within_two_ulp() {
        let (mut worst, mut worst_wide): (f64, f64) = (0.0, 0.0);
        let mut check = |y: f64, x: f64| {
            let got = atan2_upper4(f64x4::splat(y), f64x4::splat(x)).to_array()[0];
            let want = y.atan2(x);
            let off = ulps(got, want);
            assert!(
                off <= 2.0,
                "atan2({y:e}, {x:e}): {got} vs {want} ({off} ulp)"
            );
            worst = worst.max(off);
            let wide = f64x4::splat(y).atan2(f64x4::splat(x)).to_array()[0];
            worst_wide = worst_wide.max(ulps(wide, want));
        };
        for i in 0..200_000 {
            // Angles over [0, π], bunched at the ends and at the reduction's seams.
            let a = std::f64::consts::PI * (i as f64 / 200_000.0).powi(1 + i % 3);
            let r = 10f64.powi(i % 13 - 6);
            check(r * a.sin(), r * a.cos());
            check(r * a.sin(), -r * a.cos());
            let (s, c) = ((i as f64 * 0.618).fract(), (i as f64 * 0.377).fract() - 0.5);
            check(s, c);
            check(s * 1e-12, -1.0 + c * 1e-14);
        }
        for (y, x) in [
            (0.0, 1.0),
            (0.0, -1.0),
            (0.0, 0.0),
            (0.0, -0.0),
            (1e-300, -1.0),
            (1e-300, 1.0),
            (1.0, 0.0),
            (1.0, -0.0),
            (0.5, -0.5),
            (5e-324, -1.0),
            (1.0, -1e-300),
            (1.0, f64::INFINITY),
            (1.0, -f64::INFINITY),
            (f64::INFINITY, 1.0),
        ] {
            let got = atan2_upper4(f64x4::splat(y), f64x4::splat(x)).to_array()[0];
            assert_eq!(got.to_bits(), y.atan2(x).to_bits(), "atan2({y}, {x})");
        }
        let nan = atan2_upper4(
            f64x4::new([f64::NAN, 1.0, f64::NAN, 0.0]),
            f64x4::new([1.0, f64::NAN, f64::NAN, f64::NAN]),
        );
        assert!(nan.to_array().iter().all(|v| v.is_nan()));
        println!("worst {worst} ulp (wide's atan2: {worst_wide})");
    }
}
