//! An animation channel as read, and its sampler evaluated as glTF 2.0 Appendix C defines it.
//!
//! | interpolation | between keys `k` and `k + 1`, `s = (t − t_k) / (t_{k+1} − t_k)` |
//! |---|---|
//! | `STEP` | `v_k`: the last key at or before `t` |
//! | `LINEAR` rotation | `slerp(v_k, v_{k+1}, s)` on the shorter arc (Appendix C, *spherical linear interpolation*) |
//! | `LINEAR` translation | `(1 − s)·v_k + s·v_{k+1}` |
//! | `CUBICSPLINE` | Hermite on the vectors, tangents scaled by `t_{k+1} − t_k`; a rotation is then normalised |
//!
//! Before the first key a channel holds its first value, after the last its last (clamped, as
//! glTF players do). A `CUBICSPLINE` output holds `(a_k, v_k, b_k)` per key: in-tangent, value,
//! out-tangent (§3.11); `a_0` and `b_{n−1}` are never used.

use glam::{DQuat, DVec3, DVec4};

/// A sampler's interpolation (glTF 2.0 §3.11, `animation.sampler.interpolation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interpolation {
    /// `LINEAR`: slerp for rotations, linear for translations.
    Linear,
    /// `STEP`: each key holds until the next.
    Step,
    /// `CUBICSPLINE`: cubic Hermite with explicit in- and out-tangents per key.
    CubicSpline,
}

impl Interpolation {
    /// The name as written in glTF (`LINEAR`, `STEP`, `CUBICSPLINE`).
    pub fn as_str(self) -> &'static str {
        match self {
            Interpolation::Linear => "LINEAR",
            Interpolation::Step => "STEP",
            Interpolation::CubicSpline => "CUBICSPLINE",
        }
    }
}

impl std::fmt::Display for Interpolation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One channel of an animation: the node it drives, the sampler's interpolation, its key times
/// and values. Built only by the reader, which has checked that the times are finite and
/// strictly increasing, the counts agree, and every value is finite (a rotation value also of
/// non-zero length).
///
/// `T` is [`DQuat`] for a rotation channel (components `x, y, z, w` as glTF stores them) and
/// [`DVec3`] for a translation channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel<T> {
    pub(super) index: usize,
    pub(super) node: usize,
    pub(super) node_name: String,
    pub(super) sampler: usize,
    pub(super) interpolation: Interpolation,
    pub(super) times_f32: Vec<f32>,
    pub(super) times: Vec<f64>,
    pub(super) values: Vec<T>,
    /// `(in, out)` tangents per key, for `CUBICSPLINE` only.
    pub(super) tangents: Option<Vec<(T, T)>>,
}

/// Consecutive rotation keys in opposite hemispheres ([`RotationChannel::sign_flips`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SignFlips {
    /// The first pair: keys `key` and `key + 1`.
    pub key: usize,
    /// Their normalised values' dot product (negative).
    pub dot: f64,
    /// How many consecutive pairs are in opposite hemispheres.
    pub pairs: usize,
}

/// The warning for a rotation channel whose consecutive keys lie in opposite hemispheres, saying
/// how the file plays: `LINEAR`'s slerp takes the shorter way (as glTF 2.0 Appendix C says, and as
/// read here), but not every player checks; `CUBICSPLINE` blends the stored 4-vectors with no
/// sign correction, so the curve swings the long way round (as the file plays, and as read here)
/// — mostly an exporter's sign flip, not what the animator saw.
pub(super) fn sign_flip_warning(ch: &RotationChannel) -> Option<String> {
    let f = ch.sign_flips()?;
    let more = match f.pairs {
        1 => String::new(),
        n => format!(" (and {} more pairs)", n - 1),
    };
    // The times as stored (float32, shortest).
    let (k, t) = (f.key, ch.times_f32());
    let pair = format!(
        "keys {k} and {} ({} s, {} s) lie in opposite hemispheres (dot {:.2}){more}",
        k + 1,
        t[k],
        t[k + 1],
        f.dot
    );
    Some(match ch.interpolation {
        Interpolation::CubicSpline => format!(
            "CUBICSPLINE {pair}: the spline blends the stored values with no sign correction \
             (glTF 2.0 Appendix C), so it turns the long way round between them, as the file \
             plays and as read here; an exporter's sign flip is the usual cause: re-export with \
             sign-continuous keys (or sampled)"
        ),
        _ => format!(
            "LINEAR {pair}: glTF's slerp takes the shorter way, as read here, but a player that \
             blends the stored values as they are turns the long way; store sign-continuous keys"
        ),
    })
}

/// A channel targeting a node's `rotation`.
pub type RotationChannel = Channel<DQuat>;
/// A channel targeting a node's `translation`.
pub type TranslationChannel = Channel<DVec3>;

impl<T: Copy> Channel<T> {
    /// The channel's index in its animation's `channels`.
    pub fn index(&self) -> usize {
        self.index
    }

    /// The index of the target node.
    pub fn node(&self) -> usize {
        self.node
    }

    /// The target node's name, or `node<index>` when it has none.
    pub fn node_name(&self) -> &str {
        &self.node_name
    }

    /// The index of the channel's sampler in its animation's `samplers`.
    pub fn sampler(&self) -> usize {
        self.sampler
    }

    /// The sampler's interpolation.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// Key times as stored (float32 seconds), strictly increasing.
    pub fn times_f32(&self) -> &[f32] {
        &self.times_f32
    }

    /// Key times in seconds: [`Channel::times_f32`] widened exactly to f64.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The key values, one per time (for `CUBICSPLINE`, the spline vertices `v_k`).
    pub fn values(&self) -> &[T] {
        &self.values
    }

    /// For `CUBICSPLINE`, the `(in-tangent a_k, out-tangent b_k)` of each key, in units of value
    /// per second; `None` otherwise.
    pub fn tangents(&self) -> Option<&[(T, T)]> {
        self.tangents.as_deref()
    }

    /// The first and last key times.
    pub fn span(&self) -> (f64, f64) {
        (self.times[0], self.times[self.times.len() - 1])
    }

    /// The key segment containing `t` and the normalised position in it, or the clamped key.
    fn locate(&self, t: f64) -> Located {
        let n = self.times.len();
        if n == 1 || t.is_nan() || t <= self.times[0] {
            return Located::Key(0);
        }
        if t >= self.times[n - 1] {
            return Located::Key(n - 1);
        }
        // The last key at or before t (times strictly increasing, t inside).
        let k = self.times.partition_point(|&x| x <= t) - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        Located::Between(k, (t - t0) / (t1 - t0), t1 - t0)
    }
}

enum Located {
    /// Exactly key `k`'s value (clamped ends, or a single key).
    Key(usize),
    /// Segment `k`, position `s ∈ (0, 1)`, duration `t_{k+1} − t_k`.
    Between(usize, f64, f64),
}

/// The Hermite basis of glTF 2.0 Appendix C (cubic spline interpolation):
/// `(2s³ − 3s² + 1, s³ − 2s² + s, −2s³ + 3s², s³ − s²)` for `p0, m0, p1, m1`.
fn hermite_basis(s: f64) -> [f64; 4] {
    let s2 = s * s;
    let s3 = s2 * s;
    [
        2.0 * s3 - 3.0 * s2 + 1.0,
        s3 - 2.0 * s2 + s,
        -2.0 * s3 + 3.0 * s2,
        s3 - s2,
    ]
}

impl Channel<DQuat> {
    /// Consecutive keys whose values lie in opposite hemispheres (`v_k · v_{k+1} < 0`, on the
    /// normalised values; for `CUBICSPLINE` the vertices): how many pairs, and the first pair's
    /// `k` and dot product. `None` when there is none, and for `STEP` (a step does not blend).
    pub(crate) fn sign_flips(&self) -> Option<SignFlips> {
        if self.interpolation == Interpolation::Step {
            return None;
        }
        let mut flips = self
            .values
            .windows(2)
            .enumerate()
            .map(|(k, w)| (k, w[0].normalize().dot(w[1].normalize())))
            .filter(|&(_, d)| d < 0.0);
        let (key, dot) = flips.next()?;
        Some(SignFlips {
            key,
            dot,
            pairs: 1 + flips.count(),
        })
    }

    /// The rotation at time `t` (seconds) by the sampler's interpolation, a unit quaternion:
    ///
    /// - `STEP`: the last key at or before `t`, normalised.
    /// - `LINEAR`: Appendix C's slerp, `a = arccos|v_k·v_{k+1}|`,
    ///   `sin(a(1 − s))/sin(a)·v_k + sign(v_k·v_{k+1})·sin(a·s)/sin(a)·v_{k+1}` (the shorter
    ///   arc; keys normalised first, a normalised lerp when `a < 1e-9`).
    /// - `CUBICSPLINE`: Appendix C's Hermite on the 4-vectors with `p0 = v_k`,
    ///   `m0 = (t_{k+1} − t_k)·b_k`, `p1 = v_{k+1}`, `m1 = (t_{k+1} − t_k)·a_{k+1}`, then
    ///   normalised. No hemisphere correction: the tangents define the curve as stored.
    ///
    /// Clamped: before the first key the first value, after the last the last.
    ///
    /// ```
    /// use glam::DQuat;
    /// # use inbetween_io::gltf::Asset;
    /// // A LINEAR channel from identity to 90° about z over one second, from a glTF asset:
    /// # let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/gltf/minimal_linear.gltf");
    /// # let asset = Asset::read_path(path.as_ref()).unwrap();
    /// let anim = &asset.animations().unwrap()[0];
    /// let q = anim.rotations()[0].sample(0.5);
    /// let expected = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_4);
    /// assert!(q.angle_between(expected) < 1e-6);
    /// ```
    pub fn sample(&self, t: f64) -> DQuat {
        let q = match self.locate(t) {
            Located::Key(k) => DVec4::from(self.values[k]),
            Located::Between(k, s, dt) => match self.interpolation {
                Interpolation::Step => DVec4::from(self.values[k]),
                Interpolation::Linear => {
                    return slerp_shortest(self.values[k], self.values[k + 1], s);
                }
                Interpolation::CubicSpline => {
                    let tangents = self.tangents.as_deref().unwrap_or_default();
                    let b = hermite_basis(s);
                    let p0 = DVec4::from(self.values[k]);
                    let p1 = DVec4::from(self.values[k + 1]);
                    let m0 = dt * DVec4::from(tangents[k].1);
                    let m1 = dt * DVec4::from(tangents[k + 1].0);
                    b[0] * p0 + b[1] * m0 + b[2] * p1 + b[3] * m1
                }
            },
        };
        DQuat::from_vec4(q / q.length())
    }
}

/// glTF 2.0 Appendix C, spherical linear interpolation, on normalised keys.
fn slerp_shortest(a: DQuat, b: DQuat, s: f64) -> DQuat {
    let (a, b) = (DVec4::from(a).normalize(), DVec4::from(b).normalize());
    let d = a.dot(b);
    let sign = if d < 0.0 { -1.0 } else { 1.0 };
    let angle = d.abs().min(1.0).acos();
    let v = if angle < 1e-9 {
        (1.0 - s) * a + s * sign * b
    } else {
        let sa = angle.sin();
        ((angle * (1.0 - s)).sin() / sa) * a + (sign * (angle * s).sin() / sa) * b
    };
    DQuat::from_vec4(v / v.length())
}

impl Channel<DVec3> {
    /// The translation at time `t` (seconds): `STEP` holds, `LINEAR` interpolates linearly,
    /// `CUBICSPLINE` is Appendix C's Hermite with tangents scaled by `t_{k+1} − t_k`. Clamped
    /// outside the keys.
    pub fn sample(&self, t: f64) -> DVec3 {
        match self.locate(t) {
            Located::Key(k) => self.values[k],
            Located::Between(k, s, dt) => match self.interpolation {
                Interpolation::Step => self.values[k],
                Interpolation::Linear => self.values[k].lerp(self.values[k + 1], s),
                Interpolation::CubicSpline => {
                    let tangents = self.tangents.as_deref().unwrap_or_default();
                    let b = hermite_basis(s);
                    b[0] * self.values[k]
                        + b[1] * (dt * tangents[k].1)
                        + b[2] * self.values[k + 1]
                        + b[3] * (dt * tangents[k + 1].0)
                }
            },
        }
    }
}

/// Whether float32 key time `key` counts as frame time `frame_time`: within two units in the
/// last place of float32 at `frame_time` (the spacing of float32 numbers just above
/// `|frame_time|`), so that keys exported at a rate come back on their frames.
///
/// (Its example is a unit test: `on_frame_example`.)
pub(crate) fn on_frame(key: f32, frame_time: f64) -> bool {
    (f64::from(key) - frame_time).abs() <= 2.0 * f32_ulp(frame_time)
}

/// The spacing of float32 numbers at `|x|` (from the float32 nearest `|x|` to the next one up).
pub(crate) fn f32_ulp(x: f64) -> f64 {
    let f = (x.abs() as f32).min(f32::MAX);
    let next = f32::from_bits(f.to_bits() + 1);
    f64::from(next) - f64::from(f)
}

/// `key` as seconds: the time of the nearest frame of `fps` when [`on_frame`] with it, else the
/// key widened exactly to f64.
///
/// (Its example is a unit test: `snap_key_time_example`.)
pub(crate) fn snap_key_time(key: f32, fps: crate::Fps) -> f64 {
    let t = f64::from(key);
    if !fps.in_range(t) {
        return t;
    }
    let frame = fps.time_of(fps.nearest_frame(t));
    if on_frame(key, frame) { frame } else { t }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    const TOL: f64 = 1e-12;

    fn chan(
        interpolation: Interpolation,
        times: &[f32],
        values: Vec<DQuat>,
        tangents: Option<Vec<(DQuat, DQuat)>>,
    ) -> RotationChannel {
        Channel {
            index: 0,
            node: 0,
            node_name: "node0".into(),
            sampler: 0,
            interpolation,
            times_f32: times.to_vec(),
            times: times.iter().map(|&t| f64::from(t)).collect(),
            values,
            tangents,
        }
    }

    fn assert_rot(a: DQuat, b: DQuat, tol: f64) {
        let (u, v) = (DVec4::from(a), DVec4::from(b));
        let v = if u.dot(v) < 0.0 { -v } else { v };
        let angle = 2.0 * (u - v).length().atan2((u + v).length());
        assert!(angle <= tol, "{a:?} vs {b:?}: {angle:e} rad apart");
    }

    #[test]
    fn step_holds_the_last_key_at_or_before() {
        let z = |a: f64| DQuat::from_rotation_z(a);
        let c = chan(
            Interpolation::Step,
            &[0.0, 1.0, 2.0],
            vec![z(0.0), z(1.0), z(2.0)],
            None,
        );
        assert_rot(c.sample(-1.0), z(0.0), TOL);
        assert_rot(c.sample(0.999), z(0.0), TOL);
        assert_rot(c.sample(1.0), z(1.0), TOL);
        assert_rot(c.sample(1.5), z(1.0), TOL);
        assert_rot(c.sample(5.0), z(2.0), TOL);
    }

    #[test]
    fn linear_is_constant_speed_on_the_shorter_arc() {
        let a = DQuat::IDENTITY;
        let b = DQuat::from_rotation_x(FRAC_PI_2);
        let c = chan(Interpolation::Linear, &[0.0, 2.0], vec![a, -b], None);
        for i in 0..=8 {
            let s = f64::from(i) / 8.0;
            assert_rot(
                c.sample(2.0 * s),
                DQuat::from_rotation_x(FRAC_PI_2 * s),
                1e-12,
            );
        }
    }

    #[test]
    fn linear_with_identical_keys() {
        let a = DQuat::from_rotation_y(0.3);
        let c = chan(Interpolation::Linear, &[0.0, 1.0], vec![a, a], None);
        assert_rot(c.sample(0.5), a, TOL);
    }

    #[test]
    fn linear_at_pi_apart_stays_unit() {
        let c = chan(
            Interpolation::Linear,
            &[0.0, 1.0],
            vec![DQuat::IDENTITY, DQuat::from_rotation_z(PI)],
            None,
        );
        let q = c.sample(0.5);
        assert!((q.length() - 1.0).abs() < 1e-15);
        assert_rot(q, DQuat::from_rotation_z(FRAC_PI_2), 1e-12);
    }

    #[test]
    fn cubic_with_zero_tangents_and_matching_hermite() {
        let a = DQuat::IDENTITY;
        let b = DQuat::from_rotation_z(1.0);
        let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
        let c = chan(
            Interpolation::CubicSpline,
            &[0.0, 1.0],
            vec![a, b],
            Some(vec![(zero, zero), (zero, zero)]),
        );
        // s = 1/2: basis (1/2, 1/8, 1/2, −1/8); zero tangents: the normalised midpoint.
        let mid = (DVec4::from(a) + DVec4::from(b)) * 0.5;
        assert_rot(c.sample(0.5), DQuat::from_vec4(mid.normalize()), TOL);
        assert_rot(c.sample(0.0), a, TOL);
        assert_rot(c.sample(1.0), b, TOL);
        assert_rot(c.sample(7.0), b, TOL);
    }

    #[test]
    fn cubic_tangents_are_scaled_by_the_segment_duration() {
        // A rotation about z at ω rad/s has dq/dt = (0, 0, ω/2·cos(ωt/2), −ω/2·sin(ωt/2)).
        let w = 1.0;
        let q = |t: f64| DQuat::from_rotation_z(w * t);
        let dq = |t: f64| {
            let h = w * t / 2.0;
            DQuat::from_xyzw(0.0, 0.0, w / 2.0 * h.cos(), -w / 2.0 * h.sin())
        };
        let times = [0.0f32, 0.5, 2.0];
        let c = chan(
            Interpolation::CubicSpline,
            &times,
            times.iter().map(|&t| q(f64::from(t))).collect(),
            Some(
                times
                    .iter()
                    .map(|&t| (dq(f64::from(t)), dq(f64::from(t))))
                    .collect(),
            ),
        );
        // Hermite with exact tangents follows the arc closely in both segments (different
        // durations): the error is the cubic's, O(Δt⁴), well under 1e-3 here.
        for i in 0..=40 {
            let t = 2.0 * f64::from(i) / 40.0;
            assert_rot(c.sample(t), q(t), 2e-3);
        }
    }

    #[test]
    fn translations() {
        let c = TranslationChannel {
            index: 0,
            node: 0,
            node_name: "n".into(),
            sampler: 0,
            interpolation: Interpolation::Linear,
            times_f32: vec![0.0, 1.0],
            times: vec![0.0, 1.0],
            values: vec![DVec3::ZERO, DVec3::new(2.0, 4.0, 6.0)],
            tangents: None,
        };
        assert_eq!(c.sample(0.25), DVec3::new(0.5, 1.0, 1.5));
        assert_eq!(c.sample(-1.0), DVec3::ZERO);
    }

    #[test]
    fn a_single_key_holds() {
        let a = DQuat::from_rotation_x(0.7);
        let c = chan(Interpolation::Linear, &[0.5], vec![a], None);
        assert_rot(c.sample(0.0), a, TOL);
        assert_rot(c.sample(3.0), a, TOL);
    }

    #[test]
    fn keys_within_two_float32_ulps_are_on_the_frame() {
        let fps = crate::Fps::new(30, 1).unwrap();
        for k in 0..3000i64 {
            let t = fps.time_of(k);
            assert_eq!(snap_key_time(t as f32, fps), t, "frame {k}");
        }
        // 1 ulp at 100 s is 2^-17 s ≈ 7.6e-6 s.
        assert_eq!(f32_ulp(100.0), 2f64.powi(-17));
        assert!(on_frame(100.0 + 2f32.powi(-16), 100.0));
        assert!(!on_frame(100.0 + 3.0 * 2f32.powi(-17), 100.0));
        assert_eq!(f32_ulp(0.0), f64::from(f32::from_bits(1)));
    }
}

#[cfg(test)]
mod examples {
    #[test]
    fn snap_key_time_example() {
        use crate::gltf::snap_key_time;
        use inbetween::Fps;
        let fps = Fps::new(30, 1).unwrap();
        assert_eq!(snap_key_time(0.1f32, fps), fps.time_of(3)); // 0.1f32 is 0.10000000149…
        assert_eq!(snap_key_time(0.11f32, fps), f64::from(0.11f32));
    }

    #[test]
    fn on_frame_example() {
        use crate::gltf::channel::on_frame;
        let frame = 0.75; // frame 3 at 4 fps, a float32 exactly
        assert!(on_frame((7.0f64 / 30.0) as f32, 7.0 / 30.0)); // frame 7 at 30 fps, rounded to float32
        assert!(on_frame(frame as f32, frame));
        assert!(on_frame(
            f32::from_bits((frame as f32).to_bits() + 2),
            frame
        ));
        assert!(!on_frame(
            f32::from_bits((frame as f32).to_bits() + 3),
            frame
        ));
    }
}
