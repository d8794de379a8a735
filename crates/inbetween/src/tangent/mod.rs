//! Keyframe preprocessing and tangents (docs/spec.md §4.1–§4.3).
//!
//! Tangents are kept as world-frame "half angular velocities" `w_i` (a pure quaternion, as a
//! [`DVec3`], per second): the curve's velocity at key `i` is `v_i = w_i·q_i`, and the angular
//! velocity is `ω_i = 2·w_i`. In segment `s` (from key `s` to `s+1`, length `Δ_s`) the
//! segment-scaled tangents are `V = (w·Δ_s)·q`.
//!
//! - Interior keys, [`TangentRule::Spline`] (the default): the derivative at the key of the
//!   not-a-knot cubic spline through the logs of up to seven keys in the key's chart
//!   (`tangent/spline.rs`); [`TangentRule::NamKim`]: `w_i = log(q_{i+1} q_{i−1}⁻¹) / (t_{i+1} − t_{i−1})`
//!   (Nam & Kim's estimate for unit spacing), or `(L⁻ + L⁺)/(t_{i+1} − t_{i−1})` with
//!   `L⁻ = log(q_i q_{i−1}⁻¹)`, `L⁺ = log(q_{i+1} q_i⁻¹)` when `‖L⁻‖ + ‖L⁺‖ > π`, where the
//!   direct log would alias to the other way round (possible only with `--path as-given`).
//! - Ends: `chord` `w_1 = log(q_2 q_1⁻¹)/Δ_1`, `w_n = log(q_n q_{n−1}⁻¹)/Δ_{n−1}`; `rest` `w = 0`;
//!   a given angular velocity ω (rad/s) gives `w = ω/2` and overrides either.

mod columns;
mod logs;
mod spline;

use crate::rotation::quat::log;
use crate::track::{Tcb, Track};
use glam::{DQuat, DVec3};

/// The tangent of an interior key without its own velocity or TCB values (`--tangent`,
/// docs/spec.md §4.1).
///
/// ```
/// use inbetween::{Curve, CurveOptions, TangentRule, Track};
/// use glam::DQuat;
///
/// // Keys of a steady turn about z, uneven in time: both rules give its speed, 1 rad/s.
/// let times = vec![0.0, 0.4, 1.0, 1.3, 2.0];
/// let keys = times.iter().map(|&t| DQuat::from_rotation_z(t)).collect();
/// let track = Track::new(times, keys)?;
/// for tangent in [TangentRule::Spline, TangentRule::NamKim] {
///     let opts = CurveOptions { tangent: Some(tangent), ..CurveOptions::default() };
///     let curve = Curve::new(&track, &opts)?;
///     assert!((curve.angular_velocity(1.0).z - 1.0).abs() < 1e-12);
/// }
/// assert_eq!("nam-kim".parse::<TangentRule>()?, TangentRule::NamKim);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum TangentRule {
    /// The derivative at the key of the not-a-knot cubic spline through the logarithms of the
    /// keys within three of it, in the key's chart: fourth order (`spline`).
    #[default]
    Spline,
    /// Nam & Kim's `log(q_{i+1} q_{i−1}⁻¹)/(t_{i+1} − t_{i−1})`: second order (`nam-kim`).
    NamKim,
}

impl TangentRule {
    /// Every rule, in the order of the command line's help.
    pub const ALL: [TangentRule; 2] = [TangentRule::Spline, TangentRule::NamKim];

    /// The rule's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TangentRule::Spline => "spline",
            TangentRule::NamKim => "nam-kim",
        }
    }
}

impl std::fmt::Display for TangentRule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

impl std::str::FromStr for TangentRule {
    type Err = crate::InputError;

    fn from_str(s: &str) -> Result<TangentRule, crate::InputError> {
        TangentRule::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| {
                crate::error::input_err!(
                    "expected a tangent rule from spline, nam-kim, found \"{s}\""
                )
            })
    }
}

/// How signs of consecutive keys are treated (docs/spec.md §4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PathMode {
    /// Flip each key into the hemisphere of the previous one: every step is at most 180°.
    #[default]
    Shortest,
    /// Keep the input signs: a key whose sign is flipped against its predecessor is reached the
    /// long way round (360° − φ).
    AsGiven,
    /// Keep the turns of Euler-angle keys: each segment's chord is the rotation vector, among
    /// those that carry key `i` to key `i+1`, nearest the motion of the angles interpolated
    /// linearly ([`crate::rotation::spin`]), so 0° → 270° turns 270° and 0° → 720° twice. Needs
    /// the track's Euler angles ([`crate::Track::with_euler_angles`]).
    Euler,
}

/// End condition when no velocity is given (docs/spec.md §4.2).
///
/// ```
/// use inbetween::{Curve, CurveOptions, Ends, Track};
/// use glam::{DQuat, DVec3};
///
/// let track = Track::new(vec![0.0, 1.0], vec![DQuat::IDENTITY, DQuat::from_rotation_y(1.0)])?;
/// let rest = CurveOptions { ends: Ends::Rest.into(), ..CurveOptions::default() };
/// let curve = Curve::new(&track, &rest)?;
/// assert!(curve.angular_velocity(0.0).length() < 1e-9); // starts at rest
/// assert!((curve.angular_velocity(0.5) - DVec3::new(0.0, 1.5, 0.0)).length() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ends {
    /// The end tangent points along the first/last chord (squad's classical `a_1 = q_1`).
    #[default]
    Chord,
    /// Zero velocity at both ends.
    Rest,
    /// A loop: the last key is the first key's rotation, and the tangent there is computed
    /// across the seam from the keys on both sides (time-aware), as at an interior key, so the
    /// loop has no velocity jump. No end velocity applies.
    Cyclic,
}

/// End conditions of a track: the default rule and optional given angular velocities (rad/s,
/// world frame).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EndConditions {
    /// The rule at an end without a given velocity.
    pub ends: Ends,
    /// Angular velocity at the first key, rad/s, world frame (overrides the track's).
    pub start: Option<DVec3>,
    /// Angular velocity at the last key, rad/s, world frame (overrides the track's).
    pub end: Option<DVec3>,
}

impl From<Ends> for EndConditions {
    /// The rule at both ends, no given velocity.
    fn from(ends: Ends) -> EndConditions {
        EndConditions {
            ends,
            start: None,
            end: None,
        }
    }
}

/// The knots of a spline: a track's times, its quaternions after the path rule, and a tangent at
/// every key.
#[derive(Debug, Clone, PartialEq)]
pub struct Knots {
    pub(crate) times: Vec<f64>,
    pub(crate) quats: Vec<DQuat>,
    /// Per-second half angular velocities leaving each key: `v_i = w[i]·q_i`.
    pub(crate) w: Vec<DVec3>,
    /// Per-second half angular velocities arriving at each key (differ from `w` only where a
    /// key's continuity is non-zero).
    pub(crate) w_in: Vec<DVec3>,
    /// Keys whose tangents were given or shaped (a key's own velocity, non-zero TCB, a cyclic
    /// seam's given velocity): squad builds its inner points from them instead of its own
    /// estimate.
    pub(crate) shaped: Vec<bool>,
    /// The track loops (`Ends::Cyclic`).
    pub(crate) cyclic: bool,
    /// Whether the end tangents were given (a velocity or `rest`) rather than `chord`.
    pub(crate) start_given: bool,
    pub(crate) end_given: bool,
    /// `--path euler`: each segment's half-angle chord `L_s` (`q_{s+1} = exp(L_s)·q_s`, any
    /// length); `None` when the chords are the logs `log(q_{s+1} q_s⁻¹)`.
    pub(crate) chords: Option<Vec<DVec3>>,
}

/// Applies `--path` to a sequence of quaternions (`Euler` keeps the signs here: its chords fix
/// them, [`Knots::new`]).
pub(crate) fn apply_path(quats: &mut [DQuat], mode: PathMode) {
    if mode == PathMode::Shortest {
        for i in 1..quats.len() {
            if quats[i - 1].dot(quats[i]) < 0.0 {
                quats[i] = -quats[i];
            }
        }
    }
}

/// Kochanek–Bartels tangents `(w_in, w_out)` per second of a key between chords `lm` and `lp`
/// over `span` seconds, the chords composed as rotations (see [`Knots::shaped`]).
fn kb_tangents(lm: DVec3, lp: DVec3, span: f64, tcb: Tcb) -> (DVec3, DVec3) {
    let ((ai, bi), (ao, bo)) = tcb.weights();
    // The alias bound on the terms composed: for zero TCB (a = b = 1/2) it is the bound of the
    // plain tangent, ‖L⁻‖ + ‖L⁺‖ > π.
    let one = |a: f64, b: f64| {
        if (lm * (2.0 * a)).length() + (lp * (2.0 * b)).length() > std::f64::consts::PI {
            (lm * (2.0 * a) + lp * (2.0 * b)) / span
        } else {
            crate::rotation::quat::log(
                crate::rotation::quat::exp(lp * (2.0 * b))
                    * crate::rotation::quat::exp(lm * (2.0 * a)),
            ) / span
        }
    };
    (one(ai, bi), one(ao, bo))
}

/// `--path euler`'s half-angle chords from the keys' Euler angles, and each key's sign set so
/// that `q_{s+1}` is `exp(L_s)·q_s` (not only the same rotation).
fn euler_chords(seq: crate::EulerSeq, angles: &[DVec3], quats: &mut [DQuat]) -> Vec<DVec3> {
    let mut chords = Vec::with_capacity(quats.len() - 1);
    for s in 0..quats.len() - 1 {
        let (q, next) = (quats[s], &mut quats[s + 1]);
        chords.push(euler_chord(seq, [angles[s], angles[s + 1]], q, next));
    }
    chords
}

/// One segment's chord of [`euler_chords`], from key `q` to key `next` (whose sign is set).
fn euler_chord(seq: crate::EulerSeq, angles: [DVec3; 2], q: DQuat, next: &mut DQuat) -> DVec3 {
    let c = crate::rotation::spin::chord(seq, angles[0], angles[1], q, *next) * 0.5;
    if (crate::rotation::quat::exp(c) * q).dot(*next) < 0.0 {
        *next = -*next;
    }
    c
}

/// `log(b a⁻¹)`: the half-angle step from `a` to `b` in the world frame.
#[inline]
pub fn step(a: DQuat, b: DQuat) -> DVec3 {
    log(b * a.conjugate())
}

impl Knots {
    /// Prepares a track: path mode, then tangents. Velocities in `ends` override the track's.
    /// `PathMode::Euler` on a track without Euler angles is `AsGiven` (a curve refuses it
    /// before: [`crate::Curve::new`]). The same as [`Knots::shaped`] with [`Tcb::ZERO`].
    pub fn new(track: &Track, path: PathMode, ends: EndConditions) -> Knots {
        Knots::shaped(track, path, ends, Tcb::ZERO, TangentRule::default())
    }

    /// [`Knots::new`] with `tcb` for the keys without their own Kochanek–Bartels values
    /// (docs/spec.md §4.1):
    ///
    /// - A key's own angular velocity ω ([`Track::with_key_velocities`]) gives both its tangents,
    ///   `w = ω/2`, over any estimate and TCB values.
    /// - An interior key with zero TCB: `rule`'s tangent ([`TangentRule`]); for `NamKim`
    ///   `w = log(q_{i+1} q_{i−1}⁻¹)/(t_{i+1} − t_{i−1})`, or `(L⁻ + L⁺)/(t_{i+1} − t_{i−1})` when
    ///   `‖L⁻‖ + ‖L⁺‖ > π` (the alias rule).
    /// - Otherwise, with Kochanek & Bartels' weights ([`Tcb::weights`]):
    ///   `w_out = log(exp(2b_out·L⁺)·exp(2a_out·L⁻))/(t_{i+1} − t_{i−1})` and `w_in` likewise —
    ///   their tangent `a·L⁻ + b·L⁺` per unit spacing, adjusted for unequal spacing as in their
    ///   paper, with the sum of chords composed as rotations (for zero TCB it is the line above);
    ///   past the alias bound of the terms composed, `‖2a·L⁻‖ + ‖2b·L⁺‖ > π`,
    ///   `(2a·L⁻ + 2b·L⁺)/(t_{i+1} − t_{i−1})`.
    /// - Ends: the rule of `ends` ([`Ends`]); `Cyclic` computes the first key as an interior key
    ///   whose previous key is the one before the last (`Spline`'s window wraps around the seam),
    ///   and gives the last key the same tangents.
    pub fn shaped(
        track: &Track,
        path: PathMode,
        ends: EndConditions,
        tcb: Tcb,
        rule: TangentRule,
    ) -> Knots {
        let mut quats = track.rotations().to_vec();
        apply_path(&mut quats, path);
        let chords = match (path, track.euler_angles()) {
            (PathMode::Euler, Some((seq, angles))) if quats.len() > 1 => {
                Some(euler_chords(seq, angles, &mut quats))
            }
            _ => None,
        };
        let t = track.times();
        let n = quats.len();
        let keys = logs::Keys::of(&quats);
        let all: Vec<DVec3> = match &chords {
            Some(c) => c.clone(),
            None => logs::chords(&keys),
        };
        if n == 1 {
            // A constant: no motion, whatever the ends say.
            return Knots {
                times: t.to_vec(),
                quats,
                w: vec![DVec3::ZERO],
                w_in: vec![DVec3::ZERO],
                shaped: vec![false],
                cyclic: false,
                start_given: true,
                end_given: true,
                chords: None,
            };
        }
        let velocity = |i: usize| track.key_velocities().and_then(|v| v[i]);
        let key_tcb = |i: usize| track.key_tcb().and_then(|v| v[i]).unwrap_or(tcb);
        let mut w = vec![DVec3::ZERO; n];
        let mut w_in = vec![DVec3::ZERO; n];
        let mut shaped = vec![false; n];
        let cyclic = ends.ends == Ends::Cyclic;
        // The windows, where a key will take its tangent from one.
        let estimated = |i: usize| velocity(i).is_none() && key_tcb(i).is_zero();
        let needed = (1..n - 1).any(estimated) || (cyclic && estimated(0) && estimated(n - 1));
        let windows = (rule == TangentRule::Spline && needed)
            .then(|| spline::Windows::new(t, &quats, &keys, &all, cyclic));
        // Every interior key takes its spline tangent (no key's own velocity or TCB values):
        // four at a time, without the per-key tests.
        let all_estimated =
            track.key_velocities().is_none() && track.key_tcb().is_none() && tcb.is_zero();
        match &windows {
            Some(windows) if all_estimated => {
                windows.fill(1, &mut w[1..n - 1]);
                w_in[1..n - 1].copy_from_slice(&w[1..n - 1]);
            }
            _ => {
                let mut in_order = windows.as_ref().map(spline::InOrder::new);
                for i in 1..n - 1 {
                    let (lm, lp) = (all[i - 1], all[i]);
                    let span = t[i + 1] - t[i - 1];
                    let (wi, wo) = match (velocity(i), key_tcb(i)) {
                        (Some(omega), _) => (omega * 0.5, omega * 0.5),
                        (None, k) if k.is_zero() && in_order.is_some() => {
                            let x = in_order.as_mut().map_or(DVec3::ZERO, |w| w.get(i));
                            (x, x)
                        }
                        (None, k) if k.is_zero() => {
                            let x = if lm.length() + lp.length() > std::f64::consts::PI {
                                (lm + lp) / span
                            } else {
                                step(quats[i - 1], quats[i + 1]) / span
                            };
                            (x, x)
                        }
                        (None, k) => kb_tangents(lm, lp, span, k),
                    };
                    (w_in[i], w[i]) = (wi, wo);
                    shaped[i] = velocity(i).is_some() || !key_tcb(i).is_zero();
                }
            }
        }
        let (start, end) = if cyclic {
            let (lm, lp) = (all[n - 2], all[0]);
            let span = (t[n - 1] - t[n - 2]) + (t[1] - t[0]);
            let given = velocity(0).or(velocity(n - 1));
            let (wi, wo) = match given {
                Some(omega) => (omega * 0.5, omega * 0.5),
                None if key_tcb(0).is_zero() && windows.is_some() => {
                    let x = windows.as_ref().map_or(DVec3::ZERO, |w| w.tangent(0));
                    (x, x)
                }
                None => kb_tangents(lm, lp, span, key_tcb(0)),
            };
            (w_in[0], w[0], w_in[n - 1], w[n - 1]) = (wi, wo, wi, wo);
            let s = given.is_some() || !key_tcb(0).is_zero();
            (shaped[0], shaped[n - 1]) = (s, s);
            (None, None)
        } else {
            let start = ends.start.or(velocity(0)).or(track.start_velocity());
            let end = ends.end.or(velocity(n - 1)).or(track.end_velocity());
            w[0] = match (start, ends.ends) {
                (Some(omega), _) => omega * 0.5,
                (None, Ends::Rest) => DVec3::ZERO,
                (None, _) => all[0] / (t[1] - t[0]),
            };
            w[n - 1] = match (end, ends.ends) {
                (Some(omega), _) => omega * 0.5,
                (None, Ends::Rest) => DVec3::ZERO,
                (None, _) => all[n - 2] / (t[n - 1] - t[n - 2]),
            };
            (w_in[0], w_in[n - 1]) = (w[0], w[n - 1]);
            (start, end)
        };
        Knots {
            times: t.to_vec(),
            quats,
            w,
            w_in,
            shaped,
            cyclic,
            start_given: cyclic || start.is_some() || ends.ends == Ends::Rest,
            end_given: cyclic || end.is_some() || ends.ends == Ends::Rest,
            chords,
        }
    }

    /// The knots [`Knots::shaped`] builds for two keys that carry their own velocities `omega`
    /// (rad/s) and, for `--path euler`, their Euler angles, not looped, written into `self`
    /// (whose buffers are kept): reduce tests millions of segments, and a track and a curve each
    /// would be built for one frame's probe. The same values as `shaped`, to the last bit.
    pub(crate) fn set_pair(
        &mut self,
        times: [f64; 2],
        mut quats: [DQuat; 2],
        path: PathMode,
        omega: [DVec3; 2],
        euler: Option<(crate::EulerSeq, [DVec3; 2])>,
    ) {
        apply_path(&mut quats, path);
        let chord = match (path, euler) {
            (PathMode::Euler, Some((seq, angles))) => {
                let [q, next] = &mut quats;
                Some(euler_chord(seq, angles, *q, next))
            }
            _ => None,
        };
        self.chords = chord.map(|c| {
            let mut v = self.chords.take().unwrap_or_default();
            v.clear();
            v.push(c);
            v
        });
        let w = omega.map(|o| o * 0.5);
        fn set<T: Copy>(v: &mut Vec<T>, x: [T; 2]) {
            v.clear();
            v.extend_from_slice(&x);
        }
        set(&mut self.times, times);
        set(&mut self.quats, quats);
        set(&mut self.w, w);
        set(&mut self.w_in, w);
        set(&mut self.shaped, [false; 2]);
        self.cyclic = false;
        self.start_given = true;
        self.end_given = true;
    }

    /// [`Knots::set_pair`] into new knots.
    pub(crate) fn pair(
        times: [f64; 2],
        quats: [DQuat; 2],
        path: PathMode,
        omega: [DVec3; 2],
        euler: Option<(crate::EulerSeq, [DVec3; 2])>,
    ) -> Knots {
        let mut k = Knots {
            times: Vec::new(),
            quats: Vec::new(),
            w: Vec::new(),
            w_in: Vec::new(),
            shaped: Vec::new(),
            cyclic: false,
            start_given: true,
            end_given: true,
            chords: None,
        };
        k.set_pair(times, quats, path, omega, euler);
        k
    }

    /// Whether the chords are `--path euler`'s (of any length) rather than the logs.
    pub fn spins(&self) -> bool {
        self.chords.is_some()
    }

    /// The half-angle chord of segment `s`: `L_s` with `q_{s+1} = exp(L_s)·q_s`.
    pub fn chord(&self, s: usize) -> DVec3 {
        match &self.chords {
            Some(c) => c[s],
            None => step(self.quats[s], self.quats[s + 1]),
        }
    }

    /// The S³ length of segment `s`'s chord (`‖L_s‖`; for the logs, the angle between the keys).
    pub fn chord_length(&self, s: usize) -> f64 {
        match &self.chords {
            Some(c) => c[s].length(),
            None => crate::rotation::arc::s3_angle(self.quats[s], self.quats[s + 1]),
        }
    }

    /// The great arc of segment `s`'s chord from `q_s` to `q_{s+1}` (slerp; squad's outer arc).
    pub(crate) fn chord_arc(&self, s: usize) -> crate::rotation::arc::Arc {
        use crate::rotation::arc::Arc;
        match &self.chords {
            Some(c) => Arc::leaving(
                self.quats[s],
                crate::rotation::quat::pure_mul(c[s], self.quats[s]),
            ),
            None => Arc::between(self.quats[s], self.quats[s + 1]),
        }
    }

    /// Key times, s.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Key quaternions after the path rule.
    pub fn quats(&self) -> &[DQuat] {
        &self.quats
    }

    /// Tangents leaving each key: per-second half angular velocities `w_i` (world frame),
    /// `v_i = w_i·q_i`.
    pub fn w(&self) -> &[DVec3] {
        &self.w
    }

    /// Whether the start and end tangents were given (a velocity, or `rest`) rather than
    /// estimated from the chord.
    pub fn ends_given(&self) -> (bool, bool) {
        (self.start_given, self.end_given)
    }

    /// Number of segments.
    pub fn segments(&self) -> usize {
        self.quats.len() - 1
    }

    /// Length in seconds of segment `s`.
    pub fn delta(&self, s: usize) -> f64 {
        self.times[s + 1] - self.times[s]
    }

    /// Tangents arriving at each key, per second (they differ from [`Knots::w`] only where a
    /// key's continuity is non-zero).
    pub fn w_in(&self) -> &[DVec3] {
        &self.w_in
    }

    /// Segment-scaled tangent `V = (w_i·Δ_s)·q_i` of key `i` in segment `s` (the tangent leaving
    /// key `i` when `s = i`, the one arriving when `s = i − 1`).
    pub fn tangent(&self, i: usize, s: usize) -> DQuat {
        let w = if s == i { self.w[i] } else { self.w_in[i] };
        crate::rotation::quat::pure_mul(w * self.delta(s), self.quats[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pair_of_keys_with_velocities_is_shaped_as_a_track_of_them() {
        let q = [DQuat::from_rotation_z(0.3), -DQuat::from_rotation_x(2.9)];
        let omega = [DVec3::new(0.1, -2.0, 7.5), DVec3::new(-3.0, 0.25, 1e-3)];
        let times = [0.125, 0.9];
        let t = Track::new(times.to_vec(), q.to_vec())
            .and_then(|t| t.with_key_velocities(omega.map(Some).to_vec()))
            .expect("a valid track");
        let seq = crate::EulerSeq::parse("ZXY").expect("a sequence");
        let angles = [DVec3::new(0.3, -1.0, 2.0), DVec3::new(4.0, 0.5, -2.5)];
        let spun = Track::new(
            times.to_vec(),
            angles.map(|e| seq.to_quat(e.to_array())).to_vec(),
        )
        .and_then(|t| t.with_key_velocities(omega.map(Some).to_vec()))
        .and_then(|t| t.with_euler_angles(seq, angles.to_vec()))
        .expect("a valid track");
        let spun_q = [spun.rotations()[0], spun.rotations()[1]];
        let none = [DVec3::ZERO; 2];
        let mut scratch = Knots::pair(
            [0.0, 1.0],
            [DQuat::IDENTITY; 2],
            PathMode::AsGiven,
            none,
            None,
        );
        for path in [PathMode::Shortest, PathMode::AsGiven, PathMode::Euler] {
            for ends in [Ends::Chord, Ends::Rest] {
                let ends = EndConditions {
                    ends,
                    ..Default::default()
                };
                let tcb = Tcb {
                    tension: 0.5,
                    ..Tcb::ZERO
                };
                let want = Knots::shaped(&t, path, ends, tcb, TangentRule::Spline);
                scratch.set_pair(times, q, path, omega, None);
                assert_eq!(scratch, want, "{path:?} {ends:?}");
                assert_eq!(Knots::pair(times, q, path, omega, None), want);
                // With Euler angles: their chords under `euler`, none otherwise.
                let want = Knots::shaped(&spun, path, ends, tcb, TangentRule::Spline);
                scratch.set_pair(times, spun_q, path, omega, Some((seq, angles)));
                assert_eq!(scratch, want, "{path:?} {ends:?} with Euler angles");
                assert_eq!(want.spins(), path == PathMode::Euler);
            }
        }
    }

    /// A steady spin about z in 100° steps with tension −1 (weights a = b = 1): the composed
    /// terms exp(2L⁺)·exp(2L⁻) turn 400° in all, past the alias bound though ‖L⁻‖ + ‖L⁺‖ (100°
    /// in half angles) is not. The tangent still points along the motion, twice the plain one.
    #[test]
    fn large_kb_weights_do_not_alias_the_tangent() {
        let step = 100f64.to_radians();
        let t = track(
            &[0.0, 1.0, 2.0],
            &[0.0, step, 2.0 * step].map(DQuat::from_rotation_z),
        );
        let tcb = Tcb {
            tension: -1.0,
            ..Tcb::ZERO
        };
        let k = Knots::shaped(
            &t,
            PathMode::Shortest,
            EndConditions::default(),
            tcb,
            TangentRule::Spline,
        );
        let want = DVec3::Z * (2.0 * step) / 2.0; // (2·L⁻ + 2·L⁺)/2 s, L = step/2
        assert!((k.w[1] - want).length() < 1e-12, "{:?} vs {want:?}", k.w[1]);
        assert!(
            (k.w_in[1] - want).length() < 1e-12,
            "{:?} vs {want:?}",
            k.w_in[1]
        );
    }

    fn track(times: &[f64], quats: &[DQuat]) -> Track {
        Track::new(times.to_vec(), quats.to_vec()).unwrap()
    }

    #[test]
    fn shortest_flips_into_the_previous_hemisphere() {
        let mut q = [
            DQuat::IDENTITY,
            -DQuat::from_rotation_z(0.5),
            DQuat::from_rotation_z(1.0),
        ];
        apply_path(&mut q, PathMode::Shortest);
        assert!(q[1].w > 0.0 && q[2].w > 0.0);
    }

    #[test]
    fn nam_kim_estimate_for_unit_spacing() {
        let q: Vec<_> = [0.0, 0.4, 1.0]
            .iter()
            .map(|a| DQuat::from_rotation_y(*a))
            .collect();
        let k = Knots::new(
            &track(&[0.0, 1.0, 2.0], &q),
            PathMode::Shortest,
            EndConditions::default(),
        );
        // ½ log(q2 q0⁻¹): half of the half-angle step 0.5 about y.
        assert!((k.w[1] - DVec3::new(0.0, 0.25, 0.0)).length() < 1e-15);
        // Chord ends.
        assert!((k.w[0] - DVec3::new(0.0, 0.2, 0.0)).length() < 1e-15);
        assert!((k.w[2] - DVec3::new(0.0, 0.3, 0.0)).length() < 1e-15);
    }

    #[test]
    fn given_velocity_and_rest() {
        let q = [DQuat::IDENTITY, DQuat::from_rotation_x(1.0)];
        let ends = EndConditions {
            ends: Ends::Rest,
            start: Some(DVec3::new(0.0, 0.0, 2.0)),
            end: None,
        };
        let k = Knots::new(&track(&[0.0, 1.0], &q), PathMode::Shortest, ends);
        assert_eq!(k.w[0], DVec3::new(0.0, 0.0, 1.0));
        assert_eq!(k.w[1], DVec3::ZERO);
    }

    #[test]
    fn more_than_a_turn_uses_the_sum_of_steps() {
        // Each step 170° (half-angle 85°) with as-given signs: 340° in two steps.
        let a = 85f64.to_radians();
        let q = [
            DQuat::IDENTITY,
            DQuat::from_xyzw(0.0, 0.0, a.sin(), a.cos()),
            DQuat::from_xyzw(0.0, 0.0, (2.0 * a).sin(), (2.0 * a).cos()),
        ];
        let k = Knots::new(
            &track(&[0.0, 1.0, 2.0], &q),
            PathMode::AsGiven,
            EndConditions::default(),
        );
        assert!((k.w[1].z - a).abs() < 1e-14, "{}", k.w[1]);
    }
}
