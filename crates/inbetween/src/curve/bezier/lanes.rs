//! Four Bézier segments at once, as SIMD lanes: their first-level arcs built from the keys
//! (`p₁ = exp(w_i/3)·q_i`, `p₂ = exp(−w_{i+1}/3)·q_{i+1}`, the middle leg between them) and their
//! frames evaluated directly, one segment per lane (`wide::f64x4`; `sin_cos` and `atan2` are
//! Agner Fog's vector-class-library polynomials, within 2 ulp: [`sin_cos4`], [`atan2_upper4`]).
//!
//! Every Bézier segment is built here — [`Bezier::new`](super::Bezier) is lane 0 of four copies
//! of itself — so a segment's arcs are the same bits whichever segments share its block (a
//! lane's operations never read another lane). A resample to a lower rate, where most segments
//! hold one frame, builds and evaluates its segments four at a time without a scalar `sin`,
//! `cos` or `atan2` ([`crate::bake`](mod@crate::bake)).

use super::super::blend4::Quat4;
use super::{Bezier, casteljau4};
use crate::rotation::arc::{Arc, TINY};
use crate::rotation::quat4::{atan2_upper4, sin_cos4};
use crate::tangent::Knots;
use glam::DQuat;
use wide::f64x4;

/// Four great arcs `C(u) = cos(α + βu)·p + sin(α + βu)·e` as lanes ([`Arc`]).
#[derive(Debug, Clone, Copy)]
struct Arc4 {
    p: Quat4,
    e: Quat4,
    alpha: f64x4,
    beta: f64x4,
}

impl Arc4 {
    /// `C(u[i])` for the four lanes: [`Arc::eval`]'s expression, its `sin_cos` in lanes.
    #[inline]
    fn eval(&self, u: f64x4) -> Quat4 {
        let (s, c) = sin_cos4(self.alpha + self.beta * u);
        self.p.combine(c, self.e, s)
    }

    /// Lane `i` as an [`Arc`].
    fn lane(&self, i: usize) -> Arc {
        Arc::from_parts(
            self.p.to_quats()[i],
            self.e.to_quats()[i],
            self.alpha.to_array()[i],
            self.beta.to_array()[i],
        )
    }
}

/// Four Bézier segments' arcs `r0`, `r1`, `r2` as lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bezier4 {
    r: [Arc4; 3],
}

/// `V/3` for the keys `i[l]` with tangents `w[i[l]]` over segments of `delta[l]` seconds, at
/// the keys' rotations `q`: [`Knots::tangent`]`/3` in lanes, operation for operation (glam's
/// product of `(0, w·Δ)` by `q`, then a division by 3), so the same bits.
#[inline]
fn third_of_tangent(w: &[glam::DVec3], i: [usize; 4], delta: f64x4, q: Quat4) -> Quat4 {
    let (x0, y0, z0) = (
        f64x4::new(i.map(|i| w[i].x)) * delta,
        f64x4::new(i.map(|i| w[i].y)) * delta,
        f64x4::new(i.map(|i| w[i].z)) * delta,
    );
    let v = Quat4 {
        w: f64x4::ZERO,
        x: x0,
        y: y0,
        z: z0,
    };
    v.mul(q).over(f64x4::splat(3.0))
}

/// `f(lane)` for each lane of an `f64x4`'s mask test, as booleans.
#[inline]
fn lanes_where(v: f64x4, f: impl Fn(f64) -> bool) -> [bool; 4] {
    v.to_array().map(f)
}

impl Bezier4 {
    /// Segments `s[i]` of `keys` (a track whose chords are the logs between its keys: not a
    /// `--path euler` spin, whose middle legs [`Bezier::new`](super::Bezier) takes apart).
    pub(crate) fn new(keys: &Knots, s: [usize; 4]) -> Bezier4 {
        let q0 = Quat4::from_quats(&s.map(|s| keys.quats[s]));
        let q3 = Quat4::from_quats(&s.map(|s| keys.quats[s + 1]));
        // The outer legs: leaving q_i along V_i/3, arriving at q_{i+1} along V_{i+1}/3.
        let delta = f64x4::new(s.map(|s| keys.delta(s)));
        let v0 = third_of_tangent(&keys.w, s, delta, q0);
        let v3 = third_of_tangent(&keys.w_in, s.map(|s| s + 1), delta, q3);
        let (t0, t3) = (v0.dot(v0).sqrt(), v3.dot(v3).sqrt());
        let (e0, e2) = (v0.over(t0), v3.over(t3));
        let (s0, c0) = sin_cos4(t0);
        let (s3, c3) = sin_cos4(-t3);
        let mut p1 = q0.combine(c0, e0, s0);
        let mut p2 = q3.combine(c3, e2, s3);
        let mut r0 = Arc4 {
            p: q0,
            e: e0,
            alpha: f64x4::ZERO,
            beta: t0,
        };
        let mut r2 = Arc4 {
            p: q3,
            e: e2,
            alpha: -t3,
            beta: t3,
        };
        // A leg shorter than TINY is the point itself (`Arc::point`): lane by lane, where the
        // test in lanes finds one.
        let tiny = f64x4::splat(TINY);
        if (t0.simd_lt(tiny) | t3.simd_lt(tiny)).any() {
            let (still0, still3) = (lanes_where(t0, |t| t < TINY), lanes_where(t3, |t| t < TINY));
            let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
            let (q0s, q3s) = (q0.to_quats(), q3.to_quats());
            let (mut p1s, mut p2s) = (p1.to_quats(), p2.to_quats());
            let (mut e0s, mut e2s) = (e0.to_quats(), e2.to_quats());
            let (mut b0, mut b2) = (t0.to_array(), t3.to_array());
            let mut a2 = (-t3).to_array();
            for l in 0..4 {
                if still0[l] {
                    (p1s[l], e0s[l], b0[l]) = (q0s[l], zero, 0.0);
                }
                if still3[l] {
                    (p2s[l], e2s[l], b2[l], a2[l]) = (q3s[l], zero, 0.0, 0.0);
                }
            }
            (p1, p2) = (Quat4::from_quats(&p1s), Quat4::from_quats(&p2s));
            (r0.e, r0.beta) = (Quat4::from_quats(&e0s), f64x4::new(b0));
            (r2.e, r2.alpha, r2.beta) = (Quat4::from_quats(&e2s), f64x4::new(a2), f64x4::new(b2));
        }
        // The middle leg: the geodesic from p₁ to p₂ (`Arc::between`).
        let (a, b) = (p1, p2);
        let d = a.dot(b);
        let perp = b.less(d, a);
        let len = perp.dot(perp).sqrt();
        let mut r1 = Arc4 {
            p: a,
            e: perp.over(len),
            alpha: f64x4::ZERO,
            beta: atan2_upper4(len, d),
        };
        if (len.simd_lt(tiny) | len.is_nan()).any() {
            // Identical or antipodal legs' ends: the scalar `Arc::between`, lane by lane.
            let flat = lanes_where(len, |v| v.is_nan() || v < TINY);
            let (p1, p2) = (p1.to_quats(), p2.to_quats());
            let (mut e1, mut b1) = (r1.e.to_quats(), r1.beta.to_array());
            for l in (0..4).filter(|&l| flat[l]) {
                let arc = Arc::between(p1[l], p2[l]);
                let (_, e, _, beta) = arc.parts();
                (e1[l], b1[l]) = (e, beta);
            }
            (r1.e, r1.beta) = (Quat4::from_quats(&e1), f64x4::new(b1));
        }
        Bezier4 { r: [r0, r1, r2] }
    }

    /// Lane `i` as a segment.
    pub(crate) fn lane(&self, i: usize) -> Bezier {
        let [r0, r1, r2] = self.r.map(|r| r.lane(i));
        Bezier { r0, r1, r2 }
    }

    /// Each lane's [`crate::curve::Segment::blend_bound`]: the sum of its arcs' spans.
    pub(crate) fn blend_bounds(&self) -> [f64; 4] {
        let [b0, b1, b2] = self.r.map(|r| r.beta.abs());
        (b0 + b1 + b2).to_array()
    }

    /// Lane `i`'s segment at `u[i]`: de Casteljau's construction, every arc and blend in lanes.
    #[inline]
    pub(crate) fn eval(&self, u: f64x4) -> [DQuat; 4] {
        let [r0, r1, r2] = &self.r;
        casteljau4(r0.eval(u), r1.eval(u), r2.eval(u), u).to_quats()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::sample_keys;
    use crate::curve::{Blend, Segment};
    use crate::tangent::{EndConditions, PathMode};
    use crate::track::Track;
    use glam::DVec3;

    fn bits(q: DQuat) -> [u64; 4] {
        q.to_array().map(f64::to_bits)
    }

    fn arc_bits(a: &Arc) -> Vec<u64> {
        let (p, e, alpha, beta) = a.parts();
        let mut v: Vec<u64> = [p, e].iter().flat_map(|q| bits(*q)).collect();
        v.extend([alpha.to_bits(), beta.to_bits()]);
        v
    }

    /// A smooth stretch, a hold of eight keys (zero tangents: the legs are points, and the
    /// middle leg joins a point to itself) and long steps.
    fn varied_keys() -> Knots {
        let mut quats = Vec::new();
        for k in 0..24 {
            let v = match k {
                8..=15 => DVec3::ZERO,
                16.. => DVec3::new(0.0, 0.9 * (k - 15) as f64, 0.1),
                _ => DVec3::new(0.3 * (0.7 * k as f64).sin(), 0.05 * k as f64, 0.2),
            };
            quats.push(crate::rotation::quat::exp(v));
        }
        let times = (0..quats.len()).map(|k| 0.04 * k as f64).collect();
        let track = Track::new(times, quats).expect("a valid track");
        Knots::new(&track, PathMode::Shortest, EndConditions::default())
    }

    /// The outer legs' velocities are `Knots::tangent / 3` to the bit.
    #[test]
    fn tangents_in_lanes_are_the_knots_bits() {
        let k = varied_keys();
        for s in 0..k.segments() - 3 {
            let segs = [s, s + 1, s + 2, s + 3];
            let q0 = Quat4::from_quats(&segs.map(|s| k.quats[s]));
            let q3 = Quat4::from_quats(&segs.map(|s| k.quats[s + 1]));
            let delta = f64x4::new(segs.map(|s| k.delta(s)));
            let v0 = third_of_tangent(&k.w, segs, delta, q0).to_quats();
            let v3 = third_of_tangent(&k.w_in, segs.map(|s| s + 1), delta, q3).to_quats();
            for (l, &s) in segs.iter().enumerate() {
                assert_eq!(bits(v0[l]), bits(k.tangent(s, s) / 3.0));
                assert_eq!(bits(v3[l]), bits(k.tangent(s + 1, s) / 3.0));
            }
        }
    }

    /// Each lane is its segment's bits whatever segments share its block: its arcs are those of
    /// `Bezier::new`, its blend bound that segment's, its frame the same as the segment alone in
    /// a block and within a few ulp of the scalar evaluation.
    #[test]
    fn a_lane_is_its_segment_whatever_shares_its_block() {
        let (mut points, mut flat) = (0, 0);
        // Ends turning 3·10¹⁰ rad/s: legs of about 5·10⁹ rad, beyond the lanes' sin_cos range.
        let spin = Track::new(vec![0.0, 1.0], vec![DQuat::IDENTITY; 2]).expect("a track");
        let ends = EndConditions {
            start: Some(DVec3::new(3e10, 1.0, 0.0)),
            end: Some(DVec3::new(0.0, 3e10, 2.0)),
            ..EndConditions::default()
        };
        let fast = Knots::new(&spin, PathMode::AsGiven, ends);
        assert!(Bezier::new(&fast, 0, Blend::Cubic).r0.span() > 1e9);
        for k in [sample_keys(), varied_keys(), fast] {
            let n = k.segments();
            for s in 0..n {
                let seg = Bezier::new(&k, s, Blend::Cubic);
                points += usize::from(seg.r0.span() == 0.0);
                flat += usize::from(seg.r1.span() == 0.0);
                for (i, &u) in [0.0, 0.21, 0.5, 0.97, 1.0].iter().enumerate() {
                    let l = (s + i) % 4;
                    let mut segs = [(s + 1) % n, (s + 5) % n, (s + 2) % n, (s + 7) % n];
                    let mut us = [0.3, 0.6, 0.9, 0.1];
                    (segs[l], us[l]) = (s, u);
                    let (q, bound) = Bezier::direct4(&k, Blend::Cubic, segs, us);
                    let (alone, _) = Bezier::direct4(&k, Blend::Cubic, [s; 4], [u; 4]);
                    assert_eq!(bits(q[l]), bits(alone[0]), "segment {s} at {u}");
                    assert_eq!(bound[l].to_bits(), seg.blend_bound().to_bits());
                    let lane = Bezier4::new(&k, segs).lane(l);
                    for (a, b) in [(lane.r0, seg.r0), (lane.r1, seg.r1), (lane.r2, seg.r2)] {
                        assert_eq!(arc_bits(&a), arc_bits(&b), "segment {s}");
                    }
                    let off = (q[l] - seg.eval(u)).length();
                    assert!(off < 4e-15, "segment {s} at {u}: {off:e}");
                }
            }
        }
        assert!(
            points > 0 && flat > 0,
            "{points} point legs, {flat} flat middle legs"
        );
    }
}
