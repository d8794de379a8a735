//! `bezier`: cubic spherical Bézier curve by de Casteljau's construction with slerp (Shoemake
//! 1985), control points from the tangents (docs/spec.md §4.4), first-level arcs by forward differences.
//!
//! ```text
//! p₀ = q_i,  p₁ = exp(w_i/3)·q_i,  p₂ = exp(−w_{i+1}/3)·q_{i+1},  p₃ = q_{i+1}   (w = V q⁻¹)
//! r_k(u) = slerp(p_k, p_{k+1}, u)          k = 0, 1, 2   (fixed arcs: forward differences)
//! s_k(u) = slerp(r_k(u), r_{k+1}(u), u)    k = 0, 1
//! Q(u)   = slerp(s₀(u), s₁(u), u)
//! ```
//! The arcs `p₀→p₁` and `p₂→p₃` are built from the tangent itself (the arc leaving `q_i` along
//! `V_i` for a third of its length), which is the same arc whenever `‖w‖/3 ≤ π` and keeps
//! `Q'(0) = V_i` exactly even for tangents of several turns. With `--path euler` the middle leg
//! is the branch of `log(p₂ p₁⁻¹)` nearest `L_i − (w_i + w_{i+1})Δ_i/3` (the chord less the outer
//! legs, `w` per second), so a spin keeps its turns.
//!
//! - Interpolation: every key. Tangency: `Q'(0) = V_i`, `Q'(1) = V_{i+1}`.
//! - Continuity: C¹ at keys, C^∞ inside.
//! - Cost per frame: three forward-difference steps and three geodesic blends.

use super::blend4::{
    self, ArcLanes, Block4, Lanes4, Pending, Quat4, geodesic4, params4, point4, steps4, weight4,
};
use super::{Blend, Segment};
use crate::rotation::arc::{Arc, ArcSteps};
use crate::rotation::quat::geodesic;
use crate::tangent::Knots;
use glam::DQuat;
use wide::f64x4;

mod lanes;

pub(crate) use lanes::Bezier4;

/// One Bézier segment.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bezier {
    r0: Arc,
    r1: Arc,
    r2: Arc,
}

/// Bézier in-betweens: the three first-level arcs by forward differences, the three blends four
/// frames at a time (`blend4.rs`).
#[derive(Debug, Clone)]
pub(crate) struct BezierFrames {
    r0: ArcSteps,
    r1: ArcSteps,
    r2: ArcSteps,
    u0: f64,
    du: f64,
    j: f64,
    block: Block4,
}

/// The last two levels of de Casteljau's construction for four frames: the lanes' blends of
/// the first-level arcs' points `a`, `b`, `c` at `u`.
#[inline]
fn casteljau4(a: Quat4, b: Quat4, c: Quat4, u: f64x4) -> Quat4 {
    // With AVX a lane group is one register, and the two middle blends side by side
    // (`geodesics4`) give the processor two chains to overlap; with SSE2 alone it is two, and
    // side by side they spill: one after the other there. The same bits either way.
    #[cfg(target_feature = "avx")]
    {
        let [s0, s1] = super::blend4::geodesics4([(a, b, u), (b, c, u)]);
        geodesic4(s0, s1, u)
    }
    #[cfg(not(target_feature = "avx"))]
    geodesic4(geodesic4(a, b, u), geodesic4(b, c, u), u)
}

#[inline]
fn casteljau(a: DQuat, b: DQuat, c: DQuat, u: f64) -> DQuat {
    geodesic(geodesic(a, b, u), geodesic(b, c, u), u)
}

impl Iterator for BezierFrames {
    type Item = DQuat;

    #[inline]
    fn next(&mut self) -> Option<DQuat> {
        let BezierFrames {
            r0,
            r1,
            r2,
            u0,
            du,
            j,
            block,
        } = self;
        Some(block.next(|| {
            let (a, b, c) = (steps4(r0), steps4(r1), steps4(r2));
            let u = params4(*u0, *du, *j, |u| u);
            *j += 4.0;
            casteljau4(a, b, c, u).to_quats()
        }))
    }
}

/// A Bézier segment's arcs as lanes ([`crate::Curve::rotations`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct BezierLanes([ArcLanes; 3]);

impl Bezier {
    /// The segment as lanes: `r0` and `r1` start at their first point, `r2` ends at `q_{i+1}`.
    pub(crate) fn lanes(&self) -> BezierLanes {
        BezierLanes([
            ArcLanes::starting(&self.r0),
            ArcLanes::starting(&self.r1),
            ArcLanes::ending(&self.r2),
        ])
    }
}

impl Lanes4 for BezierLanes {
    #[inline]
    fn eval4(&self, u: f64x4) -> Quat4 {
        let [r0, r1, r2] = &self.0;
        let (a, b, c) = (r0.eval4(u), r1.eval4(u), r2.eval4(u));
        casteljau4(a, b, c, u)
    }
}

impl Segment for Bezier {
    type Frames = BezierFrames;
    type Pending = Pending<3>;

    fn gather(&self, u0: f64, du: f64, n: usize) -> Option<[Pending<3>; 3]> {
        Some(blend4::gather(
            [&self.r0, &self.r1, &self.r2],
            u0,
            du,
            n,
            |u| u,
        ))
    }

    fn direct(keys: &Knots) -> bool {
        !keys.spins()
    }

    fn direct4(keys: &Knots, _blend: Blend, s: [usize; 4], u: [f64; 4]) -> ([DQuat; 4], [f64; 4]) {
        let four = Bezier4::new(keys, s);
        (four.eval(f64x4::new(u)), four.blend_bounds())
    }

    fn finish4(lanes: &[Pending<3>; 4]) -> [DQuat; 4] {
        let point = |k| point4(lanes, k);
        casteljau4(point(0), point(1), point(2), weight4(lanes)).to_quats()
    }

    fn new(keys: &Knots, s: usize, _blend: Blend) -> Self {
        if !keys.spins() {
            // Built as every segment of a track is, in lanes (`lanes.rs`): the same bits.
            return Bezier4::new(keys, [s; 4]).lane(0);
        }
        let r0 = Arc::leaving(keys.quats[s], keys.tangent(s, s) / 3.0);
        let r2 = Arc::arriving(keys.quats[s + 1], keys.tangent(s + 1, s) / 3.0);
        // The middle leg stands in for the chord less the two outer legs.
        let target = keys.chord(s) - (keys.w[s] + keys.w_in[s + 1]) * (keys.delta(s) / 3.0);
        let r1 = Arc::near(r0.eval(1.0), r2.eval(0.0), target);
        Bezier { r0, r1, r2 }
    }

    fn eval(&self, u: f64) -> DQuat {
        casteljau(self.r0.eval(u), self.r1.eval(u), self.r2.eval(u), u)
    }

    fn frames(&self, u0: f64, du: f64) -> BezierFrames {
        BezierFrames {
            r0: self.r0.steps(u0, du),
            r1: self.r1.steps(u0, du),
            r2: self.r2.steps(u0, du),
            u0,
            du,
            j: 0.0,
            block: Block4::default(),
        }
    }

    fn blend_bound(&self) -> f64 {
        self.r0.span() + self.r1.span() + self.r2.span()
    }

    fn blend_gap(&self, u: f64) -> f64 {
        let (a, b, c) = (self.r0.eval(u), self.r1.eval(u), self.r2.eval(u));
        let (s0, s1) = (geodesic(a, b, u), geodesic(b, c, u));
        (a + b)
            .length()
            .min((b + c).length())
            .min((s0 + s1).length())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::*;

    #[test]
    fn keys_and_forward_differences() {
        check_segment::<Bezier>(&sample_keys(), Blend::Cubic);
    }

    #[test]
    fn gathered_frames_are_the_frames_bits() {
        check_gathered::<3, Bezier>(&sample_keys(), Blend::Cubic);
    }

    #[test]
    fn end_tangents_equal_v() {
        let k = sample_keys();
        for s in 0..k.segments() {
            let seg = Bezier::new(&k, s, Blend::Cubic);
            assert!((deriv(&seg, 0.0) - k.tangent(s, s)).length() < 1e-8);
            assert!((deriv(&seg, 1.0) - k.tangent(s + 1, s)).length() < 1e-8);
        }
    }
}
