//! `squad` (Shoemake 1987), with the non-uniform inner points of docs/spec.md §4.4 and its outer arcs by
//! forward differences (Nam & Kim 1996, §4).
//!
//! ```text
//! Q(u) = slerp(slerp(q_i, q_{i+1}, u), slerp(a_i, b_{i+1}, u), 2u(1−u))
//! P = log(q_{i+1} q_i⁻¹), M = log(q_{i−1} q_i⁻¹), m_i = (P/Δ_i − M/Δ_{i−1})/2
//! a_i = exp((Δ_i m_i − P)/2)·q_i,   b_i = exp((−M − Δ_{i−1} m_i)/2)·q_i
//! ends, from w = V q⁻¹:  a_1 = exp((w_1 − log(q_2 q_1⁻¹))/2)·q_1,
//!                         b_n = exp((log(q_n q_{n−1}⁻¹) − w_n)/2)·q_n
//! ```
//! For uniform times `a_i = b_i = exp(−(P + M)/4)·q_i`, Shoemake's formula; `chord` ends give
//! `a_1 = q_1`, `b_n = q_n`. With `--path euler`, `P` and `M` are the segments' chords `L_i` and
//! `−L_{i−1}`, the outer arc is `exp(u·L_i) q_i`, and the inner arc is the branch of
//! `log(b_{i+1} a_i⁻¹)` nearest `L_i + X_b − X_a`, so a spin keeps its turns.
//!
//! - Interpolation: every key. Tangency: the velocity at key `i` is `m_i·q_i` per second from
//!   both sides; at the ends it is the given `V`.
//! - Continuity: C¹ at keys (also for non-uniform spacing), C^∞ inside.
//! - Cost per frame: two forward-difference steps and one geodesic blend.
//! - Limitations: an inner point is `exp(X)·q` with `X` from the formulas above; the blend sees it
//!   only through `log(exp(X)) = X`, true for `‖X‖ < π`. Beyond (end velocities of more than
//!   about a turn per segment, or a reversal next to a much shorter segment) the tangent is lost
//!   and the curve is not C¹ there; the tool says so on stderr.

use super::blend4::{self, Block4, Pending, geodesic4, params4, steps4};
use super::{Blend, Segment};
use crate::error::{Message, Setting};
use crate::message;
use crate::rotation::arc::{Arc, ArcSteps};
use crate::rotation::quat::{exp, geodesic};
use crate::tangent::{Knots, step};
use glam::{DQuat, DVec3};

/// One squad segment.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Squad {
    outer: Arc,
    inner: Arc,
    gap: f64,
    aliased: bool,
}

/// `P = log(q_{i+1} q_i⁻¹)`: the chord leaving key `i` (`--path euler`: the segment's chord;
/// a cyclic track's last key: the first segment's).
fn ahead(k: &Knots, i: usize) -> DVec3 {
    let i = if i == k.quats.len() - 1 { 0 } else { i };
    match &k.chords {
        Some(c) => c[i],
        None => step(k.quats[i], k.quats[i + 1]),
    }
}

/// `M = log(q_{i−1} q_i⁻¹)`: the chord back from key `i` (`--path euler`: minus the previous
/// segment's chord; a cyclic track's first key: minus the last segment's).
fn behind(k: &Knots, i: usize) -> DVec3 {
    let i = if i == 0 { k.quats.len() - 1 } else { i };
    match &k.chords {
        Some(c) => -c[i - 1],
        None => step(k.quats[i], k.quats[i - 1]),
    }
}

/// Length of the segment before key `i` (across the seam of a cyclic track).
fn delta_before(k: &Knots, i: usize) -> f64 {
    k.delta(if i == 0 { k.quats.len() - 2 } else { i - 1 })
}

/// Length of the segment after key `i` (across the seam of a cyclic track).
fn delta_after(k: &Knots, i: usize) -> f64 {
    k.delta(if i == k.quats.len() - 1 { 0 } else { i })
}

/// Squad's own tangent at key `i`, per second: `m_i = (P/Δ_i − M/Δ_{i−1})/2`.
fn own(k: &Knots, i: usize) -> DVec3 {
    (ahead(k, i) / delta_after(k, i) - behind(k, i) / delta_before(k, i)) * 0.5
}

/// Whether key `i` is an end of an open track (its tangent is the end rule's).
fn open_end(k: &Knots, i: usize) -> bool {
    !k.cyclic && (i == 0 || i == k.quats.len() - 1)
}

/// The exponent `X` of the inner control point `a_i = exp(X)·q_i` (leaving key `i`):
/// `(Δ_i m − P)/2` with `m` squad's own tangent, or the key's given or shaped one.
fn a_exponent(k: &Knots, i: usize) -> DVec3 {
    let p = ahead(k, i);
    let m = if k.shaped[i] || open_end(k, i) {
        k.w[i]
    } else {
        own(k, i)
    };
    (m * k.delta(i) - p) * 0.5
}

/// The exponent `X` of the inner control point `b_i = exp(X)·q_i` (arriving at key `i`):
/// `(−M − Δ_{i−1} m)/2`.
fn b_exponent(k: &Knots, i: usize) -> DVec3 {
    let m_back = behind(k, i);
    let m = if k.shaped[i] || open_end(k, i) {
        k.w_in[i]
    } else {
        own(k, i)
    };
    (-m_back - m * k.delta(i - 1)) * 0.5
}

#[cfg(test)]
fn a_point(k: &Knots, i: usize) -> DQuat {
    exp(a_exponent(k, i)) * k.quats[i]
}

#[cfg(test)]
fn b_point(k: &Knots, i: usize) -> DQuat {
    exp(b_exponent(k, i)) * k.quats[i]
}

/// Squad in-betweens: both arcs by forward differences, the blends four frames at a time
/// (`blend4.rs`).
#[derive(Debug, Clone)]
pub(crate) struct SquadFrames {
    outer: ArcSteps,
    inner: ArcSteps,
    u0: f64,
    du: f64,
    j: f64,
    block: Block4,
}

/// Squad's blend weight `2u(1 − u)` between the outer and inner arcs.
#[inline]
fn weight(u: f64) -> f64 {
    2.0 * u * (1.0 - u)
}

impl Iterator for SquadFrames {
    type Item = DQuat;

    #[inline]
    fn next(&mut self) -> Option<DQuat> {
        let SquadFrames {
            outer,
            inner,
            u0,
            du,
            j,
            block,
        } = self;
        Some(block.next(|| {
            let (a, b) = (steps4(outer), steps4(inner));
            let f = params4(*u0, *du, *j, weight);
            *j += 4.0;
            geodesic4(a, b, f).to_quats()
        }))
    }
}

/// A squad segment's arcs as lanes ([`crate::Curve::rotations`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SquadLanes {
    outer: super::blend4::ArcLanes,
    inner: super::blend4::ArcLanes,
}

impl Squad {
    /// The segment as lanes: both arcs start at their first point.
    pub(crate) fn lanes(&self) -> SquadLanes {
        SquadLanes {
            outer: super::blend4::ArcLanes::starting(&self.outer),
            inner: super::blend4::ArcLanes::starting(&self.inner),
        }
    }
}

impl super::blend4::Lanes4 for SquadLanes {
    #[inline]
    fn eval4(&self, u: wide::f64x4) -> super::blend4::Quat4 {
        let f = super::blend4::map4(u, weight);
        geodesic4(self.outer.eval4(u), self.inner.eval4(u), f)
    }
}

impl Segment for Squad {
    type Frames = SquadFrames;
    type Pending = Pending<2>;

    fn gather(&self, u0: f64, du: f64, n: usize) -> Option<[Pending<2>; 3]> {
        Some(blend4::gather(
            [&self.outer, &self.inner],
            u0,
            du,
            n,
            weight,
        ))
    }

    fn finish4(lanes: &[Pending<2>; 4]) -> [DQuat; 4] {
        blend4::finish_one(lanes)
    }

    fn new(keys: &Knots, s: usize, _blend: Blend) -> Self {
        let (q0, q1) = (keys.quats[s], keys.quats[s + 1]);
        let (xa, xb) = (a_exponent(keys, s), b_exponent(keys, s + 1));
        let (a, b) = (exp(xa) * q0, exp(xb) * q1);
        let outer = keys.chord_arc(s);
        let inner = if keys.spins() {
            // The inner arc runs beside the chord: the branch nearest L + X_b − X_a.
            Arc::near(a, b, keys.chord(s) + xb - xa)
        } else {
            Arc::between(a, b)
        };
        Squad {
            outer,
            inner,
            gap: crate::rotation::arc::s3_angle(q0, a) + outer.span() + inner.span(),
            aliased: xa.length().max(xb.length()) >= std::f64::consts::PI,
        }
    }

    fn eval(&self, u: f64) -> DQuat {
        geodesic(self.outer.eval(u), self.inner.eval(u), weight(u))
    }

    fn frames(&self, u0: f64, du: f64) -> SquadFrames {
        SquadFrames {
            outer: self.outer.steps(u0, du),
            inner: self.inner.steps(u0, du),
            u0,
            du,
            j: 0.0,
            block: Block4::default(),
        }
    }

    fn blend_bound(&self) -> f64 {
        self.gap
    }

    fn blend_gap(&self, u: f64) -> f64 {
        (self.outer.eval(u) + self.inner.eval(u)).length()
    }

    fn limitation(&self) -> Option<Message> {
        self.aliased.then(|| {
            message![
                "an inner control point of squad is half a turn or more from its key (an end \
                 velocity or a change of spacing too large for squad), so the curve misses the \
                 tangent there; use ",
                Setting::Scheme,
                " hermite or add keys"
            ]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::*;
    use crate::rotation::quat::log;
    use crate::tangent::EndConditions;
    use glam::DVec3;

    #[test]
    fn gathered_frames_are_the_frames_bits() {
        check_gathered::<2, Squad>(&sample_keys(), Blend::Cubic);
    }

    #[test]
    fn keys_and_forward_differences() {
        check_segment::<Squad>(&sample_keys(), Blend::Cubic);
    }

    #[test]
    fn uniform_times_give_shoemakes_points() {
        let q = [
            DQuat::IDENTITY,
            DQuat::from_rotation_y(0.7),
            DQuat::from_axis_angle(DVec3::new(1.0, 0.0, 1.0).normalize(), 1.4),
            DQuat::from_rotation_z(0.3),
        ];
        let k = keys(&[0.0, 1.0, 2.0, 3.0], &q, EndConditions::default());
        for i in 1..3 {
            let seed =
                exp(-(log(q[i + 1] * q[i].conjugate()) + log(q[i - 1] * q[i].conjugate())) / 4.0)
                    * q[i];
            assert!((a_point(&k, i) - seed).length() < 1e-15);
            assert!((b_point(&k, i) - seed).length() < 1e-15);
        }
        // chord ends
        assert!((a_point(&k, 0) - q[0]).length() < 1e-15);
        assert!((b_point(&k, 3) - q[3]).length() < 1e-15);
    }

    #[test]
    fn c1_in_time_with_uneven_spacing() {
        let k = sample_keys();
        for i in 1..k.segments() {
            let left = Squad::new(&k, i - 1, Blend::Cubic);
            let right = Squad::new(&k, i, Blend::Cubic);
            let dl = deriv(&left, 1.0) / k.delta(i - 1);
            let dr = deriv(&right, 0.0) / k.delta(i);
            assert!(
                (dl - dr).length() < 1e-6 * dl.length(),
                "key {i}: {dl} vs {dr}"
            );
        }
    }
}
