//! `reduce`: the fewest keys that a scheme turns back into dense motion, within a tolerance
//! (docs/spec.md §5a, docs/reduce.md).
//!
//! Input: a track's frames (times, rotations, optional positions). Output: the indices of the
//! frames kept as keys — the first and last always — with, by default, each kept key's angular
//! velocity estimated from the frames, such that the curve of `scheme` through the kept keys
//! (with those velocities) reproduces **every** frame within the tolerance: the geodesic angle,
//! or with a distance `D` the displacement `2·D·sin(θ/2)` of a point `D` from the joint;
//! positions within their own tolerance.
//!
//! ## Methods
//! - **Greedy**: from each key, the farthest next key whose segment alone meets the tolerance,
//!   found by doubling then bisection (a segment with both end velocities given depends on its
//!   two keys only, for hermite, bezier, squad and slerp).
//! - **Optimal**: a shortest path over the frames, an edge `i → j` wherever the segment `i..j`
//!   alone meets the tolerance (segments up to [`optimal_window`] frames: twice greedy's longest
//!   segment on the track, at most [`OPTIMAL_WINDOW`]): the fewest keys whose segments each meet
//!   it. It is exactly minimal where segments are local — slerp, and hermite, bezier and squad
//!   with velocities — among key sets with segments of at most the window;
//!   elsewhere (minaccel, estimated tangents) its keys are then completed like greedy's, and
//!   where it would keep more keys than greedy, greedy's are kept.
//!
//! Both end with **verification**: the curve through the chosen keys is built exactly as
//! `interp` builds it ([`Curve`]), evaluated at every frame, and wherever a frame misses the
//! tolerance the worst frame of that segment becomes a key, until none misses. The result is
//! therefore guaranteed, whatever the scheme, and checked before it is returned.

use crate::curve::{Curve, CurveOptions, Scheme};
use crate::error::InputResult;
use crate::rotation::quat::{log, rotation_angle_between};
use crate::track::Track;
use glam::{DQuat, DVec3};

/// Longest segment (frames) the optimal method considers.
pub const OPTIMAL_WINDOW: usize = 600;

/// The optimal method considers segments up to this many times the longest segment of the
/// track's greedy keys ([`optimal_window`]).
pub const OPTIMAL_GREEDY_FACTOR: usize = 2;

/// How keys are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Farthest feasible next key, then verification (near-linear).
    #[default]
    Greedy,
    /// Fewest keys by shortest path over feasible segments, then verification.
    Optimal,
}

/// What `reduce` must guarantee and how.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReduceOptions {
    /// The curve the keys are for (scheme, ends, path, minaccel's grid rate).
    pub curve: CurveOptions,
    /// Largest rotation error, rad (or, with `distance`, a length).
    pub tolerance: f64,
    /// Measure the error as the displacement of a point this far from the joint.
    pub distance: Option<f64>,
    /// Largest position error (length units), for tracks with translations.
    pub translation_tolerance: Option<f64>,
    /// Give each key the frames' angular velocity at it.
    pub velocities: bool,
    /// Greedy or optimal.
    pub method: Method,
}

/// A reduced track.
#[derive(Debug, Clone, PartialEq)]
pub struct Reduced {
    /// Indices of the frames kept as keys, increasing; the first and last frame included.
    pub keys: Vec<usize>,
    /// The kept keys' angular velocities (rad/s, world frame), when asked for.
    pub velocities: Option<Vec<DVec3>>,
    /// Largest error over the frames (rad, or length with a distance).
    pub max_error: f64,
    /// Mean error over the frames.
    pub mean_error: f64,
}

/// Each frame's angular velocity (rad/s, world frame): the derivative of the quadratic through
/// the frame and its two neighbours in the log map (second order, uneven spacing allowed), one-
/// sided at the first and last frame.
pub fn frame_velocities(times: &[f64], quats: &[DQuat]) -> Vec<DVec3> {
    let n = quats.len();
    if n < 2 {
        return vec![DVec3::ZERO; n];
    }
    let step = |a: usize, b: usize| log(quats[b] * quats[a].conjugate());
    let flip = |q: DQuat, near: DQuat| if q.dot(near) < 0.0 { -q } else { q };
    if n == 2 {
        let w = step(0, 1) * (2.0 / (times[1] - times[0]));
        return vec![w, w];
    }
    let mut out = Vec::with_capacity(n);
    // One-sided: f(0) = 0, f(t1) = L01, f(t2) = L02 ⇒ f'(0) = (L01·t2² − L02·t1²)/(t1 t2 (t2 − t1)).
    let one_sided = |i: usize, j: usize, k: usize| {
        let (t1, t2) = (times[j] - times[i], times[k] - times[i]);
        let qj = flip(quats[j], quats[i]);
        let qk = flip(quats[k], qj);
        let (l1, l2) = (
            log(qj * quats[i].conjugate()),
            log(qk * quats[i].conjugate()),
        );
        (l1 * (t2 * t2) - l2 * (t1 * t1)) * (2.0 / (t1 * t2 * (t2 - t1)))
    };
    out.push(one_sided(0, 1, 2));
    for i in 1..n - 1 {
        let (hm, hp) = (times[i] - times[i - 1], times[i + 1] - times[i]);
        let (lm, lp) = (step(i - 1, i), step(i, i + 1));
        out.push((lp * (hm / ((hm + hp) * hp)) + lm * (hp / ((hm + hp) * hm))) * 2.0);
    }
    out.push(one_sided(n - 1, n - 2, n - 3));
    out
}

/// The error measure: the angle, or the displacement at `distance`.
fn error(opts: &ReduceOptions, a: DQuat, b: DQuat) -> f64 {
    let theta = rotation_angle_between(a, b);
    match opts.distance {
        Some(d) => 2.0 * d * (0.5 * theta).sin(),
        None => theta,
    }
}

/// The frames of one track.
struct Frames<'a> {
    times: &'a [f64],
    quats: &'a [DQuat],
    positions: Option<&'a [DVec3]>,
    omega: Option<Vec<DVec3>>,
    threshold: Threshold,
    /// The frame that last missed in [`Frames::feasible`].
    hint: std::cell::Cell<usize>,
}

impl<'a> Frames<'a> {
    /// One track's frames for `opts`: its velocities estimated when keys carry them.
    fn new(
        times: &'a [f64],
        quats: &'a [DQuat],
        positions: Option<&'a [DVec3]>,
        opts: &ReduceOptions,
    ) -> Frames<'a> {
        Frames {
            times,
            quats,
            positions,
            omega: opts.velocities.then(|| frame_velocities(times, quats)),
            threshold: Threshold::new(opts),
            hint: std::cell::Cell::new(0),
        }
    }

    /// The curve through the frames `keys` (with their velocities when asked), as `interp`
    /// builds it.
    fn curve(&self, keys: &[usize], opts: &ReduceOptions) -> InputResult<Curve> {
        let t: Vec<f64> = keys.iter().map(|&i| self.times[i]).collect();
        let q: Vec<DQuat> = keys.iter().map(|&i| self.quats[i]).collect();
        let mut track = Track::new(t, q)?;
        if let Some(w) = &self.omega {
            track = track.with_key_velocities(keys.iter().map(|&i| Some(w[i])).collect())?;
        }
        if let Some(p) = self.positions {
            track = track.with_translations(keys.iter().map(|&i| p[i]).collect())?;
        }
        Curve::new(&track, &opts.curve)
    }

    /// The worst frame strictly between keys `a` and `b` of `curve` and whether every frame
    /// there meets the tolerances.
    fn check(&self, curve: &Curve, a: usize, b: usize, opts: &ReduceOptions) -> (bool, usize) {
        let mut worst = (0.0f64, a);
        let mut ok = true;
        // A hair inside the tolerance, so that keys written and read back (velocities in
        // degrees per second round to the last bit) still meet it.
        let tol = opts.tolerance * (1.0 - 1e-9);
        for k in a + 1..b {
            let e = error(opts, curve.rotation(self.times[k]), self.quats[k]);
            let mut bad = e > tol;
            let mut score = e / opts.tolerance;
            if let (Some(p), Some(tol)) = (self.positions, opts.translation_tolerance) {
                let d = (curve.position(self.times[k]).unwrap_or(DVec3::ZERO) - p[k]).length();
                bad |= d > tol;
                score = score.max(d / tol);
            }
            ok &= !bad;
            if score > worst.0 {
                worst = (score, k);
            }
        }
        (ok, worst.1)
    }

    /// Whether the segment `a..b` alone meets the tolerances. Stops at the first frame that
    /// misses, trying first the frame that missed last time (`hint`: neighbouring segments
    /// usually miss at the same frame), and decides most frames from the cosine of the half
    /// angle ([`Threshold`]); the answer is the same as [`Frames::check`]'s.
    fn feasible(&self, a: usize, b: usize, opts: &ReduceOptions) -> InputResult<bool> {
        if b == a + 1 {
            return Ok(true);
        }
        let curve = self.curve(&[a, b], opts)?;
        let within = |k: usize| {
            if !self
                .threshold
                .within(opts, curve.rotation(self.times[k]), self.quats[k])
            {
                return false;
            }
            match (self.positions, opts.translation_tolerance) {
                (Some(p), Some(tol)) => {
                    let d = (curve.position(self.times[k]).unwrap_or(DVec3::ZERO) - p[k]).length();
                    d <= tol
                }
                _ => true,
            }
        };
        let hint = self.hint.get();
        if hint > a && hint < b && !within(hint) {
            return Ok(false);
        }
        for k in a + 1..b {
            if k != hint && !within(k) {
                self.hint.set(k);
                return Ok(false);
            }
        }
        Ok(true)
    }
}

/// The rotation test of [`Frames::check`] (`error > tolerance·(1 − 1e-9)` misses) decided from
/// `|a·b|`, the cosine of half the angle between the rotations, which the error decreases with:
/// clearly above the threshold's cosine a frame meets the tolerance, clearly below it misses,
/// and within 1e-9 of it the error is computed as [`Frames::check`] computes it.
#[derive(Debug, Clone, Copy)]
struct Threshold {
    cos_half: f64,
}

/// Half-width of the band around [`Threshold::cos_half`] where the exact error decides.
const BAND: f64 = 1e-9;

impl Threshold {
    fn new(opts: &ReduceOptions) -> Threshold {
        let tol = opts.tolerance * (1.0 - 1e-9);
        // The half angle at which the error reaches `tol` (the error is `θ`, or `2D·sin(θ/2)`).
        let half = match opts.distance {
            Some(d) if tol >= 2.0 * d => std::f64::consts::FRAC_PI_2,
            Some(d) => (tol / (2.0 * d)).asin(),
            None => (0.5 * tol).min(std::f64::consts::FRAC_PI_2),
        };
        Threshold {
            cos_half: half.cos(),
        }
    }

    /// Whether `a` is within the tolerance of `b` (the same answer as `error(a, b) <= tol`).
    #[inline]
    fn within(&self, opts: &ReduceOptions, a: DQuat, b: DQuat) -> bool {
        let c = a.dot(b).abs();
        if c > self.cos_half + BAND {
            true
        } else if c < self.cos_half - BAND {
            false
        } else {
            error(opts, a, b) <= opts.tolerance * (1.0 - 1e-9)
        }
    }
}

/// Reduces one track (see the module documentation). `positions`, when given, are the frames'
/// translations, and need `translation_tolerance`.
pub fn reduce(
    times: &[f64],
    quats: &[DQuat],
    positions: Option<&[DVec3]>,
    opts: &ReduceOptions,
) -> InputResult<Reduced> {
    let n = quats.len();
    let frames = Frames::new(times, quats, positions, opts);
    if n < 2 {
        return Ok(Reduced {
            keys: (0..n).collect(),
            velocities: frames.omega.clone(),
            max_error: 0.0,
            mean_error: 0.0,
        });
    }
    let greedy = verified(&frames, greedy_keys(&frames, opts)?, opts)?;
    let keys = match opts.method {
        Method::Greedy => greedy,
        Method::Optimal => {
            let window = optimal_window(&greedy);
            let best = verified(&frames, optimal_keys(&frames, window, opts)?, opts)?;
            if best.len() <= greedy.len() {
                best
            } else {
                greedy
            }
        }
    };
    // The guarantee, measured once more on the final keys.
    let curve = frames.curve(&keys, opts)?;
    let (mut max, mut sum) = (0.0f64, 0.0);
    for k in 0..n {
        let e = error(opts, curve.rotation(times[k]), quats[k]);
        max = max.max(e);
        sum += e;
    }
    if max > opts.tolerance * (1.0 + 1e-12) {
        return Err(crate::error::input_err!(
            "internal error: reduce's keys miss a frame by {max:e} (tolerance {:e})",
            opts.tolerance
        ));
    }
    Ok(Reduced {
        velocities: frames
            .omega
            .as_ref()
            .map(|w| keys.iter().map(|&i| w[i]).collect()),
        keys,
        max_error: max,
        mean_error: sum / n as f64,
    })
}

/// One track's frames for [`reduce_shared`]: times, rotations, optional positions.
pub type TrackFrames<'a> = (&'a [f64], &'a [DQuat], Option<&'a [DVec3]>);

/// Reduces each track on its own ([`reduce`]), the tracks shared out among the machine's cores
/// (at most [`MAX_THREADS`] threads, tracks taken in order as threads come free). The result is
/// in the tracks' order and the same whatever the number of threads; on errors, the first
/// track's error.
pub fn reduce_each(tracks: &[TrackFrames<'_>], opts: &ReduceOptions) -> InputResult<Vec<Reduced>> {
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(MAX_THREADS)
        .min(tracks.len());
    if threads <= 1 {
        return tracks
            .iter()
            .map(|&(t, q, p)| reduce(t, q, p, opts))
            .collect();
    }
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<InputResult<Reduced>>>> =
        Mutex::new((0..tracks.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&(t, q, p)) = tracks.get(i) else {
                        break;
                    };
                    let r = reduce(t, q, p, opts);
                    if let Ok(mut v) = results.lock() {
                        v[i] = Some(r);
                    }
                }
            });
        }
    });
    results
        .into_inner()
        .unwrap_or_default()
        .into_iter()
        .map(|r| {
            r.unwrap_or_else(|| {
                Err(crate::error::input_err!(
                    "internal error: a reduce thread did not finish"
                ))
            })
        })
        .collect()
}

/// Most threads [`reduce_each`] uses.
pub const MAX_THREADS: usize = 8;

/// Reduces several tracks to one set of key times (`--shared-keys`): each track's own keys, their
/// union, then verification of every track on the union until all meet the tolerances. The
/// tracks must have the same frame times.
pub fn reduce_shared(
    tracks: &[TrackFrames<'_>],
    opts: &ReduceOptions,
) -> InputResult<Vec<Reduced>> {
    let Some(&(times, _, _)) = tracks.first() else {
        return Ok(Vec::new());
    };
    if tracks.iter().any(|(t, _, _)| *t != times) {
        return Err(crate::error::input_err!(
            "--shared-keys: the tracks have different frame times; shared keys need one grid"
        ));
    }
    let mut keys: Vec<usize> = Vec::new();
    for r in reduce_each(tracks, opts)? {
        keys.extend(r.keys);
    }
    keys.sort_unstable();
    keys.dedup();
    let frames: Vec<Frames> = tracks
        .iter()
        .map(|&(t, q, p)| Frames::new(t, q, p, opts))
        .collect();
    loop {
        let before = keys.len();
        for f in &frames {
            keys = verified(f, keys, opts)?;
        }
        if keys.len() == before {
            break;
        }
    }
    frames
        .iter()
        .map(|frames| {
            let (t, q) = (frames.times, frames.quats);
            let curve = frames.curve(&keys, opts)?;
            let (mut max, mut sum) = (0.0f64, 0.0);
            for k in 0..q.len() {
                let e = error(opts, curve.rotation(t[k]), q[k]);
                max = max.max(e);
                sum += e;
            }
            Ok(Reduced {
                velocities: frames
                    .omega
                    .as_ref()
                    .map(|w| keys.iter().map(|&i| w[i]).collect()),
                keys: keys.clone(),
                max_error: max,
                mean_error: sum / q.len() as f64,
            })
        })
        .collect()
}

/// Greedy keys: from each key the farthest next key whose segment alone is feasible (doubling,
/// then bisection between the last feasible and the first infeasible length).
fn greedy_keys(frames: &Frames, opts: &ReduceOptions) -> InputResult<Vec<usize>> {
    let n = frames.quats.len();
    let mut keys = vec![0];
    let mut a = 0;
    while a < n - 1 {
        let (mut good, mut step) = (a + 1, 1);
        let mut bad = None;
        while good < n - 1 {
            let b = (a + 2 * step).min(n - 1);
            if frames.feasible(a, b, opts)? {
                good = b;
                step *= 2;
            } else {
                bad = Some(b);
                break;
            }
        }
        if let Some(mut hi) = bad {
            let mut lo = good;
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if frames.feasible(a, mid, opts)? {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            good = lo;
        }
        keys.push(good);
        a = good;
    }
    Ok(keys)
}

/// The longest segment (frames) the optimal method considers on a track whose greedy keys are
/// `greedy`: [`OPTIMAL_GREEDY_FACTOR`] times greedy's longest segment, at most
/// [`OPTIMAL_WINDOW`].
pub fn optimal_window(greedy: &[usize]) -> usize {
    let longest = greedy.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(1);
    (OPTIMAL_GREEDY_FACTOR * longest).min(OPTIMAL_WINDOW)
}

/// Optimal keys: the shortest path over feasible segments of at most `window` frames.
fn optimal_keys(frames: &Frames, window: usize, opts: &ReduceOptions) -> InputResult<Vec<usize>> {
    let n = frames.quats.len();
    let mut cost = vec![usize::MAX; n];
    let mut prev = vec![0usize; n];
    cost[0] = 0;
    for a in 0..n - 1 {
        if cost[a] == usize::MAX {
            continue;
        }
        for b in a + 1..(a + window).min(n - 1) + 1 {
            if cost[a] + 1 < cost[b] && frames.feasible(a, b, opts)? {
                cost[b] = cost[a] + 1;
                prev[b] = a;
            }
        }
    }
    let mut keys = vec![n - 1];
    while *keys.last().unwrap_or(&0) != 0 {
        let last = keys[keys.len() - 1];
        keys.push(prev[last]);
    }
    keys.reverse();
    Ok(keys)
}

/// Completes `keys` until the whole curve meets the tolerances at every frame: the worst frame
/// of each segment that misses becomes a key.
fn verified(
    frames: &Frames,
    mut keys: Vec<usize>,
    opts: &ReduceOptions,
) -> InputResult<Vec<usize>> {
    loop {
        let curve = frames.curve(&keys, opts)?;
        let mut added = Vec::new();
        for w in keys.windows(2) {
            let (ok, worst) = frames.check(&curve, w[0], w[1], opts);
            if !ok {
                added.push(worst);
            }
        }
        if added.is_empty() {
            return Ok(keys);
        }
        keys.extend(added);
        keys.sort_unstable();
        keys.dedup();
    }
}

/// Whether a scheme's segments are determined by their two keys alone when both carry
/// velocities (so that greedy's and optimal's segment checks are exact).
pub fn local_with_velocities(scheme: Scheme) -> bool {
    !matches!(scheme, Scheme::MinAccel)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn smooth(n: usize, fps: f64) -> (Vec<f64>, Vec<DQuat>) {
        let t: Vec<f64> = (0..n).map(|i| i as f64 / fps).collect();
        let q = t
            .iter()
            .map(|&t| {
                DQuat::from_euler(
                    glam::EulerRot::ZYX,
                    1.3 * t,
                    0.4 * (2.0 * t).sin(),
                    0.2 * t * t,
                )
            })
            .collect();
        (t, q)
    }

    #[test]
    fn velocities_are_second_order() {
        let (t, q) = smooth(61, 30.0);
        let w = frame_velocities(&t, &q);
        // Against a fine central difference of the exact motion.
        let exact = |t: f64| {
            let h = 1e-6;
            let f = |t: f64| {
                DQuat::from_euler(
                    glam::EulerRot::ZYX,
                    1.3 * t,
                    0.4 * (2.0 * t).sin(),
                    0.2 * t * t,
                )
            };
            let d = f(t + h) * f(t - h).conjugate();
            d.to_scaled_axis() / (2.0 * h)
        };
        for i in [0, 1, 30, 59, 60] {
            assert!(
                (w[i] - exact(t[i])).length() < 2e-3,
                "{i}: {} vs {}",
                w[i],
                exact(t[i])
            );
        }
    }

    #[test]
    fn every_scheme_and_method_meets_the_tolerance() {
        let (t, q) = smooth(121, 60.0);
        for scheme in Scheme::ALL {
            for method in [Method::Greedy, Method::Optimal] {
                for velocities in [true, false] {
                    let opts = ReduceOptions {
                        curve: CurveOptions {
                            scheme,
                            grid_rate: crate::Fps::new(60, 1).unwrap(),
                            ..CurveOptions::default()
                        },
                        tolerance: 0.2f64.to_radians(),
                        distance: None,
                        translation_tolerance: None,
                        velocities,
                        method,
                    };
                    let r = reduce(&t, &q, None, &opts).unwrap();
                    assert_eq!((r.keys[0], *r.keys.last().unwrap()), (0, 120));
                    assert!(r.max_error <= opts.tolerance, "{scheme} {method:?}");
                    assert!(
                        r.keys.len() < 60,
                        "{scheme} {method:?} {velocities}: {}",
                        r.keys.len()
                    );
                }
            }
        }
    }
}
