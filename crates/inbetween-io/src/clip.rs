//! A motion clip on a skeleton: the joints (names, parents, offsets, channels, End Sites) and
//! one row of channel values per frame on an exact frame rate. The model BVH is read into and
//! written from ([`crate::bvh`]); a [`crate::document::Document`] read from a clip keeps it as
//! its skeleton, which is what BVH output is written against.

use inbetween::clock::Fps;
use inbetween::rotation::EulerSeq;
use std::collections::HashMap;
use std::ops::Range;

/// One channel of a joint: a position or a rotation about one axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Channel {
    /// `Xposition`.
    Xposition,
    /// `Yposition`.
    Yposition,
    /// `Zposition`.
    Zposition,
    /// `Xrotation`, degrees.
    Xrotation,
    /// `Yrotation`, degrees.
    Yrotation,
    /// `Zrotation`, degrees.
    Zrotation,
}

impl Channel {
    /// All six, in the order messages list them.
    pub const ALL: [Channel; 6] = [
        Channel::Xposition,
        Channel::Yposition,
        Channel::Zposition,
        Channel::Xrotation,
        Channel::Yrotation,
        Channel::Zrotation,
    ];

    /// The channel named exactly as BVH files write it (`Zrotation`; case-sensitive).
    pub fn parse(s: &str) -> Option<Channel> {
        Channel::ALL.into_iter().find(|c| c.as_str() == s)
    }

    /// The name as written in a file, e.g. `Zrotation`.
    pub fn as_str(self) -> &'static str {
        match self {
            Channel::Xposition => "Xposition",
            Channel::Yposition => "Yposition",
            Channel::Zposition => "Zposition",
            Channel::Xrotation => "Xrotation",
            Channel::Yrotation => "Yrotation",
            Channel::Zrotation => "Zrotation",
        }
    }

    /// Whether this is a rotation channel.
    pub fn is_rotation(self) -> bool {
        matches!(
            self,
            Channel::Xrotation | Channel::Yrotation | Channel::Zrotation
        )
    }

    /// The axis: 0 for x, 1 for y, 2 for z.
    pub fn axis(self) -> usize {
        match self {
            Channel::Xposition | Channel::Xrotation => 0,
            Channel::Yposition | Channel::Yrotation => 1,
            Channel::Zposition | Channel::Zrotation => 2,
        }
    }
}

impl std::fmt::Display for Channel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A joint of the hierarchy as read: a `ROOT` or `JOINT` block (an `End Site` is not a joint;
/// its offset is the joint's [`Joint::end_site`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    pub(crate) name: String,
    pub(crate) parent: Option<usize>,
    pub(crate) offset: [f64; 3],
    pub(crate) channels: Vec<Channel>,
    pub(crate) first_column: usize,
    pub(crate) end_site: Option<[f64; 3]>,
    pub(crate) line: usize,
    /// Set by the parser once every joint is known ([`Joint::track_name`]).
    pub(crate) track_name: String,
}

impl Joint {
    /// The name as written after `ROOT` or `JOINT` (the rest of that line, trimmed; it may
    /// contain spaces, as 3ds Max's `Bip01 L Thigh`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Index of the parent in [`Clip::joints`]; `None` for a `ROOT`. A parent always comes
    /// before its children.
    pub fn parent(&self) -> Option<usize> {
        self.parent
    }

    /// `OFFSET x y z`.
    pub fn offset(&self) -> [f64; 3] {
        self.offset
    }

    /// The channels in their listed order (possibly none).
    pub fn channels(&self) -> &[Channel] {
        &self.channels
    }

    /// The columns of a motion row that hold this joint's channels, in their listed order.
    pub fn columns(&self) -> Range<usize> {
        self.first_column..self.first_column + self.channels.len()
    }

    /// The `OFFSET` of the joint's `End Site`, if it has one.
    pub fn end_site(&self) -> Option<[f64; 3]> {
        self.end_site
    }

    /// The line of the file where the joint's `ROOT` or `JOINT` keyword is (1-based).
    pub fn line(&self) -> usize {
        self.line
    }

    /// The joint's rotation when it has rotation channels (one, two or three, in any order,
    /// possibly interleaved with position channels): an intrinsic Euler sequence and, for each
    /// of its three angles, the row column holding it (degrees), or `None` for an axis the
    /// joint does not list, whose angle is 0. The sequence is the listed axes in their listed
    /// order (`Zrotation Xrotation Yrotation` is `ZXY`: `R = Rz·Rx·Ry`), completed by the axes
    /// the joint does not list in x, y, z order: `Xrotation` alone (a hinge) is `XYZ` with
    /// columns `[Some(c), None, None]`, `Zrotation Xrotation` is `ZXY` with `[Some(c₁),
    /// Some(c₂), None]`. The missing angles being 0, the rotation is the product of the listed
    /// axes' rotations whatever the completion; this one keeps the listed angles first, so the
    /// columns written back are exactly the joint's own. `None` without rotation channels.
    pub fn rotation(&self) -> Option<(EulerSeq, [Option<usize>; 3])> {
        let mut letters = [0u8; 3];
        let mut cols = [None; 3];
        let mut n = 0;
        let mut listed = [false; 3];
        for (i, c) in self.channels.iter().enumerate() {
            // A joint never lists a channel twice (the parser refuses it): at most 3.
            if c.is_rotation() && n < 3 {
                cols[n] = Some(self.first_column + i);
                letters[n] = b"XYZ"[c.axis()];
                listed[c.axis()] = true;
                n += 1;
            }
        }
        if n == 0 {
            return None;
        }
        for (axis, _) in listed.iter().enumerate().filter(|(_, l)| !**l) {
            letters[n] = b"XYZ"[axis];
            n += 1;
        }
        // Three distinct axes: a valid Tait–Bryan sequence.
        let seq = std::str::from_utf8(&letters)
            .ok()
            .and_then(|s| EulerSeq::parse(s).ok())?;
        Some((seq, cols))
    }

    /// The row columns of `Xposition`, `Yposition`, `Zposition` (in that order, whatever the
    /// listed order) when the joint has position channels, `None` for an axis it does not list
    /// (whose position is 0); `None` without position channels.
    pub fn position(&self) -> Option<[Option<usize>; 3]> {
        let col = |want: Channel| {
            self.channels
                .iter()
                .position(|&c| c == want)
                .map(|i| self.first_column + i)
        };
        let cols = [
            col(Channel::Xposition),
            col(Channel::Yposition),
            col(Channel::Zposition),
        ];
        cols.iter().any(Option::is_some).then_some(cols)
    }

    /// The name of the joint's track: its [`name`](Joint::name), made unique among the
    /// hierarchy's joints by `unique_names` with the joint's
    /// index in [`Clip::joints`] (docs/spec.md §3, *BVH*): the first joint of a name keeps it,
    /// a later one is `name#<index>` (then `name#<index>#2`, … when that is taken).
    pub fn track_name(&self) -> &str {
        &self.track_name
    }

    /// Whether the joint is a track: it has rotation or position channels.
    pub fn is_track(&self) -> bool {
        !self.channels.is_empty()
    }
}

/// A BVH file as read: the hierarchy (as joints and as its exact text), the `MOTION` header as
/// written, the recovered rate and the motion values.
///
/// Invariants (kept by [`crate::bvh::parse`], the only constructor): at least one channel; the joints'
/// columns tile `0..channel_count()` in file order; `values().len() == frame_count() ·
/// channel_count()`; every value finite; the frame time positive and finite; the joints'
/// track names distinct.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    pub(crate) joints: Vec<Joint>,
    pub(crate) hierarchy: String,
    pub(crate) declared_frames: u64,
    pub(crate) frame_time_text: String,
    pub(crate) frame_time: f64,
    pub(crate) fps: Fps,
    pub(crate) channels: usize,
    pub(crate) values: Vec<f64>,
    /// Each joint's index by its [`Joint::track_name`].
    pub(crate) by_track_name: HashMap<String, usize>,
}

impl Clip {
    /// The joints in file order (depth first, as written).
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// The joint whose [track name](Joint::track_name) is `name`: the first joint of a given
    /// name (which keeps it), or a later one by its `name#<index>`. One hash lookup.
    pub fn joint(&self, name: &str) -> Option<&Joint> {
        self.joint_index(name).map(|j| &self.joints[j])
    }

    /// The index in [`Clip::joints`] of the joint [`Clip::joint`] finds.
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        self.by_track_name.get(name).copied()
    }

    /// The indices of the joints that are tracks ([`Joint::is_track`]: those with channels),
    /// in file order: the order of the tracks of the clip's document.
    pub fn track_joints(&self) -> Vec<usize> {
        (0..self.joints.len())
            .filter(|&j| self.joints[j].is_track())
            .collect()
    }

    /// The exact text of the `HIERARCHY` section: from the `HIERARCHY` keyword up to the start
    /// of the `MOTION` keyword (a leading byte-order mark and blank space before `HIERARCHY`
    /// are not part of it). Line ends and indentation are as in the file, so a writer given
    /// this text reproduces the hierarchy byte for byte.
    pub fn hierarchy(&self) -> &str {
        &self.hierarchy
    }

    /// The count after `Frames:` as written, which may disagree with
    /// [`Clip::frame_count`] (the rows win, with a warning).
    pub fn declared_frames(&self) -> u64 {
        self.declared_frames
    }

    /// The value after `Frame Time:` exactly as written, e.g. `.0083333`.
    pub fn frame_time_text(&self) -> &str {
        &self.frame_time_text
    }

    /// The value after `Frame Time:` as a float (seconds), e.g. 0.0083333.
    pub fn frame_time(&self) -> f64 {
        self.frame_time
    }

    /// The exact rate recovered from the frame time (`rate_from_frame_time`): 120 for
    /// `.0083333`.
    pub fn fps(&self) -> Fps {
        self.fps
    }

    /// The number of channels of the hierarchy: the values in one motion row.
    pub fn channel_count(&self) -> usize {
        self.channels
    }

    /// The number of motion rows (frames) in the file.
    pub fn frame_count(&self) -> usize {
        self.values.len() / self.channels
    }

    /// All motion values, row-major: frame `i`, column `c` is `values()[i·channel_count() + c]`.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The values of frame `i`. Panics if `i ≥ frame_count()`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.values[i * self.channels..(i + 1) * self.channels]
    }

    /// The rows in order.
    pub fn rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.values.chunks_exact(self.channels)
    }

    /// Time of frame `i` in seconds: `i / fps()`, from the index (never accumulated).
    pub fn time_of(&self, i: usize) -> f64 {
        self.fps.time_of(i as i64)
    }
}

impl Clip {
    /// The hierarchy as an [`inbetween::skeleton::Skeleton`], for world-space measures: every
    /// joint in file order at its `OFFSET`, unrotated at rest, its `End Site` as its end point;
    /// the joints with channels are the tracks, in file order (the tracks of the clip's
    /// document). A joint's position channels replace its `OFFSET` (the skeleton's rule).
    pub fn skeleton(&self) -> inbetween::skeleton::Skeleton {
        use inbetween::skeleton::{Joint as SkelJoint, Skeleton};
        let mut track = 0;
        let joints = self
            .joints
            .iter()
            .map(|j| {
                let mut s = SkelJoint::new(&j.track_name, j.parent, j.offset.into());
                if j.is_track() {
                    s = s.with_track(track);
                    track += 1;
                }
                s.with_ends(j.end_site.iter().map(|&e| e.into()).collect())
            })
            .collect();
        // Parents come first and offsets are finite (the parser's invariants); each track once.
        Skeleton::new(joints).expect("a parsed BVH hierarchy is a skeleton")
    }
}
