//! [`Played`]: a joint's keys as an FBX player plays the curves written for them
//! ([`super::write`]): each channel — the angle about X, about Y, about Z in degrees, and each
//! coordinate of a translation — a float32 value at each key, interpolated linearly on its own
//! between the keys around a time and held beyond the first and last (as ufbx evaluates linear
//! keys), the three angles then composed in the joint's order. What `reduce -o x.fbx` verifies
//! its keys by.

use super::write::{TICKS_PER_SECOND, curve_degrees};
use glam::{DQuat, DVec3};
use inbetween::rotation::EulerSeq;

/// One joint's curves as written: key ticks, float32 angles (degrees about X, Y, Z) and
/// positions.
#[derive(Debug, Clone)]
pub struct Played {
    seq: EulerSeq,
    ticks: Vec<i64>,
    angles: Vec<[f32; 3]>,
    positions: Option<Vec<[f32; 3]>>,
}

impl Played {
    /// The curves of keys at `ticks` (increasing, at least one) with `rotations` (and
    /// `positions`) in the intrinsic sequence `seq`, as [`super::write`] writes them.
    pub fn new(
        seq: EulerSeq,
        ticks: Vec<i64>,
        rotations: &[DQuat],
        positions: Option<&[DVec3]>,
    ) -> Played {
        let f32s = |v: [f64; 3]| v.map(|x| x as f32);
        Played {
            seq,
            ticks,
            angles: curve_degrees(seq, rotations)
                .into_iter()
                .map(f32s)
                .collect(),
            positions: positions.map(|p| p.iter().map(|v| f32s(v.to_array())).collect()),
        }
    }

    /// The segment of time `t` (seconds): the index of the key at or before it and the fraction
    /// of the way to the next (0 before the first key and from the last on).
    fn segment(&self, t: f64) -> (usize, f64) {
        let tick = t * TICKS_PER_SECOND as f64;
        let n = self.ticks.len();
        let i = self.ticks.partition_point(|&k| (k as f64) <= tick);
        if i == 0 {
            return (0, 0.0);
        }
        if i == n {
            return (n - 1, 0.0);
        }
        let (a, b) = (self.ticks[i - 1] as f64, self.ticks[i] as f64);
        (i - 1, (tick - a) / (b - a))
    }

    fn lerp(v: &[[f32; 3]], (i, u): (usize, f64)) -> [f64; 3] {
        let a = v[i].map(f64::from);
        if u == 0.0 {
            return a;
        }
        let b = v[i + 1].map(f64::from);
        [0, 1, 2].map(|c| a[c] + (b[c] - a[c]) * u)
    }

    /// The rotation the curves play at `t` (seconds).
    pub fn rotation(&self, t: f64) -> DQuat {
        let xyz = Played::lerp(&self.angles, self.segment(t));
        let angles = self
            .seq
            .as_str()
            .bytes()
            .map(|c| xyz[usize::from(c.to_ascii_uppercase() - b'X')].to_radians());
        let [a, b, c]: [f64; 3] = angles.collect::<Vec<_>>().try_into().unwrap_or([0.0; 3]);
        self.seq.to_quat([a, b, c])
    }

    /// The position the curves play at `t` (seconds), for curves with positions.
    pub fn position(&self, t: f64) -> Option<DVec3> {
        let p = self.positions.as_ref()?;
        Some(DVec3::from_array(Played::lerp(p, self.segment(t))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_channel_is_linear_between_keys_and_held_beyond() {
        // A spin about Y from 0° to 270° over one second (three keys, the last at 270° after
        // 170°: continuous, not -90°), in ZXY.
        let seq = EulerSeq::parse("ZXY").unwrap();
        let rot = |deg: f64| DQuat::from_rotation_y(deg.to_radians());
        let k = TICKS_PER_SECOND;
        let played = Played::new(
            seq,
            vec![0, k / 2, k],
            &[rot(0.0), rot(170.0), rot(270.0)],
            Some(&[DVec3::ZERO, DVec3::X, DVec3::new(3.0, 0.0, 0.0)]),
        );
        // Per channel: 85° at a quarter, 220° at three quarters (never through 0°).
        let at = |t: f64, deg: f64| played.rotation(t).angle_between(rot(deg));
        assert!(at(0.25, 85.0) < 1e-6);
        assert!(at(0.75, 220.0) < 1e-6);
        assert!(at(-1.0, 0.0) < 1e-9 && at(2.0, 270.0) < 1e-6);
        let p = played.position(0.75).unwrap();
        assert!((p - DVec3::new(2.0, 0.0, 0.0)).length() < 1e-9);
    }
}
