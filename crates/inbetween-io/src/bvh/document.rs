//! A BVH clip as a keyframe [`Document`]: one track per joint, one key per motion row.
//!
//! A joint with channels is a track named by its [`Joint::track_name`] (the joint's name, made
//! unique), in file order. Each row is a key at frame `i` of the clip's rate: its rotation from
//! the joint's own channel order (intrinsic, degrees: `Zrotation Xrotation Yrotation` is
//! `euler:ZXY`; one or two rotation channels are that sequence completed, the missing angles 0:
//! [`Joint::rotation`]), its Euler angles kept as written (so that `--path euler` and continuous
//! Euler output start from them; an angle beyond ±1e9° is first reduced exactly modulo 360°:
//! `angle_to_rad`), and its position channels, if any, as the key's translation
//! (an axis without a channel at 0). A joint with position channels only is a track of identity
//! rotations carrying those positions. Joints without channels have no track.

use super::{Clip, Joint};
use crate::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use glam::{DQuat, DVec3};
use inbetween::error::InputResult;
use inbetween::{Tcb, Track};
use std::sync::Arc;

/// Angles beyond this many degrees are reduced exactly modulo 360° before anything else
/// ([`angle_to_rad`]).
pub(crate) const REDUCE_BEYOND_DEG: f64 = 1e9;

/// A BVH angle (degrees) in radians: converted as it is up to ±[`REDUCE_BEYOND_DEG`] (so the
/// turns between rows are kept; the conversion's error stays below 1e-8 rad), and beyond it
/// first reduced exactly modulo 360° (`%` of two finite f64 is exact), as CSV and JSON degrees
/// are: `1e200` is 128°, where the radians of `1e200` would carry an error of many turns.
pub(crate) fn angle_to_rad(deg: f64) -> f64 {
    if deg.abs() > REDUCE_BEYOND_DEG {
        (deg % 360.0).to_radians()
    } else {
        deg.to_radians()
    }
}

/// The clip's joints as tracks (see the module documentation); `source` names the file, and
/// `warnings` are the parser's.
pub fn document(clip: Clip, source: &str, warnings: Vec<String>) -> Document {
    let tracks = clip
        .joints()
        .iter()
        .filter_map(|joint| joint_track(&clip, joint))
        .collect();
    Document {
        fps: Some(clip.fps()),
        tracks,
        named_tracks: true,
        warnings,
        hierarchy: Some(Arc::new(clip.skeleton())),
        skeleton: Some(Arc::new(clip)),
        ..Document::new(source.to_string())
    }
}

/// The track of one joint of `clip` (see the module documentation); `None` for a joint without
/// rotation or position channels.
pub(crate) fn joint_track(clip: &Clip, joint: &Joint) -> Option<DocTrack> {
    let rotation = joint.rotation();
    let position = joint.position();
    if rotation.is_none() && position.is_none() {
        return None;
    }
    let n = clip.frame_count();
    let mut keys = Vec::with_capacity(n);
    let mut angles = Vec::with_capacity(if rotation.is_some() { n } else { 0 });
    let mut translations = Vec::with_capacity(if position.is_some() { n } else { 0 });
    for (i, row) in clip.rows().enumerate() {
        let rot = match rotation {
            Some((seq, cols)) => {
                let e = cols.map(|c| c.map_or(0.0, |c| angle_to_rad(row[c])));
                angles.push(DVec3::from_array(e));
                inbetween::rotation::quat::canonical(seq.to_quat(e))
            }
            None => DQuat::IDENTITY,
        };
        if let Some(cols) = position {
            translations.push(Some(DVec3::from_array(
                cols.map(|c| c.map_or(0.0, |c| row[c])),
            )));
        }
        keys.push(Key {
            when: KeyTime::Frame(i as f64),
            rot,
        });
    }
    Some(DocTrack {
        name: Some(joint.track_name().to_string()),
        keys,
        start_velocity: None,
        end_velocity: None,
        origin: KeyOrigin::Frames,
        euler: rotation.map(|(seq, _)| (seq, angles)),
        velocities: Vec::new(),
        tcb: Vec::new(),
        translations,
    })
}

/// The track of one joint of `clip` both as the clip's [`document`] holds it (`joint_track`)
/// and validated exactly as [`Document::tracks_shaped`] validates it there (`source` names the
/// file in errors, `tcb` as there): one joint at a time, for a caller that reads the joints
/// apart and needs the keys as read beside the track. `Ok(None)` for a joint that is not a track.
pub fn joint_tracks(
    clip: &Clip,
    joint: &Joint,
    source: &str,
    tcb: Tcb,
) -> InputResult<Option<(DocTrack, Track)>> {
    let Some(doc_track) = joint_track(clip, joint) else {
        return Ok(None);
    };
    let mut doc = Document {
        fps: Some(clip.fps()),
        tracks: vec![doc_track],
        named_tracks: true,
        ..Document::new(source.to_string())
    };
    let track = doc.tracks_shaped(clip.fps(), tcb)?.pop();
    Ok(doc.tracks.pop().zip(track))
}
