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
//! use inbetween_io::bvh;
//!
//! let text = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition \
//!             Zposition Zrotation Xrotation Yrotation\n  End Site\n  {\n    OFFSET 0 1 0\n  \
//!             }\n}\nMOTION\nFrames: 2\nFrame Time: 0.0333333\n0 1 2 10 20 30\n0 1 2 11 21 31\n";
//! let (clip, warnings) = bvh::parse(text, "clip.bvh")?;
//! assert!(warnings.is_empty());
//! assert_eq!((clip.fps().num(), clip.fps().den()), (30, 1));
//! let (seq, cols) = clip.joints()[0].rotation().unwrap();
//! assert_eq!((seq.as_str(), cols), ("ZXY", [Some(3), Some(4), Some(5)]));
//! assert_eq!(clip.row(1)[3], 11.0);
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
    name: String,
    parent: Option<usize>,
    offset: [f64; 3],
    channels: Vec<Channel>,
    first_column: usize,
    end_site: Option<[f64; 3]>,
    line: usize,
    /// Set by the parser once every joint is known ([`Joint::track_name`]).
    track_name: String,
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
    /// hierarchy's joints by [`unique_names`](crate::names::unique_names) with the joint's
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
/// Invariants (kept by [`parse`], the only constructor): at least one channel; the joints'
/// columns tile `0..channel_count()` in file order; `values().len() == frame_count() ·
/// channel_count()`; every value finite; the frame time positive and finite; the joints'
/// track names distinct.
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
    /// Each joint's index by its [`Joint::track_name`].
    by_track_name: HashMap<String, usize>,
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

    /// A one-joint file with `channels`, one row of `values`.
    fn one_joint(channels: &str, values: &str) -> Clip {
        let n = channels.split_whitespace().count();
        let text = format!(
            "HIERARCHY\nROOT a\n{{\nOFFSET 0 0 0\nCHANNELS {n} {channels}\n}}\n\
             MOTION\nFrames: 1\nFrame Time: 0.01\n{values}\n"
        );
        parse(&text, "a.bvh").unwrap().0
    }

    #[test]
    fn one_or_two_rotation_channels_are_the_listed_axes_completed_in_xyz_order() {
        use glam::DQuat;
        let elementary = |axis: char, deg: f64| match axis {
            'X' => DQuat::from_rotation_x(deg.to_radians()),
            'Y' => DQuat::from_rotation_y(deg.to_radians()),
            _ => DQuat::from_rotation_z(deg.to_radians()),
        };
        // (listed axes, the completed sequence: listed first, then the others in x, y, z order)
        let cases = [
            ("X", "XYZ"),
            ("Y", "YXZ"),
            ("Z", "ZXY"),
            ("XY", "XYZ"),
            ("YX", "YXZ"),
            ("XZ", "XZY"),
            ("ZX", "ZXY"),
            ("YZ", "YZX"),
            ("ZY", "ZYX"),
        ];
        for (listed, want) in cases {
            let channels: Vec<String> = listed.chars().map(|c| format!("{c}rotation")).collect();
            let values = ["25", "-70"][..listed.len()].join(" ");
            let clip = one_joint(&channels.join(" "), &values);
            let joint = &clip.joints()[0];
            let (seq, cols) = joint.rotation().unwrap();
            assert_eq!(seq.as_str(), want, "{listed}");
            let mut want_cols = [None; 3];
            for (i, c) in want_cols.iter_mut().enumerate().take(listed.len()) {
                *c = Some(i);
            }
            assert_eq!(cols, want_cols, "{listed}");
            assert_eq!(joint.position(), None);
            assert!(joint.is_track());
            // The rotation with the missing angles 0 is the product of the listed ones.
            let angles = cols.map(|c| c.map_or(0.0, |c| clip.row(0)[c]).to_radians());
            let product = listed
                .chars()
                .zip([25.0, -70.0])
                .fold(DQuat::IDENTITY, |q, (axis, deg)| q * elementary(axis, deg));
            let q = seq.to_quat(angles);
            assert!(
                q.dot(product).abs() > 1.0 - 1e-15,
                "{listed}: {q} vs {product}"
            );
        }
    }

    #[test]
    fn some_position_channels_are_a_position_with_the_others_at_zero() {
        let clip = one_joint("Yposition Xrotation", "3 4");
        let joint = &clip.joints()[0];
        assert_eq!(joint.position(), Some([None, Some(0), None]));
        assert_eq!(joint.rotation().unwrap().1, [Some(1), None, None]);
        let clip = one_joint("Zposition", "3");
        assert_eq!(clip.joints()[0].position(), Some([None, None, Some(0)]));
        assert_eq!(clip.joints()[0].rotation(), None);
        assert!(clip.joints()[0].is_track());
    }

    #[test]
    fn joints_sharing_a_name_have_distinct_track_names_found_by_hash() {
        let text = "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n\
                    JOINT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\n\
                    JOINT a#1\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\n}\n\
                    MOTION\nFrames: 1\nFrame Time: 0.01\n1 2 3\n";
        let (clip, _) = parse(text, "a.bvh").unwrap();
        let names: Vec<&str> = clip.joints().iter().map(Joint::track_name).collect();
        // The second `a` (index 1) would be `a#1`, which the third joint is given.
        assert_eq!(names, ["a", "a#1#2", "a#1"]);
        assert_eq!(clip.joint_index("a"), Some(0));
        assert_eq!(clip.joint_index("a#1#2"), Some(1));
        assert_eq!(clip.joint_index("a#1"), Some(2));
        assert_eq!(clip.joint("a#1").unwrap().name(), "a#1");
        assert_eq!(clip.joint_index("b"), None);
        assert_eq!(clip.track_joints(), [0, 1, 2]);
    }
}

#[cfg(test)]
mod fixtures {
    use super::*;

    #[test]
    fn the_mixed_order_fixture_has_each_joints_own_sequence() {
        let text = include_str!("../../../../fixtures/bvh/mixed_orders.bvh");
        let (clip, warnings) = parse(text, "mixed_orders.bvh").unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        let seqs: Vec<Option<String>> = clip
            .joints()
            .iter()
            .map(|j| j.rotation().map(|(s, _)| s.as_str().to_string()))
            .collect();
        let want = [Some("ZXY"), Some("ZYX"), Some("YXZ"), None, Some("ZXY")];
        assert_eq!(seqs, want.map(|s| s.map(String::from)));
        assert_eq!(
            clip.joint("Tail").unwrap().position(),
            Some([Some(13), Some(15), Some(17)])
        );
        assert_eq!(
            clip.joint("Tail").unwrap().rotation().unwrap().1,
            [Some(12), Some(14), Some(16)]
        );
        assert_eq!((clip.frame_count(), clip.channel_count()), (4, 18));
    }
}

/// Writes one frame of a joint into its row of channel values: the rotation as the next
/// continuous Euler triple of `unwrap` in degrees at the rotation columns, the position at the
/// position columns (each only where the joint has those channels: the angles and coordinates
/// of axes it does not list are not written).
pub(crate) fn fill_joint_row(
    row: &mut [f64],
    rotation: Option<(inbetween::rotation::EulerSeq, [Option<usize>; 3])>,
    unwrap: Option<&mut inbetween::rotation::unwrap::EulerUnwrap>,
    position_cols: Option<[Option<usize>; 3]>,
    q: glam::DQuat,
    position: Option<glam::DVec3>,
) {
    if let (Some((_, cols)), Some(u)) = (rotation, unwrap) {
        for (c, a) in cols.iter().zip(u.next(q)) {
            if let Some(c) = c {
                row[*c] = a.to_degrees();
            }
        }
    }
    if let (Some(cols), Some(p)) = (position_cols, position) {
        for (c, x) in cols.iter().zip(p.to_array()) {
            if let Some(c) = c {
                row[*c] = x;
            }
        }
    }
}
