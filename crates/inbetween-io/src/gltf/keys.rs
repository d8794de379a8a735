//! Keys written back into the asset: `reduce`'s kept keys of each channel as a new `LINEAR`
//! sampler with its own times. A glTF player interpolates `LINEAR` rotations by slerp and
//! translations and scales by lerp (glTF 2.0 Appendix C), so keys reduced for `slerp` (whose
//! positions are linear between keys) play as they were verified.

use super::document::{GltfClip, Mode};
use super::{Animation, Asset, ContainerFormat, Resampled, Values};
use glam::DQuat;
use inbetween::Error;
use inbetween::error::InputResult;
use inbetween::rotation::quat::rotation_angle_between;
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
/// How far a rotation read back may be from its key: float32 components (about 2.4e-7 rad at
/// most).
const ROTATION_READ_BACK: f64 = 1e-6;

/// The asset `bytes` ([`keys_asset`] of `clip` and `keys`) read back as any input is (external
/// files from `base`, where it is written), each channel of `keys` checked to hold its keys: the
/// times as float32, rotations within float32 precision, vectors (translations, scales) equal
/// to their float32 values. Returns the animations read back, for a caller that checks more
/// (reduce: every frame within its tolerance). A miss is [`Error::Internal`] (a writer bug):
/// the caller writes nothing.
pub fn read_back(
    clip: &GltfClip,
    keys: &[ChannelKeys],
    bytes: &[u8],
    base: Option<&Path>,
) -> Result<Vec<Animation>, Error> {
    let internal = |m: String| Error::Internal(format!("internal error: glTF output: {m}"));
    let back = Asset::from_slice(bytes, clip.asset().source(), base)
        .and_then(|a| a.animations())
        .map_err(|e| {
            internal(format!(
                "the asset written does not read back: {}",
                e.message()
            ))
        })?;
    for k in keys {
        let anim = &back[clip.animations()[k.animation].index()];
        let f32_times: Vec<f32> = k.times.iter().map(|&t| t as f32).collect();
        let ok = match &k.values {
            Values::Rotations(want) => anim
                .rotations()
                .iter()
                .find(|c| c.index() == k.channel)
                .is_some_and(|c| {
                    c.times_f32() == f32_times.as_slice()
                        && c.values().len() == want.len()
                        && c.values().iter().zip(want).all(|(got, w)| {
                            rotation_angle_between(got.normalize(), w.normalize())
                                <= ROTATION_READ_BACK
                        })
                }),
            Values::Vectors(want) => anim
                .translations()
                .iter()
                .chain(anim.scales())
                .find(|c| c.index() == k.channel)
                .is_some_and(|c| {
                    c.times_f32() == f32_times.as_slice()
                        && c.values().len() == want.len()
                        && c.values()
                            .iter()
                            .zip(want)
                            .all(|(got, w)| *got == w.as_vec3().as_dvec3())
                }),
        };
        if !ok {
            let label = clip.channel_label(k.animation, k.channel);
            return Err(internal(format!("{label} does not read back as its keys")));
        }
    }
    Ok(back)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clip() -> GltfClip {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../fixtures/gltf/minimal_linear.gltf"
        );
        GltfClip::new(Asset::read_path(Path::new(path)).unwrap(), None).unwrap()
    }

    /// The keys of the clip's first track, halved: the first and last of every other.
    fn some_keys(clip: &GltfClip) -> ChannelKeys {
        let name = clip.sources(Mode::Frames)[0].name.clone();
        let r = clip.animations()[0].rotations()[0].clone();
        let times: Vec<f64> = r.times().iter().step_by(2).copied().collect();
        let rots: Vec<DQuat> = r.values().iter().step_by(2).copied().collect();
        ChannelKeys::of_track(clip, &name, times, rots).unwrap()
    }

    #[test]
    fn written_keys_read_back_and_others_are_an_internal_error() {
        let clip = clip();
        let keys = [some_keys(&clip)];
        let bytes = keys_asset(&clip, &keys, ContainerFormat::Glb, None).unwrap();
        let back = read_back(&clip, &keys, &bytes, None).unwrap();
        assert_eq!(back.len(), clip.animations().len());
        // Keys the bytes do not hold: a rotation 0.01 rad off, a time moved.
        let mut off = keys[0].clone();
        if let Values::Rotations(r) = &mut off.values {
            r[0] *= DQuat::from_rotation_z(0.01);
        }
        let e = read_back(&clip, &[off], &bytes, None).unwrap_err();
        assert!(
            matches!(&e, Error::Internal(m) if m.ends_with("does not read back as its keys")),
            "{e}"
        );
        let mut moved = keys[0].clone();
        moved.times[0] += 1e-3;
        assert!(matches!(
            read_back(&clip, &[moved], &bytes, None),
            Err(Error::Internal(_))
        ));
        // Bytes that are no asset.
        let e = read_back(&clip, &keys, &bytes[..bytes.len() / 2], None).unwrap_err();
        assert!(e.to_string().contains("does not read back"), "{e}");
    }
}
