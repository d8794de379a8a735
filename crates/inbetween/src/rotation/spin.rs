//! Euler spins (`--path euler`, docs/spec.md §4.3): the chord of a segment whose keys were given
//! as Euler angles, keeping the turns the angles make.
//!
//! Between keys `e_s` and `e_{s+1}` (radians, as written), the angles interpolated linearly,
//! `e(σ) = e_s + σ(e_{s+1} − e_s)`, describe a motion `R(σ)` with world-frame angular velocity
//! `ω(σ)` per unit `σ`. Its swept angle `A = ∫₀¹ ‖ω‖ dσ` and net rotation vector `W = ∫₀¹ ω dσ`
//! (composite Simpson, `PANELS` panels) pick the chord among the rotation vectors that carry
//! key `s` to key `s+1`: the shortest rotation's axis `n` (angle `φ ∈ [0, π]`), signed to agree
//! with `W`, and the length `ψ` nearest `A` among those of that sign (`φ + 360°k` along `n`,
//! `360°k − φ` against it). The identity has no axis: `W`'s direction is taken. For a single-axis
//! spin (`ω` of constant direction) the chord is exact: `W = A·n`, and `ψ = A`.

use super::euler::EulerSeq;
use super::quat::{NO_AXIS, log};
use glam::{DQuat, DVec3};
use std::f64::consts::{PI, TAU};

/// Simpson panels of the sweep integrals (even). The integrals only choose among lengths 360°
/// apart (and, for the identity, give a direction), so a coarse rule is ample.
pub(crate) const PANELS: usize = 256;

/// The unit vector of an axis letter.
fn axis(letter: u8) -> DVec3 {
    match letter.to_ascii_lowercase() {
        b'x' => DVec3::X,
        b'y' => DVec3::Y,
        _ => DVec3::Z,
    }
}

/// A sequence's axes in product order (left to right), with the index of each one's angle:
/// intrinsic `ABC` is `R = R_A(a)·R_B(b)·R_C(c)`, extrinsic `abc` is `R = R_C(c)·R_B(b)·R_A(a)`.
fn factors(seq: EulerSeq) -> [(DVec3, usize); 3] {
    let l = seq.as_str().as_bytes();
    let u = [axis(l[0]), axis(l[1]), axis(l[2])];
    if l[0].is_ascii_uppercase() {
        [(u[0], 0), (u[1], 1), (u[2], 2)]
    } else {
        [(u[2], 2), (u[1], 1), (u[0], 0)]
    }
}

/// The world-frame angular velocity of `e(σ)` at angles `e` moving at `de` per unit `σ`, for
/// the sequence's [`factors`]: `ω = a′·A + b′·R_A(a)·B + c′·R_A(a)·R_B(b)·C` (intrinsic; the
/// extrinsic sequence in its product order).
fn omega_of(factors: &[(DVec3, usize); 3], e: [f64; 3], de: [f64; 3]) -> DVec3 {
    let mut frame = DQuat::IDENTITY;
    let mut w = DVec3::ZERO;
    for (k, &(u, i)) in factors.iter().enumerate() {
        w += frame * u * de[i];
        // The last factor turns no later axis.
        if k < 2 {
            frame *= DQuat::from_axis_angle(u, e[i]);
        }
    }
    w
}

/// [`omega_of`] for `seq`.
#[cfg(test)]
fn omega(seq: EulerSeq, e: [f64; 3], de: [f64; 3]) -> DVec3 {
    omega_of(&factors(seq), e, de)
}

/// `(A, W)`: the angle swept (rad) and the net rotation vector of the linear Euler motion from
/// `e0` to `e1` (radians) in `seq`.
pub(crate) fn sweep(seq: EulerSeq, e0: DVec3, e1: DVec3) -> (f64, DVec3) {
    sweep_with(seq, e0, e1, PANELS)
}

/// [`sweep`] by composite Simpson on `panels` panels (even).
fn sweep_with(seq: EulerSeq, e0: DVec3, e1: DVec3, panels: usize) -> (f64, DVec3) {
    let de = (e1 - e0).to_array();
    let factors = factors(seq);
    let (mut a, mut w) = (0.0, DVec3::ZERO);
    for j in 0..=panels {
        let sigma = j as f64 / panels as f64;
        let weight = match j {
            0 => 1.0,
            _ if j == panels => 1.0,
            _ if j % 2 == 1 => 4.0,
            _ => 2.0,
        };
        let o = omega_of(&factors, (e0 + (e1 - e0) * sigma).to_array(), de);
        a += weight * o.length();
        w += o * weight;
    }
    let h = 1.0 / (3.0 * panels as f64);
    (a * h, w * h)
}

/// Panels per quarter radian of angle change (`Σ|Δe_i|`) of the coarse rule [`chord`] tries
/// first. `‖ω‖ ≤ Σ|Δe_i|`, and the integrands' `k`-th derivatives in `σ` scale as
/// `(Σ|Δe_i|)^(k+1)`, so at this density Simpson's error bound `h⁴·max|f⁗|/180` is about 1.4e-6
/// of the angle swept whatever the motion's length, far inside [`SIGN_MARGIN`] (where `‖ω‖` has
/// a kink, at a gimbal-locked stop, the swept angle's error is at most about `h²·(Σ|Δe_i|)²` =
/// 0.016 rad, a quarter of [`TIE_MARGIN`]'s 0.063 rad).
pub(crate) const PANELS_PER_QUARTER_RADIAN: usize = 2;

/// How clear the coarse rule's sign must be: `|n·W|` above this fraction of the angle swept.
pub(crate) const SIGN_MARGIN: f64 = 1e-3;

/// How clear the coarse rule's length must be: the candidates' tie this many turns away.
pub(crate) const TIE_MARGIN: f64 = 1e-2;

/// The chord along `n` (the shortest rotation's axis, angle `phi`) that the sweep `(swept,
/// net)` picks, and whether the choice is clear by `margins` (sign, tie; see [`chord`]).
fn pick(n: DVec3, phi: f64, (swept, net): (f64, DVec3), margins: (f64, f64)) -> (DVec3, bool) {
    let tie = |x: f64| (x - x.floor() - 0.5).abs() > margins.1;
    let along = n.dot(net);
    let clear_sign = along.abs() > margins.0 * swept;
    if along >= 0.0 {
        let x = (swept - phi) / TAU;
        let k = x.round().max(0.0);
        (n * (phi + TAU * k), clear_sign && tie(x))
    } else {
        let x = (swept + phi) / TAU;
        let k = x.round().max(1.0);
        (-n * (TAU * k - phi), clear_sign && tie(x))
    }
}

/// The chord (a rotation vector, radians) from key rotation `q0` to `q1`, given as the Euler
/// angles `e0`, `e1` in `seq` (see the module documentation).
///
/// ```
/// use inbetween::EulerSeq;
/// use inbetween::rotation::spin::chord;
/// use glam::DVec3;
///
/// let zyx = EulerSeq::parse("ZYX")?;
/// let e = |z: f64| DVec3::new(z.to_radians(), 0.0, 0.0);
/// let c = chord(zyx, e(0.0), e(-450.0), zyx.to_quat([0.0; 3]), zyx.to_quat(e(-450.0).to_array()));
/// assert!((c - DVec3::new(0.0, 0.0, -450f64.to_radians())).length() < 1e-12);
/// # Ok::<(), inbetween::InputError>(())
/// ```
///
/// Between keys that differ, the sweep is first integrated on a coarse rule
/// (`PANELS_PER_QUARTER_RADIAN`, while that is fewer than `PANELS`); where its choice is
/// clear (`SIGN_MARGIN`, `TIE_MARGIN`) it is the `PANELS` rule's choice, and the chord the
/// same to the bit (the chord depends on the integrals only through the choice).
pub fn chord(seq: EulerSeq, e0: DVec3, e1: DVec3, q0: DQuat, q1: DQuat) -> DVec3 {
    let mut d = q1 * q0.conjugate();
    if d.w < 0.0 {
        d = -d;
    }
    let v = DVec3::new(d.x, d.y, d.z);
    if v.length() < NO_AXIS {
        if e0 == e1 {
            // No motion: ω = 0 throughout, so W = 0 and the chord is zero.
            return DVec3::ZERO;
        }
        // The identity has no axis: the net rotation's direction, from the full rule.
        let (swept, net) = sweep(seq, e0, e1);
        let w = net.length();
        if w == 0.0 {
            return DVec3::ZERO;
        }
        return pick(net / w, 0.0, (swept, net), (0.0, 0.0)).0;
    }
    let l = log(d);
    let half = l.length();
    let (n, phi) = (l / half, (2.0 * half).min(PI));
    let change = (e1 - e0).abs().element_sum();
    let quarters = (change / 0.25).ceil().max(1.0);
    if quarters * (PANELS_PER_QUARTER_RADIAN as f64) < PANELS as f64 {
        let panels = PANELS_PER_QUARTER_RADIAN * quarters as usize;
        let (c, clear) = pick(
            n,
            phi,
            sweep_with(seq, e0, e1, panels),
            (SIGN_MARGIN, TIE_MARGIN),
        );
        if clear {
            return c;
        }
    }
    pick(n, phi, sweep(seq, e0, e1), (0.0, 0.0)).0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seqs() -> Vec<EulerSeq> {
        EulerSeq::all()
    }

    /// ω against a central difference of the rotation, every sequence.
    #[test]
    fn omega_is_the_derivative_of_the_rotation() {
        let e = [0.4, -1.1, 2.3];
        let de = [0.7, 0.2, -1.3];
        for seq in seqs() {
            let h = 1e-6;
            let at = |s: f64| seq.to_quat([e[0] + s * de[0], e[1] + s * de[1], e[2] + s * de[2]]);
            let (a, b) = (at(-h), at(h));
            let b = if a.dot(b) < 0.0 { -b } else { b };
            let dq = (b - a) * (1.0 / (2.0 * h));
            let p = dq * at(0.0).conjugate();
            let fd = DVec3::new(p.x, p.y, p.z) * 2.0;
            let w = omega(seq, e, de);
            assert!((w - fd).length() < 1e-8, "{}: {w} vs {fd}", seq.as_str());
        }
    }

    #[test]
    fn single_axis_spins_are_exact() {
        for seq in seqs() {
            for deg in [270.0, 360.0, 720.0, -450.0, 30.0, -180.0, 1000.0] {
                for slot in 0..3 {
                    let mut e1 = [0.1, 0.0, -0.2];
                    let e0 = e1;
                    e1[slot] += f64::to_radians(deg);
                    let (e0, e1) = (DVec3::from_array(e0), DVec3::from_array(e1));
                    let c = chord(
                        seq,
                        e0,
                        e1,
                        seq.to_quat(e0.to_array()),
                        seq.to_quat(e1.to_array()),
                    );
                    let (swept, net) = sweep(seq, e0, e1);
                    assert!((c.length() - deg.to_radians().abs()).abs() < 1e-9, "{deg}");
                    assert!((swept - deg.to_radians().abs()).abs() < 1e-12);
                    assert!((c - net).length() < 1e-9, "{} {deg} {slot}", seq.as_str());
                }
            }
        }
    }

    #[test]
    fn chord_carries_key_to_key() {
        let zxy = EulerSeq::parse("zxy").unwrap();
        let (e0, e1) = (DVec3::new(0.3, 0.2, -0.1), DVec3::new(5.0, 1.0, 0.4));
        let (q0, q1) = (zxy.to_quat(e0.to_array()), zxy.to_quat(e1.to_array()));
        let c = chord(zxy, e0, e1, q0, q1);
        let q = DQuat::from_scaled_axis(c) * q0;
        assert!(q.dot(q1).abs() > 1.0 - 1e-15);
        let (swept, _) = sweep(zxy, e0, e1);
        assert!((c.length() - swept).abs() <= PI);
    }

    /// The coarse rule tried first for short motions chooses as the full rule: the chord is the
    /// same to the bit, for every sequence, on short motions, near gimbal lock, and on motions
    /// too long for the coarse rule.
    #[test]
    fn the_coarse_rule_gives_the_full_rules_chord() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut coarse = 0;
        for seq in seqs() {
            for case in 0..400 {
                let e0 = DVec3::new(next() * 3.0, next() * 1.5, next() * 3.0);
                let scale = [1e-6, 0.01, 0.05, 0.3, 0.5, 2.0, 4.0, 9.0][case % 8];
                let mut e1 = e0 + DVec3::new(next(), next(), next()) * scale;
                if case % 11 == 0 {
                    // No motion at all.
                    e1 = e0;
                } else if case % 5 == 0 {
                    // Near gimbal lock: the middle angle at a quarter turn.
                    e1.y = std::f64::consts::FRAC_PI_2 - 1e-9;
                }
                let (q0, q1) = (seq.to_quat(e0.to_array()), seq.to_quat(e1.to_array()));
                let got = chord(seq, e0, e1, q0, q1);
                let mut d = q1 * q0.conjugate();
                if d.w < 0.0 {
                    d = -d;
                }
                // The rule as it was: always the full integrals.
                let (swept, net) = sweep(seq, e0, e1);
                let full = if DVec3::new(d.x, d.y, d.z).length() < NO_AXIS {
                    let w = net.length();
                    if w == 0.0 {
                        DVec3::ZERO
                    } else {
                        pick(net / w, 0.0, (swept, net), (0.0, 0.0)).0
                    }
                } else {
                    let l = log(d);
                    let half = l.length();
                    let (n, phi) = (l / half, (2.0 * half).min(PI));
                    pick(n, phi, (swept, net), (0.0, 0.0)).0
                };
                assert_eq!(got, full, "{} {e0} {e1}", seq.as_str());
                coarse += usize::from((e1 - e0).abs().element_sum() <= 16.0);
            }
        }
        assert!(coarse > 24 * 300, "{coarse}");
    }
}
