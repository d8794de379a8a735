//! `write`: tracks of arrays as a keyframe document (CSV, JSON), frames (npy, npz), BVH motion
//! on a skeleton, or keys written into the glTF asset they were read from ([`crate::gltf`]),
//! through the formats crate's writers (the bytes the command line writes), into the file
//! atomically (nothing is left on error).

use crate::arrays::{self, Layout};
use crate::{input_error, options};
use glam::DVec3;
use inbetween::Fps;
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};
use inbetween_commands::capability::{self, Needs};
use inbetween_commands::output::Output;
use inbetween_io::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use inbetween_io::num::NumFormat;
use inbetween_io::write::{EulerMode, Style};
use inbetween_io::{Format, OutputFormat};
use numpy::PyReadonlyArrayDyn;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// One track as the Python layer hands it over.
type TrackArrays<'py> = (
    String,
    PyReadonlyArrayDyn<'py, f64>,
    PyReadonlyArrayDyn<'py, f64>,
    Option<PyReadonlyArrayDyn<'py, f64>>,
);

/// Writes `tracks` (name, times (K,), rotations (K, 4), translations (K, 3) or None) to `path`
/// in the format its extension names (csv, json, npy, npz, bvh, gltf, glb); `fps` is the rate
/// of the frames (BVH: the skeleton's when None), `skeleton` the BVH file whose hierarchy BVH
/// output is written on, `asset` the glTF asset glTF output is written into (its name in
/// messages, its path, its bytes); `to`, `angles`, `precision` and `euler` as `inbetween
/// convert`'s options; `parents` (J,) and `offsets` (J, 3), the clip's tree, go into `.npz`
/// output as `interp` writes them.
#[pyfunction]
#[pyo3(signature = (
    path, tracks, *, fps = None, skeleton = None, asset = None, to = "quat", angles = "deg",
    precision = None, euler = "continuous", scalar_first = true, parents = None, offsets = None
))]
#[allow(clippy::too_many_arguments)]
pub fn write<'py>(
    py: Python<'py>,
    path: PathBuf,
    tracks: Vec<TrackArrays<'py>>,
    fps: Option<Bound<'py, PyAny>>,
    skeleton: Option<PathBuf>,
    asset: Option<crate::gltf::SourceAsset>,
    to: &str,
    angles: &str,
    precision: Option<Bound<'py, PyAny>>,
    euler: &str,
    scalar_first: bool,
    parents: Option<Vec<i64>>,
    offsets: Option<Vec<[f64; 3]>>,
) -> PyResult<()> {
    let tree = match (parents, offsets) {
        (Some(parents), Some(offsets)) => {
            let j = tracks.len() as i64;
            if parents.len() != tracks.len()
                || offsets.len() != tracks.len()
                || parents.iter().any(|&p| p < -1 || p >= j)
                || offsets.iter().flatten().any(|x| !x.is_finite())
            {
                return Err(input_error(format!(
                    "parents, offsets: expected {j} parents in -1..{j} and {j} finite offsets, \
                     one per track"
                )));
            }
            Some(inbetween_io::write::npz::Tree { parents, offsets })
        }
        (None, None) => None,
        _ => return Err(input_error("parents, offsets: give both or neither")),
    };
    let precision = match precision {
        None => None,
        Some(p) => match crate::options::integer("precision", &p, (0, 17))? {
            Some(p) => Some(p as usize),
            None => return Err(input_error("precision: expected 0 to 17 digits")),
        },
    };
    let located = |e: inbetween::InputError| input_error(crate::message(&e));
    let source = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    // USD and FBX are not written by `write` (a skeleton's scene; `process_file` writes them):
    // `.usda` and `.fbx` are refused, never CSV under their names.
    let target = match ext.as_deref().and_then(|e| OutputFormat::parse(e).ok()) {
        Some(t) if !matches!(t, OutputFormat::Usda | OutputFormat::Fbx) => t,
        _ => {
            return Err(input_error(format!(
                "path: {source}: write takes .csv, .json, .npy, .npz, .bvh, .glb or .gltf"
            )));
        }
    };
    if let OutputFormat::Gltf(container) = target {
        return write_gltf(
            py,
            &path,
            (&tracks, scalar_first),
            asset,
            container,
            (to, precision, skeleton),
        );
    }
    if asset.is_some() {
        return Err(input_error(
            "asset: only glTF output (.glb, .gltf) is written into an asset",
        ));
    }
    let format = match target {
        OutputFormat::Doc(f) => f,
        _ => Format::Bvh, // frames on a grid
    };
    let style = Style {
        repr: Repr::parse(to).map_err(|e| input_error(format!("to: {}", crate::message(&e))))?,
        angles: AngleUnit::parse(angles)
            .map_err(|e| input_error(format!("angles: {}", crate::message(&e))))?,
        quat_order: QuatOrder::Wxyz,
        num: precision.map_or(NumFormat::Shortest, NumFormat::Fixed),
        euler: match euler {
            "continuous" => EulerMode::Continuous,
            "wrapped" => EulerMode::Wrapped,
            _ => {
                return Err(input_error(format!(
                    "euler: expected continuous or wrapped, found {euler:?}"
                )));
            }
        },
    };
    let fps = fps.as_ref().map(|r| options::rate("fps", r)).transpose()?;
    let needs = capability::of(target).needs;
    let skeleton = match (needs, skeleton) {
        (Needs::Skeleton, Some(s)) => Some(read_skeleton(&s).map_err(located)?),
        (Needs::Skeleton, None) => {
            return Err(input_error(
                "skeleton: BVH output is written on a skeleton: give the BVH file whose \
                 hierarchy and channels the motion is for",
            ));
        }
        (_, Some(_)) => {
            return Err(input_error(
                "skeleton: only BVH output is written on a skeleton",
            ));
        }
        _ => None,
    };
    let rate = fps.or(skeleton.as_ref().map(|s| s.fps()));
    if needs == Needs::Rate && rate.is_none() {
        return Err(input_error(
            "fps: npy and npz hold frames: give the rate the times are frames of",
        ));
    }
    let doc = document(&source, &tracks, rate, format, scalar_first)?;
    let io = |e: std::io::Error| cannot_write(&source, e);
    let mut file = Output::open(Some(&path), &[], "").map_err(crate::error)?;
    py.detach(|| -> PyResult<()> {
        let out = &mut file;
        let frames = rate.unwrap_or(Fps::DEFAULT);
        match (&skeleton, target) {
            (_, OutputFormat::Npy | OutputFormat::Npz) => {
                crate::frames::write(out, &doc, target, style, (frames, tree))
            }
            (Some(s), _) => inbetween_io::bvh::keys::write_keys(out, &doc, s, frames, style.euler)
                .map_err(located),
            (None, _) => inbetween_io::write::write_keys(
                out,
                &doc,
                format,
                style,
                rate.unwrap_or(Fps::DEFAULT),
            )
            .map_err(io),
        }
    })?;
    file.commit().map_err(io)?;
    Ok(())
}

/// An error writing `source`, naming it once (the output's own errors name it already): a
/// writer's check of its own output (`internal error: …`) a `RuntimeError`, anything else the
/// system's error as Python names it (`OSError`, `BrokenPipeError`, …), its kind kept.
fn cannot_write(source: &str, e: std::io::Error) -> PyErr {
    let m = e.to_string();
    let m = if m.starts_with(&format!("{source}: ")) {
        m
    } else {
        format!("{source}: cannot write: {m}")
    };
    if m.contains("internal error") {
        pyo3::exceptions::PyRuntimeError::new_err(m)
    } else {
        std::io::Error::new(e.kind(), m).into()
    }
}

/// The folder of `path` (`.` for a bare file name), where a `.gltf`'s external files are.
fn folder(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// glTF output: the tracks written into `asset` ([`crate::gltf::bytes`]), atomically. The
/// options of the other formats (`to`, `precision`, `skeleton`) are refused rather than
/// ignored.
fn write_gltf(
    py: Python<'_>,
    path: &Path,
    (tracks, scalar_first): (&[TrackArrays<'_>], bool),
    asset: Option<crate::gltf::SourceAsset>,
    container: inbetween_io::gltf::ContainerFormat,
    (to, precision, skeleton): (&str, Option<usize>, Option<PathBuf>),
) -> PyResult<()> {
    let source = path.display().to_string();
    let Some(asset) = asset else {
        return Err(input_error(format!(
            "path: {source}: glTF output is written into the asset the clip was read from (its \
             meshes, skins and other channels kept), as BVH output is written on a skeleton: \
             write a clip that inbetween.read read from a .glb or .gltf"
        )));
    };
    if to != "quat" {
        return Err(input_error(format!(
            "to: glTF stores rotations as quaternions, found {to:?}"
        )));
    }
    if precision.is_some() {
        return Err(input_error(
            "precision: glTF stores float32 numbers; precision is for csv and json",
        ));
    }
    if skeleton.is_some() {
        return Err(input_error(
            "skeleton: only BVH output is written on a skeleton",
        ));
    }
    let doc = document(&source, tracks, None, Format::Json, scalar_first)?;
    let dir = folder(path);
    let io = |e: std::io::Error| cannot_write(&source, e);
    let mut file = Output::open(Some(path), &[], "").map_err(crate::error)?;
    py.detach(|| -> PyResult<()> {
        let bytes = crate::gltf::bytes(&doc, &asset, container, &dir)?;
        std::io::Write::write_all(&mut file, &bytes).map_err(io)
    })?;
    file.commit().map_err(io)?;
    Ok(())
}

/// The skeleton of a BVH file (its hierarchy, channels and rate).
fn read_skeleton(path: &Path) -> inbetween::error::InputResult<inbetween_io::clip::Clip> {
    let bytes = inbetween_io::read_bytes_limited(path, inbetween_io::DEFAULT_MAX_INPUT_BYTES)?;
    let source = path.display().to_string();
    let text = String::from_utf8(bytes)
        .map_err(|_| inbetween::InputError::new(format!("{source}: not UTF-8 text")))?;
    inbetween_io::bvh::read::parse(&text, &source).map(|(clip, _)| clip)
}

/// The tracks as a document: keys at their times, or for BVH at frame numbers of `fps`
/// (each time must be a frame of that rate within 1e-9 s).
fn document(
    source: &str,
    tracks: &[TrackArrays<'_>],
    fps: Option<Fps>,
    format: Format,
    scalar_first: bool,
) -> PyResult<Document> {
    let mut doc_tracks = Vec::with_capacity(tracks.len());
    for (i, (name, times, rotations, translations)) in tracks.iter().enumerate() {
        let what = |field: &str| format!("tracks[{i}] ({name:?}) {field}");
        let times = arrays::times(times, &what("times"))?;
        let (layout, quats) = arrays::quats(rotations, &what("rotations"), scalar_first)?;
        if layout.joints.is_some() || layout.rows != times.len() {
            return Err(input_error(format!(
                "{}: expected ({}, 4) rotations for {} times",
                what("rotations"),
                times.len(),
                times.len()
            )));
        }
        let positions: Vec<Option<DVec3>> = match translations {
            Some(p) => {
                let like = Layout {
                    rows: times.len(),
                    joints: None,
                };
                let v = arrays::vectors(p, &what("translations"), like, "times")?;
                v.into_iter()
                    .next()
                    .unwrap_or_default()
                    .into_iter()
                    .map(Some)
                    .collect()
            }
            None => Vec::new(),
        };
        let mut keys = Vec::with_capacity(times.len());
        for (k, (&t, q)) in times.iter().zip(&quats[0]).enumerate() {
            let when = match (format, fps) {
                (Format::Bvh, Some(f)) => {
                    let Some(n) = f.frame_at(t) else {
                        return Err(input_error(format!(
                            "{}[{k}]: {t} s is not a frame at {f} fps (BVH rows are frames)",
                            what("times")
                        )));
                    };
                    KeyTime::Frame(n as f64)
                }
                _ => KeyTime::Seconds(t),
            };
            // Unit by arrays::quats (the command line's normalisation rule).
            keys.push(Key { when, rot: *q });
        }
        doc_tracks.push(DocTrack {
            name: Some(name.clone()),
            translations: positions,
            ..DocTrack::new(keys, KeyOrigin::Frames)
        });
    }
    Ok(Document {
        fps,
        rotation: Some(Repr::Quat),
        tracks: doc_tracks,
        named_tracks: true,
        ..Document::new(source.to_string())
    })
}
