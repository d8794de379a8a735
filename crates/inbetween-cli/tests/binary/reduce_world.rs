//! `reduce --position-tolerance`: the world-space guarantee replayed by the independent checker
//! (`fixtures/world/replay_ref.py`: its own BVH and glTF readers, slerp and forward kinematics)
//! on real BVH and glTF motion, with `--shell`, `--joint-tolerance`, `--shared-keys` and
//! `--tolerance`; and the refusals.

use crate::support::{bin, checker_python, python_json, stdout_of};
use serde_json::Value;
use std::ffi::OsStr;
use std::path::Path;

const CMU: &str = "fixtures/bvh/cmu_01_01.bvh";
const CESIUM: &str = "fixtures/gltf/real/CesiumMan.glb";

fn keys_of(path: &Path) -> usize {
    let doc: Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    doc["tracks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["keys"].as_array().unwrap().len())
        .sum()
}

/// The checker's verdict on `reduced` against `original`: it exits 0 only when every joint is
/// within its limit; the largest displacement it measured.
fn replay(python: &Path, original: &str, reduced: &Path, extra: &[&str]) -> Value {
    let mut args: Vec<&OsStr> = vec![OsStr::new(original), reduced.as_os_str()];
    args.extend(extra.iter().map(OsStr::new));
    args.push(OsStr::new("--json"));
    let r = python_json(python, "fixtures/world/replay_ref.py", &args);
    assert_eq!(r["within"], true, "{r}");
    r
}

fn max_displacement(r: &Value) -> f64 {
    r["max_displacement"].as_f64().unwrap()
}

/// Bezier keys (the default) replayed as `interp` plays them at the clip's rate, and slerp keys
/// replayed by the checker's own slerp: every joint and End Site within LEN at every frame, the
/// shell's points too with `--shell`; and the bound is used, not met by keeping every frame.
#[test]
fn every_point_of_a_bvh_clip_stays_within_the_position_tolerance() {
    let Some(python) = checker_python("world-space replay of reduce") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (len, shell, scheme) in [
        ("0.5", None, "bezier"),
        ("0.3", Some("3"), "bezier"),
        ("0.5", None, "slerp"),
        ("0.2", Some("2"), "slerp"),
    ] {
        let keys = dir.path().join(format!("{scheme}-{len}.json"));
        let mut cmd = bin();
        cmd.args([
            "reduce",
            CMU,
            "--position-tolerance",
            len,
            "--scheme",
            scheme,
        ]);
        if let Some(d) = shell {
            cmd.args(["--shell", d]);
        }
        stdout_of(cmd.arg("-o").arg(&keys));
        let replayed = if scheme == "slerp" {
            keys.clone()
        } else {
            let dense = dir.path().join(format!("dense-{len}.json"));
            stdout_of(
                bin()
                    .args(["interp", "--fps", "120", "--scheme", scheme])
                    .arg(&keys)
                    .arg("-o")
                    .arg(&dense),
            );
            dense
        };
        let mut extra = vec!["--limit", len];
        if let Some(d) = shell {
            extra.extend(["--shell", d]);
        }
        let r = replay(&python, CMU, &replayed, &extra);
        let len: f64 = len.parse().unwrap();
        // 31 tracks of 61 frames: far fewer keys, and the error near its bound.
        assert!(keys_of(&keys) < 31 * 61 / 3, "{scheme} {len}");
        assert!(max_displacement(&r) > 0.5 * len, "{scheme} {len}: {r}");
    }
}

/// `--joint-tolerance` tightens the named joints' points (a later glob wins), `--shared-keys`
/// gives every track one set of key times, and `--tolerance` keeps bounding each joint's local
/// angle as well.
#[test]
fn joint_tolerances_shared_keys_and_local_angles_hold_together() {
    let Some(python) = checker_python("world-space replay of reduce") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let keys = dir.path().join("shared.json");
    stdout_of(
        bin()
            .args([
                "reduce",
                CMU,
                "--scheme",
                "slerp",
                "--position-tolerance",
                "0.6",
                "--joint-tolerance",
                "L*=0.1",
                "--joint-tolerance",
                "LeftHand*=0.3",
                "--tolerance",
                "0.4",
                "--shared-keys",
                "-o",
            ])
            .arg(&keys),
    );
    let r = replay(
        &python,
        CMU,
        &keys,
        &[
            "--limit",
            "0.6",
            "--joint-limit",
            "L*=0.1",
            "--joint-limit",
            "LeftHand*=0.3",
            "--shared-keys",
        ],
    );
    let joints = r["joints"].as_array().unwrap();
    let named = |n: &str| joints.iter().find(|j| j["name"] == n).unwrap();
    assert_eq!(named("LeftFoot")["limit"], 0.1);
    assert_eq!(named("LeftHand")["limit"], 0.3);
    for j in joints {
        assert!(
            j["max_angle_deg"].as_f64().unwrap() <= 0.4 * (1.0 + 1e-9),
            "{j}"
        );
    }
    // Without the overrides and the local bound the left leg moves further: they were what
    // bound it.
    let loose = dir.path().join("loose.json");
    stdout_of(
        bin()
            .args([
                "reduce",
                CMU,
                "--scheme",
                "slerp",
                "--position-tolerance",
                "0.6",
            ])
            .args(["--shared-keys", "-o"])
            .arg(&loose),
    );
    let free = replay(&python, CMU, &loose, &["--limit", "0.6", "--shared-keys"]);
    let free_joints = free["joints"].as_array().unwrap();
    let free_foot = free_joints
        .iter()
        .find(|j| j["name"] == "LeftFoot")
        .unwrap();
    assert!(
        free_foot["max_displacement"].as_f64().unwrap() > 0.1,
        "{free_foot}"
    );
    assert!(keys_of(&loose) < keys_of(&keys));
}

/// A glTF asset: the reduced asset as a glTF player plays it (float32 keys, LINEAR slerp),
/// every node's points within LEN, with the shell's too.
#[test]
fn a_reduced_gltf_asset_plays_within_the_position_tolerance() {
    let Some(python) = checker_python("world-space replay of reduce") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (len, shell) in [("0.005", None), ("0.01", Some("0.05"))] {
        let out = dir.path().join(format!("small-{len}.glb"));
        let mut cmd = bin();
        cmd.args(["reduce", CESIUM, "--position-tolerance", len]);
        if let Some(d) = shell {
            cmd.args(["--shell", d]);
        }
        stdout_of(cmd.arg("-o").arg(&out));
        let mut extra = vec!["--limit", len];
        if let Some(d) = shell {
            extra.extend(["--shell", d]);
        }
        let r = replay(&python, CESIUM, &out, &extra);
        assert!(
            max_displacement(&r) > 0.3 * len.parse::<f64>().unwrap(),
            "{r}"
        );
    }
}

fn refused(args: &[&str], needle: &str) {
    let out = bin().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn what_a_position_tolerance_cannot_be_given_with_is_refused() {
    // Two animations pose the nodes apart: the message asks for one and lists them.
    refused(
        &[
            "reduce",
            "fixtures/gltf/real/RiggedSimple.gltf",
            "--position-tolerance",
            "0.01",
        ],
        "poses one animation at a time, and this asset has 2: choose one with --animation \
         NAME|INDEX (0, 1)",
    );
    // A keys document has no skeleton to pose.
    refused(
        &[
            "reduce",
            "fixtures/diff/turned.json",
            "--position-tolerance",
            "1",
        ],
        "needs a skeleton",
    );
    refused(
        &[
            "reduce",
            CMU,
            "--position-tolerance",
            "1",
            "--distance",
            "3",
            "--tolerance",
            "1",
        ],
        "cannot be given with --distance",
    );
    refused(
        &[
            "reduce",
            CMU,
            "--position-tolerance",
            "1",
            "--precision",
            "4",
        ],
        "cannot be given with --precision",
    );
    refused(
        &[
            "reduce",
            CMU,
            "--position-tolerance",
            "1",
            "--joint-tolerance",
            "Tail*=0.1",
        ],
        "\"Tail*\" matches no joint; the joints are \"Hips\"",
    );
    refused(
        &[
            "reduce",
            CMU,
            "--position-tolerance",
            "1",
            "--joint-tolerance",
            "Hips",
        ],
        "expected GLOBS=LEN",
    );
    refused(
        &["reduce", CMU, "--shell", "3", "--tolerance", "1"],
        "--position-tolerance",
    );
    refused(&["reduce", CMU], "--tolerance");
}

/// Every bone bounded without `--shell`: CesiumMan's five leaf joints (no children, no end)
/// get end points at their bone length, which the checker derives on its own
/// (`--default-ends`, written from the contract) and replays within LEN; with `--shell 0` (no
/// points added, as before) the same points are 4–18 times LEN off — the leaves were unbounded.
#[test]
fn leaf_bones_are_bounded_by_default() {
    let Some(python) = checker_python("world-space replay of reduce") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let (bounded, opted_out) = (dir.path().join("b.glb"), dir.path().join("o.glb"));
    let out = bin()
        .args([
            "reduce",
            CESIUM,
            "--position-tolerance",
            "0.005",
            "-v",
            "-o",
        ])
        .arg(&bounded)
        .output()
        .unwrap();
    assert!(out.status.success());
    let told = String::from_utf8(out.stderr).unwrap();
    let line = told
        .lines()
        .find(|l| l.contains("world: skeleton of 21 joints"))
        .unwrap_or_else(|| panic!("{told}"));
    let r = replay(
        &python,
        CESIUM,
        &bounded,
        &["--limit", "0.005", "--default-ends"],
    );
    let given = r["default_ends"].as_object().unwrap();
    assert_eq!(given.len(), 5, "{r}");
    for name in given.keys() {
        assert!(
            line.contains(&format!("\"{name}\"")),
            "{name} not in {line}"
        );
    }
    stdout_of(
        bin()
            .args([
                "reduce",
                CESIUM,
                "--position-tolerance",
                "0.005",
                "--shell",
                "0",
                "-o",
            ])
            .arg(&opted_out),
    );
    let mut args: Vec<&OsStr> = vec![OsStr::new(CESIUM), opted_out.as_os_str()];
    args.extend(["--limit", "0.005", "--default-ends", "--json"].map(OsStr::new));
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let out = std::process::Command::new(&python)
        .arg(root.join("fixtures/world/replay_ref.py"))
        .args(&args)
        .current_dir(root)
        .output()
        .unwrap();
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["within"], false, "{r}");
    assert!(max_displacement(&r) > 4.0 * 0.005, "{r}");
}

/// FBX leaf nodes (an exporter's `Bone.006_end`) are kept as End Sites, so the bones above
/// them are bounded in world space (their budgets were 180°), and BVH written from FBX has
/// them; the reduced keys replayed by the checker on that BVH stay within LEN.
#[test]
fn fbx_end_nodes_are_end_sites_that_bound_their_bones() {
    let fbx = "fixtures/fbx/real/huesitos.fbx";
    let bvh = stdout_of(bin().args(["convert", fbx, "--output-format", "bvh"]));
    assert_eq!(bvh.matches("End Site").count(), 2, "{bvh}");
    let out = bin()
        .args([
            "reduce",
            fbx,
            "--position-tolerance",
            "0.02",
            "-v",
            "-o",
            "-",
        ])
        .output()
        .unwrap();
    let told = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "{told}");
    assert!(!told.contains("budget 1.800e2"), "{told}");
    let Some(python) = checker_python("world-space replay of reduce") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let original = dir.path().join("huesitos.bvh");
    std::fs::write(&original, &bvh).unwrap();
    let keys = dir.path().join("keys.json");
    stdout_of(
        bin()
            .arg("reduce")
            .arg(&original)
            .args(["--position-tolerance", "0.02", "--scheme", "slerp", "-o"])
            .arg(&keys),
    );
    let r = replay(
        &python,
        original.to_str().unwrap(),
        &keys,
        &["--limit", "0.02"],
    );
    assert!(max_displacement(&r) <= 0.02, "{r}");
}

/// The sampler input counts of a GLB's animation 0 (its JSON chunk, read here).
fn input_counts(glb: &Path) -> Vec<u64> {
    let bytes = std::fs::read(glb).unwrap();
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&bytes[20..20 + len]).unwrap();
    let anim = &json["animations"][0];
    anim["samplers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            json["accessors"][s["input"].as_u64().unwrap() as usize]["count"]
                .as_u64()
                .unwrap()
        })
        .collect()
}

/// Channels keyed at their own times (as Blender and three.js export them, and as reduce
/// writes them): every channel is played as glTF plays it at the union of all channels' times,
/// where the skeleton is posed; the checker replays both assets at that union (its own rule
/// for a glTF's frames) and finds every point within LEN.
#[test]
fn gltf_channels_with_their_own_key_times_are_reduced_in_world_space() {
    let dir = tempfile::tempdir().unwrap();
    let uneven = dir.path().join("uneven.glb");
    stdout_of(
        bin()
            .args([
                "reduce",
                CESIUM,
                "--tolerance",
                "1",
                "--scheme",
                "slerp",
                "-o",
            ])
            .arg(&uneven),
    );
    let mut counts = input_counts(&uneven);
    counts.sort_unstable();
    counts.dedup();
    assert!(
        counts.len() > 3,
        "the channels' key counts differ: {counts:?}"
    );
    // Read as keys, every translation channel keyed apart from its rotation is one finding:
    // one warning naming the first channel and counting the others, not one per channel.
    let out = bin()
        .arg("reduce")
        .arg(&uneven)
        .args(["--tolerance", "1", "--translation-tolerance", "0.01", "-o"])
        .arg(dir.path().join("keys.json"))
        .output()
        .unwrap();
    let told = String::from_utf8(out.stderr).unwrap();
    let lines: Vec<&str> = told
        .lines()
        .filter(|l| l.contains("has other key times than the rotation"))
        .collect();
    assert_eq!(lines.len(), 1, "{told}");
    assert!(lines[0].contains("(and 18 other channels: "), "{told}");
    let small = dir.path().join("small.glb");
    stdout_of(
        bin()
            .arg("reduce")
            .arg(&uneven)
            .args(["--position-tolerance", "0.01", "-o"])
            .arg(&small),
    );
    let Some(python) = checker_python("world-space replay of reduce") else {
        return;
    };
    let r = replay(
        &python,
        uneven.to_str().unwrap(),
        &small,
        &["--limit", "0.01", "--default-ends"],
    );
    assert!(max_displacement(&r) > 0.3 * 0.01, "{r}");
}

/// CesiumMan with its armature scaled by `k` (a unit conversion, as an exporter writes one):
/// the GLB's JSON chunk edited, the binary chunk kept.
fn scaled_cesium(k: f64, out: &Path) {
    let bytes =
        std::fs::read(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join(CESIUM))
            .unwrap();
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let mut json: Value = serde_json::from_slice(&bytes[20..20 + len]).unwrap();
    let armature = json["nodes"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|n| n["name"] == "Armature")
        .unwrap();
    let m = armature["matrix"].as_array_mut().unwrap();
    for (i, v) in m.iter_mut().enumerate().take(12) {
        if i % 4 != 3 {
            *v = Value::from(v.as_f64().unwrap() * k);
        }
    }
    let mut text = serde_json::to_vec(&json).unwrap();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let rest = &bytes[20 + len..];
    let mut glb = Vec::new();
    glb.extend_from_slice(&bytes[..8]);
    glb.extend_from_slice(&((12 + 8 + text.len() + rest.len()) as u32).to_le_bytes());
    glb.extend_from_slice(&(text.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&text);
    glb.extend_from_slice(rest);
    std::fs::write(out, glb).unwrap();
}

/// `--shell D` is in world units, as the tolerance is: under an armature scaled by 0.5 the
/// shell's points are D from their joints in the scene (the checker's `--world-shell`, its own
/// σ from the rest scales), and every point stays within LEN.
#[test]
fn the_shell_is_in_world_units_under_a_scaled_armature() {
    let Some(python) = checker_python("world-space replay of reduce") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let scaled = dir.path().join("scaled.glb");
    scaled_cesium(0.5, &scaled);
    let small = dir.path().join("small.glb");
    stdout_of(
        bin()
            .arg("reduce")
            .arg(&scaled)
            .args(["--position-tolerance", "0.005", "--shell", "0.05", "-o"])
            .arg(&small),
    );
    let r = replay(
        &python,
        scaled.to_str().unwrap(),
        &small,
        &["--limit", "0.005", "--world-shell", "0.05"],
    );
    assert!(max_displacement(&r) > 0.3 * 0.005, "{r}");
}
