//! FBX input (binary and ASCII) through the `ufbx` crate: one animation stack of a scene as a
//! motion clip on its node hierarchy (docs/spec.md §3, *FBX*).
//!
//! ufbx parses the file and evaluates each node's local transform at a time — the FBX transform
//! stack with its pre- and post-rotations, pivots, rotation order and animation layers — which
//! is the part of FBX that is easy to get wrong and that ufbx's authors test against Autodesk's
//! SDK. This module only chooses what becomes the clip:
//!
//! - **Nodes.** Every node that is animated in the stack (a curve on its `Lcl Rotation` or
//!   `Lcl Translation`) and every ancestor of one (below the scene's root), in the scene's
//!   order, parents first. A node is a joint of the clip; its rotation is a track unless it is
//!   the identity at every sample (an ancestor that only places its children), its translation
//!   a track's positions when it moves, else the joint's offset.
//! - **Frames.** Every frame of the scene's rate (its exact time mode: NTSC is 30000/1001) from
//!   the stack's start to its end, the start at time 0 (as a BVH clip starts); the stack's keys,
//!   where they lie on that rate, are among those frames, and between keys the frames are FBX's
//!   own interpolation of its curves as ufbx evaluates it.
//! - **Scale.** A uniform scale of a node (a unit conversion on an armature, typically) scales
//!   the translations below it, so that world positions are the scene's; a non-uniform or
//!   animated scale cannot be carried by a joint's rotation and translation and is a warning.
//!
//! The clip is built as BVH text (each joint's rotation channels in the node's own FBX rotation
//! order: FBX `XYZ` applies X first, `R = Rz·Ry·Rx`, which is BVH's `Zrotation Yrotation
//! Xrotation`; angles and lengths written as the shortest decimals that read back exactly) and
//! read by [`crate::bvh::parse`], so an FBX clip is a BVH clip in every later step: tracks, BVH
//! output, the skeleton of world-space measures.

pub(crate) mod binary;
pub mod frames;
pub mod keys;
pub mod play;
pub mod write;

use crate::bvh::rate::frame_time_text;
use crate::clip::Clip;
use glam::{DQuat, DVec3};
use inbetween::clock::Fps;
use inbetween::error::{Error, InputError, InputResult, Setting, shorten};
use inbetween::message;
use inbetween::rotation::EulerSeq;
use std::collections::HashMap;
use std::fmt::Write as _;

/// The samples (frames × nodes) a clip read from FBX may take at least: 2²² (about 1 GB at
/// the peak of reading), so that a stack declaring an absurd span is refused before it is
/// sampled...
pub(crate) const MIN_SAMPLE_BUDGET: u64 = 1 << 22;

/// ...or this many per byte of the file, where that is more (a file whose curves are baked at
/// every frame holds several bytes per sample, so a long real take is read whole).
pub(crate) const SAMPLES_PER_BYTE: u64 = 8;

/// Sampling evaluates every animation layer of the stack at each sample: the samples times the
/// layers may be at most this many times the sample budget.
pub(crate) const LAYER_WORK_FACTOR: u64 = 4;

/// ufbx may use this many bytes of memory per byte of the file (each of its two allocators)...
pub(crate) const MEMORY_PER_BYTE: usize = 32;

/// ...and at least this many.
pub(crate) const MIN_MEMORY_LIMIT: usize = 256 << 20;

/// How far apart (relative) two scales may be and still be the same: a few float32 steps.
pub(crate) const SCALE_TOLERANCE: f64 = 1e-5;

/// Whether `bytes` look like FBX: the binary magic, or an ASCII file's `; FBX` header comment.
pub(crate) fn is_fbx(bytes: &[u8]) -> bool {
    bytes.starts_with(b"Kaydara FBX Binary") || {
        let head = &bytes[..bytes.len().min(64)];
        let text = String::from_utf8_lossy(head);
        let t = text.trim_start_matches('\u{feff}').trim_start();
        t.starts_with("; FBX")
    }
}

/// What an FBX scene's chosen stack became.
#[derive(Debug, Clone)]
pub(crate) struct FbxClip {
    /// The clip, as [`crate::bvh::parse`] reads it.
    pub clip: Clip,
    /// The scene's unit in metres (`UnitScaleFactor` / 100), which lengths are in.
    pub unit_meters: f64,
    /// Whether the scene is Z up (its `UpAxis`); else Y up.
    pub z_up: bool,
    /// Warnings, each naming the file.
    pub warnings: Vec<String>,
}

/// Reads FBX bytes (`source` names them in messages) and the stack chosen by `animation` (a
/// name, else an index; `None`: the first, with a warning when there are several).
pub(crate) fn read(bytes: &[u8], source: &str, animation: Option<&str>) -> Result<FbxClip, Error> {
    read_back(sample(bytes, source, animation)?, source)
}

/// The clip of a sampled stack: its text read as BVH. Text that does not read back is the
/// sampler's fault, not the file's: an internal error.
fn read_back(sampled: Sampled, source: &str) -> Result<FbxClip, Error> {
    let (clip, bvh_warnings) = crate::bvh::parse(&sampled.text, source).map_err(|e| {
        Error::Internal(format!(
            "{source}: internal error: the clip made of its FBX nodes does not read back: {}",
            e.message()
        ))
    })?;
    let mut warnings = sampled.warnings;
    warnings.extend(bvh_warnings);
    Ok(FbxClip {
        clip,
        unit_meters: sampled.unit_meters,
        z_up: sampled.z_up,
        warnings,
    })
}

/// A stack sampled into BVH text, with what the text cannot say.
struct Sampled {
    text: String,
    unit_meters: f64,
    z_up: bool,
    warnings: Vec<String>,
}

/// The chosen stack of FBX `bytes` sampled at its frames, as BVH text ([`bvh_text`]).
fn sample(bytes: &[u8], source: &str, animation: Option<&str>) -> InputResult<Sampled> {
    // ufbx's memory is bounded too, so that a small file cannot claim gigabytes.
    let limit = MEMORY_PER_BYTE
        .saturating_mul(bytes.len())
        .max(MIN_MEMORY_LIMIT);
    let allocator = || ufbx::AllocatorOpts {
        memory_limit: limit,
        ..Default::default()
    };
    let opts = ufbx::LoadOpts {
        ignore_geometry: true,
        ignore_embedded: true,
        load_external_files: false,
        temp_allocator: allocator(),
        result_allocator: allocator(),
        ..Default::default()
    };
    let scene = ufbx::load_memory(bytes, opts).map_err(|e| {
        input_err!(
            "{source}: not a readable FBX file: {}{}",
            e.description.as_ref() as &str,
            match e.info() {
                "" => String::new(),
                i => format!(" ({})", shorten(i)),
            }
        )
    })?;
    let mut warnings = Vec::new();
    let stacks = &scene.anim_stacks;
    if stacks.is_empty() {
        return Err(input_err!("{source}: the scene has no animation stack"));
    }
    let label = |i: usize| format!("{i} (\"{}\")", shorten(&stacks[i].element.name));
    let index = match animation {
        None => {
            if stacks.len() > 1 {
                let others: Vec<String> = (1..stacks.len()).map(label).collect();
                warnings.push(format!(
                    "{source}: the scene has {} animation stacks; reading the first, {}, not {}",
                    stacks.len(),
                    label(0),
                    others.join(", ")
                ));
            }
            0
        }
        Some(want) => {
            let found = stacks
                .iter()
                .position(|s| s.element.name.as_ref() as &str == want)
                .or_else(|| want.parse::<usize>().ok().filter(|&i| i < stacks.len()));
            found.ok_or_else(|| {
                let list: Vec<String> = (0..stacks.len()).map(label).collect();
                InputError::new(message![
                    Setting::Animation,
                    format!(
                        " {}: no such animation stack in {source} (it has {})",
                        shorten(want),
                        list.join(", ")
                    )
                ])
            })?
        }
    };
    let stack = &stacks[index];
    let fps = scene_rate(&scene.settings, source)?;
    let (start, end) = (stack.time_begin, stack.time_end);
    if !(start.is_finite() && end.is_finite() && end >= start) {
        return Err(input_err!(
            "{source}: animation stack {}: its span {start} s to {end} s is not a time span",
            label(index)
        ));
    }
    let span_frames = ((end - start) * fps.as_f64() + 1e-6).floor();

    // The animated nodes, and their ancestors: nodes by element id in a hash map, each
    // ancestor chain walked until a node already wanted (linear in nodes and properties).
    let nodes = &scene.nodes;
    let by_id: HashMap<u32, usize> = nodes
        .iter()
        .map(|n| (n.element.element_id, node_index(n)))
        .collect();
    let mut wanted = vec![false; nodes.len()];
    for layer in stack.layers.iter() {
        for prop in layer.anim_props.iter() {
            let name: &str = prop.prop_name.as_ref();
            if name != "Lcl Rotation" && name != "Lcl Translation" {
                continue;
            }
            let Some(&first) = by_id.get(&prop.element.element_id) else {
                continue;
            };
            let mut n = &nodes[first];
            while !n.is_root && !wanted[node_index(n)] {
                wanted[node_index(n)] = true;
                match &n.parent {
                    Some(p) => n = p,
                    None => break,
                }
            }
        }
    }
    let order: Vec<usize> = (0..nodes.len()).filter(|&i| wanted[i]).collect();
    if order.is_empty() {
        return Err(input_err!(
            "{source}: animation stack {} animates no node's rotation or translation",
            label(index)
        ));
    }
    // The work the stack claims, refused before any sample is taken or allocated.
    let budget = MIN_SAMPLE_BUDGET.max(SAMPLES_PER_BYTE.saturating_mul(bytes.len() as u64));
    let layers = (stack.layers.len() as u64).max(1);
    let samples = (span_frames + 1.0) * order.len() as f64;
    if samples > budget as f64 || samples * layers as f64 > (budget * LAYER_WORK_FACTOR) as f64 {
        return Err(input_err!(
            "{source}: animation stack {} spans {} s, {} frames at {fps} fps, for {} node(s){}: \
             more than the {budget} samples this file may claim (frames × nodes{}; at least \
             {MIN_SAMPLE_BUDGET}, or {SAMPLES_PER_BYTE} per byte of the file)",
            label(index),
            end - start,
            span_frames + 1.0,
            order.len(),
            if layers > 1 {
                format!(" in {layers} layers")
            } else {
                String::new()
            },
            if layers > LAYER_WORK_FACTOR {
                format!(" × layers / {LAYER_WORK_FACTOR}")
            } else {
                String::new()
            }
        ));
    }
    let frames = span_frames as u64 + 1;
    let frames = frames as usize;
    let time = |k: usize| start + fps.time_of(k as i64);

    // Each chosen node's local transform at every frame.
    let anim = &stack.anim;
    let mut rotations: Vec<Vec<DQuat>> = Vec::with_capacity(order.len());
    let mut translations: Vec<Vec<DVec3>> = Vec::with_capacity(order.len());
    let mut scales: Vec<f64> = Vec::with_capacity(order.len());
    for &i in &order {
        let node = &nodes[i];
        let name = node_name(node, i);
        let mut r = Vec::with_capacity(frames);
        let mut t = Vec::with_capacity(frames);
        let mut s0 = None;
        let mut scale_moves = false;
        for k in 0..frames {
            let tr = ufbx::evaluate_transform(anim, node, time(k));
            let q = DQuat::from_xyzw(tr.rotation.x, tr.rotation.y, tr.rotation.z, tr.rotation.w);
            let p = DVec3::new(tr.translation.x, tr.translation.y, tr.translation.z);
            let s = DVec3::new(tr.scale.x, tr.scale.y, tr.scale.z);
            if !(q.is_finite() && p.is_finite() && s.is_finite()) || q.length() < 1e-6 {
                return Err(input_err!(
                    "{source}: node \"{}\" has a transform that is not finite at {} s",
                    shorten(&name),
                    time(k)
                ));
            }
            match s0 {
                None => s0 = Some(s),
                Some(first) => scale_moves |= !same_scale(first, s),
            }
            r.push(q.normalize());
            t.push(p);
        }
        let s = s0.expect("at least one frame");
        let uniform = same_scale(DVec3::splat(s.x), s);
        if scale_moves || !uniform {
            warnings.push(format!(
                "{source}: node \"{}\" has a {} scale, which a joint cannot carry: positions \
                 below it use its scale {} on every axis",
                shorten(&name),
                if scale_moves { "moving" } else { "non-uniform" },
                s.x
            ));
        }
        rotations.push(r);
        translations.push(t);
        scales.push(s.x);
    }

    // Parents within the chosen nodes; the scale every translation is multiplied by.
    let mut slot: Vec<Option<usize>> = vec![None; nodes.len()];
    for (j, &i) in order.iter().enumerate() {
        slot[i] = Some(j);
    }
    let parents: Vec<Option<usize>> = order
        .iter()
        .map(|&i| nodes[i].parent.as_ref().and_then(|p| slot[node_index(p)]))
        .collect();
    let mut factor = vec![1.0; order.len()];
    for j in 0..order.len() {
        if let Some(p) = parents[j] {
            factor[j] = factor[p] * scales[p];
        }
    }
    let text = bvh_text(
        &order,
        nodes,
        (&wanted, &scales),
        &parents,
        &factor,
        &rotations,
        &translations,
        fps,
        frames,
    );
    use ufbx::CoordinateAxis as A;
    let z_up = match scene.settings.axes.up {
        A::PositiveZ | A::NegativeZ => true,
        A::PositiveY | A::NegativeY | A::Unknown => false,
        A::PositiveX | A::NegativeX => {
            warnings.push(format!(
                "{source}: the scene is X up, which USD cannot say (its upAxis is Y or Z): \
                 written as Y up"
            ));
            false
        }
    };
    Ok(Sampled {
        text,
        unit_meters: scene.settings.unit_meters,
        z_up,
        warnings,
    })
}

/// Scales are the same within [`SCALE_TOLERANCE`] of their size (files store float32, and
/// exporters leave a scale of 1 as 1.0000001).
fn same_scale(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element()
        <= SCALE_TOLERANCE * a.abs().max_element().max(b.abs().max_element())
}

/// The scene's frame rate, exact for the FBX time modes (NTSC is 30000/1001, 59.94 is
/// 60000/1001), else the shortest decimal of its custom rate.
fn scene_rate(settings: &ufbx::SceneSettings, source: &str) -> InputResult<Fps> {
    use ufbx::TimeMode as M;
    let exact = match settings.time_mode {
        M::NtscDropFrame | M::NtscFullFrame | M::E30FpsDrop => Some((30000, 1001)),
        M::E5994Fps => Some((60000, 1001)),
        M::FilmFullFrame => Some((24000, 1001)),
        _ => None,
    };
    match exact {
        Some((n, d)) => Fps::new(n, d),
        None => Fps::from_f64(settings.frames_per_second),
    }
    .map_err(|e| input_err!("{source}: the scene's frame rate: {}", e.message()))
}

/// A node's name as a joint name: control characters and braces (which BVH text cannot hold in
/// a name) become `_`, the name is trimmed, and an empty one is `node<index>`.
fn node_name(node: &ufbx::Node, index: usize) -> String {
    let raw: &str = node.element.name.as_ref();
    let clean: String = raw
        .chars()
        .map(|c| {
            if c.is_control() || c == '{' || c == '}' {
                '_'
            } else {
                c
            }
        })
        .collect();
    let clean = clean.trim();
    if clean.is_empty() {
        format!("node{index}")
    } else {
        clean.to_string()
    }
}

/// The BVH channel sequence of an FBX rotation order: FBX `XYZ` applies X first (`R =
/// Rz·Ry·Rx`), BVH lists the outermost first, so the letters reverse. Spheric is read as XYZ.
fn bvh_order(order: ufbx::RotationOrder) -> &'static str {
    use ufbx::RotationOrder as O;
    match order {
        O::Xyz | O::Spheric => "ZYX",
        O::Xzy => "YZX",
        O::Yzx => "XZY",
        O::Yxz => "ZXY",
        O::Zxy => "YXZ",
        O::Zyx => "XYZ",
    }
}

/// The clip as BVH text: the hierarchy of the chosen nodes and one row per frame.
#[allow(clippy::too_many_arguments)]
fn bvh_text(
    order: &[usize],
    nodes: &ufbx::RefList<ufbx::Node>,
    (wanted, scales): (&[bool], &[f64]),
    parents: &[Option<usize>],
    factor: &[f64],
    rotations: &[Vec<DQuat>],
    translations: &[Vec<DVec3>],
    fps: Fps,
    frames: usize,
) -> String {
    let n = order.len();
    let rotates: Vec<bool> = rotations
        .iter()
        .map(|r| r.iter().any(|q| q.xyz() != DVec3::ZERO))
        .collect();
    let moves: Vec<bool> = translations
        .iter()
        .map(|t| t.iter().any(|p| *p != t[0]))
        .collect();
    let seqs: Vec<&str> = order
        .iter()
        .map(|&i| bvh_order(nodes[i].rotation_order))
        .collect();
    // Each joint's children, in the scene's order (one pass; the roots under `n`).
    let mut kids: Vec<Vec<usize>> = vec![Vec::new(); n + 1];
    for (j, p) in parents.iter().enumerate() {
        kids[p.unwrap_or(n)].push(j);
    }
    let mut text = String::from("HIERARCHY\n");
    // Depth-first, children in the scene's order; an explicit stack keeps deep chains safe.
    let mut listed: Vec<usize> = Vec::with_capacity(n);
    // Not indented: the text is read, never shown, and an indent as deep as the joint made a
    // 20 000-node chain gigabytes of spaces.
    fn open(text: &mut String, depth: usize, name: &str, offset: DVec3, channels: &str) {
        let kind = if depth == 0 { "ROOT" } else { "JOINT" };
        let _ = writeln!(text, "{kind} {name}\n{{");
        let _ = writeln!(text, "OFFSET {} {} {}", offset.x, offset.y, offset.z);
        let _ = writeln!(text, "{channels}");
    }
    let mut stack: Vec<(usize, usize, bool)> =
        kids[n].iter().rev().map(|&j| (j, 0, false)).collect();
    while let Some((j, depth, closing)) = stack.pop() {
        if closing {
            text.push_str("}\n");
            continue;
        }
        let mut channels = Vec::new();
        if moves[j] {
            channels.extend(["Xposition", "Yposition", "Zposition"]);
        }
        if rotates[j] {
            for c in seqs[j].chars() {
                channels.push(match c {
                    'X' => "Xrotation",
                    'Y' => "Yrotation",
                    _ => "Zrotation",
                });
            }
        }
        let spec = format!("CHANNELS {} {}", channels.len(), channels.join(" "));
        let offset = translations[j][0] * factor[j];
        open(
            &mut text,
            depth,
            &node_name(&nodes[order[j]], order[j]),
            offset,
            spec.trim_end(),
        );
        // The node's first child that nothing animates and that has no children of its own
        // (an exporter's `Head_end`): the bone's end, as a BVH End Site, so that the joint's
        // rotation moves a point.
        let node = &nodes[order[j]];
        if let Some(end) = node
            .children
            .iter()
            .find(|c| !wanted[node_index(c)] && c.children.is_empty())
        {
            let t = end.local_transform.translation;
            let e = DVec3::new(t.x, t.y, t.z) * factor[j] * scales[j];
            if e.is_finite() {
                let _ = writeln!(text, "End Site\n{{\nOFFSET {} {} {}\n}}", e.x, e.y, e.z);
            }
        }
        listed.push(j);
        stack.push((j, depth, true));
        stack.extend(kids[j].iter().rev().map(|&c| (c, depth + 1, false)));
    }
    let _ = writeln!(
        text,
        "MOTION\nFrames: {frames}\nFrame Time: {}",
        frame_time_text(fps)
    );
    let seq_of: Vec<Option<EulerSeq>> = seqs.iter().map(|s| EulerSeq::parse(s).ok()).collect();
    for k in 0..frames {
        let mut first = true;
        let mut put = |text: &mut String, x: f64| {
            if !first {
                text.push(' ');
            }
            first = false;
            let _ = write!(text, "{x}");
        };
        for &j in &listed {
            if moves[j] {
                let p = translations[j][k] * factor[j];
                put(&mut text, p.x);
                put(&mut text, p.y);
                put(&mut text, p.z);
            }
            if rotates[j] {
                let seq = seq_of[j].as_ref().expect("a valid sequence");
                for a in seq.from_quat(rotations[j][k]) {
                    put(&mut text, a.to_degrees());
                }
            }
        }
        text.push('\n');
    }
    text
}

/// A node's position in the scene's node list.
fn node_index(node: &ufbx::Node) -> usize {
    node.element.typed_id as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sampled text the BVH reader refuses is the library's bug: exit 1, not the file's fault.
    #[test]
    fn text_that_does_not_read_back_is_an_internal_error() {
        let sampled = Sampled {
            text: "HIERARCHY\nROOT a\n{\n".to_string(),
            unit_meters: 0.01,
            z_up: false,
            warnings: Vec::new(),
        };
        match read_back(sampled, "clip.fbx") {
            Err(Error::Internal(m)) => assert!(
                m.starts_with("clip.fbx: internal error: the clip made of its FBX nodes"),
                "{m}"
            ),
            other => panic!("expected an internal error, found {other:?}"),
        }
    }
}
