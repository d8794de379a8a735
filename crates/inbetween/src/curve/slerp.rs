//! `slerp` (Shoemake 1985; Szeliski 2010, Algorithm 2.1; docs/spec.md, References): the great
//! arc between consecutive keys, `Q(u) = exp(u · log(q_{i+1} q_i⁻¹)) q_i` (with `--path euler`,
//! `exp(u·L_i) q_i` for the segment's chord `L_i`, which may turn more than once).
//!
//! - Interpolation: every key. Tangency: none imposed; the velocity is the chord's.
//! - Continuity: C⁰ at keys (the angular velocity jumps there), C^∞ inside.
//! - Parametrisation: constant angular speed within a segment.
//! - Cost: one forward-difference step per frame (4 multiply-adds per component).
//! - Use it for constant-speed moves and as the baseline the smooth schemes are compared to.

use super::{Blend, Segment};
use crate::rotation::arc::{Arc, ArcSteps};
use crate::tangent::Knots;
use glam::DQuat;

/// One slerp segment.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Slerp {
    arc: Arc,
}

impl Slerp {
    /// The segment's arc as lanes ([`crate::Curve::rotations`]); it starts at `q_i`.
    pub(crate) fn lanes(&self) -> super::blend4::ArcLanes {
        super::blend4::ArcLanes::starting(&self.arc)
    }
}

impl Segment for Slerp {
    type Frames = ArcSteps;
    type Pending = std::convert::Infallible;

    fn finish4(lanes: &[Self::Pending; 4]) -> [DQuat; 4] {
        match lanes[0] {}
    }

    fn new(keys: &Knots, s: usize, _blend: Blend) -> Self {
        Slerp {
            arc: keys.chord_arc(s),
        }
    }

    fn eval(&self, u: f64) -> DQuat {
        self.arc.eval(u)
    }

    fn frames(&self, u0: f64, du: f64) -> ArcSteps {
        self.arc.steps(u0, du)
    }

    fn blend_bound(&self) -> f64 {
        0.0
    }

    fn blend_gap(&self, _u: f64) -> f64 {
        2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::*;
    use crate::rotation::quat;

    #[test]
    fn keys_and_forward_differences() {
        check_segment::<Slerp>(&sample_keys(), Blend::Cubic);
    }

    #[test]
    fn matches_the_log_exp_formula() {
        let k = sample_keys();
        let seg = Slerp::new(&k, 1, Blend::Cubic);
        let l = quat::log(k.quats[2] * k.quats[1].conjugate());
        for u in [0.1, 0.5, 0.9] {
            let want = quat::exp(l * u) * k.quats[1];
            assert!((seg.eval(u) - want).length() < 1e-15);
        }
    }
}
