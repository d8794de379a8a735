//! glTF in and out (issue 14): LINEAR rotations resampled at their own key rate come back to
//! float32 precision; a STEP channel stays a step; a CUBICSPLINE channel is baked exactly as the
//! module evaluates Appendix C (itself checked against `fixtures/gltf/cubicspline_ref.json`);
//! every glTF written passes the Khronos glTF Validator; errors exit 2 naming the file and the
//! animation or channel.

use crate::support::{bin, fixtures, read_table, rot_angle};
use base64::Engine;
use glam::{DQuat, DVec3};
use inbetween_io::gltf::{Asset, Interpolation, RotationChannel, TranslationChannel};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// Float32 resolution of a unit quaternion, as an angle: a rotation written as float32 and read
/// back is within this of the one computed.
const F32_ANGLE: f64 = 4.0 * f32::EPSILON as f64;

/// A smooth rotation about a tilted axis, past 180°.
fn spin(t: f64) -> DQuat {
    let axis = DVec3::new(1.0, 2.0, 3.0).normalize();
    DQuat::from_axis_angle(axis, 4.0 * t + 0.5 * (3.0 * t).sin()) * DQuat::from_rotation_x(0.3 * t)
}

/// Buffers, views and accessors of a test asset, built as JSON with a `data:` URI.
#[derive(Default)]
struct Builder {
    data: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    fn accessor(&mut self, values: &[f32], type_: &str, count: usize, minmax: bool) -> usize {
        while !self.data.len().is_multiple_of(4) {
            self.data.push(0);
        }
        self.views
            .push(json!({"buffer": 0, "byteOffset": self.data.len(),
                               "byteLength": values.len() * 4}));
        self.data
            .extend(values.iter().flat_map(|x| x.to_le_bytes()));
        let mut acc = json!({"bufferView": self.views.len() - 1, "componentType": 5126,
                             "count": count, "type": type_});
        if minmax {
            acc["min"] = json!([values[0]]);
            acc["max"] = json!([values[values.len() - 1]]);
        }
        self.accessors.push(acc);
        self.accessors.len() - 1
    }

    fn times(&mut self, t: &[f32]) -> usize {
        self.accessor(t, "SCALAR", t.len(), true)
    }

    fn quats(&mut self, q: &[DQuat]) -> usize {
        let flat: Vec<f32> = q
            .iter()
            .flat_map(|q| q.to_array().map(|x| x as f32))
            .collect();
        self.accessor(&flat, "VEC4", q.len(), false)
    }
}

fn at_rate(frames: std::ops::RangeInclusive<i64>, fps: f64) -> Vec<f32> {
    frames.map(|k| (k as f64 / fps) as f32).collect()
}

/// `walk.gltf`: nodes Hips, Arm, Step, Cubic; animation "Walk" (0) with LINEAR Hips rotation
/// and translation at 30 fps over 1 s, LINEAR Arm rotation over frames 5..=20 only, a STEP
/// rotation with keys at 0, 0.1, 0.5, 0.7 s (frames 0, 3, 15, 21 at 30 fps; not float32-exact)
/// and a CUBICSPLINE rotation; animation "Idle" (1), one LINEAR rotation on Arm.
fn walk_json() -> Value {
    walk_json_signed(false)
}

/// [`walk_json`], with `flip`: Hips' LINEAR key 10 and Cubic's CUBICSPLINE key 1 (vertex and
/// tangents) stored negated — the same rotations, in the opposite hemisphere from their
/// neighbours, as some exporters write them.
fn walk_json_signed(flip: bool) -> Value {
    let mut b = Builder::default();
    let t30 = at_rate(0..=30, 30.0);
    let mut hips: Vec<DQuat> = t30.iter().map(|&t| spin(f64::from(t))).collect();
    if flip {
        hips[10] = -hips[10];
    }
    let tr: Vec<f32> = t30.iter().flat_map(|&t| [t, 2.0 * t * t, -t]).collect();
    let t_arm = at_rate(5..=20, 30.0);
    let arm: Vec<DQuat> = t_arm
        .iter()
        .map(|&t| spin(2.0 * f64::from(t) + 1.0))
        .collect();
    let t_step: Vec<f32> = vec![0.0, 0.1, 0.5, 0.7];
    let step: Vec<DQuat> = [0.0, 0.6, 1.2, 1.8]
        .iter()
        .map(|&a| DQuat::from_rotation_y(a))
        .collect();
    let t_cubic: Vec<f32> = vec![0.0, 0.4, 1.0];
    let mut cubic = Vec::new();
    for (k, &t) in t_cubic.iter().enumerate() {
        let a = 1.5 * f64::from(t);
        let v = DQuat::from_rotation_z(a);
        let d = DQuat::from_xyzw(0.0, 0.0, 0.75 * (a / 2.0).cos(), -0.75 * (a / 2.0).sin());
        let s = 1.0 + 0.1 * k as f64;
        let d = DQuat::from_xyzw(d.x * s, d.y * s, d.z * s, d.w * s);
        let sign = if flip && k == 1 { -1.0 } else { 1.0 };
        cubic.extend([d * sign, v * sign, d * sign]);
    }
    let idle = [DQuat::IDENTITY, DQuat::from_rotation_x(0.5)];

    let inputs = [
        b.times(&t30),
        b.times(&t_arm),
        b.times(&t_step),
        b.times(&t_cubic),
        b.times(&[0.0, 0.5]),
    ];
    let outputs = [
        b.quats(&hips),
        b.accessor(&tr, "VEC3", t30.len(), false),
        b.quats(&arm),
        b.quats(&step),
        b.quats(&cubic),
        b.quats(&idle),
    ];
    let sampler =
        |i, o, interp| json!({"input": inputs[i], "output": outputs[o], "interpolation": interp});
    let channel = |s, node, path| json!({"sampler": s, "target": {"node": node, "path": path}});
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&b.data)
    );
    json!({
        "asset": {"version": "2.0", "generator": "inbetween tests"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"name": "Hips", "children": [1, 2, 3]},
            {"name": "Arm", "extras": {"kept": true}},
            {"name": "Step"},
            {"name": "Cubic"}
        ],
        "animations": [
            {
                "name": "Walk",
                "samplers": [
                    sampler(0, 0, "LINEAR"),
                    sampler(0, 1, "LINEAR"),
                    sampler(1, 2, "LINEAR"),
                    sampler(2, 3, "STEP"),
                    sampler(3, 4, "CUBICSPLINE")
                ],
                "channels": [
                    channel(0, 0, "rotation"),
                    channel(1, 0, "translation"),
                    channel(2, 1, "rotation"),
                    channel(3, 2, "rotation"),
                    channel(4, 3, "rotation")
                ]
            },
            {
                "name": "Idle",
                "samplers": [sampler(4, 5, "LINEAR")],
                "channels": [channel(0, 1, "rotation")]
            }
        ],
        "buffers": [{"byteLength": b.data.len(), "uri": uri}],
        "bufferViews": b.views,
        "accessors": b.accessors
    })
}

fn write_walk(dir: &Path, json: &Value) -> PathBuf {
    let path = dir.join("walk.gltf");
    std::fs::write(&path, serde_json::to_vec_pretty(json).unwrap()).unwrap();
    path
}

fn run(args: &[&std::ffi::OsStr]) -> std::process::Output {
    bin().args(args).output().unwrap()
}

#[track_caller]
fn ok(args: &[&std::ffi::OsStr]) -> String {
    let out = run(args);
    assert!(
        out.status.success(),
        "exit {:?}: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stderr).into_owned()
}

macro_rules! args {
    ($($a:expr),* $(,)?) => { &[$(std::ffi::OsStr::new($a)),*] };
}

fn channel(asset: &Asset, animation: usize, index: usize) -> RotationChannel {
    asset.animations().unwrap()[animation]
        .rotations()
        .iter()
        .find(|c| c.index() == index)
        .unwrap()
        .clone()
}

/// `(time, rotation)` of every frame of `track` in a CSV written by interp.
fn csv_track(path: &Path, track: &str) -> Vec<(f64, DQuat)> {
    read_table(path)
        .iter()
        .filter(|r| r["track"] == track)
        .map(|r| {
            let f = |c: &str| r[c].parse::<f64>().unwrap();
            (f("time"), DQuat::from_xyzw(f("x"), f("y"), f("z"), f("w")))
        })
        .collect()
}

/// Asserts that the vector channels `got` play as `want` (sampled as glTF plays them at every
/// key time of either) within float32 precision, and target the same channels and nodes.
#[track_caller]
fn same_vectors(got: &[TranslationChannel], want: &[TranslationChannel], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    for (g, w) in got.iter().zip(want) {
        assert_eq!((g.index(), g.node()), (w.index(), w.node()), "{what}");
        for &t in g.times().iter().chain(w.times()) {
            let (a, b) = (g.sample(t), w.sample(t));
            let tol = 4.0 * f32::EPSILON as f64 * (1.0 + b.abs().max_element());
            assert!(
                (a - b).abs().max_element() <= tol,
                "{what}: channel {} at {t} s: {a} against {b}",
                g.index()
            );
        }
    }
}

#[test]
fn linear_at_its_own_key_rate_comes_back_to_float32() {
    let dir = tempfile::tempdir().unwrap();
    let src = write_walk(dir.path(), &walk_json());
    let input = Asset::read_path(&src).unwrap();
    let hips_in = channel(&input, 0, 0);
    let arm_in = channel(&input, 0, 2);
    for scheme in ["bezier", "hermite", "squad", "slerp"] {
        for ext in ["glb", "gltf"] {
            let out = dir.path().join(format!("{scheme}.{ext}"));
            let path = out.to_str().unwrap();
            ok(args!(
                "interp", &src, "--fps", "30", "--scheme", scheme, "-o", path
            ));
            validate(&out);
            let back = Asset::read_path(&out).unwrap();
            let hips = channel(&back, 0, 0);
            assert_eq!(hips.interpolation(), Interpolation::Linear);
            // The same float32 times, every key reproduced.
            assert_eq!(hips.times_f32(), hips_in.times_f32(), "{scheme} {ext}");
            for (k, (a, b)) in hips.values().iter().zip(hips_in.values()).enumerate() {
                let d = rot_angle(*a, b.normalize());
                assert!(d <= F32_ANGLE, "{scheme} {ext}: key {k}: {d:e} rad");
            }
            // Arm's keys cover frames 5..=20 of the animation's 0..=30: held outside.
            let arm = channel(&back, 0, 2);
            assert_eq!(arm.times_f32(), hips_in.times_f32());
            for (k, q) in arm.values().iter().enumerate() {
                let want = arm_in.values()[k.clamp(5, 20) - 5].normalize();
                let d = rot_angle(*q, want);
                assert!(d <= F32_ANGLE, "{scheme} {ext}: arm frame {k}: {d:e} rad");
            }
            // Everything else as it was: the translation channel, the other animation's times,
            // the node's extras.
            let (a, b) = (&back.animations().unwrap(), &input.animations().unwrap());
            same_vectors(a[0].translations(), b[0].translations(), scheme);
            // Idle, over its own span 0..=0.5 s.
            assert_eq!(a[1].rotations()[0].times_f32(), &hips_in.times_f32()[..16]);
            if ext == "gltf" {
                let text = std::fs::read_to_string(&out).unwrap();
                let json: Value = serde_json::from_str(&text).unwrap();
                assert_eq!(json["nodes"][1]["extras"], json!({"kept": true}));
            }
        }
    }
}

#[test]
fn other_animations_are_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let src = write_walk(dir.path(), &walk_json());
    let out = dir.path().join("walk-only.gltf");
    ok(args!(
        "interp",
        &src,
        "--animation",
        "Walk",
        "--fps",
        "60",
        "-o",
        &out
    ));
    validate(&out);
    let (back, input) = (
        Asset::read_path(&out).unwrap(),
        Asset::read_path(&src).unwrap(),
    );
    let (a, b) = (back.animations().unwrap(), input.animations().unwrap());
    assert_eq!(a[1], b[1]);
    assert_eq!(a[0].rotations()[0].times_f32().len(), 61);
}

#[test]
fn step_stays_a_step() {
    let dir = tempfile::tempdir().unwrap();
    let src = write_walk(dir.path(), &walk_json());
    let keys = channel(&Asset::read_path(&src).unwrap(), 0, 3);
    let key_frames_30 = [0, 3, 15, 21];
    for (fps, key_times) in [(30.0, [0.0, 0.1, 0.5, 0.7]), (24.0, [0.0, 0.1, 0.5, 0.7])] {
        let csv = dir.path().join(format!("step{fps}.csv"));
        ok(args!(
            "interp",
            &src,
            "--animation",
            "Walk",
            "--fps",
            &fps.to_string(),
            "-o",
            &csv
        ));
        let frames = csv_track(&csv, "Step");
        assert_eq!(frames.len(), fps as usize + 1);
        for (k, (t, q)) in frames.iter().enumerate() {
            // The last key at or before the frame (keys on a frame count as on it).
            let key = key_times.iter().rposition(|&kt| kt <= *t + 1e-9).unwrap();
            let d = rot_angle(*q, keys.values()[key]);
            assert!(
                d < 1e-12,
                "{fps} fps frame {k} ({t} s): want key {key}, {d:e} rad"
            );
        }
        if fps == 30.0 {
            for (i, &k) in key_frames_30.iter().enumerate() {
                assert!(rot_angle(frames[k].1, keys.values()[i]) < 1e-12);
                if k > 0 {
                    assert!(rot_angle(frames[k - 1].1, keys.values()[i - 1]) < 1e-12);
                }
            }
        }
    }
    // Into glTF: a LINEAR sampler whose frames hold each key.
    let out = dir.path().join("step.glb");
    ok(args!("interp", &src, "--fps", "30", "-o", &out));
    validate(&out);
    let back = channel(&Asset::read_path(&out).unwrap(), 0, 3);
    assert_eq!(back.interpolation(), Interpolation::Linear);
    for (k, q) in back.values().iter().enumerate() {
        let key = key_frames_30.iter().rposition(|&f| f <= k).unwrap();
        assert!(rot_angle(*q, keys.values()[key]) <= F32_ANGLE, "frame {k}");
    }
}

#[test]
fn cubicspline_is_baked_as_appendix_c_evaluates_it() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("gltf/samplers.glb");
    let asset = Asset::read_path(&src).unwrap();
    let anim = &asset.animations().unwrap()[0];
    let cubic = anim
        .rotations()
        .iter()
        .find(|c| c.interpolation() == Interpolation::CubicSpline)
        .unwrap();
    let mut baked = Vec::new();
    for scheme in ["bezier", "minaccel"] {
        let csv = dir.path().join(format!("cubic-{scheme}.csv"));
        ok(args!(
            "interp",
            &src,
            "--animation",
            "Mixed",
            "--fps",
            "24",
            "--scheme",
            scheme,
            "-o",
            &csv
        ));
        let frames = csv_track(&csv, "cubic");
        // The animation's span is 0..=2 s.
        assert_eq!(frames.len(), 49);
        for (k, (t, q)) in frames.iter().enumerate() {
            assert_eq!(*t, k as f64 / 24.0);
            let d = rot_angle(*q, cubic.sample(*t));
            assert!(d < 1e-12, "{scheme}: frame {k}: {d:e} rad from Appendix C");
        }
        baked.push(frames);
    }
    // --scheme does not apply to it.
    assert_eq!(baked[0], baked[1]);
    // Into glTF: the same curve as float32 keys of a LINEAR sampler.
    for ext in ["glb", "gltf"] {
        let out = dir.path().join(format!("cubic.{ext}"));
        ok(args!("interp", &src, "--fps", "24", "-o", &out));
        validate(&out);
        let back = Asset::read_path(&out).unwrap();
        let ch = channel(&back, 0, cubic.index());
        assert_eq!(ch.interpolation(), Interpolation::Linear);
        assert_eq!(ch.values().len(), 49);
        for (k, q) in ch.values().iter().enumerate() {
            let d = rot_angle(*q, cubic.sample(k as f64 / 24.0));
            assert!(d <= F32_ANGLE, "{ext}: frame {k}: {d:e} rad");
        }
    }
}

#[test]
fn tracks_are_channels_named_by_node_and_animation() {
    let dir = tempfile::tempdir().unwrap();
    let src = write_walk(dir.path(), &walk_json());
    let csv = dir.path().join("all.csv");
    ok(args!("interp", &src, "--fps", "10", "-o", &csv));
    let mut names: Vec<String> = read_table(&csv)
        .into_iter()
        .map(|r| r["track"].clone())
        .collect();
    names.dedup();
    assert_eq!(
        names,
        [
            "Walk/Hips",
            "Walk/Arm",
            "Walk/Step",
            "Walk/Cubic",
            "Idle/Arm"
        ]
    );
    // Hips carries its translation channel's keys.
    let rows = read_table(&csv);
    let hips = rows
        .iter()
        .find(|r| r["track"] == "Walk/Hips" && r["frame"] == "5");
    let tx: f64 = hips.unwrap()["tx"].parse().unwrap();
    assert!((tx - 0.5).abs() < 1e-7);
    // One animation: names are the nodes'.
    let one = dir.path().join("idle.csv");
    ok(args!(
        "interp",
        &src,
        "--animation",
        "1",
        "--fps",
        "10",
        "-o",
        &one
    ));
    assert!(read_table(&one).iter().all(|r| r["track"] == "Arm"));
}

#[test]
fn convert_writes_the_keys_on_their_frames() {
    let dir = tempfile::tempdir().unwrap();
    let src = write_walk(dir.path(), &walk_json());
    let out = dir.path().join("keys.json");
    let stderr = ok(args!(
        "convert",
        &src,
        "--animation",
        "Walk",
        "--fps",
        "30",
        "-o",
        &out
    ));
    assert!(
        stderr.contains("channel 3: a STEP sampler's keys are written as keys"),
        "{stderr}"
    );
    // The CUBICSPLINE tangents are written as the keys' own angular velocities.
    assert!(!stderr.contains("not written"), "{stderr}");
    let doc: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let hips = &doc["tracks"][0];
    assert_eq!(hips["name"], "Hips");
    // Float32 times exported at 30 fps come back on their frames: 0.1 s, not 0.10000000149.
    assert_eq!(hips["keys"][3]["time"], json!(0.1));
    assert_eq!(hips["keys"].as_array().unwrap().len(), 31);
    assert!(hips["keys"][3]["translation"].is_array());
}

#[test]
fn errors_exit_2_naming_the_file_and_the_channel() {
    let dir = tempfile::tempdir().unwrap();
    let mut json = walk_json();
    // Channel 3's output has 16 floats for 4 keys; make it claim 3 keys.
    let acc = json["animations"][0]["samplers"][3]["output"]
        .as_u64()
        .unwrap() as usize;
    json["accessors"][acc]["count"] = json!(3);
    let src = write_walk(dir.path(), &json);
    let out = run(args!(
        "interp",
        &src,
        "--fps",
        "30",
        "-o",
        dir.path().join("o.glb").as_os_str()
    ));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("walk.gltf: animations[0].channels[3] (animation \"Walk\""),
        "{err}"
    );
    assert!(!dir.path().join("o.glb").exists());

    let good = write_walk(dir.path(), &walk_json());
    for (args, want) in [
        (
            vec!["interp", "--animation", "Run"],
            "--animation Run: no such animation in",
        ),
        (
            vec!["convert", "--animation", "7"],
            "--animation 7: no such animation",
        ),
    ] {
        let out = bin()
            .args(&args[..1])
            .arg(&good)
            .args(&args[1..])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(want) && err.contains("walk.gltf"), "{err}");
    }

    // A truncated GLB.
    let glb = std::fs::read(fixtures().join("gltf/samplers.glb")).unwrap();
    let cut = dir.path().join("cut.glb");
    std::fs::write(&cut, &glb[..glb.len() / 2]).unwrap();
    let out = run(args!(
        "interp",
        &cut,
        "-o",
        dir.path().join("c.csv").as_os_str()
    ));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("cut.glb"), "{err}");

    // glTF output needs a glTF input; --animation needs one too.
    let csv = dir.path().join("k.csv");
    std::fs::write(&csv, "time,w,x,y,z\n0,1,0,0,0\n1,1,0,0,0\n").unwrap();
    for (extra, want) in [
        (
            &["-o", "x.glb"][..],
            "glTF output is written into a glTF input's asset",
        ),
        (&["--animation", "0"][..], "--animation"),
    ] {
        let out = bin()
            .arg("interp")
            .arg(&csv)
            .args(extra)
            .current_dir(dir.path())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(want), "{err}");
    }
}

// ---- the Khronos glTF Validator (same rule as src/io/gltf/tests.rs) ----

/// Runs `node tools/gltf-validator/validate.js FILE` and asserts no errors, when node and the
/// validator are installed (`npm ci --prefix tools/gltf-validator`); otherwise skips with a
/// note, unless INBETWEEN_REQUIRE_GLTF_VALIDATOR is set (CI), which makes it a failure.
#[track_caller]
pub(crate) fn validate(file: &Path) -> Option<Value> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("tools/gltf-validator");
    let installed = dir.join("node_modules/gltf-validator").is_dir();
    let node = std::process::Command::new("node")
        .arg("--version")
        .output()
        .is_ok();
    if !(installed && node) {
        assert!(
            std::env::var_os("INBETWEEN_REQUIRE_GLTF_VALIDATOR").is_none(),
            "the glTF Validator is required but not installed: npm ci --prefix tools/gltf-validator"
        );
        eprintln!(
            "note: glTF Validator check skipped: needs node and `npm ci --prefix tools/gltf-validator`"
        );
        return None;
    }
    let out = std::process::Command::new("node")
        .arg(dir.join("validate.js"))
        .arg(file)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}: the glTF Validator reports errors:\n{}\n{}",
        file.display(),
        String::from_utf8_lossy(&out.stderr),
        String::from_utf8_lossy(&out.stdout)
    );
    Some(serde_json::from_slice(&out.stdout).unwrap())
}

/// The JSON pointers of the objects the glTF Validator reports unused in `file`
/// (`UNUSED_OBJECT`), when it is installed (see [`validate`]).
#[track_caller]
pub(crate) fn unused_objects(file: &Path) -> Option<Vec<String>> {
    let report = validate(file)?;
    let messages = report["issues"]["messages"].as_array().unwrap().iter();
    let unused = messages.filter(|m| m["code"] == "UNUSED_OBJECT");
    Some(
        unused
            .map(|m| m["pointer"].as_str().unwrap().to_string())
            .collect(),
    )
}

// ---- real assets (fixtures/gltf/real, credited in fixtures/README.md) ----

/// The independent playback of one rotation channel (`fixtures/gltf/playback_ref.py`, numpy and
/// pygltflib: LINEAR by Appendix C's slerp, STEP held, CUBICSPLINE by Appendix C through
/// `cubicspline_ref.py`) at `times`, when the checkers' venv exists (CI builds it;
/// INBETWEEN_REQUIRE_PYTHON_CHECKS makes its absence a failure).
pub(crate) fn python_playback(
    asset: &Path,
    animation: usize,
    channel: usize,
    times: &[f64],
) -> Option<Vec<DQuat>> {
    let doc = python_channel(asset, animation, channel, times)?;
    let rotations = doc["rotations"].as_array().unwrap().iter();
    Some(
        rotations
            .map(|r| DQuat::from_array(numbers(r).try_into().unwrap()))
            .collect(),
    )
}

/// As [`python_playback`], for a translation or scale channel.
pub(crate) fn python_vectors(
    asset: &Path,
    animation: usize,
    channel: usize,
    times: &[f64],
) -> Option<Vec<DVec3>> {
    let doc = python_channel(asset, animation, channel, times)?;
    let values = doc["values"].as_array().unwrap().iter();
    Some(values.map(|v| DVec3::from_slice(&numbers(v))).collect())
}

fn numbers(v: &Value) -> Vec<f64> {
    let xs = v.as_array().unwrap().iter();
    xs.map(|x| x.as_f64().unwrap()).collect()
}

fn python_channel(asset: &Path, animation: usize, channel: usize, times: &[f64]) -> Option<Value> {
    let python = crate::support::checker_python("glTF playback reference check")?;
    let (a, c) = (animation.to_string(), channel.to_string());
    let times: Vec<String> = times.iter().map(|t| format!("{t:?}")).collect();
    let mut args: Vec<&std::ffi::OsStr> = vec![asset.as_os_str(), a.as_ref(), c.as_ref()];
    args.extend(times.iter().map(std::ffi::OsStr::new));
    Some(crate::support::python_json(
        &python,
        "fixtures/gltf/playback_ref.py",
        &args,
    ))
}

/// Without `--scheme`, `interp` of a glTF plays every sampler as glTF defines it: each frame at
/// 30 fps (not the keys' rate) equals the independent Appendix C playback of the asset — LINEAR
/// (float32 and normalized-integer keys) by slerp, STEP held, CUBICSPLINE — to 1e-9 rad
/// (measured: 1.1e-15), on the synthetic samplers and the Khronos sample RiggedSimple.
/// `--scheme bezier` re-interpolates the LINEAR keys and so leaves that playback (measured: 0.18
/// and 0.089 rad at worst; more than 1e-3 rad somewhere on each asset is asserted).
#[test]
fn gltf_without_a_scheme_plays_as_the_asset_defines() {
    let dir = tempfile::tempdir().unwrap();
    // (asset, animation index and name, rotation channels with their track names); the sparse
    // channel of samplers.gltf is left out (the reference does not read sparse accessors).
    // (animation, channel, track name) of each rotation channel checked.
    type Channels<'a> = &'a [(usize, usize, &'a str)];
    let cases: [(&str, Channels); 2] = [
        (
            "gltf/samplers.gltf",
            &[
                (0, 0, "Mixed/step"),
                (0, 1, "Mixed/byte"),
                (0, 2, "Mixed/short"),
                (0, 4, "Mixed/cubic"),
                (1, 0, "Other/other"),
            ],
        ),
        (
            "gltf/real/RiggedSimple.gltf",
            &[(0, 1, "0/node2"), (1, 1, "1/node3")],
        ),
    ];
    for (asset, channels) in cases {
        let src = fixtures().join(asset);
        let mut bezier_off = 0.0f64;
        for scheme in [None, Some("bezier")] {
            let csv = dir.path().join("frames.csv");
            let mut argv = args!("interp", &src, "--fps", "30", "-o", &csv).to_vec();
            if let Some(s) = scheme {
                argv.extend(args!("--scheme", s));
            }
            ok(&argv);
            for &(a, c, track) in channels {
                let frames = csv_track(&csv, track);
                assert!(
                    frames.len() > 30,
                    "{asset} {track}: {} frames",
                    frames.len()
                );
                let times: Vec<f64> = frames.iter().map(|f| f.0).collect();
                let Some(want) = python_playback(&src, a, c, &times) else {
                    return;
                };
                let worst = frames
                    .iter()
                    .zip(&want)
                    .map(|((_, q), w)| rot_angle(*q, *w))
                    .fold(0.0, f64::max);
                match scheme {
                    None => assert!(worst < 1e-9, "{asset} {track}: {worst:e} rad"),
                    Some(_) => bezier_off = bezier_off.max(worst),
                }
            }
        }
        assert!(
            bezier_off > 1e-3,
            "{asset}: bezier within {bezier_off:e} rad"
        );
    }
}

/// glTF output keeps each animation's first and last poses: its new time accessor starts at the
/// earliest and ends at the latest time of any of the animation's samplers (the accessors' own
/// `min` and `max`), frames or not — RiggedSimple's 1/24 s at 30 fps, the synthetic samplers'
/// 0.5 s at 14.4 fps — with the grid's frames between, and the rotation at every time written
/// is the independent playback of the input there, to float32 (1e-6 rad).
#[test]
fn gltf_output_keeps_the_first_and_last_pose() {
    let dir = tempfile::tempdir().unwrap();
    for (asset, fps, channels) in [
        ("gltf/real/RiggedSimple.gltf", "30", &[(0, 1), (1, 1)][..]),
        (
            "gltf/samplers.gltf",
            "14.4",
            &[(0, 0), (0, 1), (0, 2), (0, 4), (1, 0)][..],
        ),
    ] {
        let src = fixtures().join(asset);
        let out = dir.path().join("out.glb");
        ok(args!("interp", &src, "--fps", fps, "-o", &out));
        // Valid, and no unused object the input did not have; but samplers.gltf has an
        // extension the writer does not know (which could name any accessor), so its replaced
        // samplers' accessors and views stay (the samplers go).
        if let (Some(before), Some(after)) = (unused_objects(&src), unused_objects(&out)) {
            if asset.contains("samplers") {
                let kept =
                    |p: &String| p.starts_with("/accessors/") || p.starts_with("/bufferViews/");
                assert!(after.iter().all(kept), "{asset}: {after:?}");
                assert!(
                    !after.is_empty(),
                    "{asset}: the unknown extension's rule untested"
                );
            } else {
                assert!(
                    after.len() <= before.len(),
                    "{asset}: {after:?}, before {before:?}"
                );
            }
        }
        let json = asset_json(&src);
        // Every channel of each animation on one time accessor; translations and scales the
        // independent playback of the input at those times.
        let written = asset_json(&out);
        for (a, anim) in written["animations"].as_array().unwrap().iter().enumerate() {
            let sampler = |c: &Value| &anim["samplers"][c["sampler"].as_u64().unwrap() as usize];
            let channels = anim["channels"].as_array().unwrap();
            let input = sampler(&channels[0])["input"].clone();
            let acc = &written["accessors"][input.as_u64().unwrap() as usize];
            let at = |k: &str| acc[k][0].as_f64().unwrap();
            let back = &back_of(&out).animations().unwrap()[a];
            let first = back.rotations().first().map(|c| c.times_f32());
            let first = first.unwrap_or_else(|| back.translations()[0].times_f32());
            let times: Vec<f64> = first.iter().map(|&t| t as f64).collect();
            assert_eq!((times[0], *times.last().unwrap()), (at("min"), at("max")));
            for (c, ch) in channels.iter().enumerate() {
                assert_eq!(
                    sampler(ch)["input"],
                    input,
                    "{asset} animation {a} channel {c}"
                );
                let path = ch["target"]["path"].as_str().unwrap();
                if path == "rotation" {
                    continue;
                }
                let got = back
                    .translations()
                    .iter()
                    .chain(back.scales())
                    .find(|g| g.index() == c)
                    .unwrap()
                    .clone();
                let Some(want) = python_vectors(&src, a, c, &times) else {
                    continue;
                };
                for (k, (g, w)) in got.values().iter().zip(&want).enumerate() {
                    let tol = 2.0 * f32::EPSILON as f64 * (1.0 + w.abs().max_element());
                    assert!(
                        (*g - *w).abs().max_element() <= tol,
                        "{asset} animation {a} {path} channel {c} at {} s: {g} against {w}",
                        times[k]
                    );
                }
            }
        }
        let back = Asset::read_path(&out).unwrap();
        let step = 1.0 / fps.parse::<f64>().unwrap();
        for &(a, c) in channels {
            let inputs = json["animations"][a]["samplers"].as_array().unwrap().iter();
            let ends = inputs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                let acc = &json["accessors"][s["input"].as_u64().unwrap() as usize];
                let at = |m: &str| acc[m][0].as_f64().unwrap();
                (lo.min(at("min")), hi.max(at("max")))
            });
            let got = channel(&back, a, c);
            let times = got.times_f32();
            let what = format!("{asset} animation {a} channel {c}");
            assert_eq!(times[0], ends.0 as f32, "{what}: first time");
            assert_eq!(*times.last().unwrap(), ends.1 as f32, "{what}: last time");
            // Between the ends, the frames of the grid.
            for w in times.windows(2) {
                let d = (w[1] - w[0]) as f64;
                assert!(
                    d > 0.0 && d <= step * (1.0 + 1e-5),
                    "{what}: {} to {}",
                    w[0],
                    w[1]
                );
            }
            let at: Vec<f64> = times.iter().map(|&t| t as f64).collect();
            let Some(want) = python_playback(&src, a, c, &at) else {
                return;
            };
            for (i, (q, w)) in got.values().iter().zip(&want).enumerate() {
                let d = rot_angle(q.normalize(), *w);
                assert!(d < 1e-6, "{what}: sample {i} ({} s): {d:e} rad", at[i]);
            }
        }
    }
}

/// Rotation keys in opposite hemispheres from their neighbours are named in a warning that says
/// how the file plays. Stored negated, Cubic's CUBICSPLINE key 1 makes Appendix C's spline turn
/// the long way (more than 1 rad from the sign-continuous file's curve between keys 0 and 1),
/// and Hips' LINEAR key 10 plays as before (slerp takes the shorter way); the same asset with
/// sign-continuous keys gets no such warning.
#[test]
fn keys_in_opposite_hemispheres_are_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let (aligned, flipped) = (dir.path().join("aligned"), dir.path().join("flipped"));
    std::fs::create_dir(&aligned).unwrap();
    std::fs::create_dir(&flipped).unwrap();
    let aligned = write_walk(&aligned, &walk_json());
    let flipped = write_walk(&flipped, &walk_json_signed(true));
    let csv = dir.path().join("f.csv");
    let quiet = ok(args!("interp", &aligned, "--animation", "Walk", "-o", &csv));
    assert!(!quiet.contains("hemispheres"), "{quiet}");
    let loud = ok(args!("interp", &flipped, "--animation", "Walk", "-o", &csv));
    assert!(
        loud.contains(
            "node \"Cubic\"): CUBICSPLINE keys 0 and 1 (0 s, 0.4 s) lie in \
             opposite hemispheres (dot -0."
        ) && loud.contains("it turns the long way round between them"),
        "{loud}"
    );
    assert!(
        loud.contains(
            "node \"Hips\"): LINEAR keys 9 and 10 (0.3 s, 0.33333334 s) lie in \
             opposite hemispheres (dot -"
        ) && loud.contains("(and 1 more pairs)"),
        "{loud}"
    );
    let (a, f) = (
        Asset::read_path(&aligned).unwrap(),
        Asset::read_path(&flipped).unwrap(),
    );
    let swing = (1..40)
        .map(|i| i as f64 / 100.0)
        .map(|t| rot_angle(channel(&a, 0, 4).sample(t), channel(&f, 0, 4).sample(t)))
        .fold(0.0, f64::max);
    assert!(swing > 1.0, "CUBICSPLINE: {swing} rad");
    let same = (0..100)
        .map(|i| i as f64 / 100.0)
        .map(|t| rot_angle(channel(&a, 0, 0).sample(t), channel(&f, 0, 0).sample(t)))
        .fold(0.0, f64::max);
    assert!(same < 1e-6, "LINEAR: {same} rad");
}

/// A `.gltf` on standard input is read as glTF (told by its top-level `"asset"`), the same frames
/// as from the file; a keyframe document on standard input is still one.
#[test]
fn a_gltf_on_standard_input_is_gltf() {
    let src = fixtures().join("gltf/minimal_linear.gltf");
    let from_file = run(args!(
        "interp",
        &src,
        "--fps",
        "10",
        "--output-format",
        "csv"
    ));
    assert!(from_file.status.success());
    let piped = bin()
        .args(args!("interp", "--fps", "10", "--output-format", "csv"))
        .write_stdin(std::fs::read(&src).unwrap())
        .output()
        .unwrap();
    assert!(
        piped.status.success(),
        "{}",
        String::from_utf8_lossy(&piped.stderr)
    );
    assert_eq!(piped.stdout, from_file.stdout);
    let keys = bin()
        .args(args!("interp", "--fps", "10"))
        .write_stdin(
            r#"{"keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "quat": [0, 1, 0, 0]}]}"#,
        )
        .output()
        .unwrap();
    assert!(
        keys.status.success(),
        "{}",
        String::from_utf8_lossy(&keys.stderr)
    );
}

/// Everything but what the writer rewrites (animations, and the lists it prunes and appends
/// to), with each accessor index of a mesh or skin replaced by that accessor (its JSON without
/// its `bufferView`, and the bytes of its view from its offset on, read here from the `.glb`'s
/// chunk, a `data:` URI or a file beside `path`): the objects, and the data they use, as they
/// were.
pub(crate) fn untouched(path: &Path) -> Value {
    let json = asset_json(path);
    let bytes = std::fs::read(path).unwrap();
    let buffer = |b: usize| -> Vec<u8> {
        match json["buffers"][b]["uri"].as_str() {
            None => {
                let n = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
                bytes[20 + n + 8..].to_vec()
            }
            Some(uri) if uri.starts_with("data:") => {
                let b64 = &uri[uri.find(',').unwrap() + 1..];
                base64::engine::general_purpose::STANDARD
                    .decode(b64)
                    .unwrap()
            }
            Some(uri) => std::fs::read(path.parent().unwrap().join(uri)).unwrap(),
        }
    };
    let accessor = |i: &Value| -> Value {
        let mut acc = json["accessors"][i.as_u64().unwrap() as usize].clone();
        let view = &json["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
        let start = view["byteOffset"].as_u64().unwrap_or(0) as usize
            + acc["byteOffset"].as_u64().unwrap_or(0) as usize;
        let end = view["byteOffset"].as_u64().unwrap_or(0) as usize
            + view["byteLength"].as_u64().unwrap() as usize;
        let data = buffer(view["buffer"].as_u64().unwrap() as usize)[start..end].to_vec();
        acc.as_object_mut().unwrap().remove("bufferView");
        // FNV-1a, to keep a failure's message short.
        let fnv = data.iter().fold(0xcbf29ce484222325u64, |h, &b| {
            (h ^ u64::from(b)).wrapping_mul(0x100000001b3)
        });
        let data = format!("{} bytes, FNV-1a {fnv:016x}", data.len());
        json!({"accessor": acc, "stride": view["byteStride"], "bytes": data})
    };
    let mut j = json.clone();
    for mesh in j["meshes"].as_array_mut().into_iter().flatten() {
        for p in mesh["primitives"].as_array_mut().unwrap() {
            for (_, a) in p["attributes"].as_object_mut().unwrap() {
                *a = accessor(a);
            }
            if p.get("indices").is_some() {
                p["indices"] = accessor(&p["indices"]);
            }
        }
    }
    for skin in j["skins"].as_array_mut().into_iter().flatten() {
        if skin.get("inverseBindMatrices").is_some() {
            skin["inverseBindMatrices"] = accessor(&skin["inverseBindMatrices"]);
        }
    }
    let o = j.as_object_mut().unwrap();
    for key in [
        "animations",
        "accessors",
        "bufferViews",
        "buffers",
        "images",
    ] {
        o.remove(key);
    }
    j
}

pub(crate) fn back_of(path: &Path) -> Asset {
    Asset::read_path(path).unwrap()
}

pub(crate) fn asset_json(path: &Path) -> Value {
    let bytes = std::fs::read(path).unwrap();
    if bytes.starts_with(b"glTF") {
        let n = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        serde_json::from_slice(&bytes[20..20 + n]).unwrap()
    } else {
        serde_json::from_slice(&bytes).unwrap()
    }
}

/// The CUBICSPLINE rotation of a real Blender export (`world.glb`, animation `gear_rotate`)
/// baked in f64 at 24 and 30 fps agrees with the independent Appendix C evaluation to 1e-9 rad.
#[test]
fn a_real_cubicspline_bake_agrees_with_the_python_reference() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("gltf/real/world.glb");
    for fps in ["24", "30"] {
        let csv = dir.path().join(format!("gear{fps}.csv"));
        ok(args!(
            "interp",
            &src,
            "--animation",
            "gear_rotate",
            "--fps",
            fps,
            "-o",
            &csv
        ));
        let frames = csv_track(&csv, "Circle");
        // The span is 1/24 s .. 1 s.
        assert_eq!(frames.len(), if fps == "24" { 24 } else { 29 });
        let times: Vec<f64> = frames.iter().map(|f| f.0).collect();
        let Some(want) = python_playback(&src, 0, 0, &times) else {
            return;
        };
        for (i, ((t, q), w)) in frames.iter().zip(&want).enumerate() {
            let d = rot_angle(*q, *w);
            assert!(d < 1e-9, "{fps} fps frame {i} ({t} s): {d:e} rad");
        }
    }
}

/// Real exports: the Khronos sample `RiggedSimple` (COLLADA2GLTF, skinned, LINEAR), Castle Game
/// Engine's `oaktree` (Blender 3.2: a STEP and a LINEAR animation, external buffer and images)
/// and `world.glb` (Blender 2.8: CUBICSPLINE rotation). Each is resampled into another folder as
/// `.glb` and `.gltf`: the Khronos validator finds no error (external files still found), nodes,
/// meshes, skins and materials are as they were, LINEAR keys come back at their own rate to
/// float32, a STEP key holds, and the CUBICSPLINE bake agrees with the independent Python
/// evaluation of Appendix C.
#[test]
fn real_assets_resample_validate_and_keep_their_keys() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("out");
    std::fs::create_dir(&sub).unwrap();
    for (name, fps) in [
        ("RiggedSimple.gltf", 24.0),
        ("oaktree.gltf", 25.0),
        ("world.glb", 24.0),
    ] {
        let src = fixtures().join("gltf/real").join(name);
        let input = Asset::read_path(&src).unwrap();
        for ext in ["glb", "gltf"] {
            let out = sub.join(format!("{name}.{ext}"));
            ok(args!("interp", &src, "--fps", &fps.to_string(), "-o", &out));
            validate(&out);
            assert_eq!(untouched(&out), untouched(&src), "{name} {ext}");
            let back = Asset::read_path(&out).unwrap();
            for (a, anim) in input.animations().unwrap().iter().enumerate() {
                for ch in anim.rotations() {
                    let got = channel(&back, a, ch.index());
                    assert_eq!(got.interpolation(), Interpolation::Linear);
                    let what = format!("{name} {ext} animation {a} channel {}", ch.index());
                    match ch.interpolation() {
                        Interpolation::Linear => {
                            // Every key is a frame of the output (COLLADA2GLTF wrote 1/24 s as
                            // 0.04166662, 13 float32 units off: within a microsecond here),
                            // reproduced to float32.
                            for (k, (&t, q)) in ch.times_f32().iter().zip(ch.values()).enumerate() {
                                let i = got
                                    .times_f32()
                                    .iter()
                                    .position(|&g| (g as f64 - t as f64).abs() <= 1e-6)
                                    .unwrap_or_else(|| {
                                        panic!("{what}: key {k} at {t} s not a frame")
                                    });
                                let d = rot_angle(got.values()[i], q.normalize());
                                assert!(d <= F32_ANGLE, "{what}: key {k}: {d:e} rad");
                            }
                        }
                        Interpolation::Step => {
                            for (i, &t) in got.times_f32().iter().enumerate() {
                                let key = ch.times_f32().iter().rposition(|&k| k <= t).unwrap_or(0);
                                let d = rot_angle(got.values()[i], ch.values()[key].normalize());
                                assert!(d <= F32_ANGLE, "{what}: frame {i}: {d:e} rad");
                            }
                        }
                        Interpolation::CubicSpline => {
                            // The frame times in f64 (the asset holds them as float32).
                            let times: Vec<f64> = got
                                .times_f32()
                                .iter()
                                .map(|&t| (t as f64 * fps).round() / fps)
                                .collect();
                            assert!(times.len() > ch.times().len(), "{what}: frames");
                            let Some(want) = python_playback(&src, a, ch.index(), &times) else {
                                continue;
                            };
                            for (i, (g, w)) in got.values().iter().zip(&want).enumerate() {
                                let d = rot_angle(*g, *w);
                                assert!(
                                    d <= F32_ANGLE,
                                    "{what}: frame {i} ({} s): {d:e} rad",
                                    times[i]
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

/// An animation whose span holds no frame at the output rate (oaktree's `idle`: one STEP key at
/// 0.04 s, written at 30 fps) is written as it was, with a warning; the others are resampled.
#[test]
fn an_animation_without_frames_is_kept_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("gltf/real/oaktree.gltf");
    let out = dir.path().join("oak30.glb");
    let stderr = ok(args!("interp", &src, "--fps", "30", "-o", &out));
    assert!(
        stderr.contains("animation idle: its span [0.03999999910593033, 0.03999999910593033] s holds no frame at 30 fps; it is written as it was"),
        "{stderr}"
    );
    validate(&out);
    let (before, after) = (asset_json(&src), asset_json(&out));
    assert_eq!(after["animations"][0], before["animations"][0]);
    assert_ne!(after["animations"][1], before["animations"][1]);
    let spawn = channel(&Asset::read_path(&out).unwrap(), 1, 1);
    assert_eq!(spawn.interpolation(), Interpolation::Linear);
    // 0.04 s (the first key, not a frame at 30 fps), then frames 2..=18 (to 0.6 s).
    assert_eq!(spawn.values().len(), 18);
    assert_eq!(spawn.times_f32()[..2], [0.04, (2.0f64 / 30.0) as f32]);
}

/// `reduce anim.gltf --scheme slerp -o small.glb`: every rotation channel becomes a LINEAR
/// sampler of its kept keys, which (sampled as glTF plays them) reproduces every frame within
/// the tolerance; the asset stays valid and the translation channel as it was. Other schemes,
/// and glTF output from a non-glTF input, are refused.
#[test]
fn reduce_writes_slerp_keys_into_the_asset() {
    let dir = tempfile::tempdir().unwrap();
    let src = write_walk(dir.path(), &walk_json());
    let input = Asset::read_path(&src).unwrap();
    let out = dir.path().join("small.glb");
    let reduce: &[&std::ffi::OsStr] = args!(
        "reduce",
        &src,
        "--animation",
        "Walk",
        "--scheme",
        "slerp",
        "--tolerance",
        "0.5",
        "--fps",
        "30"
    );
    ok(&[reduce, args!("-o", &out)].concat());
    validate(&out);
    let back = Asset::read_path(&out).unwrap();
    let (a, b) = (
        &input.animations().unwrap()[0],
        &back.animations().unwrap()[0],
    );
    same_vectors(b.translations(), a.translations(), "reduce");
    let tol = 0.5f64.to_radians();
    for ch in a.rotations() {
        let got = channel(&back, 0, ch.index());
        assert_eq!(got.interpolation(), Interpolation::Linear);
        assert!(got.values().len() >= 2);
        for k in 0..=30 {
            let t = f64::from((k as f64 / 30.0) as f32);
            let d = rot_angle(got.sample(t), ch.sample(t));
            assert!(
                d <= tol,
                "channel {}: frame {k}: {} deg",
                ch.index(),
                d.to_degrees()
            );
        }
    }
    // The 31 LINEAR keys of Hips' smooth spin need far fewer.
    assert!(channel(&back, 0, 0).values().len() < 16);
    // Without -o, the input's container, as interp writes it: a .gltf input as glTF JSON.
    let o = run(reduce);
    assert_eq!(o.status.code(), Some(0));
    let text: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(text["animations"].is_array());
    let (b, c, cmu) = (
        dir.path().join("b.glb"),
        dir.path().join("c.glb"),
        fixtures().join("bvh/cmu_01_01.bvh"),
    );
    let refused = |args: &[&std::ffi::OsStr], want: &str| {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2));
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains(want), "{e}");
        assert!(!b.exists() && !c.exists(), "nothing written");
    };
    // glTF output without --scheme is slerp's (the only scheme a LINEAR sampler plays): the
    // same bytes; another scheme is refused.
    let d = dir.path().join("default.glb");
    let no_scheme = [&reduce[..4], &reduce[6..], args!("-o", &d)].concat();
    ok(&no_scheme);
    assert_eq!(std::fs::read(&d).unwrap(), std::fs::read(&out).unwrap());
    refused(
        args!(
            "reduce",
            &src,
            "--scheme",
            "bezier",
            "--tolerance",
            "0.5",
            "-o",
            &b
        ),
        "only --scheme slerp's keys play as reduced",
    );
    refused(
        args!(
            "reduce",
            &cmu,
            "--scheme",
            "slerp",
            "--tolerance",
            "0.5",
            "-o",
            &c
        ),
        "the input must be glTF",
    );
}

/// A reduce makes the asset smaller: RiggedSimple baked at 60 fps into a `.glb`, then reduced
/// to a `.glb` at 0.5°, is smaller than the bake (the bake's samplers, accessors, views and
/// bytes are gone with its keys), valid, with no unused object the bake did not have.
#[test]
fn reduce_to_glb_is_smaller_than_its_input() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("gltf/real/RiggedSimple.gltf");
    let (baked, small) = (dir.path().join("baked.glb"), dir.path().join("small.glb"));
    ok(args!("interp", &src, "--fps", "60", "-o", &baked));
    ok(args!(
        "reduce",
        &baked,
        "--scheme",
        "slerp",
        "--tolerance",
        "0.5",
        "-o",
        &small
    ));
    let size = |p: &Path| std::fs::metadata(p).unwrap().len();
    assert!(
        size(&small) < size(&baked),
        "{} bytes from {}",
        size(&small),
        size(&baked)
    );
    if let (Some(before), Some(after)) = (unused_objects(&baked), unused_objects(&small)) {
        assert!(after.len() <= before.len(), "{after:?}, before {before:?}");
    }
}

/// A translation channel on other key times than its node's rotation is sampled at the
/// rotation keys for keys documents, with a warning; glTF output bakes (interp) or keeps and
/// reduces (reduce) the translation channel itself, so the warning does not apply there and is
/// not printed. The asset: walk.gltf with Arm (rotation keys at frames 5..=20) also translated
/// on Hips' 31 times.
#[test]
fn translation_warnings_only_where_they_apply() {
    let dir = tempfile::tempdir().unwrap();
    let mut json = walk_json();
    let walk = &mut json["animations"][0];
    let hips_translation = walk["samplers"][1].clone();
    walk["samplers"]
        .as_array_mut()
        .unwrap()
        .push(hips_translation);
    let arm = json!({"sampler": 5, "target": {"node": 1, "path": "translation"}});
    walk["channels"].as_array_mut().unwrap().push(arm);
    let src = write_walk(dir.path(), &json);
    let says = "translation channel 5 has other key times than the rotation";
    let (json_out, glb, keys, small) = (
        dir.path().join("out.json"),
        dir.path().join("out.glb"),
        dir.path().join("keys.json"),
        dir.path().join("small.glb"),
    );
    let walk_only: &[&std::ffi::OsStr] = args!("--animation", "Walk", "--tolerance", "0.5");
    let err = ok(args!(
        "interp",
        &src,
        "--animation",
        "Walk",
        "-o",
        &json_out
    ));
    assert!(err.contains(says), "{err}");
    let err = ok(args!("interp", &src, "--animation", "Walk", "-o", &glb));
    assert!(!err.contains("translation channel"), "{err}");
    let tolerance: &[&std::ffi::OsStr] = args!("--translation-tolerance", "0.01");
    let err = ok(&[
        args!("reduce", &src),
        walk_only,
        tolerance,
        args!("-o", &keys),
    ]
    .concat());
    assert!(err.contains(says), "{err}");
    let err = ok(&[args!("reduce", &src), walk_only, args!("-o", &small)].concat());
    assert!(!err.contains("translation channel"), "{err}");
    // The bake still carries Arm's translation, on the bake's times, as the asset plays it.
    let back = Asset::read_path(&glb).unwrap();
    assert_eq!(back.animations().unwrap()[0].translations().len(), 2);
}
