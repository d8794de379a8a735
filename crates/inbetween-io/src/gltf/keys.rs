//! Keys written back into the asset: `reduce`'s kept keys of each rotation channel as a new
//! `LINEAR` sampler with its own times (a glTF player interpolates `LINEAR` rotations by slerp,
//! glTF 2.0 Appendix C, so keys reduced for `slerp` play as they were verified).

use super::document::{GltfClip, Mode};
use super::{ContainerFormat, Resampled, Values};
use glam::DQuat;
use inbetween::error::InputResult;
use std::path::Path;

/// The kept keys of one track (a rotation channel of the clip, by track name).
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelKeys<'a> {
    /// The track's name, as [`GltfClip::document`] named it.
    pub name: &'a str,
    /// Key times in seconds, strictly increasing (also as float32).
    pub times: Vec<f64>,
    /// One rotation per time.
    pub rotations: Vec<DQuat>,
}

/// The clip's asset with each named channel repointed to a new `LINEAR` sampler holding its
/// keys, everything else as read ([`super::Asset::to_bytes_in`]; `out_dir` as there). Errors:
/// a name that is no rotation channel of the clip, and the writer's own (times not strictly
/// increasing in float32, a channel named twice, a rotation that is not finite and non-zero).
pub fn keys_asset(
    clip: &GltfClip,
    keys: &[ChannelKeys<'_>],
    format: ContainerFormat,
    out_dir: Option<&Path>,
) -> InputResult<Vec<u8>> {
    let src = clip.asset().source();
    let mut resampled = Vec::with_capacity(keys.len());
    for k in keys {
        let s = clip
            .source_of(k.name, Mode::Frames)
            .ok_or_else(|| input_err!("{src}: no rotation channel for track {:?}", k.name))?;
        resampled.push(Resampled {
            animation: clip.animations()[s.animation].index(),
            times: k.times.clone(),
            channels: vec![(s.channel, Values::Rotations(k.rotations.clone()))],
        });
    }
    clip.asset().to_bytes_in(&resampled, format, out_dir)
}
