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
//! A key carries one of its frame's `velocity_estimates` (finite differences of the frames:
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
//!   to `optimal_window` frames: twice greedy's longest segment on the track, at most
//!   `OPTIMAL_WINDOW`): the fewest keys, among key sets whose keys carry their preferred
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
use crate::error::{Error, InputResult};
use crate::rotation::quat::{log, rotation_angle_between};
use crate::tangent::{EndConditions, Ends, Knots, PathMode, apply_path};
use crate::track::Track;
use glam::{DQuat, DVec3};
use std::cell::RefMut;

mod estimates;
mod frames;
mod greedy;
mod optimal;
mod shared;
mod verify;
mod world;

pub(crate) use estimates::ESTIMATES;
#[cfg(test)]
use estimates::frame_velocities;
pub(crate) use estimates::velocity_estimates;
use frames::Frames;
use frames::error;
pub use frames::error as rotation_error;
use greedy::{farthest_by, greedy_keys};
pub(crate) use optimal::optimal_window;
use optimal::{Edge, SlerpSpeeds, optimal_keys, shortest_path};
pub use shared::reduce_shared;
pub(crate) use shared::reduce_shared_each;
pub use verify::curve_errors;
use verify::{Errors, shared_verified, verified};
pub use world::{Budget, WorldReduced, WorldTolerance, reduce_world};

/// A minaccel segment test solves at most this many times the grid steps its frames span (one
/// refinement of the frame grid), plus [`SEGMENT_GRID_SLACK`] points; a segment whose start curve
/// needs more is not feasible (docs/spec.md §4.7).
pub(crate) const SEGMENT_GRID_FACTOR: usize = 2;

/// Grid points a minaccel segment test may use beyond [`SEGMENT_GRID_FACTOR`] times its steps
/// (the extra steps beside keys with their own velocities, and phantom points).
pub(crate) const SEGMENT_GRID_SLACK: usize = 8;

/// Longest segment (frames) the optimal method considers.
pub(crate) const OPTIMAL_WINDOW: usize = 600;

/// The optimal method considers segments up to this many times the longest segment of the
/// track's greedy keys ([`optimal_window`]).
pub(crate) const OPTIMAL_GREEDY_FACTOR: usize = 2;

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
    /// Give each key an estimate of the frames' angular velocity at it (`velocity_estimates`).
    pub velocities: bool,
    /// Greedy or optimal.
    pub method: Method,
}

impl Default for ReduceOptions {
    /// The command line's defaults: keys for the default curve ([`CurveOptions::default`],
    /// bezier), a tolerance of 0.5° (what the README's examples use; the command line has no
    /// default and asks for one), the error as an angle, positions not reduced, key velocities
    /// estimated, the greedy method.
    fn default() -> ReduceOptions {
        ReduceOptions {
            curve: CurveOptions::default(),
            tolerance: 0.5f64.to_radians(),
            distance: None,
            translation_tolerance: None,
            velocities: true,
            method: Method::Greedy,
        }
    }
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

/// Reduces one track (see the module documentation). `positions`, when given, are the frames'
/// translations, and need `translation_tolerance`. Frames given as Euler angles, for
/// `--path euler`: [`reduce_frames`].
pub fn reduce(
    times: &[f64],
    quats: &[DQuat],
    positions: Option<&[DVec3]>,
    opts: &ReduceOptions,
) -> Result<Reduced, Error> {
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
pub fn reduce_frames(track: &TrackFrames<'_>, opts: &ReduceOptions) -> Result<Reduced, Error> {
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
        std::slice::from_ref(opts),
        || greedy_keys(&frames[0], opts),
        |window| optimal_keys(&frames[0], window, opts),
    )?;
    reduced(&frames[0], keys, errors[0], opts)
}

/// `r`'s keys with the frames `added` made keys too (each carrying its centred velocity
/// estimate; `r`'s keys keep theirs), completed by verification under `opts` (docs/spec.md
/// §4.7: the worst frame of each segment that misses becomes a key). `r` must be a result of
/// [`reduce_frames`] on `track` with options differing from `opts` in their tolerances only.
pub(crate) fn with_keys(
    track: &TrackFrames<'_>,
    r: &Reduced,
    added: &[usize],
    opts: &ReduceOptions,
) -> Result<Reduced, Error> {
    let frames = Frames::new(track, opts);
    if let (Some(estimates), Some(velocities)) = (&frames.estimates, &r.velocities) {
        for (&k, v) in r.keys.iter().zip(velocities) {
            let c = estimates[k].iter().position(|e| e == v).ok_or_else(|| {
                Error::Internal(format!(
                    "internal error: key {k}'s velocity is none of its frame's estimates"
                ))
            })?;
            frames.choose(k, c);
        }
    }
    let mut keys = r.keys.clone();
    keys.extend(added.iter().filter(|&&k| k < frames.quats.len()));
    keys.sort_unstable();
    keys.dedup();
    let (keys, errors) = verified(&frames, keys, opts)?;
    reduced(&frames, keys, errors, opts)
}

/// The keys `opts.method` gives tracks reduced together (one track, or shared keys): `greedy`'s
/// keys, verified; for optimal, `optimal`'s (given the window of greedy's keys), verified, unless
/// they are more than greedy's, whose estimates are then restored. minaccel's optimal keeps
/// greedy's keys: its segments are not local, and a shortest path would solve a curve per tested
/// segment (minutes on a few hundred frames) for a test that is not exact anyway. Returns the
/// keys and each track's errors on them. `opts` are each track's options (differing in their
/// tolerances only).
fn method_keys(
    frames: &[Frames],
    opts: &[ReduceOptions],
    greedy: impl FnOnce() -> InputResult<Vec<usize>>,
    optimal: impl FnOnce(usize) -> InputResult<Vec<usize>>,
) -> InputResult<(Vec<usize>, Vec<Errors>)> {
    if opts[0].curve.scheme == Scheme::Nlerp && opts[0].curve.path == PathMode::Euler {
        // Curve::new refuses it too; the segment tests build their curves from knots.
        return Err(crate::InputError::new(
            "path euler: nlerp blends the keys' four components and cannot keep a turn of a \
             whole rotation or more between two keys; use another scheme",
        ));
    }
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
    if opts[0].method == Method::Greedy || opts[0].curve.scheme == Scheme::MinAccel {
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
) -> Result<Reduced, Error> {
    if errors.max > opts.tolerance * (1.0 + 1e-12) {
        return Err(Error::Internal(format!(
            "internal error: reduce's keys miss a frame by {:e} (tolerance {:e})",
            errors.max, opts.tolerance
        )));
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
/// (at most `MAX_THREADS` (8) threads, tracks taken in order as threads come free). The result is
/// in the tracks' order and the same whatever the number of threads; on errors, the first
/// track's error.
pub fn reduce_each(
    tracks: &[TrackFrames<'_>],
    opts: &ReduceOptions,
) -> Result<Vec<Reduced>, Error> {
    crate::parallel::map(tracks, |t| reduce_frames(t, opts))
        .into_iter()
        .collect()
}

/// The track of a reduced track's kept keys, as `interp` reads them back: their times (the
/// frames' key times where given), rotations, velocities, translations where the frames have
/// them, and Euler angles for `--path euler`. The curve [`Curve::new`] builds from it with the
/// options the track was reduced for is the curve reduce verified.
pub(crate) fn kept_track(
    track: &TrackFrames<'_>,
    r: &Reduced,
    opts: &CurveOptions,
) -> InputResult<Track> {
    let key_times = track.key_times.unwrap_or(track.times);
    let t: Vec<f64> = r.keys.iter().map(|&i| key_times[i]).collect();
    let q: Vec<DQuat> = r.keys.iter().map(|&i| track.rotations[i]).collect();
    let mut out = Track::new(t, q)?;
    if let Some(v) = &r.velocities {
        out = out.with_key_velocities(v.iter().copied().map(Some).collect())?;
    }
    if let Some(p) = track.positions {
        out = out.with_translations(r.keys.iter().map(|&i| p[i]).collect())?;
    }
    if let Some((seq, e)) = track.euler.filter(|_| opts.path == PathMode::Euler) {
        out = out.with_euler_angles(seq, r.keys.iter().map(|&i| e[i]).collect())?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::frames::even_spacing;
    use super::*;

    fn rotations_only<'a>(times: &'a [f64], rotations: &'a [DQuat]) -> TrackFrames<'a> {
        TrackFrames {
            times,
            rotations,
            positions: None,
            euler: None,
            key_times: None,
        }
    }

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

    /// Frames added to a reduced track's keys become keys carrying their centred estimates
    /// (their velocity the curve's through the neighbouring frames), the old keys keep their
    /// velocities, and the result meets the tolerance.
    #[test]
    fn added_keys_carry_the_centred_estimate_and_the_rest_keep_theirs() {
        let (t, q) = smooth(240, 60.0);
        let frames = rotations_only(&t, &q);
        let opts = ReduceOptions {
            tolerance: 0.3f64.to_radians(),
            ..ReduceOptions::default()
        };
        let r = reduce_frames(&frames, &opts).unwrap();
        let added: Vec<usize> = r
            .keys
            .windows(2)
            .filter(|w| w[1] - w[0] > 2)
            .map(|w| (w[0] + w[1]) / 2)
            .collect();
        assert!(added.len() > 3, "{:?}", r.keys);
        let more = with_keys(&frames, &r, &added, &opts).unwrap();
        let velocity = |x: &Reduced, k: usize| {
            let i = x.keys.binary_search(&k).unwrap();
            x.velocities.as_ref().unwrap()[i]
        };
        assert_eq!(more.keys.len(), r.keys.len() + added.len());
        for &k in &r.keys {
            assert_eq!(velocity(&more, k), velocity(&r, k));
        }
        let centred = Frames::new(&frames, &opts).estimates.unwrap();
        for &k in &added {
            assert_eq!(velocity(&more, k), centred[k][0]);
        }
        assert!(more.max_error <= opts.tolerance);
        let curve = Curve::new(
            &kept_track(&frames, &more, &opts.curve).unwrap(),
            &opts.curve,
        );
        let (worst, _) = curve_errors(&frames, &curve.unwrap(), &opts);
        assert!(worst <= opts.tolerance, "{worst}");
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
                let frames = rotations_only(&t, &q);
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
