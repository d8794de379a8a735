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
