//! Keys written back into the asset: `reduce`'s kept keys of each channel as a new `LINEAR`
//! sampler with its own times. A glTF player interpolates `LINEAR` rotations by slerp and
//! translations and scales by lerp (glTF 2.0 Appendix C), so keys reduced for `slerp` (whose
//! positions are linear between keys) play as they were verified.

use super::document::{GltfClip, Mode};
use super::{ContainerFormat, Resampled, Values};
use glam::DQuat;
use inbetween::error::InputResult;
use std::path::Path;

/// The kept keys of one channel of the clip.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelKeys {
    /// The animation's position in [`GltfClip::animations`].
    pub animation: usize,
    /// The channel's index in the animation's `channels`.
    pub channel: usize,
    /// Key times in seconds, strictly increasing (also as float32).
    pub times: Vec<f64>,
    /// One value per time: rotations for a rotation channel, vectors for a translation or
    /// scale channel.
    pub values: Values,
}

impl ChannelKeys {
    /// The keys of the rotation channel of the clip's track `name` ([`GltfClip::document`]'s
    /// names). Errors: a name that is no rotation channel of the clip.
    pub fn of_track(
        clip: &GltfClip,
        name: &str,
        times: Vec<f64>,
        rotations: Vec<DQuat>,
    ) -> InputResult<ChannelKeys> {
        let s = clip.source_of(name, Mode::Frames).ok_or_else(|| {
            input_err!(
                "{}: no rotation channel for track {name:?}",
                clip.asset().source()
            )
        })?;
        Ok(ChannelKeys {
            animation: s.animation,
            channel: s.channel,
            times,
            values: Values::Rotations(rotations),
        })
    }
}

/// The clip's asset with each channel of `keys` repointed to a new `LINEAR` sampler holding its
/// keys, what no channel uses any more removed, everything else as read
/// ([`super::Asset::to_bytes_in`]; `out_dir` as there). Errors: an animation position outside
/// the clip's, and the writer's own (times not strictly increasing in float32, a channel named
/// twice or of another kind than its values, a value that is not finite, a zero rotation).
pub fn keys_asset(
    clip: &GltfClip,
    keys: &[ChannelKeys],
    format: ContainerFormat,
    out_dir: Option<&Path>,
) -> InputResult<Vec<u8>> {
    let src = clip.asset().source();
    let mut resampled = Vec::with_capacity(keys.len());
    for k in keys {
        let anim = clip.animations().get(k.animation).ok_or_else(|| {
            input_err!(
                "{src}: animation {} is not one of the clip's {}",
                k.animation,
                clip.animations().len()
            )
        })?;
        resampled.push(Resampled {
            animation: anim.index(),
            times: k.times.clone(),
            channels: vec![(k.channel, k.values.clone())],
        });
    }
    clip.asset().to_bytes_in(&resampled, format, out_dir)
}
