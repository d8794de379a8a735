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
//! ## Velocities
//! A key carries one of its frame's [`velocity_estimates`] (finite differences of the frames:
//! centred, one-sided of first and second order, wide centred). Which one is chosen so that fewer
//! keys meet the tolerance: on captured motion the one-sided estimates at a frame where the motion
//! turns let a key there start or end a long segment. With slerp (no tangents) or without
//! velocities there is nothing to choose.
//!
//! ## Methods
//! - **Greedy**: from each key, the farthest next key whose segment alone meets the tolerance,
//!   over the estimates the next key may carry (`greedy_step`: doubling then bisection); where
//!   several estimates reach it, the one from which the following step goes farthest (one step
//!   of look-ahead, each estimate after the first searched only past the farthest so far). A
//!   segment with both end velocities given depends on its two keys only, for hermite, bezier,
//!   squad and slerp.
//! - **Optimal**: each frame first takes its *preferred* estimate, the one from which a segment
//!   starting there reaches farthest (`preferred_estimates`); then a shortest path over the
//!   frames, an edge `i → j` wherever the segment `i..j` alone meets the tolerance (segments up
//!   to [`optimal_window`] frames: twice greedy's longest segment on the track, at most
//!   [`OPTIMAL_WINDOW`]): the fewest keys, among key sets whose keys carry their preferred
//!   estimates and whose segments fit the window, whose segments each meet it. Slerp (one
//!   estimate, or none) has no window: an exact early cut (`SlerpSpeeds`) ends the search
//!   from a key, so its result is exactly minimal. Elsewhere (minaccel,
//!   estimated tangents) its keys are then completed like greedy's, and where it would keep
//!   more keys than greedy, greedy's are kept (with greedy's estimates).
//! - **Shared keys** ([`reduce_shared`]): the same methods on all tracks at once, a segment
//!   meeting the tolerances when it meets them on every track.
//!
//! All end with **verification**: the curve through the chosen keys is built exactly as
//! `interp` builds it ([`Curve`]), evaluated at every frame, and wherever a frame misses the
//! tolerance the worst frame of that segment becomes a key (carrying its centred estimate),
//! until none misses. The result is therefore guaranteed, whatever the scheme, and checked
//! before it is returned.

use crate::curve::piecewise::{MAX_SPEED, segment_rotation};
use crate::curve::{Curve, CurveOptions, Scheme};
use crate::error::InputResult;
use crate::rotation::quat::{log, rotation_angle_between};
use crate::tangent::{EndConditions, Ends, Knots, PathMode, apply_path};
use crate::track::Track;
use glam::{DQuat, DVec3};
use std::cell::RefMut;

/// A minaccel segment test solves at most this many times the grid steps its frames span (one
/// refinement of the frame grid), plus [`SEGMENT_GRID_SLACK`] points; a segment whose start curve
/// needs more is not feasible (docs/spec.md §4.7).
pub const SEGMENT_GRID_FACTOR: usize = 2;

/// Grid points a minaccel segment test may use beyond [`SEGMENT_GRID_FACTOR`] times its steps
/// (the extra steps beside keys with their own velocities, and phantom points).
pub const SEGMENT_GRID_SLACK: usize = 8;

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
    /// Give each key an estimate of the frames' angular velocity at it ([`velocity_estimates`]).
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
    /// Largest position error over the frames (length units), for a track whose positions were
    /// reduced (`translation_tolerance`).
    pub max_position_error: Option<f64>,
}

/// Each frame's angular velocity (rad/s, world frame): the derivative of the quadratic through
/// the frame and its two neighbours in the log map (second order, uneven spacing allowed), one-
/// sided at the first and last frame.
///
/// The quaternions are taken as the curve connects them: the motion from frame `i` to frame `j`
/// is `log(q_j q_i⁻¹)`, so a frame whose sign is flipped against its neighbour is reached the
/// long way round. For the shortest path, pass them each in the hemisphere of the one before
/// ([`crate::tangent::apply_path`]), as [`reduce`] does.
pub fn frame_velocities(times: &[f64], quats: &[DQuat]) -> Vec<DVec3> {
    let n = quats.len();
    if n < 2 {
        return vec![DVec3::ZERO; n];
    }
    let step = |a: usize, b: usize| log(quats[b] * quats[a].conjugate());
    if n == 2 {
        let w = step(0, 1) * (2.0 / (times[1] - times[0]));
        return vec![w, w];
    }
    let mut out = Vec::with_capacity(n);
    // One-sided: f(0) = 0, f(t1) = L01, f(t2) = L02 ⇒ f'(0) = (L01·t2² − L02·t1²)/(t1 t2 (t2 − t1)).
    let one_sided = |i: usize, j: usize, k: usize| {
        let (t1, t2) = (times[j] - times[i], times[k] - times[i]);
        let (l1, l2) = (step(i, j), step(i, k));
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

/// How many velocity estimates a key may choose from ([`velocity_estimates`]).
pub const ESTIMATES: usize = 6;

/// Each frame's angular velocity estimates (rad/s, world frame), the derivative at the frame of
/// the polynomial through the frame and neighbours in the log map, for six stencils, in order:
/// centred (the previous and next frame: [`frame_velocities`], one-sided at the ends), backward
/// and forward first order (the previous, the next frame), backward and forward second order
/// (the two previous, the two next frames), wide centred (the frames two before and two after,
/// which passes over the quantisation of a file's numbers). Where a stencil runs off the track,
/// the centred estimate stands in. On smooth motion they agree to first or second order; where
/// the motion turns sharply (a foot strike, a hit) the one-sided ones are the velocities arriving
/// and leaving, which let a key there start or end a long segment. The quaternions are taken as
/// the curve connects them, as in [`frame_velocities`].
pub fn velocity_estimates(times: &[f64], quats: &[DQuat]) -> Vec<[DVec3; ESTIMATES]> {
    let centred = frame_velocities(times, quats);
    let n = quats.len();
    // The derivative at t_i of f(t) = αt + βt² through f(0) = 0, f(t1) = L1, f(t2) = L2 (t1, t2
    // signed), doubled: the log map holds half angles.
    let second = |i: usize, j: usize, k: usize| {
        let (t1, t2) = (times[j] - times[i], times[k] - times[i]);
        let (l1, l2) = (
            log(quats[j] * quats[i].conjugate()),
            log(quats[k] * quats[i].conjugate()),
        );
        (l1 * (t2 * t2) - l2 * (t1 * t1)) * (2.0 / (t1 * t2 * (t2 - t1)))
    };
    let first =
        |i: usize, j: usize| log(quats[j] * quats[i].conjugate()) * (2.0 / (times[j] - times[i]));
    (0..n)
        .map(|i| {
            let c = centred[i];
            [
                c,
                if i >= 1 { first(i, i - 1) } else { c },
                if i + 1 < n { first(i, i + 1) } else { c },
                if i >= 2 { second(i, i - 1, i - 2) } else { c },
                if i + 2 < n {
                    second(i, i + 1, i + 2)
                } else {
                    c
                },
                if i >= 2 && i + 2 < n {
                    second(i, i - 2, i + 2)
                } else {
                    c
                },
            ]
        })
        .collect()
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
    /// The frames' Euler angles, for `--path euler`.
    euler: Option<(crate::EulerSeq, &'a [DVec3])>,
    /// Each frame's velocity estimates, when keys carry velocities.
    estimates: Option<Vec<[DVec3; ESTIMATES]>>,
    /// The estimate each frame carries when it is a key (an index into its estimates; the
    /// centred one until a method chooses another).
    choice: Vec<std::cell::Cell<u8>>,
    /// How many estimates the methods choose from: [`ESTIMATES`] where keys carry velocities
    /// and the scheme uses them, else 1.
    choices: usize,
    threshold: Threshold,
    /// The frame that last missed in [`Frames::feasible`].
    hint: std::cell::Cell<usize>,
    /// The key before the segments being tested, which their first key's tangent depends on
    /// when tangents are estimated ([`Frames::segment_curve`]); set by the methods.
    before: std::cell::Cell<Option<usize>>,
    /// The frames' spacing (s) when they are evenly spaced ([`even_spacing`]): then segments
    /// are evaluated at the frames as `interp` generates in-betweens.
    spacing: Option<f64>,
    /// The times the keys will be written at, per frame, when they differ from the frames'
    /// ([`TrackFrames::key_times`]).
    key_times: Option<&'a [f64]>,
    /// Knots reused by [`Frames::probe`], where segment tests may be probed
    /// ([`Frames::with_probe`]).
    probe: Option<std::cell::RefCell<Knots>>,
    /// Per frame, the last frame of the run of frames held exactly from it (the same rotation
    /// to the bit, and position and Euler angles where they are tested), where there is a
    /// probe ([`Frames::held`]).
    held_until: Vec<usize>,
}

/// The spacing of evenly spaced frame times: every time within 1e-9 of a frame of the spacing
/// from the first (a rate's frame clock, a file's fixed frame time), else `None`.
fn even_spacing(times: &[f64]) -> Option<f64> {
    let n = times.len();
    if n < 3 {
        return None;
    }
    let dt = (times[n - 1] - times[0]) / (n - 1) as f64;
    let even = times
        .iter()
        .enumerate()
        .all(|(k, &t)| (t - (times[0] + k as f64 * dt)).abs() <= 1e-9 * dt);
    (dt > 0.0 && even).then_some(dt)
}

impl<'a> Frames<'a> {
    /// One track's frames for `opts`: its velocities estimated when keys carry them.
    fn new(track: &TrackFrames<'a>, opts: &ReduceOptions) -> Frames<'a> {
        let (times, quats) = (track.times, track.rotations);
        Frames {
            times,
            quats,
            positions: track.positions,
            euler: track.euler,
            estimates: opts.velocities.then(|| {
                // The frames as the curve connects them: `--path as-given` as given, else each
                // in the hemisphere of the one before (`--path euler`'s chords between
                // neighbouring frames are those steps, unless the angles jump by half a turn).
                let mut q = quats.to_vec();
                if opts.curve.path != PathMode::AsGiven {
                    apply_path(&mut q, PathMode::Shortest);
                }
                velocity_estimates(times, &q)
            }),
            choice: vec![std::cell::Cell::new(0); quats.len()],
            choices: if opts.velocities && opts.curve.scheme != Scheme::Slerp {
                ESTIMATES
            } else {
                1
            },
            threshold: Threshold::new(opts),
            hint: std::cell::Cell::new(0),
            before: std::cell::Cell::new(None),
            // Keys at other times than their frames' are evaluated directly at the frame times.
            spacing: even_spacing(times).filter(|_| track.key_times.is_none()),
            key_times: track.key_times,
            probe: None,
            held_until: Vec::new(),
        }
        .with_probe(opts)
    }

    /// Whether segment `a..b` surely meets the tolerances because it holds one pose: its frames
    /// are held exactly ([`Frames::held_until`]) and its keys' velocities are zero, so its curve
    /// is that pose to round-off (a few ulps, against tolerances of at least [`HELD_TOLERANCE`]).
    /// On held joints every segment test passes, each evaluating every frame; this decides them
    /// without a curve.
    fn held(&self, a: usize, b: usize, opts: &ReduceOptions) -> bool {
        let n = self.quats.len();
        let ends = opts.curve.ends;
        let still = |v: Option<DVec3>| v == Some(DVec3::ZERO);
        self.held_until.get(a).is_some_and(|&last| last >= b)
            && still(ends.start.filter(|_| a == 0).or(self.velocity(a)))
            && still(ends.end.filter(|_| b == n - 1).or(self.velocity(b)))
    }

    /// Segment tests are probed ([`Frames::probe`]) where the probe's knots are the
    /// segment curve's and building that curve cannot fail: keys carry velocities, all within
    /// the curve's speed limit (the ends' too), the scheme is a segment scheme, TCB is valid,
    /// the keys sit at their frames' times, and the frames are a valid track, with their Euler
    /// angles for `--path euler` (so every subset of them is).
    fn with_probe(mut self, opts: &ReduceOptions) -> Frames<'a> {
        let fine = |v: &DVec3| {
            v.is_finite() && crate::rotation::magnitude::length(v.to_array()) <= MAX_SPEED
        };
        let c = &opts.curve;
        let probes = self
            .estimates
            .as_ref()
            .is_some_and(|e| e.iter().flatten().all(fine))
            && [c.ends.start, c.ends.end].iter().flatten().all(fine)
            && c.scheme != Scheme::MinAccel
            && c.tcb.is_valid()
            && self.key_times.is_none()
            && self
                .positions
                .is_none_or(|p| p.iter().all(|x| x.is_finite()))
            && Track::new(self.times.to_vec(), self.quats.to_vec()).is_ok_and(|t| {
                match (c.path, self.euler) {
                    (PathMode::Euler, Some((seq, e))) => {
                        t.with_euler_angles(seq, e.to_vec()).is_ok()
                    }
                    (PathMode::Euler, None) => false,
                    _ => true,
                }
            });
        if !probes {
            return self;
        }
        let (t, q) = (
            [self.times[0], self.times[1]],
            [self.quats[0], self.quats[1]],
        );
        let knots = Knots::pair(t, q, c.path, [DVec3::ZERO; 2], None);
        self.probe = Some(std::cell::RefCell::new(knots));
        let positions = self.positions.filter(|_| self.reduces_positions(opts));
        let ample = |tol: f64, size: f64| tol >= HELD_TOLERANCE * size.max(1.0);
        let tolerant = ample(self.threshold.angle, 1.0)
            && positions.is_none_or(|p| {
                let size = p.iter().map(|x| x.abs().max_element()).fold(0.0, f64::max);
                opts.translation_tolerance
                    .is_some_and(|tol| ample(tol, size))
            });
        if tolerant {
            let euler = self.euler.filter(|_| c.path == PathMode::Euler);
            let same = |i: usize, j: usize| {
                let bits = |q: DQuat| q.to_array().map(f64::to_bits);
                bits(self.quats[i]) == bits(self.quats[j])
                    && positions.is_none_or(|p| p[i] == p[j])
                    && euler.is_none_or(|(_, e)| e[i] == e[j])
            };
            let n = self.quats.len();
            self.held_until = vec![n - 1; n];
            for i in (0..n - 1).rev() {
                if same(i, i + 1) {
                    self.held_until[i] = self.held_until[i + 1];
                } else {
                    self.held_until[i] = i;
                }
            }
        }
        self
    }

    /// The knots of segment `a..b`'s curve as [`Frames::segment_curve`] would shape them, in
    /// the reused probe knots, where there is a probe ([`Frames::with_probe`]): the two keys with
    /// their velocities (the ends' velocities only at the first and last frame).
    fn probe(&self, a: usize, b: usize, opts: &ReduceOptions) -> Option<RefMut<'_, Knots>> {
        let (probe, va, vb) = (self.probe.as_ref()?, self.velocity(a)?, self.velocity(b)?);
        let n = self.quats.len();
        let ends = opts.curve.ends;
        let start = ends.start.filter(|_| a == 0).unwrap_or(va);
        let end = ends.end.filter(|_| b == n - 1).unwrap_or(vb);
        let mut knots = probe.borrow_mut();
        let (t, q) = (
            [self.times[a], self.times[b]],
            [self.quats[a], self.quats[b]],
        );
        let euler = self.euler.map(|(seq, e)| (seq, [e[a], e[b]]));
        knots.set_pair(t, q, opts.curve.path, [start, end], euler);
        Some(knots)
    }

    /// The curve of segment `a..b` on the probe's `knots` ([`Frames::probe`]): the curve
    /// [`Frames::segment_curve`] builds, without its track.
    fn probe_curve(&self, knots: &Knots, a: usize, b: usize, opts: &ReduceOptions) -> Curve {
        let positions = self.positions.map(|p| {
            let linear = opts.curve.scheme == Scheme::Slerp;
            crate::position::Positions::new(&knots.times, &[p[a], p[b]], linear, Ends::Chord)
        });
        let euler = self.euler.filter(|_| opts.curve.path == PathMode::Euler);
        let euler_start = euler.map(|(seq, e)| (seq, e[a].to_array()));
        Curve::of_knots(knots.clone(), &opts.curve, positions, euler_start)
    }

    /// Whether the track's positions are reduced (it has them, and a tolerance for them).
    fn reduces_positions(&self, opts: &ReduceOptions) -> bool {
        self.positions.is_some() && opts.translation_tolerance.is_some()
    }

    /// The velocity frame `i` carries as a key (its chosen estimate), when keys carry them.
    fn velocity(&self, i: usize) -> Option<DVec3> {
        self.estimates
            .as_ref()
            .map(|e| e[i][usize::from(self.choice[i].get())])
    }

    /// Frame `i` carries estimate `c` when it is a key.
    fn choose(&self, i: usize, c: usize) {
        self.choice[i].set(c as u8);
    }

    /// The velocities the frames `keys` carry, when keys carry them.
    fn key_velocities(&self, keys: &[usize]) -> Option<Vec<DVec3>> {
        self.estimates
            .as_ref()
            .map(|_| keys.iter().filter_map(|&i| self.velocity(i)).collect())
    }

    /// The curve through the frames `keys` (with their velocities when asked), as `interp`
    /// builds it.
    fn curve(&self, keys: &[usize], opts: &CurveOptions) -> InputResult<Curve> {
        Curve::new(&self.track(keys, opts)?, opts)
    }

    /// [`Frames::curve`], unless minaccel's grid would need more than `grid_limit` points
    /// ([`Curve::new_within`]).
    fn curve_within(
        &self,
        keys: &[usize],
        opts: &CurveOptions,
        grid_limit: usize,
    ) -> InputResult<Option<Curve>> {
        Curve::new_within(&self.track(keys, opts)?, opts, grid_limit)
    }

    /// The frames `keys` as a track's keys: their times (as written), rotations, and, as the
    /// frames have them, velocities, translations and (for `--path euler`) Euler angles.
    fn track(&self, keys: &[usize], opts: &CurveOptions) -> InputResult<Track> {
        let key_times = self.key_times.unwrap_or(self.times);
        let t: Vec<f64> = keys.iter().map(|&i| key_times[i]).collect();
        let q: Vec<DQuat> = keys.iter().map(|&i| self.quats[i]).collect();
        let mut track = Track::new(t, q)?;
        if self.estimates.is_some() {
            track = track.with_key_velocities(keys.iter().map(|&i| self.velocity(i)).collect())?;
        }
        if let Some(p) = self.positions {
            track = track.with_translations(keys.iter().map(|&i| p[i]).collect())?;
        }
        if let Some((seq, e)) = self.euler.filter(|_| opts.path == PathMode::Euler) {
            track = track.with_euler_angles(seq, keys.iter().map(|&i| e[i]).collect())?;
        }
        Ok(track)
    }

    /// The curve [`Frames::feasible`] tests segment `a..b` on, as the whole curve will have it:
    /// the keys `a` and `b`, and where the keys' tangents are estimated from their neighbours (no
    /// velocities) the key before `a` ([`Frames::before`]) and a stand-in for the key after `b`
    /// (as far past `b` as `a` is before it); the start's end condition only on the first frame,
    /// the end's only on the last (rest as a zero velocity there), and a loop's seam as a chord
    /// end (verification, on the whole curve, settles the seam).
    ///
    /// `None` for a minaccel segment whose grid would need more than one refinement of its
    /// frames ([`SEGMENT_GRID_FACTOR`]): its start curve turns more than a quarter turn between
    /// two frames, and the segment is taken as not feasible, unsolved.
    fn segment_curve(
        &self,
        a: usize,
        b: usize,
        opts: &ReduceOptions,
    ) -> InputResult<Option<Curve>> {
        let n = self.quats.len();
        let neighbours = self.estimates.is_none();
        let mut keys = Vec::with_capacity(4);
        keys.extend(self.before.get().filter(|&p| neighbours && p < a));
        keys.extend([a, b]);
        keys.extend((neighbours && b < n - 1).then(|| (2 * b - a).min(n - 1)));
        let ends = opts.curve.ends;
        // Rest is the velocity of an end without one: with velocities, the key's own.
        let rest = neighbours && ends.ends == Ends::Rest;
        let given =
            |at: bool, v: Option<DVec3>| at.then(|| v.or(rest.then_some(DVec3::ZERO))).flatten();
        let curve = CurveOptions {
            ends: EndConditions {
                ends: Ends::Chord,
                start: given(keys[0] == 0, ends.start),
                end: given(keys[keys.len() - 1] == n - 1, ends.end),
            },
            ..opts.curve
        };
        let key_times = self.key_times.unwrap_or(self.times);
        let span = key_times[keys[keys.len() - 1]] - key_times[keys[0]];
        let steps = (span * opts.curve.grid_rate.as_f64()).ceil();
        let limit = (SEGMENT_GRID_FACTOR as f64 * steps).min(usize::MAX as f64) as usize;
        self.curve_within(&keys, &curve, limit.saturating_add(SEGMENT_GRID_SLACK))
    }

    /// The worst frame strictly between keys `a` and `b` of `curve` and whether every frame
    /// there meets the tolerances; their rotation errors are added to `errors`.
    fn check(
        &self,
        curve: &Curve,
        (piece, a, b): (usize, usize, usize),
        opts: &ReduceOptions,
        errors: &mut Errors,
    ) -> (bool, usize) {
        let mut worst = (0.0f64, a);
        let mut ok = true;
        // A hair inside the tolerance, so that keys written and read back (velocities in
        // degrees per second round to the last bit) still meet it.
        let tol = opts.tolerance * (1.0 - 1e-9);
        let points = self.generated(curve, (piece, a, b));
        for k in a + 1..b {
            let q = points
                .as_ref()
                .map_or_else(|| curve.rotation(self.times[k]), |p| p[k - a - 1]);
            let e = error(opts, q, self.quats[k]);
            errors.add(e);
            let mut bad = e > tol;
            let mut score = e / opts.tolerance;
            if let (Some(p), Some(tol)) = (self.positions, opts.translation_tolerance) {
                let d = (curve.position(self.times[k]).unwrap_or(DVec3::ZERO) - p[k]).length();
                errors.position = Some(errors.position.unwrap_or(0.0).max(d));
                bad |= d > tol;
                score = score.max(d / tol);
            }
            ok &= !bad;
            if score > worst.0 {
                worst = (score, k);
            }
        }
        if b > a + 1
            && let Some(u) = near_antipode(curve, piece)
        {
            // The frame nearest the blend's near-antipode becomes a key.
            let k = a + (u * (b - a) as f64).round() as usize;
            return (false, k.clamp(a + 1, b - 1));
        }
        (ok, worst.1)
    }

    /// The frames strictly inside segment `piece` of `curve` (from frame `a` to frame `b`) as
    /// `interp` generates them at the frames' rate ([`Curve::segment_points`]: forward
    /// differences from the segment's first frame after its key, the first at
    /// `u₀ = (t_{a+1} − t_a)/Δ`, then steps of the spacing over `Δ`), when the frames are
    /// evenly spaced and the scheme is a segment scheme; else `None` (evaluated directly).
    fn generated(&self, curve: &Curve, (piece, a, b): (usize, usize, usize)) -> Option<Vec<DQuat>> {
        let dt = self.spacing?;
        if b <= a + 1 {
            return None;
        }
        let delta = self.times[b] - self.times[a];
        let u0 = (self.times[a + 1] - self.times[a]) / delta;
        let mut points = Vec::with_capacity(b - a - 1);
        curve.segment_points(piece, (u0, dt / delta), b - a - 1, |q| {
            points.push(q);
            true
        })?;
        Some(points)
    }

    /// Whether the segment `a..b` alone meets the tolerances. Stops at the first frame that
    /// misses, trying first the frame that missed last time (`hint`: neighbouring segments
    /// usually miss at the same frame), and decides most frames from the cosine of the half
    /// angle ([`Threshold`]). Evenly spaced frames are generated as `interp` generates
    /// in-betweens ([`Curve::segment_points`]), which agrees with [`Curve::rotation`], and so
    /// with [`Frames::check`], to round-off: a frame within round-off of the tolerance may be
    /// judged differently, which verification settles.
    fn feasible(&self, a: usize, b: usize, opts: &ReduceOptions) -> InputResult<bool> {
        if b == a + 1 || self.held(a, b, opts) {
            return Ok(true);
        }
        let hint = self.hint.get();
        let curve = match self.probe(a, b, opts) {
            // Most tests miss at the frame that missed last: that frame is evaluated on the
            // probe's one segment (the curve's value to the last bit) before any curve is built.
            Some(knots) => {
                let c = &opts.curve;
                let miss = |k: usize| {
                    let q = segment_rotation(&knots, c.scheme, c.blend, self.times[k]);
                    !self.threshold.within(opts, q, self.quats[k])
                };
                if hint > a && hint < b && miss(hint) {
                    return Ok(false);
                }
                self.probe_curve(&knots, a, b, opts)
            }
            None => match self.segment_curve(a, b, opts)? {
                Some(curve) => curve,
                None => return Ok(false),
            },
        };
        // The segment's index in that curve: after the key before `a`, if it has one.
        let start = self.key_times.map_or(self.times[a], |t| t[a]);
        let piece = curve.key_times().partition_point(|&t| t < start);
        let within = |k: usize, q: DQuat| {
            if !self.threshold.within(opts, q, self.quats[k]) {
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
        if hint > a && hint < b && !within(hint, curve.rotation(self.times[hint])) {
            return Ok(false);
        }
        // The frames first: most segments tested miss a frame, and the antipode's search
        // (hundreds of blend evaluations) is then not needed.
        let missed = match self.spacing {
            Some(dt) => {
                let delta = self.times[b] - self.times[a];
                let mut k = a + 1;
                curve
                    .segment_points(piece, (dt / delta, dt / delta), b - a - 1, |q| {
                        let ok = k == hint || within(k, q);
                        k += 1;
                        ok
                    })
                    .map(|all| (!all).then(|| k - 1))
            }
            None => None,
        };
        let missed = missed.unwrap_or_else(|| {
            (a + 1..b).find(|&k| k != hint && !within(k, curve.rotation(self.times[k])))
        });
        if let Some(k) = missed {
            self.hint.set(k);
            return Ok(false);
        }
        Ok(near_antipode(&curve, piece).is_none())
    }

    /// [`Frames::feasible`] with frame `b` carrying estimate `c`.
    fn feasible_with(
        &self,
        a: usize,
        b: usize,
        c: usize,
        opts: &ReduceOptions,
    ) -> InputResult<bool> {
        self.choose(b, c);
        self.feasible(a, b, opts)
    }

    /// Every frame that is not one of `keys` back to the centred estimate, so that keys added by
    /// verification carry it.
    fn keep_choices(&self, keys: &[usize]) {
        let mut k = keys.iter().peekable();
        for (i, c) in self.choice.iter().enumerate() {
            if k.peek() == Some(&&i) {
                k.next();
            } else {
                c.set(0);
            }
        }
    }
}

/// The smallest tolerance (rad, and relative to the largest coordinate for positions) at which
/// held frames are taken as met without evaluating them ([`Frames::held`]): far above the
/// round-off of a curve through keys that are one pose.
const HELD_TOLERANCE: f64 = 1e-9;

/// How near an antipode (`‖a + b‖` of a blend's two points, [`crate::curve::antipode_gap`])
/// the blends of a segment with frames inside may come. Where they come nearer, the geodesic
/// between them is barely defined: a perturbation `ε` of its points (round-off: direct
/// evaluation against `interp`'s forward differences, a velocity written to the last digit)
/// moves it by about `π·ε/gap`, and at the antipode itself by anything up to half a turn. A
/// segment nearer than this is never feasible, and verification splits it (docs/spec.md §4.7).
pub const ANTIPODE_MARGIN: f64 = 1e-3;

/// Where the blends of segment `piece` of `curve` come within [`ANTIPODE_MARGIN`] of an
/// antipode: the `u` where they come nearest.
fn near_antipode(curve: &Curve, piece: usize) -> Option<f64> {
    curve
        .segment_antipode_gap(piece)
        .filter(|&(gap, _)| gap < ANTIPODE_MARGIN)
        .map(|(_, u)| u)
}

/// The rotation test of [`Frames::check`] (`error > tolerance·(1 − 1e-9)` misses) decided from
/// `|a·b|`, the cosine of half the angle between the rotations, which the error decreases with:
/// clearly above the threshold's cosine a frame meets the tolerance, clearly below it misses,
/// and within 1e-9 of it the error is computed as [`Frames::check`] computes it.
#[derive(Debug, Clone, Copy)]
struct Threshold {
    cos_half: f64,
    /// The largest rotation angle error allowed (rad).
    angle: f64,
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
            angle: 2.0 * half,
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
/// translations, and need `translation_tolerance`. Frames given as Euler angles, for
/// `--path euler`: [`reduce_frames`].
pub fn reduce(
    times: &[f64],
    quats: &[DQuat],
    positions: Option<&[DVec3]>,
    opts: &ReduceOptions,
) -> InputResult<Reduced> {
    let frames = TrackFrames {
        times,
        rotations: quats,
        positions,
        euler: None,
        key_times: None,
    };
    reduce_frames(&frames, opts)
}

/// Reduces one track's frames (see the module documentation).
pub fn reduce_frames(track: &TrackFrames<'_>, opts: &ReduceOptions) -> InputResult<Reduced> {
    let n = track.rotations.len();
    let frames = Frames::new(track, opts);
    if n < 2 {
        let keys: Vec<usize> = (0..n).collect();
        return Ok(Reduced {
            velocities: frames.key_velocities(&keys),
            keys,
            max_error: 0.0,
            mean_error: 0.0,
            max_position_error: frames.reduces_positions(opts).then_some(0.0),
        });
    }
    let frames = [frames];
    let (keys, errors) = method_keys(
        &frames,
        opts,
        || greedy_keys(&frames[0], opts),
        |window| optimal_keys(&frames[0], window, opts),
    )?;
    reduced(&frames[0], keys, errors[0], opts)
}

/// The keys `opts.method` gives tracks reduced together (one track, or shared keys): `greedy`'s
/// keys, verified; for optimal, `optimal`'s (given the window of greedy's keys), verified, unless
/// they are more than greedy's, whose estimates are then restored. minaccel's optimal keeps
/// greedy's keys: its segments are not local, and a shortest path would solve a curve per tested
/// segment (minutes on a few hundred frames) for a test that is not exact anyway. Returns the
/// keys and each track's errors on them.
fn method_keys(
    frames: &[Frames],
    opts: &ReduceOptions,
    greedy: impl FnOnce() -> InputResult<Vec<usize>>,
    optimal: impl FnOnce(usize) -> InputResult<Vec<usize>>,
) -> InputResult<(Vec<usize>, Vec<Errors>)> {
    let keep = |keys: &[usize]| {
        for f in frames {
            f.keep_choices(keys);
        }
    };
    let keys = greedy()?;
    keep(&keys);
    let greedy_choice: Vec<Vec<u8>> = frames
        .iter()
        .map(|f| f.choice.iter().map(std::cell::Cell::get).collect())
        .collect();
    let greedy = shared_verified(frames, keys, opts)?;
    if opts.method == Method::Greedy || opts.curve.scheme == Scheme::MinAccel {
        return Ok(greedy);
    }
    let best = optimal(optimal_window(&greedy.0))?;
    keep(&best);
    let best = shared_verified(frames, best, opts)?;
    if best.0.len() <= greedy.0.len() {
        return Ok(best);
    }
    for (f, g) in frames.iter().zip(&greedy_choice) {
        for (c, &g) in f.choice.iter().zip(g) {
            c.set(g);
        }
    }
    Ok(greedy)
}

/// A track's result: its keys, their velocities, the errors verification measured on them (the
/// guarantee checked once more).
fn reduced(
    frames: &Frames,
    keys: Vec<usize>,
    errors: Errors,
    opts: &ReduceOptions,
) -> InputResult<Reduced> {
    if errors.max > opts.tolerance * (1.0 + 1e-12) {
        return Err(crate::error::input_err!(
            "internal error: reduce's keys miss a frame by {:e} (tolerance {:e})",
            errors.max,
            opts.tolerance
        ));
    }
    Ok(Reduced {
        velocities: frames.key_velocities(&keys),
        keys,
        max_error: errors.max,
        mean_error: errors.sum / frames.quats.len() as f64,
        max_position_error: frames
            .reduces_positions(opts)
            .then(|| errors.position.unwrap_or(0.0)),
    })
}

/// One track's dense frames, for [`reduce_frames`], [`reduce_each`] and [`reduce_shared`].
#[derive(Debug, Clone, Copy)]
pub struct TrackFrames<'a> {
    /// The frame times (s), increasing.
    pub times: &'a [f64],
    /// The frames' rotations.
    pub rotations: &'a [DQuat],
    /// The frames' translations, reduced under `translation_tolerance`.
    pub positions: Option<&'a [DVec3]>,
    /// The Euler angles (radians) the frames were given as: with `--path euler`
    /// ([`PathMode::Euler`]) the keys' curve keeps the turns their angles make.
    pub euler: Option<(crate::EulerSeq, &'a [DVec3])>,
    /// The time each frame will have as a key when it differs from the frame's (glTF output
    /// writes float32 times): the keys' curve is built on these and verified at the frame
    /// times, as a player evaluates it. Increasing, one per frame; `None`: the frame times.
    pub key_times: Option<&'a [f64]>,
}

impl<'a> TrackFrames<'a> {
    /// The frames of a track whose keys are the dense frames: times, rotations, translations
    /// and Euler angles as the track has them.
    pub fn of(track: &'a Track) -> TrackFrames<'a> {
        TrackFrames {
            times: track.times(),
            rotations: track.rotations(),
            positions: track.translations(),
            euler: track.euler_angles(),
            key_times: None,
        }
    }
}

/// Reduces each track on its own ([`reduce`]), the tracks shared out among the machine's cores
/// (at most [`MAX_THREADS`] threads, tracks taken in order as threads come free). The result is
/// in the tracks' order and the same whatever the number of threads; on errors, the first
/// track's error.
pub fn reduce_each(tracks: &[TrackFrames<'_>], opts: &ReduceOptions) -> InputResult<Vec<Reduced>> {
    crate::parallel::map(tracks, |t| reduce_frames(t, opts))
        .into_iter()
        .collect()
}

/// Most threads [`reduce_each`] uses.
pub use crate::parallel::MAX_THREADS;

/// Reduces several tracks to one set of key times (`--shared-keys`): the methods run on all
/// tracks at once, a segment meeting the tolerances when it meets them on every track (each
/// track's key carrying its own estimate; optimal is exactly the fewest shared keys for slerp),
/// then verification of every track on the keys until all meet the tolerances. The tracks must
/// have the same frame times.
pub fn reduce_shared(
    tracks: &[TrackFrames<'_>],
    opts: &ReduceOptions,
) -> InputResult<Vec<Reduced>> {
    let Some(times) = tracks.first().map(|t| t.times) else {
        return Ok(Vec::new());
    };
    if tracks.iter().any(|t| t.times != times) {
        return Err(crate::error::input_err!(
            "--shared-keys: the tracks have different frame times; shared keys need one grid"
        ));
    }
    let n = times.len();
    let frames: Vec<Frames> = tracks.iter().map(|t| Frames::new(t, opts)).collect();
    if n < 2 {
        return tracks.iter().map(|t| reduce_frames(t, opts)).collect();
    }
    let (keys, errors) = method_keys(
        &frames,
        opts,
        || shared_greedy_keys(&frames, opts),
        |window| shared_optimal_keys(&frames, window, opts),
    )?;
    frames
        .iter()
        .zip(errors)
        .map(|(f, e)| reduced(f, keys.clone(), e, opts))
        .collect()
}

/// Whether segment `a..b` meets the tolerances on every track, each track's frame `b` carrying
/// the first of its estimates with which it does (its choice set to it). `first` is the track
/// to test first: the one that missed last time (updated).
fn shared_feasible(
    frames: &[Frames],
    a: usize,
    b: usize,
    first: &std::cell::Cell<usize>,
    opts: &ReduceOptions,
) -> InputResult<bool> {
    let m = frames.len();
    for j in 0..m {
        let t = (first.get() + j) % m;
        let f = &frames[t];
        let mut ok = false;
        for c in 0..f.choices {
            if f.feasible_with(a, b, c, opts)? {
                ok = true;
                break;
            }
        }
        if !ok {
            first.set(t);
            return Ok(false);
        }
    }
    Ok(true)
}

/// Greedy shared keys: from each key the farthest next key whose segment meets the tolerances on
/// every track ([`shared_feasible`], doubling then bisection), each track's key carrying the first
/// of its estimates that meets them there.
fn shared_greedy_keys(frames: &[Frames], opts: &ReduceOptions) -> InputResult<Vec<usize>> {
    let n = frames[0].quats.len();
    let first = std::cell::Cell::new(0);
    let mut keys = vec![0];
    let mut a = 0;
    while a < n - 1 {
        for f in frames {
            f.before.set(keys.len().checked_sub(2).map(|i| keys[i]));
        }
        let b = farthest_by(n, a + 1, |b| shared_feasible(frames, a, b, &first, opts))?;
        // The key's estimates: those of the test at `b` itself.
        shared_feasible(frames, a, b, &first, opts)?;
        keys.push(b);
        a = b;
    }
    Ok(keys)
}

/// Optimal shared keys: the shortest path over the frames with an edge `a → b` wherever the
/// segment meets the tolerances on every track ([`shared_feasible`]: each track's frame `b`
/// carrying the first of its estimates with which it does), each track's frame `a` carrying the
/// estimate of the edge by which the path reached `a`. Without estimates to choose (slerp, or
/// no velocities) that is the fewest shared keys with segments of at most `window` frames; slerp
/// has no window: the search from a key stops where any track's early cut ([`SlerpSpeeds`]) says
/// no longer segment can meet the tolerance on it, so its result is exactly the fewest.
fn shared_optimal_keys(
    frames: &[Frames],
    window: usize,
    opts: &ReduceOptions,
) -> InputResult<Vec<usize>> {
    let n = frames[0].quats.len();
    let slerp = opts.curve.scheme == Scheme::Slerp && opts.curve.path == PathMode::Shortest;
    let first = std::cell::Cell::new(0);
    let mut speeds: Vec<SlerpSpeeds> = Vec::new();
    // Each track's estimate at each frame, from the edge that reached it.
    let mut reached: Vec<Vec<u8>> = frames.iter().map(|_| vec![0; n]).collect();
    shortest_path(n, |a, b, improves, before| {
        if b == a + 1 {
            speeds = frames.iter().map(|_| SlerpSpeeds::new(a)).collect();
            for (f, r) in frames.iter().zip(&reached) {
                f.choose(a, usize::from(r[a]));
                f.before.set(before);
            }
        }
        if slerp {
            if !speeds.iter_mut().zip(frames).all(|(s, f)| s.admit(f, b)) {
                return Ok(Edge::Stop);
            }
        } else if b > a + window {
            return Ok(Edge::Stop);
        }
        if !improves || (slerp && !speeds.iter().zip(frames).all(|(s, f)| s.allows(f, b))) {
            return Ok(Edge::No);
        }
        if !shared_feasible(frames, a, b, &first, opts)? {
            return Ok(Edge::No);
        }
        for (f, r) in frames.iter().zip(&mut reached) {
            r[b] = f.choice[b].get();
        }
        Ok(Edge::Yes)
    })
    .inspect(|keys| {
        for (f, r) in frames.iter().zip(&reached) {
            for &k in keys {
                f.choose(k, usize::from(r[k]));
            }
        }
    })
}

/// From key `a` (its velocity chosen), the farthest next key `b ≥ from` whose segment alone meets
/// the tolerances with `b` carrying estimate `c`, given that `from` does ([`farthest_by`]).
fn farthest(
    frames: &Frames,
    a: usize,
    from: usize,
    c: usize,
    opts: &ReduceOptions,
) -> InputResult<usize> {
    farthest_by(frames.quats.len(), from, |b| {
        frames.feasible_with(a, b, c, opts)
    })
}

/// The farthest frame `b ≥ from` (of `n`) that passes `test`, given that `from` does: doubling
/// past `from`, then bisection between the last frame that passes and the first that does not.
fn farthest_by(
    n: usize,
    from: usize,
    mut test: impl FnMut(usize) -> InputResult<bool>,
) -> InputResult<usize> {
    let (mut good, mut step) = (from, 1);
    let mut bad = None;
    while good < n - 1 {
        let b = (good + step).min(n - 1);
        if test(b)? {
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
            if test(mid)? {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        good = lo;
    }
    Ok(good)
}

/// One greedy step from key `a` (its velocity chosen) that goes past frame `floor`: the farthest
/// next key over the estimates it may carry ([`farthest`]; each estimate is searched only when it
/// meets the tolerances one frame past the farthest so far, or past `floor`), and the estimates
/// that reach that key; `None` when no estimate goes past `floor`. With `floor = a` there is
/// always a step (the next frame).
fn greedy_step(
    frames: &Frames,
    a: usize,
    floor: usize,
    opts: &ReduceOptions,
) -> InputResult<Option<(usize, Vec<usize>)>> {
    let n = frames.quats.len();
    let mut best: Option<(usize, Vec<usize>)> = None;
    for c in 0..frames.choices {
        let far = best.as_ref().map_or(floor, |b| b.0);
        if far < n - 1 && frames.feasible_with(a, far + 1, c, opts)? {
            best = Some((farthest(frames, a, far + 1, c, opts)?, vec![c]));
        } else if let Some((far, reach)) = &mut best
            && frames.feasible_with(a, *far, c, opts)?
        {
            reach.push(c);
        }
    }
    Ok(best)
}

/// Of the estimates `reach` key `b` may carry, the one from which the next step goes farthest
/// (the first on a tie), with that step. Each estimate after the first is searched only past
/// the farthest step so far ([`greedy_step`]'s `floor`).
fn look_ahead(
    frames: &Frames,
    b: usize,
    reach: &[usize],
    opts: &ReduceOptions,
) -> InputResult<(usize, (usize, Vec<usize>))> {
    let mut best: Option<(usize, (usize, Vec<usize>))> = None;
    for &c in reach {
        frames.choose(b, c);
        let floor = best.as_ref().map_or(b, |(_, (far, _))| *far);
        if let Some(next) = greedy_step(frames, b, floor, opts)? {
            best = Some((c, next));
        }
    }
    let (c, next) = best.unwrap_or((0, (b, Vec::new())));
    frames.choose(b, c);
    Ok((c, next))
}

/// Greedy keys: from each key the farthest next key whose segment alone meets the tolerances
/// ([`greedy_step`]). Where keys carry velocities and the scheme uses them, a key may carry any
/// of its frame's [`velocity_estimates`]: the farthest next key over them, and where several
/// estimates reach it, the one from which the step after goes farthest (one step of look-ahead;
/// the first frame likewise).
fn greedy_keys(frames: &Frames, opts: &ReduceOptions) -> InputResult<Vec<usize>> {
    let n = frames.quats.len();
    let mut keys = vec![0];
    let all: Vec<usize> = (0..frames.choices).collect();
    frames.before.set(None);
    let (_, mut step) = look_ahead(frames, 0, &all, opts)?;
    loop {
        let (b, reach) = step;
        frames.before.set(keys.last().copied());
        keys.push(b);
        if b >= n - 1 {
            return Ok(keys);
        }
        step = if reach.len() > 1 {
            look_ahead(frames, b, &reach, opts)?.1
        } else {
            frames.choose(b, reach[0]);
            greedy_step(frames, b, b, opts)?.unwrap_or((b + 1, vec![0]))
        };
    }
}

/// The longest segment (frames) the optimal method considers on a track whose greedy keys are
/// `greedy`: [`OPTIMAL_GREEDY_FACTOR`] times greedy's longest segment, at most
/// [`OPTIMAL_WINDOW`].
pub fn optimal_window(greedy: &[usize]) -> usize {
    let longest = greedy.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(1);
    (OPTIMAL_GREEDY_FACTOR * longest).min(OPTIMAL_WINDOW)
}

/// Each frame's preferred estimate for the optimal method: the one from which a segment starting
/// at the frame reaches farthest (up to `window` frames), the next key carrying its centred
/// estimate, searched as
/// [`greedy_step`] searches (the centred estimate first; another only when it meets the
/// tolerances one frame past the farthest so far). The last frame keeps its centred estimate.
fn preferred_estimates(frames: &Frames, window: usize, opts: &ReduceOptions) -> InputResult<()> {
    let n = frames.quats.len();
    for b in 0..n - 1 {
        // The shortest path takes no segment longer than the window: reaching past it is
        // reaching it (on held motion every estimate does, and the search ends there).
        let end = (b + window).min(n - 1);
        let reach =
            |from: usize| farthest_by(end + 1, from, |x| frames.feasible_with(b, x, 0, opts));
        frames.choose(b, 0);
        let mut best = (reach(b + 1)?, 0);
        for c in 1..frames.choices {
            frames.choose(b, c);
            if best.0 < end && frames.feasible_with(b, best.0 + 1, 0, opts)? {
                best = (reach(best.0 + 1)?, c);
            }
        }
        frames.choose(b, best.1);
    }
    frames.choose(n - 1, 0);
    Ok(())
}

/// Optimal keys: the shortest path over the frames, an edge wherever the segment between two
/// frames (each carrying its preferred estimate, [`preferred_estimates`]) alone meets the
/// tolerances, for segments of at most `window` frames.
fn optimal_keys(frames: &Frames, window: usize, opts: &ReduceOptions) -> InputResult<Vec<usize>> {
    if frames.choices > 1 {
        preferred_estimates(frames, window, opts)?;
    }
    let slerp = opts.curve.scheme == Scheme::Slerp && opts.curve.path == PathMode::Shortest;
    let mut speeds = SlerpSpeeds::new(0);
    shortest_path(frames.quats.len(), |a, b, improves, before| {
        if b == a + 1 {
            speeds = SlerpSpeeds::new(a);
            frames.before.set(before);
        }
        if slerp {
            if !speeds.admit(frames, b) {
                return Ok(Edge::Stop);
            }
        } else if b > a + window {
            return Ok(Edge::Stop);
        }
        Ok(
            if improves && (!slerp || speeds.allows(frames, b)) && frames.feasible(a, b, opts)? {
                Edge::Yes
            } else {
                Edge::No
            },
        )
    })
}

/// What [`shortest_path`] learns of the segment from one frame to a later one.
enum Edge {
    /// The segment meets the tolerances.
    Yes,
    /// It does not (or it need not be tested).
    No,
    /// Neither it nor any longer segment from the same frame does.
    Stop,
}

/// The fewest keys from frame 0 to frame `n − 1` (`n ≥ 2`) over the edges `edge(a, b, improves,
/// before)` says meet the tolerances, the frames `b` tried in increasing order from each
/// reachable `a` (`improves`: an edge `a → b` would shorten the path to `b`, so it needs
/// testing; `before`: the key before `a` on the shortest path to it). Ties go to the earliest
/// predecessor.
fn shortest_path(
    n: usize,
    mut edge: impl FnMut(usize, usize, bool, Option<usize>) -> InputResult<Edge>,
) -> InputResult<Vec<usize>> {
    let mut cost = vec![usize::MAX; n];
    let mut prev = vec![0usize; n];
    cost[0] = 0;
    for a in 0..n - 1 {
        if cost[a] == usize::MAX {
            continue;
        }
        for b in a + 1..n {
            let before = (a > 0).then(|| prev[a]);
            match edge(a, b, cost[a] + 1 < cost[b], before)? {
                Edge::Yes => {
                    cost[b] = cost[a] + 1;
                    prev[b] = a;
                }
                Edge::No => {}
                Edge::Stop => break,
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

/// Slerp's exact early cut. Slerp from key `a` to key `b` (the shorter way) turns at the constant
/// angular speed `ω = θ_ab / (t_b − t_a)`, so at a frame `k` between them it is `ω·(t_k − t_a)`
/// from `q_a`; if it is within the tolerance `T` of frame `k`, the triangle inequality of the
/// rotation angle gives `|θ_ak − ω·(t_k − t_a)| ≤ T`. Each frame inside the segment thus bounds
/// `ω` to an interval; the intervals of the frames after `a` only narrow as the segment grows,
/// and once they no longer meet, no segment from `a` reaching past them meets the tolerance.
struct SlerpSpeeds {
    lo: f64,
    hi: f64,
    a: usize,
}

impl SlerpSpeeds {
    fn new(a: usize) -> SlerpSpeeds {
        SlerpSpeeds {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            a,
        }
    }

    /// The tolerance on the angle, a hair wide (relative 1e-9, absolute 1e-12 rad, far above the
    /// rounding of the speeds) so that rounding never cuts a segment that meets it.
    fn tol(frames: &Frames) -> f64 {
        frames.threshold.angle * (1.0 + 1e-9) + 1e-12
    }

    /// The speed of slerp from `a` to `k` and the time between them.
    fn speed(&self, frames: &Frames, k: usize) -> (f64, f64) {
        let dt = frames.times[k] - frames.times[self.a];
        (
            rotation_angle_between(frames.quats[self.a], frames.quats[k]),
            dt,
        )
    }

    /// Frame `b − 1` joins the inside of the segment `a..b`; false when no segment from `a` to `b`
    /// or beyond can meet the tolerance.
    fn admit(&mut self, frames: &Frames, b: usize) -> bool {
        if b >= self.a + 2 {
            let (d, dt) = self.speed(frames, b - 1);
            let tol = Self::tol(frames);
            self.lo = self.lo.max((d - tol) / dt);
            self.hi = self.hi.min((d + tol) / dt);
        }
        self.lo <= self.hi
    }

    /// Whether the speed of slerp from `a` to `b` is in every inside frame's interval (if not,
    /// the segment misses the tolerance).
    fn allows(&self, frames: &Frames, b: usize) -> bool {
        let (d, dt) = self.speed(frames, b);
        (self.lo..=self.hi).contains(&(d / dt))
    }
}

/// The rotation error over a track's frames: largest, and sum in frame order; and the largest
/// position error, where positions are reduced.
#[derive(Debug, Clone, Copy, Default)]
struct Errors {
    max: f64,
    sum: f64,
    position: Option<f64>,
}

impl Errors {
    fn add(&mut self, e: f64) {
        self.max = self.max.max(e);
        self.sum += e;
    }
}

/// Completes `keys` until the whole curve meets the tolerances at every frame: the worst frame
/// of each segment that misses becomes a key. Returns the keys and the rotation error of their
/// curve over every frame.
fn verified(
    frames: &Frames,
    mut keys: Vec<usize>,
    opts: &ReduceOptions,
) -> InputResult<(Vec<usize>, Errors)> {
    loop {
        let curve = frames.curve(&keys, &opts.curve)?;
        let at_key = |k: usize| {
            let e = error(opts, curve.rotation(frames.times[k]), frames.quats[k]);
            // A key is its frame, unless it is written at another time (float32).
            if e > opts.tolerance * (1.0 - 1e-9) {
                return Err(key_time_miss(frames, k, e, opts));
            }
            Ok(e)
        };
        let mut errors = Errors::default();
        let mut added = Vec::new();
        for (piece, w) in keys.windows(2).enumerate() {
            errors.add(at_key(w[0])?);
            let (ok, worst) = frames.check(&curve, (piece, w[0], w[1]), opts, &mut errors);
            if !ok {
                added.push(worst);
            }
        }
        if let Some(&last) = keys.last() {
            errors.add(at_key(last)?);
        }
        if added.is_empty() {
            return Ok((keys, errors));
        }
        keys.extend(added);
        keys.sort_unstable();
        keys.dedup();
    }
}

/// The error for a key that misses its own frame: only a key written at another time than its
/// frame's ([`TrackFrames::key_times`]) can, when the motion in that time difference exceeds
/// the tolerance.
fn key_time_miss(
    frames: &Frames,
    k: usize,
    e: f64,
    opts: &ReduceOptions,
) -> crate::error::InputError {
    let written = frames.key_times.map_or(frames.times[k], |t| t[k]);
    let unit = if opts.distance.is_some() { "" } else { " rad" };
    crate::error::input_err!(
        "frame {k} ({} s): its key is written at {written} s (float32), and the motion in those \
         {:.1e} s misses the frame by {e:.3e}{unit}, more than the tolerance {:.3e}{unit}; give a \
         larger tolerance or a timeline nearer 0",
        frames.times[k],
        (written - frames.times[k]).abs(),
        opts.tolerance
    )
}

/// [`verified`] on every track, until the keys meet the tolerances on all. Returns the keys and
/// each track's error over its frames.
fn shared_verified(
    frames: &[Frames],
    mut keys: Vec<usize>,
    opts: &ReduceOptions,
) -> InputResult<(Vec<usize>, Vec<Errors>)> {
    // Each track's errors and the number of keys they were measured on. Keys only grow, so a
    // track measured on as many keys as there are now was measured on the final keys.
    let mut measured: Vec<Option<(usize, Errors)>> = vec![None; frames.len()];
    for t in (0..frames.len()).cycle() {
        if measured
            .iter()
            .all(|m| m.is_some_and(|(n, _)| n == keys.len()))
        {
            break;
        }
        let (k, e) = verified(&frames[t], keys, opts)?;
        keys = k;
        measured[t] = Some((keys.len(), e));
    }
    let errors = measured.into_iter().flatten().map(|(_, e)| e).collect();
    Ok((keys, errors))
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

    /// The probe (one segment evaluated on reused knots, the curve then built from them) and
    /// the held-pose shortcut decide every segment test as the segment's own curve does, on
    /// motion with a held stretch, with positions, on each path and segment scheme.
    #[test]
    fn probed_and_held_segment_tests_decide_as_the_built_curve() {
        let seq = crate::EulerSeq::parse("ZYX").unwrap();
        let n = 90;
        let t: Vec<f64> = (0..n).map(|i| i as f64 / 30.0).collect();
        // Held from frame 30 to 60 (exactly: the same angles), moving elsewhere.
        let e: Vec<DVec3> = t
            .iter()
            .map(|&t| {
                let s = t.min(1.0) + (t - 2.0).max(0.0) * 0.5;
                DVec3::new(2.1 * s, 0.5 * (3.0 * s).sin(), 0.3 * s * s)
            })
            .collect();
        let q: Vec<DQuat> = e.iter().map(|e| seq.to_quat(e.to_array())).collect();
        let p: Vec<DVec3> = e.iter().map(|e| *e * 10.0).collect();
        let track = TrackFrames {
            times: &t,
            rotations: &q,
            positions: Some(&p),
            euler: Some((seq, &e)),
            key_times: None,
        };
        let mut probed = 0;
        for scheme in [
            Scheme::Bezier,
            Scheme::Hermite,
            Scheme::Squad,
            Scheme::Slerp,
        ] {
            for path in [PathMode::Shortest, PathMode::Euler] {
                let opts = ReduceOptions {
                    curve: CurveOptions {
                        scheme,
                        path,
                        ..CurveOptions::default()
                    },
                    tolerance: 0.5f64.to_radians(),
                    distance: None,
                    translation_tolerance: Some(0.05),
                    velocities: true,
                    method: Method::Greedy,
                };
                let fast = Frames::new(&track, &opts);
                let mut plain = Frames::new(&track, &opts);
                assert!(fast.probe.is_some() && fast.held_until[30] == 60);
                (plain.probe, plain.held_until) = (None, Vec::new());
                for a in 0..n - 1 {
                    for b in a + 1..(a + 40).min(n) {
                        for c in [0, 1, 3] {
                            for f in [&fast, &plain] {
                                f.choose(b, c);
                                f.choose(a, (a + c) % ESTIMATES);
                            }
                            let got = fast.feasible(a, b, &opts).unwrap();
                            let want = plain.feasible(a, b, &opts).unwrap();
                            assert_eq!(got, want, "{scheme} {path:?} {a}..{b} estimate {c}");
                            probed += usize::from(got);
                        }
                    }
                }
            }
        }
        // Both outcomes occur.
        assert!(probed > 1000 && probed < 8 * 3 * 89 * 39, "{probed}");
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
    fn even_spacing_is_a_frame_clock() {
        let clock: Vec<f64> = (0..1000).map(|k| k as f64 / 29.97).collect();
        let dt = even_spacing(&clock).unwrap();
        assert!((dt - 1.0 / 29.97).abs() < 1e-15);
        // Off by 1e-6 of a frame at one frame: not evenly spaced.
        let mut off = clock.clone();
        off[500] += 1e-6 * dt;
        assert_eq!(even_spacing(&off), None);
        assert_eq!(even_spacing(&[0.0, 0.5]), None);
        assert_eq!(even_spacing(&[0.0, 0.1, 0.3]), None);
    }

    #[test]
    fn evenly_spaced_frames_decide_as_the_direct_evaluation() {
        let (t, q) = smooth(241, 120.0);
        for scheme in [
            Scheme::Slerp,
            Scheme::Hermite,
            Scheme::Squad,
            Scheme::Bezier,
        ] {
            for tolerance in [0.1f64, 0.5, 2.0] {
                let opts = ReduceOptions {
                    curve: CurveOptions {
                        scheme,
                        ..CurveOptions::default()
                    },
                    tolerance: tolerance.to_radians(),
                    distance: None,
                    translation_tolerance: None,
                    velocities: true,
                    method: Method::Greedy,
                };
                let frames = TrackFrames {
                    times: &t,
                    rotations: &q,
                    positions: None,
                    euler: None,
                    key_times: None,
                };
                let even = Frames::new(&frames, &opts);
                assert!(even.spacing.is_some());
                let direct = Frames {
                    spacing: None,
                    ..Frames::new(&frames, &opts)
                };
                let keys = greedy_keys(&even, &opts).unwrap();
                assert!(keys.len() > 2, "{scheme} {tolerance}");
                assert_eq!(
                    keys,
                    greedy_keys(&direct, &opts).unwrap(),
                    "{scheme} {tolerance}"
                );
            }
        }
    }

    #[test]
    fn velocity_estimates_are_exact_where_their_order_says() {
        // About a fixed axis the log map is linear in the angle: θ(t) = ω0·t + α·t²/2, uneven
        // spacing. Second-order stencils give θ'(t) exactly; first-order ones miss it by
        // α·(t_j − t_i)/2.
        let axis = DVec3::new(1.0, -2.0, 0.5).normalize();
        let (w0, alpha) = (1.3, 0.8);
        let t: Vec<f64> = (0..9)
            .map(|i| 0.1 * i as f64 + 0.01 * (i * i) as f64)
            .collect();
        let q: Vec<DQuat> = t
            .iter()
            .map(|&t| DQuat::from_axis_angle(axis, w0 * t + 0.5 * alpha * t * t))
            .collect();
        let e = velocity_estimates(&t, &q);
        for i in 0..t.len() {
            let exact = axis * (w0 + alpha * t[i]);
            for c in [0, 3, 4, 5] {
                assert!((e[i][c] - exact).length() < 1e-12, "{i} {c}: {}", e[i][c]);
            }
            if i >= 1 {
                let first = axis * (w0 + alpha * 0.5 * (t[i] + t[i - 1]));
                assert!((e[i][1] - first).length() < 1e-12, "{i} backward");
            }
            if i + 1 < t.len() {
                let first = axis * (w0 + alpha * 0.5 * (t[i] + t[i + 1]));
                assert!((e[i][2] - first).length() < 1e-12, "{i} forward");
            }
        }
        // Where a stencil runs off the track, the centred estimate stands in.
        assert_eq!(e[0][1], e[0][0]);
        assert_eq!(e[1][3], e[1][0]);
        assert_eq!(e[8][4], e[8][0]);
        assert_eq!(e[7][5], e[7][0]);
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
