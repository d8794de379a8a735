//! Great arcs of S³ and their generation by forward differences (Nam & Kim, §3).
//!
//! An arc is `C(u) = cos(α + βu)·p + sin(α + βu)·e` with `p`, `e` orthonormal in R⁴: a great
//! circle traversed at constant angular speed `β` per unit `u`. Hermite's `C₁`, `C₂`, squad's
//! outer slerps, Bézier's first-level arcs and slerp itself are such arcs.
//!
//! ## Forward differences
//! Points `q_j = C(u₀ + jδ)` satisfy `q_{j+1} − 2q_j + q_{j−1} = −s·q_j` with
//! `s = 2(1 − cos βδ) = 4 sin²(βδ/2)`, so with `d_j = q_{j+1} − q_j`:
//!
//! ```text
//! q_{j+1} = q_j + d_j,     d_j = d_{j−1} − s·q_j          (4 multiply-adds a component)
//! ```
//!
//! Two changes from the paper keep this at f64 round-off instead of drifting as n²:
//! `s = 4 sin²(βδ/2)` (the paper's `2(1 − cos βδ)` cancels: for βδ = 1e-4 it keeps only 8
//! digits), and the first difference is built without subtraction,
//! `d₀ = C(u₀+δ) − C(u₀) = 2 sin(βδ/2)·(−sin(φ₀ + βδ/2)·p + cos(φ₀ + βδ/2)·e)`, `φ₀ = α + βu₀`.
//! Measured drift against direct evaluation: see `docs/schemes.md` (test
//! `forward_differences_stay_within_bound`).

use glam::DQuat;

/// A great arc of S³ (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Arc {
    p: DQuat,
    e: DQuat,
    alpha: f64,
    beta: f64,
}

/// Below this 4D norm a tangent counts as zero (the arc is a point).
pub(crate) const TINY: f64 = 1e-300;

impl Arc {
    /// The constant "arc" at `p`.
    pub(crate) fn point(p: DQuat) -> Arc {
        Arc {
            p,
            e: DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0),
            alpha: 0.0,
            beta: 0.0,
        }
    }

    /// The geodesic from `a` (u = 0) to `b` (u = 1) on S³, without hemisphere flip: when
    /// `a·b < 0` it is longer than a quarter circle (the long way round in SO(3)). For antipodal
    /// points it turns about the world x axis, the choice [`crate::rotation::quat::log`] makes
    /// for `−1`.
    pub(crate) fn between(a: DQuat, b: DQuat) -> Arc {
        let d = a.dot(b);
        let perp = b - a * d;
        let s = perp.length();
        if s < TINY {
            if d >= 0.0 {
                return Arc::point(a);
            }
            let e = DQuat::from_xyzw(1.0, 0.0, 0.0, 0.0) * a;
            return Arc {
                p: a,
                e,
                alpha: 0.0,
                beta: std::f64::consts::PI,
            };
        }
        Arc {
            p: a,
            e: perp / s,
            alpha: 0.0,
            beta: s.atan2(d),
        }
    }

    /// The arc from `a` (u = 0) to `b` (u = 1) whose step is the branch of `log(b a⁻¹)` nearest
    /// `target` (`log_near`): `exp(u·X)·a`. With `--path euler` the arcs
    /// inside a segment that stand in for part of a spin take it, so they keep its turns.
    pub(crate) fn near(a: DQuat, b: DQuat, target: glam::DVec3) -> Arc {
        let x = crate::rotation::quat::log_near(b * a.conjugate(), target);
        Arc::leaving(a, crate::rotation::quat::pure_mul(x, a))
    }

    /// The arc leaving `q` at u = 0 with velocity `v` (a tangent at `q`, `v·q = 0`):
    /// `C(u) = cos(‖v‖u)·q + sin(‖v‖u)·v̂` (Nam & Kim's `C₁`).
    pub(crate) fn leaving(q: DQuat, v: DQuat) -> Arc {
        let theta = v.length();
        if theta < TINY {
            return Arc::point(q);
        }
        Arc {
            p: q,
            e: v / theta,
            alpha: 0.0,
            beta: theta,
        }
    }

    /// The arc arriving at `q` at u = 1 with velocity `v`:
    /// `C(u) = cos(‖v‖(1−u))·q − sin(‖v‖(1−u))·v̂` (Nam & Kim's `C₂`).
    pub(crate) fn arriving(q: DQuat, v: DQuat) -> Arc {
        let theta = v.length();
        if theta < TINY {
            return Arc::point(q);
        }
        Arc {
            p: q,
            e: v / theta,
            alpha: -theta,
            beta: theta,
        }
    }

    /// The arc `cos(α + βu)·p + sin(α + βu)·e` from its parts (`p`, `e` orthonormal), as the
    /// lanes build four at once (`curve/bezier/lanes.rs`).
    pub(crate) fn from_parts(p: DQuat, e: DQuat, alpha: f64, beta: f64) -> Arc {
        Arc { p, e, alpha, beta }
    }

    /// The parts `(p, e, α, β)` ([`Arc::from_parts`]).
    pub(crate) fn parts(&self) -> (DQuat, DQuat, f64, f64) {
        (self.p, self.e, self.alpha, self.beta)
    }

    /// Total angle swept on S³ for u in [0, 1].
    pub(crate) fn span(&self) -> f64 {
        self.beta.abs()
    }

    /// Direct evaluation `C(u)`.
    #[inline]
    pub(crate) fn eval(&self, u: f64) -> DQuat {
        let (s, c) = (self.alpha + self.beta * u).sin_cos();
        self.p * c + self.e * s
    }

    /// Derivative `dC/du`.
    pub(crate) fn deriv(&self, u: f64) -> DQuat {
        let (s, c) = (self.alpha + self.beta * u).sin_cos();
        (self.e * c - self.p * s) * self.beta
    }

    /// The points `C(u₀ + jδ)`, j = 0, 1, 2, … by forward differences.
    #[inline]
    pub(crate) fn steps(&self, u0: f64, du: f64) -> ArcSteps {
        let h = self.beta * du;
        let half = 0.5 * h;
        let sh = half.sin();
        let (sp, cp) = (self.alpha + self.beta * u0 + half).sin_cos();
        ArcSteps {
            q: self.eval(u0),
            d: (self.e * cp - self.p * sp) * (2.0 * sh),
            s: 4.0 * sh * sh,
        }
    }
}

/// Iterator of an arc's points at equal steps (see [`Arc::steps`]). Never ends; take as many as
/// needed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArcSteps {
    q: DQuat,
    d: DQuat,
    s: f64,
}

impl ArcSteps {
    /// The next point (the iterator never ends).
    #[inline(always)]
    pub(crate) fn next_point(&mut self) -> DQuat {
        let out = self.q;
        self.q += self.d;
        self.d -= self.q * self.s;
        out
    }
}

impl Iterator for ArcSteps {
    type Item = DQuat;

    #[inline(always)]
    fn next(&mut self) -> Option<DQuat> {
        Some(self.next_point())
    }
}

/// Angle between two unit quaternions as points of S³ (not as rotations).
pub(crate) fn s3_angle(a: DQuat, b: DQuat) -> f64 {
    (a - b).length().atan2((a + b).length()) * 2.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rotation::quat;
    use glam::DVec3;

    /// Forward-difference drift against direct evaluation, as quoted in docs/schemes.md
    /// (`cargo test --release -p inbetween --lib drift -- --nocapture` prints the table): for one
    /// great arc of 4 rad on S³, the largest 4D distance between the recurrence and `C(u)`
    /// evaluated directly, for this formulation (`s = 4 sin²(h/2)`, first difference without
    /// subtraction) and the paper's (`s = 2(1 − cos h)`, `d₀ = C(δ) − C(0)`), at 10² … 10⁶ steps.
    #[test]
    fn drift_stays_far_below_the_papers_formulation() {
        let a = DQuat::from_rotation_x(0.2);
        let b = DQuat::from_axis_angle(DVec3::new(0.0, 0.6, 0.8), 4.0);
        let arc = Arc::between(a, b);
        println!("steps      ours        paper");
        for n in [100usize, 1_000, 10_000, 100_000, 1_000_000] {
            let du = 1.0 / n as f64;
            let ours = arc
                .steps(0.0, du)
                .take(n + 1)
                .enumerate()
                .map(|(j, q)| (q - arc.eval(j as f64 * du)).length())
                .fold(0.0, f64::max);
            let h = arc.span() * du;
            let s = 2.0 * (1.0 - h.cos());
            let (mut q, mut d) = (arc.eval(0.0), arc.eval(du) - arc.eval(0.0));
            let mut paper: f64 = 0.0;
            for j in 0..=n {
                paper = paper.max((q - arc.eval(j as f64 * du)).length());
                q += d;
                d -= q * s;
            }
            println!("{n:<9}  {ours:.2e}    {paper:.2e}");
            assert!(ours < 2e-13, "{n} steps: {ours:e}");
            if n >= 1_000 {
                assert!(
                    ours * 100.0 < paper,
                    "{n} steps: {ours:e} against {paper:e}"
                );
            }
        }
    }

    #[test]
    fn between_hits_both_ends() {
        let a = DQuat::from_rotation_y(0.3);
        let b = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 2.0) / 3.0, 2.0);
        let arc = Arc::between(a, b);
        assert!((arc.eval(0.0) - a).length() < 1e-15);
        assert!((arc.eval(1.0) - b).length() < 1e-15);
        let mid = quat::geodesic(a, b, 0.37);
        assert!((arc.eval(0.37) - mid).length() < 1e-15);
    }

    #[test]
    fn leaving_and_arriving_have_the_given_velocity() {
        let q = DQuat::from_rotation_z(0.4);
        let v = quat::pure_mul(DVec3::new(0.3, -0.2, 0.5), q);
        let c1 = Arc::leaving(q, v);
        assert!((c1.eval(0.0) - q).length() < 1e-15);
        assert!((c1.deriv(0.0) - v).length() < 1e-15);
        let c2 = Arc::arriving(q, v);
        assert!((c2.eval(1.0) - q).length() < 1e-15);
        assert!((c2.deriv(1.0) - v).length() < 1e-15);
    }

    #[test]
    fn antipodal_between_is_a_half_circle() {
        let a = DQuat::from_rotation_z(0.4);
        let arc = Arc::between(a, -a);
        assert!((arc.eval(1.0) + a).length() < 1e-15);
        assert!((arc.eval(0.5).length() - 1.0).abs() < 1e-15);
    }

    /// Largest distance between forward differences and direct evaluation over `n` steps.
    fn drift(arc: &Arc, n: usize) -> f64 {
        let du = 1.0 / n as f64;
        let u0 = 0.3 * du;
        arc.steps(u0, du)
            .take(n)
            .enumerate()
            .map(|(j, q)| (q - arc.eval(u0 + j as f64 * du)).length())
            .fold(0.0, f64::max)
    }

    #[test]
    fn forward_differences_stay_within_bound() {
        let a = DQuat::from_rotation_x(0.2);
        let b = DQuat::from_axis_angle(DVec3::new(0.0, 0.6, 0.8), 2.5);
        for arc in [
            Arc::between(a, b),
            Arc::between(a, -b),
            Arc::arriving(b, a * 3.0),
        ] {
            assert!(drift(&arc, 10) < 1e-15);
            assert!(drift(&arc, 1_000) < 1e-14, "{}", drift(&arc, 1_000));
            assert!(drift(&arc, 10_000) < 1e-13, "{}", drift(&arc, 10_000));
        }
    }

    #[test]
    fn papers_s_drifts_more() {
        // The paper's s = 2(1 − cos βδ) with a first step by subtraction, for comparison.
        let arc = Arc::between(DQuat::IDENTITY, DQuat::from_rotation_z(2.0));
        let n = 10_000;
        let du = 1.0 / n as f64;
        let h = arc.beta * du;
        let s = 2.0 * (1.0 - h.cos());
        let mut q = arc.eval(0.0);
        let mut d = arc.eval(du) - q;
        let mut worst: f64 = 0.0;
        for j in 0..n {
            worst = worst.max((q - arc.eval(j as f64 * du)).length());
            q += d;
            d -= q * s;
        }
        assert!(worst > 100.0 * drift(&arc, n), "paper {worst:e}");
    }
}
