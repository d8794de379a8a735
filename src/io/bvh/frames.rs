//! [`BvhFrames`]: baked frames written as a BVH file on the input's skeleton.
//!
//! Each track is a joint (by name). A frame sets the joint's rotation channels — the rotation
//! as continuous Euler angles in the joint's own channel order, degrees, starting from the
//! first key's own triple (docs/spec.md §2, continuous Euler output) — and its position
//! channels, from the track's positions. Every track is written over the same frames (the
//! clip's span); the rows are assembled in memory and written at [`FrameSink::finish`].

use super::Clip;
use crate::bake::FrameSink;
use crate::clock::Fps;
use crate::rotation::EulerSeq;
use crate::rotation::unwrap::EulerUnwrap;
use glam::{DQuat, DVec3};
use std::io::{self, Write};
use std::sync::Arc;

/// Baked frames into a BVH file (see the module documentation).
pub struct BvhFrames<W: Write> {
    out: Option<W>,
    clip: Arc<Clip>,
    fps: Fps,
    /// Row-major values of every frame written so far.
    values: Vec<f64>,
    /// Frame number of the first row.
    first: Option<i64>,
    /// Rows the first track made (the others must make as many).
    rows: usize,
    /// The current track's joint: its rotation sequence and columns, its position columns.
    rotation: Option<(EulerSeq, [usize; 3])>,
    position: Option<[usize; 3]>,
    unwrap: Option<EulerUnwrap>,
    track_index: usize,
}

fn internal(msg: String) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("internal error: {msg}"),
    )
}

impl<W: Write> BvhFrames<W> {
    /// Frames of the tracks of `clip`'s joints, at `fps`, to be written to `out`.
    pub fn new(out: W, clip: Arc<Clip>, fps: Fps) -> BvhFrames<W> {
        BvhFrames {
            out: Some(out),
            clip,
            fps,
            values: Vec::new(),
            first: None,
            rows: 0,
            rotation: None,
            position: None,
            unwrap: None,
            track_index: 0,
        }
    }

    /// The destination, after [`FrameSink::finish`].
    pub fn into_inner(mut self) -> io::Result<W> {
        self.out
            .take()
            .ok_or_else(|| internal("BVH output taken twice".into()))
    }

    fn set(&mut self, k: i64, q: DQuat, position: Option<DVec3>) -> io::Result<()> {
        let first = *self.first.get_or_insert(k);
        let j = usize::try_from(k - first).map_err(|_| internal(format!("frame {k} early")))?;
        let width = self.clip.channel_count();
        if self.track_index == 0 {
            if j != self.rows {
                return Err(internal(format!("frame {k} out of order")));
            }
            self.values.resize((j + 1) * width, 0.0);
            self.rows = j + 1;
        } else if j >= self.rows {
            return Err(internal(format!(
                "track {} has more frames than the first ({})",
                self.track_index, self.rows
            )));
        }
        let row = &mut self.values[j * width..(j + 1) * width];
        super::fill_joint_row(
            row,
            self.rotation,
            self.unwrap.as_mut(),
            self.position,
            q,
            position,
        );
        Ok(())
    }
}

impl<W: Write> FrameSink for BvhFrames<W> {
    fn begin_track(&mut self, name: Option<&str>) -> io::Result<()> {
        let joint = name
            .and_then(|n| self.clip.joint(n))
            .ok_or_else(|| internal(format!("no joint for track {name:?}")))?;
        self.rotation = joint.rotation();
        self.position = joint.position();
        self.unwrap = self.rotation.map(|(seq, _)| EulerUnwrap::new(seq));
        Ok(())
    }

    fn euler_start(&mut self, seq: EulerSeq, angles: [f64; 3]) {
        if self.rotation.is_some_and(|(s, _)| s == seq) {
            self.unwrap = Some(EulerUnwrap::with_start(seq, angles));
        }
    }

    fn frame(&mut self, k: i64, _time: f64, q: DQuat, _omega: Option<DVec3>) -> io::Result<()> {
        self.set(k, q, None)
    }

    fn frame_at(
        &mut self,
        k: i64,
        _time: f64,
        q: DQuat,
        _omega: Option<DVec3>,
        position: DVec3,
    ) -> io::Result<()> {
        self.set(k, q, Some(position))
    }

    fn end_track(&mut self) -> io::Result<()> {
        self.track_index += 1;
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        let out = self
            .out
            .as_mut()
            .ok_or_else(|| internal("BVH output finished twice".into()))?;
        super::write(
            &mut *out,
            self.clip.hierarchy(),
            self.fps,
            self.clip.channel_count(),
            &self.values,
        )?;
        out.flush()
    }
}
