//! The glTF reader on arbitrary bytes (a `.gltf` JSON document or a `.glb` container): the
//! asset is parsed and checked, its animations read (every accessor decoded, every channel
//! validated), its channels sampled as the specification defines them, its rotation channels
//! turned into tracks (keys and frames modes) and baked. Nothing may panic; every sample and
//! frame is finite and unit. External files are never read (no folder is given).
#![no_main]

#[path = "asset_common.rs"]
mod common;

use inbetween_io::gltf::Asset;
use inbetween_io::gltf::document::{GltfClip, Mode};
use inbetween::{Fps, Scheme};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if data.is_empty() {
        return;
    }
    let (o, bytes) = data.split_at(1);
    let Ok(asset) = Asset::from_slice(bytes, "fuzz.gltf", None) else {
        return;
    };
    if let Ok(animations) = asset.animations() {
        for a in &animations {
            for ch in a.rotations() {
                let (lo, hi) = ch.span();
                for s in [lo, 0.5 * (lo + hi), hi, lo - 1.0, hi + 1.0] {
                    let q = ch.sample(s);
                    assert!(q.is_finite() && (q.length() - 1.0).abs() < 1e-6, "{q}");
                }
            }
            for ch in a.translations() {
                let (lo, hi) = ch.span();
                let p = ch.sample(0.5 * (lo + hi));
                assert!(p.is_finite(), "{p}");
            }
        }
    }
    let Ok(clip) = GltfClip::new(asset, None) else {
        return;
    };
    let fps = [Fps::DEFAULT, Fps::new(24, 1).unwrap(), Fps::new(1000, 1).unwrap()]
        [o[0] as usize % 3];
    let mode = [Mode::Frames, Mode::Keys, Mode::Sampled][(o[0] as usize / 4) % 3];
    let Ok(doc) = clip.document(fps, mode) else {
        return;
    };
    common::bake_document(&doc, fps, Scheme::Slerp, 20_000.0);
});
