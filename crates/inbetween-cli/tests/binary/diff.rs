//! `diff A B`: angles per track against closed forms, world-space displacements against the
//! independent reference (`fixtures/world/world_ref.py`: its own BVH reader and forward
//! kinematics), the exit status of `--max-angle`/`--max-position`, and refusals.

use crate::support::{bin, checker_python, python_json};
use serde_json::Value;
use std::path::Path;

fn json_of(cmd: &mut assert_cmd::Command) -> Value {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("a number: {v}"))
}

/// A wheel turning 0° → 45° about z against one turning 10° → 55°: 10° apart at both keys.
#[test]
fn angles_are_the_rotation_between_the_two() {
    let d = json_of(bin().args([
        "diff",
        "fixtures/diff/turned.json",
        "fixtures/diff/turned_more.json",
        "--output-format",
        "json",
    ]));
    let wheel = &d["tracks"][0];
    assert_eq!(wheel["track"], "wheel");
    assert_eq!(wheel["frames"], 2);
    assert!((num(&wheel["max_angle"]) - 10.0).abs() < 1e-12);
    assert!((num(&wheel["mean_angle"]) - 10.0).abs() < 1e-12);
    assert!(wheel["max_world"].is_null() && wheel["max_translation"].is_null());
    assert_eq!(d["total"]["max_angle_track"], "wheel");
    let rad = json_of(bin().args([
        "diff",
        "fixtures/diff/turned.json",
        "fixtures/diff/turned_more.json",
        "--output-format",
        "json",
        "--angles",
        "rad",
    ]));
    assert!((num(&rad["total"]["max_angle"]) - 10f64.to_radians()).abs() < 1e-15);
}

#[test]
fn a_limit_exceeded_exits_1_with_the_report_written() {
    let run = |limit: &str| {
        bin()
            .args([
                "diff",
                "fixtures/diff/turned.json",
                "fixtures/diff/turned_more.json",
            ])
            .args(["--max-angle", limit])
            .output()
            .unwrap()
    };
    let over = run("9.5");
    assert_eq!(over.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&over.stderr);
    assert!(
        stderr.contains(
            "the largest angle, 10.0000 deg (track \"wheel\", 0 s), exceeds --max-angle 9.5"
        ),
        "{stderr}"
    );
    assert!(String::from_utf8_lossy(&over.stdout).starts_with("track"));
    assert_eq!(run("10.5").status.code(), Some(0));
}

#[test]
fn different_tracks_are_refused() {
    let out = bin()
        .args([
            "diff",
            "fixtures/diff/turned.json",
            "fixtures/bvh/cmu_01_01.bvh",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("track \"wheel\" of fixtures/diff/turned.json is not a track of fixtures/bvh/cmu_01_01.bvh"),
        "{stderr}"
    );
    let both = bin().args(["diff", "-", "-"]).output().unwrap();
    assert_eq!(both.status.code(), Some(2));
}

/// CMU 01_01 reduced at 0.5° and played back as BVH: `diff`'s local angles and world
/// displacements (with and without a shell) equal the independent reference's, joint by joint;
/// the keys document itself (interpolated by `diff`) gives the same figures; and compared only
/// at its own keys it is the capture exactly.
#[test]
fn world_displacements_agree_with_the_independent_reference() {
    let dir = tempfile::tempdir().unwrap();
    let (keys, back) = (dir.path().join("keys.json"), dir.path().join("back.bvh"));
    let clip = "fixtures/bvh/cmu_01_01.bvh";
    bin()
        .args([
            "reduce",
            clip,
            "--tolerance",
            "0.5",
            "--translation-tolerance",
            "0.1",
            "-o",
        ])
        .arg(&keys)
        .assert()
        .success();
    bin()
        .arg("interp")
        .arg(&keys)
        .args(["--skeleton", clip, "-o"])
        .arg(&back)
        .assert()
        .success();
    let diff = |b: &Path, extra: &[&str]| {
        json_of(
            bin()
                .args(["diff", clip])
                .arg(b)
                .args(["--output-format", "json"])
                .args(extra),
        )
    };
    let ours = diff(&back, &[]);
    let from_keys = diff(&keys, &[]);
    for (a, b) in ours["tracks"]
        .as_array()
        .unwrap()
        .iter()
        .zip(from_keys["tracks"].as_array().unwrap())
    {
        for field in ["max_angle", "max_world", "mean_world"] {
            assert!(
                (num(&a[field]) - num(&b[field])).abs() < 1e-8,
                "{field} {a} {b}"
            );
        }
    }
    let common = diff(&keys, &["--common-frames"]);
    for t in common["tracks"].as_array().unwrap() {
        // Each track has its own keys: no frame where all are compared, so no world figures.
        assert!(
            num(&t["max_angle"]) < 1e-12 && t["max_world"].is_null(),
            "{t}"
        );
    }
    let Some(python) = checker_python("world-space reference check") else {
        return;
    };
    for shell in [None, Some("5")] {
        use std::ffi::OsStr;
        let mut args: Vec<&OsStr> = vec![OsStr::new(clip), back.as_os_str(), OsStr::new("--json")];
        let mut extra = Vec::new();
        if let Some(d) = shell {
            args.extend([OsStr::new("--shell"), OsStr::new(d)]);
            extra = vec!["--shell", d];
        }
        let reference = python_json(&python, "fixtures/world/world_ref.py", &args);
        let ours = diff(&back, &extra);
        let joints = reference["joints"].as_array().unwrap();
        let tracks = ours["tracks"].as_array().unwrap();
        assert_eq!(joints.len(), tracks.len());
        for (r, t) in joints.iter().zip(tracks) {
            assert_eq!(r["name"], t["track"]);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
            assert!(
                close(num(&t["max_world"]), num(&r["max_displacement"])),
                "{r} {t}"
            );
            assert!(
                close(num(&t["mean_world"]), num(&r["mean_origin_displacement"])),
                "{r} {t}"
            );
            assert!(
                close(num(&t["max_angle"]), num(&r["max_angle_deg"])),
                "{r} {t}"
            );
            let frame = num(&t["max_world_time"]) * 120.0;
            assert!(
                (frame - num(&r["max_displacement_frame"])).abs() < 1e-6,
                "{r} {t}"
            );
        }
    }
}

/// A clip against itself is zero everywhere; CSV carries the same figures as JSON, one row per
/// track and a total row.
#[test]
fn a_clip_against_itself_is_zero_and_csv_has_the_same_rows() {
    let clip = "fixtures/bvh/cmu_01_01.bvh";
    let d = json_of(bin().args([
        "diff",
        clip,
        clip,
        "--output-format",
        "json",
        "--shell",
        "3",
    ]));
    for t in d["tracks"].as_array().unwrap() {
        assert!(num(&t["max_angle"]) < 1e-12, "{t}");
        assert_eq!(num(&t["max_world"]), 0.0, "{t}");
    }
    let csv = crate::support::stdout_of(bin().args([
        "diff",
        "fixtures/diff/turned.json",
        "fixtures/diff/turned_more.json",
        "--output-format",
        "csv",
    ]));
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "kind,track,frames,max_angle,max_angle_time,mean_angle,max_translation,\
         max_translation_time,max_world,max_world_time,mean_world"
    );
    for (line, kind) in lines[1..].iter().zip(["track", "total"]) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(
            (cells[0], cells[1], cells[2]),
            (kind, "wheel", "2"),
            "{line}"
        );
        let angle: f64 = cells[3].parse().unwrap();
        assert!((angle - 10.0).abs() < 1e-12, "{line}");
        assert!(cells[6..].iter().all(|c| c.is_empty()), "{line}");
    }
    assert_eq!(lines.len(), 3);
}

/// CMU 01_01 (120 fps) resampled to 30 fps, compared at the capture's frames with the 30 fps
/// frames played by slerp: the largest angle of every track and the largest world displacement
/// are the independent checker's (`replay_ref.py`: its own BVH reader, scipy's slerp of the 30
/// fps frames taken as keys, its own forward kinematics).
#[test]
fn a_resample_is_measured_as_the_independent_replay_measures_it() {
    let dir = tempfile::tempdir().unwrap();
    let clip = "fixtures/bvh/cmu_01_01.bvh";
    let resampled = dir.path().join("r30.json");
    bin()
        .args(["interp", clip, "--fps", "30", "-o"])
        .arg(&resampled)
        .assert()
        .success();
    let ours = json_of(bin().args(["diff", clip]).arg(&resampled).args([
        "--scheme",
        "slerp",
        "--output-format",
        "json",
    ]));
    let Some(python) = checker_python("independent replay of a resample") else {
        return;
    };
    // The 30 fps frames as keys, for the checker to slerp between.
    let mut doc: Value = serde_json::from_slice(&std::fs::read(&resampled).unwrap()).unwrap();
    for t in doc["tracks"].as_array_mut().unwrap() {
        let frames = t.as_object_mut().unwrap().remove("frames").unwrap();
        t["keys"] = frames;
    }
    let keys = dir.path().join("r30_keys.json");
    std::fs::write(&keys, serde_json::to_vec(&doc).unwrap()).unwrap();
    use std::ffi::OsStr;
    let reference = python_json(
        &python,
        "fixtures/world/replay_ref.py",
        &[OsStr::new(clip), keys.as_os_str(), OsStr::new("--json")],
    );
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
    let joints = reference["joints"].as_array().unwrap();
    for t in ours["tracks"].as_array().unwrap() {
        let r = joints.iter().find(|j| j["name"] == t["track"]).unwrap();
        assert!(
            close(num(&t["max_angle"]), num(&r["max_angle_deg"])),
            "{t} {r}"
        );
    }
    let total = &ours["total"];
    assert!(num(&total["max_angle"]) > 10.0, "{total}");
    assert!(
        close(
            num(&total["max_world"]),
            num(&reference["max_displacement"])
        ),
        "{total} {reference}"
    );
}

/// A glTF asset (CesiumMan) and its reduction as written: `diff` plays B's translation channels
/// as a player does, so its world displacements are the independent glTF player's
/// (`replay_ref.py`: its own node-tree forward kinematics) to float32 time snapping, and its
/// translation difference is within the tolerance the channels were reduced under.
#[test]
fn a_reduced_gltf_asset_is_measured_as_a_player_plays_it() {
    let dir = tempfile::tempdir().unwrap();
    let original = "fixtures/gltf/real/CesiumMan.glb";
    let small = dir.path().join("small.glb");
    bin()
        .args(["reduce", original, "--tolerance", "0.5"])
        .args(["--translation-tolerance", "0.001", "-o"])
        .arg(&small)
        .assert()
        .success();
    let ours = json_of(bin().args(["diff", original]).arg(&small).args([
        "--scheme",
        "slerp",
        "--output-format",
        "json",
    ]));
    let total = &ours["total"];
    assert!(num(&total["max_translation"]) <= 0.001, "{total}");
    let Some(python) = checker_python("independent glTF replay") else {
        return;
    };
    use std::ffi::OsStr;
    let reference = python_json(
        &python,
        "fixtures/world/replay_ref.py",
        &[
            OsStr::new(original),
            small.as_os_str(),
            OsStr::new("--json"),
        ],
    );
    let joints = reference["joints"].as_array().unwrap();
    let mut compared = 0;
    for t in ours["tracks"].as_array().unwrap() {
        let r = joints.iter().find(|j| j["name"] == t["track"]).unwrap();
        let (a, b) = (num(&t["max_world"]), num(&r["max_displacement"]));
        assert!((a - b).abs() <= 1e-7, "{t} {r}");
        compared += 1;
    }
    assert!(compared > 10 && num(&total["max_world"]) > 1e-3, "{total}");
}
