//! `reduce anim.glb -o small.glb`: the kept keys written back into the asset. Each rotation
//! channel of a track is repointed to a `LINEAR` sampler with its kept keys, which a glTF player
//! interpolates by slerp, as verified; with `--translation-tolerance` and `--scale-tolerance`
//! the animations' `LINEAR` translation and scale channels are reduced too, played by lerp as
//! glTF plays them (docs/spec.md §5a, glTF output).

use super::tracks::{FLOAT32_MARGIN, reduce_options, reduce_tracks};
use crate::args::ReduceArgs;
use crate::events::Events;
use crate::settings::Curves;
use glam::DQuat;
use inbetween::reduce::{ReduceOptions, Reduced, TrackFrames, reduce_each, rotation_error};
use inbetween::{Error, InputError, Scheme};
use inbetween_io::gltf::document::{GltfClip, Mode};
use inbetween_io::gltf::keys::{ChannelKeys, keys_asset, read_back};
use inbetween_io::gltf::{ContainerFormat, Interpolation, TranslationChannel, Values};
use std::collections::HashSet;

/// Runs `reduce` for glTF output (see the module documentation).
pub(super) fn to_gltf(
    args: &ReduceArgs,
    input: &Curves,
    container: ContainerFormat,
    told: &mut dyn Events,
) -> Result<(), Error> {
    let Some(clip) = &input.gltf else {
        return Err(InputError::new(
            "glTF output writes keys into the input asset: the input must be glTF (.gltf or .glb)",
        )
        .into());
    };
    if input.opts.scheme != Scheme::Slerp {
        return Err(InputError::new(
            "glTF output: a glTF LINEAR sampler plays keys by slerp, so only --scheme slerp's keys \
             play as reduced; use --scheme slerp, or write csv or json",
        )
        .into());
    }
    let margin = FLOAT32_MARGIN * args.distance.unwrap_or(1.0);
    let reduced = reduce_tracks(args, input, (margin, 0.0), (false, true), told)?;
    super::report::report_all(args, input, &reduced, told);
    let mut keys = Vec::with_capacity(reduced.len());
    for (t, r) in input.tracks.iter().zip(&reduced) {
        let name = t.name().unwrap_or_default();
        let times = r.keys.iter().map(|&i| t.times()[i]).collect();
        let rotations = r.keys.iter().map(|&i| t.rotations()[i]).collect();
        keys.push(ChannelKeys::of_track(clip, name, times, rotations)?);
    }
    let (vector_keys, originals) = vector_keys(args, input, clip, told)?;
    keys.extend(vector_keys);
    let container = crate::settings::gltf_container(&args.output, container, clip);
    let bytes = keys_asset(clip, &keys, container, args.output.folder())?;
    check_written(args, input, clip, &keys, &originals, &bytes)?;
    let mut out = crate::output::open_output(args.output.output.as_deref(), &input.reads)?;
    std::io::Write::write_all(&mut out, &bytes)?;
    out.commit()?;
    Ok(())
}

/// A translation or scale channel to reduce: the animation's position in the clip, the channel,
/// and what it holds (for messages).
type VectorChannel<'a> = (usize, &'a TranslationChannel, &'static str);

/// A reduced translation or scale channel as read, and its tolerance.
type Original<'a> = (&'a TranslationChannel, f64);

/// The kept keys of the clip's `LINEAR` translation channels (with `--translation-tolerance`)
/// and scale channels (with `--scale-tolerance`) of more than two keys, in the chosen animations
/// and, with `--tracks`, on the nodes of the chosen tracks. Each is reduced as the positions of a
/// slerp curve (linear between keys, as glTF's lerp) under its tolerance, verified at every key
/// of the channel; both curves being linear between the channel's keys, the bound then holds at
/// every time. The kept values and times are the channel's own float32 numbers, written back
/// unchanged; a channel that keeps every key is left as it was. Beside the keys, each reduced
/// channel as read and its tolerance, for [`check_written`].
fn vector_keys<'c>(
    args: &ReduceArgs,
    input: &Curves,
    clip: &'c GltfClip,
    told: &mut dyn Events,
) -> Result<(Vec<ChannelKeys>, Vec<Original<'c>>), Error> {
    let nodes = args
        .input
        .tracks
        .is_some()
        .then(|| track_nodes(input, clip));
    let (mut keys, mut originals) = (Vec::new(), Vec::new());
    for (tolerance, what) in [
        (args.translation_tolerance, "translation"),
        (args.scale_tolerance, "scale"),
    ] {
        let Some(tolerance) = tolerance else { continue };
        let mut channels: Vec<VectorChannel> = Vec::new();
        for (a, anim) in clip.animations().iter().enumerate() {
            let of_kind = match what {
                "translation" => anim.translations(),
                _ => anim.scales(),
            };
            channels.extend(
                of_kind
                    .iter()
                    .filter(|c| c.interpolation() == Interpolation::Linear && c.times().len() > 2)
                    .filter(|c| nodes.as_ref().is_none_or(|n| n.contains(&(a, c.node()))))
                    .map(|c| (a, c, what)),
            );
        }
        let opts = ReduceOptions {
            translation_tolerance: Some(tolerance),
            ..reduce_options(args, input.opts, (0.0, 0.0), true)?
        };
        let reduced = reduce_vectors(&channels, &opts).map_err(|e| match e {
            Error::Input(e) => Error::Input(e.at(clip.asset().source())),
            other => other,
        })?;
        for (&(a, ch, what), r) in channels.iter().zip(&reduced) {
            if args.verbose {
                told.report(&report(clip, a, ch, what, r));
            }
            if r.keys.len() == ch.times().len() {
                continue; // every key kept: the channel stays as it was
            }
            keys.push(ChannelKeys {
                animation: a,
                channel: ch.index(),
                times: r.keys.iter().map(|&i| ch.times()[i]).collect(),
                values: Values::Vectors(r.keys.iter().map(|&i| ch.values()[i]).collect()),
            });
            originals.push((ch, tolerance));
        }
    }
    Ok((keys, originals))
}

/// Each channel's values reduced as the positions of a track that does not turn.
fn reduce_vectors(
    channels: &[VectorChannel<'_>],
    opts: &ReduceOptions,
) -> Result<Vec<Reduced>, Error> {
    let still: Vec<Vec<DQuat>> = channels
        .iter()
        .map(|(_, c, _)| vec![DQuat::IDENTITY; c.times().len()])
        .collect();
    let frames: Vec<TrackFrames> = channels
        .iter()
        .zip(&still)
        .map(|(&(_, c, _), rotations)| TrackFrames {
            times: c.times(),
            rotations,
            positions: Some(c.values()),
            euler: None,
            key_times: None,
        })
        .collect();
    reduce_each(&frames, opts)
}

/// `(animation position, node)` of every track of the input.
fn track_nodes(input: &Curves, clip: &GltfClip) -> HashSet<(usize, usize)> {
    input
        .tracks
        .iter()
        .filter_map(|t| clip.source_of(t.name()?, Mode::Frames))
        .filter_map(|s| {
            let anim = &clip.animations()[s.animation];
            let ch = anim.rotations().iter().find(|c| c.index() == s.channel)?;
            Some((s.animation, ch.node()))
        })
        .collect()
}

/// `-v`'s line for a reduced translation or scale channel.
fn report(clip: &GltfClip, a: usize, ch: &TranslationChannel, what: &str, r: &Reduced) -> String {
    let len = ch.times().len();
    format!(
        "inbetween: reduce: {} ({what} of node \"{}\"): {len} keys, {} kept ({:.1} %), max \
         error {:.3e}",
        clip.channel_label(a, ch.index()),
        inbetween::error::shorten(ch.node_name()),
        r.keys.len(),
        100.0 * r.keys.len() as f64 / len as f64,
        r.max_position_error.unwrap_or(0.0),
    )
}

/// The guarantee checked on the asset as written (float32 times and values, normalised and
/// sign-continuous rotations): the asset is read back as any input is, and each reduced
/// channel sampled as glTF 2.0 Appendix C plays it — a track's rotation channel at every frame
/// time, a translation or scale channel at every key time of the original — must meet its
/// tolerance. A miss, or an asset that does not read back, is an internal error (the float32
/// margin and the verification on float32 times are meant to make it impossible). `keys` are
/// the tracks' keys, then the vector channels' whose originals and tolerances `originals` has.
fn check_written(
    args: &ReduceArgs,
    input: &Curves,
    clip: &GltfClip,
    keys: &[ChannelKeys],
    originals: &[Original<'_>],
    bytes: &[u8],
) -> Result<(), Error> {
    let internal = |m: String| Error::Internal(format!("reduce to glTF: {m}"));
    let base = args.output.folder().or(clip.asset().base_dir());
    // Every channel holds its keys (as Python's glTF write checks), then every frame of the
    // input is within the tolerance as the asset plays.
    let back = read_back(clip, keys, bytes, base)?;
    let opts = reduce_options(args, input.opts, (0.0, 0.0), false)?;
    let written = |k: &ChannelKeys| &back[clip.animations()[k.animation].index()];
    for (t, k) in input.tracks.iter().zip(keys) {
        let Some(ch) = written(k)
            .rotations()
            .iter()
            .find(|c| c.index() == k.channel)
        else {
            return Err(internal(format!("channel {} is no rotation", k.channel)));
        };
        for (&time, &q) in t.times().iter().zip(t.rotations()) {
            let e = rotation_error(&opts, ch.sample(time), q);
            if e.is_nan() || e > opts.tolerance {
                return Err(internal(format!(
                    "track {:?} as written misses its frame at {time} s by {e:e}, more than \
                     {:e}",
                    t.name().unwrap_or_default(),
                    opts.tolerance
                )));
            }
        }
    }
    for (k, &(was, tolerance)) in keys[input.tracks.len()..].iter().zip(originals) {
        let now = written(k)
            .translations()
            .iter()
            .chain(written(k).scales())
            .find(|c| c.index() == k.channel)
            .ok_or_else(|| internal(format!("channel {} is gone", k.channel)))?;
        for (&time, v) in was.times().iter().zip(was.values()) {
            let d = (now.sample(time) - *v).length();
            if d.is_nan() || d > tolerance {
                return Err(internal(format!(
                    "channel {} as written misses its key at {time} s by {d:e}, more than \
                     {tolerance:e}",
                    k.channel
                )));
            }
        }
    }
    Ok(())
}
