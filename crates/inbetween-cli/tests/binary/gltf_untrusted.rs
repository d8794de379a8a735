//! glTF assets from strangers: URIs that lead out of the asset's folder (percent-encoded, `..`,
//! symbolic links), devices and FIFOs, external bytes past `--max-input-bytes`, `-o` naming a
//! file the asset reads, channels the tool does not process, indices and counts that do not
//! fit, and what glTF forbids. Each is refused with exit 2 and nothing written, or (channels
//! the tool does not process) ignored with one warning.
//!
//! The binary runs under a 2 GB address-space cap and a timeout, so that a reader that follows
//! `/dev/zero` or waits on a FIFO fails the test instead of the machine.

use crate::support::fixtures;
use base64::Engine as _;
use serde_json::{Value, json};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::Duration;

/// Runs the binary with `args` under `ulimit -v` (2 GB) and a 60 s timeout.
fn run(args: &[&OsStr]) -> Output {
    let bin = assert_cmd::cargo::cargo_bin("inbetween");
    let mut cmd = assert_cmd::Command::new("sh");
    cmd.arg("-c")
        .arg("ulimit -v 2000000; exec \"$0\" \"$@\"")
        .arg(bin)
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .timeout(Duration::from_secs(60));
    cmd.output().expect("the binary runs")
}

fn os<S: AsRef<OsStr> + ?Sized>(s: &S) -> &OsStr {
    s.as_ref()
}

/// The JSON of `minimal_linear.gltf` (one LINEAR rotation channel and one translation channel
/// on node 0) and the 64 bytes of its buffer.
fn minimal() -> (Value, Vec<u8>) {
    let text = std::fs::read_to_string(fixtures().join("gltf/minimal_linear.gltf")).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    let uri = json["buffers"][0]["uri"].as_str().unwrap();
    let payload = uri.split_once(";base64,").unwrap().1;
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(payload)
        .unwrap();
    assert_eq!(bytes.len(), 64);
    (json, bytes)
}

/// `dir/name` holding the minimal asset with its buffer at `uri`; returns its path.
fn asset_with_uri(dir: &Path, name: &str, uri: &str) -> PathBuf {
    let (mut json, _) = minimal();
    json["buffers"][0]["uri"] = json!(uri);
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    path
}

/// Runs `convert asset -o out.json` and `convert asset` (standard output) and checks that each
/// exits 2 with `want` in its message and writes nothing.
#[track_caller]
fn refused(asset: &Path, want: &str) {
    let out = asset.with_file_name("out.json");
    let o = run(&[os("convert"), asset.as_os_str(), os("-o"), out.as_os_str()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{}: {err}", asset.display());
    assert!(err.contains(want), "{}: {err}", asset.display());
    assert!(!out.exists(), "{}: -o written", asset.display());
    let o = run(&[os("convert"), asset.as_os_str()]);
    assert_eq!(o.status.code(), Some(2), "{}", asset.display());
    assert!(o.stdout.is_empty(), "{}: stdout written", asset.display());
}

/// A folder `asset/` with `good.bin` (the buffer) inside, and `outside.bin` (the same bytes)
/// beside the folder.
fn folders() -> (tempfile::TempDir, PathBuf) {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("asset");
    std::fs::create_dir(&dir).unwrap();
    let (_, bytes) = minimal();
    std::fs::write(dir.join("good.bin"), &bytes).unwrap();
    std::fs::write(root.path().join("outside.bin"), &bytes).unwrap();
    (root, dir)
}

#[test]
fn a_buffer_outside_the_assets_folder_is_refused() {
    let (root, dir) = folders();
    let outside = std::fs::canonicalize(root.path().join("outside.bin")).unwrap();
    let encoded = outside.to_str().unwrap().replace('/', "%2F");
    for (name, uri, want) in [
        ("pct.gltf", encoded.as_str(), "is an absolute path"),
        ("dotdot.gltf", "../outside.bin", "leaves the asset's folder"),
        (
            "dotdot_pct.gltf",
            "%2E%2E%2Foutside.bin",
            "leaves the asset's folder",
        ),
        (
            "deep.gltf",
            "../../../../../../../../etc/passwd",
            "leaves the asset's folder",
        ),
        (
            "scheme.gltf",
            "file:///etc/passwd",
            "expected a relative file name",
        ),
    ] {
        refused(&asset_with_uri(&dir, name, uri), want);
    }
}

#[test]
fn a_symbolic_link_out_of_the_folder_is_refused() {
    let (_root, dir) = folders();
    std::os::unix::fs::symlink("../outside.bin", dir.join("link.bin")).unwrap();
    refused(
        &asset_with_uri(&dir, "link.gltf", "link.bin"),
        "outside the asset's folder (through a symbolic link)",
    );
    // A link that stays inside, and `..` that stays inside, are fine.
    std::os::unix::fs::symlink("good.bin", dir.join("inner.bin")).unwrap();
    std::fs::create_dir(dir.join("sub")).unwrap();
    for (name, uri) in [("inner.gltf", "inner.bin"), ("sub.gltf", "sub/../good.bin")] {
        let asset = asset_with_uri(&dir, name, uri);
        let o = run(&[os("convert"), asset.as_os_str()]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{uri}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn devices_and_fifos_are_refused_without_being_read() {
    let (_root, dir) = folders();
    refused(
        &asset_with_uri(&dir, "zero.gltf", "%2Fdev%2Fzero"),
        "is an absolute path",
    );
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
    refused(
        &asset_with_uri(&dir, "zerolink.gltf", "zero.bin"),
        "outside the asset's folder",
    );
    refused(
        &asset_with_uri(&dir, "dir.gltf", "."),
        "is not a regular file",
    );
}

#[test]
fn a_fifo_beside_the_asset_is_refused_without_waiting() {
    let (_root, dir) = folders();
    let fifo = dir.join("fifo.bin");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    refused(
        &asset_with_uri(&dir, "fifo.gltf", "fifo.bin"),
        "is not a regular file",
    );
}

#[test]
fn external_bytes_count_against_max_input_bytes() {
    let (_root, dir) = folders();
    let asset = asset_with_uri(&dir, "good.gltf", "good.bin");
    let size = std::fs::metadata(&asset).unwrap().len();
    // The asset's own bytes and its 64-byte buffer together.
    for (limit, code) in [(size + 63, 2), (size + 64, 0)] {
        let o = run(&[
            os("convert"),
            asset.as_os_str(),
            os("--max-input-bytes"),
            os(&limit.to_string()),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(code), "limit {limit}: {err}");
        if code == 2 {
            assert!(
                err.contains("buffers[0].byteLength: 64 bytes from \"good.bin\""),
                "{err}"
            );
            assert!(o.stdout.is_empty());
        }
    }
}

#[test]
fn an_output_naming_a_file_the_asset_reads_is_refused() {
    let (_root, dir) = folders();
    let asset = asset_with_uri(&dir, "good.gltf", "good.bin");
    let before = std::fs::read(dir.join("good.bin")).unwrap();
    std::os::unix::fs::symlink("good.bin", dir.join("alias.bin")).unwrap();
    for target in ["good.bin", "alias.bin"] {
        let out = dir.join(target);
        let o = run(&[
            os("interp"),
            asset.as_os_str(),
            os("--fps"),
            os("4"),
            os("-o"),
            out.as_os_str(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{target}: {err}");
        assert!(err.contains("which the command reads"), "{err}");
        assert_eq!(std::fs::read(dir.join("good.bin")).unwrap(), before);
    }
}

/// The minimal asset with an image at `uri`, its buffer embedded.
fn asset_with_image(dir: &Path, name: &str, uri: &str) -> PathBuf {
    let (mut json, _) = minimal();
    json["images"] = json!([{ "uri": uri }]);
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    path
}

#[test]
fn image_uris_follow_the_same_rules_and_are_embedded_when_written_elsewhere() {
    let (root, dir) = folders();
    refused(
        &asset_with_image(&dir, "pct.gltf", "%2Fetc%2Fpasswd"),
        "images[0].uri (\"%2Fetc%2Fpasswd\"): \"/etc/passwd\" is an absolute path",
    );
    refused(
        &asset_with_image(&dir, "up.gltf", "../outside.bin"),
        "leaves the asset's folder",
    );
    std::os::unix::fs::symlink("../outside.bin", dir.join("link.png")).unwrap();
    refused(
        &asset_with_image(&dir, "link.gltf", "link.png"),
        "outside the asset's folder",
    );
    // An image on the web is never fetched: its URI is kept.
    let web = asset_with_image(&dir, "web.gltf", "https://example.com/skin.png");
    let o = run(&[os("convert"), web.as_os_str()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    refused(
        &asset_with_image(&dir, "file.gltf", "file:///etc/passwd"),
        "expected a relative file name",
    );
    // An image inside: written into another folder, the output carries its bytes (it names
    // no file outside its own folder), and reads back.
    let png = b"\x89PNG\r\n\x1a\nnot really a picture";
    std::fs::write(dir.join("skin.png"), png).unwrap();
    let asset = asset_with_image(&dir, "img.gltf", "skin.png");
    let out_dir = root.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let out = out_dir.join("o.gltf");
    let o = run(&[
        os("interp"),
        asset.as_os_str(),
        os("--fps"),
        os("4"),
        os("-o"),
        out.as_os_str(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let written: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let uri = written["images"][0]["uri"].as_str().unwrap();
    let expected = format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png)
    );
    assert_eq!(uri, expected);
    let back = run(&[os("convert"), out.as_os_str()]);
    assert_eq!(back.status.code(), Some(0));
}

/// The minimal asset (buffer embedded) edited by `edit`, written to `dir/name`.
fn edited(dir: &Path, name: &str, edit: impl FnOnce(&mut Value)) -> PathBuf {
    let (mut json, _) = minimal();
    edit(&mut json);
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    path
}

#[test]
fn a_channel_on_a_node_that_does_not_exist_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(
        &edited(d, "node.gltf", |j| {
            j["animations"][0]["channels"][0]["target"]["node"] = json!(7)
        }),
        "animations[0].channels[0].target.node: node 7 does not exist",
    );
}

#[test]
fn sparse_accessors_of_2_pow_62_or_1e11_elements_are_refused_unallocated() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A sparse output (accessor 1) or input (accessor 0) of 2^62 or 10^11 elements with no
    // buffer view: zeros plus one value.
    let cases = [
        (1, "VEC4", 1, "elements, expected 2 for 2 keys"),
        (0, "SCALAR", 0, "times with no bufferView"),
    ];
    for (accessor, kind, values, expected) in cases {
        for count in [1u64 << 62, 100_000_000_000] {
            refused(
                &edited(d, &format!("sparse{accessor}_{count}.gltf"), |j| {
                    j["accessors"][accessor] = json!({
                        "componentType": 5126, "count": count, "type": kind,
                        "sparse": {"count": 1,
                                   "indices": {"bufferView": 0, "componentType": 5125},
                                   "values": {"bufferView": values}}
                    })
                }),
                &format!("accessors[{accessor}].count: {count} {expected}"),
            );
        }
    }
}

#[test]
fn channels_the_tool_does_not_process_are_ignored_with_one_warning() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let pointer = |node: bool| {
        let mut target = json!({
            "path": "pointer",
            "extensions": {"KHR_animation_pointer": {"pointer": "/nodes/0/rotation"}}
        });
        if node {
            target["node"] = json!(0);
        }
        json!({"sampler": 0, "target": target})
    };
    for (name, channels) in [
        ("with_node.gltf", vec![pointer(true)]),
        ("without_node.gltf", vec![pointer(false)]),
        ("both.gltf", vec![pointer(true), pointer(false)]),
        (
            "unknown.gltf",
            vec![json!({"sampler": 0, "target": {"node": 0, "path": "colour"}})],
        ),
    ] {
        let n = channels.len();
        let asset = edited(d, name, |j| {
            let list = j["animations"][0]["channels"].as_array_mut().unwrap();
            // Before the rotation channel, so that JSON indices and read channels differ.
            for (k, c) in channels.into_iter().enumerate() {
                list.insert(k, c);
            }
        });
        let o = run(&[os("convert"), asset.as_os_str()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{name}: {err}");
        assert_eq!(err.matches("warning").count(), 1, "{name}: {err}");
        assert!(
            err.contains("animations[0].channels[0] (path \""),
            "{name}: {err}"
        );
        assert!(err.contains("ignored"), "{name}: {err}");
        if n == 2 {
            assert!(err.contains(" and 1 more: ignored"), "{err}");
        }
        // The rotation channel is still read and written back (into the right JSON channel).
        let out = d.join(format!("{name}.gltf"));
        let o = run(&[
            os("interp"),
            asset.as_os_str(),
            os("--fps"),
            os("4"),
            os("-o"),
            out.as_os_str(),
        ]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let written: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
        let chans = &written["animations"][0]["channels"];
        for k in 0..n {
            assert_eq!(
                chans[k]["sampler"],
                json!(0),
                "{name}: the ignored channel {k} kept"
            );
        }
        assert_eq!(chans[n]["target"]["path"], json!("rotation"));
        // The rotation's old sampler (1) is gone: the new LINEAR one takes its place.
        assert_eq!(
            chans[n]["sampler"],
            json!(1),
            "{name}: the new LINEAR sampler"
        );
        let sampler = &written["animations"][0]["samplers"][1];
        assert_eq!(sampler["interpolation"], json!("LINEAR"), "{name}");
    }
}

#[test]
fn what_gltf_forbids_is_refused_with_its_path() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    refused(
        &edited(d, "twice.gltf", |j| {
            j["animations"][0]["channels"]
                .as_array_mut()
                .unwrap()
                .push(json!({"sampler": 0, "target": {"node": 0, "path": "rotation"}}))
        }),
        "animations[0].channels[2]: targets node 0's rotation, as animations[0].channels[0] does",
    );
    // Duplicate keys, at the top and deep inside.
    let (json, _) = minimal();
    let text = serde_json::to_string(&json).unwrap();
    let top = text.replacen("{\"accessors\"", "{\"scene\": 0, \"accessors\"", 1);
    assert_ne!(top, text);
    let path = d.join("dup_top.gltf");
    std::fs::write(&path, top).unwrap();
    refused(&path, "the top-level object: duplicate key \"scene\"");
    let deep = text.replacen(
        "\"path\":\"rotation\"",
        "\"path\":\"rotation\",\"path\":\"scale\"",
        1,
    );
    assert_ne!(deep, text);
    let path = d.join("dup_deep.gltf");
    std::fs::write(&path, deep).unwrap();
    refused(
        &path,
        "animations[0].channels[0].target: duplicate key \"path\"",
    );
}

/// A GLB of `json` with `bin` as its BIN chunk.
fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    let mut text = serde_json::to_vec(json).unwrap();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((text.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(text);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

#[test]
fn a_glb_whose_bin_chunk_is_not_buffer_0_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (mut json, bytes) = minimal();
    // The good layout first: buffer 0 is the BIN chunk.
    json["buffers"] = json!([{"byteLength": 64}]);
    let good = dir.path().join("good.glb");
    std::fs::write(&good, glb(&json, &bytes)).unwrap();
    let o = run(&[os("convert"), good.as_os_str()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // Buffer 1 without a URI, used by every view: glTF 2.0 §4.4.3.3 allows only buffer 0.
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    );
    json["buffers"] = json!([{"byteLength": 64, "uri": uri}, {"byteLength": 64}]);
    for v in json["bufferViews"].as_array_mut().unwrap() {
        v["buffer"] = json!(1);
    }
    let bad = dir.path().join("bad.glb");
    std::fs::write(&bad, glb(&json, &bytes)).unwrap();
    refused(
        &bad,
        "buffers[1]: has no uri, but only buffers[0] may refer to the GLB BIN",
    );
}

#[test]
fn messages_quote_at_most_60_characters_and_name_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let asset = edited(dir.path(), "long.gltf", |j| {
        j["accessors"][0]["count"] = json!("a".repeat(1_000_000))
    });
    refused(&asset, "accessors[0].count: invalid type: string");
    let o = run(&[os("convert"), asset.as_os_str()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.len() < 300,
        "{} bytes: {}",
        err.len(),
        &err[..300.min(err.len())]
    );
    assert!(err.contains(&format!("\"{}…\"", "a".repeat(60))), "{err}");
}

#[test]
fn a_nan_time_is_named_in_words() {
    let dir = tempfile::tempdir().unwrap();
    let (mut json, mut bytes) = minimal();
    bytes[4..8].copy_from_slice(&f32::NAN.to_le_bytes()); // time 1 of accessor 0
    json["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    ));
    let asset = dir.path().join("nan.gltf");
    std::fs::write(&asset, serde_json::to_vec(&json).unwrap()).unwrap();
    refused(
        &asset,
        "nan.gltf: animations[0].samplers[0].input: accessors[0]: time 1 is not a number: \
         expected a finite number",
    );
    let o = run(&[os("convert"), asset.as_os_str()]);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("NaN"));
}

#[test]
fn non_unit_rotations_are_normalised_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let (mut json, mut bytes) = minimal();
    // Rotation key 0 (accessor 1, bytes 8..40: two VEC4; key 0 is the identity) scaled by 2.
    for k in 0..4 {
        let at = 8 + 4 * k;
        let x = f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
        bytes[at..at + 4].copy_from_slice(&(2.0 * x).to_le_bytes());
    }
    json["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    ));
    let asset = dir.path().join("scaled.gltf");
    std::fs::write(&asset, serde_json::to_vec(&json).unwrap()).unwrap();
    let o = run(&[os("convert"), asset.as_os_str()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains(
            "scaled.gltf: animations[0].channels[0]: samplers[0].output: accessors[1]: key 0: \
             quaternion norm 2 is off 1 by more than 1e-3; normalized"
        ),
        "{err}"
    );
    // The fixture as it is draws no such warning.
    let o = run(&[
        os("convert"),
        fixtures().join("gltf/minimal_linear.gltf").as_os_str(),
    ]);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("norm"));
}
