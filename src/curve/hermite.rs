//! `hermite`: Nam & Kim's Hermite curve, two great arcs blended on S³ (Nam & Kim 1996, §2; the
//! forward-difference generation of §3; full reference in docs/spec.md, References).
//!
//! With segment-scaled tangents `V_i`, `V_{i+1}` (docs/spec.md §4.1), `θ₁ = ‖V_i‖`, `θ₂ = ‖V_{i+1}‖`:
//!
//! ```text
//! C₁(u) = cos(θ₁u)·q_i + sin(θ₁u)·V̂_i                 leaves q_i with velocity V_i
//! C₂(u) = cos(θ₂(1−u))·q_{i+1} − sin(θ₂(1−u))·V̂_{i+1}  arrives at q_{i+1} with velocity V_{i+1}
//! Q(u)  = exp(f(u)·log(C₂(u) C₁(u)⁻¹))·C₁(u)           f(u) = 3u² − 2u³ (or the quadratic blend)
//! ```
//!
//! - Interpolation: every key. Tangency: `Q'(0) = V_i`, `Q'(1) = V_{i+1}` (since `f'(0) = f'(1) =
//!   0`), so the angular velocity at a key is the tangent estimate, the same from both sides.
//! - Continuity: C¹ at keys (in time: tangents scale with `Δ`), C^∞ inside for the cubic blend,
//!   C¹ inside for the quadratic one.
//! - Cost per frame: two forward-difference steps and one geodesic blend (one `atan2`, one
//!   `sqrt`, one `sin_cos`).
//! - Limitations: a blend whose two arcs come near antipodal (tangents beyond about half a turn
//!   per segment) is ill defined; the tool warns (docs/spec.md §4.3).

use super::arc::{Arc, ArcSteps};
use super::blend4::{Block4, geodesic4, params4, steps4};
use super::{Blend, Segment};
use crate::rotation::quat::geodesic;
use crate::tangent::Knots;
use glam::DQuat;

/// One Hermite segment.
#[derive(Debug, Clone, Copy)]
pub struct Hermite {
    c1: Arc,
    c2: Arc,
    chord: f64,
    blend: Blend,
}

/// Hermite in-betweens: both arcs by forward differences, the blends four frames at a time
/// (`blend4.rs`).
#[derive(Debug, Clone)]
pub struct HermiteFrames {
    c1: ArcSteps,
    c2: ArcSteps,
    u0: f64,
    du: f64,
    j: f64,
    blend: Blend,
    block: Block4,
}

impl Iterator for HermiteFrames {
    type Item = DQuat;

    #[inline]
    fn next(&mut self) -> Option<DQuat> {
        let HermiteFrames {
            c1,
            c2,
            u0,
            du,
            j,
            blend,
            block,
        } = self;
        Some(block.next(|| {
            let (a, b) = (steps4(c1), steps4(c2));
            let f = params4(*u0, *du, *j, |u| blend.f(u));
            *j += 4.0;
            geodesic4(a, b, f).to_quats()
        }))
    }
}

impl Segment for Hermite {
    type Frames = HermiteFrames;

    fn new(keys: &Knots, s: usize, blend: Blend) -> Self {
        Hermite {
            c1: Arc::leaving(keys.quats[s], keys.tangent(s, s)),
            c2: Arc::arriving(keys.quats[s + 1], keys.tangent(s + 1, s)),
            chord: keys.chord_length(s),
            blend,
        }
    }

    fn eval(&self, u: f64) -> DQuat {
        geodesic(self.c1.eval(u), self.c2.eval(u), self.blend.f(u))
    }

    fn frames(&self, u0: f64, du: f64) -> HermiteFrames {
        HermiteFrames {
            c1: self.c1.steps(u0, du),
            c2: self.c2.steps(u0, du),
            u0,
            du,
            j: 0.0,
            blend: self.blend,
            block: Block4::default(),
        }
    }

    fn blend_bound(&self) -> f64 {
        self.c1.span() + self.c2.span() + self.chord
    }

    fn blend_gap(&self, u: f64) -> f64 {
        (self.c1.eval(u) + self.c2.eval(u)).length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::*;
    use crate::tangent::{EndConditions, Ends};
    use glam::DVec3;

    #[test]
    fn keys_and_forward_differences() {
        check_segment::<Hermite>(&sample_keys(), Blend::Cubic);
        check_segment::<Hermite>(&sample_keys(), Blend::Quadratic);
    }

    #[test]
    fn end_tangents_equal_v() {
        let k = sample_keys();
        for s in 0..k.segments() {
            for blend in [Blend::Cubic, Blend::Quadratic] {
                let seg = Hermite::new(&k, s, blend);
                let d0 = deriv(&seg, 0.0);
                let d1 = deriv(&seg, 1.0);
                assert!((d0 - k.tangent(s, s)).length() < 1e-8, "{s} start: {d0}");
                assert!((d1 - k.tangent(s + 1, s)).length() < 1e-8, "{s} end: {d1}");
            }
        }
    }

    #[test]
    fn rest_ends_start_and_stop() {
        let q = [DQuat::IDENTITY, DQuat::from_axis_angle(DVec3::Y, 1.0)];
        let ends = EndConditions {
            ends: Ends::Rest,
            ..Default::default()
        };
        let k = keys(&[0.0, 1.0], &q, ends);
        let seg = Hermite::new(&k, 0, Blend::Cubic);
        assert!(deriv(&seg, 0.0).length() < 1e-8);
        assert!(deriv(&seg, 1.0).length() < 1e-8);
        assert!(super::super::antipode_gap(&seg).is_none());
    }

    #[test]
    fn blend_functions() {
        for b in [Blend::Cubic, Blend::Quadratic] {
            assert_eq!(b.f(0.0), 0.0);
            assert_eq!(b.f(1.0), 1.0);
            assert!((b.f(0.5) - 0.5).abs() < 1e-15);
        }
    }
}
