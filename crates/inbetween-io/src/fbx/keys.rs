//! A document's keys as an FBX scene: what `convert` and `reduce` write. Each joint's curves
//! have their own key times (FBX plays every channel separately), so tracks need not share
//! them; between keys a player interpolates each Euler angle and coordinate linearly.

use super::write::{Scene, TrackKeys, time_tick, write_fbx};
use crate::clip::Clip;
use crate::document::Document;
use crate::usd::write::Stage;
use inbetween::Error;
use inbetween::clock::Fps;
use inbetween::error::InputError;
use inbetween::rotation::EulerSeq;
use std::io::Write;

/// Each joint's intrinsic Euler sequence in `doc`'s skeleton: a BVH clip's (BVH and FBX input:
/// the joint's rotation channels, a hinge's completed as BVH reads it), else `ZYX` (FBX's
/// default order, `eEulerXYZ`).
pub fn joint_orders(doc: &Document) -> Vec<EulerSeq> {
    let n = doc.hierarchy.as_ref().map_or(0, |h| h.joints().len());
    match &doc.skeleton {
        Some(clip) if clip.joints().len() == n => clip_orders(clip),
        _ => vec![default_order(); n],
    }
}

/// Each joint's intrinsic Euler sequence in a BVH clip: its rotation channels' (a hinge's
/// completed as BVH reads it), else `ZYX` (FBX's default order, `eEulerXYZ`).
pub fn clip_orders(clip: &Clip) -> Vec<EulerSeq> {
    clip.joints()
        .iter()
        .map(|j| j.rotation().map_or(default_order(), |(seq, _)| seq))
        .collect()
}

fn default_order() -> EulerSeq {
    EulerSeq::parse("ZYX").expect("a valid sequence")
}

/// The stage of a document: its unit (else centimetres, 0.01 m) and up axis.
pub fn stage(doc: &Document) -> Stage {
    Stage {
        meters_per_unit: doc.unit_meters.unwrap_or(BVH_STAGE.meters_per_unit),
        z_up: doc.z_up == Some(true),
    }
}

/// The stage of a BVH file, which declares neither: centimetres (0.01 m), Y up. What FBX output
/// on a `--skeleton` template is written on, as a BVH input's is.
pub const BVH_STAGE: Stage = Stage {
    meters_per_unit: 0.01,
    z_up: false,
};

/// Writes the keys of `doc` as the motion of the BVH template `clip` at `fps` (`convert
/// keys.json --skeleton clip.bvh -o out.fbx`): template track `k` (its `k`-th joint with
/// channels) is `doc`'s track `order[k]` (as the caller matched them by name), each key the
/// pose the joint's channels carry ([`crate::bvh::channel_pose`]), at its time's tick. A joint
/// with position channels needs every key's translation. Tracks need not share key times.
pub fn write_keys_on<W: Write>(
    out: W,
    doc: &Document,
    clip: &Clip,
    order: &[usize],
    fps: Fps,
) -> Result<(), Error> {
    let joints = clip.track_joints();
    if order.len() != joints.len() {
        return Err(Error::Internal(format!(
            "internal error: {} tracks on a skeleton of {}",
            order.len(),
            joints.len()
        )));
    }
    let mut tracks = Vec::with_capacity(order.len());
    for (&i, &j) in order.iter().zip(&joints) {
        let (track, joint) = (&doc.tracks[i], &clip.joints()[j]);
        let times = doc.track_times(track, fps, 1)?;
        let mut keys = TrackKeys {
            ticks: times.iter().map(|&t| time_tick(t, fps)).collect(),
            ..TrackKeys::default()
        };
        for (k, key) in track.keys.iter().enumerate() {
            let p = track.translations.get(k).copied().flatten();
            if joint.position().is_some() && p.is_none() {
                return Err(InputError::new(format!(
                    "{}: track \"{}\": joint \"{}\" has position channels, so every key needs \
                     a translation",
                    doc.source,
                    inbetween::error::shorten(joint.track_name()),
                    inbetween::error::shorten(joint.name())
                ))
                .into());
            }
            let (rot, p) = crate::bvh::channel_pose(joint, key.rot, p);
            keys.rotations.push(rot);
            if let Some(p) = p {
                keys.positions.get_or_insert_with(Vec::new).push(p);
            }
        }
        tracks.push(keys);
    }
    let orders = clip_orders(clip);
    let scene = Scene {
        skeleton: &clip.skeleton(),
        orders: &orders,
        fps,
        tracks: &tracks,
        stage: BVH_STAGE,
    };
    write_fbx(out, &scene)?;
    Ok(())
}

/// Writes the keys of `doc` (a document with a skeleton: BVH, glTF, FBX or USD input, or keys
/// reduced from one) as an FBX scene at `fps`: each key a key of its joint's curves, at its
/// time's tick ([`time_tick`]: a frame's exact tick where the key is on a frame). Errors: no
/// skeleton, and the writer's.
pub fn write_keys<W: Write>(out: W, doc: &Document, fps: Fps) -> Result<(), Error> {
    let skeleton = doc.output_skeleton("FBX")?;
    let joints = skeleton.track_joints();
    let mut tracks = Vec::with_capacity(doc.tracks.len());
    for (i, track) in doc.tracks.iter().enumerate() {
        let times = doc.track_times(track, fps, 1)?;
        let positions = track.positions_or(joints[i].map(|j| skeleton.joints()[j].translation));
        tracks.push(TrackKeys {
            ticks: times.iter().map(|&t| time_tick(t, fps)).collect(),
            rotations: track.keys.iter().map(|k| k.rot).collect(),
            positions,
        });
    }
    let orders = joint_orders(doc);
    let scene = Scene {
        skeleton,
        orders: &orders,
        fps,
        tracks: &tracks,
        stage: stage(doc),
    };
    write_fbx(out, &scene)?;
    Ok(())
}
