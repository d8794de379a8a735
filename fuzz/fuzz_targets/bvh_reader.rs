//! The BVH reader on arbitrary text: the hierarchy and motion are parsed and checked, the
//! joints turned into tracks, and the tracks baked with a scheme chosen by the first byte at the
//! file's own rate. Nothing may panic; every frame is finite and unit, every position finite.
#![no_main]

#[path = "asset_common.rs"]
mod common;

use inbetween::Scheme;
use inbetween_io::{Format, ReadOptions, read_document};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if data.is_empty() {
        return;
    }
    let (o, rest) = data.split_at(1);
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let Ok(doc) = read_document(text, "fuzz.bvh", Format::Bvh, &ReadOptions::default()) else {
        return;
    };
    let scheme = [Scheme::Slerp, Scheme::Bezier, Scheme::Hermite, Scheme::Squad][o[0] as usize % 4];
    let fps = doc.fps.unwrap_or(inbetween::Fps::DEFAULT);
    common::bake_document(&doc, fps, scheme, 20_000.0);
});
