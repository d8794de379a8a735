//! The CSV reader on arbitrary bytes: it must return a document or an error, never panic.
#![no_main]

use inbetween_io::ReadOptions;
use inbetween_io::read::csv;
use inbetween::rotation::{AngleUnit, Repr};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let from = match sel % 4 {
        0 => None,
        1 => Some(Repr::parse("euler:ZYX").unwrap()),
        2 => Some(Repr::Matrix),
        _ => Some(Repr::AxisAngle),
    };
    let opts = ReadOptions {
        from,
        angles: if sel & 4 == 0 { AngleUnit::Deg } else { AngleUnit::Rad },
        ..Default::default()
    };
    if let Ok(doc) = csv::read(text, "fuzz.csv", &opts) {
        for t in &doc.tracks {
            for k in &t.keys {
                assert!(k.rot.is_finite() && (k.rot.length() - 1.0).abs() < 1e-9);
            }
        }
    }
});
