//! Binary USD input (`.usdc`, `.usdz`, `.usd`): each usdc and usdz twin of a `.usda` fixture,
//! authored by usd-core (`fixtures/usd/make_binary.py`) or exported by Blender
//! (`fixtures/usd/blender_export.py`), reads to the same keys as its `.usda`; Blender's three
//! exports read to the motion usd-core evaluates in them (`fixtures/usd/usd_samples.py`:
//! UsdSkel's own reading); a damaged file is an input error naming it, nothing written.

use crate::support::{bin, checker_python, fixtures, python_json, stdout_of};
use serde_json::Value;
use std::path::Path;

/// `convert FILE --to quat --output-format json [args]`, parsed.
fn keys(path: &Path, args: &[&str]) -> String {
    stdout_of(
        bin()
            .args(["convert", "--to", "quat", "--output-format", "json"])
            .args(args)
            .arg(path),
    )
}

#[test]
fn usdc_and_usdz_twins_read_as_their_usda() {
    let dir = fixtures().join("usd");
    let pairs = [
        ("skel_closed_24.usdc", "skel_closed_24.usda"),
        ("skel_ntsc.usdc", "skel_ntsc.usda"),
        ("skel_ntsc.usdz", "skel_ntsc.usda"),
        ("minimal_example.usdz", "minimal_example.usda"),
        ("blender_mixed.usdc", "blender_mixed.usda"),
        ("blender_mixed.usdz", "blender_mixed.usda"),
    ];
    for (twin, text) in pairs {
        let want = keys(&dir.join(text), &[]);
        // The same tracks, times and values, bit for bit: the text holds the float32 values the
        // crate stores, and the text reader rounds them to float32 as USD does.
        assert_eq!(keys(&dir.join(twin), &[]), want, "{twin} vs {text}");
        // Declared by its format name.
        let name = twin.rsplit('.').next().unwrap();
        assert_eq!(
            keys(&dir.join(twin), &["--input-format", name]),
            want,
            "{twin} --input-format {name}"
        );
    }
    // On standard input, recognised by the bytes: a crate's magic, a zip whose first entry is a
    // USD layer.
    for twin in ["skel_ntsc.usdc", "skel_ntsc.usdz"] {
        let out = stdout_of(
            bin()
                .args(["convert", "-", "--to", "quat", "--output-format", "json"])
                .write_stdin(std::fs::read(dir.join(twin)).unwrap()),
        );
        assert_eq!(
            out,
            keys(&dir.join("skel_ntsc.usda"), &[]),
            "{twin} on stdin"
        );
    }
    // `.usd` names either syntax.
    let tmp = tempfile::tempdir().unwrap();
    let usd = tmp.path().join("clip.usd");
    std::fs::copy(dir.join("skel_ntsc.usdc"), &usd).unwrap();
    assert_eq!(keys(&usd, &[]), keys(&dir.join("skel_ntsc.usda"), &[]));
}

/// The angle between two unit quaternions (w, x, y, z), sign-insensitive, in radians.
fn angle(a: &[f64], b: &[f64]) -> f64 {
    let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let na: f64 = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nb: f64 = b.iter().map(|x| x * x).sum::<f64>().sqrt();
    2.0 * (dot.abs() / (na * nb)).min(1.0).acos()
}

#[test]
fn blender_exports_read_as_usd_core_evaluates_them() {
    let Some(python) = checker_python("Blender USD exports against usd-core") else {
        return;
    };
    let dir = fixtures().join("usd");
    for file in [
        "blender_mixed.usdc",
        "blender_mixed.usdz",
        "blender_mixed.usda",
    ] {
        let path = dir.join(file);
        let usd: Value = python_json(&python, "fixtures/usd/usd_samples.py", &[path.as_os_str()]);
        let got: Value = serde_json::from_str(&keys(&path, &[])).unwrap();
        // Blender writes the scene's 30/0.999999 as 30.000030398399637: a standard rate within
        // 1e-4, read as 30.
        let tcps = usd["time_codes_per_second"].as_f64().unwrap();
        assert!((tcps - 30.0).abs() < 1e-4 * 30.0, "{file}: {tcps}");
        assert_eq!(got["fps"], 30, "{file}");
        let joints = usd["joints"].as_array().unwrap();
        let tracks = got["tracks"].as_array().unwrap();
        assert_eq!(tracks.len(), joints.len(), "{file}: a track per joint");
        let codes = usd["time_codes"].as_array().unwrap();
        assert_eq!(codes.len(), 4, "{file}: mixed_orders.bvh has 4 frames");
        let (mut worst_angle, mut worst_move) = (0.0f64, 0.0f64);
        for (j, joint) in joints.iter().enumerate() {
            let track = tracks.iter().find(|t| &t["name"] == joint).unwrap();
            let keys = track["keys"].as_array().unwrap();
            assert_eq!(keys.len(), codes.len(), "{file} {joint}");
            for (i, code) in codes.iter().enumerate() {
                assert_eq!(
                    keys[i]["frame"].as_f64(),
                    code.as_f64(),
                    "{file} {joint} {i}"
                );
                let nums = |v: &Value| -> Vec<f64> {
                    v.as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_f64().unwrap())
                        .collect()
                };
                let a = angle(&nums(&keys[i]["quat"]), &nums(&usd["rotations"][i][j]));
                worst_angle = worst_angle.max(a);
                let p = nums(&keys[i]["translation"]);
                let q = nums(&usd["translations"][i][j]);
                for c in 0..3 {
                    worst_move = worst_move.max((p[c] - q[c]).abs() / q[c].abs().max(1.0));
                }
            }
        }
        // Within float32: the tool normalises the stored quatf in float64, usd-core hands it
        // back as float32.
        assert!(worst_angle < 1e-6, "{file}: {worst_angle} rad");
        assert!(worst_move < 1e-6, "{file}: {worst_move}");
    }
}

#[test]
fn damaged_binary_usd_is_an_input_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read(fixtures().join("usd/skel_ntsc.usdc")).unwrap();
    let zip = std::fs::read(fixtures().join("usd/skel_ntsc.usdz")).unwrap();
    let cases: [(&str, Vec<u8>, &str); 4] = [
        (
            "cut.usdc",
            good[..good.len() / 2].to_vec(),
            "cut.usdc: usdc: ",
        ),
        (
            "v3.usdc",
            {
                let mut b = good.clone();
                b[9] = 3; // version 0.3: older than openusd reads
                b
            },
            "v3.usdc: usdc: usdc version 0.3.0; versions 0.4.0 to 0.12.0 are read",
        ),
        ("cut.usdz", zip[..zip.len() - 30].to_vec(), "cut.usdz: "),
        (
            "text.usdz",
            {
                // A zip whose first entry is no USD layer: its name, in the local header and the
                // central directory, ends `.usdx`.
                let mut b = zip.clone();
                for i in 0..b.len() - 14 {
                    if &b[i..i + 14] == b"skel_ntsc.usdc" {
                        b[i + 13] = b'x';
                    }
                }
                b
            },
            "text.usdz: the usdz package's first entry \"skel_ntsc.usdx\" is not a USD layer",
        ),
    ];
    for (name, bytes, says) in cases {
        let input = dir.path().join(name);
        std::fs::write(&input, bytes).unwrap();
        let out = dir.path().join("out.json");
        let o = bin()
            .arg("convert")
            .arg(&input)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(!out.exists(), "{name}: nothing written");
    }
}

/// A folder of binary USD: each file is an input of the batch, and `interp` writes each as the
/// USD the tool writes, `.usda`, the same as from the `.usda` twin.
#[test]
fn a_batch_reads_binary_usd_and_writes_usda() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir(&input).unwrap();
    let usd = fixtures().join("usd");
    for f in ["skel_ntsc.usdz", "skel_closed_24.usdc"] {
        std::fs::copy(usd.join(f), input.join(f)).unwrap();
    }
    let out = dir.path().join("out");
    let o = bin()
        .arg("interp")
        .arg(&input)
        .arg("--out-dir")
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    for name in ["skel_ntsc", "skel_closed_24"] {
        let got = std::fs::read_to_string(out.join(format!("{name}.usda"))).unwrap();
        let want = stdout_of(
            bin()
                .arg("interp")
                .arg(usd.join(format!("{name}.usda")))
                .args(["--output-format", "usda"]),
        );
        assert_eq!(got, want, "{name}");
    }
}
