//! [`BvhFrames`]: baked frames written as a BVH file on the input's skeleton.
//!
//! The tracks are the clip's document's, in its order: track `k` is the `k`-th joint that is a
//! track ([`Clip::track_joints`]), by index, its name checked against the joint's
//! [`track_name`](super::Joint::track_name) (unique, so two joints sharing a name cannot swap
//! their data). A frame sets the joint's rotation channels — the rotation
//! as continuous Euler angles in the joint's own channel order, degrees, starting from the
//! first key's own triple (docs/spec.md §2, continuous Euler output) — and its position
//! channels, from the track's positions. Every track is written over the same frames (the
//! clip's span); the rows are assembled in memory and written at [`FrameSink::finish`].

use super::Clip;
use glam::{DQuat, DVec3};
use inbetween::bake::FrameSink;
use inbetween::clock::Fps;
use inbetween::rotation::EulerSeq;
use inbetween::rotation::unwrap::EulerUnwrap;
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
    /// The joints that are tracks, in the tracks' order.
    track_joints: Vec<usize>,
    /// The current track's joint: its rotation sequence and columns, its position columns.
    rotation: Option<(EulerSeq, [Option<usize>; 3])>,
    position: Option<[Option<usize>; 3]>,
    unwrap: Option<EulerUnwrap>,
    /// Each triple in scipy's ranges instead of continuous ([`BvhFrames::wrapped`]).
    wrapped: bool,
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
            track_joints: clip.track_joints(),
            clip,
            fps,
            values: Vec::new(),
            first: None,
            rows: 0,
            rotation: None,
            position: None,
            unwrap: None,
            wrapped: false,
            track_index: 0,
        }
    }

    /// Rotations as each triple in scipy's ranges (`--euler wrapped`), not continuous along
    /// the track.
    pub fn wrapped(mut self) -> BvhFrames<W> {
        self.wrapped = true;
        self
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
        let joint = self
            .track_joints
            .get(self.track_index)
            .map(|&j| &self.clip.joints()[j])
            .filter(|j| name == Some(j.track_name()))
            .ok_or_else(|| {
                internal(format!(
                    "track {} ({:?}) is not a joint of the skeleton",
                    self.track_index,
                    name.map(inbetween::error::shorten)
                ))
            })?;
        self.rotation = joint.rotation();
        self.position = joint.position();
        self.unwrap = self
            .rotation
            .filter(|_| !self.wrapped)
            .map(|(seq, _)| EulerUnwrap::new(seq));
        Ok(())
    }

    fn euler_start(&mut self, seq: EulerSeq, angles: [f64; 3]) {
        if !self.wrapped && self.rotation.is_some_and(|(s, _)| s == seq) {
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
        if self.track_index != self.track_joints.len() {
            return Err(internal(format!(
                "{} tracks for {} joints with channels",
                self.track_index,
                self.track_joints.len()
            )));
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::read::tests::{least_of_runs, many_joints};
    use crate::bvh::{document::document, parse};

    /// Every track's frames into the sink, as `bake` hands them: begin, two frames, end.
    fn feed(sink: &mut BvhFrames<Vec<u8>>, doc: &crate::document::Document) {
        for t in &doc.tracks {
            sink.begin_track(t.name.as_deref()).unwrap();
            for (k, key) in t.keys.iter().enumerate() {
                sink.frame(k as i64, k as f64, key.rot, None).unwrap();
            }
            sink.end_track().unwrap();
        }
        sink.finish().unwrap();
    }

    /// Finding each track's joint is one step: 16n joints take about 16 times as long as n, not
    /// 256 (a linear search by name: a minute for 100 000 joints). The bound, 128, is half the
    /// quadratic ratio: a fresh-clone CI run under load measured 70x (0.56 ms against 39 ms, the
    /// larger clip's rows out of cache), past the earlier bound of 64.
    #[test]
    fn finding_each_tracks_joint_is_linear() {
        let time = |n: usize| {
            let clip = Arc::new(parse(&many_joints(n, 300), "many.bvh").unwrap().0);
            let doc = document((*clip).clone(), "many.bvh", Vec::new());
            least_of_runs(|| {
                let mut sink = BvhFrames::new(Vec::new(), clip.clone(), clip.fps());
                feed(&mut sink, &doc);
                assert!(sink.into_inner().unwrap().len() > 12 * n);
            })
        };
        let (small, large) = (time(1000), time(16_000));
        assert!(
            large < 128.0 * small,
            "{small} s for 1000 joints, {large} s for 16000"
        );
    }

    /// Joints sharing a name each get their own track's frames (by index), and a track that is
    /// not the next joint's is an internal error, not data in the wrong place.
    #[test]
    fn tracks_go_to_their_own_joints() {
        let text = "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Zrotation\n}\n\
                    ROOT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Zrotation\n}\n\
                    MOTION\nFrames: 1\nFrame Time: 0.04\n10 20\n";
        let clip = Arc::new(parse(text, "a.bvh").unwrap().0);
        let doc = document((*clip).clone(), "a.bvh", Vec::new());
        let mut sink = BvhFrames::new(Vec::new(), clip.clone(), clip.fps());
        feed(&mut sink, &doc);
        let out = String::from_utf8(sink.into_inner().unwrap()).unwrap();
        assert!(out.ends_with("Frame Time: 0.04\n10 20\n"), "{out}");
        let mut sink = BvhFrames::new(Vec::new(), clip.clone(), clip.fps());
        let err = sink.begin_track(Some("a#1")).unwrap_err().to_string();
        assert!(err.starts_with("internal error: track 0"), "{err}");
        let mut sink = BvhFrames::new(Vec::new(), clip.clone(), clip.fps());
        sink.begin_track(Some("a")).unwrap();
        sink.end_track().unwrap();
        let err = sink.finish().unwrap_err().to_string();
        assert_eq!(err, "internal error: 1 tracks for 2 joints with channels");
    }
}
