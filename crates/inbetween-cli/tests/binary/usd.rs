//! USD output (`.usda`): every file the tool writes is opened and evaluated by usd-core
//! (`fixtures/usd/check_usd.py`: UsdSkel's own evaluation at every frame against the tool's
//! frames), and a reduced `--scheme slerp --shared-keys` file plays within its tolerance under
//! USD's own interpolation.

use crate::support::{bin, checker_python, fixtures};
use std::path::Path;

/// `check_usd.py usda npz extra…`, run.
fn check_usd(python: &Path, usda: &Path, npz: &Path, extra: &[&str]) -> std::process::Output {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    std::process::Command::new(python)
        .arg(root.join("fixtures/usd/check_usd.py"))
        .arg(usda)
        .arg(npz)
        .args(extra)
        .output()
        .unwrap()
}

/// `check_usd.py usda npz extra…` succeeds (the checker prints its findings on failure).
fn usd_core_accepts(python: &Path, usda: &Path, npz: &Path, extra: &[&str]) {
    let o = check_usd(python, usda, npz, extra);
    assert!(
        o.status.success(),
        "check_usd {}: {}{}",
        usda.display(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// `interp input [args] -o out.usda` and `interp input --to quat [args] -o frames.npz`.
fn frames_and_usda(
    input: &Path,
    args: &[&str],
    dir: &Path,
) -> (std::path::PathBuf, std::path::PathBuf) {
    let usda = dir.join("clip.usda");
    let npz = dir.join("frames.npz");
    bin()
        .arg("interp")
        .arg(input)
        .args(args)
        .arg("-o")
        .arg(&usda)
        .assert()
        .success();
    bin()
        .arg("interp")
        .arg(input)
        .args(args)
        .args(["--to", "quat", "-o"])
        .arg(&npz)
        .assert()
        .success();
    (usda, npz)
}

#[test]
fn usd_core_plays_every_frame_interp_writes() {
    let Some(python) = checker_python("usd-core check of USD output") else {
        return;
    };
    let f = fixtures();
    for (input, args) in [
        (f.join("bvh/cmu_01_01.bvh"), vec![]),
        (f.join("bvh/cmu_01_01.bvh"), vec!["--fps", "30000/1001"]),
        (f.join("bvh/mixed_orders.bvh"), vec![]),
        (f.join("fbx/real/huesitos.fbx"), vec![]),
        (f.join("fbx/closed_ntsc_2997.fbx"), vec![]),
        (f.join("gltf/real/CesiumMan.glb"), vec!["--fps", "24"]),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let (usda, npz) = frames_and_usda(&input, &args, dir.path());
        // The clip's first and last poses at its own rate: where they are not frames (a 120 fps
        // clip's last at 29.97), USD samples them too, at their fractional time codes.
        let own = dir.path().join("own.npz");
        bin()
            .arg("interp")
            .arg(&input)
            .args(["--to", "quat", "-o"])
            .arg(&own)
            .assert()
            .success();
        usd_core_accepts(&python, &usda, &npz, &["--ends", own.to_str().unwrap()]);
    }
}

/// The last pose of a 120 fps clip baked at 29.97 lies between frames: USD keeps it as a
/// sample at its fractional time code (the clip's end times the rate), as glTF output keeps
/// it; without it the clip would end a frame early.
#[test]
fn usd_output_keeps_the_first_and_last_poses_off_the_frame_grid() {
    let dir = tempfile::tempdir().unwrap();
    let usda = dir.path().join("clip.usda");
    bin()
        .args([
            "interp",
            "fixtures/bvh/cmu_01_01.bvh",
            "--fps",
            "30000/1001",
            "-o",
        ])
        .arg(&usda)
        .assert()
        .success();
    let text = std::fs::read_to_string(&usda).unwrap();
    let end = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("endTimeCode = "))
        .unwrap();
    // 61 frames at 120 fps end at 0.5 s: time code 0.5 × 30000/1001, not a whole frame.
    let code: f64 = end.parse().unwrap();
    assert!((code - 0.5 * 30000.0 / 1001.0).abs() < 1e-9, "{end}");
}

#[test]
fn a_reduced_slerp_file_plays_within_its_tolerance_in_usd() {
    let Some(python) = checker_python("usd-core check of reduced USD output") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let clip = fixtures().join("bvh/cmu_01_01.bvh");
    let small = dir.path().join("small.usda");
    bin()
        .arg("reduce")
        .arg(&clip)
        .args([
            "--shared-keys",
            "--tolerance",
            "1",
            "--translation-tolerance",
            "0.1",
            "-o",
        ])
        .arg(&small)
        .assert()
        .success();
    let text = std::fs::read_to_string(&small).unwrap();
    let samples = text.matches("\n                ").count() / 3;
    assert!(
        (10..61).contains(&samples),
        "{samples} shared keys of 61 frames"
    );
    let npz = dir.path().join("frames.npz");
    bin()
        .arg("interp")
        .arg(&clip)
        .args(["--to", "quat", "-o"])
        .arg(&npz)
        .assert()
        .success();
    // USD's own slerp between the kept samples, at every input frame: within 1° and 0.1.
    usd_core_accepts(
        &python,
        &small,
        &npz,
        &[
            "--times-from-npz",
            "--max-angle-deg",
            "1",
            "--max-translation",
            "0.1",
        ],
    );
    // And not within a tenth of it: the check can fail.
    let o = check_usd(
        &python,
        &small,
        &npz,
        &[
            "--times-from-npz",
            "--max-angle-deg",
            "0.1",
            "--max-translation",
            "0.1",
        ],
    );
    assert!(
        !o.status.success(),
        "a 0.1° bound should fail on keys reduced at 1°"
    );
}

#[test]
fn usd_output_is_refused_where_usd_could_not_play_it() {
    let clip = fixtures().join("bvh/cmu_01_01.bvh");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("small.usda");
    let cases: [(&[&str], &str); 3] = [
        (
            &[
                "reduce",
                "--scheme",
                "bezier",
                "--shared-keys",
                "--tolerance",
                "1",
                "--translation-tolerance",
                "0.1",
            ],
            "inbetween: error: --scheme: USD plays its samples by slerp",
        ),
        (
            &[
                "reduce",
                "--tolerance",
                "1",
                "--translation-tolerance",
                "0.1",
            ],
            "inbetween: error: USD samples every joint at the same times: give --shared-keys",
        ),
        (
            &["interp", "--velocity"],
            "inbetween: error: --velocity: USD has no place",
        ),
    ];
    for (args, message) in cases {
        let o = bin()
            .args(&args[..1])
            .arg(&clip)
            .args(&args[1..])
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with(message), "{args:?}: {err}");
        assert!(!out.exists());
    }
    // Keys without a skeleton.
    let o = bin()
        .arg("interp")
        .arg(fixtures().join("interp/nonuniform.csv"))
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("USD output is a skeleton's animation"));
    assert!(!out.exists());
}

/// `convert FILE --to quat` as JSON.
fn keys_of(path: &Path) -> serde_json::Value {
    let out = crate::support::stdout_of(
        bin()
            .args(["convert", "--to", "quat", "--output-format", "json"])
            .arg(path),
    );
    serde_json::from_str(&out).unwrap()
}

#[test]
fn usd_input_reads_the_samples_usd_core_authored() {
    for name in ["skel_closed_24", "skel_ntsc"] {
        let dir = fixtures().join("usd");
        let want: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join(format!("{name}.expected.json"))).unwrap(),
        )
        .unwrap();
        let got = keys_of(&dir.join(format!("{name}.usda")));
        assert_eq!(
            got["fps"]
                .as_str()
                .map(str::to_string)
                .unwrap_or(got["fps"].to_string()),
            want["rate_exact"].as_str().unwrap().trim_end_matches("/1"),
            "{name}: rate"
        );
        let codes = want["time_codes"].as_array().unwrap();
        // Tracks are named by the joints' full paths, as usd-core lists them.
        let names = want["joints"].as_array().unwrap();
        let tracks = got["tracks"].as_array().unwrap();
        assert_eq!(tracks.len(), names.len(), "{name}: one track per joint");
        for (j, joint) in names.iter().enumerate() {
            let track = tracks.iter().find(|t| &t["name"] == joint).unwrap();
            let keys = track["keys"].as_array().unwrap();
            assert_eq!(keys.len(), codes.len(), "{name} {joint}: a key per sample");
            for (i, code) in codes.iter().enumerate() {
                assert_eq!(
                    keys[i]["frame"].as_f64(),
                    code.as_f64(),
                    "{name} {joint} key {i}"
                );
                let q = &want["rotations_wxyz"][i][j];
                let v = |x: &serde_json::Value, k: usize| x[k].as_f64().unwrap();
                let a = glam::DQuat::from_xyzw(v(q, 1), v(q, 2), v(q, 3), v(q, 0)).normalize();
                let k = &keys[i]["quat"];
                let b = glam::DQuat::from_xyzw(v(k, 1), v(k, 2), v(k, 3), v(k, 0));
                crate::support::assert_rot_close(a, b, 1e-12, &format!("{name} {joint} {i}"));
                let t = &want["translations"][i][j];
                let p = &keys[i]["translation"];
                for c in 0..3 {
                    assert!((v(t, c) - v(p, c)).abs() <= 1e-12 * v(t, c).abs().max(1.0));
                }
            }
        }
    }
}

#[test]
fn usd_through_convert_comes_back_within_a_float32_step() {
    let dir = tempfile::tempdir().unwrap();
    let clip = fixtures().join("bvh/cmu_01_01.bvh");
    let first = dir.path().join("first.usda");
    let again = dir.path().join("again.usda");
    bin()
        .arg("convert")
        .arg(&clip)
        .arg("-o")
        .arg(&first)
        .assert()
        .success();
    bin()
        .arg("convert")
        .arg(&first)
        .arg("-o")
        .arg(&again)
        .assert()
        .success();
    let a = std::fs::read_to_string(&first).unwrap();
    let b = std::fs::read_to_string(&again).unwrap();
    // The same layout line by line; each number within one float32 step of the first (a
    // float32 quaternion is renormalised on reading).
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    assert_eq!(la.len(), lb.len());
    let nums = |l: &str| -> Vec<f64> {
        l.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
            .filter_map(|t| t.parse().ok())
            .collect()
    };
    let mut differ = 0;
    for (x, y) in la.iter().zip(&lb) {
        let (nx, ny) = (nums(x), nums(y));
        assert_eq!(nx.len(), ny.len(), "{x} / {y}");
        for (p, q) in nx.iter().zip(&ny) {
            // As the float32 values USD reads: at most one step apart.
            let (a, b) = (*p as f32, *q as f32);
            let steps = if a.signum() == b.signum() || a == 0.0 || b == 0.0 {
                (a.abs().to_bits() as i64 - b.abs().to_bits() as i64).abs()
            } else {
                i64::MAX
            };
            assert!(steps <= 1 || (a - b).abs() < 1e-30, "{p} vs {q} in {x}");
            differ += usize::from(p != q);
        }
    }
    assert!(differ < la.len() * 40, "{differ} numbers differ");
    // And usd-core plays the copy as the original's frames.
    if let Some(python) = checker_python("usd-core check of USD → USD") {
        let npz = dir.path().join("frames.npz");
        bin()
            .arg("interp")
            .arg(&clip)
            .args(["--to", "quat", "-o"])
            .arg(&npz)
            .assert()
            .success();
        usd_core_accepts(&python, &again, &npz, &[]);
    }
}

#[test]
fn bad_usd_input_is_a_located_error() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read_to_string(fixtures().join("usd/minimal_example.usda")).unwrap();
    let cases = [
        (
            "no_anim.usda",
            good.replace("rel skel:animationSource = </Clip/Skeleton/Animation>", ""),
            "no Skeleton with an animation",
        ),
        ("cut.usda", good[..good.len() / 2].to_string(), "expected"),
        (
            "short.usda",
            good.replacen("(1, 0, 0, 0), (1, 0, 0, 0)]", "(1, 0, 0, 0)]", 1),
            "1 values for 2 joints",
        ),
        (
            "nan.usda",
            good.replacen(
                "(0.70710677, 0, 0, 0.70710677), (1, 0, 0, 0)]",
                "(nan, 0, 0, 0.70710677), (1, 0, 0, 0)]",
                1,
            ),
            "expected 4 finite numbers",
        ),
    ];
    for (name, text, message) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let o = bin().arg("analyze").arg(&path).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.starts_with(&format!("inbetween: error: {}", path.display())),
            "{name}: {err}"
        );
        assert!(err.contains(message), "{name}: {err}");
    }
}

#[test]
fn usd_input_follows_usd_core_where_a_layer_leaves_things_out() {
    let dir = tempfile::tempdir().unwrap();
    // A binding on the SkelRoot is the Skeleton's (as UsdSkel resolves it).
    let bound = keys_of(&fixtures().join("usd/bind_on_skelroot.usda"));
    assert_eq!(bound["tracks"].as_array().unwrap().len(), 2);
    // Without timeCodesPerSecond, framesPerSecond is the rate (usd-core's fallback).
    let ntsc = std::fs::read_to_string(fixtures().join("usd/skel_ntsc.usda")).unwrap();
    let kept: String = ntsc
        .lines()
        .filter(|l| !l.contains("timeCodesPerSecond"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(kept, ntsc);
    let path = dir.path().join("no_tcps.usda");
    std::fs::write(&path, kept).unwrap();
    assert_eq!(keys_of(&path)["fps"], "30000/1001");
    // A usdc too short for its header: an input error naming the file (binary USD is read,
    // tests/binary/usd_binary.rs).
    let usdc = dir.path().join("clip.usdc");
    std::fs::write(&usdc, b"PXR-USDC\x00\x07\x00\x00").unwrap();
    let o = bin().arg("convert").arg(&usdc).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("clip.usdc: usdc: not a usdc crate (too short for its header)"),
        "{err}"
    );
}

#[test]
fn usd_output_keeps_the_inputs_unit_and_up_axis() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("z.usda");
    // A hand-written ASCII FBX, Z up, in inches (UnitScaleFactor 2.54).
    bin()
        .arg("interp")
        .arg(fixtures().join("fbx/zup_inches_ascii.fbx"))
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("    metersPerUnit = 0.0254\n"), "{text}");
    assert!(text.contains("    upAxis = \"Z\"\n"));
    let back = dir.path().join("back.usda");
    bin()
        .arg("convert")
        .arg(&out)
        .arg("-o")
        .arg(&back)
        .assert()
        .success();
    let again = std::fs::read_to_string(&back).unwrap();
    assert!(again.contains("    upAxis = \"Z\"\n") && again.contains("metersPerUnit = 0.0254\n"));
    // --tracks and --precision have no place in a USD skeleton.
    for (flag, value, message) in [
        (
            "--tracks",
            "Hips",
            "--tracks: a USD skeleton is written with every joint",
        ),
        (
            "--precision",
            "3",
            "--precision: USD stores its values as float32",
        ),
    ] {
        let o = bin()
            .arg("interp")
            .arg(fixtures().join("bvh/cmu_01_01.bvh"))
            .args([flag, value, "-o"])
            .arg(dir.path().join("t.usda"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(message),
            "{flag}"
        );
    }
}
