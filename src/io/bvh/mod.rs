//! BVH (Biovision Hierarchy) motion capture files: a skeleton and its motion, read into a
//! [`Clip`] and written back.
//!
//! ```text
//! HIERARCHY                                    the skeleton, kept as text (hierarchy())
//! ROOT Hips                                    joints in file order; ROOT may appear again
//! {
//!   OFFSET 0 0 0                               the joint's offset from its parent
//!   CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
//!   JOINT Chest                                the columns of a motion row, in this order
//!   {
//!     OFFSET 0 5.2 0
//!     CHANNELS 3 Zrotation Yrotation Xrotation each joint its own order
//!     End Site
//!     {
//!       OFFSET 0 3.9 0
//!     }
//!   }
//! }
//! MOTION
//! Frames: 2                                    as written; the rows win when they disagree
//! Frame Time: 0.0333333                        rounded by every writer: see rate
//! 0 35 0 0 0 0 0 0 0                           one row per frame, one value per channel
//! 0 35 0 5 0 0 10 0 0
//! ```
//!
//! Conventions: rotation channels are degrees; a joint whose channels list `Zrotation
//! Xrotation Yrotation` rotates by `R = Rz·Rx·Ry`, the intrinsic sequence in the listed order,
//! which is [`EulerSeq::parse("ZXY")`](EulerSeq::parse) ([`Joint::rotation`]). Frame `i` is at
//! `i / rate` seconds ([`Clip::time_of`]), the rate being recovered from the rounded
//! `Frame Time` by [`rate::rate_from_frame_time`].
//!
//! - [`read`]: the parser, [`parse`]: text → [`Clip`] and located warnings; [`parse_reader`]:
//!   the same from a reader in pieces, never holding the text.
//! - [`resample`]: a clip resampled one joint at a time (`interp`'s lean path).
//! - [`rate`]: `Frame Time` ↔ an exact [`Fps`].
//! - [`mod@write`]: [`write()`](write::write) and the streaming [`BvhWriter`].
//!
//! ```
//! use inbetween::io::bvh;
//!
//! let text = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition \
//!             Zposition Zrotation Xrotation Yrotation\n  End Site\n  {\n    OFFSET 0 1 0\n  \
//!             }\n}\nMOTION\nFrames: 2\nFrame Time: 0.0333333\n0 1 2 10 20 30\n0 1 2 11 21 31\n";
//! let (clip, warnings) = bvh::parse(text, "clip.bvh")?;
//! assert!(warnings.is_empty());
//! assert_eq!((clip.fps().num(), clip.fps().den()), (30, 1));
//! let (seq, cols) = clip.joints()[0].rotation().unwrap();
//! assert_eq!((seq.as_str(), cols), ("ZXY", [3, 4, 5]));
//! assert_eq!(clip.row(1)[cols[0]], 11.0);
//! // Written back: the hierarchy byte for byte, the frame time with 9 significant digits.
//! let mut out = Vec::new();
//! bvh::write(&mut out, clip.hierarchy(), clip.fps(), clip.channel_count(), clip.values())?;
//! let out = String::from_utf8(out).unwrap();
//! assert!(out.starts_with(clip.hierarchy()));
//! assert!(out.contains("MOTION\nFrames: 2\nFrame Time: 0.0333333333\n0 1 2 10 20 30\n"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod document;
pub mod frames;
pub mod keys;
pub mod rate;
pub mod read;
pub mod resample;
pub mod write;

pub use read::{parse, parse_reader};
pub use write::{BvhWriter, write};

use crate::clock::Fps;
use crate::rotation::EulerSeq;
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
    name: String,
    parent: Option<usize>,
    offset: [f64; 3],
    channels: Vec<Channel>,
    first_column: usize,
    end_site: Option<[f64; 3]>,
    line: usize,
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

    /// The joint's rotation when it has exactly the three rotation channels (in any order,
    /// possibly interleaved with position channels): the intrinsic Euler sequence of their
    /// listed order (`Zrotation Xrotation Yrotation` is `ZXY`: `R = Rz·Rx·Ry`, degrees) and
    /// the three row columns holding the angles, in that order. `None` when it has no
    /// rotation channels or only some of them.
    pub fn rotation(&self) -> Option<(EulerSeq, [usize; 3])> {
        let mut letters = String::with_capacity(3);
        let mut cols = [0; 3];
        for (i, c) in self.channels.iter().enumerate() {
            if c.is_rotation() {
                if letters.len() == 3 {
                    return None;
                }
                cols[letters.len()] = self.first_column + i;
                letters.push(['X', 'Y', 'Z'][c.axis()]);
            }
        }
        if letters.len() != 3 {
            return None;
        }
        // Three distinct axes (a joint never lists a channel twice), so this is a valid
        // Tait–Bryan sequence.
        EulerSeq::parse(&letters).ok().map(|seq| (seq, cols))
    }

    /// The row columns of `Xposition`, `Yposition`, `Zposition` (in that order, whatever the
    /// listed order) when the joint has all three.
    pub fn position(&self) -> Option<[usize; 3]> {
        let col = |want: Channel| {
            self.channels
                .iter()
                .position(|&c| c == want)
                .map(|i| self.first_column + i)
        };
        Some([
            col(Channel::Xposition)?,
            col(Channel::Yposition)?,
            col(Channel::Zposition)?,
        ])
    }
}

/// A BVH file as read: the hierarchy (as joints and as its exact text), the `MOTION` header as
/// written, the recovered rate and the motion values.
///
/// Invariants (kept by [`parse`], the only constructor): at least one channel; the joints'
/// columns tile `0..channel_count()` in file order; `values().len() == frame_count() ·
/// channel_count()`; every value finite; the frame time positive and finite.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    joints: Vec<Joint>,
    hierarchy: String,
    declared_frames: u64,
    frame_time_text: String,
    frame_time: f64,
    fps: Fps,
    channels: usize,
    values: Vec<f64>,
}

impl Clip {
    /// The joints in file order (depth first, as written).
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// The joint with this name, the first one if the name is used twice.
    pub fn joint(&self, name: &str) -> Option<&Joint> {
        self.joints.iter().find(|j| j.name == name)
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

    /// The exact rate recovered from the frame time ([`rate::rate_from_frame_time`]): 120 for
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

#[cfg(test)]
mod tests {
    use super::read::tests::SMALL;
    use super::*;

    fn round_trip(clip: &Clip) -> Clip {
        let mut out = Vec::new();
        write(
            &mut out,
            clip.hierarchy(),
            clip.fps(),
            clip.channel_count(),
            clip.values(),
        )
        .unwrap();
        let (back, warnings) = parse(std::str::from_utf8(&out).unwrap(), "out.bvh").unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        back
    }

    #[test]
    fn parse_write_parse_is_the_same_clip() {
        let (clip, _) = parse(SMALL, "clip.bvh").unwrap();
        let back = round_trip(&clip);
        assert_eq!(back.hierarchy(), clip.hierarchy());
        assert_eq!(back.joints(), clip.joints());
        assert_eq!(back.values(), clip.values());
        assert_eq!(back.fps(), clip.fps());
        assert_eq!(back.frame_time_text(), "0.0333333333");
        // And once more: now byte for byte.
        let again = round_trip(&back);
        assert_eq!(again, back);
    }

    #[test]
    fn the_hierarchy_is_reproduced_byte_for_byte_with_crlf_and_odd_spacing() {
        let messy = SMALL
            .replace('\n', "\r\n")
            .replace("\tOFFSET", "  OFFSET   ");
        let (clip, _) = parse(&messy, "clip.bvh").unwrap();
        let mut out = Vec::new();
        write(&mut out, clip.hierarchy(), clip.fps(), 18, clip.values()).unwrap();
        let end = messy.find("MOTION").unwrap();
        assert_eq!(&out[..end], &messy.as_bytes()[..end]);
        assert_eq!(&out[end..end + 7], b"MOTION\n");
        assert_eq!(round_trip(&clip).values(), clip.values());
    }

    #[test]
    fn channel_names_round_trip() {
        for c in Channel::ALL {
            assert_eq!(Channel::parse(c.as_str()), Some(c));
            assert_eq!(c.to_string(), c.as_str());
        }
        assert_eq!(Channel::parse("zrotation"), None);
        assert_eq!(
            Channel::ALL.map(|c| (c.axis(), c.is_rotation())),
            [
                (0, false),
                (1, false),
                (2, false),
                (0, true),
                (1, true),
                (2, true)
            ]
        );
    }

    #[test]
    fn a_joint_with_some_rotation_channels_has_no_rotation() {
        let text = "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 2 Zrotation Xrotation\n}\n\
                    MOTION\nFrames: 1\nFrame Time: 0.01\n1 2\n";
        let (clip, _) = parse(text, "a.bvh").unwrap();
        assert_eq!(clip.joints()[0].rotation(), None);
        assert_eq!(clip.joints()[0].position(), None);
    }
}

#[cfg(test)]
mod fixtures {
    use super::*;

    #[test]
    fn the_mixed_order_fixture_has_each_joints_own_sequence() {
        let text = include_str!("../../../fixtures/bvh/mixed_orders.bvh");
        let (clip, warnings) = parse(text, "mixed_orders.bvh").unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        let seqs: Vec<Option<String>> = clip
            .joints()
            .iter()
            .map(|j| j.rotation().map(|(s, _)| s.as_str().to_string()))
            .collect();
        let want = [Some("ZXY"), Some("ZYX"), Some("YXZ"), None, Some("ZXY")];
        assert_eq!(seqs, want.map(|s| s.map(String::from)));
        assert_eq!(clip.joint("Tail").unwrap().position(), Some([13, 15, 17]));
        assert_eq!(
            clip.joint("Tail").unwrap().rotation().unwrap().1,
            [12, 14, 16]
        );
        assert_eq!((clip.frame_count(), clip.channel_count()), (4, 18));
    }
}

/// Writes one frame of a joint into its row of channel values: the rotation as the next
/// continuous Euler triple of `unwrap` in degrees at the rotation columns, the position at the
/// position columns (each only where the joint has those channels).
pub(crate) fn fill_joint_row(
    row: &mut [f64],
    rotation: Option<(crate::rotation::EulerSeq, [usize; 3])>,
    unwrap: Option<&mut crate::rotation::unwrap::EulerUnwrap>,
    position_cols: Option<[usize; 3]>,
    q: glam::DQuat,
    position: Option<glam::DVec3>,
) {
    if let (Some((_, cols)), Some(u)) = (rotation, unwrap) {
        for (c, a) in cols.iter().zip(u.next(q)) {
            row[*c] = a.to_degrees();
        }
    }
    if let (Some(cols), Some(p)) = (position_cols, position) {
        for (c, x) in cols.iter().zip(p.to_array()) {
            row[*c] = x;
        }
    }
}
