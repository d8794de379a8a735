//! `nlerp`: the normalised linear blend of consecutive keys' four components,
//!
//! ```text
//! Q(u) = p(u) / ‖p(u)‖,   p(u) = (1 − u)·q_i + u·q_{i+1},   u = (t − t_i)/(t_{i+1} − t_i)
//! ```
//!
//! with the keys' signs after the path rule (`--path shortest`: each key in the hemisphere of
//! the one before; `as-given`: as given, so a key whose sign flips is reached the long way
//! round, as slerp reaches it). It is how players that store quaternion keys play them between
//! keys: Blender evaluates a quaternion's four F-curves one by one (`LINEAR`: the lerp of each
//! component) and normalises the result before turning it into a matrix
//! (`BKE_pchan_rot_to_mat3`, `source/blender/blenkernel/intern/armature.c`: `normalize_qt_qt`,
//! then `quat_to_mat3`), and ozz-animation's runtime samples rotations with `NLerpEst`
//! (`SamplingJob`, `src/animation/runtime/sampling_job.cc`; its offline builder negates opposed
//! keys, the shortest path). So keys reduced under nlerp carry their guarantee to those players.
//!
//! - Interpolation: every key. Tangency: none imposed.
//! - Continuity: C⁰ at keys (the angular velocity jumps there), C^∞ inside.
//! - Parametrisation: the same great arc as slerp (`p(u)` stays in the plane of the two keys),
//!   at a speed that is not constant: `ω(u) = 2·vec(q_{i+1} q_i⁻¹)/(Δ·‖p(u)‖²)`, fastest at the
//!   middle of the segment, where `‖p‖² = (1 + cos φ)/2` for keys `φ` apart on S³ (half the
//!   rotation angle). Against slerp it lags, then leads: the largest difference in rotation
//!   angle over a segment turning `θ` is about `θ³/(144·√3)` rad for small `θ` (0.27° at 60°,
//!   1.96° at 115°).
//! - Cost per frame: a lerp and a square root (frames are evaluated directly; no forward
//!   differences are needed).
//! - Limitations: between antipodal keys (`--path as-given` with `q_{i+1} = −q_i`) `p` passes
//!   through zero at `u = ½`; the rotation stays the key's (`±q_i` is one rotation), the
//!   quaternion changes sign there, and the tool warns as for any blend at an antipode.
//!   `--path euler` is refused: the blend of two quaternions cannot keep a turn of a full
//!   rotation or more.

use super::{Blend, Segment};
use crate::tangent::Knots;
use glam::{DQuat, DVec3};

/// One nlerp segment: its two keys.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Nlerp {
    a: DQuat,
    b: DQuat,
}

impl Nlerp {
    /// The segment from `a` (`u = 0`) to `b` (`u = 1`), the quaternions as they are blended.
    pub(crate) fn between(a: DQuat, b: DQuat) -> Nlerp {
        Nlerp { a, b }
    }

    /// `p(u) = (1 − u)·a + u·b`, before normalising.
    #[inline]
    fn lerp(&self, u: f64) -> DQuat {
        self.a * (1.0 - u) + self.b * u
    }

    /// `vec(b·a⁻¹)`: the axis of the segment's rotation times the sine of half its angle.
    #[inline]
    fn chord_sine(&self) -> DVec3 {
        let r = self.b * self.a.conjugate();
        DVec3::new(r.x, r.y, r.z)
    }

    /// The world-frame angular velocity per unit `u` (divide by the segment's duration for
    /// rad/s), exactly: with `ω = 2·vec(Q'·Q⁻¹)` and `Q = p/‖p‖`,
    /// `Q'·Q⁻¹ = vec(p'·p̄)/‖p‖² + scalar`, and `vec((b − a)·p̄) = vec(b·ā)` for unit keys, so
    /// `ω(u) = 2·vec(b·a⁻¹)/‖p(u)‖²`: a fixed axis, the speed varying with `‖p‖⁻²`.
    pub(crate) fn omega(&self, u: f64) -> DVec3 {
        self.chord_sine() * (2.0 / self.lerp(u).length_squared())
    }

    /// The world-frame angular acceleration per unit `u`² (divide by the duration squared for
    /// rad/s²), exactly: the derivative of [`Nlerp::omega`],
    /// `α(u) = −4·(p·(b − a))·vec(b·a⁻¹)/‖p(u)‖⁴`, along the same axis.
    pub(crate) fn alpha(&self, u: f64) -> DVec3 {
        let p = self.lerp(u);
        let n2 = p.length_squared();
        self.chord_sine() * (-4.0 * p.dot(self.b - self.a) / (n2 * n2))
    }
}

/// The frames of an nlerp segment, each evaluated directly ([`Segment::eval`] at
/// `u₀ + j·δ`).
#[derive(Debug, Clone)]
pub(crate) struct NlerpFrames {
    seg: Nlerp,
    u0: f64,
    du: f64,
    j: f64,
}

impl Iterator for NlerpFrames {
    type Item = DQuat;

    fn next(&mut self) -> Option<DQuat> {
        let q = self.seg.eval(self.u0 + self.j * self.du);
        self.j += 1.0;
        Some(q)
    }
}

impl Segment for Nlerp {
    type Frames = NlerpFrames;
    type Pending = std::convert::Infallible;

    fn finish4(lanes: &[Self::Pending; 4]) -> [DQuat; 4] {
        match lanes[0] {}
    }

    fn new(keys: &Knots, s: usize, _blend: Blend) -> Self {
        Nlerp::between(keys.quats[s], keys.quats[s + 1])
    }

    /// `p(u)/‖p(u)‖`; where `p` is zero (antipodal keys at `u = ½`) the first key, the same
    /// rotation as every point of such a segment.
    fn eval(&self, u: f64) -> DQuat {
        let p = self.lerp(u);
        let n = p.length();
        if n > 0.0 { p / n } else { self.a }
    }

    fn frames(&self, u0: f64, du: f64) -> NlerpFrames {
        NlerpFrames {
            seg: *self,
            u0,
            du,
            j: 0.0,
        }
    }

    /// The S³ angle between the two keys: the blend `p` is zero only when it is π.
    fn blend_bound(&self) -> f64 {
        crate::rotation::arc::s3_angle(self.a, self.b)
    }

    /// `2·‖p(u)‖`: `‖a + b‖` at the middle, where it is smallest, and 2 at the keys.
    fn blend_gap(&self, u: f64) -> f64 {
        2.0 * self.lerp(u).length()
    }

    fn velocity(&self, u: f64) -> Option<DVec3> {
        Some(self.omega(u))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::*;
    use crate::rotation::quat::rotation_angle_between as angle;

    /// One tolerance for the closed forms (4D distance, or relative for derivatives).
    const TOL: f64 = 1e-14;

    fn q(axis: DVec3, angle: f64) -> DQuat {
        DQuat::from_axis_angle(axis.normalize(), angle)
    }

    #[test]
    fn keys_and_frames() {
        check_segment::<Nlerp>(&sample_keys(), Blend::Cubic);
    }

    #[test]
    fn keys_at_u_0_and_1() {
        let (a, b) = (q(DVec3::new(1.0, 2.0, 3.0), 0.7), q(DVec3::Y, 2.0));
        let s = Nlerp::between(a, b);
        assert!((s.eval(0.0) - a).length() < TOL);
        assert!((s.eval(1.0) - b).length() < TOL);
    }

    /// At the middle the blend is `(a + b)/‖a + b‖`: the slerp midpoint, half the rotation.
    #[test]
    fn midpoint_is_the_half_rotation() {
        let axis = DVec3::new(0.3, -0.5, 0.8).normalize();
        let a = q(DVec3::X, 0.4);
        for theta in [1e-6, 0.3, 2.0, 3.1] {
            let b = q(axis, theta) * a;
            let s = Nlerp::between(a, b);
            let want = (a + b).normalize();
            assert!((s.eval(0.5) - want).length() < TOL, "{theta}");
            assert!(
                angle(s.eval(0.5), q(axis, theta / 2.0) * a) < 1e-12,
                "{theta}"
            );
        }
    }

    /// Off the middle, nlerp is the slerp of the angle `atan2(u·sin φ, (1 − u) + u·cos φ)` on
    /// S³ (`φ` the keys' S³ angle): the same arc at another speed.
    #[test]
    fn is_slerp_at_the_closed_form_angle() {
        let axis = DVec3::new(1.0, 1.0, -0.5).normalize();
        let a = q(DVec3::Z, 1.0);
        let theta = 115f64.to_radians();
        let b = q(axis, theta) * a;
        let s = Nlerp::between(a, b);
        let phi = theta / 2.0;
        let mut worst: f64 = 0.0;
        for j in 0..=100 {
            let u = j as f64 / 100.0;
            let psi = (u * phi.sin()).atan2(1.0 - u + u * phi.cos());
            let want = q(axis, 2.0 * psi) * a;
            assert!((s.eval(u) - want).length() < TOL, "{u}");
            worst = worst.max(angle(s.eval(u), q(axis, u * theta) * a));
        }
        // The largest difference from slerp on a 115° segment (docs/schemes.md): 1.957°.
        assert!(
            (worst.to_degrees() - 1.957).abs() < 0.001,
            "{}",
            worst.to_degrees()
        );
    }

    /// `ω = 2·Q'·Q⁻¹` and `α = ω'` against central differences of the rotation itself.
    #[test]
    fn derivatives_match_finite_differences() {
        let k = sample_keys();
        for s in 0..k.segments() {
            let seg = Nlerp::new(&k, s, Blend::Cubic);
            for u in [0.0, 0.1, 0.37, 0.5, 0.81, 1.0] {
                let dq = deriv(&seg, u);
                let p = dq * seg.eval(u).conjugate();
                let fd = DVec3::new(p.x, p.y, p.z) * 2.0;
                let w = seg.omega(u);
                assert!((w - fd).length() < 1e-8 * w.length().max(1.0), "{s} {u}");
                let h = 1e-5;
                let fd_alpha = (seg.omega(u + h) - seg.omega(u - h)) / (2.0 * h);
                let al = seg.alpha(u);
                assert!(
                    (al - fd_alpha).length() < 1e-7 * al.length().max(1.0),
                    "{s} {u}: {al} vs {fd_alpha}"
                );
            }
        }
    }

    /// The curve's world-frame velocity, sampled through `Curve`, is the closed form over the
    /// segment's duration, and agrees with differences of `Curve::rotation` in time.
    #[test]
    fn curve_velocity_is_the_closed_form() {
        let track = sample_track();
        let opts = crate::CurveOptions {
            scheme: crate::Scheme::Nlerp,
            ..Default::default()
        };
        let c = crate::Curve::new(&track, &opts).unwrap();
        let k = sample_keys();
        for t in [0.1, 0.3, 0.6, 1.0, 1.7] {
            let s = k.times.partition_point(|&x| x <= t) - 1;
            let seg = Nlerp::new(&k, s, Blend::Cubic);
            let u = (t - k.times[s]) / k.delta(s);
            let want = seg.omega(u) / k.delta(s);
            assert!((c.angular_velocity(t) - want).length() < TOL * want.length().max(1.0));
            let h = 1e-6;
            let dq = (c.rotation(t + h) - c.rotation(t - h)) / (2.0 * h);
            let p = dq * c.rotation(t).conjugate();
            let fd = DVec3::new(p.x, p.y, p.z) * 2.0;
            assert!((fd - want).length() < 1e-7 * want.length(), "{t}");
            let want_alpha = seg.alpha(u) / (k.delta(s) * k.delta(s));
            assert!(
                (c.angular_acceleration(t) - want_alpha).length()
                    < TOL * want_alpha.length().max(1.0)
            );
        }
    }

    /// Under `--path shortest` a key given with the other sign is blended in the previous
    /// key's hemisphere (the short way); `as-given` blends it as given (the long way round).
    #[test]
    fn sign_continuity_follows_the_path() {
        let a = DQuat::IDENTITY;
        let b = q(DVec3::Z, 0.5);
        let track = crate::Track::new(vec![0.0, 1.0], vec![a, -b]).unwrap();
        let curve = |path| {
            let opts = crate::CurveOptions {
                scheme: crate::Scheme::Nlerp,
                path,
                ..Default::default()
            };
            crate::Curve::new(&track, &opts).unwrap()
        };
        let short = curve(crate::PathMode::Shortest);
        assert!(angle(short.rotation(0.5), q(DVec3::Z, 0.25)) < 1e-12);
        let long = curve(crate::PathMode::AsGiven);
        // The other way round: half of 360° − 0.5 rad, about −z.
        let want = q(DVec3::Z, -(std::f64::consts::TAU - 0.5) / 2.0);
        assert!(angle(long.rotation(0.5), want) < 1e-12);
    }

    /// Antipodal keys: the rotation is the key's all along (no NaN at the middle), and the
    /// blend gap says so.
    #[test]
    fn antipodal_keys_hold_the_rotation() {
        let a = q(DVec3::new(1.0, 0.0, 1.0), 0.9);
        let s = Nlerp::between(a, -a);
        for u in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let r = s.eval(u);
            assert!(r.is_finite() && angle(r, a) < 1e-12, "{u}");
        }
        assert_eq!(crate::curve::antipode_gap(&s).map(|g| g.0), Some(0.0));
    }
}
