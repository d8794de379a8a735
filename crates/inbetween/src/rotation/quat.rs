//! Quaternion helpers that glam does not have: the half-angle `log`/`exp` of the papers, and the
//! geodesic blend on S³ without hemisphere flipping.
//!
//! Convention (docs/spec.md §2, §4): `q = w + xi + yj + zk`, Hamilton product, `v' = q v q*`. A unit
//! quaternion `q = (cos θ, sin θ·a)` rotates by `2θ` about `a`; `log q = θ·a` is returned as a
//! [`DVec3`] (the pure quaternion's vector part) and `exp` is its inverse. So a rotation vector
//! (axis × angle) is `2·log(q)`, and a world-frame angular velocity ω corresponds to the tangent
//! `½ ω q` at `q`.

use glam::{DQuat, DVec3};

/// Half-angle logarithm of a unit quaternion: `log(cos θ + sin θ·a) = θ·a`, `θ ∈ [0, π]`.
///
/// Exact for tiny angles (uses `atan2(|v|, w)/|v|`, no small-angle series needed). For `q = −1`
/// (θ = π, the axis is undefined) it returns `π·x̂`: the world x axis, a documented choice.
///
/// ```
/// use inbetween::rotation::quat::{exp, log};
/// use glam::{DQuat, DVec3};
///
/// // A 90° turn about z: half-angle 45°, so log is (0, 0, π/4) and 2·log is the rotation vector.
/// let q = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
/// assert!((log(q) - DVec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_4)).length() < 1e-15);
/// assert!((exp(log(q)) - q).length() < 1e-15);
/// assert_eq!(log(-DQuat::IDENTITY), DVec3::new(std::f64::consts::PI, 0.0, 0.0));
/// ```
pub fn log(q: DQuat) -> DVec3 {
    let v = DVec3::new(q.x, q.y, q.z);
    let s = v.length();
    if s == 0.0 {
        if q.w < 0.0 {
            return DVec3::new(std::f64::consts::PI, 0.0, 0.0);
        }
        return DVec3::ZERO;
    }
    v * (s.atan2(q.w) / s)
}

/// Below this norm of its vector part a unit quaternion counts as `±1`: its log has no axis.
pub(crate) const NO_AXIS: f64 = 1e-12;

/// The branch of the half-angle logarithm of the unit quaternion `q` nearest `target`: among
/// `n·(θ + 2πk)`, `k ∈ ℤ`, with `θ·n = log(q)`, the one nearest `target` (every one has
/// `exp(·) = q`). Where `q` has no axis (`±1`, vector part below [`NO_AXIS`]) the axis is
/// `target`'s direction. `--path euler` draws the arcs inside a segment with it (docs/spec.md
/// §4.3), so that an arc standing in for part of a spin keeps the spin's turns.
///
/// (The examples of the documentation are a unit test, `log_near_picks_the_branch_nearest_the_target`.)
pub(crate) fn log_near(q: DQuat, target: DVec3) -> DVec3 {
    let tau = 2.0 * std::f64::consts::PI;
    let v = DVec3::new(q.x, q.y, q.z);
    let s = v.length();
    let (n, theta) = if s < NO_AXIS {
        let t = target.length();
        if t == 0.0 || !t.is_finite() {
            return log(q);
        }
        (
            target / t,
            if q.w < 0.0 { std::f64::consts::PI } else { 0.0 },
        )
    } else {
        (v / s, s.atan2(q.w))
    };
    let k = ((n.dot(target) - theta) / tau).round();
    n * (theta + tau * k)
}

/// Exponential of a pure quaternion `θ·a` (given as its vector part): `cos θ + sin θ·a`.
pub fn exp(v: DVec3) -> DQuat {
    let theta = v.length();
    if theta == 0.0 {
        return DQuat::IDENTITY;
    }
    let (s, c) = theta.sin_cos();
    let k = s / theta;
    DQuat::from_xyzw(v.x * k, v.y * k, v.z * k, c)
}

/// Pure quaternion (vector part) times a quaternion: `(0, v) · q`.
pub(crate) fn pure_mul(v: DVec3, q: DQuat) -> DQuat {
    DQuat::from_xyzw(v.x, v.y, v.z, 0.0) * q
}

/// The point `f` of the way along the great arc of S³ from unit `a` to unit `b`:
/// `exp(f · log(b a⁻¹)) a`, computed in R⁴ as `cos(fΩ) a + sin(fΩ) ê` with `Ω = ∠(a, b)` and `ê`
/// the unit direction of `b − (a·b) a`. No hemisphere flip: when `a·b < 0` the arc is longer
/// than 90° on S³ (the long way round in SO(3)), as docs/spec.md §4.3 requires.
///
/// When `a` and `b` are antipodal the arc is undefined; this returns the arc through the
/// direction [`log`] chooses for `−1`.
///
/// ```
/// use inbetween::rotation::quat::geodesic;
/// use glam::DQuat;
///
/// let (a, b) = (DQuat::IDENTITY, DQuat::from_rotation_x(3.0));
/// assert!((geodesic(a, b, 0.5) - DQuat::from_rotation_x(1.5)).length() < 1e-15);
/// // No hemisphere flip: towards −b is the long way round (2π − 3 rad), half of it here.
/// let long = geodesic(a, -b, 0.5);
/// assert!((long - DQuat::from_rotation_x(1.5 - std::f64::consts::PI)).length() < 1e-15);
/// ```
#[inline]
pub fn geodesic(a: DQuat, b: DQuat, f: f64) -> DQuat {
    let d = a.dot(b);
    let perp = b - a * d;
    let s = perp.length();
    if s < 1e-300 {
        if d >= 0.0 {
            return a;
        }
        // Antipodal: rotate about the world x axis (same choice as `log(−1)`).
        let e = DQuat::from_xyzw(1.0, 0.0, 0.0, 0.0) * a;
        let (sn, cs) = (f * std::f64::consts::PI).sin_cos();
        return a * cs + e * sn;
    }
    let omega = s.atan2(d);
    let (sn, cs) = (f * omega).sin_cos();
    a * cs + perp * (sn / s)
}

/// Angle in radians between two rotations (in SO(3), so `q` and `−q` are the same rotation).
pub fn rotation_angle_between(a: DQuat, b: DQuat) -> f64 {
    let r = b * a.conjugate();
    let r = if r.w < 0.0 { -r } else { r };
    2.0 * log(r).length()
}

/// `q` with `w ≥ 0` (the same rotation).
pub fn canonical(q: DQuat) -> DQuat {
    if q.w < 0.0 { -q } else { q }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const TOL: f64 = 1e-14;

    #[test]
    fn log_exp_round_trip() {
        for v in [
            DVec3::new(0.3, -0.2, 0.9),
            DVec3::new(1e-12, 0.0, 0.0),
            DVec3::new(0.0, 3.0, 0.0),
            DVec3::ZERO,
        ] {
            let back = log(exp(v));
            assert!((back - v).length() < TOL, "{v} -> {back}");
        }
    }

    #[test]
    fn log_of_minus_one_is_pi_about_x() {
        assert_eq!(log(-DQuat::IDENTITY), DVec3::new(PI, 0.0, 0.0));
    }

    #[test]
    fn log_matches_axis_angle_closed_form() {
        let q = DQuat::from_axis_angle(DVec3::new(0.0, 0.6, 0.8), 1.2);
        let l = log(q);
        assert!((l - DVec3::new(0.0, 0.6, 0.8) * 0.6).length() < TOL);
    }

    #[test]
    fn geodesic_ends_and_midpoint() {
        let a = DQuat::from_rotation_z(0.2);
        let b = DQuat::from_rotation_z(1.4);
        assert!((geodesic(a, b, 0.0) - a).length() < TOL);
        assert!((geodesic(a, b, 1.0) - b).length() < TOL);
        assert!((geodesic(a, b, 0.5) - DQuat::from_rotation_z(0.8)).length() < TOL);
    }

    #[test]
    fn geodesic_does_not_flip_hemisphere() {
        let a = DQuat::IDENTITY;
        let b = -DQuat::from_rotation_z(0.5); // same rotation class as a small step, but far on S³
        let mid = geodesic(a, b, 0.5);
        // The long way: the midpoint is near 90° from both on S³.
        assert!(mid.dot(a).abs() < 0.3, "{mid}");
        let direct = exp(log(b * a.conjugate()) * 0.5) * a;
        assert!((mid - direct).length() < TOL);
    }

    #[test]
    fn log_near_picks_the_branch_nearest_the_target() {
        use std::f64::consts::PI;

        // A 300° turn about z: log is a half angle of 150° about z, and its branches 150° + 360°k.
        // Nearest a target of −200° it is −210° (a turn of −420°, which is also +300°).
        let q = DQuat::from_rotation_z(300f64.to_radians());
        let v = log_near(q, DVec3::new(0.0, 0.0, -200f64.to_radians()));
        assert!((v.z + 210f64.to_radians()).abs() < 1e-14);
        // −1 (a full turn) nearest a target along y: π about y.
        assert_eq!(
            log_near(-DQuat::IDENTITY, DVec3::new(0.0, 3.0, 0.0)),
            DVec3::new(0.0, PI, 0.0)
        );
        assert!((exp(log_near(q, DVec3::new(0.0, 0.0, 9.0))) - q).length() < 1e-14);
    }
}
