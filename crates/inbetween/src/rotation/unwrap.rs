//! Continuous ("unwrapped") Euler angles along a track.
//!
//! A rotation has many Euler triples in a sequence: the two solutions of the sequence, each angle
//! plus any multiple of 2π. [`EulerSeq::from_quat`] picks one in scipy's canonical ranges, so a
//! spin about one axis wraps at ±180° and a path through the middle angle's limit flips to the
//! other solution. The rule here picks, for each rotation of a track, the triple nearest the
//! previous one:
//!
//! * the track starts from a given start triple (or, without one, from the first rotation's
//!   canonical triple);
//! * each following triple is, among all triples of the same rotation, the one nearest the
//!   previous triple (Euclidean distance of the three angles, in radians; in degrees it is the
//!   same choice);
//! * at gimbal lock only the sum (or difference) of the first and third angle is determined; the
//!   pair is the point of that family nearest the previous pair, which moves both angles by the
//!   same amount (see `nearest_triple`);
//! * every triple rebuilds its rotation to 1e-12 rad (while the angles stay below ~1e3 rad in
//!   magnitude, beyond which the spacing of f64 itself approaches that budget).
//!
//! The two solutions, from a triple (a, b, c) of a sequence whose letters are axes i, j, k:
//!
//! ```text
//! Tait–Bryan (i, j, k all different):  (a + π, π − b, c + π)
//! proper Euler (k = i):                (a + π,   − b, c + π)
//! ```
//!
//! because a half turn about one axis reverses the other two axes: `R_i(π) R_j(β) = R_j(−β)
//! R_i(π)`, and `R_i(π) R_k(π) = R_j(π)` for three different axes (read the products from the
//! right for extrinsic sequences).

use super::euler::EulerSeq;
use glam::DQuat;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Distance (radians) of the middle angle from its singular value within which a rotation is
/// treated as gimbal-locked by `nearest_triple`.
///
/// Snapping the middle angle to the singular value moves the rotation by exactly that distance,
/// so the tolerance must stay below the 1e-12 rad rebuild budget; 1e-13 leaves a factor of ten.
/// It sits well above the noise of the distance itself (the middle angle comes from `atan2` of two
/// norms and is accurate to a few 1e-16 rad everywhere), so rotations that are a lock up to
/// accumulated rounding are caught: a product such as `Rz(a)·Ry(π/2)·Rx(c)` computed in f64
/// lands at a distance of 0 to a few 1e-15, where the regular split of a and c is rounding noise
/// (measured 0.01–0.3 rad). Beyond the tolerance the regular formula is exact for the rotation,
/// and the split carries rounding noise of order 1e-16/d rad at a distance d (measured ≤ 1e-4
/// rad just outside, ≤ 1e-7 rad beyond 1e-9). The test is on the middle angle because it is the
/// well-conditioned quantity; `cos b` or `sin b` would do as well, but scipy's 1e-7 would break
/// the rebuild budget by five orders of magnitude.
pub(crate) const GIMBAL_LOCK_TOL: f64 = 1e-13;

/// The Euler triple of `q` in `seq` nearest `prev` (all angles in radians, in the order of the
/// letters): among both solutions of the sequence, each angle plus any multiple of 2π, the one at
/// the least Euclidean distance from `prev`. `q` is a unit quaternion (its sign does not matter);
/// `prev` is any finite triple, in or out of the canonical ranges.
///
/// Ties (`prev` equally far from both solutions) go to the solution of the canonical triple; an
/// angle exactly half a turn from the previous one goes to the representative [`f64::round`]
/// picks (half-way rounds away from zero in turns).
///
/// **Gimbal lock.** When the middle angle is within `GIMBAL_LOCK_TOL` of its singular value
/// (±π/2 for Tait–Bryan, 0 or π for proper Euler), the rotation fixes only the middle angle and
/// `a + σc` modulo 2π, with σ = ±1 set by the sequence and the singularity. The middle angle is
/// then exactly the singular value (the representative nearest `prev[1]`), and (a, c) is the point
/// of the lines `a + σc ≡ a₀ + σc₀ (mod 2π)` nearest `(prev[0], prev[2])`: with `r` the smallest
/// correction that brings `prev[0] + σ·prev[2]` onto a line, `a = prev[0] + r/2` and
/// `c = prev[2] + σr/2` — the correction split equally, which is the Euclidean nearest point, so
/// the rule needs no extra convention. The triple differs from `q` by the distance of the middle
/// angle from the singular value (≤ 1e-13 rad).
///
/// ```
/// use inbetween::EulerSeq;
/// use inbetween::rotation::unwrap::EulerUnwrap;
/// use glam::DQuat;
///
/// let zyx = EulerSeq::parse("ZYX")?;
/// let nearest_triple = |seq, q, prev| EulerUnwrap::with_start(seq, prev).next(q);
/// let deg = |t: [f64; 3]| t.map(f64::to_degrees);
/// // 185° about z: canonically −175°, but next to 170° it is 185°.
/// let q = DQuat::from_rotation_z(185f64.to_radians());
/// let t = nearest_triple(zyx, q, [170f64.to_radians(), 0.0, 0.0]);
/// assert!((deg(t)[0] - 185.0).abs() < 1e-12 && t[1] == 0.0 && t[2] == 0.0);
/// // Past the middle angle's limit: 100° about y is (0°, 100°, 0°) next to (0°, 95°, 0°)
/// // (canonically (180°, 80°, 180°), the other solution).
/// let q = DQuat::from_rotation_y(100f64.to_radians());
/// let t = deg(nearest_triple(zyx, q, [0.0, 95f64.to_radians(), 0.0]));
/// assert!(t[0].abs() < 1e-12 && (t[1] - 100.0).abs() < 1e-12 && t[2].abs() < 1e-12);
/// // Gimbal lock: at 90° pitch ZYX fixes only a − c; the correction is split equally.
/// let q = zyx.to_quat([0.5, std::f64::consts::FRAC_PI_2, 0.2]); // a − c = 0.3
/// let t = nearest_triple(zyx, q, [0.4, 1.5, 0.2]); // prev a − c = 0.2: r = 0.1
/// assert!((t[0] - 0.45).abs() < 1e-12 && t[1] == std::f64::consts::FRAC_PI_2);
/// assert!((t[2] - 0.15).abs() < 1e-12);
/// # Ok::<(), inbetween::InputError>(())
/// ```
pub(crate) fn nearest_triple(seq: EulerSeq, q: DQuat, prev: [f64; 3]) -> [f64; 3] {
    nearest_with_tol(seq, q, prev, GIMBAL_LOCK_TOL)
}

/// `nearest_triple` with the gimbal-lock tolerance as a parameter (the tests compare with −∞:
/// never locked).
fn nearest_with_tol(seq: EulerSeq, q: DQuat, prev: [f64; 3], lock_tol: f64) -> [f64; 3] {
    let canonical = seq.from_quat(q);
    let shape = Shape::of(seq);
    if let Some((b0, sigma)) = shape.lock(canonical[1], lock_tol) {
        // a + σc is well conditioned even where the split between a and c is not.
        let fixed = canonical[0] + sigma * canonical[2];
        let s = prev[0] + sigma * prev[2];
        let r = nearest_rep(fixed, s) - s;
        return [
            prev[0] + 0.5 * r,
            nearest_rep(b0, prev[1]),
            prev[2] + sigma * 0.5 * r,
        ];
    }
    let near = |t: [f64; 3]| [0, 1, 2].map(|i| nearest_rep(t[i], prev[i]));
    let (first, second) = (near(canonical), near(shape.other_solution(canonical)));
    if dist2(second, prev) < dist2(first, prev) {
        second
    } else {
        first
    }
}

/// Continuous Euler angles along a track: each [`next`](EulerUnwrap::next) returns the triple of
/// its rotation nearest the previous one (`nearest_triple`); the first is nearest the start
/// triple when one is given, else the canonical triple ([`EulerSeq::from_quat`]).
///
/// ```
/// use inbetween::EulerSeq;
/// use inbetween::rotation::unwrap::EulerUnwrap;
/// use glam::DQuat;
///
/// let mut spin = EulerUnwrap::new(EulerSeq::parse("ZYX")?);
/// let yaw: Vec<f64> = (0..=8)
///     .map(|k| spin.next(DQuat::from_rotation_z((k as f64 * 100.0).to_radians()))[0].to_degrees())
///     .collect();
/// for (k, y) in yaw.iter().enumerate() {
///     assert!((y - k as f64 * 100.0).abs() < 1e-9); // 0, 100, …, 800: no wrap at ±180°
/// }
/// // A start triple: the first key's own angles survive when they describe its rotation.
/// let zyx = EulerSeq::parse("ZYX")?;
/// let start = [400f64.to_radians(), 0.1, -0.2];
/// let mut track = EulerUnwrap::with_start(zyx, start);
/// let t = track.next(zyx.to_quat(start));
/// assert!((0..3).all(|i| (t[i] - start[i]).abs() < 1e-12));
/// # Ok::<(), inbetween::InputError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerUnwrap {
    seq: EulerSeq,
    prev: Option<[f64; 3]>,
}

impl EulerUnwrap {
    /// A track in `seq` that starts from its first rotation's canonical triple.
    pub fn new(seq: EulerSeq) -> EulerUnwrap {
        EulerUnwrap { seq, prev: None }
    }

    /// A track in `seq` whose first triple is the one nearest `start` (radians, finite).
    pub fn with_start(seq: EulerSeq, start: [f64; 3]) -> EulerUnwrap {
        debug_assert!(start.iter().all(|x| x.is_finite()), "start {start:?}");
        EulerUnwrap {
            seq,
            prev: Some(start),
        }
    }

    /// The triple (radians) of `q` under the rule, which becomes the previous triple.
    pub fn next(&mut self, q: DQuat) -> [f64; 3] {
        let t = match self.prev {
            Some(prev) => nearest_triple(self.seq, q, prev),
            None => self.seq.from_quat(q),
        };
        self.prev = Some(t);
        t
    }

    /// The sequence.
    pub fn seq(&self) -> EulerSeq {
        self.seq
    }

    /// The triple the next rotation will be nearest: the last one returned, else the start
    /// triple, else `None`.
    pub fn prev(&self) -> Option<[f64; 3]> {
        self.prev
    }
}

/// `x` plus the multiple of 2π that brings it nearest `target`.
fn nearest_rep(x: f64, target: f64) -> f64 {
    x + TAU * ((target - x) / TAU).round()
}

fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum()
}

/// What the unwrapping needs to know of a sequence.
#[derive(Debug, Clone, Copy)]
struct Shape {
    /// First and third letter name the same axis.
    proper: bool,
    /// Tait–Bryan only: at b = +π/2 the rotation fixes `a + parity·c`.
    parity: f64,
}

impl Shape {
    fn of(seq: EulerSeq) -> Shape {
        let l = seq.as_str().as_bytes();
        let axis = |c: u8| (c.to_ascii_lowercase() - b'x') as i32;
        let (i, j) = (axis(l[0]), axis(l[1]));
        let cyclic = (j - i).rem_euclid(3) == 1;
        let intrinsic = l[0].is_ascii_uppercase();
        // Intrinsic i-j-k at b = π/2: R_j(π/2) carries axis k onto +i when (i, j, k) is cyclic,
        // so R_i(a) R_j(π/2) R_k(c) = R_i(a + c) R_j(π/2); onto −i otherwise. Extrinsic is the
        // product read from the right, which swaps the roles and the sign.
        Shape {
            proper: l[0].eq_ignore_ascii_case(&l[2]),
            parity: if cyclic == intrinsic { 1.0 } else { -1.0 },
        }
    }

    /// The other solution of the sequence for a triple (same rotation).
    fn other_solution(self, [a, b, c]: [f64; 3]) -> [f64; 3] {
        let b2 = if self.proper { -b } else { PI - b };
        [a + PI, b2, c + PI]
    }

    /// For a canonical middle angle within `tol` of a singular value: that value and σ, such
    /// that the rotation fixes `a + σc`.
    fn lock(self, b: f64, tol: f64) -> Option<(f64, f64)> {
        if self.proper {
            // b ∈ [−π, π]; singular at 0 (R_i(a + c)) and ±π (R_i(a − c)).
            if b.abs() <= tol {
                Some((0.0, 1.0))
            } else if PI - b.abs() <= tol {
                Some((PI, -1.0))
            } else {
                None
            }
        } else {
            // b ∈ [−π/2, π/2]; singular at ±π/2.
            (FRAC_PI_2 - b.abs() <= tol).then(|| {
                let b0 = FRAC_PI_2.copysign(b);
                (b0, self.parity * b0.signum())
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rotation::quat::rotation_angle_between as angle;

    const ROT_TOL: f64 = 1e-12;

    /// Deterministic pseudo-random numbers in [lo, hi) (xorshift64*).
    struct Rng(u64);
    impl Rng {
        fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let u = (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64;
            lo + (hi - lo) * u
        }
        fn triple(&mut self, r: f64) -> [f64; 3] {
            [0; 3].map(|_| self.uniform(-r, r))
        }
    }

    #[test]
    fn the_other_solution_is_the_same_rotation_in_all_24_sequences() {
        let mut rng = Rng(7);
        for seq in EulerSeq::all() {
            let shape = Shape::of(seq);
            for _ in 0..50 {
                let t = rng.triple(4.0);
                let other = shape.other_solution(t);
                let d = angle(seq.to_quat(t), seq.to_quat(other));
                assert!(d < ROT_TOL, "{} {t:?}: {d:e}", seq.as_str());
                // And it is a different triple modulo 2π (not a restatement).
                let same = (0..3).all(|i| (nearest_rep(other[i], t[i]) - t[i]).abs() < 1e-9);
                assert!(!same, "{} {t:?}", seq.as_str());
            }
        }
    }

    #[test]
    fn at_lock_the_rotation_fixes_a_plus_sigma_c_in_all_24_sequences() {
        let mut rng = Rng(11);
        for seq in EulerSeq::all() {
            let shape = Shape::of(seq);
            let singular: &[f64] = if shape.proper {
                &[0.0, PI, -PI]
            } else {
                &[FRAC_PI_2, -FRAC_PI_2]
            };
            for &b in singular {
                let (b0, sigma) = shape.lock(b, 0.0).expect("singular");
                assert_eq!(nearest_rep(b0, b), b);
                for _ in 0..20 {
                    let [a, _, c] = rng.triple(4.0);
                    let t = rng.uniform(-4.0, 4.0);
                    let q = seq.to_quat([a, b, c]);
                    let moved = seq.to_quat([a + t, b, c - sigma * t]);
                    assert!(
                        angle(q, moved) < ROT_TOL,
                        "{} b={b} σ={sigma}",
                        seq.as_str()
                    );
                    // The other sign is a different rotation: σ is not a free choice.
                    let wrong = seq.to_quat([a + t, b, c + sigma * t]);
                    if t.abs() > 0.1 && (2.0 * t).rem_euclid(TAU) > 0.1 {
                        assert!(angle(q, wrong) > 1e-3, "{} b={b}", seq.as_str());
                    }
                }
            }
        }
    }

    #[test]
    fn away_from_lock_is_not_locked() {
        let zyx = Shape::of(EulerSeq::parse("ZYX").unwrap());
        assert!(zyx.lock(FRAC_PI_2 - 1e-12, GIMBAL_LOCK_TOL).is_none());
        assert!(zyx.lock(FRAC_PI_2 - 1e-14, GIMBAL_LOCK_TOL).is_some());
        let zxz = Shape::of(EulerSeq::parse("zxz").unwrap());
        assert!(zxz.lock(1e-12, GIMBAL_LOCK_TOL).is_none());
        assert_eq!(zxz.lock(-PI, GIMBAL_LOCK_TOL), Some((PI, -1.0)));
    }

    #[test]
    fn every_triple_rebuilds_its_rotation_in_all_24_sequences() {
        let mut rng = Rng(3);
        for seq in EulerSeq::all() {
            for n in 0..200 {
                // A quarter of the rotations at gimbal lock, built from a triple.
                let q = if n % 4 == 0 {
                    let proper = Shape::of(seq).proper;
                    let b = match (proper, n % 8 == 0) {
                        (true, true) => 0.0,
                        (true, false) => PI,
                        (false, true) => FRAC_PI_2,
                        (false, false) => -FRAC_PI_2,
                    };
                    seq.to_quat([rng.uniform(-4.0, 4.0), b, rng.uniform(-4.0, 4.0)])
                } else {
                    seq.to_quat(rng.triple(4.0))
                };
                let prev = rng.triple(20.0);
                let t = nearest_triple(seq, q, prev);
                let d = angle(q, seq.to_quat(t));
                assert!(
                    d < ROT_TOL,
                    "{} {q} from {prev:?}: {t:?} off by {d:e}",
                    seq.as_str()
                );
            }
        }
    }

    /// ZYX through the lock at t = π/2: R = Rz(0.3t)·Ry(t)·Rx(0.2), t = kπ/200, with the lock
    /// tolerance given (−∞: never locked, the regular formula everywhere).
    fn through_lock(lock_tol: f64) -> Vec<[f64; 3]> {
        let zyx = EulerSeq::parse("ZYX").unwrap();
        let mut prev = zyx.from_quat(DQuat::from_rotation_x(0.2));
        let mut out = vec![prev];
        for k in 1..=200 {
            let t = k as f64 * PI / 200.0;
            let q = DQuat::from_rotation_z(0.3 * t)
                * DQuat::from_rotation_y(t)
                * DQuat::from_rotation_x(0.2);
            prev = nearest_with_tol(zyx, q, prev, lock_tol);
            assert!(angle(q, zyx.to_quat(prev)) < ROT_TOL, "t = {t}");
            out.push(prev);
        }
        out
    }

    #[test]
    fn angles_up_to_1e3_rad_still_rebuild() {
        // Far from zero the representatives are rounded to the f64 spacing there (1.1e-13 at
        // 1e3 rad); the budget holds up to about that (measured: 2.7e-13 at 1e3, 3.4e-12 at 1e4).
        let mut rng = Rng(5);
        for seq in EulerSeq::all() {
            for _ in 0..200 {
                let q = seq.to_quat(rng.triple(4.0));
                let prev = rng.triple(1e3);
                let t = nearest_triple(seq, q, prev);
                assert!(dist2(t, prev).sqrt() < 2.0 * PI, "{t:?} from {prev:?}");
                assert!(angle(q, seq.to_quat(t)) < ROT_TOL, "{t:?} from {prev:?}");
            }
        }
    }

    #[test]
    fn the_lock_rule_applies_at_a_rounded_lock() {
        // The sample at t = π/2 is a lock up to rounding: its canonical split is noise (a − c is
        // right, a and c are not). The rule puts it at the point of the lock line nearest the
        // previous sample (0.3(t − h), t − h, 0.2): a − c must grow by 0.3h, split equally.
        let h = PI / 200.0;
        let want = [0.3 * FRAC_PI_2 - 0.15 * h, FRAC_PI_2, 0.2 - 0.15 * h];
        let with = through_lock(GIMBAL_LOCK_TOL);
        assert!(dist2(with[100], want).sqrt() < 1e-12, "{:?}", with[100]);
        // Without the lock rule the split is whatever the rounding left (0.3 rad off here).
        let without = through_lock(f64::NEG_INFINITY);
        assert!(
            dist2(without[100], want).sqrt() > 1e-6,
            "{:?}",
            without[100]
        );
    }

    #[test]
    fn a_near_lock_is_snapped_only_within_the_tolerance() {
        // Tilt the lock sample by d about y: its rotation is (0.3t, π/2 + d, 0.2) exactly.
        let zyx = EulerSeq::parse("ZYX").unwrap();
        let (t, h) = (FRAC_PI_2, PI / 200.0);
        let prev = [0.3 * (t - h), t - h, 0.2];
        let lock_point = [0.3 * t - 0.15 * h, t, 0.2 - 0.15 * h];
        for d in [1e-15, 3e-14, 1e-13 * 0.9, 1e-13 * 1.1, 1e-12, 1e-9, 1e-6] {
            let q = DQuat::from_rotation_z(0.3 * t)
                * DQuat::from_rotation_y(t)
                * DQuat::from_rotation_y(d)
                * DQuat::from_rotation_x(0.2);
            let got = nearest_triple(zyx, q, prev);
            let err = angle(q, zyx.to_quat(got));
            if d < GIMBAL_LOCK_TOL {
                assert!(dist2(got, lock_point).sqrt() < 1e-12, "{d:e}: {got:?}");
                assert!(err <= d * 1.01 + 1e-15, "{d:e}: {err:e}");
            } else {
                // The regular formula: exact for the rotation, its split within rounding noise
                // of order 1e-16/d of the true one.
                let truth = [0.3 * t, t + d, 0.2];
                assert!(dist2(got, truth).sqrt() < 1e-14 / d, "{d:e}: {got:?}");
                assert!(err < 1e-15, "{d:e}: {err:e}");
            }
        }
    }

    #[test]
    fn the_track_starts_canonical_or_from_the_start_triple() {
        let zyx = EulerSeq::parse("ZYX").unwrap();
        let q = DQuat::from_rotation_z(3.0);
        let mut track = EulerUnwrap::new(zyx);
        assert_eq!(track.prev(), None);
        assert_eq!(track.next(q), zyx.from_quat(q));
        assert_eq!(track.prev(), Some(zyx.from_quat(q)));
        let mut track = EulerUnwrap::with_start(zyx, [3.0 - TAU, 0.0, 0.0]);
        assert!((track.next(q)[0] - (3.0 - TAU)).abs() < 1e-15);
        assert_eq!(track.seq(), zyx);
    }
}
