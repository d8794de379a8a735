//! A real asset baked and reduced end to end: the Khronos sample model CesiumMan
//! (`fixtures/gltf/real/CesiumMan.glb`, COLLADA2GLTF, credited in fixtures/README.md): a
//! skinned figure whose one animation moves 19 joints, each by a LINEAR rotation, translation
//! and scale channel with its own time accessor of 48 keys from 1/24 s (as 0.04166662) to 2 s.
//! The expected values come from the independent numpy playback of the asset
//! (`fixtures/gltf/playback_ref.py`), the expected times from the input's accessors and the
//! 30 fps grid.

use crate::gltf::{
    asset_json, back_of, python_playback, python_vectors, untouched, unused_objects, validate,
};
use crate::support::{bin, fixtures, rot_angle, stdout_of};
use glam::{DQuat, DVec3};
use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn cesium_man() -> PathBuf {
    fixtures().join("gltf/real/CesiumMan.glb")
}

/// `f` of every item, in order, on three threads (each call runs a Python reference, about
/// half a second, most of it starting Python).
fn on_threads<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let chunk = items.len().div_ceil(3).max(1);
    std::thread::scope(|s| {
        let f = &f;
        let handles: Vec<_> = items
            .chunks(chunk)
            .map(|c| s.spawn(move || c.iter().map(f).collect::<Vec<R>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    })
}

/// The earliest and the latest time of any sampler of animation `a` (its input accessors'
/// `min` and `max`).
fn key_span(json: &Value, a: usize) -> (f64, f64) {
    let samplers = json["animations"][a]["samplers"].as_array().unwrap().iter();
    samplers.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
        let acc = &json["accessors"][s["input"].as_u64().unwrap() as usize];
        let at = |m: &str| acc[m][0].as_f64().unwrap();
        (lo.min(at("min")), hi.max(at("max")))
    })
}

/// The input accessor of each channel of animation `a`, in channel order.
fn channel_inputs(json: &Value, a: usize) -> Vec<u64> {
    let anim = &json["animations"][a];
    let channels = anim["channels"].as_array().unwrap().iter();
    channels
        .map(|c| {
            let sampler = &anim["samplers"][c["sampler"].as_u64().unwrap() as usize];
            sampler["input"].as_u64().unwrap()
        })
        .collect()
}

/// What one channel plays, as the independent reference gives it.
enum Played {
    Rotations(Vec<DQuat>),
    Vectors(Vec<DVec3>),
}

/// The independent playback of every channel of animation 0 of `asset` at `times`, in channel
/// order, or `None` without the checkers' venv.
fn reference(asset: &Path, paths: &[String], times: &[f64]) -> Option<Vec<Played>> {
    let channels: Vec<(usize, &String)> = paths.iter().enumerate().collect();
    let played = on_threads(&channels, |&(c, path)| {
        if path == "rotation" {
            python_playback(asset, 0, c, times).map(Played::Rotations)
        } else {
            python_vectors(asset, 0, c, times).map(Played::Vectors)
        }
    });
    played.into_iter().collect()
}

fn target_paths(json: &Value) -> Vec<String> {
    let channels = json["animations"][0]["channels"].as_array().unwrap().iter();
    let paths = channels.map(|c| c["target"]["path"].as_str().unwrap().to_string());
    paths.collect()
}

/// `interp CesiumMan.glb --fps 30 -o out.glb`, no `--scheme`: one time accessor for all 57
/// channels, holding the animation's first key time (1/24 s, off the 30 fps grid), the grid's
/// frames after it, and its last (2 s); every rotation, translation and scale at every one of
/// those times the independent playback of the input (slerp and lerp) to float32 — 1e-6 rad
/// (measured 4.2e-7: float32 values at float32 times), and 2 float32 units of the value's size
/// for vectors (measured 3e-8 of it); validator-clean, no unused object the input did not have
/// (the replaced samplers, accessors, views and bytes are gone), meshes and skins untouched.
#[test]
fn cesium_man_bakes_as_it_plays_on_one_time_accessor() {
    let dir = tempfile::tempdir().unwrap();
    let (src, out) = (cesium_man(), dir.path().join("out.glb"));
    stdout_of(
        bin()
            .arg("interp")
            .arg(&src)
            .args(["--fps", "30", "-o"])
            .arg(&out),
    );
    validate(&out);
    if let (Some(before), Some(after)) = (unused_objects(&src), unused_objects(&out)) {
        assert!(after.len() <= before.len(), "{after:?}, before {before:?}");
    }
    assert_eq!(untouched(&out), untouched(&src));

    let (input, written) = (asset_json(&src), asset_json(&out));
    assert_eq!(written["animations"].as_array().unwrap().len(), 1);
    // The input has a time accessor per channel; the bake one for all.
    let before: BTreeSet<u64> = channel_inputs(&input, 0).into_iter().collect();
    let after: BTreeSet<u64> = channel_inputs(&written, 0).into_iter().collect();
    assert_eq!((before.len(), channel_inputs(&written, 0).len()), (19, 57));
    assert_eq!(after.len(), 1, "time accessors {after:?}");
    let paths = target_paths(&written);
    assert_eq!(paths, target_paths(&input));

    // The times: the first and last key times, the 30 fps frames strictly between.
    let (first, last) = key_span(&input, 0);
    assert_eq!((first as f32, last as f32), (0.04166662, 2.0));
    let mut want = vec![first as f32];
    let grid = (1..=60).map(|k| k as f64 / 30.0);
    want.extend(grid.filter(|&t| t > first && t < last).map(|t| t as f32));
    want.push(last as f32);
    let back = back_of(&out);
    let anim = &back.animations().unwrap()[0];
    let times_f32 = anim.rotations()[0].times_f32().to_vec();
    assert_eq!(times_f32, want);
    let times: Vec<f64> = times_f32.iter().map(|&t| t as f64).collect();

    let Some(played) = reference(&src, &paths, &times) else {
        return;
    };
    let (mut worst_rot, mut worst_vec) = (0.0f64, 0.0f64);
    for (c, want) in played.iter().enumerate() {
        let what = format!("channel {c} ({})", paths[c]);
        match want {
            Played::Rotations(want) => {
                let got = anim.rotations().iter().find(|g| g.index() == c).unwrap();
                assert_eq!(got.times_f32(), times_f32.as_slice(), "{what}");
                for (k, (g, w)) in got.values().iter().zip(want).enumerate() {
                    let d = rot_angle(g.normalize(), *w);
                    worst_rot = worst_rot.max(d);
                    assert!(d < 1e-6, "{what} at {} s: {d:e} rad", times[k]);
                }
            }
            Played::Vectors(want) => {
                let vectors = anim.translations().iter().chain(anim.scales());
                let got = vectors.clone().find(|g| g.index() == c).unwrap();
                assert_eq!(got.times_f32(), times_f32.as_slice(), "{what}");
                for (k, (g, w)) in got.values().iter().zip(want).enumerate() {
                    let size = 1.0 + w.abs().max_element();
                    let d = (*g - *w).abs().max_element() / size;
                    worst_vec = worst_vec.max(d);
                    assert!(
                        d <= 2.0 * f32::EPSILON as f64,
                        "{what} at {} s: {g} against {w}",
                        times[k]
                    );
                }
            }
        }
    }
    eprintln!("CesiumMan at 30 fps: {worst_rot:e} rad, vectors {worst_vec:e} of their size");
}

/// `reduce CesiumMan.glb --tolerance 0.5 -o small.glb` (slerp keys, the LINEAR sampler's): a
/// file smaller than the input, validator-clean, no unused object the input did not have,
/// meshes and skins untouched; and, played by the independent reference, every rotation of the
/// reduced file within 0.5° (and float32) of the input's at each of the input's keys.
#[test]
fn cesium_man_reduces_to_a_smaller_valid_glb() {
    let dir = tempfile::tempdir().unwrap();
    let (src, small) = (cesium_man(), dir.path().join("small.glb"));
    stdout_of(
        bin()
            .arg("reduce")
            .arg(&src)
            .args(["--tolerance", "0.5", "-o"])
            .arg(&small),
    );
    let size = |p: &Path| std::fs::metadata(p).unwrap().len();
    assert!(
        size(&small) < size(&src),
        "{} bytes from {}",
        size(&small),
        size(&src)
    );
    validate(&small);
    if let (Some(before), Some(after)) = (unused_objects(&src), unused_objects(&small)) {
        assert!(after.len() <= before.len(), "{after:?}, before {before:?}");
    }
    assert_eq!(untouched(&small), untouched(&src));

    let input = back_of(&src);
    let keys: Vec<f64> = input.animations().unwrap()[0].rotations()[0]
        .times_f32()
        .iter()
        .map(|&t| t as f64)
        .collect();
    let paths = target_paths(&asset_json(&src));
    assert_eq!(paths, target_paths(&asset_json(&small)));
    let rotation_channels: Vec<usize> = (0..paths.len())
        .filter(|&c| paths[c] == "rotation")
        .collect();
    assert_eq!(rotation_channels.len(), 19);
    let pairs = on_threads(&rotation_channels, |&c| {
        let before = python_playback(&src, 0, c, &keys)?;
        let after = python_playback(&small, 0, c, &keys)?;
        Some((c, before, after))
    });
    let tol = 0.5f64.to_radians() + 1e-6;
    let mut worst = 0.0f64;
    for (c, before, after) in pairs.into_iter().flatten() {
        for (k, (b, a)) in before.iter().zip(&after).enumerate() {
            let d = rot_angle(*a, *b);
            worst = worst.max(d);
            assert!(d <= tol, "channel {c} at key {k}: {}°", d.to_degrees());
        }
    }
    eprintln!(
        "CesiumMan reduced at 0.5°: {} bytes from {}, worst {}°",
        size(&small),
        size(&src),
        worst.to_degrees()
    );
}
