//! A track's curve as a function of time, with its world-frame angular velocity and
//! acceleration: what `interp --velocity`, `analyze` and `plot` measure.
//!
//! The curve is piecewise: a segment between keys for hermite, squad, bezier and slerp; a grid
//! interval (slerp between grid points) for minaccel. Derivatives are one-sided at the pieces'
//! ends: each is taken from one piece's own formula (continued a little past its end), so a jump
//! at a key shows as the difference of the two sides.
//!
//! - `ω = 2·(dQ/dt)·Q⁻¹` (vector part), world frame, rad/s. For a segment scheme `dQ/du` is the
//!   fourth-order central difference of the exact segment formula with `h = 1e-3` in `u`
//!   (truncation ~h⁴·Q⁽⁵⁾/30, rounding ~ε/h: about 1e-12 relative for ordinary motion); for
//!   minaccel's slerp pieces it is exact, `2·log(q_{j+1} q_j⁻¹)/h_j`.
//! - `α = dω/dt` by the same difference of `ω` within the piece (about 1e-9 relative).
//! - At a time that is a piece boundary, [`Side::Right`] takes the piece that starts there
//!   (except at the last point, which has only a left piece).

use crate::clock::Fps;
use crate::curve::bezier::Bezier;
use crate::curve::hermite::Hermite;
use crate::curve::minaccel::{self, Report};
use crate::curve::slerp::Slerp;
use crate::curve::squad::Squad;
use crate::curve::{Blend, Scheme, Segment};
use crate::error::InputResult;
use crate::rotation::quat::{geodesic, log};
use crate::tangent::Keys;
use glam::{DQuat, DVec3};

/// Which piece to use at a piece boundary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Left,
    Right,
}

/// Step in `u` of the finite differences.
const H: f64 = 1e-3;

/// A track's curve, evaluable at any time.
#[derive(Debug, Clone)]
pub enum TrackCurve {
    Segments {
        keys: Keys,
        scheme: Scheme,
        blend: Blend,
    },
    /// minaccel's solution: slerp between grid points.
    Grid {
        times: Vec<f64>,
        points: Vec<DQuat>,
        key_times: Vec<f64>,
    },
}

/// `ω = 2·Q'·Q⁻¹` from a derivative `dq` at `q`.
#[inline]
fn omega_of(q: DQuat, dq: DQuat) -> DVec3 {
    let p = dq * q.conjugate();
    DVec3::new(p.x, p.y, p.z) * 2.0
}

/// Fourth-order central difference of `f` at `x` with step `h`.
#[inline]
fn d4<T, F>(f: F, x: f64, h: f64) -> T
where
    F: Fn(f64) -> T,
    T: std::ops::Sub<Output = T> + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
{
    (f(x - 2.0 * h) - f(x + 2.0 * h) + (f(x + h) - f(x - h)) * 8.0) * (1.0 / (12.0 * h))
}

/// Angular velocity (rad/s) of a segment at parameter `u`, for a segment `delta` seconds long:
/// fourth-order difference of its exact formula.
pub fn segment_omega<S: Segment>(seg: &S, u: f64, delta: f64) -> DVec3 {
    let dq = d4(|x| seg.eval(x), u, H) * (1.0 / delta);
    omega_of(seg.eval(u), dq)
}

/// Angular velocity (rad/s) of the slerp from `a` to `b` over `h` seconds.
pub fn chord_omega(a: DQuat, b: DQuat, h: f64) -> DVec3 {
    log(b * a.conjugate()) * (2.0 / h)
}

impl TrackCurve {
    /// Builds the curve of `keys` (solving minaccel on its grid at `fps`, which can fail for
    /// an absurd grid size).
    pub fn new(
        keys: Keys,
        scheme: Scheme,
        blend: Blend,
        fps: Fps,
    ) -> InputResult<(TrackCurve, Option<Report>)> {
        Ok(match scheme {
            Scheme::MinAccel => {
                let sol = minaccel::solve(&keys, fps.as_f64())?;
                let report = sol.report;
                (
                    TrackCurve::Grid {
                        times: sol.times,
                        points: sol.points,
                        key_times: keys.times,
                    },
                    Some(report),
                )
            }
            _ => (
                TrackCurve::Segments {
                    keys,
                    scheme,
                    blend,
                },
                None,
            ),
        })
    }

    /// The piece boundaries: key times, or minaccel's grid times.
    pub fn breaks(&self) -> &[f64] {
        match self {
            TrackCurve::Segments { keys, .. } => &keys.times,
            TrackCurve::Grid { times, .. } => times,
        }
    }

    /// minaccel's grid points (empty for a segment curve).
    pub fn grid_points(&self) -> &[DQuat] {
        match self {
            TrackCurve::Segments { .. } => &[],
            TrackCurve::Grid { points, .. } => points,
        }
    }

    /// The key times.
    pub fn key_times(&self) -> &[f64] {
        match self {
            TrackCurve::Segments { keys, .. } => &keys.times,
            TrackCurve::Grid { key_times, .. } => key_times,
        }
    }

    /// The piece containing `t` on `side`, and `t`'s parameter `u` in it.
    fn piece(&self, t: f64, side: Side) -> (usize, f64) {
        let b = self.breaks();
        let n = b.len();
        let i = match side {
            Side::Right => b.partition_point(|&x| x <= t).saturating_sub(1),
            Side::Left => b.partition_point(|&x| x < t).saturating_sub(1),
        }
        .min(n - 2);
        (i, (t - b[i]) / (b[i + 1] - b[i]))
    }

    /// Evaluates piece `i` at parameter `u` (continued past [0, 1] by its own formula).
    fn eval_piece(&self, i: usize, u: f64) -> DQuat {
        match self {
            TrackCurve::Segments {
                keys,
                scheme,
                blend,
            } => match scheme {
                Scheme::Slerp => Slerp::new(keys, i, *blend).eval(u),
                Scheme::Hermite => Hermite::new(keys, i, *blend).eval(u),
                Scheme::Squad => Squad::new(keys, i, *blend).eval(u),
                Scheme::Bezier => Bezier::new(keys, i, *blend).eval(u),
                Scheme::MinAccel => unreachable!("minaccel is a Grid curve"),
            },
            TrackCurve::Grid { points, .. } => geodesic(points[i], points[i + 1], u),
        }
    }

    /// The curve at time `t` (the right piece at a boundary).
    pub fn eval(&self, t: f64) -> DQuat {
        let (i, u) = self.piece(t, Side::Right);
        self.eval_piece(i, u)
    }

    /// Angular velocity in piece `i` at parameter `u`, rad/s.
    fn omega_piece(&self, i: usize, u: f64) -> DVec3 {
        let b = self.breaks();
        let delta = b[i + 1] - b[i];
        match self {
            TrackCurve::Grid { points, .. } => chord_omega(points[i], points[i + 1], delta),
            TrackCurve::Segments { .. } => {
                let dq = d4(|x| self.eval_piece(i, x), u, H) * (1.0 / delta);
                omega_of(self.eval_piece(i, u), dq)
            }
        }
    }

    /// World-frame angular velocity at `t`, rad/s.
    ///
    /// For minaccel's grid curve: inside a piece, the piece's own (exact) velocity; at a grid
    /// point, the velocity of the smooth curve the grid discretises — the mean of the two
    /// neighbouring pieces (second order), or, at a key or an end, the one-sided second-order
    /// extrapolation `1.5·ω_near − 0.5·ω_next` from `side`, so that a jump at a key measures the
    /// curve and not its discretisation.
    pub fn omega(&self, t: f64, side: Side) -> DVec3 {
        let (i, u) = self.piece(t, side);
        let TrackCurve::Grid { times, .. } = self else {
            return self.omega_piece(i, u);
        };
        let Some((g, one_sided)) = self.grid_point(t) else {
            return self.omega_piece(i, u);
        };
        let n = times.len() - 1; // pieces
        let c = |j: usize| self.omega_piece(j, 0.5);
        match (one_sided, side) {
            (false, _) => (c(g - 1) + c(g)) * 0.5,
            (true, Side::Right) if g < n => {
                if g + 1 < n {
                    c(g) * 1.5 - c(g + 1) * 0.5
                } else {
                    c(g)
                }
            }
            (true, _) if g >= 1 => {
                if g >= 2 {
                    c(g - 1) * 1.5 - c(g - 2) * 0.5
                } else {
                    c(g - 1)
                }
            }
            _ => c(g.min(n - 1)),
        }
    }

    /// For a grid curve and a time on one of its points: the point's index, and whether only
    /// one-sided estimates make sense there (a key or an end).
    fn grid_point(&self, t: f64) -> Option<(usize, bool)> {
        let TrackCurve::Grid {
            times, key_times, ..
        } = self
        else {
            return None;
        };
        let g = times.partition_point(|&x| x < t);
        if g >= times.len() || times[g] != t {
            return None;
        }
        let edge = g == 0
            || g == times.len() - 1
            || key_times.binary_search_by(|k| k.total_cmp(&t)).is_ok();
        Some((g, edge))
    }

    /// World-frame angular acceleration at `t`, rad/s². For minaccel's grid curve, the
    /// difference of neighbouring pieces' velocities over the distance of their midpoints:
    /// centred inside, one-sided (on `side`) at a key or an end.
    pub fn alpha(&self, t: f64, side: Side) -> DVec3 {
        let (i, u) = self.piece(t, side);
        match self {
            TrackCurve::Grid { times, .. } => {
                let n = times.len() - 1;
                if n < 2 {
                    return DVec3::ZERO;
                }
                let mid = |j: usize| 0.5 * (times[j] + times[j + 1]);
                let slope = |a: usize, b: usize| {
                    (self.omega_piece(b, 0.5) - self.omega_piece(a, 0.5)) / (mid(b) - mid(a))
                };
                match self.grid_point(t) {
                    Some((g, true)) => match side {
                        Side::Right if g + 1 < n => slope(g, g + 1),
                        Side::Left if g >= 2 => slope(g - 2, g - 1),
                        _ => slope(i.min(n - 2), i.min(n - 2) + 1),
                    },
                    Some((g, false)) => slope(g - 1, g),
                    None => slope(i.saturating_sub(1).min(n - 2), (i + 1).min(n - 1).max(1)),
                }
            }
            TrackCurve::Segments { .. } => {
                let b = self.breaks();
                d4(|x| self.omega_piece(i, x), u, H) * (1.0 / (b[i + 1] - b[i]))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::sample_keys;

    #[test]
    fn slerp_velocity_is_the_chord() {
        let k = sample_keys();
        let (c, _) = TrackCurve::new(
            k.clone(),
            Scheme::Slerp,
            Blend::Cubic,
            Fps::new(30, 1).unwrap(),
        )
        .unwrap();
        let w = log(k.quats[2] * k.quats[1].conjugate()) * (2.0 / k.delta(1));
        for t in [0.5, 0.7, 1.0, 1.2] {
            assert!((c.omega(t, Side::Right) - w).length() < 1e-10 * w.length());
        }
        // At key 1 the left side is the previous chord.
        let w0 = log(k.quats[1] * k.quats[0].conjugate()) * (2.0 / k.delta(0));
        assert!((c.omega(0.5, Side::Left) - w0).length() < 1e-10 * w0.length());
        assert!(c.alpha(0.7, Side::Right).length() < 1e-6);
    }

    #[test]
    fn hermite_velocity_at_keys_is_the_tangent() {
        let k = sample_keys();
        let (c, _) = TrackCurve::new(
            k.clone(),
            Scheme::Hermite,
            Blend::Cubic,
            Fps::new(30, 1).unwrap(),
        )
        .unwrap();
        for i in 0..k.times.len() {
            let want = k.w[i] * 2.0;
            for side in [Side::Left, Side::Right] {
                let got = c.omega(k.times[i], side);
                assert!(
                    (got - want).length() < 1e-9 * want.length().max(1.0),
                    "{i} {side:?}"
                );
            }
        }
    }
}
