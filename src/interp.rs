//! The in-betweening loop: for each track, every frame of the output grid (SPEC §3), segment by
//! segment, streamed to a [`FrameSink`].
//!
//! Frame `k` is at `k/fps` (exact rational, from the index). A track's frames are those with
//! `t_1 − 1e-9 ≤ k/fps ≤ t_n + 1e-9`. Segment `s` takes the frames with
//! `t_s − 1e-9 ≤ k/fps < t_{s+1} − 1e-9` (the last segment up to `t_n + 1e-9`); a frame within
//! 1e-9 s of a key is that key exactly (`u = 0`, or `u = 1` at the last key), the others run the
//! scheme's forward differences from the segment's first frame with step `δ = 1/(fps·Δ_s)`.

use crate::clock::{Fps, TIME_TOL};
use crate::curve::bezier::Bezier;
use crate::curve::hermite::Hermite;
use crate::curve::minaccel::{self, Report};
use crate::curve::slerp::Slerp;
use crate::curve::squad::Squad;
use crate::curve::{Blend, Scheme, Segment, antipode_gap};
use crate::io::write::FrameSink;
use crate::keys::TimedTrack;
use crate::motion::{Side, TrackCurve, segment_omega};
use crate::rotation::quat::geodesic;
use crate::tangent::{EndConditions, Keys, PathMode};
use glam::{DQuat, DVec3};
use std::io;

/// Everything `interp` needs besides the tracks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    pub fps: Fps,
    pub scheme: Scheme,
    pub blend: Blend,
    pub path: PathMode,
    pub ends: EndConditions,
    /// Compute each frame's angular velocity (SPEC: `interp --velocity`).
    pub velocity: bool,
    /// Generate long tracks on two threads (same frames; off for comparisons).
    pub parallel: bool,
}

/// Tolerance for "a blend comes within 1e-9 of an antipode" (SPEC §4.3).
pub const ANTIPODE_TOL: f64 = 1e-9;

/// Interpolates every track into `sink`. Warnings (antipodal blends, a solver that did not
/// converge) go to `warn`. Returns the minaccel solver's report of each track (empty for the
/// other schemes). Errors: the sink's I/O errors, and an [`crate::InputError`] when minaccel
/// cannot solve a track (its grid would be too large) — possibly after earlier tracks were
/// written, which is why `-o` output is atomic.
pub fn run(
    tracks: &[TimedTrack],
    settings: &Settings,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&str),
) -> anyhow::Result<Vec<Report>> {
    let mut reports = Vec::new();
    for track in tracks {
        let keys = Keys::new(track, settings.path, settings.ends);
        sink.begin_track(track.name.as_deref())?;
        match settings.scheme {
            Scheme::Slerp => track_frames::<Slerp>(&keys, track, settings, sink, warn)?,
            Scheme::Hermite => track_frames::<Hermite>(&keys, track, settings, sink, warn)?,
            Scheme::Squad => track_frames::<Squad>(&keys, track, settings, sink, warn)?,
            Scheme::Bezier => track_frames::<Bezier>(&keys, track, settings, sink, warn)?,
            Scheme::MinAccel => {
                reports.push(minaccel_frames(&keys, track, settings, sink, warn)?);
            }
        }
        sink.end_track()?;
    }
    sink.finish()?;
    Ok(reports)
}

/// `minaccel`: solve on the grid, then every frame by slerp of its neighbouring grid points (a
/// frame within 1e-9 s of a grid point is that point, so keys are exact).
fn minaccel_frames(
    keys: &Keys,
    track: &TimedTrack,
    settings: &Settings,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&str),
) -> anyhow::Result<Report> {
    let fps = settings.fps;
    let sol = minaccel::solve(keys, fps.as_f64()).map_err(|e| match &track.name {
        Some(n) => e.at(format!("track \"{n}\"")),
        None => e,
    })?;
    let r = sol.report;
    if !r.converged {
        let name = track
            .name
            .as_deref()
            .map_or(String::new(), |n| format!("track \"{n}\": "));
        warn(&format!(
            "{name}minaccel did not converge in {} iterations (projected gradient {:.1e}, {:.1e} \
             of its start); the frames are the best curve found",
            r.iterations,
            r.gradient,
            r.gradient / r.gradient_start
        ));
    }
    let curve = TrackCurve::Grid {
        times: sol.times,
        points: sol.points,
        key_times: keys.times.clone(),
    };
    let (times, pts) = (curve.breaks(), curve.grid_points());
    let n = times.len();
    let (first, last) = fps.frames_between(times[0], times[n - 1]);
    let mut j = 0;
    for k in first..=last {
        let t = fps.time_of(k);
        // The next grid interval once within 1e-9 s of its start, unless nearer this one's.
        while j + 2 < n && t >= times[j + 1] - TIME_TOL && times[j + 1] - t <= t - times[j] {
            j += 1;
        }
        let q = if (t - times[j]).abs() <= TIME_TOL {
            pts[j]
        } else if (t - times[j + 1]).abs() <= TIME_TOL {
            pts[j + 1]
        } else {
            let u = ((t - times[j]) / (times[j + 1] - times[j])).clamp(0.0, 1.0);
            geodesic(pts[j], pts[j + 1], u)
        };
        let omega = settings.velocity.then(|| {
            let side = if k == last { Side::Left } else { Side::Right };
            // On a grid point, the grid point's own time (frames snap to it).
            let tg = if (t - times[j]).abs() <= TIME_TOL {
                times[j]
            } else if (t - times[j + 1]).abs() <= TIME_TOL {
                times[j + 1]
            } else {
                t
            };
            curve.omega(tg, side)
        });
        sink.frame(k, t, q, omega)?;
    }
    Ok(r)
}

/// The frames `[from, to)` of segment `s` (only segments with frames are listed).
#[derive(Debug, Clone, Copy)]
struct SegmentFrames {
    s: usize,
    from: i64,
    to: i64,
}

/// Which frames each segment writes (see the module documentation).
fn plan(keys: &Keys, fps: Fps) -> Vec<SegmentFrames> {
    let times = &keys.times;
    let n = times.len();
    let (first, last) = fps.frames_between(times[0], times[n - 1]);
    let mut k = first;
    let mut out = Vec::new();
    for s in 0..n - 1 {
        let (t0, t1) = (times[s], times[s + 1]);
        let k_end = if s == n - 2 {
            last + 1
        } else {
            // Frames from 1e-9 s before the next key belong to it, except one that is nearer
            // this key (keys less than 2e-9 s apart).
            let mut e = fps.first_frame_from(t1).min(last + 1);
            while e <= last && fps.time_of(e) < t1 && fps.time_of(e) - t0 < t1 - fps.time_of(e) {
                e += 1;
            }
            e
        };
        if k < k_end {
            out.push(SegmentFrames {
                s,
                from: k,
                to: k_end,
            });
            k = k_end;
        }
    }
    out
}

/// One generated frame: number, time, rotation, angular velocity.
type Frame = (i64, f64, DQuat, Option<DVec3>);

/// Generates the frames of one segment into `emit`; warnings about it go to `warn`.
fn segment_frames<S: Segment>(
    keys: &Keys,
    track: &TimedTrack,
    settings: &Settings,
    p: SegmentFrames,
    warn: &mut dyn FnMut(&str),
    emit: &mut dyn FnMut(Frame) -> io::Result<()>,
) -> io::Result<()> {
    let fps = settings.fps;
    let times = &keys.times;
    let n = times.len();
    let s = p.s;
    let (t0, t1) = (times[s], times[s + 1]);
    let period = fps.den() as f64 / fps.num() as f64;
    let seg = S::new(keys, s, settings.blend);
    let name = || {
        track
            .name
            .as_deref()
            .map_or(String::new(), |n| format!("track \"{n}\", "))
    };
    if let Some(note) = seg.limitation() {
        warn(&format!("{}segment {s} ({t0} s to {t1} s): {note}", name()));
    }
    if let Some((gap, u)) = antipode_gap(&seg)
        && gap < ANTIPODE_TOL
    {
        warn(&format!(
            "{}segment {s} ({t0} s to {t1} s): a blend of the {} curve comes within \
             {gap:.1e} of an antipode at u = {u:.4}, where the curve may jump; add keys or \
             use --scheme minaccel",
            name(),
            settings.scheme.name()
        ));
    }
    let delta = t1 - t0;
    let omega = |u: f64| settings.velocity.then(|| segment_omega(&seg, u, delta));
    let mut k = p.from;
    if (fps.time_of(k) - t0).abs() <= TIME_TOL {
        emit((k, fps.time_of(k), keys.quats[s], omega(0.0)))?;
        k += 1;
    }
    let end_snap = s == n - 2 && k < p.to && (fps.time_of(p.to - 1) - t1).abs() <= TIME_TOL;
    let stop = if end_snap { p.to - 1 } else { p.to };
    if stop > k {
        let u0 = (fps.time_of(k) - t0) / delta;
        let du = period / delta;
        for (j, q) in seg.frames(u0, du).take((stop - k) as usize).enumerate() {
            let kj = k + j as i64;
            let w = omega((fps.time_of(kj) - t0) / delta);
            emit((kj, fps.time_of(kj), q, w))?;
        }
        k = stop;
    }
    if end_snap {
        emit((k, fps.time_of(k), keys.quats[n - 1], omega(1.0)))?;
    }
    Ok(())
}

/// Tracks with at least this many frames are generated on two threads.
const PARALLEL_FRAMES: i64 = 1 << 17;
/// About this many frames per chunk of segments handed to the second thread.
const CHUNK_FRAMES: i64 = 1 << 14;

/// Every frame of a track into `sink`, in order. A long track is generated on two threads:
/// chunks of segments alternate between this thread (straight into the sink) and a worker whose
/// frames come back through a one-slot channel, so memory stays bounded and the sink sees the
/// frames in order (and the same frames: each segment is generated the same way either way).
fn track_frames<S: Segment>(
    keys: &Keys,
    track: &TimedTrack,
    settings: &Settings,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&str),
) -> io::Result<()> {
    let plans = plan(keys, settings.fps);
    let total: i64 = plans.iter().map(|p| p.to - p.from).sum();
    let mut to_sink = |(k, t, q, w): Frame| sink.frame(k, t, q, w);
    let parallel = settings.parallel
        && total >= PARALLEL_FRAMES
        && plans.len() >= 2
        && std::thread::available_parallelism().is_ok_and(|n| n.get() >= 2);
    if !parallel {
        for &p in &plans {
            segment_frames::<S>(keys, track, settings, p, warn, &mut to_sink)?;
        }
        return Ok(());
    }
    // Chunks of consecutive segments of about CHUNK_FRAMES frames.
    let mut chunks = Vec::new();
    let (mut start, mut frames) = (0, 0);
    for (i, p) in plans.iter().enumerate() {
        frames += p.to - p.from;
        if frames >= CHUNK_FRAMES || i + 1 == plans.len() {
            chunks.push(start..i + 1);
            (start, frames) = (i + 1, 0);
        }
    }
    std::thread::scope(|scope| {
        let (tx, rx) = std::sync::mpsc::sync_channel::<(Vec<Frame>, Vec<String>)>(1);
        let (plans, chunks) = (&plans, &chunks);
        scope.spawn(move || {
            for c in chunks.iter().skip(1).step_by(2) {
                let mut frames = Vec::with_capacity(CHUNK_FRAMES as usize + 4096);
                let mut notes = Vec::new();
                for &p in &plans[c.clone()] {
                    let _ = segment_frames::<S>(
                        keys,
                        track,
                        settings,
                        p,
                        &mut |m| notes.push(m.to_string()),
                        &mut |f| {
                            frames.push(f);
                            Ok(())
                        },
                    );
                }
                if tx.send((frames, notes)).is_err() {
                    return;
                }
            }
        });
        for (i, c) in chunks.iter().enumerate() {
            if i % 2 == 0 {
                for &p in &plans[c.clone()] {
                    segment_frames::<S>(keys, track, settings, p, warn, &mut to_sink)?;
                }
            } else {
                let (frames, notes) = rx
                    .recv()
                    .map_err(|_| io::Error::other("the generating thread stopped"))?;
                for m in &notes {
                    warn(m);
                }
                for f in frames {
                    to_sink(f)?;
                }
            }
        }
        Ok(())
    })
}

/// Direct evaluation of a track's curve at time `t` (clamped to the keys' span), for tests and
/// samples off the frame grid. `None` for `minaccel`, which has no closed form (solve it with
/// [`minaccel::solve`]).
pub fn eval_at(keys: &Keys, scheme: Scheme, blend: Blend, t: f64) -> Option<glam::DQuat> {
    let times = &keys.times;
    let s = match times.iter().rposition(|&tk| tk <= t) {
        None => 0,
        Some(i) => i.min(times.len() - 2),
    };
    let u = ((t - times[s]) / keys.delta(s)).clamp(0.0, 1.0);
    Some(match scheme {
        Scheme::Slerp => Slerp::new(keys, s, blend).eval(u),
        Scheme::Hermite => Hermite::new(keys, s, blend).eval(u),
        Scheme::Squad => Squad::new(keys, s, blend).eval(u),
        Scheme::Bezier => Bezier::new(keys, s, blend).eval(u),
        Scheme::MinAccel => return None,
    })
}
