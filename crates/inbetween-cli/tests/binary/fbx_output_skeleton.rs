//! FBX output on a `--skeleton` template (`interp keys.json --skeleton clip.bvh -o out.fbx`,
//! `convert … --skeleton clip.bvh -o out.fbx`): the file, read back by ufbx (the FBX reader of
//! `inbetween_io`), is the BVH output of the same command, read back by the BVH reader — the
//! same tracks, rotations and positions at every frame, within float32 — from keys `reduce`
//! made of the clip, at 30 and 29.97 fps; a hinge joint and a joint without position channels
//! are written as their channels carry them (what BVH output writes); and the refusals that
//! still apply.

use super::fbx_output::{ANGLE_TOL, POSITION_TOL, frames, read};
use crate::support::{bin, fixtures, stderr_of};
use std::ffi::OsStr;
use std::path::Path;

/// Runs the binary with `args`, then `-o out`, which must succeed.
fn run(args: &[&OsStr], out: &Path) {
    bin().args(args).arg("-o").arg(out).assert().success();
}

/// The FBX file `fbx` read back against the BVH file `bvh` (both at `fps`): the same tracks,
/// the same frames (the FBX reader starts at the scene's first frame, the BVH's frame 0 at
/// `start` seconds), every rotation within [`ANGLE_TOL`], translations on the same tracks and
/// within [`POSITION_TOL`]. Returns the largest angle (rad) and relative position error.
fn same_motion(bvh: &Path, fbx: &Path, fps: inbetween::Fps, start: f64) -> (f64, f64) {
    let (a, b) = (read(bvh), read(fbx));
    assert_eq!(a.fps, Some(fps), "{}: the BVH's rate", bvh.display());
    assert_eq!(b.fps, Some(fps), "{}: the scene's rate", fbx.display());
    let (a, b) = (frames(&a, fps), frames(&b, fps));
    for name in b.keys() {
        assert!(a.contains_key(name), "{}: track {name}", fbx.display());
    }
    let (mut worst_angle, mut worst_pos) = (0.0f64, 0.0f64);
    for (name, (times, rots, trans)) in &a {
        let label = format!("{} at {fps}: track {name}", fbx.display());
        let Some((btimes, brots, btrans)) = b.get(name) else {
            // Not a track when read back: the identity at every frame, at rest (ufbx's reader
            // drops it).
            assert!(
                rots.iter()
                    .all(|q| q.angle_between(glam::DQuat::IDENTITY) < ANGLE_TOL)
                    && trans.iter().all(Option::is_none),
                "{label}: missing from the FBX"
            );
            continue;
        };
        assert_eq!(times.len(), btimes.len(), "{label}: frames");
        assert_eq!(
            trans.iter().any(Option::is_some),
            btrans.iter().any(Option::is_some),
            "{label}: translations"
        );
        for k in 0..times.len() {
            assert!(
                (times[k] - (btimes[k] + start)).abs() < 1e-9,
                "{label}: time of frame {k}"
            );
            let angle = rots[k].angle_between(brots[k]);
            assert!(angle < ANGLE_TOL, "{label}: frame {k} is {angle} rad off");
            worst_angle = worst_angle.max(angle);
            if let (Some(Some(p)), Some(Some(q))) = (trans.get(k), btrans.get(k)) {
                let d = (*p - *q).length() / p.length().max(1.0);
                assert!(d < POSITION_TOL, "{label}: frame {k} position {p} vs {q}");
                worst_pos = worst_pos.max(d);
            }
        }
    }
    (worst_angle, worst_pos)
}

/// `reduce clip.bvh` → keys.json → `interp keys.json --skeleton clip.bvh --fps rate` into FBX
/// and into BVH: the two read back the same at every frame, at 30 and 29.97, for the CMU clip
/// and for the clip of mixed rotation orders (a joint with position and rotation channels
/// interleaved below the root, a joint without channels).
#[test]
fn interp_skeleton_fbx_is_the_bvh_output_at_30_and_2997() {
    let dir = tempfile::tempdir().unwrap();
    for clip in ["bvh/cmu_01_01.bvh", "bvh/mixed_orders.bvh"] {
        let src = fixtures().join(clip);
        let keys = dir.path().join("keys.json");
        run(
            &[
                "reduce".as_ref(),
                src.as_os_str(),
                "--tolerance".as_ref(),
                "0.5".as_ref(),
                "--translation-tolerance".as_ref(),
                "0.01".as_ref(),
            ],
            &keys,
        );
        for rate in ["30", "29.97"] {
            let (bvh, fbx) = (dir.path().join("back.bvh"), dir.path().join("back.fbx"));
            for out in [&bvh, &fbx] {
                let args: [&OsStr; 6] = [
                    "interp".as_ref(),
                    keys.as_os_str(),
                    "--skeleton".as_ref(),
                    src.as_os_str(),
                    "--fps".as_ref(),
                    rate.as_ref(),
                ];
                run(&args, out);
            }
            let fps = inbetween::Fps::parse(rate).unwrap();
            let (a, p) = same_motion(&bvh, &fbx, fps, 0.0);
            eprintln!("{clip} at {rate}: {a:.2e} rad, {p:.2e} relative");
        }
    }
}

/// `convert keys.json --skeleton clip.bvh -o out.fbx`: keys of one grid (the clip's own, as
/// `convert` writes them) read back as `convert`'s BVH output of them; keys `reduce` kept (each
/// track its own frames, which BVH output refuses) read back, at each track's key frames, as
/// the keys themselves.
#[test]
fn convert_skeleton_fbx_is_the_bvh_output_and_keeps_reduced_keys() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("bvh/cmu_01_01.bvh");
    let keys = dir.path().join("keys.json");
    run(&["convert".as_ref(), src.as_os_str()], &keys);
    let (bvh, fbx) = (dir.path().join("back.bvh"), dir.path().join("back.fbx"));
    for out in [&bvh, &fbx] {
        let args: [&OsStr; 4] = [
            "convert".as_ref(),
            keys.as_os_str(),
            "--skeleton".as_ref(),
            src.as_os_str(),
        ];
        run(&args, out);
    }
    let fps = inbetween::Fps::new(120, 1).unwrap();
    let (a, p) = same_motion(&bvh, &fbx, fps, 0.0);
    eprintln!("convert, one grid: {a:.2e} rad, {p:.2e} relative");

    let reduced = dir.path().join("reduced.json");
    run(
        &[
            "reduce".as_ref(),
            src.as_os_str(),
            "--tolerance".as_ref(),
            "1".as_ref(),
            "--translation-tolerance".as_ref(),
            "0.1".as_ref(),
        ],
        &reduced,
    );
    let out = dir.path().join("reduced.fbx");
    let args: [&OsStr; 4] = [
        "convert".as_ref(),
        reduced.as_os_str(),
        "--skeleton".as_ref(),
        src.as_os_str(),
    ];
    run(&args, &out);
    let (want, got) = (frames(&read(&reduced), fps), frames(&read(&out), fps));
    assert!(got.keys().all(|name| want.contains_key(name)));
    let mut sparse = false;
    for (name, (times, rots, trans)) in &want {
        let Some((bt, br, btr)) = got.get(name) else {
            // Dropped by ufbx's reader: the identity at every key, at rest.
            assert!(
                rots.iter()
                    .all(|q| q.angle_between(glam::DQuat::IDENTITY) < ANGLE_TOL)
                    && trans.iter().all(Option::is_none),
                "{name}: missing from the FBX"
            );
            continue;
        };
        sparse |= times.len() < bt.len();
        for (k, t) in times.iter().enumerate() {
            // The key's frame among the read-back frames (every frame of the scene).
            let i = bt
                .iter()
                .position(|b| (b - t).abs() < 1e-9)
                .unwrap_or_else(|| panic!("{name}: no frame at key {k}"));
            let angle = rots[k].angle_between(br[i]);
            assert!(angle < ANGLE_TOL, "{name} key {k}: {angle} rad");
            if let (Some(Some(p)), Some(Some(q))) = (trans.get(k), btr.get(i)) {
                let d = (*p - *q).length() / p.length().max(1.0);
                assert!(d < POSITION_TOL, "{name} key {k}: {p} vs {q}");
            }
            assert_eq!(
                trans.get(k).copied().flatten().is_some(),
                btr.get(i).copied().flatten().is_some(),
                "{name} key {k}: a translation"
            );
        }
    }
    assert!(sparse, "the reduced keys are not every frame");
}

/// A template with a hinge (`Xrotation` alone) and a joint without position channels, given
/// keys that turn the hinge off its axis and move the other joint: FBX output writes what the
/// BVH output writes (the hinge's angle about its axis, the joint at its `OFFSET`), through
/// `interp` and `convert` alike.
#[test]
fn skeleton_fbx_writes_what_the_channels_carry() {
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("hinge.bvh");
    std::fs::write(
        &template,
        "HIERARCHY\nROOT root\n{\nOFFSET 0 1 0\nCHANNELS 6 Xposition Yposition Zposition \
         Zrotation Xrotation Yrotation\nJOINT knee\n{\nOFFSET 0 -2 0\nCHANNELS 1 Xrotation\n\
         End Site\n{\nOFFSET 0 -2 0\n}\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n\
         0 1 0 0 0 0 0\n",
    )
    .unwrap();
    // The knee's keys turn about tilted axes (rotation vectors, degrees), and carry
    // translations its joint has no channels for.
    let keys = dir.path().join("keys.json");
    std::fs::write(
        &keys,
        r#"{"fps": 10, "tracks": [
{"name": "root", "keys": [
 {"frame": 0, "rotvec": [0, 10, 0], "translation": [0, 1, 0]},
 {"frame": 1, "rotvec": [5, 20, 0], "translation": [0.5, 1, 0]},
 {"frame": 2, "rotvec": [5, 30, 10], "translation": [1, 1.5, 0]}]},
{"name": "knee", "keys": [
 {"frame": 0, "rotvec": [20, 10, 0], "translation": [3, 3, 3]},
 {"frame": 1, "rotvec": [40, 15, 5], "translation": [3, 3, 3]},
 {"frame": 2, "rotvec": [60, 5, 10], "translation": [3, 3, 3]}]}]}"#,
    )
    .unwrap();
    let fps = inbetween::Fps::new(10, 1).unwrap();
    for command in ["interp", "convert"] {
        let (bvh, fbx) = (dir.path().join("out.bvh"), dir.path().join("out.fbx"));
        for out in [&bvh, &fbx] {
            let args: [&OsStr; 4] = [
                command.as_ref(),
                keys.as_os_str(),
                "--skeleton".as_ref(),
                template.as_os_str(),
            ];
            run(&args, out);
        }
        same_motion(&bvh, &fbx, fps, 0.0);
        // The BVH output did drop the knee's off-axis turn: its keys are not what it wrote.
        let (given, written) = (frames(&read(&keys), fps), frames(&read(&bvh), fps));
        let off = given["knee"].1[1].angle_between(written["knee"].1[1]);
        assert!(
            off > 0.1,
            "{command}: the knee's key 1 is {off} rad from the BVH's"
        );
    }
}

/// What `--skeleton` still refuses with FBX output: a format other than BVH or FBX, what FBX
/// has no place for (`--velocity`, `--tracks`), and keys that miss a joint or a translation
/// its position channels need; nothing is written.
#[test]
fn skeleton_fbx_refusals() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("bvh/cmu_01_01.bvh");
    let keys = dir.path().join("keys.json");
    run(&["convert".as_ref(), src.as_os_str()], &keys);
    let text = std::fs::read_to_string(&keys).unwrap();
    // The Hips keys without their translations.
    let bare = dir.path().join("bare.json");
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut doc = doc;
    for key in doc["tracks"][0]["keys"].as_array_mut().unwrap() {
        key.as_object_mut().unwrap().remove("translation");
    }
    assert_eq!(doc["tracks"][0]["name"], "Hips");
    std::fs::write(&bare, doc.to_string()).unwrap();
    let lone = dir.path().join("lone.json");
    std::fs::write(
        &lone,
        r#"{"tracks": [{"name": "Hips", "keys": [
            {"time": 0, "quat": [1, 0, 0, 0], "translation": [0, 0, 0]},
            {"time": 1, "quat": [1, 0, 0, 0], "translation": [0, 0, 0]}]}]}"#,
    )
    .unwrap();
    let fbx = dir.path().join("x.fbx");
    let usda = dir.path().join("x.usda");
    let with = |cmd: &'static str, keys: &Path, extra: &[&'static str], out: &Path| {
        let mut args: Vec<std::ffi::OsString> = vec![
            cmd.into(),
            keys.into(),
            "--skeleton".into(),
            src.clone().into(),
        ];
        args.extend(extra.iter().map(Into::into));
        args.extend(["-o".into(), out.into()]);
        args
    };
    let cases = [
        (
            with("interp", &keys, &[], &usda),
            "--skeleton: the output is neither BVH nor FBX",
        ),
        (
            with("convert", &keys, &[], &usda),
            "--skeleton: the output is neither BVH nor FBX",
        ),
        (
            with("interp", &keys, &["--velocity"], &fbx),
            "--velocity: FBX has no place for angular velocities",
        ),
        (
            with("interp", &keys, &["--tracks", "Hips"], &fbx),
            "--tracks: an FBX skeleton is written with every joint",
        ),
        (
            with("interp", &lone, &[], &fbx),
            "no track for joint \"LHipJoint\"",
        ),
        (
            with("convert", &lone, &[], &fbx),
            "no track for joint \"LHipJoint\"",
        ),
        (
            with("interp", &bare, &[], &fbx),
            "track \"Hips\" has no translations, which joint \"Hips\"",
        ),
        (
            with("convert", &bare, &[], &fbx),
            "track \"Hips\" has no translations, which joint \"Hips\"",
        ),
    ];
    for (args, says) in cases {
        let err = stderr_of(bin().args(&args), 2);
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!fbx.exists() && !usda.exists(), "{args:?} wrote a file");
    }
}
