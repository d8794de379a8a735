//! USD input (`.usda` text, `.usdc` crate, `.usdz` package): a UsdSkel `Skeleton`'s bound `SkelAnimation` as tracks (docs/spec.md §3, *USD
//! input*). Each joint the animation lists is a track named by its joint's full path
//! (`Hips/Spine/LeftArm`, unique in the Skeleton); its keys are the animation's time samples — a time code is a frame number at
//! `timeCodesPerSecond` — and its translations the `translations` samples. Where rotations and
//! translations are sampled at different times, the keys are at every time either has one, the
//! other attribute evaluated there as USD does (slerp, linear, held beyond its ends). The
//! Skeleton's joints and `restTransforms` give the hierarchy for world-space measures and USD
//! output.

use super::binary;
use super::text::{Layer, Prim, Property, Value, parse};
use crate::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use glam::{DMat4, DQuat, DVec3, DVec4};
use inbetween::clock::Fps;
use inbetween::error::{InputError, InputResult};
use inbetween::skeleton::{Joint, Skeleton};
use std::collections::HashMap;
use std::sync::Arc;

/// USD's default `timeCodesPerSecond` when a layer gives neither it nor `framesPerSecond`.
pub(crate) const DEFAULT_TIME_CODES_PER_SECOND: f64 = 24.0;

/// Reads `.usda` text into a document (see the module documentation).
pub fn read(text: &str, source: &str) -> InputResult<Document> {
    document(&parse(text, source)?, source)
}

/// Reads a USD layer of any syntax into a document: a usdc crate (`PXR-USDC`), a usdz package
/// (a zip: its root layer, the first entry, read as usdc or usda), else `.usda` text. Messages
/// about a package's root layer name it as `clip.usdz[clip.usdc]`; the document's source stays
/// `source`.
pub fn read_bytes(bytes: &[u8], source: &str) -> InputResult<Document> {
    if binary::is_zip(bytes) {
        let (name, root) = binary::package_root(bytes, source)?;
        let inner = format!("{source}[{}]", inbetween::error::shorten(&name));
        if binary::is_zip(&root) {
            return Err(InputError::new(format!(
                "{inner}: a usdz package inside a usdz package is not read"
            )));
        }
        let mut doc = read_bytes(&root, &inner)?;
        doc.source = source.to_string();
        return Ok(doc);
    }
    if binary::is_crate(bytes) {
        return document(&binary::read_crate(bytes, source)?, source);
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        InputError::new(format!(
            "{source}: expected a USD layer (usda text, a usdc crate or a usdz package), found \
             an invalid UTF-8 byte at offset {}",
            e.valid_up_to()
        ))
    })?;
    read(text, source)
}

/// Where a prim or property is: `file:line` in text, `file` in a binary layer (line 0), whose
/// messages name the field instead.
fn place(source: &str, line: usize) -> String {
    if line == 0 {
        source.to_string()
    } else {
        format!("{source}:{line}")
    }
}

/// A parsed layer (of either syntax) as a document.
fn document(layer: &Layer, source: &str) -> InputResult<Document> {
    let at =
        |prim: &Prim, prop: Option<&Property>| place(source, prop.map_or(prim.line, |p| p.line));
    // A Skeleton's animation: its own skel:animationSource, else its nearest ancestor's (a
    // SkelRoot's binding is inherited, as UsdSkel resolves it).
    let binding = |skel: usize| -> Option<(usize, &Property)> {
        let mut at = Some(skel);
        while let Some(k) = at {
            let prim = &layer.prims[k];
            if let Some(rel) = prim.property("skel:animationSource") {
                return Some((k, rel));
            }
            at = prim.parent;
        }
        None
    };
    let (skeleton, (bound_at, source_rel)) = layer
        .prims
        .iter()
        .enumerate()
        .filter(|(_, p)| p.type_name == "Skeleton")
        .find_map(|(i, p)| binding(i).map(|b| (p, b)))
        .ok_or_else(|| {
            InputError::new(format!(
                "{source}: no Skeleton with an animation (skel:animationSource) in the layer"
            ))
        })?;
    let target = match &source_rel.value {
        Some(Value::Path(p)) => p.clone(),
        Some(Value::List(v)) if v.len() == 1 => match &v[0] {
            Value::Path(p) => p.clone(),
            _ => String::new(),
        },
        _ => String::new(),
    };
    let target = if target.starts_with('/') {
        target
    } else {
        format!("{}/{target}", layer.path(bound_at))
    };
    let anim = layer
        .find(&target)
        .map(|i| &layer.prims[i])
        .filter(|p| p.type_name == "SkelAnimation")
        .ok_or_else(|| {
            InputError::new(format!(
                "{}: skel:animationSource: no SkelAnimation at <{}>",
                at(skeleton, Some(source_rel)),
                inbetween::error::shorten(&target)
            ))
        })?;
    let skel_joints = tokens(skeleton, "joints", source)?;
    let anim_joints = tokens(anim, "joints", source)?;
    let rate = layer
        .number("timeCodesPerSecond")
        .or_else(|| layer.number("framesPerSecond"))
        .unwrap_or(DEFAULT_TIME_CODES_PER_SECOND);
    let fps = exact_rate(rate)
        .map_err(|e| InputError::new(format!("{source}: timeCodesPerSecond: {}", e.message())))?;

    // The hierarchy: parents from the joint paths, rest poses from restTransforms.
    let rest = match skeleton.property("restTransforms") {
        Some(p) => matrices(p, skel_joints.len(), source)?,
        None => vec![DMat4::IDENTITY; skel_joints.len()],
    };
    // Joints by path: a hash map, so that finding parents and the animation's joints is
    // linear in the joints.
    let mut index_of: HashMap<&str, usize> = HashMap::with_capacity(skel_joints.len());
    let mut joints: Vec<Joint> = Vec::with_capacity(skel_joints.len());
    for (i, path) in skel_joints.iter().enumerate() {
        if let Some(&first) = index_of.get(path.as_str()) {
            return Err(InputError::new(format!(
                "{}: joints[{first}] and joints[{i}] are both \"{}\": a joint path is listed once",
                at(skeleton, skeleton.property("joints")),
                inbetween::error::shorten(path)
            )));
        }
        let parent = path
            .rsplit_once('/')
            .and_then(|(head, _)| index_of.get(head).copied());
        if path.contains('/') && parent.is_none() {
            return Err(InputError::new(format!(
                "{}: joints[{i}] \"{}\": its parent is not listed before it",
                at(skeleton, skeleton.property("joints")),
                inbetween::error::shorten(path)
            )));
        }
        index_of.insert(path, i);
        let (scale, rotation, translation) = rest[i].to_scale_rotation_translation();
        // The joint's full path is its name: two joints `arm/hand` and `leg/hand` stay two.
        let mut j = Joint::new(path.as_str(), parent, translation);
        j.rotation = rotation.normalize();
        j.scale = scale;
        joints.push(j);
    }

    // The samples.
    let rot = anim.property("rotations");
    let tra = anim.property("translations");
    let rotations = samples(rot, anim_joints.len(), 4, source)?;
    let translations = samples(tra, anim_joints.len(), 3, source)?;
    let mut codes: Vec<f64> = rotations
        .iter()
        .chain(&translations)
        .map(|(c, _)| *c)
        .collect();
    codes.sort_by(f64::total_cmp);
    codes.dedup();
    if rotations.is_empty() {
        return Err(InputError::new(format!(
            "{}: the SkelAnimation has no rotations",
            at(anim, rot)
        )));
    }
    let mut tracks = Vec::with_capacity(anim_joints.len());
    for (k, path) in anim_joints.iter().enumerate() {
        let Some(&j) = index_of.get(path.as_str()) else {
            return Err(InputError::new(format!(
                "{}: joints[{k}] \"{}\" is not a joint of the Skeleton",
                at(anim, anim.property("joints")),
                inbetween::error::shorten(path)
            )));
        };
        joints[j].track = Some(tracks.len());
        let mut track = DocTrack {
            name: Some(joints[j].name.clone()),
            keys: Vec::with_capacity(codes.len()),
            start_velocity: None,
            end_velocity: None,
            origin: KeyOrigin::Frames,
            euler: None,
            velocities: Vec::new(),
            tcb: Vec::new(),
            translations: Vec::new(),
        };
        for &c in &codes {
            let q = at_code(&rotations, c, k, 4, |a, b, u| {
                let qa = quat(a);
                let qb = quat(b);
                let q = qa.slerp(qb, u);
                vec![q.w, q.x, q.y, q.z]
            });
            let q = quat(&q);
            if !(q.is_finite() && q.length() > 1e-6) {
                return Err(InputError::new(format!(
                    "{}: joint \"{}\" at time code {c}: expected a rotation, found ({}, {}, {}, {})",
                    at(anim, rot),
                    inbetween::error::shorten(path),
                    q.w,
                    q.x,
                    q.y,
                    q.z
                )));
            }
            track.keys.push(Key {
                when: KeyTime::Frame(c),
                rot: q.normalize(),
            });
            if !translations.is_empty() {
                let p = at_code(&translations, c, k, 3, |a, b, u| {
                    a.iter().zip(b).map(|(x, y)| x + (y - x) * u).collect()
                });
                track.translations.push(Some(DVec3::new(p[0], p[1], p[2])));
            }
        }
        tracks.push(track);
    }
    // Tracks in the skeleton's joint order (parents first), as every skeleton's are.
    let mut tracks: Vec<Option<DocTrack>> = tracks.into_iter().map(Some).collect();
    let mut sorted = Vec::with_capacity(tracks.len());
    for joint in &mut joints {
        if let Some(t) = joint.track {
            joint.track = Some(sorted.len());
            sorted.push(tracks[t].take().expect("one joint per animation joint"));
        }
    }
    let hierarchy = Skeleton::new(joints)
        .map_err(|e| InputError::new(format!("{source}: the Skeleton: {}", e.message())))?;
    let unit = layer
        .number("metersPerUnit")
        .filter(|u| u.is_finite() && *u > 0.0);
    Ok(Document {
        fps: Some(fps),
        tracks: sorted,
        named_tracks: true,
        hierarchy: Some(Arc::new(hierarchy)),
        unit_meters: Some(unit.unwrap_or(0.01)),
        z_up: Some(layer.word("upAxis").is_some_and(|a| a == "Z")),
        ..Document::new(source.to_string())
    })
}

/// A `timeCodesPerSecond` as an exact rate: `n` or `n/1001` where it is one (`29.97002997002997`
/// is 30000/1001), else a standard rate within 1e-4 relative (BVH's rule for a rounded rate:
/// Blender writes 30.000030398399637 for a scene at 30/0.999999), else the shortest decimal of
/// the double.
fn exact_rate(x: f64) -> InputResult<Fps> {
    for den in [1u64, 1001] {
        let n = (x * den as f64).round();
        if n >= 1.0 && (n / den as f64 - x).abs() <= 1e-12 * x {
            return Fps::new(n as u64, den);
        }
    }
    if let Some(fps) = crate::bvh::rate::nearest_standard(x) {
        return Ok(fps);
    }
    Fps::from_f64(x)
}

/// A prim's `token[]` property as strings.
fn tokens(prim: &Prim, name: &str, source: &str) -> InputResult<Vec<String>> {
    let prop = prim.property(name).ok_or_else(|| {
        InputError::new(format!(
            "{}: the {} has no {name}",
            place(source, prim.line),
            prim.type_name
        ))
    })?;
    match &prop.value {
        Some(Value::List(items)) => items
            .iter()
            .enumerate()
            .map(|(i, v)| match v {
                Value::Str(s) => Ok(s.clone()),
                _ => Err(InputError::new(format!(
                    "{}: {name}[{i}]: expected a quoted token",
                    place(source, prop.line)
                ))),
            })
            .collect(),
        _ => Err(InputError::new(format!(
            "{}: {name}: expected a list of tokens",
            place(source, prop.line)
        ))),
    }
}

/// Numbers of a value (a number or a tuple of numbers), flattened.
fn numbers(v: &Value, out: &mut Vec<f64>) -> bool {
    match v {
        Value::Num(x) => {
            out.push(*x);
            true
        }
        Value::Tuple(items) => items.iter().all(|i| numbers(i, out)),
        Value::Numbers(xs) => {
            out.extend_from_slice(xs);
            true
        }
        _ => false,
    }
}

/// A `matrix4d[]` of `n` matrices (rows, the translation last: USD's row vectors).
fn matrices(prop: &Property, n: usize, source: &str) -> InputResult<Vec<DMat4>> {
    let bad = |what: &str| {
        InputError::new(format!(
            "{}: {}: {what}",
            place(source, prop.line),
            prop.name
        ))
    };
    let Some(Value::List(items)) = &prop.value else {
        return Err(bad("expected a list of matrices"));
    };
    if items.len() != n {
        return Err(bad(&format!("{} matrices for {n} joints", items.len())));
    }
    items
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let mut v = Vec::with_capacity(16);
            if !numbers(m, &mut v) || v.len() != 16 || v.iter().any(|x| !x.is_finite()) {
                return Err(bad(&format!(
                    "[{i}]: expected a matrix of 16 finite numbers"
                )));
            }
            let row = |r: usize| DVec4::new(v[4 * r], v[4 * r + 1], v[4 * r + 2], v[4 * r + 3]);
            Ok(DMat4::from_cols(row(0), row(1), row(2), row(3)))
        })
        .collect()
}

/// An attribute's samples: per time code, `n` values of `width` numbers each (rounded to float32
/// for `quatf[]` and `float3[]`, as USD reads them). Its default value counts as one sample at
/// time code 0 when it has no time samples.
fn samples(
    prop: Option<&Property>,
    n: usize,
    width: usize,
    source: &str,
) -> InputResult<Vec<(f64, Vec<f64>)>> {
    let Some(prop) = prop else {
        return Ok(Vec::new());
    };
    let list: Vec<(f64, &Value)> = match (&prop.samples, &prop.value) {
        (Some(s), _) => s.iter().map(|(c, v)| (*c, v)).collect(),
        (None, Some(v)) => vec![(0.0, v)],
        (None, None) => return Ok(Vec::new()),
    };
    let single = matches!(prop.type_name.as_str(), "quatf[]" | "float3[]");
    let mut out: Vec<(f64, Vec<f64>)> = Vec::with_capacity(list.len());
    for (code, v) in list {
        let bad = |what: String| {
            InputError::new(format!(
                "{}: {} at time code {code}: {what}",
                place(source, prop.line),
                prop.name
            ))
        };
        if !code.is_finite() {
            return Err(bad("the time code is not finite".into()));
        }
        let Value::List(items) = v else {
            return Err(bad(format!("expected a list of {n} values")));
        };
        if items.len() != n {
            return Err(bad(format!("{} values for {n} joints", items.len())));
        }
        // Joint j's numbers at values[j * width..][..width]: one allocation per time code.
        let mut values = Vec::with_capacity(n * width);
        for (j, item) in items.iter().enumerate() {
            let start = values.len();
            if !numbers(item, &mut values)
                || values.len() - start != width
                || values[start..].iter().any(|x| !x.is_finite())
            {
                return Err(bad(format!("[{j}]: expected {width} finite numbers")));
            }
            if single {
                // What USD holds: the text read as float32.
                let v = &mut values[start..];
                v.iter_mut().for_each(|x| *x = f64::from(*x as f32));
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(bad(format!("[{j}]: a value beyond float32's range")));
                }
            }
            if width == 4 {
                // A `quatd` of 1e300 (or 1e-300) is a rotation whose norm overflows (underflows)
                // float64: scaled to its largest component first, as the other readers do.
                let v = &mut values[start..];
                let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                if m > 1e150 || (m > 0.0 && m < 1e-150) {
                    v.iter_mut().for_each(|x| *x /= m);
                }
            }
        }
        out.push((code, values));
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    if out.windows(2).any(|w| w[0].0 == w[1].0) {
        return Err(InputError::new(format!(
            "{}: {}: a time code sampled twice",
            place(source, prop.line),
            prop.name
        )));
    }
    Ok(out)
}

/// Joint `k`'s value at `code`: its sample there, else `blend` of the samples around it, else
/// the nearest end's (USD holds an attribute's first and last samples beyond them).
fn at_code(
    samples: &[(f64, Vec<f64>)],
    code: f64,
    k: usize,
    width: usize,
    blend: impl Fn(&[f64], &[f64], f64) -> Vec<f64>,
) -> Vec<f64> {
    let i = samples.partition_point(|(c, _)| *c < code);
    let of = |v: &[f64]| v[k * width..][..width].to_vec();
    match (i.checked_sub(1).map(|p| &samples[p]), samples.get(i)) {
        (_, Some((c, v))) if *c == code => of(v),
        (Some((c0, v0)), Some((c1, v1))) => blend(
            &v0[k * width..][..width],
            &v1[k * width..][..width],
            (code - c0) / (c1 - c0),
        ),
        (Some((_, v)), None) | (None, Some((_, v))) => of(v),
        (None, None) => unreachable!("samples are not empty"),
    }
}

/// `(w, x, y, z)` as a quaternion.
fn quat(v: &[f64]) -> DQuat {
    DQuat::from_xyzw(v[1], v[2], v[3], v[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_are_exact() {
        assert_eq!(
            exact_rate(29.97002997002997).unwrap(),
            Fps::new(30000, 1001).unwrap()
        );
        assert_eq!(exact_rate(24.0).unwrap(), Fps::new(24, 1).unwrap());
        assert_eq!(exact_rate(12.5).unwrap(), Fps::new(25, 2).unwrap());
        // Blender's scene at 30/0.999999 (a BVH import's rate), and 1e-4 off: not snapped.
        assert_eq!(
            exact_rate(30.000030398399637).unwrap(),
            Fps::new(30, 1).unwrap()
        );
        assert_eq!(exact_rate(30.006).unwrap(), Fps::new(15003, 500).unwrap());
    }

    #[test]
    fn a_sample_missing_in_one_attribute_is_evaluated_as_usd_does() {
        let s = vec![(0.0, vec![0.0, 0.0, 0.0]), (4.0, vec![4.0, 8.0, 0.0])];
        let lerp = |a: &[f64], b: &[f64], u: f64| -> Vec<f64> {
            a.iter().zip(b).map(|(x, y)| x + (y - x) * u).collect()
        };
        assert_eq!(at_code(&s, 1.0, 0, 3, lerp), vec![1.0, 2.0, 0.0]);
        assert_eq!(at_code(&s, -1.0, 0, 3, lerp), vec![0.0, 0.0, 0.0]);
        assert_eq!(at_code(&s, 9.0, 0, 3, lerp), vec![4.0, 8.0, 0.0]);
    }
}
