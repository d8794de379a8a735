//! [`FbxFrames`]: baked frames written as a binary FBX scene on the input's skeleton
//! ([`super::write`]), every frame a key of each joint's curves.
//!
//! Track `k` animates the joint of the skeleton whose track is `k`. The keys are held in memory
//! and written at [`FrameSink::finish`]. A frame's time is its exact tick
//! ([`super::write::frame_tick`]). Only frames are keys: the scene's animation stack spans the
//! first frame to the last, and a player samples it at the frames of its rate from its start,
//! so a key between frames (the clip's first time where it is not a frame, as USD output
//! samples it) would shift every frame a player shows.

use super::write::{Scene, TrackKeys, frame_tick, write_fbx};
use crate::clip::Clip;
use crate::usd::write::Stage;
use glam::{DQuat, DVec3};
use inbetween::bake::FrameSink;
use inbetween::clock::Fps;
use inbetween::rotation::EulerSeq;
use inbetween::skeleton::Skeleton;
use std::io::{self, Write};
use std::sync::Arc;

/// Baked frames into an FBX file (see the module documentation).
pub struct FbxFrames<W: Write> {
    out: Option<W>,
    skeleton: Arc<Skeleton>,
    orders: Vec<EulerSeq>,
    fps: Fps,
    stage: Stage,
    tracks: Vec<TrackKeys>,
    current: Option<TrackKeys>,
    /// A BVH template's joints, in its tracks' order ([`FbxFrames::on_channels`]).
    channels: Option<(Arc<Clip>, Vec<usize>)>,
}

fn internal(msg: String) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("internal error: {msg}"),
    )
}

impl<W: Write> FbxFrames<W> {
    /// Frames of `skeleton`'s tracks at `fps`, each joint's rotation in its intrinsic sequence
    /// of `orders`, to be written to `out` on `stage`.
    pub fn new(
        out: W,
        skeleton: Arc<Skeleton>,
        orders: Vec<EulerSeq>,
        fps: Fps,
        stage: Stage,
    ) -> FbxFrames<W> {
        FbxFrames {
            out: Some(out),
            skeleton,
            orders,
            fps,
            stage,
            tracks: Vec::new(),
            current: None,
            channels: None,
        }
    }

    /// Frames of the tracks of a BVH template `clip`'s joints (`skeleton` being
    /// [`Clip::skeleton`]): each frame written as the pose the joint's channels carry
    /// ([`crate::bvh::channel_pose`]), as BVH output on the template writes it.
    pub fn on_channels(mut self, clip: Arc<Clip>) -> FbxFrames<W> {
        self.channels = Some((clip.clone(), clip.track_joints()));
        self
    }

    /// The output, once finished.
    pub fn into_inner(mut self) -> io::Result<W> {
        self.out
            .take()
            .ok_or_else(|| internal("FBX output taken twice".into()))
    }

    fn push(&mut self, k: i64, q: DQuat, p: Option<DVec3>) -> io::Result<()> {
        let fps = self.fps;
        let (q, p) = match &self.channels {
            Some((clip, joints)) => {
                let j = joints.get(self.tracks.len()).ok_or_else(|| {
                    internal(format!("track {} is not a joint's", self.tracks.len()))
                })?;
                crate::bvh::channel_pose(&clip.joints()[*j], q, p)
            }
            None => (q, p),
        };
        let keys = self
            .current
            .as_mut()
            .ok_or_else(|| internal("a frame outside a track".into()))?;
        keys.ticks.push(frame_tick(k, fps));
        keys.rotations.push(q);
        if let Some(p) = p {
            keys.positions.get_or_insert_with(Vec::new).push(p);
        }
        Ok(())
    }
}

impl<W: Write> FrameSink for FbxFrames<W> {
    fn begin_track(&mut self, _name: Option<&str>) -> io::Result<()> {
        self.current = Some(TrackKeys::default());
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
        let keys = self
            .current
            .take()
            .ok_or_else(|| internal("a track ended twice".into()))?;
        if keys
            .positions
            .as_ref()
            .is_some_and(|p| p.len() != keys.rotations.len())
        {
            return Err(internal(
                "a track with positions at some frames only".into(),
            ));
        }
        self.tracks.push(keys);
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        let out = self
            .out
            .as_mut()
            .ok_or_else(|| internal("FBX output finished twice".into()))?;
        let scene = Scene {
            skeleton: &self.skeleton,
            orders: &self.orders,
            fps: self.fps,
            tracks: &self.tracks,
            stage: self.stage,
        };
        write_fbx(&mut *out, &scene)
    }
}
