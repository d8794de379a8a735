//! Positions beside the rotations (BVH and glTF translations; docs/spec.md §4.6): the Euclidean
//! counterpart of each scheme. `slerp` is linear between keys; every other scheme is the cubic
//! Hermite curve with the same tangent rule as its rotations — time-aware central differences
//! `m_i = (p_{i+1} − p_{i−1})/(t_{i+1} − t_{i−1})` inside, and at the ends the chord
//! (`(p_2 − p_1)/Δ_1`), rest (0) or, for a loop, the central difference across the seam.
//!
//! **No overflow.** Any finite keys give finite positions. The curve is evaluated as written
//! above; only when that overflows (a difference of two keys beyond ±f64::MAX, a tangent over a
//! tiny interval: keys of 1e300 and more) is it evaluated again without differences. The linear
//! curve is then `(1 − u)·p₀ + u·p₁`, kept within the two keys (the exact value is); the cubic
//! is the same Hermite curve as a weighted sum of the keys, `Σ c_k·p_k` with each tangent's
//! `Δ·m = (Δ/span)·(p_a − p_b)`, `Δ/span ≤ 1`, on the keys scaled by 1/8 and scaled back:
//! `Σ|c_k| ≤ 3/2`, so no partial sum overflows, and only an overshoot of the cubic beyond
//! ±f64::MAX itself (possible for keys beyond ±1.19e308, the largest finite number being
//! 1.797e308) is held at ±f64::MAX.

use crate::tangent::Ends;
use glam::DVec3;

/// A track's position curve (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Positions {
    times: Vec<f64>,
    points: Vec<DVec3>,
    /// Per-second tangents at the keys (`None`: linear).
    tangents: Option<Vec<DVec3>>,
    /// The end rule the tangents were made with (for the overflow-free evaluation).
    ends: Ends,
}

impl Positions {
    /// The curve through `points` at `times` (validated key times, one point per key):
    /// linear, or cubic Hermite with the end rule `ends`.
    pub(crate) fn new(times: &[f64], points: &[DVec3], linear: bool, ends: Ends) -> Positions {
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
            ends,
        }
    }

    /// Key `j`'s tangent as `(p_a − p_b) / span`, `None` for a zero tangent (the rule of
    /// [`Positions::new`], without the subtraction).
    fn tangent_rule(&self, j: usize) -> Option<(usize, usize, f64)> {
        let (t, n) = (&self.times, self.times.len());
        if j > 0 && j + 1 < n {
            return Some((j + 1, j - 1, t[j + 1] - t[j - 1]));
        }
        match self.ends {
            Ends::Chord if j == 0 => Some((1, 0, t[1] - t[0])),
            Ends::Chord => Some((n - 1, n - 2, t[n - 1] - t[n - 2])),
            Ends::Rest => None,
            Ends::Cyclic => Some((1, n - 2, (t[n - 1] - t[n - 2]) + (t[1] - t[0]))),
        }
    }

    /// Segment `i` at `u` where the direct formula overflowed (see the module documentation).
    #[cold]
    fn at_without_overflow(&self, i: usize, u: f64, d: f64) -> DVec3 {
        let (p0, p1) = (self.points[i], self.points[i + 1]);
        if self.tangents.is_none() {
            let p = p0 * (1.0 - u) + p1 * u;
            return p.clamp(p0.min(p1), p0.max(p1));
        }
        const SCALE: f64 = 0.125;
        let p = |k: usize| self.points[k] * SCALE;
        // Δ·m_j, scaled: (Δ/span)·(p_a − p_b)·SCALE, at most twice a scaled key.
        let dm = |j: usize| {
            self.tangent_rule(j)
                .filter(|&(_, _, span)| span > 0.0)
                .map_or(DVec3::ZERO, |(a, b, span)| {
                    (p(a) - p(b)) * (d / span).min(1.0)
                })
        };
        let (u2, u3) = (u * u, u * u * u);
        let scaled = p(i) * (2.0 * u3 - 3.0 * u2 + 1.0)
            + dm(i) * (u3 - 2.0 * u2 + u)
            + p(i + 1) * (-2.0 * u3 + 3.0 * u2)
            + dm(i + 1) * (u3 - u2);
        (scaled / SCALE).clamp(DVec3::splat(-f64::MAX), DVec3::splat(f64::MAX))
    }

    /// The position at `t` (clamped to the keys' span): finite for finite keys (see the module
    /// documentation).
    pub(crate) fn at(&self, t: f64) -> DVec3 {
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
        let p = match &self.tangents {
            None => p0 + (p1 - p0) * u,
            Some(m) => {
                let (u2, u3) = (u * u, u * u * u);
                p0 * (2.0 * u3 - 3.0 * u2 + 1.0)
                    + m[i] * (d * (u3 - 2.0 * u2 + u))
                    + p1 * (-2.0 * u3 + 3.0 * u2)
                    + m[i + 1] * (d * (u3 - u2))
            }
        };
        if p.is_finite() {
            p
        } else {
            self.at_without_overflow(i, u, d)
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

    /// The curve is linear in its keys (for fixed times): the curve of `k·keys` is `k` times the
    /// curve of `keys`, which a small `k·keys` evaluates directly, without overflow.
    fn scaled_reference(
        times: &[f64],
        unit: &[DVec3],
        k: f64,
        ends: Ends,
        linear: bool,
        t: f64,
    ) -> DVec3 {
        Positions::new(times, unit, linear, ends).at(t) * k
    }

    #[test]
    fn keys_near_the_largest_float_interpolate_without_overflow() {
        let big = 1e308;
        let unit = [
            DVec3::new(1.0, -1.0, 0.5),
            DVec3::new(-1.0, 1.0, -1.7),
            DVec3::new(1.0, 1.0, 1.7),
            DVec3::new(-1.0, -0.3, -1.0),
        ];
        let keys: Vec<DVec3> = unit.iter().map(|&p| p * big).collect();
        // Even spacing, and keys 1 ns apart, whose tangents alone overflow.
        for times in [[0.0, 1.0, 2.0, 3.0], [0.0, 1e-9, 3e-9, 4e-9]] {
            for (linear, ends) in [
                (true, Ends::Chord),
                (false, Ends::Chord),
                (false, Ends::Rest),
                (false, Ends::Cyclic),
            ] {
                let c = Positions::new(&times, &keys, linear, ends);
                for j in 0..=60 {
                    let t = times[3] * j as f64 / 60.0;
                    let got = c.at(t);
                    let want = scaled_reference(&times, &unit, big, ends, linear, t);
                    assert!(got.is_finite(), "{ends:?} {linear} t {t}: {got}");
                    assert!(
                        (got - want).abs().max_element() <= 1e-12 * big,
                        "{ends:?} {linear} t {t}: {got} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_largest_floats_stay_finite_and_within_the_keys_when_linear() {
        let m = f64::MAX;
        let keys = [DVec3::splat(-m), DVec3::splat(m), DVec3::new(m, -m, m)];
        let times = [0.0, 1.0, 2.0];
        let lin = Positions::new(&times, &keys, true, Ends::Chord);
        for j in 0..=40 {
            let t = j as f64 / 20.0;
            let p = lin.at(t);
            assert!(p.is_finite(), "t {t}: {p}");
        }
        assert_eq!(lin.at(0.5), DVec3::ZERO);
        assert!((lin.at(0.25).x / m + 0.5).abs() < 1e-15);
        // A cubic through them may overshoot beyond f64::MAX: held there, never infinite.
        let cubic = Positions::new(&times, &keys, false, Ends::Chord);
        for j in 0..=40 {
            let p = cubic.at(j as f64 / 20.0);
            assert!(p.is_finite() && p.abs().max_element() <= m, "{p}");
        }
    }
}
