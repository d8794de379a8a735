//! A validated track: keyframe times and rotations that every scheme can interpolate.
//!
//! The constructors are the only way in, so a [`Track`] is known to hold keys whose
//! times are finite, strictly increasing and at least `MIN_KEY_GAP` apart, with finite unit
//! quaternions; nothing downstream re-checks. The same time rule serves the readers of keyframe
//! documents ([`check_times`]), so a file and a program are held to one contract.

use crate::error::{Error, InputError};
use crate::rotation::EulerSeq;
use glam::{DQuat, DVec3};
use std::fmt;

/// Smallest accepted time between consecutive keys, in seconds: closer keys would make the chord
/// tangent `log(q_{i+1} q_i⁻¹)/Δ` overflow (at denormal Δ) or meaningless; the frame tolerance
/// is 1e-9 s.
pub(crate) const MIN_KEY_GAP: f64 = 1e-12;

/// How far a rotation's norm may be from 1 (it is used as given, not renormalised).
pub(crate) const UNIT_TOL: f64 = 1e-6;

/// How far the rotation of a key's Euler triple may be from the key's rotation, rad
/// ([`Track::with_euler_angles`]).
pub(crate) const EULER_TOL: f64 = 1e-6;

/// Why a [`Track`] could not be built. Indices count keys from 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrackError {
    /// Fewer than two keys given to [`Track::new`] (a single key is [`Track::constant`]).
    TooFewKeys {
        /// The number of keys given.
        found: usize,
    },
    /// `times` and `rotations` differ in length.
    LengthMismatch {
        /// Number of times.
        times: usize,
        /// Number of rotations.
        rotations: usize,
    },
    /// A time is NaN or infinite.
    NonFiniteTime {
        /// The key.
        index: usize,
        /// Its time.
        time: f64,
    },
    /// A time is not after its predecessor (unsorted or duplicate).
    NotIncreasing {
        /// The key.
        index: usize,
        /// Its time, s.
        time: f64,
        /// The previous key's time, s.
        previous: f64,
    },
    /// A time is after its predecessor by less than `MIN_KEY_GAP`.
    TooClose {
        /// The key.
        index: usize,
        /// Its time, s.
        time: f64,
        /// The previous key's time, s.
        previous: f64,
    },
    /// A rotation is not a finite unit quaternion (norm within `UNIT_TOL` of 1).
    NotUnit {
        /// The key.
        index: usize,
        /// The quaternion's norm.
        norm: f64,
    },
    /// A given end velocity is not finite.
    NonFiniteVelocity,
    /// [`Track::with_euler_angles`] got a number of triples other than the number of keys.
    EulerCount {
        /// Number of keys.
        keys: usize,
        /// Number of triples.
        angles: usize,
    },
    /// A per-key list ([`Track::with_key_velocities`], [`Track::with_key_tcb`]) does not have one
    /// entry per key.
    KeyCount {
        /// What the list holds.
        what: &'static str,
        /// Number of keys.
        keys: usize,
        /// Number of entries.
        found: usize,
    },
    /// A key's angular velocity is not finite.
    KeyVelocity {
        /// The key.
        index: usize,
    },
    /// A key's translation is not finite.
    KeyTranslation {
        /// The key.
        index: usize,
    },
    /// A key's tension, continuity or bias is not a finite number in `[−1, 1]`.
    KeyTcb {
        /// The key.
        index: usize,
    },
    /// A key's Euler angles are not finite, beyond ±1e15 rad, or not its rotation.
    EulerAngles {
        /// The key.
        index: usize,
        /// The angle between the triple's rotation and the key's, rad (NaN when the triple
        /// is not finite or out of range).
        off: f64,
    },
}

impl TrackError {
    /// The key the error is about, if it is about one.
    pub fn index(&self) -> Option<usize> {
        match *self {
            TrackError::NonFiniteTime { index, .. }
            | TrackError::NotIncreasing { index, .. }
            | TrackError::TooClose { index, .. }
            | TrackError::NotUnit { index, .. }
            | TrackError::EulerAngles { index, .. }
            | TrackError::KeyVelocity { index }
            | TrackError::KeyTcb { index }
            | TrackError::KeyTranslation { index } => Some(index),
            _ => None,
        }
    }
}

impl fmt::Display for TrackError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use crate::error::num;
        match *self {
            TrackError::TooFewKeys { found } => {
                write!(f, "expected at least 2 keys, found {found}")
            }
            TrackError::LengthMismatch { times, rotations } => write!(
                f,
                "expected as many rotations as times, found {rotations} rotations for {times} times"
            ),
            TrackError::NonFiniteTime { time, .. } => {
                write!(f, "expected a finite number, found {time}")
            }
            TrackError::NotIncreasing { time, previous, .. } => write!(
                f,
                "expected times strictly increasing within a track, found {} s after {} s",
                num(time),
                num(previous)
            ),
            TrackError::TooClose { time, previous, .. } => write!(
                f,
                "expected keys at least 1e-12 s apart, found {} s only {:e} s after {} s \
                 (merge the two keys)",
                num(time),
                time - previous,
                num(previous)
            ),
            TrackError::NotUnit { norm, .. } => write!(
                f,
                "expected a unit quaternion (norm within {UNIT_TOL:e} of 1), found norm {}",
                num(norm)
            ),
            TrackError::NonFiniteVelocity => {
                write!(f, "expected a finite end velocity")
            }
            TrackError::KeyCount { what, keys, found } => write!(
                f,
                "expected one {what} per key, found {found} for {keys} keys"
            ),
            TrackError::KeyTranslation { .. } => {
                write!(f, "expected a finite translation")
            }
            TrackError::KeyVelocity { .. } => {
                write!(f, "expected a finite angular velocity")
            }
            TrackError::KeyTcb { .. } => {
                write!(f, "expected tension, continuity and bias between -1 and 1")
            }
            TrackError::EulerCount { keys, angles } => write!(
                f,
                "expected one Euler triple per key, found {angles} triples for {keys} keys"
            ),
            TrackError::EulerAngles { off, .. } if off.is_nan() => {
                write!(f, "expected finite Euler angles within ±1e15 rad")
            }
            TrackError::EulerAngles { off, .. } => write!(
                f,
                "expected Euler angles of the key's rotation (within {EULER_TOL:e} rad), found \
                 {} rad away",
                num(off)
            ),
        }
    }
}

impl std::error::Error for TrackError {}

/// Checks key times: finite, strictly increasing, consecutive keys at least `MIN_KEY_GAP`
/// apart (any number of keys). The time rule of [`Track::new`], for readers that also accept
/// one-key tracks.
pub fn check_times(times: &[f64]) -> Result<(), TrackError> {
    for (index, &time) in times.iter().enumerate() {
        if !time.is_finite() {
            return Err(TrackError::NonFiniteTime { index, time });
        }
        if index == 0 {
            continue;
        }
        let previous = times[index - 1];
        if time <= previous {
            return Err(TrackError::NotIncreasing {
                index,
                time,
                previous,
            });
        }
        if time - previous < MIN_KEY_GAP {
            return Err(TrackError::TooClose {
                index,
                time,
                previous,
            });
        }
    }
    Ok(())
}

/// Keyframes ready for interpolation: times in seconds and unit quaternions, validated.
///
/// Quaternion signs are kept as given; `--path`-style hemisphere handling happens when a curve is
/// built ([`crate::PathMode`]). End velocities, when given, are world-frame angular velocities in
/// rad/s and take precedence over the curve options' end rule only when those give none.
///
/// ```
/// use inbetween::{Track, TrackError};
/// use glam::DQuat;
///
/// let q = [DQuat::IDENTITY, DQuat::from_rotation_z(1.0), DQuat::from_rotation_x(0.5)];
/// let track = Track::new(vec![0.0, 0.5, 1.25], q.to_vec())?.with_name("hip");
/// assert_eq!(track.span(), (0.0, 1.25));
/// assert_eq!(track.name(), Some("hip"));
///
/// // Unsorted times are refused, with the key and the numbers.
/// let err = Track::new(vec![0.0, 1.0, 0.5], q.to_vec()).unwrap_err();
/// assert_eq!(
///     err,
///     TrackError::NotIncreasing { index: 2, time: 0.5, previous: 1.0 }
/// );
/// # Ok::<(), TrackError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    name: Option<String>,
    times: Vec<f64>,
    rotations: Vec<DQuat>,
    start_velocity: Option<DVec3>,
    end_velocity: Option<DVec3>,
    euler: Option<(EulerSeq, Vec<DVec3>)>,
    key_velocities: Option<Vec<Option<DVec3>>>,
    key_tcb: Option<Vec<Option<Tcb>>>,
    translations: Option<Vec<DVec3>>,
}

impl Track {
    /// A track from key times (seconds) and rotations (unit quaternions), one per key.
    ///
    /// Refuses fewer than two keys (a joint that does not move is [`Track::constant`]),
    /// mismatched lengths, non-finite, unsorted, duplicate or closer-than-`MIN_KEY_GAP` times,
    /// and quaternions that are not finite and of unit norm (within `UNIT_TOL`).
    pub fn new(times: Vec<f64>, rotations: Vec<DQuat>) -> Result<Track, TrackError> {
        if times.len() != rotations.len() {
            return Err(TrackError::LengthMismatch {
                times: times.len(),
                rotations: rotations.len(),
            });
        }
        if times.len() < 2 {
            return Err(TrackError::TooFewKeys { found: times.len() });
        }
        Track::checked(times, rotations)
    }

    /// A constant: one key, at `time`, whose rotation holds over any span it is written over (a
    /// joint that does not move). Its curve is at rest everywhere.
    pub fn constant(time: f64, rotation: DQuat) -> Result<Track, TrackError> {
        Track::checked(vec![time], vec![rotation])
    }

    /// The checks shared by the constructors: times, then rotations.
    fn checked(times: Vec<f64>, rotations: Vec<DQuat>) -> Result<Track, TrackError> {
        check_times(&times)?;
        for (index, q) in rotations.iter().enumerate() {
            let norm = q.length();
            if !q.is_finite() || (norm - 1.0).abs() > UNIT_TOL {
                return Err(TrackError::NotUnit { index, norm });
            }
        }
        Ok(Track {
            name: None,
            times,
            rotations,
            start_velocity: None,
            end_velocity: None,
            euler: None,
            key_velocities: None,
            key_tcb: None,
            translations: None,
        })
    }

    /// Gives every key a position (a BVH or glTF translation, in the file's length unit), one per
    /// key, finite. A curve interpolates them beside the rotations ([`Curve::position`](crate::Curve::position)).
    pub fn with_translations(mut self, p: Vec<DVec3>) -> Result<Track, TrackError> {
        if p.len() != self.len() {
            return Err(TrackError::KeyCount {
                what: "translation",
                keys: self.len(),
                found: p.len(),
            });
        }
        if let Some(index) = p.iter().position(|x| !x.is_finite()) {
            return Err(TrackError::KeyTranslation { index });
        }
        self.translations = Some(p);
        Ok(self)
    }

    /// The keys' positions, when the track has them.
    pub fn translations(&self) -> Option<&[DVec3]> {
        self.translations.as_deref()
    }

    /// Gives keys their own world-frame angular velocities (rad/s; `None` for a key without
    /// one), one entry per key. At such a key the curve's tangent is that velocity, over any
    /// estimate and Kochanek–Bartels values; at the first or last key it is the end velocity
    /// unless the curve options give one ([`crate::EndConditions`]).
    ///
    /// ```
    /// use inbetween::{Curve, CurveOptions, Track};
    /// use glam::{DQuat, DVec3};
    ///
    /// let q = [DQuat::IDENTITY, DQuat::from_rotation_z(1.0), DQuat::from_rotation_z(2.0)];
    /// let track = Track::new(vec![0.0, 1.0, 2.0], q.to_vec())?
    ///     .with_key_velocities(vec![None, Some(DVec3::new(0.0, 0.0, 3.0)), None])?;
    /// let curve = Curve::new(&track, &CurveOptions::default())?;
    /// assert!((curve.angular_velocity(1.0) - DVec3::new(0.0, 0.0, 3.0)).length() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_key_velocities(mut self, v: Vec<Option<DVec3>>) -> Result<Track, TrackError> {
        if v.len() != self.len() {
            return Err(TrackError::KeyCount {
                what: "angular velocity",
                keys: self.len(),
                found: v.len(),
            });
        }
        if let Some(index) = v.iter().position(|x| x.is_some_and(|x| !x.is_finite())) {
            return Err(TrackError::KeyVelocity { index });
        }
        self.key_velocities = v.iter().any(Option::is_some).then_some(v);
        Ok(self)
    }

    /// Gives keys their own Kochanek–Bartels tension, continuity and bias (`None` for a key that
    /// takes the curve options' [`crate::CurveOptions::tcb`]), one entry per key; each value in
    /// `[−1, 1]`. They shape interior keys (and the seam of a cyclic track).
    pub fn with_key_tcb(mut self, v: Vec<Option<Tcb>>) -> Result<Track, TrackError> {
        if v.len() != self.len() {
            return Err(TrackError::KeyCount {
                what: "tension/continuity/bias",
                keys: self.len(),
                found: v.len(),
            });
        }
        if let Some(index) = v.iter().position(|x| x.is_some_and(|x| !x.is_valid())) {
            return Err(TrackError::KeyTcb { index });
        }
        self.key_tcb = v.iter().any(Option::is_some).then_some(v);
        Ok(self)
    }

    /// The keys' own angular velocities (rad/s, world frame), when any key has one.
    pub fn key_velocities(&self) -> Option<&[Option<DVec3>]> {
        self.key_velocities.as_deref()
    }

    /// The keys' own Kochanek–Bartels values, when any key has them.
    pub fn key_tcb(&self) -> Option<&[Option<Tcb>]> {
        self.key_tcb.as_deref()
    }

    /// Keeps the Euler angles the keys were given as (radians, as written: not wrapped), one
    /// triple per key in `seq`. They are what `PathMode::Euler` builds its chords from (the turns
    /// the angles make between keys, docs/spec.md §4.3), and where a continuous Euler output in
    /// the same sequence starts. Each triple must be finite, within ±1e15 rad, and give its key's
    /// rotation within `EULER_TOL` rad.
    ///
    /// ```
    /// use inbetween::{EulerSeq, Track};
    /// use glam::DVec3;
    ///
    /// let zyx = EulerSeq::parse("ZYX")?;
    /// let e = [DVec3::ZERO, DVec3::new(4.712388980384690, 0.0, 0.0)]; // 0° and 270° about z
    /// let q = e.iter().map(|e| zyx.to_quat(e.to_array())).collect();
    /// let track = Track::new(vec![0.0, 1.0], q)?.with_euler_angles(zyx, e.to_vec())?;
    /// assert_eq!(track.euler_angles().unwrap().1[1], e[1]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_euler_angles(
        mut self,
        seq: EulerSeq,
        angles: Vec<DVec3>,
    ) -> Result<Track, TrackError> {
        if angles.len() != self.rotations.len() {
            return Err(TrackError::EulerCount {
                keys: self.rotations.len(),
                angles: angles.len(),
            });
        }
        for (index, (e, &q)) in angles.iter().zip(&self.rotations).enumerate() {
            if !e.is_finite() || e.abs().max_element() > crate::rotation::magnitude::MAX_ANGLE {
                return Err(TrackError::EulerAngles {
                    index,
                    off: f64::NAN,
                });
            }
            let off = crate::rotation::quat::rotation_angle_between(seq.to_quat(e.to_array()), q);
            if off > EULER_TOL {
                return Err(TrackError::EulerAngles { index, off });
            }
        }
        self.euler = Some((seq, angles));
        Ok(self)
    }

    /// The Euler angles the keys were given as, when they were ([`Track::with_euler_angles`]).
    pub fn euler_angles(&self) -> Option<(EulerSeq, &[DVec3])> {
        self.euler.as_ref().map(|(s, a)| (*s, a.as_slice()))
    }

    /// The same track with its keys at other `times` (one per key; everything else kept), by
    /// the time rule of [`Track::new`].
    pub fn retimed(&self, times: Vec<f64>) -> Result<Track, TrackError> {
        if times.len() != self.len() {
            return Err(TrackError::LengthMismatch {
                times: times.len(),
                rotations: self.len(),
            });
        }
        check_times(&times)?;
        Ok(Track {
            times,
            ..self.clone()
        })
    }

    /// Names the track (used in warnings and in multi-track output).
    pub fn with_name(mut self, name: impl Into<String>) -> Track {
        self.name = Some(name.into());
        self
    }

    /// Sets the world-frame angular velocities (rad/s) at the first and last key; `None` leaves
    /// an end to the curve options' rule.
    pub fn with_end_velocities(
        mut self,
        start: Option<DVec3>,
        end: Option<DVec3>,
    ) -> Result<Track, TrackError> {
        if start.is_some_and(|v| !v.is_finite()) || end.is_some_and(|v| !v.is_finite()) {
            return Err(TrackError::NonFiniteVelocity);
        }
        self.start_velocity = start;
        self.end_velocity = end;
        Ok(self)
    }

    /// The track's name, if it has one.
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// Key times in seconds: finite, strictly increasing; at least two, or one for a constant.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Key rotations, unit quaternions with their signs as given.
    pub fn rotations(&self) -> &[DQuat] {
        &self.rotations
    }

    /// Number of keys (one for a constant).
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Always false: a track has at least one key (a constant).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// First and last key time, s.
    pub fn span(&self) -> (f64, f64) {
        (self.times[0], self.times[self.times.len() - 1])
    }

    /// The given angular velocity at the first key, rad/s, world frame.
    pub fn start_velocity(&self) -> Option<DVec3> {
        self.start_velocity
    }

    /// The given angular velocity at the last key, rad/s, world frame.
    pub fn end_velocity(&self) -> Option<DVec3> {
        self.end_velocity
    }
}

/// Kochanek–Bartels tension, continuity and bias of a key (each in `[−1, 1]`; all zero gives
/// the ordinary tangent). See [`Knots`](crate::tangent::Knots) for how they shape the tangents on S³.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Tcb {
    /// Tension `t`: 1 stops at the key, −1 doubles the tangent.
    pub tension: f64,
    /// Continuity `c`: non-zero makes the incoming and outgoing tangents differ (a corner).
    pub continuity: f64,
    /// Bias `b`: positive leans the tangent towards the incoming chord, negative the outgoing.
    pub bias: f64,
}

impl Tcb {
    /// All zero: the ordinary tangent.
    pub const ZERO: Tcb = Tcb {
        tension: 0.0,
        continuity: 0.0,
        bias: 0.0,
    };

    /// Whether all three are zero.
    pub fn is_zero(&self) -> bool {
        *self == Tcb::ZERO
    }

    /// Whether all three are finite and within `[−1, 1]`.
    pub fn is_valid(&self) -> bool {
        [self.tension, self.continuity, self.bias]
            .iter()
            .all(|x| x.is_finite() && x.abs() <= 1.0)
    }

    /// Kochanek & Bartels' weights `((a_in, b_in), (a_out, b_out))` of the incoming chord `L⁻`
    /// and the outgoing chord `L⁺` in the tangent arriving at the key (their source derivative)
    /// and the one leaving it (their destination derivative):
    /// `a_in = (1−t)(1+b)(1−c)/2`, `b_in = (1−t)(1−b)(1+c)/2`, `a_out = (1−t)(1+b)(1+c)/2`,
    /// `b_out = (1−t)(1−b)(1−c)/2` (all ½ for zero). So `c = −1` makes each segment leave and
    /// arrive along its own chord (box corners), as in VTK, Gamebryo and 3ds Max.
    pub fn weights(&self) -> ((f64, f64), (f64, f64)) {
        let (t, c, b) = (self.tension, self.continuity, self.bias);
        let k = (1.0 - t) * 0.5;
        (
            (k * (1.0 + b) * (1.0 - c), k * (1.0 - b) * (1.0 + c)),
            (k * (1.0 + b) * (1.0 + c), k * (1.0 - b) * (1.0 - c)),
        )
    }
}

impl From<TrackError> for InputError {
    fn from(e: TrackError) -> InputError {
        InputError::new(e.to_string())
    }
}

impl From<TrackError> for Error {
    fn from(e: TrackError) -> Error {
        Error::Input(e.into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quats(n: usize) -> Vec<DQuat> {
        (0..n).map(|i| DQuat::from_rotation_y(i as f64)).collect()
    }

    #[test]
    fn refuses_bad_times_with_typed_errors() {
        let new = |t: &[f64]| Track::new(t.to_vec(), quats(t.len()));
        assert_eq!(new(&[0.0]), Err(TrackError::TooFewKeys { found: 1 }));
        assert_eq!(new(&[]), Err(TrackError::TooFewKeys { found: 0 }));
        // One key is said on purpose.
        let c = Track::constant(0.5, DQuat::IDENTITY).unwrap();
        assert_eq!((c.len(), c.span()), (1, (0.5, 0.5)));
        assert!(matches!(
            Track::constant(f64::NAN, DQuat::IDENTITY),
            Err(TrackError::NonFiniteTime { .. })
        ));
        assert!(matches!(
            new(&[0.0, f64::NAN]),
            Err(TrackError::NonFiniteTime { index: 1, .. })
        ));
        assert_eq!(
            new(&[f64::NEG_INFINITY, 1.0]),
            Err(TrackError::NonFiniteTime {
                index: 0,
                time: f64::NEG_INFINITY
            })
        );
        assert_eq!(
            new(&[0.0, 1.0, 1.0]),
            Err(TrackError::NotIncreasing {
                index: 2,
                time: 1.0,
                previous: 1.0
            })
        );
        assert_eq!(
            new(&[0.0, 1.0, 1.0 + 4e-13]),
            Err(TrackError::TooClose {
                index: 2,
                time: 1.0 + 4e-13,
                previous: 1.0
            })
        );
        assert!(new(&[0.0, 1e-12]).is_ok());
        assert_eq!(
            Track::new(vec![0.0, 1.0], quats(3)),
            Err(TrackError::LengthMismatch {
                times: 2,
                rotations: 3
            })
        );
    }

    #[test]
    fn refuses_non_unit_rotations() {
        let mut q = quats(3);
        q[1] *= 2.0;
        assert!(matches!(
            Track::new(vec![0.0, 1.0, 2.0], q),
            Err(TrackError::NotUnit { index: 1, .. })
        ));
        let q = vec![DQuat::IDENTITY, DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0)];
        assert!(matches!(
            Track::new(vec![0.0, 1.0], q),
            Err(TrackError::NotUnit { index: 1, .. })
        ));
    }

    #[test]
    fn messages_name_the_numbers() {
        let e = Track::new(vec![0.0, 1.0, 0.5], quats(3)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "expected times strictly increasing within a track, found 0.5 s after 1 s"
        );
        assert_eq!(e.index(), Some(2));
    }
}
