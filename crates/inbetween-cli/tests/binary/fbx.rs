//! FBX input (through ufbx): every key `convert` writes against values computed without the
//! tool — the closed forms of the files Blender made (fixtures/fbx/make_closed_form.py) and
//! Blender's own import of the real assimp files (fixtures/fbx/blender_expected.py) — and the
//! errors of corrupt files.

use crate::support::{assert_rot_close, bin, fixtures, stdout_of};
use glam::{DQuat, DVec3};
use serde_json::Value;

/// float32 keys through two conversions (Euler degrees in the file, quaternions here): Blender's
/// own re-import of the generated files agreed with their closed forms to 1.0e-6 rad
/// (fixtures/fbx/README.md).
const ANGLE: f64 = 2e-6;

/// A JSON array of numbers.
fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// `[w, x, y, z]`.
fn quat(v: &Value) -> DQuat {
    let a = numbers(v);
    DQuat::from_xyzw(a[1], a[2], a[3], a[0])
}

fn vec3(v: &Value) -> DVec3 {
    let a = numbers(v);
    DVec3::new(a[0], a[1], a[2])
}

/// `convert FILE --to quat` against `expected/NAME.json`: each expected node is a track of the
/// same name whose key at each expected time (the stack starts at time 0) has the expected
/// rotation and, scaled by `scale(node)` (the product of its ancestors' Lcl Scaling, which the
/// clip folds into translations), translation.
fn agrees(file: &str, expected: &str, scale: impl Fn(&str) -> f64) {
    let dir = fixtures().join("fbx");
    let want: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("expected").join(expected)).unwrap(),
    )
    .unwrap();
    let out = stdout_of(
        bin()
            .args(["convert", "--to", "quat", "--output-format", "json"])
            .arg(dir.join(file)),
    );
    let got: Value = serde_json::from_str(&out).unwrap();
    let rate = want["rate"].as_array().unwrap();
    let (num, den) = (rate[0].as_u64().unwrap(), rate[1].as_u64().unwrap());
    let fps = if den == 1 {
        Value::from(num)
    } else {
        Value::from(format!("{num}/{den}"))
    };
    assert_eq!(got["fps"], fps, "{file}: the rate");
    let times: Vec<f64> = want["times"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    // Blender's float32 arithmetic (world matrices, then parent⁻¹·world) carries an error of a
    // few float32 steps of the scene's largest translation into every local one.
    let largest = want["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|n| {
            let s = scale(n["name"].as_str().unwrap());
            n["translations"]
                .as_array()
                .into_iter()
                .flatten()
                .map(move |t| vec3(t).length() * s)
        })
        .fold(1.0, f64::max);
    let reach = 4.0 * f32::EPSILON as f64 * largest;
    let mut compared = 0;
    for node in want["nodes"].as_array().unwrap() {
        let name = node["name"].as_str().unwrap();
        let track = got["tracks"]
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["name"] == name)
            .unwrap_or_else(|| panic!("{file}: no track {name}"));
        let keys = track["keys"].as_array().unwrap();
        for (i, &t) in times.iter().enumerate() {
            // Frame numbers from the stack's start; Blender's exporter truncates key times to
            // ticks (up to 2e-11 s early), so the nearest frame.
            let frame = (t * num as f64 / den as f64).round() as i64;
            let key = keys
                .iter()
                .find(|k| k["frame"].as_i64() == Some(frame))
                .unwrap_or_else(|| panic!("{file}: {name} has no key at frame {frame}"));
            let what = format!("{file}: {name} at {t} s");
            assert_rot_close(
                quat(&key["quat"]),
                quat(&node["rotations_wxyz"][i]),
                ANGLE,
                &what,
            );
            if let Some(ts) = node["translations"].as_array() {
                let p = key["translation"].as_array().map_or_else(
                    || {
                        // A joint whose translation does not move keeps it as its offset.
                        None
                    },
                    |_| Some(vec3(&key["translation"])),
                );
                if let Some(p) = p {
                    let w = vec3(&ts[i]) * scale(name);
                    let d = (p - w).length();
                    assert!(
                        d <= reach,
                        "{what}: {p} vs {w}: {d:e} (tolerance {reach:e})"
                    );
                }
            }
            compared += 1;
        }
    }
    assert!(
        compared >= times.len() * 2,
        "{file}: compared {compared} keys"
    );
}

#[test]
fn the_generated_files_agree_with_their_closed_forms() {
    // The armature's bones are inside the node "Armature", whose Lcl Scaling is 100 (the
    // exporter's unit scale; fixtures/fbx/README.md).
    agrees("closed_armature_30.fbx", "closed_armature_30.json", |n| {
        if n == "Armature" { 1.0 } else { 100.0 }
    });
    agrees(
        "closed_empties_zxy_24.fbx",
        "closed_empties_zxy_24.json",
        |_| 1.0,
    );
    agrees("closed_ntsc_2997.fbx", "closed_ntsc_2997.json", |_| 1.0);
}

#[test]
fn the_real_files_agree_with_blenders_import() {
    for (file, json) in [
        (
            "real/animation_with_skeleton.fbx",
            "animation_with_skeleton.json",
        ),
        ("real/huesitos.fbx", "huesitos.json"),
    ] {
        agrees(file, json, |n| if n == "Armature" { 1.0 } else { 100.0 });
    }
}

#[test]
fn an_fbx_clip_becomes_a_bvh_that_bvhio_reads_back_to_the_closed_form() {
    let Some(python) = crate::support::checker_python("bvhio check of FBX → BVH") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let bvh = dir.path().join("clip.bvh");
    let fixtures = fixtures().join("fbx");
    bin()
        .arg("interp")
        .arg(fixtures.join("closed_armature_30.fbx"))
        .args(["--fps", "30", "-o"])
        .arg(&bvh)
        .assert()
        .success();
    let text = std::fs::read_to_string(&bvh).unwrap();
    assert!(text.starts_with("HIERARCHY\nROOT Armature\n"), "{text}");
    // bvhio (fixtures/bvh/read_bvh.py), not the tool, reads it back; its rotations are compared
    // with the closed form the FBX file was made from.
    let back = crate::support::python_json(&python, "fixtures/bvh/read_bvh.py", &[bvh.as_os_str()]);
    let want: Value = serde_json::from_str(
        &std::fs::read_to_string(fixtures.join("expected/closed_armature_30.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(back["frame_count"].as_u64(), Some(31));
    assert!((back["frame_time"].as_f64().unwrap() - 1.0 / 30.0).abs() < 1e-9);
    let joints = back["joints"].as_array().unwrap();
    let mut compared = 0;
    for node in want["nodes"].as_array().unwrap() {
        let j = joints
            .iter()
            .position(|j| j["name"] == node["name"])
            .unwrap_or_else(|| panic!("no joint {}", node["name"]));
        for (f, q) in node["rotations_wxyz"]
            .as_array()
            .unwrap()
            .iter()
            .enumerate()
        {
            let got = quat(&back["frames"][f][j]["rotation"]).normalize();
            // bvhio computes in float32.
            assert_rot_close(got, quat(q), 1e-5, &format!("{} frame {f}", node["name"]));
            compared += 1;
        }
    }
    assert_eq!(compared, 5 * 31);
}

#[test]
fn corrupt_fbx_files_are_located_errors() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read(fixtures().join("fbx/closed_armature_30.fbx")).unwrap();
    let cases: [(&str, Vec<u8>, &str); 3] = [
        (
            "cut.fbx",
            good[..good.len() / 3].to_vec(),
            "not a readable FBX file",
        ),
        ("empty.fbx", Vec::new(), "not a readable FBX file"),
        (
            "junk.fbx",
            b"Kaydara FBX Binary  \0\x1a\0garbage".to_vec(),
            "not a readable FBX file",
        ),
    ];
    for (name, bytes, message) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        let out_path = dir.path().join("out.json");
        let o = bin()
            .arg("convert")
            .arg(&path)
            .arg("-o")
            .arg(&out_path)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.starts_with(&format!("inbetween: error: {}: {message}", path.display())),
            "{name}: {err}"
        );
        assert!(!out_path.exists(), "{name}: nothing written");
    }
    // A scene without animation.
    let still = dir.path().join("still.fbx");
    let ascii = "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n FBXHeaderVersion: 1003\n FBXVersion: 7400\n}\n";
    std::fs::write(&still, ascii).unwrap();
    let o = bin().arg("analyze").arg(&still).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no animation stack"));
}
