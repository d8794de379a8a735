//! Writing an asset back with resampled channels, everything else preserved.
//!
//! The JSON is edited as a `serde_json::Value` (so unknown extensions, `extras` and every
//! object this module does not understand are copied as they were). Appended:
//!
//! - per [`Resampled`] (one per processed animation for `interp`, one per channel for
//!   `reduce`), one float32 SCALAR time accessor with `min` and `max` (glTF 2.0
//!   §3.11 requires them on a sampler input), shared by its channels;
//! - per processed channel, one float32 output accessor — VEC4 unit quaternions (`x y z w`,
//!   sign-continuous: a quaternion whose dot product with the previous one is negative is
//!   written negated) or VEC3 translations or scales — and one new `LINEAR` sampler, to which
//!   the channel is repointed;
//! - the bytes of those accessors, each 4-byte aligned, in new buffer views.
//!
//! Then what no channel uses any more is removed (`prune`): the replaced samplers, and the
//! accessors, buffer views and buffers only they used, every index renumbered; a buffer whose
//! bytes are written here loses the bytes of its removed views (each remaining view keeps its
//! offset modulo 4). Objects the input already left unused stay.
//!
//! Where the bytes go depends on the output container:
//!
//! - `.glb`: appended to buffer 0, which becomes (or stays) the `BIN` chunk (§4.4.3). A `.gltf`
//!   input's buffer 0 (a `data:` URI or a file beside it) is embedded; other buffers keep their
//!   URIs.
//! - `.gltf`: a new buffer with a base64 `data:` URI holding only the new bytes; a `.glb`
//!   input's `BIN` buffer becomes a `data:` URI too (a `.gltf` cannot have a chunk).
//!
//! Buffers in files beside the input are never rewritten (their unused bytes stay). Relative
//! URIs (images, buffers that stay external) still name the input's files: written into another
//! folder ([`Asset::to_bytes_in`]), each is rewritten relative to that folder
//! (`../assets/skin.png`); `data:` URIs and absolute URIs are kept as they are.

use super::Asset;
use super::prune::{Removed, compact};
use base64::Engine;
use glam::{DQuat, DVec3, DVec4};
use gltf::animation::Property;
use inbetween::error::{Error, InputError, Setting};
use inbetween::message;
use serde_json::{Value, json};
use std::borrow::Cow;
use std::collections::HashSet;
use std::io::Write;
use std::path::Path;

/// The container of a glTF asset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContainerFormat {
    /// JSON text (`.gltf`).
    Gltf,
    /// Binary glTF (`.glb`, glTF 2.0 §4).
    Glb,
}

impl ContainerFormat {
    /// From a file extension: `.gltf` or `.glb` (case-insensitive).
    pub fn from_path(path: &Path) -> Option<ContainerFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "gltf" => Some(ContainerFormat::Gltf),
            "glb" => Some(ContainerFormat::Glb),
            _ => None,
        }
    }
}

/// New keys for channels of one animation, all on one time grid. An animation may have several
/// (each with its own grid: `reduce` keeps other keys on each channel); a channel is replaced
/// once.
#[derive(Debug, Clone, PartialEq)]
pub struct Resampled {
    /// The animation's index in the asset.
    pub animation: usize,
    /// The frame times in seconds; they must stay strictly increasing when rounded to float32.
    pub times: Vec<f64>,
    /// `(channel index in the animation, one value per time)` for each channel to replace:
    /// rotations for a channel targeting a `rotation`, vectors for a `translation` or `scale`.
    pub channels: Vec<(usize, Values)>,
}

/// The new values of one channel, one per frame time, played by the `LINEAR` sampler written
/// for them (slerp for rotations, lerp for vectors: glTF 2.0 Appendix C).
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Rotations; they need not be unit or sign-continuous: they are written normalised and
    /// sign-continuous (each negated when its dot product with the previous one is negative).
    Rotations(Vec<DQuat>),
    /// Translations or scales.
    Vectors(Vec<DVec3>),
}

impl Values {
    fn len(&self) -> usize {
        match self {
            Values::Rotations(q) => q.len(),
            Values::Vectors(v) => v.len(),
        }
    }

    fn fits(&self, property: Property) -> bool {
        match self {
            Values::Rotations(_) => property == Property::Rotation,
            Values::Vectors(_) => matches!(property, Property::Translation | Property::Scale),
        }
    }

    fn what(&self) -> &'static str {
        match self {
            Values::Rotations(_) => "a rotation",
            Values::Vectors(_) => "a translation or scale",
        }
    }

    fn noun(&self) -> &'static str {
        match self {
            Values::Rotations(_) => "rotation",
            Values::Vectors(_) => "vector",
        }
    }

    fn expected(&self) -> &'static str {
        match self {
            Values::Rotations(_) => "a finite non-zero quaternion",
            Values::Vectors(_) => "a finite vector",
        }
    }

    fn show(&self, k: usize) -> String {
        match self {
            Values::Rotations(q) => format!("{:?}", q[k]),
            Values::Vectors(v) => format!("{:?}", v[k]),
        }
    }

    /// The float32 components as written and the accessor type; `Err(k)` for the first value
    /// that cannot be written.
    fn floats(&self) -> Result<(Vec<f32>, &'static str), usize> {
        match self {
            Values::Rotations(q) => {
                let unit = continuous_unit(q)?;
                let floats = unit.iter().flat_map(|v| v.to_array().map(|x| x as f32));
                Ok((floats.collect(), "VEC4"))
            }
            Values::Vectors(v) => {
                let floats: Vec<f32> = v
                    .iter()
                    .flat_map(|p| p.to_array().map(|x| x as f32))
                    .collect();
                match floats.iter().position(|x| !x.is_finite()) {
                    Some(i) => Err(i / 3),
                    None => Ok((floats, "VEC3")),
                }
            }
        }
    }
}

/// `times` as float32, checked finite and strictly increasing (a sampler input, glTF 2.0
/// §3.11).
fn float32_times(src: &str, a: usize, times64: &[f64]) -> Result<Vec<f32>, InputError> {
    let times: Vec<f32> = times64.iter().map(|&t| t as f32).collect();
    if times.is_empty() {
        return Err(input_err!("{src}: animation {a}: no frame times to write"));
    }
    for (k, (&t, &t64)) in times.iter().zip(times64).enumerate() {
        if !t.is_finite() {
            return Err(input_err!(
                "{src}: animation {a}: frame time {k} is {}: expected a finite float32",
                inbetween::error::num(t64)
            ));
        }
        if k > 0 && t <= times[k - 1] {
            return Err(input_err!(
                "{src}: animation {a}: frame times {} and {} s are the same float32: \
                 expected strictly increasing float32 times",
                k - 1,
                k
            ));
        }
    }
    Ok(times)
}

/// The new accessors, views and bytes, before they are placed in a buffer.
#[derive(Default)]
struct Appended {
    bytes: Vec<u8>,
    /// `(offset in bytes, length)` of each new view, relative to the start of the new bytes.
    views: Vec<(usize, usize)>,
}

impl Appended {
    /// Adds `data` as a new view (4-byte aligned); returns the view's number among the new ones.
    fn push(&mut self, data: &[u8]) -> usize {
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        self.views.push((self.bytes.len(), data.len()));
        self.bytes.extend_from_slice(data);
        self.views.len() - 1
    }
}

fn f32_bytes(xs: impl IntoIterator<Item = f32>) -> Vec<u8> {
    xs.into_iter().flat_map(f32::to_le_bytes).collect()
}

fn pad4(v: &mut Vec<u8>, byte: u8) {
    while !v.len().is_multiple_of(4) {
        v.push(byte);
    }
}

/// Whether `uri` is a relative reference (RFC 3986 §4.2) naming a file: not a `data:` URI, no
/// scheme, not an absolute path.
fn is_relative_reference(uri: &str) -> bool {
    let scheme = uri.split_once(':').is_some_and(|(s, _)| {
        s.starts_with(|c: char| c.is_ascii_alphabetic())
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    });
    !scheme && !uri.starts_with('/') && !uri.starts_with('\\')
}

/// Whether `out_dir` and `base_dir` are one folder (or either cannot be resolved).
fn same_folder(out_dir: &Path, base_dir: &Path) -> bool {
    match (
        std::fs::canonicalize(out_dir),
        std::fs::canonicalize(base_dir),
    ) {
        (Ok(o), Ok(b)) => o == b,
        _ => true,
    }
}

/// A base64 `data:` URI of `bytes` with media type `mime`.
fn data_uri(mime: &str, bytes: &[u8]) -> String {
    format!(
        "data:{mime};base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// The media type of an image: its `mimeType` when given, else from its first bytes (PNG,
/// JPEG, WebP, KTX2), else `application/octet-stream`.
fn image_mime(declared: Option<&str>, bytes: &[u8]) -> String {
    if let Some(m) = declared {
        return m.to_string();
    }
    let m = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        "image/png"
    } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        "image/jpeg"
    } else if bytes.len() >= 12 && &bytes[..4] == b"RIFF" && &bytes[8..12] == b"WEBP" {
        "image/webp"
    } else if bytes.starts_with(b"\xabKTX 20\xbb") {
        "image/ktx2"
    } else {
        "application/octet-stream"
    };
    m.to_string()
}

fn array_mut<'v>(obj: &'v mut Value, key: &str) -> &'v mut Vec<Value> {
    let map = obj.as_object_mut().expect("a glTF object");
    let entry = map.entry(key).or_insert_with(|| Value::Array(Vec::new()));
    if !entry.is_array() {
        *entry = Value::Array(Vec::new());
    }
    entry.as_array_mut().expect("an array")
}

impl Asset {
    /// Replaces, in `json`, every relative URI of `buffers` (with the bytes read) and of
    /// `images` that exist (read under the same rules as buffer files, within what is left of
    /// the byte budget) with a `data:` URI, for an asset written into another folder than
    /// `base`: the output then references no file outside its own folder. A missing image
    /// keeps its URI.
    fn embed_files(&self, json: &mut Value, base: &Path) -> Result<(), InputError> {
        let src = &self.source;
        if let Some(buffers) = json.get_mut("buffers").and_then(Value::as_array_mut) {
            for (i, b) in buffers.iter_mut().enumerate() {
                if b.get("uri")
                    .and_then(Value::as_str)
                    .is_some_and(is_relative_reference)
                {
                    b["uri"] = json!(data_uri("application/octet-stream", self.buffer(i)));
                }
            }
        }
        let mut used = self.bytes_read;
        if let Some(images) = json.get_mut("images").and_then(Value::as_array_mut) {
            for (i, image) in images.iter_mut().enumerate() {
                let Some(uri) = image.get("uri").and_then(Value::as_str) else {
                    continue;
                };
                if !is_relative_reference(uri) {
                    continue;
                }
                let at = |e: String| {
                    input_err!(
                        "{src}: images[{i}].uri (\"{}\"): {e}",
                        inbetween::error::shorten(uri)
                    )
                };
                let rel = super::accessor::relative_path(uri).map_err(at)?;
                if std::fs::symlink_metadata(base.join(rel)).is_err() {
                    continue;
                }
                let path = super::accessor::resolve(uri, base).map_err(at)?;
                let left = self.max_bytes.saturating_sub(used);
                let bytes = super::accessor::read_file(&path, left.saturating_add(1) as usize)
                    .map_err(at)?;
                if bytes.len() as u64 > left {
                    return Err(InputError::new(message![
                        format!(
                            "embedding it would take the input past {} bytes (",
                            self.max_bytes
                        ),
                        Setting::MaxInputBytes,
                        ")"
                    ])
                    .at_setting(format!(
                        "{src}: images[{i}].uri (\"{}\")",
                        inbetween::error::shorten(uri)
                    )));
                }
                used += bytes.len() as u64;
                let mime = image_mime(image.get("mimeType").and_then(Value::as_str), &bytes);
                image["uri"] = json!(data_uri(&mime, &bytes));
            }
        }
        Ok(())
    }

    /// Puts the bytes of the buffers that are written inline (a `.glb`'s buffer 0, `data:`
    /// URIs, a `.gltf` output's buffers without a URI) and the `new` bytes where `format` keeps
    /// them, each such buffer that lost a view compacted ([`compact`]), and points the new views
    /// (buffer `null`) at the new bytes; returns a `.glb`'s `BIN` chunk.
    fn place(
        &self,
        json: &mut Value,
        removed: &Removed,
        new: &[u8],
        format: ContainerFormat,
    ) -> Option<Vec<u8>> {
        let kept = &removed.buffers_kept;
        let glb = format == ContainerFormat::Glb;
        for (i, &old) in kept.iter().enumerate().skip(usize::from(glb)) {
            let uri = json["buffers"][i].get("uri").and_then(Value::as_str);
            let has_uri = uri.is_some();
            let mime = match uri {
                None => "application/octet-stream".to_string(),
                Some(u) if u.starts_with("data:") => {
                    let m = u["data:".len()..]
                        .split([';', ','])
                        .next()
                        .unwrap_or_default();
                    if m.is_empty() {
                        "application/octet-stream"
                    } else {
                        m
                    }
                    .to_string()
                }
                Some(_) => continue,
            };
            let mut bytes = Cow::Borrowed(self.buffer(old));
            let compacted = removed.views_in.contains(&old)
                && compact(json, i, &bytes)
                    .map(|c| bytes = Cow::Owned(c))
                    .is_some();
            if compacted || !has_uri {
                let b = &mut json["buffers"][i];
                b["uri"] = json!(data_uri(&mime, &bytes));
                b["byteLength"] = json!(bytes.len());
            }
        }
        let (target, base, bin) = if glb {
            let mut bin = if kept.first() == Some(&0) {
                let bin = self.buffer(0);
                match removed.views_in.contains(&0) {
                    true => compact(json, 0, bin).unwrap_or_else(|| bin.to_vec()),
                    false => bin.to_vec(),
                }
            } else {
                Vec::new()
            };
            pad4(&mut bin, 0);
            let base = bin.len();
            bin.extend_from_slice(new);
            let buffers = array_mut(json, "buffers");
            if buffers.is_empty() {
                buffers.push(json!({}));
            }
            let b0 = buffers[0].as_object_mut().expect("buffer object");
            b0.remove("uri");
            b0.insert("byteLength".into(), json!(bin.len()));
            (0, base, Some(bin))
        } else {
            let buffers = array_mut(json, "buffers");
            if !new.is_empty() {
                let uri = data_uri("application/octet-stream", new);
                buffers.push(json!({"byteLength": new.len(), "uri": uri}));
            }
            (buffers.len().saturating_sub(1), 0, None)
        };
        for view in array_mut(json, "bufferViews") {
            if view.get("buffer").is_some_and(Value::is_null) {
                let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
                view["buffer"] = json!(target);
                view["byteOffset"] = json!(base + offset);
            }
        }
        bin
    }

    /// Writes the asset with the channels of `resampled` replaced, as `format`, to
    /// `out` (see the module documentation for what is appended, removed and where). Errors: an
    /// input error for a bad request (an unknown animation or channel, values of another kind
    /// than the channel's target, a channel named twice, counts that disagree, times not
    /// strictly increasing in float32, a rotation that is not finite and non-zero or a vector
    /// that is not finite, a `.glb` over 4 GiB); an I/O error from `out`.
    pub fn write(
        &self,
        resampled: &[Resampled],
        format: ContainerFormat,
        out: &mut dyn Write,
    ) -> Result<(), Error> {
        let bytes = self.to_bytes(resampled, format)?;
        out.write_all(&bytes)?;
        Ok(())
    }

    /// The bytes [`Asset::write`] writes: relative URIs unchanged, for a file beside the input.
    pub fn to_bytes(
        &self,
        resampled: &[Resampled],
        format: ContainerFormat,
    ) -> Result<Vec<u8>, InputError> {
        self.to_bytes_in(resampled, format, None)
    }

    /// The bytes of the asset written into the folder `out_dir`: as [`Asset::to_bytes`], with
    /// every relative URI of `buffers` and `images` rewritten to name, from `out_dir`, the file
    /// it named beside the input (unchanged when the folders are the same, when either cannot
    /// be resolved, or when the asset was read from bytes alone).
    pub fn to_bytes_in(
        &self,
        resampled: &[Resampled],
        format: ContainerFormat,
        out_dir: Option<&Path>,
    ) -> Result<Vec<u8>, InputError> {
        let src = &self.source;
        let mut json = self.json.clone();
        if let (Some(out), Some(base)) = (out_dir, self.base_dir.as_deref())
            && !same_folder(out, base)
        {
            self.embed_files(&mut json, base)?;
        }
        let before = json.clone();
        let mut new = Appended::default();
        // New accessors as (new view number, accessor JSON without bufferView).
        let mut accessors: Vec<(usize, Value)> = Vec::new();
        // (animation, channel, input, output): the new samplers, accessors numbered among the new.
        let mut samplers: Vec<(usize, usize, usize, usize)> = Vec::new();
        // A channel may be replaced once; an animation may have several time grids (one
        // `Resampled` each: reduced keys differ from channel to channel).
        let mut seen_channels = HashSet::new();
        let animations: Vec<_> = self.document.animations().collect();
        for r in resampled {
            let a = r.animation;
            let Some(anim) = animations.get(a) else {
                return Err(input_err!(
                    "{src}: no animation {a} to replace (the asset has {})",
                    animations.len()
                ));
            };
            let times = float32_times(src, a, &r.times)?;
            let time_view = new.push(&f32_bytes(times.iter().copied()));
            let time_acc = accessors.len();
            accessors.push((
                time_view,
                json!({
                    "componentType": 5126,
                    "count": times.len(),
                    "type": "SCALAR",
                    "min": [f64::from(times[0])],
                    "max": [f64::from(times[times.len() - 1])],
                }),
            ));
            let channels: Vec<_> = anim.channels().collect();
            for (c, values) in &r.channels {
                let c = *c;
                let Some(ch) = self.typed_channel(a, c).and_then(|t| channels.get(t)) else {
                    return Err(input_err!(
                        "{src}: animation {a}: no channel {c} that is read (it has {})",
                        channels.len()
                    ));
                };
                let property = ch.target().property();
                if !values.fits(property) {
                    return Err(input_err!(
                        "{src}: animation {a}: channel {c} targets {property:?}, not {}",
                        values.what()
                    ));
                }
                if !seen_channels.insert((a, c)) {
                    return Err(input_err!(
                        "{src}: animation {a}: channel {c} is resampled twice"
                    ));
                }
                if values.len() != times.len() {
                    return Err(input_err!(
                        "{src}: animation {a}: channel {c}: {} {}s for {} frame times",
                        values.len(),
                        values.noun(),
                        times.len()
                    ));
                }
                let (floats, kind) = values.floats().map_err(|k| {
                    input_err!(
                        "{src}: animation {a}: channel {c}: {} {k} is {}: expected {}",
                        values.noun(),
                        values.show(k),
                        values.expected()
                    )
                })?;
                let view = new.push(&f32_bytes(floats));
                let out_acc = accessors.len();
                accessors.push((
                    view,
                    json!({"componentType": 5126, "count": times.len(), "type": kind}),
                ));
                samplers.push((a, c, time_acc, out_acc));
            }
        }

        // The new views (their buffer set once the bytes are placed), accessors and samplers,
        // each processed channel repointed; then what no channel uses any more is removed.
        let first_view = array_mut(&mut json, "bufferViews").len();
        let first_acc = array_mut(&mut json, "accessors").len();
        let views = array_mut(&mut json, "bufferViews");
        for &(offset, len) in &new.views {
            views.push(json!({"buffer": null, "byteOffset": offset, "byteLength": len}));
        }
        let accs = array_mut(&mut json, "accessors");
        for (view, mut acc) in accessors {
            acc["bufferView"] = json!(first_view + view);
            accs.push(acc);
        }
        let anims = array_mut(&mut json, "animations");
        for (a, c, input, output) in samplers {
            let anim = &mut anims[a];
            let list = array_mut(anim, "samplers");
            list.push(json!({
                "input": first_acc + input,
                "interpolation": "LINEAR",
                "output": first_acc + output,
            }));
            let sampler = list.len() - 1;
            array_mut(anim, "channels")[c]["sampler"] = json!(sampler);
        }
        let removed = super::prune::prune(&before, &mut json, format == ContainerFormat::Glb);
        let bin = self.place(&mut json, &removed, &new.bytes, format);

        match format {
            ContainerFormat::Gltf => {
                let mut text = serde_json::to_vec_pretty(&json)
                    .map_err(|e| input_err!("{src}: cannot serialise the JSON: {e}"))?;
                text.push(b'\n');
                Ok(text)
            }
            ContainerFormat::Glb => {
                let mut text = serde_json::to_vec(&json)
                    .map_err(|e| input_err!("{src}: cannot serialise the JSON: {e}"))?;
                pad4(&mut text, b' ');
                let mut bin = bin.unwrap_or_default();
                pad4(&mut bin, 0);
                let total = 12 + 8 + text.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
                let total = u32::try_from(total).map_err(|_| {
                    input_err!("{src}: the output is {total} bytes, over the 4 GiB a .glb can hold")
                })?;
                let mut out = Vec::with_capacity(total as usize);
                out.extend_from_slice(b"glTF");
                out.extend_from_slice(&2u32.to_le_bytes());
                out.extend_from_slice(&total.to_le_bytes());
                out.extend_from_slice(&(text.len() as u32).to_le_bytes());
                out.extend_from_slice(b"JSON");
                out.extend_from_slice(&text);
                if !bin.is_empty() {
                    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
                    out.extend_from_slice(b"BIN\0");
                    out.extend_from_slice(&bin);
                }
                Ok(out)
            }
        }
    }
}

/// `qs` normalised, each negated when its dot product with the previous written one is
/// negative; `Err(k)` for the first that is not finite or has zero length.
fn continuous_unit(qs: &[DQuat]) -> Result<Vec<DVec4>, usize> {
    let mut out: Vec<DVec4> = Vec::with_capacity(qs.len());
    for (k, &q) in qs.iter().enumerate() {
        let v = DVec4::from(q);
        let len = v.length();
        if !len.is_finite() || len == 0.0 {
            return Err(k);
        }
        let mut u = v / len;
        if out.last().is_some_and(|p| p.dot(u) < 0.0) {
            u = -u;
        }
        out.push(u);
    }
    Ok(out)
}

#[cfg(test)]
mod uri_tests {
    use super::{image_mime, is_relative_reference};

    #[test]
    fn relative_references_are_files_without_a_scheme() {
        for uri in ["a.bin", "tex/skin%20a.png", "../b.bin", "c:d.png"] {
            assert_eq!(is_relative_reference(uri), uri != "c:d.png", "{uri}");
        }
        for uri in [
            "data:application/octet-stream;base64,AA==",
            "https://x/y.png",
            "/abs/y.bin",
        ] {
            assert!(!is_relative_reference(uri), "{uri}");
        }
    }

    #[test]
    fn image_media_types() {
        assert_eq!(image_mime(Some("image/x"), b""), "image/x");
        assert_eq!(image_mime(None, b"\x89PNG\r\n\x1a\nrest"), "image/png");
        assert_eq!(image_mime(None, &[0xFF, 0xD8, 0xFF, 0xE0]), "image/jpeg");
        assert_eq!(image_mime(None, b"RIFF\0\0\0\0WEBPVP8 "), "image/webp");
        assert_eq!(image_mime(None, b"GIF89a"), "application/octet-stream");
    }
}
