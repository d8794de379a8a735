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
//! - With `--path euler` the blend's log is the branch of `log(C₂ C₁⁻¹)` nearest its part of the
//!   chord, `L − u·w_iΔ − (1 − u)·w_{i+1}Δ` (the 1-D difference `C₂ − C₁`), so a spin keeps its
//!   turns even where the two arcs are a full turn apart (frames computed one at a time).

use super::blend4::{self, Block4, Pending, geodesic4, params4, steps4};
use super::{Blend, Segment};
use crate::rotation::arc::{Arc, ArcSteps};
use crate::rotation::quat::{exp, geodesic, log_near};
use crate::tangent::Knots;
use glam::{DQuat, DVec3};

/// One Hermite segment.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Hermite {
    c1: Arc,
    c2: Arc,
    chord: f64,
    blend: Blend,
    spin: Option<Spin>,
}

/// `--path euler`: the segment's chord `L` and its end tangents `w_sΔ`, `w_{s+1}Δ` (world frame),
/// whose 1-D difference `L − u·w_sΔ − (1 − u)·w_{s+1}Δ` picks the branch of the blend's log.
#[derive(Debug, Clone, Copy)]
struct Spin {
    chord: DVec3,
    start: DVec3,
    end: DVec3,
}

impl Spin {
    /// The blend at `u` between the arcs' points `a` and `b`, weight `f`.
    #[inline]
    fn blend(&self, a: DQuat, b: DQuat, u: f64, f: f64) -> DQuat {
        let target = self.chord - self.start * u - self.end * (1.0 - u);
        exp(log_near(b * a.conjugate(), target) * f) * a
    }
}

/// Hermite in-betweens: both arcs by forward differences, the blends four frames at a time
/// (`blend4.rs`).
#[derive(Debug, Clone)]
pub(crate) struct HermiteFrames {
    c1: ArcSteps,
    c2: ArcSteps,
    u0: f64,
    du: f64,
    j: f64,
    blend: Blend,
    block: Block4,
    spin: Option<Spin>,
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
            spin,
        } = self;
        if let Some(spin) = spin {
            let u = *u0 + *j * *du;
            *j += 1.0;
            let (a, b) = (c1.next_point(), c2.next_point());
            return Some(spin.blend(a, b, u, blend.f(u)));
        }
        Some(block.next(|| {
            let (a, b) = (steps4(c1), steps4(c2));
            let f = params4(*u0, *du, *j, |u| blend.f(u));
            *j += 4.0;
            geodesic4(a, b, f).to_quats()
        }))
    }
}

/// A hermite segment's arcs as lanes ([`crate::Curve::rotations`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct HermiteLanes {
    c1: super::blend4::ArcLanes,
    c2: super::blend4::ArcLanes,
    blend: Blend,
}

impl Hermite {
    /// The segment as lanes (`C₁` starts at `q_i`, `C₂` ends at `q_{i+1}`); `None` with
    /// `--path euler`, whose blend picks a branch of a log per point.
    pub(crate) fn lanes(&self) -> Option<HermiteLanes> {
        self.spin.is_none().then(|| HermiteLanes {
            c1: super::blend4::ArcLanes::starting(&self.c1),
            c2: super::blend4::ArcLanes::ending(&self.c2),
            blend: self.blend,
        })
    }
}

impl super::blend4::Lanes4 for HermiteLanes {
    #[inline]
    fn eval4(&self, u: wide::f64x4) -> super::blend4::Quat4 {
        let f = super::blend4::map4(u, |u| self.blend.f(u));
        geodesic4(self.c1.eval4(u), self.c2.eval4(u), f)
    }
}

impl Segment for Hermite {
    type Frames = HermiteFrames;
    type Pending = Pending<2>;

    fn gather(&self, u0: f64, du: f64, n: usize) -> Option<[Pending<2>; 3]> {
        // `--path euler` blends point by point (`Spin::blend`), not in lanes.
        let blend = self.blend;
        self.spin
            .is_none()
            .then(|| blend4::gather([&self.c1, &self.c2], u0, du, n, |u| blend.f(u)))
    }

    fn finish4(lanes: &[Pending<2>; 4]) -> [DQuat; 4] {
        blend4::finish_one(lanes)
    }

    fn new(keys: &Knots, s: usize, blend: Blend) -> Self {
        Hermite {
            c1: Arc::leaving(keys.quats[s], keys.tangent(s, s)),
            c2: Arc::arriving(keys.quats[s + 1], keys.tangent(s + 1, s)),
            chord: keys.chord_length(s),
            blend,
            spin: keys.spins().then(|| Spin {
                chord: keys.chord(s),
                start: keys.w[s] * keys.delta(s),
                end: keys.w_in[s + 1] * keys.delta(s),
            }),
        }
    }

    fn eval(&self, u: f64) -> DQuat {
        let (a, b, f) = (self.c1.eval(u), self.c2.eval(u), self.blend.f(u));
        match &self.spin {
            Some(spin) => spin.blend(a, b, u, f),
            None => geodesic(a, b, f),
        }
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
            spin: self.spin,
        }
    }

    fn blend_bound(&self) -> f64 {
        match self.spin {
            // Always sampled: the hazard is a tie between two branches, not an antipode.
            Some(_) => f64::INFINITY,
            None => self.c1.span() + self.c2.span() + self.chord,
        }
    }

    fn blend_gap(&self, u: f64) -> f64 {
        let (a, b) = (self.c1.eval(u), self.c2.eval(u));
        match &self.spin {
            // How far the branch taken is from half a turn off its target (0: a tie, where the
            // blend could jump to the other branch).
            Some(spin) => {
                let target = spin.chord - spin.start * u - spin.end * (1.0 - u);
                let x = log_near(b * a.conjugate(), target);
                (std::f64::consts::PI - (x - target).length()).max(0.0)
            }
            None => (a + b).length(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::*;
    use crate::tangent::{EndConditions, Ends};
    use glam::DVec3;

    #[test]
    fn gathered_frames_are_the_frames_bits() {
        check_gathered::<2, Hermite>(&sample_keys(), Blend::Cubic);
        check_gathered::<2, Hermite>(&sample_keys(), Blend::Quadratic);
    }

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
