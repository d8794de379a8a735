//! Four geodesic blends at once, for the in-between loops.
//!
//! Each frame of hermite, squad and bezier ends in one or three blends
//! `geodesic(a, b, f) = cos(fΩ)·a + sin(fΩ)/sin Ω·(b − (a·b)·a)`, `Ω = atan2(|b − (a·b)a|, a·b)`
//! ([`crate::rotation::quat::geodesic`]), and their `atan2` and `sin_cos` are most of a frame's
//! cost. Here four blends run as SIMD lanes (`wide::f64x4`; `atan2` and `sin_cos` are Agner
//! Fog's vector-class-library polynomials, within 2 ulp: [`atan2_upper4`] and `wide`'s
//! `sin_cos`), in structure-of-arrays form. A lane whose pair is degenerate
//! (`|b − (a·b)a| < 1e-300`: identical or antipodal points) is done by the scalar function,
//! which handles those cases; the two agree to a few ulp (test below). No lane's result depends
//! on the other lanes of its block.

use crate::rotation::arc::Arc;
use crate::rotation::quat::geodesic;
use glam::DQuat;
use wide::f64x4;

pub(crate) use crate::rotation::quat4::Quat4;
use crate::rotation::quat4::atan2_upper4;

/// Hands out frames computed four at a time: `next` refills the block when it is used up.
#[derive(Debug, Clone)]
pub(crate) struct Block4 {
    buf: [DQuat; 4],
    pos: usize,
}

impl Default for Block4 {
    fn default() -> Self {
        Block4 {
            buf: [DQuat::IDENTITY; 4],
            pos: 4,
        }
    }
}

impl Block4 {
    #[inline]
    pub(crate) fn next(&mut self, refill: impl FnOnce() -> [DQuat; 4]) -> DQuat {
        if self.pos == 4 {
            self.buf = refill();
            self.pos = 0;
        }
        self.pos += 1;
        self.buf[self.pos - 1]
    }
}

/// The next four points of an arc's forward differences, as lanes.
#[inline]
pub(crate) fn steps4(steps: &mut crate::rotation::arc::ArcSteps) -> Quat4 {
    let q: [DQuat; 4] = std::array::from_fn(|_| steps.next_point());
    Quat4::from_quats(&q)
}

/// `f(u₀ + (j + i)·δ)` for lanes `i = 0..4`, with `u` from the frame index (never accumulated).
#[inline]
pub(crate) fn params4(u0: f64, du: f64, j: f64, f: impl Fn(f64) -> f64) -> f64x4 {
    f64x4::new(std::array::from_fn(|i| f(u0 + (j + i as f64) * du)))
}

/// A frame up to its last blends ([`crate::curve::Segment::gather`]): the points of the
/// segment's `K` fixed arcs at the frame, and the frame's parameter through the scheme's weight
/// (`u` for bezier, squad's `2u(1 − u)`, hermite's blend).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pending<const K: usize> {
    pub points: [DQuat; K],
    pub f: f64,
}

/// The first `n` (1 ≤ `n` ≤ 3) frames from `u0` by `du` up to their last blends, exactly as the
/// scheme's frame iterator makes them: the arcs' points by their forward differences (the first
/// is `eval(u0)` itself, all that one frame needs), the weight of `params4`'s first block. Slots
/// from `n` on repeat the first.
pub(crate) fn gather<const K: usize>(
    arcs: [&Arc; K],
    u0: f64,
    du: f64,
    n: usize,
    weight: impl Fn(f64) -> f64,
) -> [Pending<K>; 3] {
    let first = arcs.map(|r| r.eval(u0));
    let mut steps = (n > 1).then(|| arcs.map(|r| r.steps(u0, du)));
    let mut out = [Pending {
        points: first,
        f: weight(u0 + 0.0 * du),
    }; 3];
    for (m, slot) in out.iter_mut().enumerate().take(n.min(3)) {
        *slot = Pending {
            points: match &mut steps {
                None => first,
                Some(steps) => steps.each_mut().map(|s| s.next_point()),
            },
            f: weight(u0 + (0.0 + m as f64) * du),
        };
    }
    let head = out[0];
    for slot in out.iter_mut().skip(n.min(3)) {
        *slot = head;
    }
    out
}

/// Point `k` of four pending frames, as lanes.
#[inline]
pub(crate) fn point4<const K: usize>(lanes: &[Pending<K>; 4], k: usize) -> Quat4 {
    Quat4::from_quats(&lanes.map(|p| p.points[k]))
}

/// The weights of four pending frames, as lanes.
#[inline]
pub(crate) fn weight4<const K: usize>(lanes: &[Pending<K>; 4]) -> f64x4 {
    f64x4::new(lanes.map(|p| p.f))
}

/// Hermite's and squad's last blend, `geodesic(a, b, f)`, for four pending frames.
pub(crate) fn finish_one(lanes: &[Pending<2>; 4]) -> [DQuat; 4] {
    geodesic4(point4(lanes, 0), point4(lanes, 1), weight4(lanes)).to_quats()
}

/// `geodesic(a[i], b[i], f[i])` for the four lanes.
#[inline]
pub(crate) fn geodesic4(a: Quat4, b: Quat4, f: f64x4) -> Quat4 {
    let [q] = geodesics4([(a, b, f)]);
    q
}

/// `N` independent [`geodesic4`]s, step by step side by side: a blend is one long chain of
/// dependent operations (a square root, two divisions, `atan2`'s and `sin_cos`'s polynomials),
/// and two chains written together give the processor two operations to overlap at every
/// step. Each blend's bits are [`geodesic4`]'s.
#[inline]
pub(crate) fn geodesics4<const N: usize>(pairs: [(Quat4, Quat4, f64x4); N]) -> [Quat4; N] {
    let d = pairs.map(|(a, b, _)| a.dot(b));
    let perp: [Quat4; N] = std::array::from_fn(|i| pairs[i].1.less(d[i], pairs[i].0));
    let s = perp.map(|p| p.dot(p).sqrt());
    let omega: [f64x4; N] = std::array::from_fn(|i| atan2_upper4(s[i], d[i]));
    let sc: [(f64x4, f64x4); N] = std::array::from_fn(|i| (pairs[i].2 * omega[i]).sin_cos());
    std::array::from_fn(|i| {
        let (a, b, f) = pairs[i];
        let (sn, cs) = sc[i];
        let out = a.combine(cs, perp[i], sn / s[i]);
        // The test in lanes (one comparison, no branch per lane): degenerate lanes are rare.
        if !(s[i].simd_lt(f64x4::splat(1e-300)) | s[i].is_nan()).any() {
            return out;
        }
        let degenerate = s[i].to_array().map(|v| v.is_nan() || v < 1e-300);
        // Each degenerate lane by the scalar blend; the others keep their own lane's result,
        // so a lane never depends on what shares its block.
        let (qa, qb, fs, mut q) = (a.to_quats(), b.to_quats(), f.to_array(), out.to_quats());
        for l in 0..4 {
            if degenerate[l] {
                q[l] = geodesic(qa[l], qb[l], fs[l]);
            }
        }
        Quat4::from_quats(&q)
    })
}

/// A great arc `C(u) = cos(α + βu)·p + sin(α + βu)·e` ([`Arc`]) evaluated at four `u` at once,
/// for [`crate::Curve::rotations`].
///
/// `Arc`'s fields are private to `rotation::arc`, so the lanes are read back from its public
/// evaluation where the phase `α + βu` is exactly zero: `p` is `C` there to the bit (`sin 0`,
/// `cos 0` are exact) and `e = C′/β` there, within an ulp of the arc's own. An arc that starts
/// at its `p` (`α = 0`: [`Arc::leaving`], [`Arc::between`], [`Arc::near`]) is read at `u = 0`,
/// one that ends there (`α = −β`: [`Arc::arriving`]) at `u = 1`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArcLanes {
    p: DQuat,
    e: DQuat,
    alpha: f64,
    beta: f64,
}

impl ArcLanes {
    /// An arc with `α = 0`.
    pub(crate) fn starting(arc: &Arc) -> ArcLanes {
        ArcLanes::read(arc, 0.0, false)
    }

    /// An arc with `α = −β`.
    pub(crate) fn ending(arc: &Arc) -> ArcLanes {
        ArcLanes::read(arc, 1.0, true)
    }

    fn read(arc: &Arc, at: f64, ending: bool) -> ArcLanes {
        let beta = arc.span();
        let e = if beta > 0.0 {
            arc.deriv(at) / beta
        } else {
            DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0)
        };
        ArcLanes {
            p: arc.eval(at),
            e,
            alpha: if ending { -beta } else { 0.0 },
            beta,
        }
    }

    /// `C(u[i])` for the four lanes.
    #[inline]
    pub(crate) fn eval4(&self, u: f64x4) -> Quat4 {
        let phase = f64x4::splat(self.alpha) + f64x4::splat(self.beta) * u;
        let (s, c) = crate::rotation::quat4::sin_cos4(phase);
        Quat4::splat(self.p).combine(c, Quat4::splat(self.e), s)
    }
}

/// A piece of a curve evaluated at four parameters of it at once ([`crate::Curve::rotations`]):
/// the scheme's direct evaluation with its arcs and blends as lanes, within a few ulp of the
/// piece's scalar evaluation.
pub(crate) trait Lanes4 {
    /// The piece at `u[i]` for the four lanes.
    fn eval4(&self, u: f64x4) -> Quat4;
}

/// `f(u[i])` for the four lanes, each by the scalar expression (the same bits as the scalar
/// evaluation's weight).
#[inline]
pub(crate) fn map4(u: f64x4, f: impl Fn(f64) -> f64) -> f64x4 {
    f64x4::new(u.to_array().map(f))
}

/// A great arc between two points as a piece ([`crate::rotation::quat::geodesic`]): minaccel's
/// grid intervals.
#[derive(Debug, Clone, Copy)]
pub(crate) struct GeodesicLanes {
    pub a: DQuat,
    pub b: DQuat,
}

impl Lanes4 for GeodesicLanes {
    #[inline]
    fn eval4(&self, u: f64x4) -> Quat4 {
        geodesic4(Quat4::splat(self.a), Quat4::splat(self.b), u)
    }
}

impl Lanes4 for ArcLanes {
    #[inline]
    fn eval4(&self, u: f64x4) -> Quat4 {
        ArcLanes::eval4(self, u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn agrees_with_the_scalar_blend() {
        let mut worst: f64 = 0.0;
        for i in 0..2000 {
            let t = i as f64 * 0.37;
            let a: [DQuat; 4] = std::array::from_fn(|j| {
                DQuat::from_axis_angle(
                    DVec3::new((t + j as f64).sin(), (0.3 * t).cos(), 0.4).normalize(),
                    0.7 * t + j as f64,
                )
            });
            let b: [DQuat; 4] = std::array::from_fn(|j| {
                DQuat::from_axis_angle(
                    DVec3::new(0.2, (t * 1.3).sin(), 1.0).normalize(),
                    t - j as f64,
                ) * if j == 3 { -1.0 } else { 1.0 }
            });
            let f = [0.0, 0.3, 0.77, 1.0].map(|x| (x + 0.001 * i as f64).fract());
            let got =
                geodesic4(Quat4::from_quats(&a), Quat4::from_quats(&b), f64x4::new(f)).to_quats();
            for j in 0..4 {
                worst = worst.max((got[j] - geodesic(a[j], b[j], f[j])).length());
            }
        }
        // Measured 1.8e-15 (angles near π); the 4D bound of the curves is 2e-13.
        assert!(worst < 4e-15, "{worst:e}");
    }

    #[test]
    fn degenerate_lanes_fall_back() {
        let a = [DQuat::IDENTITY; 4];
        let b = [
            DQuat::IDENTITY,
            -DQuat::IDENTITY,
            DQuat::from_rotation_x(0.5),
            DQuat::IDENTITY,
        ];
        let f = [0.5; 4];
        let got = geodesic4(Quat4::from_quats(&a), Quat4::from_quats(&b), f64x4::new(f)).to_quats();
        for j in 0..4 {
            assert!((got[j] - geodesic(a[j], b[j], f[j])).length() < 1e-16);
        }
    }
}
