//! The `spline` tangent of an interior key (docs/spec.md §4.1): the derivative at the key of the
//! not-a-knot cubic spline through the logarithms of up to seven keys in the key's own chart.
//!
//! In the chart at key `i` every key `j` of the window `|j − i| ≤ 3` is the point
//! `(t_j, L_j)` with `L_j = log(q_j q_i⁻¹)` (so `L_i = 0`), or — when the chords between the two
//! keys have lengths summing to more than π, where that log would alias to the other way round —
//! the sum of those chords, `L_s = log(q_{s+1} q_s⁻¹)` (or `--path euler`'s own). The tangent is
//! `w_i = s'(t_i)` for the not-a-knot cubic spline `s` through those points: a fourth-order
//! estimate of the half angular velocity (the curve's error falls as h⁴, docs/schemes.md) that
//! keeps the curve local (seven keys) and C¹. For uniform spacing `h` and a full window it is
//!
//! ```text
//! w_i = [37(L₁ − L₋₁) − 8(L₂ − L₋₂) + (L₃ − L₋₃)] / (48h)
//! ```
//!
//! The tangent is then kept near Nam & Kim's at the key, `w_NK` (the `nam-kim` rule): with
//! `c = w − w_NK`, when `‖c‖ > ½‖w_NK‖` it becomes `w_NK + c·(½‖w_NK‖/‖c‖)`. On smooth motion
//! `‖c‖ = O(h²)‖w‖` and the limit is far off; where the window holds motion of another pace (a
//! steady turn before one fast key, a hold before a quick move) the spline's slope can point
//! against the motion or overshoot by turns (keys 0°, 0°, 90° at 0, 1, 1.05 s: 1714°/s at the
//! middle key), and the limit keeps it pointing Nam & Kim's way, within ½ and 1½ of its length
//! (128.6°/s there, Nam & Kim 85.7°/s).
//!
//! A key whose two neighbouring chords turn a half-turn or more together (`‖L_{i−1}‖ + ‖L_i‖ ≥
//! π − 10⁻⁹`: spins of `--path euler`, long steps of `--path as-given`) takes Nam & Kim's tangent
//! instead: after a 720° spin then a hold the spline's slope (2π/3 rad/s against π) pushed the
//! Bézier's middle leg past a half-turn and the curve jumped 45° in a frame.
//!
//! Near an end the window is cut to the keys there are (one-sided: the second key's is keys
//! 0‥4); with three keys the spline is the parabola through them, with four the cubic. A loop
//! (`Ends::Cyclic`) wraps the window around its seam.

use super::columns::Columns;
use super::logs::Keys;
use crate::rotation::quat::log;
use glam::{DQuat, DVec3};

mod lanes;

pub(super) use lanes::InOrder;

/// Keys each side of the key whose tangent is estimated.
const REACH: usize = 3;

/// How near π chords may sum before their sum replaces the log between their keys (a 360°
/// step of `--path euler` is π exactly, and the log of `−1` has no axis).
const TIE: f64 = 1e-9;

/// What the windows are cut from: a track's times, its quaternions after the path rule, and
/// its chords (with their lengths).
pub(super) struct Windows<'a> {
    times: &'a [f64],
    quats: &'a [DQuat],
    chords: &'a [DVec3],
    lengths: Vec<f64>,
    /// The last key is the first key's rotation and the window wraps around the seam.
    cyclic: bool,
    /// `far[k − 2]` at `s` is `log(q_{s+k} q_s⁻¹)`, `k` = 2, 3 (where that key exists; by
    /// [`super::logs::far`]), each log shared by the two keys it joins; empty for a loop, whose
    /// windows take their own.
    far: [Columns; 2],
    /// The chords again as columns, for the lanes (empty for a loop).
    chord_columns: Columns,
}

impl<'a> Windows<'a> {
    /// The windows of a track (`chords[s]` of segment `s`; `keys` its `quats` as columns).
    pub(super) fn new(
        times: &'a [f64],
        quats: &'a [DQuat],
        keys: &Keys,
        chords: &'a [DVec3],
        cyclic: bool,
    ) -> Windows<'a> {
        let lengths = chords.iter().map(|c| c.length()).collect();
        let (far, chord_columns) = if cyclic {
            Default::default()
        } else {
            (super::logs::far(keys), Columns::of(chords))
        };
        Windows {
            times,
            quats,
            chords,
            lengths,
            cyclic,
            far,
            chord_columns,
        }
    }

    /// Whether the far logs were taken (not a loop).
    fn has_far(&self) -> bool {
        !self.far[0].is_empty()
    }

    /// `log(q_j q_i⁻¹)` for key `j = i ± k` (`k` = 2 or 3; unrolled around a loop).
    fn log_to(&self, i: usize, k: usize, forward: bool) -> DVec3 {
        match (self.has_far(), forward) {
            (true, true) => self.far[k - 2].get(i),
            (true, false) => -self.far[k - 2].get(i - k),
            (false, _) => {
                let j = if forward {
                    i as isize + k as isize
                } else {
                    i as isize - k as isize
                };
                log(self.unrolled(j) * self.quats[i].conjugate())
            }
        }
    }

    /// The `spline` tangent of key `i` (for a loop, `i = 0` is the seam).
    pub(super) fn tangent(&self, i: usize) -> DVec3 {
        let n = self.quats.len();
        let segments = n - 1;
        // Neighbouring chords that turn a half-turn or more together (spins, as-given steps):
        // Nam & Kim's tangent; the spline through wrapping logs does no better there.
        let beside = [wrap(i + segments - 1, segments), i];
        if self.lengths[beside[0]] + self.lengths[beside[1]] >= std::f64::consts::PI - TIE {
            return self.nam_kim(i, beside);
        }
        // The window at positions `REACH − left ..= REACH + right`, key i at `REACH`: `y` the
        // points, `h[p]` the spacing from position p to p + 1.
        let (mut h, mut y) = ([0.0; 2 * REACH], [DVec3::ZERO; 2 * REACH + 1]);
        let (mut left, mut right) = (0, 0);
        for forward in [false, true] {
            let (mut sum, mut len) = (DVec3::ZERO, 0.0);
            for k in 1..=REACH {
                // The segment crossed to reach the k-th key (wrapped around a loop).
                let s = if forward {
                    if !self.cyclic && i + k >= n {
                        break;
                    }
                    wrap(i + k - 1, segments)
                } else {
                    if !self.cyclic && k > i {
                        break;
                    }
                    wrap(i + segments * REACH - k, segments)
                };
                let chord = if forward {
                    self.chords[s]
                } else {
                    -self.chords[s]
                };
                sum += chord;
                len += self.lengths[s];
                // A neighbour is its chord; further keys their log unless the chords between sum
                // to π or more (within 1e-9: at π the log is log(−1), which has no axis).
                let point = if k == 1 {
                    chord
                } else if len > std::f64::consts::PI - TIE {
                    sum
                } else {
                    self.log_to(i, k, forward)
                };
                let spacing = self.times[s + 1] - self.times[s];
                if forward {
                    (y[REACH + k], h[REACH + k - 1], right) = (point, spacing, k);
                } else {
                    (y[REACH - k], h[REACH - k], left) = (point, spacing, k);
                }
            }
        }
        let w = slope(
            &h[REACH - left..REACH + right],
            &y[REACH - left..=REACH + right],
            left,
        );
        // The limit: within half its length of Nam & Kim's tangent.
        let nk = self.nam_kim(i, beside);
        let (c, room) = (w - nk, 0.5 * nk.length());
        let off = c.length();
        if off > room { nk + c * (room / off) } else { w }
    }

    /// Nam & Kim's tangent at key `i` between the segments `[before, after]`:
    /// `log(q_{i+1} q_{i−1}⁻¹)/(t_{i+1} − t_{i−1})`, or the sum of the two chords over that span
    /// where they turn π − 10⁻⁹ or more together.
    fn nam_kim(&self, i: usize, [before, after]: [usize; 2]) -> DVec3 {
        let span = (self.times[before + 1] - self.times[before])
            + (self.times[after + 1] - self.times[after]);
        // The alias rule from π − TIE: at π the chords compose to a half-turn without an axis.
        if self.lengths[before] + self.lengths[after] >= std::f64::consts::PI - TIE {
            (self.chords[before] + self.chords[after]) / span
        } else if self.has_far() {
            // log(q_{i+1} q_{i−1}⁻¹), already taken for the window of key i − 1.
            self.far[0].get(i - 1) / span
        } else {
            let i = i as isize;
            log(self.unrolled(i + 1) * self.unrolled(i - 1).conjugate()) / span
        }
    }

    /// Key `u` of the track unrolled around its loop: past the last key the keys come round
    /// again, each as `σ·q` where `q_{n−1} = σ·q_0` (`σ = −1` for a loop that turns a full turn
    /// in S³); within the track, its own key.
    fn unrolled(&self, mut u: isize) -> DQuat {
        let last = self.quats.len() as isize - 1;
        let sigma = if self.quats[0].dot(self.quats[last as usize]) < 0.0 {
            -1.0
        } else {
            1.0
        };
        let mut sign = 1.0;
        while u > last {
            (u, sign) = (u - last, sign * sigma);
        }
        while u < 0 {
            (u, sign) = (u + last, sign * sigma);
        }
        self.quats[u as usize] * sign
    }
}

/// `s` modulo `segments` for `s < (REACH + 1)·segments`, by subtraction (a division per window
/// key cost more than the rest of the tangent).
#[inline]
fn wrap(mut s: usize, segments: usize) -> usize {
    while s >= segments {
        s -= segments;
    }
    s
}

/// The derivative at point `c` (neither end) of the not-a-knot cubic spline through `y` with
/// spacings `h` (`h[k]` from point `k` to `k + 1`), for 3 to 7 points: the parabola through
/// three, the cubic through four.
///
/// With the not-a-knot end rows of the slope equations subtracted from their neighbours, the
/// slopes `s_1‥s_{m−2}` solve a tridiagonal system whose rows are diagonally dominant
/// (`(h₀+h₁)s₁ + h₀s₂ = b₁ − b₀`, `h_k s_{k−1} + 2(h_{k−1}+h_k)s_k + h_{k−1}s_{k+1} = b_k`,
/// `h_{m−2}s_{m−3} + (h_{m−3}+h_{m−2})s_{m−2} = b_{m−2} − b_{m−1}`): Thomas' algorithm.
pub(crate) fn slope(h: &[f64], y: &[DVec3], c: usize) -> DVec3 {
    let m = y.len();
    debug_assert!((3..=2 * REACH + 1).contains(&m) && h.len() == m - 1 && (1..m - 1).contains(&c));
    let mut d = [DVec3::ZERO; 2 * REACH];
    for k in 0..m - 1 {
        d[k] = (y[k + 1] - y[k]) * (1.0 / h[k]);
    }
    if m == 3 {
        return (d[0] * h[1] + d[1] * h[0]) / (h[0] + h[1]);
    }
    let mut b = [DVec3::ZERO; 2 * REACH + 1];
    for k in 1..m - 1 {
        b[k] = (d[k - 1] * h[k] + d[k] * h[k - 1]) * 3.0;
    }
    let (h0, h1) = (h[0], h[1]);
    b[0] = (d[0] * ((h0 + 2.0 * (h0 + h1)) * h1) + d[1] * (h0 * h0)) / (h0 + h1);
    let (ha, hb) = (h[m - 3], h[m - 2]);
    b[m - 1] = (d[m - 3] * (hb * hb) + d[m - 2] * ((2.0 * (ha + hb) + hb) * ha)) / (ha + hb);
    // Unknowns s_1‥s_{m−2} as rows r = 0‥N−1: sub·s_{r−1} + diag·s_r + sup·s_{r+1} = rhs.
    let rows = m - 2;
    let row = |r: usize| -> (f64, f64, f64, DVec3) {
        let k = r + 1;
        if r == 0 {
            (0.0, h0 + h1, h0, b[1] - b[0])
        } else if r == rows - 1 {
            (hb, ha + hb, 0.0, b[m - 2] - b[m - 1])
        } else {
            (h[k], 2.0 * (h[k - 1] + h[k]), h[k - 1], b[k])
        }
    };
    let (mut cp, mut dp) = ([0.0; 2 * REACH], [DVec3::ZERO; 2 * REACH]);
    for r in 0..rows {
        let (sub, diag, sup, rhs) = row(r);
        let (c_prev, d_prev) = if r == 0 {
            (0.0, DVec3::ZERO)
        } else {
            (cp[r - 1], dp[r - 1])
        };
        let inv = 1.0 / (diag - sub * c_prev);
        cp[r] = sup * inv;
        dp[r] = (rhs - d_prev * sub) * inv;
    }
    let mut s = dp[rows - 1];
    for r in (c - 1..rows - 1).rev() {
        s = dp[r] - s * cp[r];
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::tangent::{EndConditions, Knots, PathMode, TangentRule};
    use crate::track::{Tcb, Track};

    fn knots(times: &[f64], quats: &[DQuat], rule: TangentRule) -> Knots {
        let track = Track::new(times.to_vec(), quats.to_vec()).expect("a valid track");
        Knots::shaped(
            &track,
            PathMode::Shortest,
            EndConditions::default(),
            Tcb::ZERO,
            rule,
        )
    }

    /// The figure of the module documentation: a hold, then 90° in 0.05 s. The spline's slope
    /// at the middle key is 1714°/s; limited, 1½ times Nam & Kim's 90°/1.05 s.
    #[test]
    fn a_hold_before_a_quick_move_stays_near_nam_and_kims_speed() {
        let q = [0.0f64, 0.0, 90.0].map(|a| DQuat::from_rotation_z(a.to_radians()));
        let times = [0.0, 1.0, 1.05];
        let unlimited = slope(
            &[1.0, 0.05],
            &[DVec3::ZERO, DVec3::ZERO, DVec3::Z * 45f64.to_radians()],
            1,
        );
        assert!((2.0 * unlimited.z.to_degrees() - 90.0 / 1.05 * 20.0).abs() < 1e-9);
        for (rule, factor) in [(TangentRule::Spline, 1.5), (TangentRule::NamKim, 1.0)] {
            let w = knots(&times, &q, rule).w[1];
            let deg_per_s = 2.0 * w.z.to_degrees();
            assert!(
                (deg_per_s - factor * 90.0 / 1.05).abs() < 1e-9,
                "{rule}: {deg_per_s}"
            );
        }
    }

    /// A 720° spin about z in one second, then held (found by an adversarial pass): the key at
    /// the end of the spin takes Nam & Kim's tangent, (2π + 0)/2 s in half angles.
    #[test]
    fn a_spin_then_a_hold_keeps_nam_and_kims_tangent() {
        let seq = crate::EulerSeq::parse("ZYX").expect("a sequence");
        let angles: Vec<DVec3> = [0.0f64, 720.0, 720.0, 720.0]
            .iter()
            .map(|a| DVec3::new(a.to_radians(), 0.0, 0.0))
            .collect();
        let q = angles.iter().map(|e| seq.to_quat(e.to_array())).collect();
        let track = Track::new(vec![0.0, 1.0, 2.0, 3.0], q)
            .and_then(|t| t.with_euler_angles(seq, angles))
            .expect("a valid track");
        let k = Knots::shaped(
            &track,
            PathMode::Euler,
            EndConditions::default(),
            Tcb::ZERO,
            TangentRule::Spline,
        );
        assert!(
            (k.w[1] - DVec3::Z * std::f64::consts::PI).length() < 1e-12,
            "{}",
            k.w[1]
        );
    }

    /// A steady 10°/s, then one key 10° on in 1/30 s (found by an adversarial pass): the
    /// spline's slope at the key before the fast one points backwards (the curve passed the key
    /// and turned back 8°); limited, it points Nam & Kim's way, within ½ and 1½ of 10°/s.
    #[test]
    fn a_steady_turn_before_a_fast_key_does_not_turn_back() {
        let times = [0.0, 1.0, 2.0, 3.0, 4.0, 4.0 + 1.0 / 30.0];
        let q =
            [0.0f64, 10.0, 20.0, 30.0, 40.0, 50.0].map(|a| DQuat::from_rotation_z(a.to_radians()));
        let k = knots(&times, &q, TangentRule::Spline);
        for (i, w) in k.w.iter().enumerate().take(4) {
            let deg_per_s = 2.0 * w.z.to_degrees();
            assert!((5.0..=15.0).contains(&deg_per_s), "key {i}: {deg_per_s}");
        }
        // The key before the fast one: at most 1½ times Nam & Kim's 20°/(31/30) s.
        let deg_per_s = 2.0 * k.w[4].z.to_degrees();
        assert!(
            (deg_per_s - 1.5 * 20.0 * 30.0 / 31.0).abs() < 1e-9,
            "{deg_per_s}"
        );
    }

    /// On a smooth motion the interior tangents converge to the true half angular velocity as
    /// h⁴ on uniform keys and h³ on uneven ones (Nam & Kim's as h² and h), and the bezier curve of
    /// the spline tangents to the motion as h⁴ on both: the error ratio when h halves.
    #[test]
    fn interior_tangents_are_fourth_order() {
        let q = |t: f64| {
            DQuat::from_rotation_z(1.3 * t + 0.4 * (2.0 * t).sin())
                * DQuat::from_rotation_y(0.8 * (1.5 * t).cos())
                * DQuat::from_rotation_x(0.5 * t * t)
        };
        // The true w(t) = ½ω by a fine central difference of the closed form.
        let w = |t: f64| {
            let e = 1e-5;
            let d = (q(t + e) - q(t - e)) / (2.0 * e);
            let v = d * q(t).conjugate();
            DVec3::new(v.x, v.y, v.z)
        };
        for uneven in [false, true] {
            let error = |h: f64, rule: TangentRule| {
                let n = (2.0 / h).round() as usize + 1;
                let times: Vec<f64> = (0..n)
                    .map(|k| {
                        let jitter = if uneven && k % 2 == 1 { 0.3 * h } else { 0.0 };
                        k as f64 * h + jitter
                    })
                    .collect();
                let quats: Vec<DQuat> = times.iter().map(|&t| q(t)).collect();
                let k = knots(&times, &quats, rule);
                (3..n - 3)
                    .map(|i| (k.w[i] - w(times[i])).length())
                    .fold(0.0, f64::max)
            };
            let curve_error = |h: f64| {
                let n = (2.0 / h).round() as usize + 1;
                let times: Vec<f64> = (0..n)
                    .map(|k| k as f64 * h + if uneven && k % 2 == 1 { 0.3 * h } else { 0.0 })
                    .collect();
                let quats: Vec<DQuat> = times.iter().map(|&t| q(t)).collect();
                let track = Track::new(times, quats).expect("a valid track");
                let curve =
                    crate::Curve::new(&track, &crate::CurveOptions::default()).expect("a curve");
                (0..=400)
                    .map(|j| 0.5 + j as f64 / 400.0)
                    .map(|t| crate::rotation::arc::s3_angle(curve.rotation(t), q(t)))
                    .fold(0.0, f64::max)
            };
            let measured = (curve_error(0.1) / curve_error(0.05)).log2();
            assert!(
                (measured - 4.0).abs() < 0.35,
                "curve, uneven {uneven}: {measured}"
            );
            // Uneven keys lose the spline's superconvergence at its knots (h³), which the
            // curve's legs multiply by their length: the curve stays fourth order (below).
            // Nam & Kim's quotient over the whole span is first order on uneven keys.
            let (spline, nam_kim) = if uneven { (3.0, 1.0) } else { (4.0, 2.0) };
            for (rule, order) in [
                (TangentRule::Spline, spline),
                (TangentRule::NamKim, nam_kim),
            ] {
                let ratio = error(0.1, rule) / error(0.05, rule);
                let measured = ratio.log2();
                assert!(
                    (measured - order).abs() < 0.35,
                    "{rule} uneven {uneven}: order {measured}"
                );
            }
        }
    }

    /// The uniform full-window weights of the module documentation.
    #[test]
    fn uniform_seven_keys_give_the_closed_form() {
        let y: [DVec3; 7] = std::array::from_fn(|k| {
            let k = k as f64;
            DVec3::new((1.3 * k).sin(), k * k * 0.1 - 0.7, (0.4 * k).cos() * 2.0)
        });
        let l = |k: i32| y[(k + 3) as usize] - y[3];
        let rel: Vec<DVec3> = (0..7).map(|k| l(k - 3)).collect();
        let h = 0.125;
        let want = ((l(1) - l(-1)) * 37.0 - (l(2) - l(-2)) * 8.0 + (l(3) - l(-3))) / (48.0 * h);
        let got = slope(&[h; 6], &rel, 3);
        assert!((got - want).length() < 1e-12, "{got} vs {want}");
    }

    /// A cubic through any window is its own not-a-knot spline: its derivative comes back
    /// exactly, at every inner point of 4 to 7 uneven points; three points give the parabola's.
    #[test]
    fn cubics_and_parabolas_are_reproduced() {
        let p = |x: f64| DVec3::new(x * x * x - 2.0 * x, 0.5 * x * x + 3.0, -x * x * x + x);
        let dp = |x: f64| DVec3::new(3.0 * x * x - 2.0, x, -3.0 * x * x + 1.0);
        let xs = [-1.7, -1.1, -0.2, 0.05, 0.9, 2.6, 2.7];
        for m in 4..=7 {
            let x = &xs[..m];
            let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
            let y: Vec<DVec3> = x.iter().map(|&x| p(x)).collect();
            for (c, &xc) in x.iter().enumerate().take(m - 1).skip(1) {
                let got = slope(&h, &y, c);
                assert!((got - dp(xc)).length() < 1e-11, "m {m} c {c}: {got}");
            }
        }
        let q = |x: f64| DVec3::new(x * x, 1.0 - 3.0 * x * x + x, 2.0 * x);
        let dq = |x: f64| DVec3::new(2.0 * x, -6.0 * x + 1.0, 2.0);
        let x = [0.3, 0.35, 1.9];
        let y = x.map(q);
        let got = slope(&[0.05, 1.55], &y, 1);
        assert!((got - dq(0.35)).length() < 1e-12, "{got}");
    }
}
