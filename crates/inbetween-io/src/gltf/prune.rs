//! What a rewrite left unused, removed: the samplers no channel uses any more, the accessors
//! only they used, the buffer views only those accessors used, and the buffers only those views
//! used, every index into each list renumbered (glTF 2.0 §3.6, §3.11).
//!
//! Only objects the rewrite orphaned go: an object the input already left unused stays (the
//! output has no unused object the input did not have). Indices are renumbered where the core
//! specification puts them, and in the extensions listed in [`KNOWN_EXTENSIONS`] (those that
//! reference no accessor, view or buffer, and `EXT_mesh_gpu_instancing`'s attributes and
//! `KHR_draco_mesh_compression`'s view, which are renumbered). An asset using any other
//! extension could hold an index this module does not know of, so only its samplers are
//! pruned (channels are the only objects that name a sampler) and its accessors, views and
//! buffers are kept as they were.

use serde_json::Value;
use std::collections::HashSet;

/// Extensions whose objects hold no index of an accessor, buffer view or buffer, or only
/// indices this module renumbers; and every `KHR_materials_*`.
const KNOWN_EXTENSIONS: [&str; 12] = [
    "KHR_texture_transform",
    "KHR_lights_punctual",
    "KHR_mesh_quantization",
    "KHR_texture_basisu",
    "KHR_xmp_json_ld",
    "KHR_animation_pointer",
    "KHR_node_visibility",
    "EXT_texture_webp",
    "EXT_texture_avif",
    "EXT_lights_image_based",
    "EXT_mesh_gpu_instancing",
    "KHR_draco_mesh_compression",
];

/// The lists whose elements are renumbered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum List {
    Accessors,
    BufferViews,
    Buffers,
}

/// What [`prune`] removed, per list (old indices), for placing the buffers' bytes afterwards.
#[derive(Debug, Default)]
pub(super) struct Removed {
    /// Per buffer (old index): whether a view into it was removed.
    pub views_in: HashSet<usize>,
    /// The old index of each buffer that is kept, in order (the new index is the position).
    pub buffers_kept: Vec<usize>,
}

/// Every extension named anywhere in `v` (each key of every `extensions` object).
fn extension_names(v: &Value, out: &mut HashSet<String>) {
    match v {
        Value::Object(map) => {
            for (k, x) in map {
                if k == "extensions"
                    && let Some(ext) = x.as_object()
                {
                    out.extend(ext.keys().cloned());
                }
                extension_names(x, out);
            }
        }
        Value::Array(xs) => xs.iter().for_each(|x| extension_names(x, out)),
        _ => {}
    }
}

/// Whether every extension of `json` (named in `extensionsUsed` or used anywhere) is known.
fn known_extensions(json: &Value) -> bool {
    let mut names = HashSet::new();
    extension_names(json, &mut names);
    if let Some(used) = json.get("extensionsUsed").and_then(Value::as_array) {
        names.extend(used.iter().filter_map(Value::as_str).map(str::to_string));
    }
    names
        .iter()
        .all(|n| n.starts_with("KHR_materials_") || KNOWN_EXTENSIONS.contains(&n.as_str()))
}

fn items<'v>(json: &'v mut Value, key: &str) -> impl Iterator<Item = &'v mut Value> {
    json.get_mut(key)
        .and_then(Value::as_array_mut)
        .into_iter()
        .flatten()
}

/// Calls `f` on every value of `json` that is an index into `list`.
fn each_ref(json: &mut Value, list: List, f: &mut dyn FnMut(&mut Value)) {
    let field = |v: &mut Value, key: &str, f: &mut dyn FnMut(&mut Value)| {
        if let Some(x) = v.get_mut(key) {
            f(x);
        }
    };
    let values = |v: Option<&mut Value>, f: &mut dyn FnMut(&mut Value)| {
        if let Some(map) = v.and_then(Value::as_object_mut) {
            map.values_mut().for_each(&mut *f);
        }
    };
    match list {
        List::Accessors => {
            for mesh in items(json, "meshes") {
                for p in items(mesh, "primitives") {
                    values(p.get_mut("attributes"), f);
                    field(p, "indices", f);
                    for t in items(p, "targets") {
                        values(Some(t), f);
                    }
                }
            }
            for skin in items(json, "skins") {
                field(skin, "inverseBindMatrices", f);
            }
            for anim in items(json, "animations") {
                for s in items(anim, "samplers") {
                    field(s, "input", f);
                    field(s, "output", f);
                }
            }
            for node in items(json, "nodes") {
                let inst = node.pointer_mut("/extensions/EXT_mesh_gpu_instancing/attributes");
                values(inst, f);
            }
        }
        List::BufferViews => {
            for acc in items(json, "accessors") {
                field(acc, "bufferView", f);
                if let Some(x) = acc.pointer_mut("/sparse/indices/bufferView") {
                    f(x);
                }
                if let Some(x) = acc.pointer_mut("/sparse/values/bufferView") {
                    f(x);
                }
            }
            for image in items(json, "images") {
                field(image, "bufferView", f);
            }
            for mesh in items(json, "meshes") {
                for p in items(mesh, "primitives") {
                    if let Some(x) =
                        p.pointer_mut("/extensions/KHR_draco_mesh_compression/bufferView")
                    {
                        f(x);
                    }
                }
            }
        }
        List::Buffers => {
            for view in items(json, "bufferViews") {
                field(view, "buffer", f);
            }
        }
    }
}

fn key(list: List) -> &'static str {
    match list {
        List::Accessors => "accessors",
        List::BufferViews => "bufferViews",
        List::Buffers => "buffers",
    }
}

/// How many times each element of `list` is referenced.
fn ref_counts(json: &mut Value, list: List) -> Vec<usize> {
    let n = json
        .get(key(list))
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    let mut counts = vec![0; n];
    each_ref(json, list, &mut |v| {
        if let Some(c) = v.as_u64().and_then(|i| counts.get_mut(i as usize)) {
            *c += 1;
        }
    });
    counts
}

/// Removes the elements of `list` not in `keep` and renumbers every reference to the others.
fn remove(json: &mut Value, list: List, keep: &[bool]) {
    let mut new_index = Vec::with_capacity(keep.len());
    let mut next = 0u64;
    for &k in keep {
        new_index.push(k.then_some(next));
        next += u64::from(k);
    }
    each_ref(json, list, &mut |v| {
        if let Some(Some(n)) = v.as_u64().and_then(|i| new_index.get(i as usize)) {
            *v = Value::from(*n);
        }
    });
    if let Some(xs) = json.get_mut(key(list)).and_then(Value::as_array_mut) {
        let mut i = 0;
        xs.retain(|_| {
            i += 1;
            keep[i - 1]
        });
    }
}

/// The references of `before` (counts per element) that `after` no longer has, as the
/// elements to remove: referenced before, referenced by nothing now.
fn orphaned(before: &[usize], after: &[usize]) -> Vec<bool> {
    before
        .iter()
        .zip(after)
        .map(|(&b, &a)| b > 0 && a == 0)
        .collect()
}

/// Removes what the channels of `json` no longer use (see the module documentation), given the
/// asset's JSON as it was before its channels were repointed (`before`). `keep_buffer_0`: buffer
/// 0 stays even when unused (a `.glb`'s `BIN` chunk, which gets the new bytes).
pub(super) fn prune(before: &Value, json: &mut Value, keep_buffer_0: bool) -> Removed {
    // Samplers: per animation, those a channel used before and none uses now.
    let mut before = before.clone();
    let anims = json
        .get("animations")
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    for a in 0..anims {
        let used = |j: &Value| -> Vec<bool> {
            let anim = &j["animations"][a];
            let n = anim["samplers"].as_array().map_or(0, Vec::len);
            let mut used = vec![false; n];
            for ch in anim["channels"].as_array().into_iter().flatten() {
                if let Some(u) = ch["sampler"]
                    .as_u64()
                    .and_then(|s| used.get_mut(s as usize))
                {
                    *u = true;
                }
            }
            used
        };
        let was = used(&before);
        let now = used(json);
        let keep: Vec<bool> = now
            .iter()
            .enumerate()
            .map(|(s, &u)| u || !was.get(s).copied().unwrap_or(false))
            .collect();
        if keep.iter().all(|&k| k) {
            continue;
        }
        let mut new_index = Vec::new();
        let mut next = 0u64;
        for &k in &keep {
            new_index.push(next);
            next += u64::from(k);
        }
        let anim = &mut json["animations"][a];
        for ch in anim["channels"].as_array_mut().into_iter().flatten() {
            if let Some(s) = ch["sampler"].as_u64() {
                ch["sampler"] = Value::from(new_index[s as usize]);
            }
        }
        if let Some(list) = anim["samplers"].as_array_mut() {
            let mut i = 0;
            list.retain(|_| {
                i += 1;
                keep[i - 1]
            });
        }
    }
    let mut removed = Removed::default();
    let buffers = json
        .get("buffers")
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    removed.buffers_kept = (0..buffers).collect();
    if !known_extensions(json) {
        return removed;
    }
    // Accessors a removed sampler used and nothing uses now.
    let mut gone_acc = orphaned(
        &ref_counts(&mut before, List::Accessors),
        &ref_counts(json, List::Accessors),
    );
    gone_acc.resize(ref_counts(json, List::Accessors).len(), false);
    // The views those accessors used.
    let mut candidate_views = HashSet::new();
    if let Some(accs) = json.get("accessors").and_then(Value::as_array) {
        for (acc, _) in accs.iter().zip(&gone_acc).filter(|(_, g)| **g) {
            for ptr in [
                "/bufferView",
                "/sparse/indices/bufferView",
                "/sparse/values/bufferView",
            ] {
                candidate_views.extend(acc.pointer(ptr).and_then(Value::as_u64));
            }
        }
    }
    remove(json, List::Accessors, &not(&gone_acc));
    let counts = ref_counts(json, List::BufferViews);
    let gone_views: Vec<bool> = (0..counts.len())
        .map(|v| counts[v] == 0 && candidate_views.contains(&(v as u64)))
        .collect();
    let mut candidate_buffers = HashSet::new();
    if let Some(views) = json.get("bufferViews").and_then(Value::as_array) {
        for (view, _) in views.iter().zip(&gone_views).filter(|(_, g)| **g) {
            candidate_buffers.extend(view.get("buffer").and_then(Value::as_u64));
        }
    }
    removed.views_in = candidate_buffers.iter().map(|&b| b as usize).collect();
    remove(json, List::BufferViews, &not(&gone_views));
    let counts = ref_counts(json, List::Buffers);
    let keep_buffers: Vec<bool> = (0..counts.len())
        .map(|b| {
            counts[b] > 0 || !candidate_buffers.contains(&(b as u64)) || (keep_buffer_0 && b == 0)
        })
        .collect();
    remove(json, List::Buffers, &keep_buffers);
    removed.buffers_kept = (0..buffers).filter(|&b| keep_buffers[b]).collect();
    removed
}

fn not(xs: &[bool]) -> Vec<bool> {
    xs.iter().map(|x| !x).collect()
}

/// The bytes of `buffer` (as read: `bytes`) with only what its views still cover, each run of
/// covered bytes moved to the same offset modulo 4 it had (so every accessor keeps its
/// alignment), and the views' `byteOffset`s updated; `None` (nothing changed) when a view
/// reaches past the bytes.
pub(super) fn compact(json: &mut Value, buffer: usize, bytes: &[u8]) -> Option<Vec<u8>> {
    let mut ranges: Vec<(usize, usize)> = Vec::new();
    for view in items(json, "bufferViews") {
        if view.get("buffer").and_then(Value::as_u64) != Some(buffer as u64) {
            continue;
        }
        let start = view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
        let len = view.get("byteLength").and_then(Value::as_u64)? as usize;
        let end = start.checked_add(len).filter(|&e| e <= bytes.len())?;
        ranges.push((start, end));
    }
    ranges.sort_unstable();
    // Overlapping or touching views share one run.
    let mut runs: Vec<(usize, usize, usize)> = Vec::new(); // (old start, old end, new start)
    let mut out = Vec::new();
    for (s, e) in ranges {
        if let Some(last) = runs.last_mut()
            && s <= last.1
        {
            if e > last.1 {
                out.extend_from_slice(&bytes[last.1..e]);
                last.1 = e;
            }
            continue;
        }
        while out.len() % 4 != s % 4 {
            out.push(0);
        }
        runs.push((s, e, out.len()));
        out.extend_from_slice(&bytes[s..e]);
    }
    for view in items(json, "bufferViews") {
        if view.get("buffer").and_then(Value::as_u64) != Some(buffer as u64) {
            continue;
        }
        let start = view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
        let run = runs.iter().rfind(|r| r.0 <= start)?;
        view["byteOffset"] = Value::from(run.2 + (start - run.0));
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn asset() -> Value {
        // Two samplers on accessors 1..=4 (times shared), a mesh on accessor 0, views 0..=2
        // (view 2 backs accessors 3 and 4), buffer 1 only for view 2.
        json!({
            "asset": {"version": "2.0"},
            "buffers": [{"byteLength": 24}, {"byteLength": 8}],
            "bufferViews": [
                {"buffer": 0, "byteLength": 4},
                {"buffer": 0, "byteOffset": 6, "byteLength": 10},
                {"buffer": 1, "byteLength": 8},
            ],
            "accessors": [
                {"bufferView": 0}, {"bufferView": 1}, {"bufferView": 1, "byteOffset": 4},
                {"bufferView": 2}, {"bufferView": 2}, {"bufferView": 0},
            ],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
            "animations": [{
                "samplers": [{"input": 1, "output": 2}, {"input": 3, "output": 4}],
                "channels": [
                    {"sampler": 0, "target": {"node": 0, "path": "rotation"}},
                    {"sampler": 1, "target": {"node": 0, "path": "translation"}},
                ],
            }],
        })
    }

    #[test]
    fn orphans_go_and_indices_follow() {
        let before = asset();
        let mut after = before.clone();
        // Channel 1 repointed to a new sampler on the mesh's accessor: sampler 1, accessors
        // 3 and 4, view 2 and buffer 1 are orphaned; accessor 5 was unused before and stays.
        after["animations"][0]["samplers"]
            .as_array_mut()
            .unwrap()
            .push(json!({"input": 1, "output": 0}));
        after["animations"][0]["channels"][1]["sampler"] = json!(2);
        let removed = prune(&before, &mut after, false);
        assert_eq!(
            after["animations"][0]["samplers"].as_array().unwrap().len(),
            2
        );
        assert_eq!(after["animations"][0]["channels"][1]["sampler"], json!(1));
        assert_eq!(after["accessors"].as_array().unwrap().len(), 4);
        assert_eq!(after["accessors"][3], json!({"bufferView": 0}));
        assert_eq!(
            after["animations"][0]["samplers"][0],
            json!({"input": 1, "output": 2})
        );
        assert_eq!(after["bufferViews"].as_array().unwrap().len(), 2);
        assert_eq!(after["buffers"].as_array().unwrap().len(), 1);
        assert_eq!(removed.buffers_kept, vec![0]);
        assert!(removed.views_in.contains(&1));
    }

    #[test]
    fn unknown_extensions_keep_accessors() {
        let mut before = asset();
        before["extensionsUsed"] = json!(["EXT_meshopt_compression"]);
        let mut after = before.clone();
        after["animations"][0]["channels"][1]["sampler"] = json!(0);
        prune(&before, &mut after, false);
        assert_eq!(
            after["animations"][0]["samplers"].as_array().unwrap().len(),
            1
        );
        assert_eq!(after["accessors"].as_array().unwrap().len(), 6);
        assert_eq!(after["buffers"].as_array().unwrap().len(), 2);
    }

    #[test]
    fn compaction_keeps_alignment_and_overlaps() {
        let mut j = json!({"bufferViews": [
            {"buffer": 0, "byteOffset": 9, "byteLength": 3},
            {"buffer": 0, "byteOffset": 20, "byteLength": 4},
            {"buffer": 0, "byteOffset": 22, "byteLength": 6},
            {"buffer": 1, "byteOffset": 0, "byteLength": 4},
        ]});
        let bytes: Vec<u8> = (0..32).collect();
        let out = compact(&mut j, 0, &bytes).unwrap();
        // Run [9, 12) at 1 (9 mod 4), run [20, 28) at 4.
        assert_eq!(out, [0, 9, 10, 11, 20, 21, 22, 23, 24, 25, 26, 27]);
        assert_eq!(j["bufferViews"][0]["byteOffset"], json!(1));
        assert_eq!(j["bufferViews"][1]["byteOffset"], json!(4));
        assert_eq!(j["bufferViews"][2]["byteOffset"], json!(6));
        assert_eq!(j["bufferViews"][3]["byteOffset"], json!(0));
        j["bufferViews"][0]["byteLength"] = json!(40);
        assert_eq!(compact(&mut j, 0, &bytes), None);
    }
}
