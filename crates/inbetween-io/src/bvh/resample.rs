//! A whole BVH clip resampled one joint at a time: `interp clip.bvh --fps 60 -o out.bvh`
//! without holding the keys of every joint at once.
//!
//! [`resample`] takes a [`Clip`] (read with [`parse_reader`](super::parse_reader), which never
//! holds the file's text) and, for each joint that is a track ([`track_joints`]), builds its
//! [`Track`] exactly as [`Document::tracks_shaped`](crate::document::Document::tracks_shaped) builds it from [`document`](super::document)
//! ([`track`]), its [`Curve`], bakes the curve over the clip's span at the output rate into that
//! joint's channels (rotations as continuous Euler angles in the joint's own order, from the
//! first row's own angles; positions), and drops the track and the curve. Joints are shared
//! among threads; each joint's frames and warnings are kept apart and handed back in joint
//! order, so the result does not depend on the threads. [`Resampled::write`] writes the rows
//! (the same bytes as [`frames::BvhFrames`](super::frames::BvhFrames) writes for the same
//! tracks). [`bake_tracks`] is the sequential counterpart into any [`FrameSink`] (CSV, JSON).
//!
//! ```
//! use inbetween_io::bvh::{self, resample};
//! use inbetween::{CurveOptions, Fps, Scheme, Tcb};
//!
//! let text = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition \
//!             Zposition Zrotation Xrotation Yrotation\n  End Site\n  {\n    OFFSET 0 1 0\n  \
//!             }\n}\nMOTION\nFrames: 3\nFrame Time: 0.0333333\n0 1 2 10 20 30\n0 1 2 11 21 31\n\
//!             0 1 2 12 22 32\n";
//! let (clip, _) = bvh::parse_reader(text.as_bytes(), "clip.bvh", None)?;
//! let opts = resample::Options {
//!     fps: clip.fps(),
//!     curve: CurveOptions { scheme: Scheme::Hermite, ..CurveOptions::default() },
//!     tcb: Tcb::ZERO,
//!     threads: 2,
//!     bake: Default::default(),
//! };
//! let (frames, warnings) = resample::resample(&clip, "clip.bvh", &opts)?;
//! assert!(warnings.is_empty());
//! let out = String::from_utf8(frames.write(Vec::new(), &clip)?).unwrap();
//! assert!(out.ends_with("Frames: 3\nFrame Time: 0.0333333333\n0 1 2 10 20 30\n\
//!                        0 1 2 11 21 31\n0 1 2 12 22 32\n"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::document::joint_tracks;
use super::write::BvhWriter;
use super::{Clip, Joint};
use glam::{DQuat, DVec3};
use inbetween::Tcb;
use inbetween::bake::{BakeOptions, FrameSink, bake_over};
use inbetween::clock::Fps;
use inbetween::curve::{Curve, CurveOptions};
use inbetween::error::{Error, InputResult, Message};
use inbetween::rotation::EulerSeq;
use inbetween::rotation::unwrap::EulerUnwrap;
use inbetween::track::Track;
use std::io::{self, Write};
use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// What [`resample`] does.
#[derive(Debug, Clone)]
pub struct Options {
    /// The output rate.
    pub fps: Fps,
    /// The curve of every joint (its `grid_rate` is minaccel's, normally `fps`).
    pub curve: CurveOptions,
    /// Tension, continuity and bias for keys that give only some of them (BVH keys give none).
    pub tcb: Tcb,
    /// Threads sharing the joints; 0 for the machine's available parallelism.
    pub threads: usize,
    /// How [`bake_tracks`] bakes each joint: angular velocities with the frames, two generating
    /// threads. [`resample`] ignores it (BVH rows have no velocities; it shares out joints).
    pub bake: BakeOptions,
}

/// The indices (in [`Clip::joints`]) of the joints that are tracks: those with rotation or
/// position channels, in file order ([`Clip::track_joints`]).
pub fn track_joints(clip: &Clip) -> Vec<usize> {
    clip.track_joints()
}

/// The span of every track of the clip, in seconds: from row 0 to the last row, at the clip's
/// rate (as the document's frame numbers are timed). `None` without rows.
pub fn span(clip: &Clip) -> Option<(f64, f64)> {
    let last = clip.frame_count().checked_sub(1)?;
    let fps = clip.fps();
    Some((fps.frame_to_time(0.0), fps.frame_to_time(last as f64)))
}

/// The track of joint `joint` of `clip`, exactly as [`Document::tracks_shaped`](crate::document::Document::tracks_shaped) makes it from
/// the clip's [`document`](super::document::document) (`source` names the file in errors);
/// `Ok(None)` for a joint that is not a track.
pub fn track(clip: &Clip, joint: &Joint, source: &str, tcb: Tcb) -> InputResult<Option<Track>> {
    Ok(joint_tracks(clip, joint, source, tcb)?.map(|(_, track)| track))
}

/// The frames of every joint, at the output rate, as BVH channel values: [`resample`]'s result.
#[derive(Debug, Clone)]
pub struct Resampled {
    fps: Fps,
    frames: usize,
    /// Per track joint: its row columns and its values, frame-major.
    joints: Vec<(Range<usize>, Vec<f64>)>,
}

impl Resampled {
    /// The output rate.
    pub fn fps(&self) -> Fps {
        self.fps
    }

    /// The number of frames (rows).
    pub fn frame_count(&self) -> usize {
        self.frames
    }

    /// Writes the BVH file: `clip`'s hierarchy (the clip these frames were made from), `Frames`,
    /// the output rate's `Frame Time`, and the rows, the channels of joints that are not tracks
    /// 0. Returns the destination, flushed.
    pub fn write<W: Write>(&self, out: W, clip: &Clip) -> io::Result<W> {
        let channels = clip.channel_count();
        let mut w = BvhWriter::new(
            out,
            clip.hierarchy(),
            self.fps,
            channels,
            self.frames as u64,
        )?;
        let mut row = vec![0.0; channels];
        for f in 0..self.frames {
            for (cols, values) in &self.joints {
                let n = cols.len();
                row[cols.clone()].copy_from_slice(&values[f * n..(f + 1) * n]);
            }
            w.row(&row)?;
        }
        w.finish()
    }
}

/// One joint's baked frames as its channel values (see [`super::frames`]).
struct JointFrames {
    width: usize,
    rotation: Option<(EulerSeq, [Option<usize>; 3])>,
    position: Option<[Option<usize>; 3]>,
    unwrap: Option<EulerUnwrap>,
    values: Vec<f64>,
}

impl JointFrames {
    fn new(joint: &Joint, frames: usize) -> JointFrames {
        let first = joint.columns().start;
        let rotation = joint
            .rotation()
            .map(|(seq, cols)| (seq, cols.map(|c| c.map(|c| c - first))));
        let width = joint.channels().len();
        JointFrames {
            width,
            rotation,
            position: joint
                .position()
                .map(|cols| cols.map(|c| c.map(|c| c - first))),
            unwrap: rotation.map(|(seq, _)| EulerUnwrap::new(seq)),
            values: Vec::with_capacity(frames * width),
        }
    }

    fn push(&mut self, q: DQuat, position: Option<DVec3>) {
        let at = self.values.len();
        self.values.resize(at + self.width, 0.0);
        let row = &mut self.values[at..];
        super::fill_joint_row(
            row,
            self.rotation,
            self.unwrap.as_mut(),
            self.position,
            q,
            position,
        );
    }
}

impl FrameSink for JointFrames {
    fn euler_start(&mut self, seq: EulerSeq, angles: [f64; 3]) {
        if self.rotation.is_some_and(|(s, _)| s == seq) {
            self.unwrap = Some(EulerUnwrap::with_start(seq, angles));
        }
    }

    fn frame(&mut self, _k: i64, _time: f64, q: DQuat, _omega: Option<DVec3>) -> io::Result<()> {
        self.push(q, None);
        Ok(())
    }

    fn frame_at(
        &mut self,
        _k: i64,
        _time: f64,
        q: DQuat,
        _omega: Option<DVec3>,
        position: DVec3,
    ) -> io::Result<()> {
        self.push(q, Some(position));
        Ok(())
    }
}

/// The curve of joint `j`, or `None` when it is not a track.
fn curve(clip: &Clip, j: usize, source: &str, opts: &Options) -> Result<Option<Curve>, Error> {
    let Some(track) = track(clip, &clip.joints()[j], source, opts.tcb)? else {
        return Ok(None);
    };
    Ok(Some(
        Curve::new(&track, &opts.curve).map_err(|e| e.at(source))?,
    ))
}

/// Every joint of `clip` that is a track, resampled at `opts.fps` over the clip's span (see the
/// module documentation), with the warnings of the bakes in joint order. Errors are input
/// errors of a track or a curve (a minaccel grid too large), the first joint's in file order,
/// located in `source` as the document path locates them; a clip without rows or tracks is an
/// input error too.
pub fn resample(
    clip: &Clip,
    source: &str,
    opts: &Options,
) -> Result<(Resampled, Vec<Message>), Error> {
    let joints = track_joints(clip);
    let Some(span) = span(clip).filter(|_| !joints.is_empty()) else {
        return Err(
            input_err!("{source}: expected at least one track with keys, found none").into(),
        );
    };
    let frames = usize::try_from(opts.fps.frame_count(span.0, span.1)).unwrap_or(usize::MAX);
    let threads = match opts.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    }
    .clamp(1, joints.len());
    type Done = Result<(Vec<f64>, Vec<Message>), Error>;
    let results: Vec<Mutex<Option<Done>>> = joints.iter().map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let one = |j: usize| -> Done {
        let joint = &clip.joints()[j];
        let curve = curve(clip, j, source, opts)?.expect("a track joint");
        let mut sink = JointFrames::new(joint, frames);
        let mut warnings = Vec::new();
        let bake = BakeOptions {
            velocity: false,
            parallel: false,
        };
        bake_over(
            &curve,
            opts.fps,
            span,
            bake,
            &mut sink,
            &mut |w: &Message| warnings.push(w.clone()),
        )?;
        if sink.values.len() != frames * sink.width {
            return Err(Error::Io(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "internal error: joint \"{}\" has {} values for {frames} frames",
                    joint.name(),
                    sink.values.len()
                ),
            )));
        }
        Ok((sink.values, warnings))
    };
    let work = || {
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            if i >= joints.len() || failed.load(Ordering::Relaxed) {
                break;
            }
            let done = one(joints[i]);
            if done.is_err() {
                failed.store(true, Ordering::Relaxed);
            }
            *results[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(done);
        }
    };
    if threads == 1 {
        work();
    } else {
        std::thread::scope(|s| {
            for _ in 1..threads {
                s.spawn(work);
            }
            work();
        });
    }
    let mut out = Resampled {
        fps: opts.fps,
        frames,
        joints: Vec::with_capacity(joints.len()),
    };
    let mut warnings = Vec::new();
    for (&j, done) in joints.iter().zip(results) {
        // After a failure, later joints may not have been done: the first failure is reported.
        let Some(done) = done.into_inner().unwrap_or_else(|e| e.into_inner()) else {
            continue;
        };
        let (values, w) = done?;
        out.joints.push((clip.joints()[j].columns(), values));
        warnings.extend(w);
    }
    if out.joints.len() != joints.len() {
        return Err(Error::Io(io::Error::other(
            "internal error: a joint was not resampled",
        )));
    }
    Ok((out, warnings))
}

/// The joints `joints` of `clip` (indices in [`Clip::joints`], each a track: all of
/// [`track_joints`], or the tracks `--tracks` chose, in file order), baked at `opts.fps` over
/// `span` into `sink` as `opts.bake` says (between its `begin_track` and `end_track`; `finish`
/// is the caller's), one joint's track and curve at a time. Warnings go to `warn`. Errors as
/// [`resample`]'s, or the sink's; an input error can come after earlier joints were written.
pub fn bake_tracks(
    clip: &Clip,
    joints: &[usize],
    source: &str,
    opts: &Options,
    span: (f64, f64),
    sink: &mut dyn FrameSink,
    warn: &mut dyn FnMut(&Message),
) -> Result<(), Error> {
    for &j in joints {
        let Some(curve) = curve(clip, j, source, opts)? else {
            return Err(Error::Io(io::Error::other(format!(
                "internal error: joint {j} is not a track"
            ))));
        };
        bake_over(&curve, opts.fps, span, opts.bake, sink, warn)?;
    }
    Ok(())
}
