//! [`UsdFrames`]: baked frames written as `.usda` on the input's skeleton ([`super::write`]).
//!
//! Track `k` animates the joint of the skeleton whose track is `k` (BVH joints with channels,
//! glTF nodes with channels, FBX nodes). Every track is written over the same frames (the clip's
//! span: USD samples every joint at every time code); the samples are held in memory and
//! written at [`FrameSink::finish`]. The span's first and last times, where they are not frames
//! (a 25 fps clip starting at 0.04 s baked at 30), are sampled too ([`UsdFrames::edge`]) at
//! their fractional time codes (1.2), so the first and last poses are kept, as glTF output
//! keeps them.

use super::write::{Stage, TrackSamples, write_usda};
use glam::{DQuat, DVec3};
use inbetween::bake::FrameSink;
use inbetween::clock::Fps;
use inbetween::skeleton::Skeleton;
use std::io::{self, Write};
use std::sync::Arc;

/// Baked frames into a `.usda` file (see the module documentation).
pub struct UsdFrames<W: Write> {
    out: Option<W>,
    skeleton: Arc<Skeleton>,
    fps: Fps,
    stage: Stage,
    /// The frame numbers of the first track (every track must have the same).
    frames: Vec<i64>,
    tracks: Vec<TrackSamples>,
    current: Option<(TrackSamples, Vec<i64>)>,
    /// Per track, the times of its samples at the span's edges that are not frames: first,
    /// last (every track must have the same).
    edge_times: Vec<[Option<f64>; 2]>,
}

fn internal(msg: String) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("internal error: {msg}"),
    )
}

impl<W: Write> UsdFrames<W> {
    /// Frames of `skeleton`'s tracks at `fps`, to be written to `out` on `stage`.
    pub fn new(out: W, skeleton: Arc<Skeleton>, fps: Fps, stage: Stage) -> UsdFrames<W> {
        UsdFrames {
            out: Some(out),
            skeleton,
            fps,
            stage,
            frames: Vec::new(),
            tracks: Vec::new(),
            current: None,
            edge_times: Vec::new(),
        }
    }

    /// The last track's pose at `time` (s), an edge of the clip's span that is not a frame:
    /// before its frames (the first edge) or after them (the last), given after the track has
    /// ended. Errors (internal): an edge before any track, or given twice.
    pub fn edge(&mut self, time: f64, q: DQuat, p: Option<DVec3>) -> io::Result<()> {
        let (Some(samples), Some(times)) = (self.tracks.last_mut(), self.edge_times.last_mut())
        else {
            return Err(internal("an edge before any track".into()));
        };
        let first = match self.frames.first() {
            Some(&k) => time < self.fps.time_of(k),
            None => times[0].is_none(),
        };
        let slot = &mut times[usize::from(!first)];
        if slot.is_some() || !time.is_finite() {
            return Err(internal(format!("a second edge at {time} s")));
        }
        *slot = Some(time);
        let at = if first { 0 } else { samples.rotations.len() };
        samples.rotations.insert(at, q);
        if let (Some(ps), Some(p)) = (samples.positions.as_mut(), p) {
            ps.insert(at, p);
        }
        Ok(())
    }

    /// The output, once finished.
    pub fn into_inner(mut self) -> io::Result<W> {
        self.out
            .take()
            .ok_or_else(|| internal("USD output taken twice".into()))
    }

    fn push(&mut self, k: i64, q: DQuat, p: Option<DVec3>) -> io::Result<()> {
        let (samples, frames) = self
            .current
            .as_mut()
            .ok_or_else(|| internal("a frame outside a track".into()))?;
        samples.rotations.push(q);
        if let Some(p) = p {
            samples.positions.get_or_insert_with(Vec::new).push(p);
        }
        frames.push(k);
        Ok(())
    }
}

impl<W: Write> FrameSink for UsdFrames<W> {
    fn begin_track(&mut self, _name: Option<&str>) -> io::Result<()> {
        self.current = Some((TrackSamples::default(), Vec::new()));
        Ok(())
    }

    fn frame(&mut self, k: i64, _time: f64, q: DQuat, _omega: Option<DVec3>) -> io::Result<()> {
        self.push(k, q, None)
    }

    fn frame_at(
        &mut self,
        k: i64,
        _time: f64,
        q: DQuat,
        _omega: Option<DVec3>,
        position: DVec3,
    ) -> io::Result<()> {
        self.push(k, q, Some(position))
    }

    fn end_track(&mut self) -> io::Result<()> {
        let (samples, frames) = self
            .current
            .take()
            .ok_or_else(|| internal("a track ended twice".into()))?;
        if self.tracks.is_empty() {
            self.frames = frames;
        } else if frames != self.frames {
            return Err(internal(format!(
                "track {} has other frames than track 0",
                self.tracks.len()
            )));
        }
        if samples
            .positions
            .as_ref()
            .is_some_and(|p| p.len() != samples.rotations.len())
        {
            return Err(internal(
                "a track with positions at some frames only".into(),
            ));
        }
        self.tracks.push(samples);
        self.edge_times.push([None, None]);
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        // Time codes are frame numbers: an edge's is its time times the rate (fractional).
        let [first, last] = self.edge_times.first().copied().unwrap_or([None, None]);
        if self.edge_times.iter().any(|t| *t != [first, last]) {
            return Err(internal("tracks with other edges than track 0".into()));
        }
        let code = |t: f64| t * self.fps.as_f64();
        let codes: Vec<f64> = first
            .map(code)
            .into_iter()
            .chain(self.frames.iter().map(|&k| k as f64))
            .chain(last.map(code))
            .collect();
        let out = self
            .out
            .as_mut()
            .ok_or_else(|| internal("USD output finished twice".into()))?;
        write_usda(
            &mut *out,
            &self.skeleton,
            self.fps,
            &codes,
            &self.tracks,
            self.stage,
        )
    }
}
