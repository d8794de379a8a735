//! glTF 2.0 animations: the rotation and translation channels of an asset (`.gltf` with
//! embedded `data:` buffers or files beside it, or `.glb`), their samplers evaluated as the
//! specification defines them, and the asset written back with resampled rotation channels.
//!
//! References are to the glTF 2.0 specification (Khronos, version 2.0.1): §3.6 *Binary Data
//! Storage* (buffers, buffer views, accessors, sparse accessors), §3.11 *Animations* (samplers,
//! channels, the output accessor types and the normalized-integer equations), §4 *GLB File
//! Format*, and Appendix C *Interpolation* (STEP, LINEAR with slerp for rotations,
//! CUBICSPLINE).
//!
//! The asset is untrusted. The JSON is parsed once with every key checked unique, channels
//! this module does not process are set aside (`json.rs`); the `gltf` crate parses and
//! validates the rest (every index and enum it checks), and what it leaves unchecked is checked
//! here (channel targets); buffer URIs are resolved inside the asset's folder only, and
//! accessors decoded with every byte range checked and every allocation bounded by the bytes
//! that back it (`accessor.rs`), so that a damaged or hostile file is an [`InputError`] naming
//! the file and the JSON path (`animations[0].channels[2]`, `accessors[4].count`), never a
//! panic, a read outside the folder or an unbounded allocation. Writing ([`Asset::write`]) works on the JSON as a `serde_json::Value`, so
//! whatever the `gltf` crate does not model (unknown extensions, `extras`) survives untouched.
//!
//! - [`document`]: the chosen animations' rotation channels as a keyframe document (tracks),
//!   keys snapped to a frame rate, `STEP`/`CUBICSPLINE` channels baked for interpolation.
//! - [`frames`]: interp's frames written back into the asset ([`frames::GltfFrames`]).
//! - [`keys`]: reduce's kept keys written back into the asset ([`keys::keys_asset`]).
//!
//! ```
//! use inbetween_io::gltf::{Asset, Interpolation};
//!
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/gltf/minimal_linear.gltf");
//! let asset = Asset::read_path(path.as_ref())?;
//! let animations = asset.animations()?;
//! let channel = &animations[0].rotations()[0];
//! assert_eq!(channel.interpolation(), Interpolation::Linear);
//! assert_eq!(channel.node_name(), "node0");
//! let q = channel.sample(0.25); // a unit DQuat, x y z w
//! # assert!((q.length() - 1.0).abs() < 1e-12);
//! # Ok::<(), inbetween::InputError>(())
//! ```

mod accessor;
mod channel;
pub mod document;
pub mod frames;
mod json;
pub mod keys;
mod prune;
mod warnings;
mod write;

pub(crate) use channel::snap_key_time;
pub use channel::{Channel, Interpolation, RotationChannel, TranslationChannel};
pub(crate) use json::has_asset_member;
pub use write::{ContainerFormat, Resampled, Values};

use accessor::Storage;
use glam::{DQuat, DVec3};
use gltf::accessor::Dimensions;
use gltf::animation::Property;
use inbetween::error::{InputError, InputResult, Setting, shorten};
use inbetween::message;
use std::path::{Path, PathBuf};

/// A glTF 2.0 asset as read: its document (parsed and validated), the bytes of its buffers, and
/// the JSON as written (for [`Asset::write`]).
#[derive(Debug)]
pub struct Asset {
    source: String,
    document: gltf::Document,
    json: serde_json::Value,
    buffers: Vec<Vec<u8>>,
    container: ContainerFormat,
    /// The folder relative URIs were resolved against (`None`: read from bytes alone).
    base_dir: Option<PathBuf>,
    /// Per animation, the JSON index of each channel of `document` (channels this crate does
    /// not process are left out of it).
    channel_index: Vec<Vec<usize>>,
    /// The files beside the asset it references (buffers read, images that exist), canonical.
    files: Vec<PathBuf>,
    /// Findings of reading (channels ignored), one message each.
    warnings: Vec<String>,
    /// The byte budget ([`Asset::from_slice_limited`]) and what reading took of it.
    max_bytes: u64,
    bytes_read: u64,
}

/// One animation of an asset: its rotation, translation and scale channels (morph-weight
/// channels are not read).
#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    index: usize,
    name: Option<String>,
    rotations: Vec<RotationChannel>,
    translations: Vec<TranslationChannel>,
    scales: Vec<TranslationChannel>,
    span: Option<(f64, f64)>,
    warnings: Vec<(String, String)>,
}

impl Animation {
    /// Its index in the asset's `animations`.
    pub fn index(&self) -> usize {
        self.index
    }

    /// Its name, if it has one.
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// The name, or the index as text when it has none (`"0"`): what `--animation` matches.
    pub fn label(&self) -> String {
        self.name.clone().unwrap_or_else(|| self.index.to_string())
    }

    /// The channels targeting a node's `rotation`, in channel order.
    pub fn rotations(&self) -> &[RotationChannel] {
        &self.rotations
    }

    /// The channels targeting a node's `translation`, in channel order.
    pub fn translations(&self) -> &[TranslationChannel] {
        &self.translations
    }

    /// The channels targeting a node's `scale`, in channel order (VEC3 float channels, read
    /// and sampled as translations are).
    pub fn scales(&self) -> &[TranslationChannel] {
        &self.scales
    }

    /// The earliest and latest input time of all the animation's samplers (every sampler, not
    /// only the rotation and translation ones), or `None` when it has no samplers.
    pub fn span(&self) -> Option<(f64, f64)> {
        self.span
    }

    /// Findings of reading its channels (rotations whose norm is off 1 and were normalised,
    /// keys whose signs flip), one per channel: where (the file, animation and channel) and
    /// what (the accessor and key).
    pub fn warnings(&self) -> &[(String, String)] {
        &self.warnings
    }
}

impl Asset {
    /// Reads a `.gltf` or `.glb` file (the container is recognised by its first bytes, not its
    /// name); external buffers are looked up beside it. The file and its external buffers
    /// together may take at most [`crate::DEFAULT_MAX_INPUT_BYTES`] bytes.
    pub fn read_path(path: &Path) -> InputResult<Asset> {
        let limit = crate::DEFAULT_MAX_INPUT_BYTES;
        let bytes = crate::read_bytes_limited(path, limit)?;
        let dir = crate::gltf_dir(path);
        Self::from_slice_limited(&bytes, &path.display().to_string(), Some(&dir), limit)
    }

    /// Parses an asset from its bytes (`.gltf` JSON or `.glb`), with at most
    /// [`crate::DEFAULT_MAX_INPUT_BYTES`] bytes in all ([`Asset::from_slice_limited`]).
    pub fn from_slice(bytes: &[u8], source: &str, base_dir: Option<&Path>) -> InputResult<Asset> {
        Self::from_slice_limited(bytes, source, base_dir, crate::DEFAULT_MAX_INPUT_BYTES)
    }

    /// Parses an asset from its bytes (`.gltf` JSON or `.glb`). `source` names it in messages;
    /// `base_dir` is where files named by relative URIs are found (`None`: such a buffer is an
    /// error). `max_bytes` bounds the asset's bytes and its external buffers' together.
    ///
    /// A URI is untrusted: percent-decoded, then accepted only as a relative path that stays
    /// inside `base_dir` once symbolic links are resolved, naming a regular file (not a
    /// device, a FIFO or a directory), of which `byteLength` bytes are read (a shorter file is
    /// an error). Image URIs are checked the same way (a missing image is allowed: it is never
    /// read). A channel this crate does not process (a `KHR_animation_pointer` channel, a path
    /// other than the four of glTF 2.0, a target without a node) is ignored, with one warning
    /// for the asset ([`Asset::warnings`]). Refused, each with its JSON path: duplicate keys in
    /// the JSON, a channel whose node does not exist, two channels of one animation on one node
    /// and path, a buffer other than the first referring to the GLB `BIN` chunk, and whatever
    /// the `gltf` crate's validation refuses.
    pub fn from_slice_limited(
        bytes: &[u8],
        source: &str,
        base_dir: Option<&Path>,
        max_bytes: u64,
    ) -> InputResult<Asset> {
        let fail = |m: String| InputError::new(m).at(source);
        if bytes.len() as u64 > max_bytes {
            return Err(InputError::new(message![
                format!("input larger than {max_bytes} bytes ("),
                Setting::MaxInputBytes,
                ")"
            ])
            .at(source));
        }
        let (json_bytes, blob, container) = if bytes.starts_with(b"glTF") {
            let glb = gltf::Glb::from_slice(bytes)
                .map_err(|e| fail(format!("invalid GLB container: {e}")))?;
            (
                glb.json.into_owned(),
                glb.bin.map(|b| b.into_owned()),
                ContainerFormat::Glb,
            )
        } else {
            (bytes.to_vec(), None, ContainerFormat::Gltf)
        };
        let parsed = json::parse(&json_bytes).map_err(fail)?;
        validate(&parsed.root).map_err(fail)?;
        validate_channels(&parsed.root, &parsed.channels).map_err(fail)?;
        let mut files = check_images(&parsed.json, base_dir).map_err(fail)?;
        let document = gltf::Document::from_json_without_validation(parsed.root);
        let mut sources = accessor::Sources {
            blob: blob.as_deref(),
            base_dir,
            limit: max_bytes,
            used: bytes.len() as u64,
        };
        let loaded = accessor::load_buffers(&document, &mut sources)
            .map_err(|m| InputError::new(m).at(source))?;
        files.extend(loaded.files);
        let mut warnings = Vec::new();
        if let Some((a, c, what)) = parsed.ignored.first() {
            let more = match parsed.ignored.len() {
                1 => String::new(),
                n => format!(" and {} more", n - 1),
            };
            warnings.push(format!(
                "{source}: animations[{a}].channels[{c}] ({what}){more}: ignored, as only \
                 channels on a node's rotation, translation, scale or weights are read"
            ));
        }
        Ok(Asset {
            source: source.to_string(),
            document,
            json: parsed.json,
            buffers: loaded.buffers,
            container,
            base_dir: base_dir.map(Path::to_path_buf),
            channel_index: parsed.channels,
            files,
            warnings,
            max_bytes,
            bytes_read: sources.used,
        })
    }

    /// Findings of reading the asset (channels ignored), each a message naming the file.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The files beside the asset that it references and that were found (the external
    /// buffers read, the images that exist), as canonical paths: what an output must not
    /// replace.
    pub fn referenced_files(&self) -> &[PathBuf] {
        &self.files
    }

    /// The JSON index of channel `typed` (an index among the document's channels) of
    /// animation `a`.
    fn json_channel(&self, a: usize, typed: usize) -> usize {
        self.channel_index
            .get(a)
            .and_then(|c| c.get(typed))
            .copied()
            .unwrap_or(typed)
    }

    /// The document's channel of animation `a` that is channel `json` in the JSON, if it was
    /// read.
    pub(super) fn typed_channel(&self, a: usize, json: usize) -> Option<usize> {
        self.channel_index.get(a)?.iter().position(|&c| c == json)
    }

    /// The name the asset has in messages.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The folder its relative URIs were resolved in (`None`: read from bytes alone).
    pub fn base_dir(&self) -> Option<&Path> {
        self.base_dir.as_deref()
    }

    /// Whether it was read from a `.glb` container or `.gltf` JSON.
    pub fn container(&self) -> ContainerFormat {
        self.container
    }

    /// The parsed document (`gltf` crate), for anything this module does not read.
    pub fn document(&self) -> &gltf::Document {
        &self.document
    }

    /// Every animation with its rotation and translation channels, read and checked: a
    /// sampler's input accessor is FLOAT SCALAR, finite and strictly increasing (glTF 2.0
    /// §3.11); its output has as many elements (three times as many for `CUBICSPLINE`, which
    /// needs at least two keys) of VEC4 FLOAT or normalized integers for a rotation, VEC3 FLOAT
    /// for a translation or a scale; every value is finite, and a rotation value (a `CUBICSPLINE` vertex
    /// too) has non-zero length. The first problem is an error naming the file, animation,
    /// channel and accessor.
    pub fn animations(&self) -> InputResult<Vec<Animation>> {
        self.document
            .animations()
            .map(|a| self.read_animation(&a))
            .collect()
    }

    fn read_animation(&self, anim: &gltf::Animation) -> InputResult<Animation> {
        let a = anim.index();
        let name = anim.name().map(str::to_string);
        let named = name
            .as_deref()
            .map(|n| format!(" (animation \"{}\")", shorten(n)))
            .unwrap_or_default();
        let mut span: Option<(f64, f64)> = None;
        for sampler in anim.samplers() {
            let at = |m: String| {
                input_err!(
                    "{}: animations[{a}].samplers[{}].input{named}: {m}",
                    self.source,
                    sampler.index()
                )
            };
            let (_, times) = self.times(&sampler.input()).map_err(at)?;
            if let (Some(&a), Some(&b)) = (times.first(), times.last()) {
                span = Some(span.map_or((a, b), |(x, y)| (x.min(a), y.max(b))));
            }
        }
        let mut rotations = Vec::new();
        let mut translations = Vec::new();
        let mut scales = Vec::new();
        let mut warnings = Vec::new();
        for ch in anim.channels() {
            let c = self.json_channel(a, ch.index());
            let node = ch.target().node();
            let label = match node.name() {
                Some(n) if name.is_some() => format!(
                    "animations[{a}].channels[{c}] (animation \"{}\", node \"{}\")",
                    shorten(name.as_deref().unwrap_or_default()),
                    shorten(n)
                ),
                Some(n) => format!("animations[{a}].channels[{c}] (node \"{}\")", shorten(n)),
                None => format!("animations[{a}].channels[{c}]{named}"),
            };
            let at = |m: String| input_err!("{}: {label}: {m}", self.source);
            match ch.target().property() {
                Property::Rotation => {
                    let (channel, warning) =
                        self.read_channel(&ch, c, ROTATION_KIND).map_err(at)?;
                    if let Some(w) = warning {
                        warnings.push((format!("{}: {label}", self.source), w));
                    }
                    if let Some(w) = channel::sign_flip_warning(&channel) {
                        warnings.push((format!("{}: {label}", self.source), w));
                    }
                    rotations.push(channel);
                }
                Property::Translation => {
                    let (channel, _) = self.read_channel(&ch, c, TRANSLATION_KIND).map_err(at)?;
                    translations.push(channel);
                }
                Property::Scale => {
                    let (channel, _) = self.read_channel(&ch, c, TRANSLATION_KIND).map_err(at)?;
                    scales.push(channel);
                }
                Property::MorphTargetWeights => {}
            }
        }
        Ok(Animation {
            index: a,
            name,
            rotations,
            translations,
            scales,
            span,
            warnings,
        })
    }

    /// A sampler's input: the float32 times and the same widened, checked. Messages start
    /// with the accessor (`accessors[0]: time 2 is …`).
    fn times(&self, acc: &gltf::Accessor) -> Result<(Vec<f32>, Vec<f64>), String> {
        let i = acc.index();
        // Elements no buffer view backs are zeros: more than one is not strictly increasing,
        // so an unbacked count is refused before anything is allocated for it.
        if acc.view().is_none() {
            let sparse = acc.sparse().map_or(0, |s| s.count());
            if acc.count() > sparse.saturating_add(1) {
                return Err(format!(
                    "accessors[{i}].count: {} times with no bufferView and {sparse} sparse \
                     values: the others are all 0, not strictly increasing",
                    acc.count()
                ));
            }
        }
        let times = accessor::read(acc, &self.buffers, Dimensions::Scalar, Storage::Float)?;
        if times.is_empty() {
            return Err(format!("accessors[{i}]: no key times"));
        }
        for (k, &t) in times.iter().enumerate() {
            if !t.is_finite() {
                return Err(format!(
                    "accessors[{i}]: time {k} is {}: expected a finite number",
                    non_finite(t)
                ));
            }
            if k > 0 && t <= times[k - 1] {
                return Err(format!(
                    "accessors[{i}]: time {k} is {} after {}: expected strictly increasing times",
                    inbetween::error::num(t),
                    inbetween::error::num(times[k - 1])
                ));
            }
        }
        // Exact: every value came from a float32.
        Ok((times.iter().map(|&t| t as f32).collect(), times))
    }

    /// Channel `ch` (channel `c` in the JSON) read as `kind`, and for a rotation a warning
    /// when a value's norm is off 1 by more than the tolerance (it is normalised when used).
    fn read_channel<T: Copy>(
        &self,
        ch: &gltf::animation::Channel,
        c: usize,
        kind: Kind<T>,
    ) -> Result<(Channel<T>, Option<String>), String> {
        let sampler = ch.sampler();
        let interpolation = match sampler.interpolation() {
            gltf::animation::Interpolation::Linear => Interpolation::Linear,
            gltf::animation::Interpolation::Step => Interpolation::Step,
            gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
        };
        let s = sampler.index();
        let input = sampler.input();
        let (times_f32, times) = self
            .times(&input)
            .map_err(|e| format!("samplers[{s}].input: {e}"))?;
        let out = sampler.output();
        let o = out.index();
        let n = kind.dims.multiplicity();
        let per_key = if interpolation == Interpolation::CubicSpline {
            3
        } else {
            1
        };
        let keys = times.len();
        if interpolation == Interpolation::CubicSpline && keys < 2 {
            return Err(format!(
                "samplers[{s}].input: accessors[{}]: CUBICSPLINE needs at least 2 keys, found 1",
                input.index()
            ));
        }
        // Checked before the output is read: its size is then bounded by the input's.
        if out.count() != keys * per_key {
            return Err(format!(
                "samplers[{s}].output: accessors[{o}].count: {} elements, expected {} for \
                 {keys} keys ({interpolation})",
                out.count(),
                keys * per_key
            ));
        }
        let raw = accessor::read(&out, &self.buffers, kind.dims, kind.storage)
            .map_err(|e| format!("samplers[{s}].output: {e}"))?;
        // The norm a stored rotation may be off 1 without a warning: 1e-3 as for CSV and JSON,
        // plus the rounding of normalized integers (at most half a step per component).
        let tolerance = inbetween::rotation::QUAT_NORM_WARN
            + match out.data_type() {
                gltf::accessor::DataType::I8 => 1.0 / 127.0,
                gltf::accessor::DataType::U8 => 1.0 / 255.0,
                gltf::accessor::DataType::I16 => 1.0 / 32767.0,
                gltf::accessor::DataType::U16 => 1.0 / 65535.0,
                _ => 0.0,
            };
        let mut off_norm: Option<(usize, f64)> = None;
        let mut off_count = 0usize;
        let mut elements = Vec::with_capacity(keys * per_key);
        for (e, comp) in raw.chunks_exact(n).enumerate() {
            let what = || match per_key {
                3 => format!(
                    "samplers[{s}].output: accessors[{o}]: key {} {}",
                    e / 3,
                    ["in-tangent", "value", "out-tangent"][e % 3]
                ),
                _ => format!("samplers[{s}].output: accessors[{o}]: key {e}"),
            };
            if let Some((j, &x)) = comp.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(format!(
                    "{}: component {j} is {}: expected finite components",
                    what(),
                    non_finite(x)
                ));
            }
            let is_value = per_key == 1 || e % 3 == 1;
            if kind.nonzero && is_value {
                let norm = comp.iter().map(|x| x * x).sum::<f64>().sqrt();
                if norm < 1e-12 {
                    return Err(format!(
                        "{}: expected a unit quaternion, found zero",
                        what()
                    ));
                }
                if (norm - 1.0).abs() > tolerance {
                    off_count += 1;
                    off_norm.get_or_insert((e / per_key, norm));
                }
            }
            elements.push((kind.build)(comp));
        }
        let warning = off_norm.map(|(k, norm)| {
            let more = match off_count {
                1 => String::new(),
                m => format!(" (and {} more keys)", m - 1),
            };
            format!(
                "samplers[{s}].output: accessors[{o}]: key {k}: quaternion norm {} is off 1 by \
                 more than 1e-3; normalized{more}",
                inbetween::error::num(norm)
            )
        });
        let (values, tangents) = if per_key == 3 {
            let values = elements.chunks_exact(3).map(|c| c[1]).collect();
            let tangents = elements.chunks_exact(3).map(|c| (c[0], c[2])).collect();
            (values, Some(tangents))
        } else {
            (elements, None)
        };
        let node = ch.target().node();
        Ok((
            Channel {
                index: c,
                node: node.index(),
                node_name: node
                    .name()
                    .map_or_else(|| format!("node{}", node.index()), str::to_string),
                sampler: s,
                interpolation,
                times_f32,
                times,
                values,
                tangents,
            },
            warning,
        ))
    }

    /// The bytes of buffer `i` as read (its declared `byteLength`).
    fn buffer(&self, i: usize) -> &[u8] {
        &self.buffers[i]
    }
}

/// How a channel's values are stored and built.
struct Kind<T> {
    dims: Dimensions,
    storage: Storage,
    nonzero: bool,
    build: fn(&[f64]) -> T,
}

const ROTATION_KIND: Kind<DQuat> = Kind {
    dims: Dimensions::Vec4,
    storage: Storage::FloatOrNormalized,
    nonzero: true,
    build: |c| DQuat::from_xyzw(c[0], c[1], c[2], c[3]),
};

const TRANSLATION_KIND: Kind<DVec3> = Kind {
    dims: Dimensions::Vec3,
    storage: Storage::Float,
    nonzero: false,
    build: |c| DVec3::new(c[0], c[1], c[2]),
};

/// The `gltf` crate's validation of every index and enum, except that an extension in
/// `extensionsRequired` the crate does not implement is accepted: this module reads only
/// animation data and copies everything else through.
fn validate(root: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::validation::Validate;
    positions_exist(root)?;
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, error| {
        let path = path().to_string();
        if !path.starts_with("extensionsRequired") {
            errors.push(format!("{path}: {error}"));
        }
    });
    match errors.first() {
        None => Ok(()),
        Some(first) if errors.len() == 1 => Err(format!("invalid glTF: {first}")),
        Some(first) => Err(format!(
            "invalid glTF: {first} (and {} more problems)",
            errors.len() - 1
        )),
    }
}

/// The one index the `gltf` crate's own validation dereferences before checking it: a mesh
/// primitive's `POSITION` accessor (gltf-json 1.4.1's `primitive_validate_hook` indexes
/// `accessors` with it to check `min` and `max`, and panics when it is out of range; found by
/// the `gltf_reader` fuzz target).
fn positions_exist(root: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::mesh::Semantic;
    use gltf::json::validation::Checked;
    let accessors = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(a) = primitive
                .attributes
                .get(&Checked::Valid(Semantic::Positions))
                && a.value() >= accessors
            {
                return Err(format!(
                    "invalid glTF: meshes[{m}].primitives[{p}].attributes.POSITION: accessor {} \
                     does not exist (the asset has {accessors} accessors)",
                    a.value()
                ));
            }
        }
    }
    Ok(())
}

/// What the `gltf` crate's validation leaves unchecked in animations (its `Animation` checks
/// only the samplers and each channel's sampler index): every channel's target node exists and
/// its path is one of glTF's, and no two channels of an animation target one node and path
/// (glTF 2.0 §3.11: "within one animation, each target MUST NOT be specified more than
/// once"). `channels` maps each kept channel to its JSON index, for the messages.
fn validate_channels(root: &gltf::json::Root, channels: &[Vec<usize>]) -> Result<(), String> {
    use gltf::json::validation::Checked;
    let nodes = root.nodes.len();
    for (a, anim) in root.animations.iter().enumerate() {
        let mut seen = std::collections::HashMap::new();
        for (k, ch) in anim.channels.iter().enumerate() {
            let c = channels.get(a).and_then(|m| m.get(k)).copied().unwrap_or(k);
            let node = ch.target.node.value();
            if node >= nodes {
                return Err(format!(
                    "animations[{a}].channels[{c}].target.node: node {node} does not exist \
                     (the asset has {nodes} nodes)"
                ));
            }
            let Checked::Valid(path) = ch.target.path else {
                return Err(format!(
                    "animations[{a}].channels[{c}].target.path: expected translation, rotation, \
                     scale or weights"
                ));
            };
            if let Some(first) = seen.insert((node, path as u8), c) {
                return Err(format!(
                    "animations[{a}].channels[{c}]: targets node {node}'s {}, as \
                     animations[{a}].channels[{first}] does: glTF allows one channel per node \
                     and path in an animation",
                    path_name(path)
                ));
            }
        }
    }
    Ok(())
}

fn path_name(p: Property) -> &'static str {
    match p {
        Property::Translation => "translation",
        Property::Rotation => "rotation",
        Property::Scale => "scale",
        Property::MorphTargetWeights => "weights",
    }
}

/// The image files the asset references, checked as buffer files are (percent-decoded,
/// relative, inside `base_dir` once links are resolved) except that a missing image is
/// allowed (images are never read here) and so is a URI with a scheme other than `file:` (an
/// image on the web, never fetched): the canonical paths of those that exist.
fn check_images(json: &serde_json::Value, base_dir: Option<&Path>) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    let Some(images) = json.get("images").and_then(serde_json::Value::as_array) else {
        return Ok(files);
    };
    for (i, image) in images.iter().enumerate() {
        let Some(uri) = image.get("uri").and_then(serde_json::Value::as_str) else {
            continue;
        };
        // A `data:` URI, or a URI with a scheme (an image on the web): nothing beside the
        // asset, and never read. `file:` is a file like any other, so it is refused below.
        if accessor::has_scheme(uri)
            && !uri
                .get(..5)
                .is_some_and(|s| s.eq_ignore_ascii_case("file:"))
        {
            continue;
        }
        let at = |e: String| format!("images[{i}].uri (\"{}\"): {e}", shorten(uri));
        let rel = accessor::relative_path(uri).map_err(at)?;
        let Some(dir) = base_dir else { continue };
        if std::fs::symlink_metadata(dir.join(&rel)).is_err() {
            continue;
        }
        let path = accessor::resolve(uri, dir).map_err(at)?;
        files.push(path);
    }
    Ok(files)
}

/// A non-finite number in words (messages never print `NaN`).
fn non_finite(x: f64) -> &'static str {
    if x.is_nan() {
        "not a number"
    } else if x > 0.0 {
        "+infinity"
    } else {
        "-infinity"
    }
}

#[cfg(test)]
mod tests;
