//! A document's keys as `.usda` samples: what `convert` and `reduce` write. USD samples every
//! joint at the same time codes, so the tracks must share their key times; between samples a
//! USD player interpolates rotations by slerp and translations linearly.

use super::write::{Stage, TrackSamples, write_usda};
use crate::document::{Document, track_label};
use inbetween::Error;
use inbetween::clock::Fps;
use inbetween::error::InputError;
use std::io::Write;

/// Writes the keys of `doc` (a document with a skeleton: BVH, glTF or FBX input, or keys reduced
/// from one) as `.usda` at `fps`: each key time `t` is the time code `t·fps` (a frame number,
/// fractional where a key is between frames). Errors: no skeleton, tracks with different key
/// times, and the writer's.
pub fn write_keys<W: Write>(out: W, doc: &Document, fps: Fps) -> Result<(), Error> {
    let skeleton = doc.output_skeleton("USD")?;
    // Once, not per track: each call walks every joint.
    let joints = skeleton.track_joints();
    let mut codes: Option<Vec<f64>> = None;
    let mut tracks = Vec::with_capacity(doc.tracks.len());
    for (i, track) in doc.tracks.iter().enumerate() {
        let times = doc.track_times(track, fps, 1)?;
        let these: Vec<f64> = times
            .iter()
            .map(|&t| {
                let c = t * fps.as_f64();
                let k = c.round();
                if (c - k).abs() <= 1e-9 * k.abs().max(1.0) {
                    k
                } else {
                    c
                }
            })
            .collect();
        match &codes {
            None => codes = Some(these),
            Some(first) if *first != these => {
                return Err(InputError::new(format!(
                    "{}: USD samples every joint at the same times, and its keys are at other \
                     times than track 0's (reduce them with shared keys)",
                    track_label(&doc.source, doc.tracks[i].name.as_deref())
                ))
                .into());
            }
            Some(_) => {}
        }
        let positions = track.positions_or(joints[i].map(|j| skeleton.joints()[j].translation));
        tracks.push(TrackSamples {
            rotations: track.keys.iter().map(|k| k.rot).collect(),
            positions,
        });
    }
    let codes = codes.unwrap_or_default();
    let stage = Stage {
        meters_per_unit: doc.unit_meters.unwrap_or(0.01),
        z_up: doc.z_up == Some(true),
    };
    write_usda(out, skeleton, fps, &codes, &tracks, stage)?;
    Ok(())
}
