//! Euler spins (`--path euler`, docs/spec.md §4.3): the chord of a segment whose keys were given
//! as Euler angles, keeping the turns the angles make.
//!
//! Between keys `e_s` and `e_{s+1}` (radians, as written), the angles interpolated linearly,
//! `e(σ) = e_s + σ(e_{s+1} − e_s)`, describe a motion `R(σ)` with world-frame angular velocity
//! `ω(σ)` per unit `σ`. Its swept angle `A = ∫₀¹ ‖ω‖ dσ` and net rotation vector `W = ∫₀¹ ω dσ`
//! (composite Simpson, [`PANELS`] panels) pick the chord among the rotation vectors that carry
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
pub const PANELS: usize = 256;

/// The unit vector of an axis letter.
fn axis(letter: u8) -> DVec3 {
    match letter.to_ascii_lowercase() {
        b'x' => DVec3::X,
        b'y' => DVec3::Y,
        _ => DVec3::Z,
    }
}

/// The world-frame angular velocity of `e(σ)` at angles `e` moving at `de` per unit `σ`.
///
/// Intrinsic `ABC` is `R = R_A(a)·R_B(b)·R_C(c)`: `ω = a′·A + b′·R_A(a)·B + c′·R_A(a)·R_B(b)·C`.
/// Extrinsic `abc` is `R = R_C(c)·R_B(b)·R_A(a)`: `ω = c′·C + b′·R_C(c)·B + a′·R_C(c)·R_B(b)·A`.
fn omega(seq: EulerSeq, e: [f64; 3], de: [f64; 3]) -> DVec3 {
    let l = seq.as_str().as_bytes();
    let (u, intrinsic) = (
        [axis(l[0]), axis(l[1]), axis(l[2])],
        l[0].is_ascii_uppercase(),
    );
    // The factors in product order (left to right) with their angles and rates.
    let order = if intrinsic { [0, 1, 2] } else { [2, 1, 0] };
    let mut frame = DQuat::IDENTITY;
    let mut w = DVec3::ZERO;
    for i in order {
        w += frame * u[i] * de[i];
        frame *= DQuat::from_axis_angle(u[i], e[i]);
    }
    w
}

/// `(A, W)`: the angle swept (rad) and the net rotation vector of the linear Euler motion from
/// `e0` to `e1` (radians) in `seq`.
pub fn sweep(seq: EulerSeq, e0: DVec3, e1: DVec3) -> (f64, DVec3) {
    let de = (e1 - e0).to_array();
    let (mut a, mut w) = (0.0, DVec3::ZERO);
    for j in 0..=PANELS {
        let sigma = j as f64 / PANELS as f64;
        let weight = match j {
            0 => 1.0,
            _ if j == PANELS => 1.0,
            _ if j % 2 == 1 => 4.0,
            _ => 2.0,
        };
        let o = omega(seq, (e0 + (e1 - e0) * sigma).to_array(), de);
        a += weight * o.length();
        w += o * weight;
    }
    let h = 1.0 / (3.0 * PANELS as f64);
    (a * h, w * h)
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
pub fn chord(seq: EulerSeq, e0: DVec3, e1: DVec3, q0: DQuat, q1: DQuat) -> DVec3 {
    let (swept, net) = sweep(seq, e0, e1);
    let mut d = q1 * q0.conjugate();
    if d.w < 0.0 {
        d = -d;
    }
    let v = DVec3::new(d.x, d.y, d.z);
    let (n, phi) = if v.length() < NO_AXIS {
        let w = net.length();
        if w == 0.0 {
            return DVec3::ZERO;
        }
        (net / w, 0.0)
    } else {
        let l = log(d);
        let half = l.length();
        (l / half, (2.0 * half).min(PI))
    };
    if n.dot(net) >= 0.0 {
        let k = ((swept - phi) / TAU).round().max(0.0);
        n * (phi + TAU * k)
    } else {
        let k = ((swept + phi) / TAU).round().max(1.0);
        -n * (TAU * k - phi)
    }
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
}
