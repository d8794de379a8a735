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
//! The `gltf` crate parses and validates the document (JSON or GLB container, every index);
//! accessors are decoded here with every byte range checked, so that a damaged
//! file is an [`InputError`] naming the file, the animation, the channel and the accessor,
//! never a panic. Writing ([`Asset::write`]) works on the JSON as a `serde_json::Value`, so
//! whatever the `gltf` crate does not model (unknown extensions, `extras`) survives untouched.
//!
//! - [`document`]: the chosen animations' rotation channels as a keyframe document (tracks),
//!   keys snapped to a frame rate, `STEP`/`CUBICSPLINE` channels baked for interpolation.
//! - [`frames`]: interp's frames written back into the asset ([`frames::GltfFrames`]).
//! - [`keys`]: reduce's kept keys written back into the asset ([`keys::keys_asset`]).
//!
//! ```
//! use inbetween::io::gltf::{Asset, Interpolation};
//!
//! let asset = Asset::read_path("fixtures/gltf/minimal_linear.gltf".as_ref())?;
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
pub mod keys;
mod write;

pub use channel::{
    Channel, Interpolation, RotationChannel, TranslationChannel, f32_ulp, on_frame, snap_key_time,
};
pub use write::{ContainerFormat, Resampled};

use crate::error::{InputError, InputResult, input_err, shorten};
use accessor::Storage;
use glam::{DQuat, DVec3};
use gltf::accessor::Dimensions;
use gltf::animation::Property;
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
}

/// One animation of an asset: its rotation and translation channels (scale and morph-weight
/// channels are not read).
#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    index: usize,
    name: Option<String>,
    rotations: Vec<RotationChannel>,
    translations: Vec<TranslationChannel>,
    span: Option<(f64, f64)>,
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

    /// The earliest and latest input time of all the animation's samplers (every sampler, not
    /// only the rotation and translation ones), or `None` when it has no samplers.
    pub fn span(&self) -> Option<(f64, f64)> {
        self.span
    }
}

impl Asset {
    /// Reads a `.gltf` or `.glb` file (the container is recognised by its first bytes, not its
    /// name); external buffers are looked up beside it.
    pub fn read_path(path: &Path) -> InputResult<Asset> {
        let source = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| input_err!("{source}: cannot read: {e}"))?;
        let dir = path
            .parent()
            .map(|p| {
                if p.as_os_str().is_empty() {
                    PathBuf::from(".")
                } else {
                    p.to_path_buf()
                }
            })
            .unwrap_or_else(|| PathBuf::from("."));
        Self::from_slice(&bytes, &source, Some(&dir))
    }

    /// Parses an asset from its bytes (`.gltf` JSON or `.glb`). `source` names it in messages;
    /// `base_dir` is where buffer files named by relative URIs are found (`None`: such a
    /// reference is an error).
    pub fn from_slice(bytes: &[u8], source: &str, base_dir: Option<&Path>) -> InputResult<Asset> {
        let fail = |m: String| InputError::new(m).at(source);
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
        let json: serde_json::Value = serde_json::from_slice(&json_bytes)
            .map_err(|e| fail(format!("invalid glTF JSON: {e}")))?;
        let root: gltf::json::Root =
            serde_json::from_value(json.clone()).map_err(|e| fail(format!("invalid glTF: {e}")))?;
        validate(&root).map_err(fail)?;
        let document = gltf::Document::from_json_without_validation(root);
        let buffers = accessor::load_buffers(&document, blob.as_deref(), base_dir).map_err(fail)?;
        Ok(Asset {
            source: source.to_string(),
            document,
            json,
            buffers,
            container,
            base_dir: base_dir.map(Path::to_path_buf),
        })
    }

    /// The name the asset has in messages.
    pub fn source(&self) -> &str {
        &self.source
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
    /// for a translation; every value is finite, and a rotation value (a `CUBICSPLINE` vertex
    /// too) has non-zero length. The first problem is an error naming the file, animation,
    /// channel and accessor.
    pub fn animations(&self) -> InputResult<Vec<Animation>> {
        self.document
            .animations()
            .map(|a| self.read_animation(&a))
            .collect()
    }

    fn read_animation(&self, anim: &gltf::Animation) -> InputResult<Animation> {
        let name = anim.name().map(str::to_string);
        let label = match &name {
            Some(n) => format!("animation {} (\"{}\")", anim.index(), shorten(n)),
            None => format!("animation {}", anim.index()),
        };
        let mut span: Option<(f64, f64)> = None;
        for sampler in anim.samplers() {
            let at = |m: String| {
                input_err!("{}: {label}: sampler {}: {m}", self.source, sampler.index())
            };
            let (_, times) = self.times(&sampler.input()).map_err(at)?;
            if let (Some(&a), Some(&b)) = (times.first(), times.last()) {
                span = Some(span.map_or((a, b), |(x, y)| (x.min(a), y.max(b))));
            }
        }
        let mut rotations = Vec::new();
        let mut translations = Vec::new();
        for ch in anim.channels() {
            let at =
                |m: String| input_err!("{}: {label}: channel {}: {m}", self.source, ch.index());
            match ch.target().property() {
                Property::Rotation => {
                    rotations.push(self.read_channel(&ch, ROTATION_KIND).map_err(at)?)
                }
                Property::Translation => {
                    translations.push(self.read_channel(&ch, TRANSLATION_KIND).map_err(at)?);
                }
                Property::Scale | Property::MorphTargetWeights => {}
            }
        }
        Ok(Animation {
            index: anim.index(),
            name,
            rotations,
            translations,
            span,
        })
    }

    /// A sampler's input: the float32 times and the same widened, checked.
    fn times(&self, acc: &gltf::Accessor) -> Result<(Vec<f32>, Vec<f64>), String> {
        let times = accessor::read(acc, &self.buffers, Dimensions::Scalar, Storage::Float)?;
        if times.is_empty() {
            return Err(format!("input accessor {}: no key times", acc.index()));
        }
        for (k, &t) in times.iter().enumerate() {
            if !t.is_finite() {
                return Err(format!(
                    "input accessor {}: time {k} is {t}: expected a finite number",
                    acc.index()
                ));
            }
            if k > 0 && t <= times[k - 1] {
                return Err(format!(
                    "input accessor {}: time {k} is {} after {}: expected strictly increasing times",
                    acc.index(),
                    crate::error::num(t),
                    crate::error::num(times[k - 1])
                ));
            }
        }
        // Exact: every value came from a float32.
        Ok((times.iter().map(|&t| t as f32).collect(), times))
    }

    fn read_channel<T: Copy>(
        &self,
        ch: &gltf::animation::Channel,
        kind: Kind<T>,
    ) -> Result<Channel<T>, String> {
        let sampler = ch.sampler();
        let interpolation = match sampler.interpolation() {
            gltf::animation::Interpolation::Linear => Interpolation::Linear,
            gltf::animation::Interpolation::Step => Interpolation::Step,
            gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
        };
        let (times_f32, times) = self.times(&sampler.input())?;
        let out = sampler.output();
        let n = kind.dims.multiplicity();
        let raw = accessor::read(&out, &self.buffers, kind.dims, kind.storage)?;
        let per_key = if interpolation == Interpolation::CubicSpline {
            3
        } else {
            1
        };
        let keys = times.len();
        if interpolation == Interpolation::CubicSpline && keys < 2 {
            return Err(format!(
                "input accessor {}: CUBICSPLINE needs at least 2 keys, found 1",
                sampler.input().index()
            ));
        }
        if raw.len() != keys * per_key * n {
            return Err(format!(
                "output accessor {} has {} elements: expected {} for {keys} keys ({interpolation})",
                out.index(),
                raw.len() / n,
                keys * per_key
            ));
        }
        let mut elements = Vec::with_capacity(keys * per_key);
        for (e, c) in raw.chunks_exact(n).enumerate() {
            let what = || match per_key {
                3 => format!(
                    "output accessor {}: key {} {}",
                    out.index(),
                    e / 3,
                    ["in-tangent", "value", "out-tangent"][e % 3]
                ),
                _ => format!("output accessor {}: key {e}", out.index()),
            };
            if let Some(x) = c.iter().find(|x| !x.is_finite()) {
                return Err(format!("{}: {x}: expected finite components", what()));
            }
            let is_value = per_key == 1 || e % 3 == 1;
            if kind.nonzero && is_value && c.iter().map(|x| x * x).sum::<f64>() < 1e-24 {
                return Err(format!(
                    "{}: expected a unit quaternion, found zero",
                    what()
                ));
            }
            elements.push((kind.build)(c));
        }
        let (values, tangents) = if per_key == 3 {
            let values = elements.chunks_exact(3).map(|c| c[1]).collect();
            let tangents = elements.chunks_exact(3).map(|c| (c[0], c[2])).collect();
            (values, Some(tangents))
        } else {
            (elements, None)
        };
        let node = ch.target().node();
        Ok(Channel {
            index: ch.index(),
            node: node.index(),
            node_name: node
                .name()
                .map_or_else(|| format!("node{}", node.index()), str::to_string),
            sampler: sampler.index(),
            interpolation,
            times_f32,
            times,
            values,
            tangents,
        })
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

#[cfg(test)]
mod tests;
