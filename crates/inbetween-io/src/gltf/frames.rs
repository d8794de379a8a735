//! [`GltfFrames`]: baked frames written into the input asset as new `LINEAR` samplers.
//!
//! Each track is a rotation channel of a [`GltfClip`] (by name). Every track of an animation is
//! baked over the frames of that animation's span ([`GltfClip::frames`]), and sampled at the
//! span's first and last times where those are not frames ([`edges`], given with
//! [`GltfFrames::edge`]), so the animation's first and last poses are kept; at
//! [`FrameSink::finish`] each animation gets one time accessor and each of its channels a new
//! sampler on it ([`Asset::write`](super::Asset::write) with [`Resampled`]): the tracks' baked
//! rotations, and its other rotation, translation and scale channels sampled at the same times
//! as their own samplers play them (STEP, LINEAR or CUBICSPLINE), so the whole animation is on
//! one grid and its old samplers are removed. The asset is otherwise as read.

use super::document::{GltfClip, Mode};
use super::{ContainerFormat, Resampled, Values};
use glam::{DQuat, DVec3};
use inbetween::bake::FrameSink;
use inbetween::clock::Fps;
use inbetween::error::{InputError, InputResult, Setting};
use inbetween::message;
use std::collections::HashSet;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Baked frames into a glTF asset (see the module documentation).
pub struct GltfFrames<W: Write> {
    out: Option<W>,
    clip: Arc<GltfClip>,
    fps: Fps,
    format: ContainerFormat,
    /// The folder the output goes to (relative URIs are rewritten for it).
    out_dir: Option<PathBuf>,
    tracks: Vec<Baked>,
}

/// One track's samples as given.
struct Baked {
    animation: usize,
    channel: usize,
    /// The first frame's number, once one is given.
    first: Option<i64>,
    /// The rotations in time order: a slot for the span's first time when that is not a frame
    /// (`start`; filled by [`GltfFrames::edge`]), then the frames'.
    rotations: Vec<DQuat>,
    start: bool,
    /// The rotations at the span's first and last times, once given, where those are not
    /// frames.
    edges: [Option<DQuat>; 2],
}

/// The times of animation `a`'s span at `fps` that are not frames and are sampled besides them:
/// its first time when that is before its first frame, its last when that is after its last
/// frame (none for an animation whose span holds no frame: it is written as it was).
pub fn edges(clip: &GltfClip, a: usize, fps: Fps) -> [Option<f64>; 2] {
    let (first, last) = clip.frames(a, fps);
    if first > last {
        return [None, None];
    }
    let (lo, hi) = clip.span(a, fps);
    [
        (lo < fps.time_of(first)).then_some(lo),
        (hi > fps.time_of(last)).then_some(hi),
    ]
}

fn internal(msg: String) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("internal error: {msg}"),
    )
}

impl<W: Write> GltfFrames<W> {
    /// Frames of `clip`'s tracks at `fps`, to be written as `format` to `out`.
    pub fn new(out: W, clip: Arc<GltfClip>, fps: Fps, format: ContainerFormat) -> GltfFrames<W> {
        GltfFrames {
            out: Some(out),
            clip,
            fps,
            format,
            out_dir: None,
            tracks: Vec::new(),
        }
    }

    /// The output goes into the folder `dir`, not beside the input: relative URIs (images,
    /// external buffers) are rewritten to name the input's files from there
    /// ([`Asset::to_bytes_in`](super::Asset::to_bytes_in)).
    pub fn in_folder(mut self, dir: &Path) -> GltfFrames<W> {
        self.out_dir = Some(dir.to_path_buf());
        self
    }

    /// The rotation at `time`, one of the [`edges`] of the animation of the track whose frames
    /// were given last (after its frames: the frames are written in time order).
    pub fn edge(&mut self, time: f64, q: DQuat) -> io::Result<()> {
        let t = self
            .tracks
            .last_mut()
            .ok_or_else(|| internal("an edge sample before a track".into()))?;
        let edges = edges(&self.clip, t.animation, self.fps);
        let side = edges
            .iter()
            .position(|&e| e == Some(time))
            .ok_or_else(|| internal(format!("{time} s is not an edge of the track's span")))?;
        if side == 0 && t.start {
            t.rotations[0] = q;
        }
        t.edges[side] = Some(q);
        Ok(())
    }

    /// The destination, after [`FrameSink::finish`].
    pub fn into_inner(mut self) -> io::Result<W> {
        self.out
            .take()
            .ok_or_else(|| internal("glTF output taken twice".into()))
    }
}

/// The most bytes of new samplers a glTF bake may add (`u32::MAX`, a `.glb`'s limit).
pub(crate) const MAX_NEW_BYTES: u64 = u32::MAX as u64;

/// Checks, before anything is written, that the frames of every chosen animation at `fps`
/// have distinct float32 times. An animation whose span holds no frame (a pose: one key at
/// 1/24 s, written at 30 fps) is written as it was, its samplers untouched; the warnings say
/// which.
///
/// It also refuses, before any frame is baked, a bake whose new samplers would take more than
/// `MAX_NEW_BYTES` (4 GiB, what a `.glb` can hold; a `.gltf`'s data URI is held to it too):
/// a float32 time per frame and a float32 quaternion per frame and rotation channel.
pub fn check_grid(clip: &GltfClip, fps: Fps) -> InputResult<Vec<String>> {
    let src = clip.asset().source();
    let mut new_bytes = 0u128;
    for (a, anim) in clip.animations().iter().enumerate() {
        let (first, last) = clip.frames(a, fps);
        if first <= last {
            let edges = edges(clip, a, fps).iter().flatten().count() as u128;
            let frames = (last - first) as u128 + 1 + edges;
            let vectors = (anim.translations().len() + anim.scales().len()) as u128;
            new_bytes += frames * (4 + 16 * anim.rotations().len() as u128 + 12 * vectors);
        }
    }
    if new_bytes > MAX_NEW_BYTES as u128 {
        return Err(input_err!(
            "{src}: its animations at {fps} fps would take {new_bytes} bytes of new samplers \
             (a float32 time a frame, a float32 quaternion a frame and rotation channel), over \
             the {MAX_NEW_BYTES} bytes a .glb can hold: use a lower frame rate or fewer \
             animations"
        ));
    }
    let mut warnings = Vec::new();
    for (a, anim) in clip.animations().iter().enumerate() {
        let (first, last) = clip.frames(a, fps);
        let (lo, hi) = clip.span(a, fps);
        if first > last {
            warnings.push(format!(
                "{src}: animation {}: its span [{}, {}] s holds no frame at {fps} fps; it is \
                 written as it was",
                anim.label(),
                inbetween::error::num(lo),
                inbetween::error::num(hi)
            ));
            continue;
        }
        // The span's ends are at least two float32 units from any frame where they are not
        // one (else they would have been snapped to it), so only frames can collide.
        let mut prev: Option<f32> = None;
        for k in first..=last {
            let t = fps.time_of(k) as f32;
            if prev.is_some_and(|p| t <= p) {
                return Err(InputError::new(message![
                    format!(
                        "{src}: animation {}: frames {} and {k} at {fps} fps have the same \
                         float32 time; glTF times are float32: use a lower ",
                        anim.label(),
                        k - 1
                    ),
                    Setting::FrameRate
                ]));
            }
            prev = Some(t);
        }
    }
    Ok(warnings)
}

impl<W: Write> FrameSink for GltfFrames<W> {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()> {
        let s = name
            .and_then(|n| self.clip.source_of(n, Mode::Frames))
            .ok_or_else(|| internal(format!("no glTF channel for track {name:?}")))?;
        let start = edges(&self.clip, s.animation, self.fps)[0].is_some();
        self.tracks.push(Baked {
            animation: s.animation,
            channel: s.channel,
            first: None,
            // The first edge's slot, so that its rotation never has to be inserted in front.
            rotations: if start {
                vec![DQuat::IDENTITY]
            } else {
                Vec::new()
            },
            start,
            edges: [None, None],
        });
        Ok(())
    }

    fn frame(&mut self, k: i64, _time: f64, q: DQuat, _omega: Option<DVec3>) -> io::Result<()> {
        let t = self
            .tracks
            .last_mut()
            .ok_or_else(|| internal("a frame before a track".into()))?;
        let first = *t.first.get_or_insert(k);
        if k - first + i64::from(t.start) != t.rotations.len() as i64 {
            return Err(internal(format!("frame {k} out of order")));
        }
        t.rotations.push(q);
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        let mut resampled: Vec<Resampled> = Vec::new();
        for (a, anim) in self.clip.animations().iter().enumerate() {
            let (first, last) = self.clip.frames(a, self.fps);
            if first > last {
                continue; // no frame: the animation stays as it was (check_grid warned)
            }
            let [lo, hi] = edges(&self.clip, a, self.fps);
            let grid = (first..=last).map(|k| self.fps.time_of(k));
            let mut r = Resampled {
                animation: anim.index(),
                times: lo.into_iter().chain(grid).chain(hi).collect(),
                channels: Vec::new(),
            };
            for t in &mut self.tracks {
                if t.animation != a {
                    continue;
                }
                let c = t.channel;
                let sides = t.edges.map(|e| e.is_some());
                if t.first != Some(first)
                    || t.rotations.len() as i64 != last - first + 1 + i64::from(t.start)
                    || sides != [lo.is_some(), hi.is_some()]
                {
                    return Err(internal(format!(
                        "animation {a} channel {c}: frames from {:?}, {} rotations, edges \
                         {sides:?} for frames {first}..={last}, edges {:?}",
                        t.first,
                        t.rotations.len(),
                        [lo, hi]
                    )));
                }
                // Moved, not copied: the frames are the bulk of the memory.
                let mut qs = std::mem::take(&mut t.rotations);
                qs.extend(t.edges[1]);
                r.channels.push((c, Values::Rotations(qs)));
            }
            if r.channels.is_empty() {
                continue;
            }
            // The animation's other channels, played as their samplers define them, on the
            // same times: rotations that are no track (not chosen), translations, scales.
            let baked: HashSet<usize> = r.channels.iter().map(|(c, _)| *c).collect();
            for ch in anim
                .rotations()
                .iter()
                .filter(|ch| !baked.contains(&ch.index()))
            {
                let qs = r.times.iter().map(|&t| ch.sample(t)).collect();
                r.channels.push((ch.index(), Values::Rotations(qs)));
            }
            for ch in anim.translations().iter().chain(anim.scales()) {
                let vs = r.times.iter().map(|&t| ch.sample(t)).collect();
                r.channels.push((ch.index(), Values::Vectors(vs)));
            }
            resampled.push(r);
        }
        let bytes = self
            .clip
            .asset()
            .to_bytes_in(&resampled, self.format, self.out_dir.as_deref())
            .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e.message().to_string()))?;
        let out = self
            .out
            .as_mut()
            .ok_or_else(|| internal("glTF output finished twice".into()))?;
        out.write_all(&bytes)?;
        out.flush()
    }
}
