//! `write` to `.glb` / `.gltf`: a clip's tracks written into the glTF asset it was read from,
//! each track's keys as a new `LINEAR` sampler of its rotation channel (and of its node's
//! translation channel when the track has translations), everything else of the asset kept —
//! the bytes `inbetween reduce anim.glb -o small.glb` writes for the same keys
//! ([`inbetween_io::gltf::keys`]). The asset comes as the bytes the Python layer read (and
//! checked against the digest taken when the clip was read); the written asset is read back
//! and each channel compared with its keys before the file is replaced.

use crate::input_error;
use glam::{DQuat, DVec3};
use inbetween_io::document::{Document, KeyTime};
use inbetween_io::gltf::document::{GltfClip, Mode};
use inbetween_io::gltf::keys::{ChannelKeys, keys_asset, read_back};
use inbetween_io::gltf::{Asset, ContainerFormat, Values};
use pyo3::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The source asset handed over by the Python layer: its name in messages (the clip's
/// `source`), the file it was read from (external buffers are beside it) and its bytes.
pub type SourceAsset = (String, PathBuf, pyo3::pybacked::PyBackedBytes);

/// The glTF bytes of `doc`'s tracks written into `asset` as `container`, for a file in
/// `out_dir`: one new `LINEAR` sampler per track (its rotation channel, found by the track's
/// name among the asset's rotation channels as `read` names them) and one per track with
/// translations (its node's translation channel in the same animation). Errors: a track that
/// is no rotation channel of the asset, translations for a node without a translation channel,
/// times that are negative or not strictly increasing as float32, two tracks for one channel.
pub fn bytes(
    doc: &Document,
    asset: &SourceAsset,
    container: ContainerFormat,
    out_dir: &Path,
) -> PyResult<Vec<u8>> {
    let located = |e: inbetween::InputError| input_error(crate::message(&e));
    let (source, file, data) = asset;
    let dir = inbetween_io::gltf_dir(file);
    let limit = inbetween_io::DEFAULT_MAX_INPUT_BYTES;
    let read = Asset::from_slice_limited(data, source, Some(&dir), limit)
        .and_then(|a| GltfClip::new(a, None))
        .map_err(located)?;
    let mut keys = Vec::with_capacity(doc.tracks.len());
    let mut vector_keys = Vec::new();
    let mut seen: HashMap<(usize, usize), usize> = HashMap::new();
    for (i, t) in doc.tracks.iter().enumerate() {
        let name = t.name.as_deref().unwrap_or_default();
        let what = format!("tracks[{i}] ({name:?})");
        let times: Vec<f64> = t
            .keys
            .iter()
            .map(|k| match k.when {
                KeyTime::Seconds(s) | KeyTime::Frame(s) => s,
            })
            .collect();
        check_times(&times, &what)?;
        let rotations: Vec<DQuat> = t.keys.iter().map(|k| k.rot).collect();
        let k = ChannelKeys::of_track(&read, name, times.clone(), rotations).map_err(|e| {
            input_error(format!(
                "{what}: {} (its tracks: {})",
                crate::message(&e),
                names(&read)
            ))
        })?;
        if let Some(j) = seen.insert((k.animation, k.channel), i) {
            return Err(input_error(format!(
                "{what}: the same rotation channel as tracks[{j}]"
            )));
        }
        if !t.translations.is_empty() {
            let positions: Vec<DVec3> = t
                .translations
                .iter()
                .map(|p| p.unwrap_or(DVec3::NAN))
                .collect();
            vector_keys.push(translation_keys(
                &read, &k, times, positions, &what, source,
            )?);
        }
        keys.push(k);
    }
    keys.extend(vector_keys);
    let bytes = keys_asset(&read, &keys, container, Some(out_dir)).map_err(located)?;
    // Read back and each channel compared with its keys, as reduce does before writing.
    read_back(&read, &keys, &bytes, Some(out_dir)).map_err(crate::error)?;
    Ok(bytes)
}

/// The keys of the translation channel of the node of `rotation`'s channel, in its animation
/// (the first, as `read` takes it).
fn translation_keys(
    clip: &GltfClip,
    rotation: &ChannelKeys,
    times: Vec<f64>,
    positions: Vec<DVec3>,
    what: &str,
    source: &str,
) -> PyResult<ChannelKeys> {
    let anim = &clip.animations()[rotation.animation];
    let node = anim
        .rotations()
        .iter()
        .find(|c| c.index() == rotation.channel)
        .map(|c| (c.node(), c.node_name().to_string()));
    let channel = node
        .as_ref()
        .and_then(|(n, _)| anim.translations().iter().find(|c| c.node() == *n));
    let Some(channel) = channel else {
        let node = node.map_or_else(String::new, |(_, name)| format!(" node {name:?}"));
        return Err(input_error(format!(
            "{what} translations: {source}: animation {} has no translation channel for{node} \
             to write them into (glTF output rewrites channels, it adds none); pass None as \
             the track's translations",
            anim.label()
        )));
    };
    if let Some(k) = positions.iter().position(|p| !p.is_finite()) {
        return Err(input_error(format!(
            "{what} translations[{k}]: expected finite numbers, found {}",
            positions[k]
        )));
    }
    Ok(ChannelKeys {
        animation: rotation.animation,
        channel: channel.index(),
        times,
        values: Values::Vectors(positions),
    })
}

/// glTF key times: at least one, finite, not negative, strictly increasing as float32 (how
/// they are stored).
fn check_times(times: &[f64], what: &str) -> PyResult<()> {
    if times.is_empty() {
        return Err(input_error(format!("{what} times: no keys to write")));
    }
    for (k, &t) in times.iter().enumerate() {
        if !t.is_finite() || t < 0.0 {
            return Err(input_error(format!(
                "{what} times[{k}]: expected a finite time of at least 0 s (glTF key times), \
                 found {t}"
            )));
        }
        if k > 0 && t as f32 <= times[k - 1] as f32 {
            return Err(input_error(format!(
                "{what} times[{k}]: {} s and {t} s are the same float32 number: glTF stores \
                 key times as float32, strictly increasing",
                times[k - 1]
            )));
        }
    }
    Ok(())
}

/// The clip's track names, for a message (the first 20).
fn names(clip: &GltfClip) -> String {
    let all = clip.sources(Mode::Frames);
    let mut list: Vec<String> = all
        .iter()
        .take(20)
        .map(|s| format!("{:?}", inbetween::error::shorten(&s.name)))
        .collect();
    if all.len() > 20 {
        list.push(format!("… ({} in all)", all.len()));
    }
    list.join(", ")
}
