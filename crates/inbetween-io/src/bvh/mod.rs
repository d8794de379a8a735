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
//! which is [`EulerSeq::parse("ZXY")`](inbetween::EulerSeq::parse) ([`Joint::rotation`]). Frame `i` is at
//! `i / rate` seconds ([`Clip::time_of`]), the rate being recovered from the rounded
//! `Frame Time` by `rate_from_frame_time`.
//!
//! - [`read`]: the parser, [`parse`]: text → [`Clip`] and located warnings; [`parse_reader`]:
//!   the same from a reader in pieces, never holding the text; [`parse_reader_chosen`]: only
//!   some joints' values kept ([`chosen`], `interp --tracks`).
//! - [`resample`]: a clip resampled one joint at a time (`interp`'s lean path).
//! - [`rate`]: `Frame Time` ↔ an exact [`Fps`](inbetween::Fps).
//! - [`mod@write`]: [`write()`](write::write) and the streaming `BvhWriter`.
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

pub mod chosen;
pub mod document;
pub mod frames;
mod hierarchy;
pub mod keys;
pub mod rate;
pub mod read;
pub mod resample;
pub mod write;

pub use read::{parse, parse_reader, parse_reader_chosen};
pub use write::write;

pub use crate::clip::{Channel, Clip, Joint};

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
        // The motion ends its lines as the hierarchy does.
        assert_eq!(&out[end..end + 8], b"MOTION\r\n");
        let lines = out.iter().filter(|&&c| c == b'\n').count();
        assert_eq!(out.windows(2).filter(|w| w == b"\r\n").count(), lines);
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
        // Read at run time from the repository (the crate's package has no fixtures/).
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../fixtures/bvh/mixed_orders.bvh"
        ))
        .unwrap();
        let (clip, warnings) = parse(&text, "mixed_orders.bvh").unwrap();
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
    if let Some((seq, cols)) = rotation {
        // Continuous along the track, or (without an unwrapper) each triple in scipy's ranges.
        let angles = unwrap.map_or_else(|| seq.from_quat(q), |u| u.next(q));
        let angles = on_listed_axes(seq, &cols, q, angles);
        for (c, a) in cols.iter().zip(angles) {
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

/// The angles of a joint with fewer than three rotation channels: its sequence lists its own
/// axes first and the others after (docs/spec.md §3, BVH), and only its own are written, so
/// the triple must keep the unlisted angles at zero. `angles` (the regular or continuous triple)
/// does, to rounding, for a rotation the joint can make — except at the sequence's gimbal lock,
/// where the first and third axes align and the split between them is arbitrary (`Zrotation
/// Xrotation` at X = 90° came back with another Z). There, and for a rotation the joint cannot
/// make exactly, the angles are solved on the listed axes alone: one axis, the rotation's
/// angle about it; two, the first angle turning the second axis where the rotation turns it,
/// then the second angle about it. Each angle the nearest to `angles`' by whole turns.
pub(crate) fn on_listed_axes(
    seq: inbetween::rotation::EulerSeq,
    cols: &[Option<usize>; 3],
    q: glam::DQuat,
    angles: [f64; 3],
) -> [f64; 3] {
    use glam::{DQuat, DVec3};
    use std::f64::consts::TAU;
    let listed = cols.iter().take_while(|c| c.is_some()).count();
    let pinned = angles[listed..].iter().all(|a| a.abs() <= 1e-12);
    if listed == 3 || listed == 0 || pinned {
        return angles;
    }
    let letters = seq.as_str().as_bytes();
    if letters[0].is_ascii_lowercase() {
        // BVH sequences are intrinsic (the channels' order); an extrinsic one is not a joint's.
        return angles;
    }
    let axis = |i: usize| match letters[i].to_ascii_lowercase() {
        b'x' => DVec3::X,
        b'y' => DVec3::Y,
        _ => DVec3::Z,
    };
    let near = |a: f64, to: f64| a + TAU * ((to - a) / TAU).round();
    let about = |r: DQuat, e: DVec3| 2.0 * r.xyz().dot(e).atan2(r.w);
    let (e0, e1) = (axis(0), axis(1));
    if listed == 1 {
        return [near(about(q, e0), angles[0]), 0.0, 0.0];
    }
    let u = q * e1;
    let a = e0.dot(e1.cross(u)).atan2(e1.dot(u));
    let b = about(DQuat::from_axis_angle(e0, a).inverse() * q, e1);
    [near(a, angles[0]), near(b, angles[1]), 0.0]
}

/// The pose `joint`'s channels carry of rotation `q` and position `p`: what BVH output writes
/// of them, read back (to the file's rounding). The rotation on the joint's listed axes
/// (solved on those axes as BVH output solves it, the unlisted angles 0), unchanged with three
/// rotation channels, the identity with none; the position on its listed position axes (0 on
/// the others), `None` without position channels (its `OFFSET` holds) or without `p`. What FBX
/// output on a skeleton template writes (docs/spec.md §3, *FBX output*), so that it means what
/// the BVH output means.
pub fn channel_pose(
    joint: &Joint,
    q: glam::DQuat,
    p: Option<glam::DVec3>,
) -> (glam::DQuat, Option<glam::DVec3>) {
    let rot = match joint.rotation() {
        None => glam::DQuat::IDENTITY,
        Some((_, cols)) if cols.iter().all(Option::is_some) => q,
        Some((seq, cols)) => {
            let angles = on_listed_axes(seq, &cols, q, seq.from_quat(q));
            let e = std::array::from_fn(|i| if cols[i].is_some() { angles[i] } else { 0.0 });
            seq.to_quat(e)
        }
    };
    let position = joint.position().zip(p).map(|(cols, p)| {
        let p = p.to_array();
        glam::DVec3::from_array(std::array::from_fn(|i| {
            if cols[i].is_some() { p[i] } else { 0.0 }
        }))
    });
    (rot, position)
}
