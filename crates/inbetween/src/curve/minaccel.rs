//! `minaccel`: the minimal-tangential-acceleration spline of Barr, Currin, Gabriel & Hughes
//! (SIGGRAPH '92, §4.2–§4.4, DOI 10.1145/133994.134086; docs/spec.md, References),
//! solved by Newton's method on the product of spheres with a banded linear solve.
//!
//! ## The problem
//! On a grid `t_0 < … < t_N` that contains every key (segment `i` split into
//! `N_i = max(1, ⌈Δ_i·fps⌉)` equal steps), find unit quaternions `q_p` equal to the keys at key
//! points that minimise the discrete tangential acceleration
//!
//! ```text
//! E = Σ_p w_p |q_p'' ∖ q_p|²,   a ∖ b = a − (a·b)/(b·b)·b
//! q_p'' = 2[(q_{p+1} − q_p)/h₊ − (q_p − q_{p−1})/h₋]/(h₋ + h₊),   w_p = (h₋ + h₊)/2
//! ```
//! (the paper's `h Σ |(q_{p+1} − 2q_p + q_{p−1})/h² ∖ q_p|²` for equal steps). The sum runs over
//! points with two neighbours. A given end velocity ω (or `--ends rest`, ω = 0) adds the paper's
//! phantom point `Q⁰ = exp(−h_first·ω/2)·Q¹` before the first key (and `Q^{K+1} =
//! exp(h_last·ω/2)·Q^K` after the last), fixed, so the first key gets a term too; otherwise the
//! ends are free (natural).
//!
//! ## The solver
//! Each free point moves in its tangent space: `q ← exp(δ)·q`, `δ ∈ R³` (a pure quaternion), so
//! the unknowns are 3 per point and every iterate is exactly unit. Each term
//! `E_p = w_p(|A_p|² − (A_p·q_p)²)`, `A_p = α q_{p−1} + β q_p + γ q_{p+1}`, touches three
//! neighbouring points, so the exact Hessian is block-pentadiagonal (3×3 blocks, half-bandwidth
//! 8): Newton's method, assembled and factorised in O(n) per iteration with `banded.rs`
//! (a multiple of the identity is added only while the Hessian is not positive definite). A
//! backtracking line search on `E` keeps every step a descent (where the Hessian is not positive
//! definite, far from a minimum, the step uses the Gauss–Newton matrix instead, which is); once
//! the predicted decrease is
//! below what `E` resolves in f64, full steps are taken while the gradient keeps shrinking. The
//! start is the `hermite` curve on the grid. It stops when the projected gradient `‖Jᵀr‖` is ≤ 1e-9 of its value at the
//! start (or ≤ 1e-14), and reports when it does not within `MAX_ITERATIONS`.
//!
//! The grid is refined where neighbouring points of the start curve would be more than 45° apart
//! on S³ (the paper's §5 keeps them within 90° against aliasing), and so that a phantom point
//! is within 45° of its key.
//!
//! Frames between grid points are the slerp of the neighbouring grid points; a frame on a grid
//! point is that point.

use super::banded::Banded;
use super::hermite::Hermite;
use super::{Blend, Segment};
use crate::error::{InputError, InputResult, Setting};
use crate::rotation::quat::exp;
use crate::tangent::Knots;
use glam::{DQuat, DVec3, DVec4};
use std::f64::consts::FRAC_PI_4;

/// Largest grid the solver accepts (about 300 bytes a point while solving).
pub(crate) const MAX_GRID_POINTS: usize = 2_000_000;

/// Iteration budget of the Newton solver.
pub(crate) const MAX_ITERATIONS: usize = 100;
/// Relative projected-gradient tolerance (docs/spec.md §4.4). A gradient at the f64 rounding floor of
/// its own computation also counts as converged (e.g. when the start is already the optimum).
pub(crate) const REL_TOL: f64 = 1e-9;
/// Absolute projected-gradient tolerance (docs/spec.md §4.4).
pub(crate) const ABS_TOL: f64 = 1e-14;

/// A cyclic track is solved on its loop repeated until at least this many keys stand on each
/// side of the middle period ([`solve`]).
pub(crate) const SEAM_KEYS: usize = 40;

/// What the solver did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Report {
    /// Grid points.
    pub points: usize,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Energy `E` of the starting curve.
    pub energy_start: f64,
    /// Energy `E` of the result.
    pub energy: f64,
    /// Norm of the projected gradient at the start.
    pub gradient_start: f64,
    /// Norm of the projected gradient at the result.
    pub gradient: f64,
    /// The gradient fell to `REL_TOL` of its start (or to the f64 floor, `ABS_TOL`).
    pub converged: bool,
}

/// The solved curve of one track: grid times and points.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Grid times, s (the keys' times among them).
    pub times: Vec<f64>,
    /// The curve's points at the grid times, unit quaternions.
    pub points: Vec<DQuat>,
    /// What the solver did.
    pub report: Report,
}

/// The grid and its fixed points: `ext` holds the optional phantom points around the grid.
#[derive(Debug, Clone)]
pub struct Problem {
    /// Times of the extended sequence (phantoms at `t_0 − h_first`, `t_N + h_last`).
    times: Vec<f64>,
    /// Points of the extended sequence.
    pts: Vec<DQuat>,
    fixed: Vec<bool>,
    /// Index of the first grid point in the extended sequence (1 with a start phantom).
    first: usize,
    /// Number of grid points.
    grid_len: usize,
}

/// Steps per segment: `max(1, ⌈Δ·fps⌉)` (1e-6 slack so that keys on the frame grid give the frame
/// grid itself).
fn base_steps(keys: &Knots, fps: f64) -> Vec<usize> {
    (0..keys.segments())
        .map(|i| ((keys.delta(i) * fps - 1e-6).ceil().max(1.0)) as usize)
        .collect()
}

/// S³ angle between unit quaternions.
fn s3_angle(a: DQuat, b: DQuat) -> f64 {
    crate::rotation::arc::s3_angle(a, b)
}

impl Problem {
    /// The grid for `keys` at `fps` frames per second, started on the hermite curve. Fails when
    /// the grid would need more than `MAX_GRID_POINTS` points (a very high rate, or end
    /// velocities of very many turns per segment).
    pub fn new(keys: &Knots, fps: f64) -> InputResult<Problem> {
        let too_many = |steps: &[usize]| {
            let total = steps.iter().fold(1usize, |a, &b| a.saturating_add(b));
            (total > MAX_GRID_POINTS).then(|| {
                InputError::new(crate::message![
                    format!(
                        "minaccel would need a grid of {total} points (at most \
                         {MAX_GRID_POINTS}): lower "
                    ),
                    Setting::FrameRate,
                    " or the end velocities, or use another scheme"
                ])
            })
        };
        let mut steps = base_steps(keys, fps);
        let n = keys.quats.len();
        // A key's own velocity fixes the grid points beside it: at least two steps in each
        // segment next to it, three when both ends of the segment are held.
        let held = |i: usize| keys.shaped[i] && i > 0 && i < n - 1;
        for (s, st) in steps.iter_mut().enumerate() {
            let need = 1 + usize::from(held(s)) + usize::from(held(s + 1));
            *st = (*st).max(need);
        }
        // Phantoms keep within 45° of their keys (S³ angle h·|ω|/2).
        if keys.start_given {
            let need = (keys.delta(0) * keys.w[0].length() / FRAC_PI_4).ceil() as usize;
            steps[0] = steps[0].max(need);
        }
        if keys.end_given {
            let s = n - 2;
            let need = (keys.delta(s) * keys.w[n - 1].length() / FRAC_PI_4).ceil() as usize;
            steps[s] = steps[s].max(need);
        }
        if let Some(e) = too_many(&steps) {
            return Err(e);
        }
        // Enough steps that the start curve moves at most 45° on S³ per step: a segment of the
        // hermite curve is no longer than its two arcs and its chord. Then up to three passes
        // refine where sampled neighbours are still further apart (a blend that passes near an
        // antipode can make the start curve jump, which no refinement removes).
        for (s, st) in steps.iter_mut().enumerate() {
            let bound = keys.tangent(s, s).length()
                + keys.tangent(s + 1, s).length()
                + keys.chord_length(s);
            let need = (bound / FRAC_PI_4).ceil();
            if need > *st as f64 {
                *st = if need < MAX_GRID_POINTS as f64 {
                    need as usize
                } else {
                    MAX_GRID_POINTS
                };
            }
        }
        if let Some(e) = too_many(&steps) {
            return Err(e);
        }
        let mut pass = 0;
        let (times, pts, is_key) = loop {
            let (times, pts, is_key) = sample_hermite(keys, &steps);
            pass += 1;
            if pass > 3 {
                break (times, pts, is_key);
            }
            let mut double = vec![false; steps.len()];
            let mut seg = 0;
            for p in 0..pts.len() - 1 {
                if is_key[p] && p > 0 {
                    seg += 1;
                }
                double[seg] |= s3_angle(pts[p], pts[p + 1]) > FRAC_PI_4;
            }
            let refined = double.iter().any(|&d| d);
            for (st, d) in steps.iter_mut().zip(double) {
                if d {
                    *st = st.saturating_mul(2);
                }
            }
            if let Some(e) = too_many(&steps) {
                return Err(e);
            }
            if !refined {
                break (times, pts, is_key);
            }
        };
        let mut ext_t = Vec::with_capacity(times.len() + 2);
        let mut ext_q = Vec::with_capacity(times.len() + 2);
        let mut fixed = Vec::with_capacity(times.len() + 2);
        let mut first = 0;
        if keys.start_given {
            let h = times[1] - times[0];
            ext_t.push(times[0] - h);
            ext_q.push(exp(-keys.w[0] * h) * keys.quats[0]);
            fixed.push(true);
            first = 1;
        }
        ext_t.extend_from_slice(&times);
        ext_q.extend_from_slice(&pts);
        fixed.extend_from_slice(&is_key);
        if keys.end_given {
            let m = times.len();
            let h = times[m - 1] - times[m - 2];
            ext_t.push(times[m - 1] + h);
            ext_q.push(exp(keys.w[n - 1] * h) * keys.quats[n - 1]);
            fixed.push(true);
        }
        // Interior keys with their own velocity ω: the neighbours are exp(∓h·ω/2)·q, fixed.
        let mut key = 0;
        for p in 0..times.len() {
            if !is_key[p] {
                continue;
            }
            if held(key) {
                let (e, w_in, w_out) = (first + p, keys.w_in[key], keys.w[key]);
                let q = keys.quats[key];
                ext_q[e - 1] = exp(-w_in * (times[p] - times[p - 1])) * q;
                ext_q[e + 1] = exp(w_out * (times[p + 1] - times[p])) * q;
                fixed[e - 1] = true;
                fixed[e + 1] = true;
            }
            key += 1;
        }
        Ok(Problem {
            times: ext_t,
            pts: ext_q,
            fixed,
            first,
            grid_len: times.len(),
        })
    }

    /// Grid times (without phantoms).
    pub fn grid_times(&self) -> &[f64] {
        &self.times[self.first..self.first + self.grid_len]
    }

    /// Grid points (without phantoms).
    pub fn grid_points(&self) -> &[DQuat] {
        &self.pts[self.first..self.first + self.grid_len]
    }

    /// `E` of other points on the same grid (with the same phantoms): for comparing schemes.
    pub fn energy_of(&self, grid_points: &[DQuat]) -> f64 {
        let mut pts = self.pts.clone();
        pts[self.first..self.first + self.grid_len].copy_from_slice(grid_points);
        energy(&self.times, &pts)
    }

    /// Solves in place and returns the solution.
    pub fn solve(mut self) -> Solution {
        let report = newton(&self.times, &mut self.pts, &self.fixed);
        Solution {
            times: self.grid_times().to_vec(),
            points: self.grid_points().to_vec(),
            report,
        }
    }
}

/// The hermite curve sampled on a grid of `steps[i]` equal steps per segment: times, points,
/// and which points are keys.
fn sample_hermite(keys: &Knots, steps: &[usize]) -> (Vec<f64>, Vec<DQuat>, Vec<bool>) {
    let total: usize = steps.iter().sum::<usize>() + 1;
    let mut times = Vec::with_capacity(total);
    let mut pts = Vec::with_capacity(total);
    let mut is_key = Vec::with_capacity(total);
    for (s, &ns) in steps.iter().enumerate() {
        let seg = Hermite::new(keys, s, Blend::Cubic);
        let (t0, d) = (keys.times[s], keys.delta(s));
        times.push(t0);
        pts.push(keys.quats[s]);
        is_key.push(true);
        if ns > 1 {
            let du = 1.0 / ns as f64;
            for (j, q) in seg.frames(du, du).take(ns - 1).enumerate() {
                times.push(t0 + d * (j + 1) as f64 * du);
                pts.push(q.normalize());
                is_key.push(false);
            }
        }
    }
    times.push(*keys.times.last().expect("two keys"));
    pts.push(*keys.quats.last().expect("two keys"));
    is_key.push(true);
    (times, pts, is_key)
}

/// Three-point coefficients `(α, β, γ)` of `q''` and the weight `w` for steps `hm`, `hp`.
#[inline]
fn stencil(hm: f64, hp: f64) -> (f64, f64, f64, f64) {
    let s = hm + hp;
    let a = 2.0 / (hm * s);
    let c = 2.0 / (hp * s);
    (a, -(a + c), c, 0.5 * s)
}

#[inline]
fn v4(q: DQuat) -> DVec4 {
    DVec4::new(q.x, q.y, q.z, q.w)
}

/// `E` of an extended sequence.
pub fn energy(times: &[f64], pts: &[DQuat]) -> f64 {
    let mut e = 0.0;
    for p in 1..pts.len().saturating_sub(1) {
        let (a, b, c, w) = stencil(times[p] - times[p - 1], times[p + 1] - times[p]);
        let acc = v4(pts[p - 1]) * a + v4(pts[p]) * b + v4(pts[p + 1]) * c;
        let q = v4(pts[p]);
        let tang = acc - q * (acc.dot(q) / q.dot(q));
        e += w * tang.length_squared();
    }
    e
}

/// Tangent basis at `q`: `i·q`, `j·q`, `k·q` (orthonormal, orthogonal to `q`).
#[inline]
fn basis(q: DQuat) -> [DVec4; 3] {
    [
        v4(DQuat::from_xyzw(1.0, 0.0, 0.0, 0.0) * q),
        v4(DQuat::from_xyzw(0.0, 1.0, 0.0, 0.0) * q),
        v4(DQuat::from_xyzw(0.0, 0.0, 1.0, 0.0) * q),
    ]
}

/// One neighbour's part of a term: unknown index, `M_a` columns, `v_a`, diagonal shift.
type Block = (usize, [DVec4; 3], DVec3, f64);

/// Assembles the exact Hessian `H` (banded) and gradient `g` of `E` in the tangent coordinates
/// of the free points; returns `E` and the rounding-noise floor of `‖g‖`.
///
/// For unit `q_p`, `E_p = w(|A|² − s²)` with `A = α q_{p−1} + β q_p + γ q_{p+1}`, `s = A·q_p`.
/// With `q_a ← exp(δ_a)·q_a = q_a + T_a δ_a − ½|δ_a|² q_a + …` (`T_a = [i q_a, j q_a, k q_a]`),
/// `M_a = k_a T_a`, `v_a = M_aᵀ q_p` (plus `T_pᵀ A` for `a = p`), `N_a = T_p` for `a = p` else 0:
///
/// ```text
/// g_a  = 2w (M_aᵀ A − s v_a)
/// H_ab = 2w (M_aᵀ M_b − v_a v_bᵀ − s (M_aᵀ N_b + N_aᵀ M_b))
///      + 2w (−k_a A·q_a + s k_a q_a·q_p + [a = p] s²) I   on diagonal blocks
/// ```
/// The noise floor: each term is a sum of parts as large as `w·(|α|+|β|+|γ|)²`, so rounding
/// leaves about ε times that in each gradient entry.
///
/// With `gauss_newton` the matrix is instead `2JᵀJ` for the residuals
/// `r_p = √w (A − s q_p)`, `J_a = √w (M_a − q_p v_aᵀ − s N_a)`: positive semi-definite, with the
/// same gradient, for iterations where the exact Hessian is not positive definite.
fn assemble(
    times: &[f64],
    pts: &[DQuat],
    unknown: &[Option<usize>],
    h: &mut Banded,
    g: &mut [f64],
    gauss_newton: bool,
) -> (f64, f64) {
    h.clear();
    g.fill(0.0);
    let mut e = 0.0;
    let mut floor2 = 0.0;
    for p in 1..pts.len() - 1 {
        let (a, b, c, w) = stencil(times[p] - times[p - 1], times[p + 1] - times[p]);
        let q = v4(pts[p]);
        let qs = [v4(pts[p - 1]), q, v4(pts[p + 1])];
        let ks = [a, b, c];
        let acc = qs[0] * a + q * b + qs[2] * c;
        let s = acc.dot(q);
        let tang = acc - q * s;
        e += w * tang.length_squared();
        let scale = w * (a.abs() + b.abs() + c.abs()).powi(2) * f64::EPSILON;
        floor2 += scale * scale;
        let two_w = 2.0 * w;
        let tp = basis(pts[p]);
        // Per neighbour: unknown index, M_a columns, v_a, diagonal shift.
        let mut blocks: [Option<Block>; 3] = [None; 3];
        for (slot, off) in blocks.iter_mut().zip(0..3) {
            let Some(u) = unknown[p + off - 1] else {
                continue;
            };
            let t = if off == 1 {
                tp
            } else {
                basis(pts[p + off - 1])
            };
            let m = t.map(|col| col * ks[off]);
            let mut v = DVec3::new(m[0].dot(q), m[1].dot(q), m[2].dot(q));
            let mut shift = -ks[off] * acc.dot(qs[off]) + s * ks[off] * qs[off].dot(q);
            if off == 1 {
                v += DVec3::new(tp[0].dot(acc), tp[1].dot(acc), tp[2].dot(acc));
                shift += s * s;
            }
            for i in 0..3 {
                g[3 * u + i] += two_w * (m[i].dot(acc) - s * v[i]);
            }
            *slot = Some((u, m, v, shift));
        }
        for (ia, ba) in blocks.iter().enumerate() {
            let Some((ua, ma, va, shift)) = ba else {
                continue;
            };
            for (ib, bb) in blocks.iter().enumerate() {
                let Some((ub, mb, vb, _)) = bb else {
                    continue;
                };
                if ub > ua {
                    continue;
                }
                for i in 0..3 {
                    for j in 0..3 {
                        let (ri, cj) = (3 * ua + i, 3 * ub + j);
                        if cj > ri {
                            continue;
                        }
                        let x = if gauss_newton {
                            let col = |m: &[DVec4; 3], v: DVec3, k: usize, a: usize| {
                                let c = m[k] - q * v[k];
                                if a == 1 { c - tp[k] * s } else { c }
                            };
                            col(ma, *va, i, ia).dot(col(mb, *vb, j, ib))
                        } else {
                            let mut x = ma[i].dot(mb[j]) - va[i] * vb[j];
                            if ib == 1 {
                                x -= s * ma[i].dot(tp[j]);
                            }
                            if ia == 1 {
                                x -= s * tp[i].dot(mb[j]);
                            }
                            if ia == ib && i == j {
                                x += shift;
                            }
                            x
                        };
                        h.add(ri, cj, two_w * x);
                    }
                }
            }
        }
    }
    (e, 16.0 * floor2.sqrt())
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Newton's method with a banded solve and backtracking line search (see the module docs).
fn newton(times: &[f64], pts: &mut [DQuat], fixed: &[bool]) -> Report {
    let mut unknown = vec![None; pts.len()];
    let mut m = 0;
    for (p, f) in fixed.iter().enumerate() {
        if !f {
            unknown[p] = Some(m);
            m += 1;
        }
    }
    let e0 = energy(times, pts);
    let mut report = Report {
        points: pts.len(),
        iterations: 0,
        energy_start: e0,
        energy: e0,
        gradient_start: 0.0,
        gradient: 0.0,
        converged: true,
    };
    if m == 0 {
        return report;
    }
    let mut h = Banded::zeros(3 * m, 8);
    let mut g = vec![0.0; 3 * m];
    let mut step = vec![0.0; 3 * m];
    let mut trial = pts.to_vec();
    let mut previous: Option<(Vec<DQuat>, f64)> = None;
    let done = |gn: f64, g0: f64, floor: f64| gn <= REL_TOL * g0 || gn <= ABS_TOL.max(floor);
    for it in 0..=MAX_ITERATIONS {
        let (e, floor) = assemble(times, pts, &unknown, &mut h, &mut g, false);
        let gn = norm(&g);
        if it == 0 {
            report.gradient_start = gn;
        }
        // A step taken without line search that did not shrink the gradient: undo it and stop.
        if let Some((before, gn_before)) = previous.take()
            && gn >= gn_before
        {
            pts.copy_from_slice(&before);
            break;
        }
        report.iterations = it;
        report.energy = e;
        report.gradient = gn;
        if done(gn, report.gradient_start, floor) {
            report.converged = true;
            return report;
        }
        if it == MAX_ITERATIONS {
            break;
        }
        // Newton's step where the Hessian is positive definite. Otherwise the Gauss–Newton
        // matrix 2JᵀJ (positive semi-definite, same gradient), with μ·s·I added (s its largest
        // diagonal entry) only while that still fails to factorise.
        let mut factored = h.clone();
        let factored = if factored.cholesky() {
            Some(factored)
        } else {
            assemble(times, pts, &unknown, &mut h, &mut g, true);
            let diag_scale = (0..3 * m)
                .map(|i| h.get(i, i).abs())
                .fold(f64::MIN_POSITIVE, f64::max);
            let mut damping = 0.0;
            loop {
                let mut hd = h.clone();
                if damping > 0.0 {
                    for i in 0..3 * m {
                        hd.add(i, i, damping * diag_scale);
                    }
                }
                if hd.cholesky() {
                    break Some(hd);
                }
                damping = if damping == 0.0 {
                    1e-12
                } else {
                    damping * 10.0
                };
                if damping > 1e3 {
                    break None;
                }
            }
        };
        let Some(factor) = factored else { break };
        for (s, gi) in step.iter_mut().zip(&g) {
            *s = -gi;
        }
        factor.solve(&mut step);
        let slope = step.iter().zip(&g).map(|(a, b)| a * b).sum::<f64>();
        if -slope <= 1e-13 * e.max(f64::MIN_POSITIVE) {
            // The predicted decrease is below what E resolves in f64: take the full step and let
            // the gradient judge it at the next iteration.
            previous = Some((pts.to_vec(), gn));
            for (p, q) in pts.iter_mut().enumerate() {
                if let Some(u) = unknown[p] {
                    let d = DVec3::new(step[3 * u], step[3 * u + 1], step[3 * u + 2]);
                    *q = (exp(d) * *q).normalize();
                }
            }
            continue;
        }
        let mut t = 1.0;
        let mut accepted = false;
        for _ in 0..40 {
            for (p, q) in pts.iter().enumerate() {
                trial[p] = match unknown[p] {
                    Some(u) => {
                        let d = DVec3::new(step[3 * u], step[3 * u + 1], step[3 * u + 2]) * t;
                        (exp(d) * *q).normalize()
                    }
                    None => *q,
                };
            }
            let et = energy(times, &trial);
            if et <= e + 1e-4 * t * slope || (et <= e && t < 1e-6) {
                accepted = et <= e;
                break;
            }
            t *= 0.5;
        }
        if !accepted {
            break;
        }
        pts.copy_from_slice(&trial);
    }
    // Out of budget, or no descent is possible any more at f64 precision.
    let (e, floor) = assemble(times, pts, &unknown, &mut h, &mut g, false);
    report.energy = e;
    report.gradient = norm(&g);
    report.converged = done(report.gradient, report.gradient_start, floor);
    report
}

/// Solves the minaccel problem for a track at `fps` (`Prepared`, then `solve`).
pub fn solve(keys: &Knots, fps: f64) -> InputResult<Solution> {
    Ok(Prepared::new(keys, fps)?.solve())
}

/// A track's minaccel problem with its grid laid out and nothing iterated yet, so that a caller
/// can see the grid's size before paying for the solve.
///
/// A cyclic track solves the periodic problem (its seam an interior key like any other): the
/// loop is repeated until [`SEAM_KEYS`] keys stand on each side of a middle copy, the repeated
/// track is solved with free ends, and the middle copy is the answer. The effect of the far
/// free ends on it decays through every fixed key between them (by about 0.27 a key for a
/// cubic spline, at worst ½), so at 40 keys it is below f64 resolution; a test checks the middle
/// copy against its neighbours.
pub(crate) struct Prepared {
    problem: Problem,
    /// Copies of the loop in `problem` (1 for a track with ends).
    copies: usize,
    /// The span of the track's own keys: the middle copy of a loop.
    span: Option<(f64, f64)>,
}

impl Prepared {
    /// The problem of `keys` at `fps`: fails as [`Problem::new`] fails.
    pub(crate) fn new(keys: &Knots, fps: f64) -> InputResult<Prepared> {
        if !keys.cyclic {
            return Ok(Prepared {
                problem: Problem::new(keys, fps)?,
                copies: 1,
                span: None,
            });
        }
        let n = keys.quats.len();
        let segs = n - 1;
        let reps = SEAM_KEYS.div_ceil(segs);
        let period = keys.times[n - 1] - keys.times[0];
        // The loop ends on the first key's rotation, on the same or the opposite sheet of S³.
        let sign = if keys.quats[0].dot(keys.quats[n - 1]) < 0.0 {
            -1.0
        } else {
            1.0
        };
        let copies = 2 * reps + 1;
        let len = copies * segs + 1;
        let mut unrolled = Knots {
            times: Vec::with_capacity(len),
            quats: Vec::with_capacity(len),
            w: Vec::with_capacity(len),
            w_in: Vec::with_capacity(len),
            shaped: Vec::with_capacity(len),
            cyclic: false,
            start_given: false,
            end_given: false,
            chords: keys.chords.as_ref().map(|_| Vec::with_capacity(len - 1)),
        };
        for c in 0..copies {
            // The middle copy (c = reps) has the track's own times and signs exactly.
            let offset = (c as f64 - reps as f64) * period;
            let s = if (c + reps).is_multiple_of(2) {
                1.0
            } else {
                sign
            };
            if c > 0 {
                // The seam key is shared: it takes this copy's time, exact in the middle copy.
                let last = unrolled.times.len() - 1;
                unrolled.times[last] = keys.times[0] + offset;
            }
            for i in usize::from(c > 0)..n {
                unrolled.times.push(keys.times[i] + offset);
                unrolled.quats.push(keys.quats[i] * s);
                unrolled.w.push(keys.w[i]);
                unrolled.w_in.push(keys.w_in[i]);
                unrolled.shaped.push(keys.shaped[i]);
            }
            if let (Some(all), Some(own)) = (&mut unrolled.chords, &keys.chords) {
                all.extend_from_slice(own);
            }
        }
        Ok(Prepared {
            problem: Problem::new(&unrolled, fps)?,
            copies,
            span: Some((keys.times[0], keys.times[n - 1])),
        })
    }

    /// Whether the grid has at most `limit` points (a loop: per copy of the loop). `reduce`
    /// tests a segment within a limit ([`crate::reduce`]): a start curve that needs a finer grid
    /// than the frames turns more than a quarter turn between two of them, and its solve can
    /// take thousands of points and the whole iteration budget.
    pub(crate) fn fits(&self, limit: usize) -> bool {
        self.problem.grid_len <= limit.saturating_mul(self.copies)
    }

    /// Runs the Newton solver; a loop keeps its middle copy.
    pub(crate) fn solve(self) -> Solution {
        let whole = self.problem.solve();
        let Some((t0, t1)) = self.span else {
            return whole;
        };
        let lo = whole.times.partition_point(|&t| t < t0);
        let hi = whole.times.partition_point(|&t| t <= t1);
        let mut report = whole.report;
        report.points = hi - lo;
        Solution {
            times: whole.times[lo..hi].to_vec(),
            points: whole.points[lo..hi].to_vec(),
            report,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::test_support::keys;
    use crate::rotation::quat::geodesic;
    use crate::tangent::{EndConditions, Ends};

    #[test]
    fn two_keys_give_the_geodesic() {
        let q = [
            DQuat::IDENTITY,
            DQuat::from_axis_angle(DVec3::new(0.0, 0.6, 0.8), 2.0),
        ];
        let k = keys(&[0.0, 1.0], &q, EndConditions::default());
        let sol = solve(&k, 30.0).unwrap();
        assert!(sol.report.converged);
        assert!(sol.report.energy < 1e-20, "{:?}", sol.report);
        for (t, p) in sol.times.iter().zip(&sol.points) {
            assert!((*p - geodesic(q[0], q[1], *t)).length() < 1e-9);
        }
    }

    #[test]
    fn lowers_energy_below_hermite_and_converges() {
        let k = crate::curve::test_support::sample_keys();
        let problem = Problem::new(&k, 30.0).unwrap();
        let start = problem.energy_of(problem.grid_points());
        let sol = problem.solve();
        assert!(sol.report.converged, "{:?}", sol.report);
        assert!(sol.report.energy < start);
        assert!(sol.report.gradient <= 1e-9 * sol.report.gradient_start);
        for p in &sol.points {
            assert!((p.length() - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn absurd_velocity_is_an_error_not_an_allocation() {
        let q = [DQuat::IDENTITY, DQuat::IDENTITY];
        let ends = EndConditions {
            ends: Ends::Chord,
            start: Some(DVec3::new(0.0, 0.0, 1e12)),
            end: None,
        };
        let k = keys(&[0.0, 1.0], &q, ends);
        let e = solve(&k, 30.0).unwrap_err();
        assert!(
            e.message().starts_with("minaccel would need a grid of"),
            "{e}"
        );
    }

    #[test]
    fn rest_ends_have_phantoms() {
        let q = [DQuat::IDENTITY, DQuat::from_rotation_z(1.0)];
        let ends = EndConditions {
            ends: Ends::Rest,
            ..Default::default()
        };
        let k = keys(&[0.0, 1.0], &q, ends);
        let p = Problem::new(&k, 30.0).unwrap();
        assert_eq!(p.times.len(), 31 + 2);
        let sol = p.solve();
        assert!(sol.report.converged, "{:?}", sol.report);
        // Starts slowly: the first step is much shorter than the geodesic's.
        let first = s3_angle(sol.points[0], sol.points[1]);
        assert!(first < 0.2 * (0.5 / 30.0), "{first}");
    }
}
