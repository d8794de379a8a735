//! The JSON reader on arbitrary bytes: a document or an error, never a panic; every key finite
//! and unit.
#![no_main]

use inbetween_io::ReadOptions;
use inbetween_io::read::json;
use inbetween::rotation::QuatOrder;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let opts = ReadOptions {
        quat_order: if sel & 1 == 0 { QuatOrder::Wxyz } else { QuatOrder::Xyzw },
        ..Default::default()
    };
    if let Ok(doc) = json::read(text, "fuzz.json", &opts) {
        for t in &doc.tracks {
            for k in &t.keys {
                assert!(k.rot.is_finite() && (k.rot.length() - 1.0).abs() < 1e-9);
            }
            if let Some(v) = t.start_velocity {
                assert!(v.is_finite());
            }
        }
    }
});
