//! `diff A B`: angles per track against closed forms, world-space displacements against the
//! independent reference (`fixtures/world/world_ref.py`: its own BVH reader and forward
//! kinematics), the exit status of `--max-angle`/`--max-position`, and refusals.

use crate::support::{bin, checker_python, fixtures, python_json};
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
            // diff measures the points reduce bounds: leaf joints' default ends too.
            OsStr::new("--default-ends"),
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

/// The largest world displacement (`total.max_world`) and the exit status of `diff A B
/// --max-position LEN --output-format json`, with `more` options.
fn max_world(a: &str, b: &Path, len: &str, more: &[&str]) -> (f64, Option<i32>) {
    let out = bin()
        .arg("diff")
        .arg(a)
        .arg(b)
        .args(["--max-position", len, "--output-format", "json"])
        .args(more)
        .output()
        .unwrap();
    let report: Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(&out.stderr)));
    (num(&report["total"]["max_world"]), out.status.code())
}

/// A glTF asset reduced for slerp (the glTF player's LINEAR) within a world tolerance is
/// within it as `diff` plays it without `--scheme`: each sampler as glTF plays it, as `interp`
/// does; replayed by bezier (`--scheme bezier`, diff's default before) it looks further off
/// than it plays and fails the same `--max-position`.
#[test]
fn a_reduced_gltf_asset_is_within_its_tolerance_as_played() {
    let dir = tempfile::tempdir().unwrap();
    let original = "fixtures/gltf/real/CesiumMan.glb";
    let small = dir.path().join("small.glb");
    bin()
        .args(["reduce", original, "--scheme", "slerp"])
        .args(["--position-tolerance", "0.05", "-o"])
        .arg(&small)
        .assert()
        .success();
    let (played, status) = max_world(original, &small, "0.05", &[]);
    let (bezier, bezier_status) = max_world(original, &small, "0.05", &["--scheme", "bezier"]);
    let (slerp, _) = max_world(original, &small, "0.05", &["--scheme", "slerp"]);
    let figures = format!("as played {played}, by bezier {bezier}");
    assert_eq!(status, Some(0), "{figures}");
    assert!(played <= 0.05 && played > 0.04, "{figures}");
    assert_eq!(played, slerp, "LINEAR samplers play by slerp: {figures}");
    assert_eq!(bezier_status, Some(1), "{figures}");
    assert!(bezier > 0.05 && bezier > played, "{figures}");
}

/// The keys `reduce --animation N -o keys.json` writes for one animation of an asset with
/// several are checked against that animation: `--animation` chooses in the side that has
/// animations (either side), and is refused when neither has.
#[test]
fn animation_chooses_in_the_side_that_has_animations() {
    let dir = tempfile::tempdir().unwrap();
    let asset = "fixtures/gltf/real/RiggedSimple.gltf";
    let keys = dir.path().join("keys.json");
    bin()
        .args([
            "reduce",
            asset,
            "--animation",
            "0",
            "--position-tolerance",
            "0.01",
            "-o",
        ])
        .arg(&keys)
        .assert()
        .success();
    let (world, status) = max_world(asset, &keys, "0.01", &["--animation", "0"]);
    assert_eq!(status, Some(0), "{world}");
    assert!(world <= 0.01, "{world}");
    let reversed = bin()
        .arg("diff")
        .arg(&keys)
        .arg(asset)
        .args(["--animation", "0", "--max-angle", "180"])
        .output()
        .unwrap();
    assert_eq!(
        reversed.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&reversed.stderr)
    );
    let neither = bin()
        .arg("diff")
        .arg(&keys)
        .arg(&keys)
        .args(["--animation", "0"])
        .output()
        .unwrap();
    assert_eq!(neither.status.code(), Some(2));
    let err = String::from_utf8_lossy(&neither.stderr);
    assert!(err.contains("is neither glTF nor FBX"), "{err}");
}

/// The rotation channels of a `.glb` asset's first animation as stored, read by the test's own
/// small reader (the JSON chunk, the BIN chunk, float accessors): per channel, its node's name,
/// its `LINEAR` key times (float32 widened) and its rotations (x, y, z, w), normalised.
fn glb_rotations(path: &Path) -> Vec<(String, Vec<f64>, Vec<[f64; 4]>)> {
    let b = std::fs::read(path).unwrap();
    let word = |i: usize| u32::from_le_bytes(b[i..i + 4].try_into().unwrap()) as usize;
    assert_eq!(
        (&b[..4], word(16)),
        (&b"glTF"[..], 0x4E4F_534A),
        "GLB, JSON first"
    );
    let doc: Value = serde_json::from_slice(&b[20..20 + word(12)]).unwrap();
    let bin_at = 20 + word(12);
    assert_eq!(word(bin_at + 4), 0x004E_4942, "the BIN chunk");
    let bin = &b[bin_at + 8..bin_at + 8 + word(bin_at)];
    let index = |v: &Value| v.as_u64().unwrap() as usize;
    let accessor = |i: &Value| -> Vec<Vec<f64>> {
        let a = &doc["accessors"][index(i)];
        assert!(
            a["componentType"] == 5126 && a.get("sparse").is_none(),
            "{a}"
        );
        let width = match a["type"].as_str().unwrap() {
            "SCALAR" => 1,
            "VEC4" => 4,
            t => panic!("{t}"),
        };
        let view = &doc["bufferViews"][index(&a["bufferView"])];
        assert_eq!(view["buffer"], 0);
        let at = |v: &Value| v.as_u64().unwrap_or(0) as usize;
        let start = at(&view["byteOffset"]) + at(&a["byteOffset"]);
        let stride = view["byteStride"]
            .as_u64()
            .map_or(4 * width, |s| s as usize);
        let float = |o: usize| f64::from(f32::from_le_bytes(bin[o..o + 4].try_into().unwrap()));
        (0..index(&a["count"]))
            .map(|k| {
                (0..width)
                    .map(|c| float(start + k * stride + 4 * c))
                    .collect()
            })
            .collect()
    };
    let anim = &doc["animations"][0];
    let channels = anim["channels"].as_array().unwrap();
    channels
        .iter()
        .filter(|c| c["target"]["path"] == "rotation")
        .map(|c| {
            let s = &anim["samplers"][index(&c["sampler"])];
            assert_eq!(s["interpolation"].as_str().unwrap_or("LINEAR"), "LINEAR");
            let node = &doc["nodes"][index(&c["target"]["node"])];
            let times = accessor(&s["input"]).iter().map(|v| v[0]).collect();
            let values = accessor(&s["output"])
                .iter()
                .map(|v| {
                    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                    [v[0] / n, v[1] / n, v[2] / n, v[3] / n]
                })
                .collect();
            (node["name"].as_str().unwrap().to_string(), times, values)
        })
        .collect()
}

/// glTF 2.0 Appendix C's LINEAR rotation at `t`: slerp between the keys around it, the shorter
/// way; the end keys hold outside.
fn play_linear(times: &[f64], values: &[[f64; 4]], t: f64) -> [f64; 4] {
    let last = times.len() - 1;
    if t <= times[0] {
        return values[0];
    }
    if t >= times[last] {
        return values[last];
    }
    let k = times.partition_point(|&x| x <= t) - 1;
    let s = (t - times[k]) / (times[k + 1] - times[k]);
    let (a, mut b) = (values[k], values[k + 1]);
    let mut d: f64 = (0..4).map(|i| a[i] * b[i]).sum();
    if d < 0.0 {
        b = b.map(|x| -x);
        d = -d;
    }
    let theta = d.min(1.0).acos();
    let (wa, wb) = if theta < 1e-12 {
        (1.0 - s, s)
    } else {
        (
            ((1.0 - s) * theta).sin() / theta.sin(),
            (s * theta).sin() / theta.sin(),
        )
    };
    let q: Vec<f64> = (0..4).map(|i| wa * a[i] + wb * b[i]).collect();
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    [q[0] / n, q[1] / n, q[2] / n, q[3] / n]
}

/// The angle in degrees of the rotation from `a` to `b` (x, y, z, w): 2·atan2(|v|, |w|) of
/// a⁻¹·b.
fn angle_deg(a: [f64; 4], b: [f64; 4]) -> f64 {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    // conj(a) · b
    let w = aw * bw + ax * bx + ay * by + az * bz;
    let x = aw * bx - ax * bw - (ay * bz - az * by);
    let y = aw * by - ay * bw - (az * bx - ax * bz);
    let z = aw * bz - az * bw - (ax * by - ay * bx);
    (2.0 * (x * x + y * y + z * z).sqrt().atan2(w.abs())).to_degrees()
}

/// A float32 key time on its frame of 30 fps when within two float32 ulps of it (docs/spec.md
/// §3 glTF, *Rate and times*), else as stored.
fn snapped(t: f64) -> f64 {
    let frame = (t * 30.0).round() / 30.0;
    let stored = t as f32;
    let ulp = f64::from(f32::from_bits(stored.to_bits() + 1) - stored);
    if (t - frame).abs() <= 2.0 * ulp {
        frame
    } else {
        t
    }
}

/// `diff`'s largest angle per track for a glTF B without `--scheme` is the angle to B as the
/// glTF player plays it, replayed here independently (the test's own GLB reader, Appendix C's
/// slerp on B's stored times, at A's key times as inbetween reads them), within 1e-6°.
#[test]
fn gltf_angles_are_those_of_an_independent_replay() {
    let dir = tempfile::tempdir().unwrap();
    let original = "fixtures/gltf/real/CesiumMan.glb";
    let small = dir.path().join("small.glb");
    bin()
        .args(["reduce", original, "--scheme", "slerp"])
        .args(["--position-tolerance", "0.05", "-o"])
        .arg(&small)
        .assert()
        .success();
    let ours = json_of(
        bin()
            .args(["diff", original])
            .arg(&small)
            .args(["--output-format", "json"]),
    );
    let a = glb_rotations(&fixtures().join("gltf/real/CesiumMan.glb"));
    let b = glb_rotations(&small);
    let tracks = ours["tracks"].as_array().unwrap();
    assert_eq!(tracks.len(), a.len());
    let mut largest: f64 = 0.0;
    for (name, times, keys) in &a {
        let (_, b_times, b_keys) = b.iter().find(|(n, _, _)| n == name).unwrap();
        let replayed = times
            .iter()
            .zip(keys)
            .map(|(&t, &q)| angle_deg(q, play_linear(b_times, b_keys, snapped(t))))
            .fold(0.0, f64::max);
        let row = tracks.iter().find(|t| t["track"] == name.as_str()).unwrap();
        let reported = num(&row["max_angle"]);
        assert!(
            (reported - replayed).abs() <= 1e-6,
            "{name}: diff {reported}°, replayed {replayed}°"
        );
        largest = largest.max(replayed);
    }
    assert!(
        largest > 1.0,
        "a reduction that moves something: {largest}°"
    );
}

/// glTF `STEP` and `CUBICSPLINE` samplers are played as authored: the asset against itself is
/// zero (to rounding), and against its own `interp` bake at 240 fps, either way round, within
/// float32 storage; replayed by bezier through its frames (`--scheme bezier`) the held steps
/// and the cubic's shape are not what the asset plays.
#[test]
fn step_and_cubicspline_samplers_are_played_as_authored() {
    let dir = tempfile::tempdir().unwrap();
    let asset = "fixtures/gltf/samplers.gltf";
    let fine = dir.path().join("fine.glb");
    bin()
        .args(["interp", asset, "--fps", "240", "-o"])
        .arg(&fine)
        .assert()
        .success();
    let diff = |a: &Path, b: &Path, more: &[&str]| {
        json_of(
            bin()
                .arg("diff")
                .arg(a)
                .arg(b)
                .args(["--output-format", "json"])
                .args(more),
        )
    };
    let asset = Path::new(asset);
    let itself = diff(asset, asset, &[]);
    let names: Vec<&str> = itself["tracks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["track"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"Mixed/step") && names.contains(&"Mixed/cubic"));
    assert!(num(&itself["total"]["max_angle"]) < 1e-12, "{itself}");
    assert_eq!(num(&itself["total"]["max_translation"]), 0.0, "{itself}");
    for (a, b) in [(asset, fine.as_path()), (fine.as_path(), asset)] {
        let played = diff(a, b, &[]);
        for t in played["tracks"].as_array().unwrap() {
            assert!(
                num(&t["max_angle"]) < 1e-4,
                "{} {}: {t}",
                a.display(),
                b.display()
            );
        }
        assert!(num(&played["total"]["max_translation"]) < 1e-5, "{played}");
    }
    // The bake's frames against the asset replayed by bezier through its 30 fps frames.
    let bezier = diff(&fine, asset, &["--scheme", "bezier"]);
    let step = bezier["tracks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["track"] == "Mixed/step")
        .unwrap();
    assert!(num(&step["max_angle"]) > 1.0, "{step}");
}

/// A keys document plays by the scheme it records: `reduce --scheme nlerp` writes
/// `"scheme": "nlerp"`, and `interp` and `diff` play the keys by nlerp without `--scheme` (the
/// same bytes as with `--scheme nlerp`, other bytes than bezier's), `diff` finds them within the
/// tolerance they were reduced under, `--scheme` still overrides, and `convert` keeps the field.
#[test]
fn a_keys_document_plays_by_the_scheme_it_records() {
    let dir = tempfile::tempdir().unwrap();
    let keys = dir.path().join("keys.json");
    let clip = "fixtures/bvh/cmu_01_01.bvh";
    bin()
        .args(["reduce", clip, "--scheme", "nlerp", "--tolerance", "0.5"])
        .args(["--translation-tolerance", "0.1", "-o"])
        .arg(&keys)
        .assert()
        .success();
    let doc: Value = serde_json::from_slice(&std::fs::read(&keys).unwrap()).unwrap();
    assert_eq!(doc["scheme"], "nlerp");
    let interp = |scheme: Option<&str>| {
        let mut cmd = bin();
        cmd.arg("interp").arg(&keys).args(["--fps", "120"]);
        if let Some(s) = scheme {
            cmd.args(["--scheme", s]);
        }
        cmd.output().unwrap().stdout
    };
    let played = interp(None);
    assert!(!played.is_empty());
    assert_eq!(played, interp(Some("nlerp")));
    assert_ne!(played, interp(Some("bezier")));
    let max_angle = |more: &[&str]| {
        let d = json_of(
            bin()
                .args(["diff", clip])
                .arg(&keys)
                .args(["--output-format", "json"])
                .args(more),
        );
        num(&d["total"]["max_angle"])
    };
    let as_recorded = max_angle(&[]);
    assert!(as_recorded <= 0.5 + 1e-9, "{as_recorded}");
    assert_eq!(as_recorded, max_angle(&["--scheme", "nlerp"]));
    assert_ne!(as_recorded, max_angle(&["--scheme", "bezier"]));
    let copy = dir.path().join("copy.json");
    bin()
        .arg("convert")
        .arg(&keys)
        .arg("-o")
        .arg(&copy)
        .assert()
        .success();
    let doc: Value = serde_json::from_slice(&std::fs::read(&copy).unwrap()).unwrap();
    assert_eq!(doc["scheme"], "nlerp");
}
