//! The logarithms a track's tangents are built from, four at a time as SIMD lanes.
//!
//! Every chord `L_s = log(q_{s+1} q_s⁻¹)` of a track ([`chords`]) and, for the `spline` windows,
//! every `log(q_{s+2} q_s⁻¹)` and `log(q_{s+3} q_s⁻¹)` ([`far`]) is taken by [`log4`]: the
//! formula of [`crate::rotation::quat::log`], `v·(atan2(|v|, w)/|v|)`, with the lanes' `atan2`
//! ([`atan2_upper4`]: the vector class library's polynomial, within 2 ulp of libm's, and libm's
//! on the edges the log meets: `w < 0`, `w = ±0`, `s = 0`) in place of the scalar one. The quaternion products feeding them are glam's, operation for operation
//! (the same bits). Keys go four to a block; the last block is filled by repeating the last key,
//! and no lane reads another's, so a log's bits depend only on its two keys — never on where
//! they fall in a block or on how long the track is.

use super::columns::{Columns, V4, load};
use crate::rotation::quat4::{Quat4, atan2_upper4};
use glam::{DQuat, DVec3};
use wide::f64x4;

/// `log(q)` of four unit quaternions: [`crate::rotation::quat::log`]'s formula with the lanes'
/// `atan2` — `v·(atan2(s, w)/s)`, `s = |v|` (glam's length); where `s == 0`, zero, or `(π, 0, 0)`
/// when `w < 0`, as the scalar log.
#[inline]
pub(super) fn log4(q: Quat4) -> V4 {
    let s = (q.x * q.x + q.y * q.y + q.z * q.z).sqrt();
    let k = atan2_upper4(s, q.w) / s;
    let out = V4 {
        x: q.x * k,
        y: q.y * k,
        z: q.z * k,
    };
    let axisless = s.simd_eq(f64x4::ZERO);
    if !axisless.any() {
        return out;
    }
    let half_turn = q.w.simd_lt(f64x4::ZERO).select(f64x4::PI, f64x4::ZERO);
    out.or_where(
        axisless,
        V4 {
            x: half_turn,
            ..V4::ZERO
        },
    )
}

/// `b·a⁻¹` for unit quaternions in lanes: glam's `b * a.conjugate()`, operation for operation.
#[inline]
fn ratio(b: Quat4, a: Quat4) -> Quat4 {
    b.mul(a.conjugate())
}

/// A track's keys as columns, so that four consecutive ones load as lanes; past the last key
/// the last key again, so that every block of four from a key of the track is there.
pub(super) struct Keys {
    w: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    /// The number of keys.
    n: usize,
}

impl Keys {
    /// The columns of `quats` (at least one key), padded past `n.div_ceil(4)·4 + 3`.
    pub(super) fn of(quats: &[DQuat]) -> Keys {
        let n = quats.len();
        let padded = n.div_ceil(4) * 4 + 4;
        let last = quats[n - 1];
        // Exact-size iterators: `collect` writes without a test per value (nor a memset first).
        let column = |f: fn(&DQuat) -> f64| -> Vec<f64> {
            quats
                .iter()
                .map(f)
                .chain(std::iter::repeat_n(f(&last), padded - n))
                .collect()
        };
        Keys {
            w: column(|q| q.w),
            x: column(|q| q.x),
            y: column(|q| q.y),
            z: column(|q| q.z),
            n,
        }
    }

    /// The block of keys `from‥from+6` (`from ≤ n.div_ceil(4)·4 − 4`): each column cut once,
    /// so that loads from it need no bounds test of their own.
    #[inline]
    fn block(&self, from: usize) -> [&[f64]; 4] {
        let to = from + 7;
        [
            &self.w[from..to],
            &self.x[from..to],
            &self.y[from..to],
            &self.z[from..to],
        ]
    }
}

/// Keys `k‥k+3` of a block ([`Keys::block`]) as lanes (`k ≤ 3`).
#[inline]
fn four([w, x, y, z]: [&[f64]; 4], k: usize) -> Quat4 {
    Quat4 {
        w: load(w, k),
        x: load(x, k),
        y: load(y, k),
        z: load(z, k),
    }
}

/// The chords `log(q_{s+1} q_s⁻¹)` of every segment `s` of `keys` (by [`log4`]).
pub(super) fn chords(keys: &Keys) -> Vec<DVec3> {
    let segments = keys.n - 1;
    let mut out = Vec::with_capacity(segments + 3);
    for s in (0..segments).step_by(4) {
        let block = keys.block(s);
        let l = log4(ratio(four(block, 1), four(block, 0)));
        out.extend_from_slice(&l.lanes());
    }
    out.truncate(segments);
    out
}

/// `[log(q_{s+2} q_s⁻¹), log(q_{s+3} q_s⁻¹)]` for every key `s` of `keys` (by [`log4`]), as
/// columns padded to a multiple of four; zero where key `s + 2` or `s + 3` does not exist.
pub(super) fn far(keys: &Keys) -> [Columns; 2] {
    let n = keys.n;
    let padded = n.div_ceil(4) * 4;
    let mut out = [
        Columns::with_capacity(padded),
        Columns::with_capacity(padded),
    ];
    for s in (0..n).step_by(4) {
        let block = keys.block(s);
        let from = four(block, 0);
        for (k, c) in out.iter_mut().enumerate() {
            c.push4(log4(ratio(four(block, k + 2), from)));
        }
    }
    for (k, c) in out.iter_mut().enumerate() {
        for s in n.saturating_sub(k + 2)..n {
            c.set_zero(s);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rotation::quat::log;

    /// A deterministic stream of numbers in [0, 1).
    fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Quaternions of every kind the lanes must take: random unit ones, near `1` and `−1`, `±1`
    /// exactly, tiny vector parts, `w = 0`.
    fn cases() -> Vec<DQuat> {
        let mut state = 7;
        let mut q = vec![
            DQuat::IDENTITY,
            -DQuat::IDENTITY,
            DQuat::from_xyzw(1.0, 0.0, 0.0, 0.0),
            DQuat::from_xyzw(0.0, -1.0, 0.0, 0.0),
            DQuat::from_xyzw(0.0, 0.0, 1e-300, -1.0),
            DQuat::from_xyzw(-5e-324, 0.0, 0.0, 1.0),
        ];
        for _ in 0..4000 {
            let mut r = || 2.0 * uniform(&mut state) - 1.0;
            let v = DVec3::new(r(), r(), r());
            let w = r();
            let scale = [1.0, 1e-3, 1e-8, 1e-12, 1e-17][(((r() + 1.0) * 2.5) as usize).min(4)];
            let v = v * scale;
            let w = if w < 0.0 { -1.0 } else { 1.0 } * (1.0 - v.length_squared()).max(0.0).sqrt();
            let w = if scale == 1.0 { r() } else { w };
            q.push(DQuat::from_xyzw(v.x, v.y, v.z, w).normalize());
        }
        q
    }

    /// The lanes' log is the scalar log within 4e-16 relative (1e-15 absolute), and equal to it
    /// where the vector part is zero; a lane's value does not depend on its neighbours.
    #[test]
    fn the_lanes_log_is_the_scalar_log() {
        let q = cases();
        let mut worst: f64 = 0.0;
        for (b, block) in q.chunks(4).enumerate() {
            let four: [DQuat; 4] = std::array::from_fn(|l| block[l.min(block.len() - 1)]);
            let got = log4(Quat4::from_quats(&four)).lanes();
            for (l, &q) in four.iter().enumerate() {
                let want = log(q);
                let err = (got[l] - want).length();
                worst = worst.max(err / want.length().max(1e-300));
                assert!(
                    err <= 4e-16 * want.length() || err <= 1e-15,
                    "block {b} lane {l}: {q} {} vs {}",
                    got[l],
                    want
                );
                if q.xyz() == DVec3::ZERO {
                    assert_eq!(got[l], want, "{q}");
                }
                // The same quaternion alone in a block of identities: the same bits.
                let mut alone = [DQuat::IDENTITY; 4];
                alone[3 - l] = q;
                let one = log4(Quat4::from_quats(&alone)).lanes()[3 - l];
                assert_eq!(
                    one.to_array().map(f64::to_bits),
                    got[l].to_array().map(f64::to_bits)
                );
            }
        }
        println!("worst relative error {worst:e}");
    }

    /// Chords and far logs of a track and of its prefixes agree bit for bit on the keys they
    /// share, whatever the prefix's length modulo four.
    #[test]
    fn logs_do_not_depend_on_what_follows() {
        let mut state = 11;
        let quats: Vec<DQuat> = (0..23)
            .map(|_| {
                let mut r = || 2.0 * uniform(&mut state) - 1.0;
                DQuat::from_xyzw(r(), r(), r(), r()).normalize()
            })
            .collect();
        let bits = |v: DVec3| v.to_array().map(f64::to_bits);
        let keys = Keys::of(&quats);
        let (all, far_all) = (chords(&keys), far(&keys));
        for n in 1..quats.len() {
            let prefix = Keys::of(&quats[..n]);
            let (c, f) = (chords(&prefix), far(&prefix));
            assert_eq!(c.len(), n - 1);
            for s in 0..n - 1 {
                assert_eq!(bits(c[s]), bits(all[s]), "prefix {n} chord {s}");
            }
            for s in 0..n {
                for k in 0..2 {
                    if s + k + 2 < n {
                        assert_eq!(bits(f[k].get(s)), bits(far_all[k].get(s)), "{n} {s} {k}");
                    } else {
                        assert_eq!(f[k].get(s), DVec3::ZERO);
                    }
                }
            }
        }
    }

    /// The spline tangents of a track and of its prefixes agree bit for bit at every key whose
    /// window (three keys each side) the prefix holds, and so does the first key's chord tangent:
    /// no value depends on where its keys fall in a block of four.
    #[test]
    fn tangents_do_not_depend_on_what_follows() {
        use crate::tangent::{EndConditions, Knots, PathMode, TangentRule};
        use crate::track::{Tcb, Track};
        let times: Vec<f64> = (0..41)
            .map(|k| k as f64 / 30.0 + 1e-3 * (k % 3) as f64)
            .collect();
        let quats: Vec<DQuat> = times
            .iter()
            .map(|&t| DQuat::from_rotation_z(2.0 * t) * DQuat::from_rotation_x((3.0 * t).sin()))
            .collect();
        let knots = |n: usize| {
            let track = Track::new(times[..n].to_vec(), quats[..n].to_vec()).expect("a track");
            let ends = EndConditions::default();
            Knots::shaped(
                &track,
                PathMode::Shortest,
                ends,
                Tcb::ZERO,
                TangentRule::Spline,
            )
        };
        let bits = |v: DVec3| v.to_array().map(f64::to_bits);
        let all = knots(times.len());
        for n in 8..times.len() {
            let prefix = knots(n);
            for i in 0..n - 3 {
                assert_eq!(bits(prefix.w()[i]), bits(all.w()[i]), "prefix {n} key {i}");
            }
        }
    }
}
