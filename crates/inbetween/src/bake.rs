//! Baking: a curve's frames on a frame grid, streamed into a [`FrameSink`] (docs/spec.md §3).
//!
//! Which frames a track has, which segment each belongs to, and when a frame is a key is the
//! frame clock's rule (`Fps::pieces`). A frame on a key is the key exactly; the others run the
//! scheme's forward differences from the segment's first frame with step `δ = 1/(fps·Δ_s)`
//! (`Segment::frames`); minaccel's frames are great arcs between the grid points either side.
//!
//! ```
//! use inbetween::{BakeOptions, Curve, CurveOptions, FrameSink, Fps, Track, bake};
//! use glam::{DQuat, DVec3};
//!
//! /// Collects the frames of one track.
//! #[derive(Default)]
//! struct Frames(Vec<(i64, f64, DQuat)>);
//!
//! impl FrameSink for Frames {
//!     fn frame(&mut self, k: i64, t: f64, q: DQuat, _w: Option<DVec3>) -> std::io::Result<()> {
//!         self.0.push((k, t, q));
//!         Ok(())
//!     }
//! }
//!
//! let track = Track::new(
//!     vec![0.0, 0.5, 1.0],
//!     vec![DQuat::IDENTITY, DQuat::from_rotation_x(1.0), DQuat::from_rotation_y(1.0)],
//! )?;
//! let curve = Curve::new(&track, &CurveOptions::default())?;
//! let mut frames = Frames::default();
//! bake(&curve, Fps::new(24, 1)?, BakeOptions::default(), &mut frames, &mut |_| {})?;
//! assert_eq!(frames.0.len(), 25); // frames 0..=24
//! assert_eq!(frames.0[12].2, track.rotations()[1]); // frame 12 is the middle key, exactly
//! assert!((frames.0[5].2 - curve.rotation(5.0 / 24.0)).length() < 1e-13);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::clock::{Fps, PieceFrames};
use crate::curve::bezier::Bezier;
use crate::curve::hermite::Hermite;
use crate::curve::nlerp::Nlerp;
use crate::curve::piecewise::{Side, segment_omega, step_in};
use crate::curve::slerp::Slerp;
use crate::curve::squad::Squad;
use crate::curve::{Curve, Scheme, Segment};
use crate::error::Message;
use crate::rotation::quat::geodesic;
use glam::{DQuat, DVec3};
use std::io;

mod queue;

use queue::{Out, Queue, check_segment};

/// Receives a curve's frames, track by track: [`bake()`] calls `begin_track`, `frame` for every
/// frame in order, then `end_track`; the caller calls `finish` after the last track. Only
/// `frame` must be written: the others do nothing unless a sink needs them (a file format that
/// opens and closes tracks).
pub trait FrameSink {
    /// A track starts (`name` when it has one).
    fn begin_track(&mut self, _name: Option<&str>) -> io::Result<()> {
        Ok(())
    }
    /// Right after `begin_track`, when the track's keys were given as Euler angles: the first
    /// key's triple in `seq` (radians, as written). A sink writing continuous Euler angles in
    /// the same sequence starts the track from it (docs/spec.md, Output of `interp`).
    fn euler_start(&mut self, _seq: crate::EulerSeq, _angles: [f64; 3]) {}
    /// One frame: its number `k` on the grid, its time `k/fps` in seconds, the rotation, and
    /// the world-frame angular velocity in rad/s when it was asked for.
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()>;
    /// One frame of a track with translations: [`FrameSink::frame`] and the position. A sink
    /// that writes positions overrides it; the default drops the position.
    fn frame_at(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        _position: DVec3,
    ) -> io::Result<()> {
        self.frame(k, time, q, omega)
    }
    /// The track's last frame has been given.
    fn end_track(&mut self) -> io::Result<()> {
        Ok(())
    }
    /// The last track has ended: write what closes the output and flush it.
    fn finish(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// What [`bake()`] computes besides the rotations, and how.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BakeOptions {
    /// Compute each frame's world-frame angular velocity (`interp --velocity`).
    pub velocity: bool,
    /// Generate long tracks on two threads (same frames, in order). Pays when the sink is cheap
    /// (npy output); with text output the formatting thread already uses the second core.
    pub parallel: bool,
}

/// Tolerance for "a blend comes within 1e-9 of an antipode" (docs/spec.md §4.3).
pub(crate) const ANTIPODE_TOL: f64 = 1e-9;

/// Streams every frame of `curve` on the grid of `fps` (frames `k` with `k/fps` in the curve's
/// span, ±1e-9 s) into `sink`, between `begin_track` and `end_track`. Warnings (a blend near an
/// antipode, squad's aliased inner points, a minaccel solve that did not converge) go to `warn`.
/// The only errors are the sink's.
pub fn bake(
    curve: &Curve,
    fps: Fps,
    opts: BakeOptions,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&Message),
) -> io::Result<()> {
    bake_over(curve, fps, curve.span(), opts, sink, warn)
}

/// [`bake()`] over a longer span `[lo, hi]` (widened to contain the curve's own): the frames
/// before the first key hold the first key and those after the last key hold the last key, at
/// rest (glTF's clamp). This is how several tracks are written over one clip.
pub fn bake_over(
    curve: &Curve,
    fps: Fps,
    (lo, hi): (f64, f64),
    opts: BakeOptions,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&Message),
) -> io::Result<()> {
    if curve.has_positions() {
        let mut with = WithPositions { sink, curve };
        return frames_over(curve, fps, (lo, hi), opts, &mut with, warn);
    }
    frames_over(curve, fps, (lo, hi), opts, sink, warn)
}

/// A sink that adds each frame's position (of a track with translations) and hands it on.
struct WithPositions<'a> {
    sink: &'a mut dyn FrameSink,
    curve: &'a Curve,
}

impl FrameSink for WithPositions<'_> {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()> {
        self.sink.begin_track(name)
    }
    fn euler_start(&mut self, seq: crate::EulerSeq, angles: [f64; 3]) {
        self.sink.euler_start(seq, angles)
    }
    #[inline]
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        let p = self.curve.position(time).unwrap_or(DVec3::ZERO);
        self.sink.frame_at(k, time, q, omega, p)
    }
    fn end_track(&mut self) -> io::Result<()> {
        self.sink.end_track()
    }
    fn finish(&mut self) -> io::Result<()> {
        self.sink.finish()
    }
}

/// [`bake_over`]'s frames, into `sink`.
fn frames_over(
    curve: &Curve,
    fps: Fps,
    (lo, hi): (f64, f64),
    opts: BakeOptions,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&Message),
) -> io::Result<()> {
    sink.begin_track(curve.name())?;
    if let Some((seq, angles)) = curve.euler_start() {
        sink.euler_start(seq, angles);
    }
    let (t0, t1) = curve.span();
    let (span_first, span_last) = fps.frames_between(lo.min(t0), hi.max(t1));
    let (first, last) = fps.frames_between(t0, t1);
    let rest = opts.velocity.then_some(DVec3::ZERO);
    let (q0, q1) = (curve.rotation(t0), curve.rotation(t1));
    for k in span_first..first {
        sink.frame(k, fps.time_of(k), q0, rest)?;
    }
    match curve.scheme() {
        _ if curve.is_constant() => {
            for k in first..=last {
                sink.frame(k, fps.time_of(k), q0, rest)?;
            }
        }
        Scheme::Slerp => track_frames::<Slerp>(curve, fps, opts, sink, warn)?,
        Scheme::Nlerp => track_frames::<Nlerp>(curve, fps, opts, sink, warn)?,
        Scheme::Hermite => track_frames::<Hermite>(curve, fps, opts, sink, warn)?,
        Scheme::Squad => track_frames::<Squad>(curve, fps, opts, sink, warn)?,
        Scheme::Bezier => track_frames::<Bezier>(curve, fps, opts, sink, warn)?,
        Scheme::MinAccel => grid_frames(curve, fps, opts.velocity, sink, warn)?,
    }
    for k in last.max(first - 1) + 1..=span_last {
        sink.frame(k, fps.time_of(k), q1, rest)?;
    }
    sink.end_track()
}

/// `minaccel`: every frame by slerp of its neighbouring grid points (a frame on a grid point is
/// that point, so keys are exact).
fn grid_frames(
    curve: &Curve,
    fps: Fps,
    velocity: bool,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&Message),
) -> io::Result<()> {
    if let Some(r) = curve.solver_report()
        && !r.converged
    {
        let name = curve.name().map_or(String::new(), |n| {
            format!("track \"{}\": ", crate::error::shorten(n))
        });
        warn(&Message::from(format!(
            "{name}minaccel did not converge in {} iterations (projected gradient {:.1e}, {:.1e} \
             of its start); the frames are the best curve found",
            r.iterations,
            r.gradient,
            r.gradient / r.gradient_start
        )));
    }
    let (times, pts) = (curve.breaks(), curve.grid_points());
    let last = fps.frames_between(times[0], times[times.len() - 1]).1;
    for p in fps.pieces(times) {
        let j = p.piece;
        for k in p.from..p.to {
            let t = fps.time_of(k);
            // A frame that snaps is the grid point, at the grid point's own time.
            let snapped = if k == p.from && p.snap_start {
                Some(j)
            } else if k == p.to - 1 && p.snap_end {
                Some(j + 1)
            } else {
                None
            };
            let q = match snapped {
                Some(g) => pts[g],
                None => {
                    let u = ((t - times[j]) / (times[j + 1] - times[j])).clamp(0.0, 1.0);
                    geodesic(pts[j], pts[j + 1], u)
                }
            };
            let omega = velocity.then(|| {
                let side = if k == last { Side::Left } else { Side::Right };
                curve.omega(snapped.map_or(t, |g| times[g]), side)
            });
            sink.frame(k, t, q, omega)?;
        }
    }
    Ok(())
}

/// One generated frame: number, time, rotation, angular velocity.
type Frame = (i64, f64, DQuat, Option<DVec3>);

/// Generates the frames of one segment into `out` (through `queue`); warnings about it go to
/// `out.warn`.
fn segment_frames<S: Segment>(
    fps: Fps,
    velocity: bool,
    p: PieceFrames,
    queue: &mut Queue<S>,
    out: &mut Out,
) -> io::Result<()> {
    let curve = out.curve;
    let keys = curve.knots();
    let times = &keys.times;
    let n = times.len();
    let s = p.piece;
    let (t0, t1) = (times[s], times[s + 1]);
    let period = fps.den() as f64 / fps.num() as f64;
    let stop = if p.snap_end { p.to - 1 } else { p.to };
    let first = p.from + i64::from(p.snap_start);
    if !velocity && stop <= first {
        // Only keys, exact (120 → 30 fps: every frame is a key): the segment's curve is not
        // needed, nor its checks, which are about frames inside it.
        if p.snap_start {
            queue.ready((p.from, fps.time_of(p.from), keys.quats[s], None), out)?;
        }
        if p.snap_end {
            queue.ready(
                (p.to - 1, fps.time_of(p.to - 1), keys.quats[n - 1], None),
                out,
            )?;
        }
        return Ok(());
    }
    let delta = t1 - t0;
    let (u0, du) = ((fps.time_of(first) - t0) / delta, period / delta);
    // A short segment of a scheme that evaluates directly: its frames wait for a block of
    // four, where the segments are built and checked (`Queue::flush`); the segment is built
    // here only for its velocities, so the rotations are the same either way. Any other segment
    // is built and checked here, after the direct frames before it (its warnings after theirs).
    let direct = stop - first < 4 && S::direct(keys);
    if !direct && !queue.direct.is_empty() {
        queue.flush(out)?;
    }
    let seg = (velocity || !direct).then(|| S::new(keys, s, curve.blend()));
    if let (false, Some(seg)) = (direct, &seg) {
        check_segment(curve, seg, s, out.warn);
    }
    let h = if velocity { step_in(keys, s) } else { 0.0 };
    let omega = |u: f64| {
        seg.as_ref()
            .filter(|_| velocity)
            .map(|seg| segment_omega(seg, u, delta, h))
    };
    if p.snap_start {
        queue.ready(
            (p.from, fps.time_of(p.from), keys.quats[s], omega(0.0)),
            out,
        )?;
    }
    match (direct, &seg) {
        (true, _) => {
            for (j, k) in (first..stop).enumerate() {
                let (u, t) = (u0 + (0.0 + j as f64) * du, fps.time_of(k));
                let f = (k, t, DQuat::IDENTITY, omega((t - t0) / delta));
                queue.direct(f, s, u, out)?;
            }
        }
        (false, Some(seg)) if stop > first => {
            let count = (stop - first) as usize;
            match (count < 4).then(|| seg.gather(u0, du, count)).flatten() {
                Some(lanes) => {
                    for (j, &lane) in lanes[..count].iter().enumerate() {
                        let kj = first + j as i64;
                        let w = omega((fps.time_of(kj) - t0) / delta);
                        queue.pending((kj, fps.time_of(kj), DQuat::IDENTITY, w), lane, out)?;
                    }
                }
                None => {
                    queue.flush(out)?;
                    for (j, q) in seg.frames(u0, du).take(count).enumerate() {
                        let kj = first + j as i64;
                        let w = omega((fps.time_of(kj) - t0) / delta);
                        (out.emit)((kj, fps.time_of(kj), q, w))?;
                    }
                }
            }
        }
        _ => {}
    }
    if p.snap_end {
        queue.ready(
            (stop, fps.time_of(stop), keys.quats[n - 1], omega(1.0)),
            out,
        )?;
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
    curve: &Curve,
    fps: Fps,
    opts: BakeOptions,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&Message),
) -> io::Result<()> {
    let velocity = opts.velocity;
    let plans: Vec<PieceFrames> = fps.pieces(&curve.knots().times).collect();
    let total: i64 = plans.iter().map(|p| p.to - p.from).sum();
    let mut to_sink = |(k, t, q, w): Frame| sink.frame(k, t, q, w);
    let parallel = opts.parallel
        && total >= PARALLEL_FRAMES
        && plans.len() >= 2
        && std::thread::available_parallelism().is_ok_and(|n| n.get() >= 2);
    if !parallel {
        let mut queue = Queue::<S>::new();
        let mut out = Out {
            curve,
            warn,
            emit: &mut to_sink,
        };
        for &p in &plans {
            segment_frames::<S>(fps, velocity, p, &mut queue, &mut out)?;
        }
        return queue.flush(&mut out);
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
        let (tx, rx) = std::sync::mpsc::sync_channel::<(Vec<Frame>, Vec<Message>)>(1);
        let (plans, chunks) = (&plans, &chunks);
        scope.spawn(move || {
            for c in chunks.iter().skip(1).step_by(2) {
                let mut frames = Vec::with_capacity(CHUNK_FRAMES as usize + 4096);
                let mut notes = Vec::new();
                let mut queue = Queue::<S>::new();
                let mut push = |f| {
                    frames.push(f);
                    Ok(())
                };
                let mut note = |m: &Message| notes.push(m.clone());
                let mut out = Out {
                    curve,
                    warn: &mut note,
                    emit: &mut push,
                };
                for &p in &plans[c.clone()] {
                    let _ = segment_frames::<S>(fps, velocity, p, &mut queue, &mut out);
                }
                let _ = queue.flush(&mut out);
                if tx.send((frames, notes)).is_err() {
                    return;
                }
            }
        });
        for (i, c) in chunks.iter().enumerate() {
            if i % 2 == 0 {
                let mut queue = Queue::<S>::new();
                let mut out = Out {
                    curve,
                    warn: &mut *warn,
                    emit: &mut to_sink,
                };
                for &p in &plans[c.clone()] {
                    segment_frames::<S>(fps, velocity, p, &mut queue, &mut out)?;
                }
                queue.flush(&mut out)?;
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

/// Keys per piece of a sampled track ([`bake_sampled`]).
const SAMPLED_CHUNK: i64 = 4096;

/// A track given as a function of time (a glTF `STEP` or `CUBICSPLINE` sampler), written at
/// every frame of `frames` (inclusive, `first <= last`) as the slerp curve through its samples
/// at those frames, taken as keys: every frame is its sample (after `--path`, so signs stay
/// continuous), and the frames before and after hold the ends, at rest (see [`bake_over`]).
///
/// The samples are never all in memory: the track is built in pieces of 4096 (`SAMPLED_CHUNK`)
/// keys, each with one more key on either side, so that every frame, its angular velocity and
/// its position are those of the whole track's curve (the tangents of a key depend on its two
/// neighbours only). Memory is bounded by the piece; time is linear in the frames.
pub struct Sampled<'a> {
    /// The track's name.
    pub name: Option<&'a str>,
    /// The frames, `(first, last)`, `first <= last`.
    pub frames: (i64, i64),
    /// The rotation (a unit quaternion) and position (when the track has positions) at a time.
    pub sample: &'a dyn Fn(f64) -> (DQuat, Option<DVec3>),
}

impl Sampled<'_> {
    /// The curve through the samples at frames `lo..=hi` (`lo <= hi`), each rotation times
    /// `sign` (±1, exact), under `opts` (`Ends::Cyclic` becomes chord ends: a piece is no loop).
    pub fn piece(
        &self,
        fps: Fps,
        opts: &crate::CurveOptions,
        (lo, hi): (i64, i64),
        sign: f64,
    ) -> crate::error::InputResult<Curve> {
        use crate::error::input_err;
        let mut times = Vec::with_capacity((hi - lo + 1) as usize);
        let mut quats = Vec::with_capacity(times.capacity());
        let mut positions = Vec::new();
        for k in lo..=hi {
            let t = fps.time_of(k);
            let (q, p) = (self.sample)(t);
            times.push(t);
            quats.push(q * sign);
            if let Some(p) = p {
                positions.push(p);
            }
        }
        let track = if lo == hi {
            crate::Track::constant(times[0], quats[0])
        } else {
            crate::Track::new(times, quats)
        };
        let located = |e: crate::TrackError| {
            let k = e.index().map_or(lo, |i| lo + i as i64);
            input_err!("{e}").at(format!(
                "frame {k} ({} s)",
                crate::error::num(fps.time_of(k))
            ))
        };
        let mut track = track.map_err(located)?;
        if !positions.is_empty() {
            track = track.with_translations(positions).map_err(located)?;
        }
        if let Some(n) = self.name {
            track = track.with_name(n);
        }
        let mut opts = *opts;
        if opts.ends.ends == crate::Ends::Cyclic {
            opts.ends.ends = crate::Ends::Chord;
        }
        Curve::new(&track, &opts)
    }

    /// What building the whole track's curve under `opts` would refuse, found before any
    /// output: the first piece's errors, and for cyclic ends the loop's (the last frame's
    /// rotation is the first's).
    pub fn check(&self, fps: Fps, opts: &crate::CurveOptions) -> crate::error::InputResult<()> {
        let (first, last) = self.frames;
        let b = (first + SAMPLED_CHUNK + 1).min(last).max(first);
        self.piece(fps, opts, (first, b), 1.0)?;
        if opts.ends.ends == crate::Ends::Cyclic && first < last {
            let (t0, t1) = (fps.time_of(first), fps.time_of(last));
            let ends =
                crate::Track::new(vec![t0, t1], vec![(self.sample)(t0).0, (self.sample)(t1).0])
                    .map_err(|e| crate::error::input_err!("{e}"))?;
            let ends = match self.name {
                Some(n) => ends.with_name(n),
                None => ends,
            };
            Curve::new(&ends, opts)?;
        }
        Ok(())
    }
}

/// Streams every frame of a [`Sampled`] track on the grid of `fps` over `[lo, hi]` (widened to
/// the track's frames) into `sink`, as [`bake_over`] streams a curve through the same samples
/// (`opts`, whose scheme should be slerp). Errors: the sink's, and a piece whose curve cannot
/// be built (an internal error: the caller checks the track first, [`Sampled::check`]).
pub fn bake_sampled(
    track: &Sampled<'_>,
    opts: &crate::CurveOptions,
    fps: Fps,
    (lo, hi): (f64, f64),
    bake_opts: BakeOptions,
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&Message),
) -> io::Result<()> {
    let (first, last) = track.frames;
    let internal = |e: crate::InputError| {
        io::Error::other(format!("internal error: a sampled track: {}", e.message()))
    };
    if first >= last {
        let curve = track
            .piece(fps, opts, (first, first), 1.0)
            .map_err(internal)?;
        return bake_over(&curve, fps, (lo, hi), bake_opts, sink, warn);
    }
    let (t0, t1) = (fps.time_of(first), fps.time_of(last));
    let (span_first, span_last) = fps.frames_between(lo.min(t0), hi.max(t1));
    let rest = bake_opts.velocity.then_some(DVec3::ZERO);
    // The ends held, with the end's position (as [`WithPositions`] gives it).
    let hold = |sink: &mut dyn FrameSink, curve: &Curve, ks: std::ops::Range<i64>, q: DQuat| {
        for k in ks {
            let t = fps.time_of(k);
            match curve.position(t) {
                Some(p) => sink.frame_at(k, t, q, rest, p)?,
                None => sink.frame(k, t, q, rest)?,
            }
        }
        Ok::<(), io::Error>(())
    };
    let one_thread = BakeOptions {
        parallel: false,
        ..bake_opts
    };
    sink.begin_track(track.name)?;
    let mut sign = 1.0;
    let mut a = first;
    loop {
        let b = (a + SAMPLED_CHUNK).min(last);
        let keys = ((a - 1).max(first), (b + 1).min(last));
        let curve = track.piece(fps, opts, keys, sign).map_err(internal)?;
        if a == first {
            hold(sink, &curve, span_first..first, curve.rotation(t0))?;
        }
        // The frames this piece writes: a..b, and b too when it is the last.
        let until = if b == last { b + 1 } else { b };
        let mut window = Window {
            sink: &mut *sink,
            from: a,
            until,
        };
        if curve.has_positions() {
            let mut with = WithPositions {
                sink: &mut window,
                curve: &curve,
            };
            track_frames::<Slerp>(&curve, fps, one_thread, &mut with, warn)?;
        } else {
            track_frames::<Slerp>(&curve, fps, one_thread, &mut window, warn)?;
        }
        if b == last {
            hold(sink, &curve, last + 1..span_last + 1, curve.rotation(t1))?;
            break;
        }
        // The next piece starts one key before its first frame, on this piece's key b − 1: its
        // sign there is the one the path rule left in this piece.
        let knot = curve.knots().quats[(b - 1 - keys.0) as usize];
        if knot != (track.sample)(fps.time_of(b - 1)).0 * sign {
            sign = -sign;
        }
        a = b;
    }
    sink.end_track()
}

/// Passes on the frames `from..until` only (the caller writes the holds outside them).
struct Window<'a> {
    sink: &'a mut dyn FrameSink,
    from: i64,
    until: i64,
}

impl FrameSink for Window<'_> {
    fn frame(&mut self, k: i64, time: f64, q: DQuat, omega: Option<DVec3>) -> io::Result<()> {
        if (self.from..self.until).contains(&k) {
            return self.sink.frame(k, time, q, omega);
        }
        Ok(())
    }
    fn frame_at(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: DVec3,
    ) -> io::Result<()> {
        if (self.from..self.until).contains(&k) {
            return self.sink.frame_at(k, time, q, omega, position);
        }
        Ok(())
    }
}
