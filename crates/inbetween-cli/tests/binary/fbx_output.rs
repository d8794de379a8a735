//! FBX output (`-o clip.fbx`): every file `interp` and `convert` write is read back by ufbx (the
//! FBX reader of `inbetween_io`, which samples what ufbx evaluates at each frame of the scene's
//! rate) and compared, frame by frame, with the tool's own frames of the same input — from BVH,
//! glTF, FBX and USD inputs, at 24, 30 and 29.97 fps; and a reduced file, read back the same
//! way, plays within its tolerance at every input frame.

use crate::support::{bin, fixtures, stderr_of};
use inbetween_io::document::Document;
use inbetween_io::{ReadOptions, read_path};
use std::collections::HashMap;
use std::path::Path;

/// The largest angle (radians) between a frame and its read-back: the keys are float32 degrees,
/// a step of 2^-17 degrees (7.6e-6°, 1.3e-7 rad) at up to 360°, three of them per rotation.
pub(super) const ANGLE_TOL: f64 = 1e-6;

/// Relative error of a read-back position: float32.
pub(super) const POSITION_TOL: f64 = 2e-7;

pub(super) fn read(path: &Path) -> Document {
    read_path(path, None, &ReadOptions::default()).unwrap().0
}

/// Each track of `doc` by name: its times (s), rotations and translations.
pub(super) type Frames = (Vec<f64>, Vec<glam::DQuat>, Vec<Option<glam::DVec3>>);

pub(super) fn frames(doc: &Document, fps: inbetween::Fps) -> HashMap<String, Frames> {
    doc.tracks
        .iter()
        .map(|t| {
            let name = t.name.clone().expect("named tracks");
            let times = doc.track_times(t, fps, 1).unwrap();
            let rots = t.keys.iter().map(|k| k.rot).collect();
            (name, (times, rots, t.translations.clone()))
        })
        .collect()
}

/// `interp input --fps rate -o clip.fbx`, read back, against `interp input --fps rate -o
/// frames.json` (quaternions and positions, f64): every track, every frame. Returns the largest
/// angle and relative position error.
fn interp_reads_back(input: &Path, rate: &str, extra: &[&str]) -> (f64, f64) {
    let dir = tempfile::tempdir().unwrap();
    let (fbx, json) = (dir.path().join("clip.fbx"), dir.path().join("frames.json"));
    for out in [&fbx, &json] {
        bin()
            .arg("interp")
            .arg(input)
            .args(["--fps", rate])
            .args(extra)
            .arg("-o")
            .arg(out)
            .assert()
            .success();
    }
    let fps = inbetween::Fps::parse(rate).unwrap();
    let (src, back) = (read(&json), read(&fbx));
    assert_eq!(back.fps, Some(fps), "{}: the scene's rate", input.display());
    let (src, back) = (frames(&src, fps), frames(&back, fps));
    let (mut worst_angle, mut worst_pos) = (0.0f64, 0.0f64);
    for (name, (times, rots, trans)) in &src {
        let label = format!("{} at {rate}: track {name}", input.display());
        let Some((btimes, brots, btrans)) = back.get(name) else {
            // Not a track when read back: the identity at every frame (ufbx's reader drops it).
            assert!(
                rots.iter()
                    .all(|q| q.angle_between(glam::DQuat::IDENTITY) < ANGLE_TOL),
                "{label}: missing from the FBX"
            );
            continue;
        };
        // Every frame a key; the reader starts the clip at the stack's start, the first frame.
        assert_eq!(times.len(), btimes.len(), "{label}: frames");
        let start = times[0];
        for (k, i) in (0..times.len()).enumerate() {
            let t = btimes[k] + start;
            assert!((times[i] - t).abs() < 1e-9, "{label}: time of frame {k}");
            let angle = rots[i].angle_between(brots[k]);
            assert!(angle < ANGLE_TOL, "{label}: frame {k} is {angle} rad off");
            worst_angle = worst_angle.max(angle);
            if let (Some(Some(p)), Some(Some(b))) = (trans.get(i), btrans.get(k)) {
                let d = (*p - *b).length() / p.length().max(1.0);
                assert!(
                    d < POSITION_TOL,
                    "{label}: frame {k} position {p} read back {b}"
                );
                worst_pos = worst_pos.max(d);
            }
        }
    }
    (worst_angle, worst_pos)
}

#[test]
fn interp_fbx_reads_back_every_frame_from_bvh_gltf_fbx_and_usd_at_24_30_and_2997() {
    let f = fixtures();
    let inputs: [(std::path::PathBuf, &[&str]); 6] = [
        (f.join("bvh/cmu_01_01.bvh"), &[]),
        (f.join("bvh/mixed_orders.bvh"), &[]),
        (f.join("gltf/real/CesiumMan.glb"), &[]),
        (f.join("fbx/real/huesitos.fbx"), &[]),
        (f.join("fbx/closed_empties_zxy_24.fbx"), &[]),
        (f.join("usd/skel_closed_24.usda"), &[]),
    ];
    for (input, extra) in &inputs {
        for rate in ["24", "30", "29.97"] {
            let (a, p) = interp_reads_back(input, rate, extra);
            eprintln!(
                "{} at {rate}: {a:.2e} rad, {p:.2e} relative",
                input.display()
            );
        }
    }
}

#[test]
fn fbx_output_keeps_each_joints_rotation_order_unit_and_up_axis() {
    let dir = tempfile::tempdir().unwrap();
    let fbx = dir.path().join("clip.fbx");
    let src = fixtures().join("bvh/mixed_orders.bvh");
    bin()
        .arg("interp")
        .arg(&src)
        .args(["--fps", "30", "-o"])
        .arg(&fbx)
        .assert()
        .success();
    let back = read(&fbx);
    let clip = back.skeleton.as_deref().expect("a BVH clip");
    let order = |name: &str| {
        let j = clip.joint(name).unwrap();
        j.rotation().map(|(s, _)| s.as_str().to_string())
    };
    // Each joint's own channel order (Hips ZXY, Chest ZYX, LeftArm YXZ), read back from the
    // node's RotationOrder.
    assert_eq!(order("Hips").as_deref(), Some("ZXY"));
    assert_eq!(order("Chest").as_deref(), Some("ZYX"));
    assert_eq!(order("LeftArm").as_deref(), Some("YXZ"));
    // End sites come back as the joints' ends.
    assert_eq!(
        clip.joint("LeftArm").unwrap().end_site(),
        Some([11.0, 0.0, 0.0])
    );
    // BVH declares no unit: centimetres, Y up.
    assert_eq!(back.unit_meters, Some(0.01));
    assert_eq!(back.z_up, Some(false));
    // An FBX input's own unit and up axis (Z up, inches) are kept.
    let zup = fixtures().join("fbx/zup_inches_ascii.fbx");
    let (src_doc, out) = (read(&zup), dir.path().join("zup.fbx"));
    bin()
        .arg("interp")
        .arg(&zup)
        .args(["--fps", "24", "-o"])
        .arg(&out)
        .assert()
        .success();
    let back = read(&out);
    assert_eq!(src_doc.z_up, Some(true));
    assert_eq!(back.z_up, Some(true));
    let (a, b) = (src_doc.unit_meters.unwrap(), back.unit_meters.unwrap());
    assert!(
        (a - 0.0254).abs() < 1e-12 && (a - b).abs() < 1e-12,
        "{a} {b}"
    );
}

#[test]
fn convert_fbx_writes_the_keys_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("bvh/cmu_01_01.bvh");
    let fbx = dir.path().join("keys.fbx");
    bin()
        .arg("convert")
        .arg(&src)
        .arg("-o")
        .arg(&fbx)
        .assert()
        .success();
    let fps = inbetween::Fps::new(120, 1).unwrap();
    let (a, b) = (frames(&read(&src), fps), frames(&read(&fbx), fps));
    assert_eq!(read(&fbx).fps, Some(fps));
    for (name, (times, rots, _)) in &a {
        let Some((bt, br, _)) = b.get(name) else {
            continue;
        };
        assert_eq!(times.len(), bt.len(), "{name}");
        for i in 0..times.len() {
            assert!((times[i] - bt[i]).abs() < 1e-9);
            assert!(rots[i].angle_between(br[i]) < ANGLE_TOL, "{name} key {i}");
        }
    }
}

/// `reduce input --tolerance deg [extra] -o small.fbx`, read back by ufbx at every frame of the
/// input's rate: every track within the tolerances at every input frame. Returns the largest
/// angle (degrees), translation error, and the number of keys of the first track's curves.
fn reduced_plays_within(input: &Path, deg: f64, extra: &[&str]) -> (f64, f64, usize) {
    let dir = tempfile::tempdir().unwrap();
    let fbx = dir.path().join("small.fbx");
    bin()
        .arg("reduce")
        .arg(input)
        .args(["--tolerance", &deg.to_string()])
        .args(extra)
        .arg("-o")
        .arg(&fbx)
        .assert()
        .success();
    let src = read(input);
    let fps = src.fps.unwrap();
    let back = read(&fbx);
    assert_eq!(back.fps, Some(fps));
    let translation_tol = extra
        .iter()
        .position(|a| *a == "--translation-tolerance")
        .map(|i| extra[i + 1].parse::<f64>().unwrap());
    let (a, b) = (frames(&src, fps), frames(&back, fps));
    let (mut worst, mut worst_p) = (0.0f64, 0.0f64);
    for (name, (times, rots, trans)) in &a {
        let label = format!("{} reduced to {deg}°: track {name}", input.display());
        let Some((bt, br, btrans)) = b.get(name) else {
            assert!(
                rots.iter()
                    .all(|q| q.angle_between(glam::DQuat::IDENTITY) < ANGLE_TOL),
                "{label}: missing from the FBX"
            );
            continue;
        };
        assert_eq!(times.len(), bt.len(), "{label}: frames");
        for i in 0..times.len() {
            let angle = rots[i].angle_between(br[i]).to_degrees();
            assert!(angle <= deg, "{label}: frame {i} plays {angle}° off");
            worst = worst.max(angle);
            if let (Some(tt), Some(Some(p)), Some(Some(q))) =
                (translation_tol, trans.get(i), btrans.get(i))
            {
                let d = (*p - *q).length();
                assert!(d <= tt, "{label}: frame {i} position {d} off");
                worst_p = worst_p.max(d);
            }
        }
    }
    // The keys of a curve of the file: what reduce kept (fewer than the frames).
    let bytes = std::fs::read(&fbx).unwrap();
    let keys = count_keys(&bytes);
    (worst, worst_p, keys)
}

/// The key count of the first `KeyTime` array of a binary FBX file (its `l` array's count).
fn count_keys(bytes: &[u8]) -> usize {
    let at = bytes
        .windows(8)
        .position(|w| w == b"\x07KeyTime")
        .expect("a KeyTime node");
    let p = at + 8;
    assert_eq!(bytes[p], b'l');
    u32::from_le_bytes(bytes[p + 1..p + 5].try_into().unwrap()) as usize
}

#[test]
fn reduce_fbx_plays_within_its_tolerance_as_ufbx_evaluates_it() {
    let f = fixtures();
    let cmu = f.join("bvh/cmu_01_01.bvh");
    let frames = 61;
    for (input, deg, extra) in [
        (&cmu, 1.0, &["--translation-tolerance", "0.1"][..]),
        (&cmu, 0.2, &["--translation-tolerance", "0.05"][..]),
        (
            &cmu,
            1.0,
            &["--translation-tolerance", "0.1", "--shared-keys"][..],
        ),
        (
            &cmu,
            1.0,
            &["--translation-tolerance", "0.1", "--scheme", "bezier"][..],
        ),
        (
            &f.join("bvh/mixed_orders.bvh"),
            0.5,
            &["--translation-tolerance", "0.01"][..],
        ),
        (
            &f.join("fbx/closed_empties_zxy_24.fbx"),
            0.5,
            &["--translation-tolerance", "0.001"][..],
        ),
    ] {
        let (worst, worst_p, keys) = reduced_plays_within(input, deg, extra);
        eprintln!(
            "{} {deg}° {extra:?}: {worst:.4}°, {worst_p:.4}, {keys} keys",
            input.display()
        );
        if input == &cmu {
            assert!(keys < frames, "{keys} keys of {frames} frames");
        }
    }
}

#[test]
fn fbx_output_refuses_what_it_has_no_place_for() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.fbx");
    let keys = fixtures().join("ok/clean.csv");
    let bvh = fixtures().join("bvh/cmu_01_01.bvh");
    let cases: [(Vec<&std::ffi::OsStr>, &str); 5] = [
        (
            vec![
                "interp".as_ref(),
                keys.as_os_str(),
                "--fps".as_ref(),
                "30".as_ref(),
            ],
            "FBX output is a skeleton's animation",
        ),
        (
            vec!["interp".as_ref(), bvh.as_os_str(), "--velocity".as_ref()],
            "--velocity: FBX has no place for angular velocities",
        ),
        (
            vec![
                "interp".as_ref(),
                bvh.as_os_str(),
                "--tracks".as_ref(),
                "Hips".as_ref(),
            ],
            "--tracks: an FBX skeleton is written with every joint",
        ),
        (
            vec![
                "reduce".as_ref(),
                bvh.as_os_str(),
                "--position-tolerance".as_ref(),
                "1".as_ref(),
            ],
            "--position-tolerance: FBX output verifies each joint's rotation",
        ),
        (
            vec![
                "reduce".as_ref(),
                bvh.as_os_str(),
                "--tolerance".as_ref(),
                "1".as_ref(),
                "--translation-tolerance".as_ref(),
                "1".as_ref(),
                "--precision".as_ref(),
                "3".as_ref(),
            ],
            "--precision: FBX stores its keys as float32",
        ),
    ];
    for (args, says) in cases {
        let err = stderr_of(bin().args(&args).arg("-o").arg(&out), 2);
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote the file");
    }
}
