//! A skeleton's motion as a binary FBX scene (the container is `binary`): what the nodes of the file
//! say (docs/spec.md §3, *FBX output*).
//!
//! ```text
//! FBXHeaderExtension  FileId  CreationTime  Creator
//! GlobalSettings      UpAxis/FrontAxis/CoordAxis (+ signs), UnitScaleFactor (cm per unit),
//!                     TimeMode (from the rate), CustomFrameRate, TimeSpanStart/Stop
//! Definitions         the count of each object type
//! Objects
//!   Model "<joint>" LimbNode       one per joint: RotationOrder, Lcl Translation (rest offset),
//!                                  Lcl Rotation, Lcl Scaling; NodeAttribute LimbNode
//!   Model "<joint>_end" LimbNode   one per end point, at its offset, not animated
//!   AnimationStack "Clip", AnimationLayer "BaseLayer"
//!   AnimationCurveNode "R" (every joint), "T" (a joint whose translation is animated)
//!   AnimationCurve d|X d|Y d|Z     KeyTime (ticks), KeyValueFloat (degrees, lengths), linear
//! Connections         OO model→parent model (0: the scene), attribute→model, layer→stack,
//!                     curve node→layer; OP curve node→model "Lcl Rotation"/"Lcl Translation",
//!                     curve→curve node "d|X"
//! Takes               the stack's span
//! ```
//!
//! **Rotations.** FBX rotates a node by Euler angles in its `RotationOrder`: `eEulerXYZ` (0)
//! applies X first, `R = Rz·Ry·Rx`, which is the intrinsic sequence `ZYX` (BVH's `Zrotation
//! Yrotation Xrotation`); the intrinsic sequence a joint is given is written as the order of its
//! letters reversed. Each channel (the angle about X, about Y, about Z, in degrees) is its own
//! curve, played separately, so the angles along a track are continuous
//! ([`EulerUnwrap`]: each key's triple the one of its rotation nearest the previous key's), never
//! jumping by a turn between two keys.
//!
//! **Times.** FBX 7 counts 46 186 158 000 ticks a second; frame `k` at the rate `n/d` is tick
//! `k·46186158000·d/n` rounded to the nearest integer (half away from zero), computed exactly in
//! integers (at 30000/1001 ticks are not whole numbers of frames: frame 1 is 1541078138.6,
//! written 1541078139).

use super::binary::{self, CREATION_TIME, FILE_ID, Node, Prop};
use crate::usd::write::Stage;
use glam::{DQuat, DVec3};
use inbetween::clock::Fps;
use inbetween::rotation::EulerSeq;
use inbetween::rotation::unwrap::EulerUnwrap;
use inbetween::skeleton::Skeleton;
use std::io::{self, Write};

/// FBX 7's ticks per second.
pub const TICKS_PER_SECOND: i64 = 46_186_158_000;

/// The tick of frame `k` at `fps`: `k·46186158000·den/num`, rounded to the nearest integer
/// (half away from zero), exactly.
pub fn frame_tick(k: i64, fps: Fps) -> i64 {
    let n = i128::from(k) * i128::from(TICKS_PER_SECOND) * i128::from(fps.den());
    let d = i128::from(fps.num());
    let q = (2 * n.abs() + d) / (2 * d);
    let q = if n < 0 { -q } else { q };
    i64::try_from(q).unwrap_or(if n < 0 { i64::MIN } else { i64::MAX })
}

/// The tick of time `t` (seconds): a frame's exact tick ([`frame_tick`]) where `t` is within
/// 1e-9 frame periods of frame `k` (relative for large frame numbers), else `t` in ticks rounded.
pub fn time_tick(t: f64, fps: Fps) -> i64 {
    let c = t * fps.as_f64();
    let k = c.round();
    if (c - k).abs() <= 1e-9 * k.abs().max(1.0) && k.abs() < 9e15 {
        frame_tick(k as i64, fps)
    } else {
        (t * TICKS_PER_SECOND as f64).round() as i64
    }
}

/// One track's keys: ticks (increasing), a rotation at each and, for a track whose translation
/// is animated, a position at each.
#[derive(Debug, Clone, Default)]
pub struct TrackKeys {
    /// Key times in FBX ticks, increasing.
    pub ticks: Vec<i64>,
    /// The rotation at each key.
    pub rotations: Vec<DQuat>,
    /// The position at each key, when the track moves its joint.
    pub positions: Option<Vec<DVec3>>,
}

/// FBX's `RotationOrder` enum of an intrinsic sequence (`R = R_a·R_b·R_c` for letters `abc`):
/// the FBX order is the letters reversed (`ZYX` is `eEulerXYZ`, 0). `None` for a sequence that
/// is not three different axes, intrinsic.
pub fn rotation_order(seq: EulerSeq) -> Option<i32> {
    let fbx: String = seq.as_str().chars().rev().collect();
    ["XYZ", "XZY", "YZX", "YXZ", "ZXY", "ZYX"]
        .iter()
        .position(|o| *o == fbx)
        .map(|i| i as i32)
}

/// Everything a scene is written from.
pub struct Scene<'a> {
    /// The joints: names, parents, rest offsets, rotations and scales, ends, tracks.
    pub skeleton: &'a Skeleton,
    /// Each joint's intrinsic Euler sequence (three different axes, upper case).
    pub orders: &'a [EulerSeq],
    /// The rate: the scene's time mode.
    pub fps: Fps,
    /// Each track's keys (track `t` is the joint whose `track` is `t`).
    pub tracks: &'a [TrackKeys],
    /// The length unit and up axis.
    pub stage: Stage,
}

fn internal(m: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, format!("internal error: {m}"))
}

fn s(x: &str) -> Prop {
    Prop::Str(x.to_string())
}

/// A name as FBX holds it: control characters (the `\0\x01` between name and class among
/// them) become `_`.
fn clean(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_control() { '_' } else { c })
        .collect()
}

/// `P: name, type, label, flags, values…` of a `Properties70`.
fn p(name: &str, kind: &str, label: &str, flags: &str, values: Vec<Prop>) -> Node {
    let mut props = vec![s(name), s(kind), s(label), s(flags)];
    props.extend(values);
    Node::new("P", props)
}

fn p3(name: &str, v: [f64; 3]) -> Node {
    let values = v.iter().map(|&x| Prop::F64(x)).collect();
    p(name, name, "", "A", values)
}

fn p_int(name: &str, kind: &str, v: i32) -> Node {
    let label = if kind == "enum" { "" } else { "Integer" };
    p(name, kind, label, "", vec![Prop::I32(v)])
}

fn p_time(name: &str, v: i64) -> Node {
    p(name, "KTime", "Time", "", vec![Prop::I64(v)])
}

fn p_f64(name: &str, v: f64) -> Node {
    p(name, "double", "Number", "", vec![Prop::F64(v)])
}

fn props70(children: Vec<Node>) -> Node {
    Node::with("Properties70", vec![], children)
}

fn leaf(name: &'static str, v: Prop) -> Node {
    Node::new(name, vec![v])
}

/// The rotation curves' values of a track's keys in `seq`: degrees about X, Y and Z, each key's
/// triple the one nearest the previous key's ([`EulerUnwrap`]). Written as float32.
pub fn curve_degrees(seq: EulerSeq, rotations: &[DQuat]) -> Vec<[f64; 3]> {
    let mut unwrap = EulerUnwrap::new(seq);
    rotations
        .iter()
        .map(|&q| xyz_degrees(seq, unwrap.next(q)))
        .collect()
}

/// Degrees about X, Y and Z of a triple (radians) in `seq`'s letter order.
fn xyz_degrees(seq: EulerSeq, t: [f64; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (c, a) in seq.as_str().bytes().zip(t) {
        out[usize::from(c.to_ascii_uppercase() - b'X')] = a.to_degrees();
    }
    out
}

/// Writes `scene` as a binary FBX 7.4 file (see the module documentation). Errors
/// (`InvalidInput`): tracks that do not match the skeleton, keys that are not increasing or
/// not finite (internal errors), a file of 4 GiB or more.
pub fn write_fbx<W: Write>(mut out: W, scene: &Scene) -> io::Result<()> {
    let nodes = scene_nodes(scene)?;
    let bytes = binary::encode(&nodes)?;
    out.write_all(&bytes)?;
    out.flush()
}

/// The ids of the objects, in the order they are made (0 is the scene's root).
struct Ids(i64);

impl Ids {
    fn next(&mut self) -> i64 {
        self.0 += 1;
        self.0
    }
}

fn check(scene: &Scene) -> io::Result<()> {
    let sk = scene.skeleton;
    if scene.tracks.len() != sk.track_count() || scene.orders.len() != sk.joints().len() {
        return Err(internal(format!(
            "{} tracks and {} orders for a skeleton of {} tracks and {} joints",
            scene.tracks.len(),
            scene.orders.len(),
            sk.track_count(),
            sk.joints().len()
        )));
    }
    if let Some(seq) = scene.orders.iter().find(|q| rotation_order(**q).is_none()) {
        return Err(internal(format!(
            "no FBX rotation order for {}",
            seq.as_str()
        )));
    }
    for (t, k) in scene.tracks.iter().enumerate() {
        let n = k.ticks.len();
        if n == 0
            || k.rotations.len() != n
            || k.positions.as_ref().is_some_and(|p| p.len() != n)
            || k.ticks.windows(2).any(|w| w[0] >= w[1])
        {
            return Err(internal(format!(
                "track {t}: its keys are empty, not increasing, or of other counts"
            )));
        }
        let finite = k.rotations.iter().all(|q| q.is_finite())
            && k.positions.iter().flatten().all(|p| p.is_finite());
        if !finite {
            return Err(internal(format!(
                "track {t} has a value that is not finite"
            )));
        }
    }
    Ok(())
}

/// The scene's top-level nodes.
fn scene_nodes(scene: &Scene) -> io::Result<Vec<Node>> {
    check(scene)?;
    let sk = scene.skeleton;
    let first = scene.tracks.iter().map(|t| t.ticks[0]).min().unwrap_or(0);
    let last = scene
        .tracks
        .iter()
        .filter_map(|t| t.ticks.last().copied())
        .max()
        .unwrap_or(0);
    let mut ids = Ids(1_000_000);
    let mut objects = Vec::new();
    let mut links = Vec::new();
    let oo = |a: i64, b: i64| Node::new("C", vec![s("OO"), Prop::I64(a), Prop::I64(b)]);
    let op = |a: i64, b: i64, what: &str| {
        Node::new("C", vec![s("OP"), Prop::I64(a), Prop::I64(b), s(what)])
    };
    let stack = ids.next();
    let layer = ids.next();
    links.push(oo(layer, stack));
    let (mut models, mut curve_nodes, mut curves) = (0usize, 0usize, 0usize);
    let mut model_ids: Vec<i64> = Vec::with_capacity(sk.joints().len());
    for (j, joint) in sk.joints().iter().enumerate() {
        let seq = scene.orders[j];
        let keys = joint.track.map(|t| &scene.tracks[t]);
        // The rotation curves: the track's keys, else the rest rotation held.
        let angles: Vec<[f64; 3]> = match keys {
            Some(k) => curve_degrees(seq, &k.rotations),
            None => curve_degrees(seq, &[joint.rotation]),
        };
        let ticks: Vec<i64> = keys.map_or_else(|| vec![first], |k| k.ticks.clone());
        let rest_t = joint.translation;
        let translation = keys
            .and_then(|k| k.positions.as_ref())
            .map_or(rest_t, |p| p[0]);
        let id = ids.next();
        model_ids.push(id);
        let order = rotation_order(seq).unwrap_or(0);
        objects.push(model(
            id,
            &joint.name,
            Some(order),
            translation,
            angles[0],
            joint.scale,
        ));
        let attr = ids.next();
        objects.push(limb_attribute(attr, &joint.name));
        links.push(oo(attr, id));
        links.push(oo(id, joint.parent.map_or(0, |p| model_ids[p])));
        models += 1;
        // R on every joint (a joint without a track holds its rest rotation), T where moved.
        let mut channels = vec![("R", "Lcl Rotation", angles)];
        if let Some(p) = keys.and_then(|k| k.positions.as_ref()) {
            channels.push((
                "T",
                "Lcl Translation",
                p.iter().map(|v| v.to_array()).collect(),
            ));
        }
        for (short, property, values) in channels {
            let node = ids.next();
            let mut defaults = Vec::new();
            for (axis, d) in ["d|X", "d|Y", "d|Z"].into_iter().enumerate() {
                let curve = ids.next();
                let v: Vec<f32> = values.iter().map(|x| x[axis] as f32).collect();
                objects.push(anim_curve(curve, &ticks, v));
                links.push(op(curve, node, d));
                defaults.push(p(d, "Number", "", "A", vec![Prop::F64(values[0][axis])]));
                curves += 1;
            }
            objects.push(Node::with(
                "AnimationCurveNode",
                vec![
                    Prop::I64(node),
                    s(&format!("{short}\0\x01AnimCurveNode")),
                    s(""),
                ],
                vec![props70(defaults)],
            ));
            links.push(oo(node, layer));
            links.push(op(node, id, property));
            curve_nodes += 1;
        }
        // The joint's end points: children that nothing animates (an exporter's `_end`).
        for (e, end) in joint.ends.iter().enumerate() {
            let end_id = ids.next();
            let name = match e {
                0 => format!("{}_end", joint.name),
                _ => format!("{}_end{e}", joint.name),
            };
            objects.push(model(end_id, &name, None, *end, [0.0; 3], DVec3::ONE));
            let attr = ids.next();
            objects.push(limb_attribute(attr, &name));
            links.push(oo(attr, end_id));
            links.push(oo(end_id, id));
            models += 1;
        }
    }
    let span = vec![
        p_time("LocalStart", first),
        p_time("LocalStop", last),
        p_time("ReferenceStart", first),
        p_time("ReferenceStop", last),
    ];
    objects.push(Node::with(
        "AnimationStack",
        vec![Prop::I64(stack), s("Clip\0\x01AnimStack"), s("")],
        vec![props70(span)],
    ));
    objects.push(Node::new(
        "AnimationLayer",
        vec![Prop::I64(layer), s("BaseLayer\0\x01AnimLayer"), s("")],
    ));
    let counts = [
        ("GlobalSettings", 1),
        ("Model", models),
        ("NodeAttribute", models),
        ("AnimationStack", 1),
        ("AnimationLayer", 1),
        ("AnimationCurveNode", curve_nodes),
        ("AnimationCurve", curves),
    ];
    Ok(vec![
        header(),
        leaf("FileId", Prop::Raw(FILE_ID.to_vec())),
        leaf("CreationTime", s(CREATION_TIME)),
        leaf("Creator", s(&creator())),
        global_settings(scene, first, last),
        definitions(&counts),
        Node::with("Objects", vec![], objects),
        Node::with("Connections", vec![], links),
        takes(first, last),
    ])
}

fn creator() -> String {
    format!("inbetween {}", env!("CARGO_PKG_VERSION"))
}

fn header() -> Node {
    let stamp = [
        "Version",
        "Year",
        "Month",
        "Day",
        "Hour",
        "Minute",
        "Second",
        "Millisecond",
    ]
    .iter()
    .zip([1000, 1970, 1, 1, 10, 0, 0, 0])
    .map(|(n, v)| leaf(n, Prop::I32(v)))
    .collect();
    Node::with(
        "FBXHeaderExtension",
        vec![],
        vec![
            leaf("FBXHeaderVersion", Prop::I32(1003)),
            leaf("FBXVersion", Prop::I32(binary::VERSION as i32)),
            leaf("EncryptionType", Prop::I32(0)),
            Node::with("CreationTimeStamp", vec![], stamp),
            leaf("Creator", s(&creator())),
        ],
    )
}

/// FBX's `TimeMode` of a rate and the rate it stands for: the standard modes where the rate is
/// exactly theirs, else 14 (custom: `CustomFrameRate`). 30000/1001 is NTSC full frame (9).
pub fn time_mode(fps: Fps) -> i32 {
    match (fps.num(), fps.den()) {
        (120, 1) => 1,
        (100, 1) => 2,
        (60, 1) => 3,
        (50, 1) => 4,
        (48, 1) => 5,
        (30, 1) => 6,
        (30000, 1001) => 9,
        (25, 1) => 10,
        (24, 1) => 11,
        (1000, 1) => 12,
        (24000, 1001) => 13,
        (96, 1) => 15,
        (72, 1) => 16,
        (60000, 1001) => 17,
        (120000, 1001) => 18,
        _ => 14,
    }
}

fn global_settings(scene: &Scene, first: i64, last: i64) -> Node {
    // Right-handed: Y up, front +Z, X right; or Z up, front −Y, X right.
    let (up, front, front_sign) = if scene.stage.z_up {
        (2, 1, -1)
    } else {
        (1, 2, 1)
    };
    let cm = scene.stage.meters_per_unit * 100.0;
    Node::with(
        "GlobalSettings",
        vec![],
        vec![
            leaf("Version", Prop::I32(1000)),
            props70(vec![
                p_int("UpAxis", "int", up),
                p_int("UpAxisSign", "int", 1),
                p_int("FrontAxis", "int", front),
                p_int("FrontAxisSign", "int", front_sign),
                p_int("CoordAxis", "int", 0),
                p_int("CoordAxisSign", "int", 1),
                p_int("OriginalUpAxis", "int", up),
                p_int("OriginalUpAxisSign", "int", 1),
                p_f64("UnitScaleFactor", cm),
                p_f64("OriginalUnitScaleFactor", cm),
                p_int("TimeMode", "enum", time_mode(scene.fps)),
                p_time("TimeSpanStart", first),
                p_time("TimeSpanStop", last),
                p_f64("CustomFrameRate", scene.fps.as_f64()),
            ]),
        ],
    )
}

fn definitions(counts: &[(&'static str, usize)]) -> Node {
    let total: usize = counts.iter().map(|c| c.1).sum();
    let mut children = vec![
        leaf("Version", Prop::I32(100)),
        leaf("Count", Prop::I32(total as i32)),
    ];
    for &(name, n) in counts {
        children.push(Node::with(
            "ObjectType",
            vec![s(name)],
            vec![leaf("Count", Prop::I32(n as i32))],
        ));
    }
    Node::with("Definitions", vec![], children)
}

fn model(id: i64, name: &str, order: Option<i32>, t: DVec3, r: [f64; 3], sc: DVec3) -> Node {
    let mut props = Vec::new();
    if let Some(o) = order {
        // The SDK and Blender's importer apply RotationOrder only where RotationActive is set
        // (ufbx assumes it); a default-order node gets it too, so every reader agrees.
        props.push(p_int("RotationOrder", "enum", o));
        props.push(p("RotationActive", "bool", "", "", vec![Prop::I32(1)]));
    }
    props.extend([
        p_int("InheritType", "enum", 1),
        p_int("DefaultAttributeIndex", "int", 0),
        p3("Lcl Translation", t.to_array()),
        p3("Lcl Rotation", r),
        p3("Lcl Scaling", sc.to_array()),
    ]);
    Node::with(
        "Model",
        vec![
            Prop::I64(id),
            s(&format!("{}\0\x01Model", clean(name))),
            s("LimbNode"),
        ],
        vec![leaf("Version", Prop::I32(232)), props70(props)],
    )
}

fn limb_attribute(id: i64, name: &str) -> Node {
    Node::with(
        "NodeAttribute",
        vec![
            Prop::I64(id),
            s(&format!("{}\0\x01NodeAttribute", clean(name))),
            s("LimbNode"),
        ],
        vec![leaf("TypeFlags", s("Skeleton"))],
    )
}

/// A curve of linear keys. The key attributes are those Blender's exporter writes: linear
/// interpolation (bit 2; the tangent bits 8, 13 and 14 do not apply to linear keys), the
/// default weights, one attribute for every key.
fn anim_curve(id: i64, ticks: &[i64], values: Vec<f32>) -> Node {
    let n = ticks.len() as i32;
    Node::with(
        "AnimationCurve",
        vec![Prop::I64(id), s("\0\x01AnimCurve"), s("")],
        vec![
            leaf("Default", Prop::F64(f64::from(values[0]))),
            leaf("KeyVer", Prop::I32(4008)),
            leaf("KeyTime", Prop::I64s(ticks.to_vec())),
            leaf("KeyValueFloat", Prop::F32s(values)),
            leaf(
                "KeyAttrFlags",
                Prop::I32s(vec![(1 << 2) | (1 << 8) | (1 << 13) | (1 << 14)]),
            ),
            leaf(
                "KeyAttrDataFloat",
                Prop::F32s(vec![0.0, 0.0, f32::from_bits(218_434_821), 0.0]),
            ),
            leaf("KeyAttrRefCount", Prop::I32s(vec![n])),
        ],
    )
}

fn takes(first: i64, last: i64) -> Node {
    let span = || vec![Prop::I64(first), Prop::I64(last)];
    Node::with(
        "Takes",
        vec![],
        vec![
            leaf("Current", s("Clip")),
            Node::with(
                "Take",
                vec![s("Clip")],
                vec![
                    leaf("FileName", s("Clip.tak")),
                    Node::new("LocalTime", span()),
                    Node::new("ReferenceTime", span()),
                ],
            ),
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ticks_are_exact_and_rounded_to_the_nearest() {
        let ntsc = Fps::new(30000, 1001).unwrap();
        // 46186158000 · 1001 / 30000 = 1541078138.6 ticks a frame.
        assert_eq!(frame_tick(1, ntsc), 1_541_078_139);
        assert_eq!(frame_tick(2, ntsc), 3_082_156_277);
        assert_eq!(frame_tick(5, ntsc), 7_705_390_693);
        assert_eq!(frame_tick(-1, ntsc), -1_541_078_139);
        assert_eq!(frame_tick(30000, ntsc), 1001 * TICKS_PER_SECOND);
        let f24 = Fps::new(24, 1).unwrap();
        assert_eq!(frame_tick(1, f24), 1_924_423_250);
        assert_eq!(time_tick(1.0 / 24.0, f24), 1_924_423_250);
        assert_eq!(time_tick(0.5 / 24.0, f24), 962_211_625);
    }

    #[test]
    fn rotation_orders_reverse_the_intrinsic_letters() {
        let order = |s: &str| rotation_order(EulerSeq::parse(s).unwrap());
        assert_eq!(order("ZYX"), Some(0));
        assert_eq!(order("YZX"), Some(1));
        assert_eq!(order("XZY"), Some(2));
        assert_eq!(order("ZXY"), Some(3));
        assert_eq!(order("YXZ"), Some(4));
        assert_eq!(order("XYZ"), Some(5));
        assert_eq!(order("ZXZ"), None);
    }

    /// The `KeyValueFloat` arrays of the scene's curves, in the order written.
    fn curve_values(nodes: &[Node]) -> Vec<Vec<f32>> {
        let objects = nodes.iter().find(|n| n.name == "Objects").unwrap();
        objects
            .children
            .iter()
            .filter(|n| n.name == "AnimationCurve")
            .map(|c| {
                let v = c
                    .children
                    .iter()
                    .find(|k| k.name == "KeyValueFloat")
                    .unwrap();
                match &v.props[0] {
                    Prop::F32s(v) => v.clone(),
                    p => panic!("{p:?}"),
                }
            })
            .collect()
    }

    #[test]
    fn euler_channels_are_continuous_through_half_a_turn() {
        use inbetween::skeleton::Joint;
        // A spin about Y from 0 to 3 turns in steps of 30°, past ±180° six times, on a joint in
        // BVH's `Zrotation Xrotation Yrotation` (FBX eEulerYXZ).
        let skeleton =
            Skeleton::new(vec![Joint::new("Root", None, DVec3::ZERO).with_track(0)]).unwrap();
        let fps = Fps::new(30, 1).unwrap();
        let n = 37;
        let keys = TrackKeys {
            ticks: (0..n).map(|k| frame_tick(k, fps)).collect(),
            rotations: (0..n)
                .map(|k| DQuat::from_rotation_y((30.0 * k as f64).to_radians()))
                .collect(),
            positions: None,
        };
        let orders = [EulerSeq::parse("ZXY").unwrap()];
        let scene = Scene {
            skeleton: &skeleton,
            orders: &orders,
            fps,
            tracks: std::slice::from_ref(&keys),
            stage: Stage {
                meters_per_unit: 0.01,
                z_up: false,
            },
        };
        let nodes = scene_nodes(&scene).unwrap();
        let [x, y, z] = <[Vec<f32>; 3]>::try_from(curve_values(&nodes)).unwrap();
        for k in 0..n as usize {
            assert!(
                x[k].abs() < 1e-4 && z[k].abs() < 1e-4,
                "key {k}: {} {}",
                x[k],
                z[k]
            );
            // Unwrapped: 30° a key, never a jump of a turn.
            assert!((y[k] - 30.0 * k as f32).abs() < 1e-3, "key {k}: {}", y[k]);
        }
        // The node's order: eEulerYXZ (3).
        let model = nodes
            .iter()
            .find(|n| n.name == "Objects")
            .unwrap()
            .children
            .iter()
            .find(|n| n.name == "Model")
            .unwrap();
        let props = &model.children[1].children;
        assert_eq!(props[0].props[0], Prop::Str("RotationOrder".into()));
        assert_eq!(props[0].props[4], Prop::I32(3));
    }

    #[test]
    fn time_modes_are_the_exact_rates() {
        let mode = |n, d| time_mode(Fps::new(n, d).unwrap());
        assert_eq!((mode(24, 1), mode(30, 1), mode(30000, 1001)), (11, 6, 9));
        assert_eq!((mode(25, 1), mode(60, 1), mode(50, 1)), (10, 3, 4));
        assert_eq!((mode(48, 1), mode(120, 1), mode(12, 1)), (5, 1, 14));
        assert_eq!(mode(25, 2), 14);
    }
}
