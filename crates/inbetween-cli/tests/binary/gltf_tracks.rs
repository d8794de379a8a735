//! How glTF channels become tracks and frames: names that cannot collide, STEP and
//! CUBICSPLINE channels sampled lazily (no frame-sized memory before `--max-frames`), many
//! channels in linear time, keys one float32 ulp apart near a frame, messages that locate a key
//! by what the file has, and `plot` on a one-key track.

use crate::support::{bin, read_table, rot_angle};
use base64::Engine;
use glam::DQuat;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A channel to build: target node, interpolation, key times, values (for CUBICSPLINE, the
/// `(in, value, out)` triples flattened).
struct Chan {
    node: usize,
    interpolation: &'static str,
    times: Vec<f32>,
    values: Vec<DQuat>,
}

/// A glTF asset (JSON, one `data:` buffer) with nodes named `nodes` and one animation of
/// `channels`, all rotation channels.
fn asset(nodes: &[&str], channels: &[Chan]) -> Value {
    let mut data: Vec<u8> = Vec::new();
    let (mut views, mut accessors, mut samplers, mut chans) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut push = |data: &mut Vec<u8>, floats: &[f32], type_: &str, count: usize, minmax| {
        let offset = data.len();
        data.extend(floats.iter().flat_map(|x| x.to_le_bytes()));
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": floats.len() * 4}));
        let mut acc = json!({"bufferView": views.len() - 1, "componentType": 5126,
                             "count": count, "type": type_});
        if minmax {
            acc["min"] = json!([floats[0]]);
            acc["max"] = json!([floats[floats.len() - 1]]);
        }
        accessors.push(acc);
        accessors.len() - 1
    };
    for (i, c) in channels.iter().enumerate() {
        let input = push(&mut data, &c.times, "SCALAR", c.times.len(), true);
        let flat: Vec<f32> = c
            .values
            .iter()
            .flat_map(|q| q.to_array().map(|x| x as f32))
            .collect();
        let output = push(&mut data, &flat, "VEC4", c.values.len(), false);
        samplers.push(json!({"input": input, "output": output, "interpolation": c.interpolation}));
        chans.push(json!({"sampler": i, "target": {"node": c.node, "path": "rotation"}}));
    }
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&data)
    );
    let nodes: Vec<Value> = nodes.iter().map(|n| json!({ "name": n })).collect();
    json!({
        "asset": {"version": "2.0"},
        "nodes": nodes,
        "animations": [{"name": "A", "samplers": samplers, "channels": chans}],
        "buffers": [{"byteLength": data.len(), "uri": uri}],
        "bufferViews": views,
        "accessors": accessors
    })
}

fn write(dir: &Path, name: &str, json: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec(json).unwrap()).unwrap();
    path
}

macro_rules! args {
    ($($a:expr),* $(,)?) => { &[$(std::ffi::OsStr::new($a)),*] };
}

#[track_caller]
fn ok(args: &[&std::ffi::OsStr]) -> String {
    let out = bin()
        .args(args)
        .timeout(Duration::from_secs(120))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "exit {:?}: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The stderr of a run that must exit 2 and write nothing to stdout.
#[track_caller]
fn refused(args: &[&std::ffi::OsStr]) -> String {
    let out = bin()
        .args(args)
        .timeout(Duration::from_secs(120))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty());
    err
}

fn step(node: usize, times: &[f32], angles: &[f64]) -> Chan {
    Chan {
        node,
        interpolation: "STEP",
        times: times.to_vec(),
        values: angles.iter().map(|&a| DQuat::from_rotation_y(a)).collect(),
    }
}

fn linear(node: usize, times: &[f32], angles: &[f64]) -> Chan {
    Chan {
        node,
        interpolation: "LINEAR",
        times: times.to_vec(),
        values: angles.iter().map(|&a| DQuat::from_rotation_x(a)).collect(),
    }
}

/// `(track, time, rotation)` rows of an interp CSV.
fn csv_frames(path: &Path) -> Vec<(String, f64, DQuat)> {
    read_table(path)
        .iter()
        .map(|r| {
            let f = |c: &str| r[c].parse::<f64>().unwrap();
            (
                r["track"].clone(),
                f("time"),
                DQuat::from_xyzw(f("x"), f("y"), f("z"), f("w")),
            )
        })
        .collect()
}

#[test]
fn nodes_named_like_a_disambiguated_name_stay_distinct_tracks() {
    // Nodes `a#2`, `a`, `a`: the old rule named the second `a` (node 2) `a#2`, the first node's
    // name, so its LINEAR channel was taken for node 0's STEP channel.
    let dir = tempfile::tempdir().unwrap();
    let t: Vec<f32> = vec![0.0, 0.5, 1.0];
    let src = write(
        dir.path(),
        "names.gltf",
        &asset(
            &["a#2", "a", "a"],
            &[
                step(0, &t, &[0.0, 1.0, 2.0]),
                linear(1, &t, &[0.0, 0.3, 0.6]),
                linear(2, &t, &[0.0, 0.9, 1.8]),
            ],
        ),
    );
    let csv = dir.path().join("out.csv");
    ok(args!("interp", &src, "--scheme", "slerp", "-o", &csv));
    let frames = csv_frames(&csv);
    let mut names: Vec<&str> = frames.iter().map(|f| f.0.as_str()).collect();
    names.dedup();
    assert_eq!(names, ["a#2", "a", "a#2#2"]);
    // Node 2's track is its own LINEAR channel: slerp of its keys, 0.9 rad about x at 0.5 s,
    // half of it at 0.25 s (frame 7.5 is not a frame: 0.2333 s is 0.42 rad).
    for (name, time, q) in &frames {
        let want = match name.as_str() {
            "a#2" => DQuat::from_rotation_y(if *time < 0.5 - 1e-9 {
                0.0
            } else if *time < 1.0 - 1e-9 {
                1.0
            } else {
                2.0
            }),
            "a" => DQuat::from_rotation_x(0.6 * time),
            _ => DQuat::from_rotation_x(1.8 * time),
        };
        assert!(
            rot_angle(*q, want) < 1e-6,
            "track {name} at {time} s: {:e} rad off",
            rot_angle(*q, want)
        );
    }
    // glTF output: each channel gets its own frames.
    let out = dir.path().join("out.gltf");
    ok(args!("interp", &src, "--scheme", "slerp", "-o", &out));
    let asset = inbetween_io::gltf::Asset::read_path(&out).unwrap();
    let anim = &asset.animations().unwrap()[0];
    for ch in anim.rotations() {
        let q = ch.sample(1.0);
        let want = match ch.node() {
            0 => DQuat::from_rotation_y(2.0),
            1 => DQuat::from_rotation_x(0.6),
            _ => DQuat::from_rotation_x(1.8),
        };
        assert!(rot_angle(q, want) < 1e-6, "node {}", ch.node());
    }
}

/// A 10 s STEP clip: `keys` values evenly over 10 s.
fn step_clip(dir: &Path, keys: usize) -> PathBuf {
    let times: Vec<f32> = (0..keys)
        .map(|k| (10.0 * k as f64 / (keys - 1) as f64) as f32)
        .collect();
    let angles: Vec<f64> = (0..keys).map(|k| 0.1 * k as f64).collect();
    write(
        dir,
        "step10s.gltf",
        &asset(&["n"], &[step(0, &times, &angles)]),
    )
}

#[test]
fn step_over_many_frames_is_refused_by_max_frames_before_any_per_frame_work() {
    // 10 s at 10^6 fps: 10^7 frames. The old reader baked them (a Vec of keys per frame, 2 GB)
    // before interp compared them with --max-frames.
    let dir = tempfile::tempdir().unwrap();
    let src = step_clip(dir.path(), 11);
    let start = Instant::now();
    let err = refused(args!(
        "interp",
        &src,
        "--fps",
        "1000000",
        "--max-frames",
        "1000",
        "-o",
        "-"
    ));
    assert!(err.contains("more than --max-frames 1000"), "{err}");
    assert!(
        start.elapsed() < Duration::from_secs(15),
        "refused after {:?}",
        start.elapsed()
    );
    // analyze and plot read the channel as its held values (two keys per key), whatever the
    // rate; their own per-frame figures (energy) cost what a LINEAR clip's do.
    ok(args!("analyze", &src, "--fps", "1000", "--scheme", "slerp"));
    let svg = dir.path().join("p.svg");
    ok(args!(
        "plot", &src, "--fps", "1000000", "--scheme", "bezier", "-o", &svg
    ));
}

#[test]
fn step_frames_are_the_held_keys_at_every_frame() {
    // Keys at 0, 0.1, 0.5, 0.7, 1 s (0.1f32 is just after frame 3 at 30 fps: on it).
    let dir = tempfile::tempdir().unwrap();
    let times = [0.0f32, 0.1, 0.5, 0.7, 1.0];
    let angles = [0.0, 0.6, 1.2, 1.8, 2.4];
    let src = write(
        dir.path(),
        "s.gltf",
        &asset(&["n"], &[step(0, &times, &angles)]),
    );
    for fps in ["30", "24", "1000"] {
        let csv = dir.path().join(format!("s{fps}.csv"));
        ok(args!(
            "interp",
            &src,
            "--fps",
            fps,
            "-o",
            &csv,
            "--velocity"
        ));
        let frames = csv_frames(&csv);
        let n: f64 = fps.parse().unwrap();
        assert_eq!(frames.len(), n as usize + 1);
        for (k, (_, t, q)) in frames.iter().enumerate() {
            assert_eq!(*t, k as f64 / n);
            let key = times
                .iter()
                .rposition(|&kt| f64::from(kt) <= *t + 1e-7)
                .unwrap();
            let want = DQuat::from_rotation_y(angles[key]);
            assert!(rot_angle(*q, want) < 1e-7, "{fps} fps frame {k}");
        }
    }
}

/// Resampling `n` LINEAR channels to `.glb` (one per node): the best of two runs' wall time.
fn many_channels_seconds(dir: &Path, n: usize) -> f64 {
    let names: Vec<String> = (0..n).map(|i| format!("j{i}")).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let chans: Vec<Chan> = (0..n)
        .map(|i| linear(i, &[0.0, 1.0], &[0.0, 0.001 * i as f64]))
        .collect();
    let src = write(dir, &format!("many{n}.gltf"), &asset(&names, &chans));
    let out = dir.join(format!("many{n}.glb"));
    (0..2)
        .map(|_| {
            let start = Instant::now();
            ok(args!("interp", &src, "--fps", "2", "-o", &out));
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Four times the channels cost less than eight times the time: linear, not quadratic (the
/// source list was rebuilt for every channel, 63–115 s for 10 000 in a release build; a
/// quadratic cost would take sixteen times as long at four times the channels).
#[test]
fn ten_thousand_channels_take_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let small = many_channels_seconds(dir.path(), 2_500);
    let large = many_channels_seconds(dir.path(), 10_000);
    assert!(
        large < 8.0 * small,
        "2 500 channels {small} s, 10 000 channels {large} s"
    );
}

#[test]
fn float32_keys_one_ulp_apart_just_before_a_frame_are_kept_in_order() {
    // Frame 10 at 30 fps is 1/3 s; 1/3 as float32 is above it, and the two float32 numbers
    // below it are within two ulps of it: both snapped onto the frame, the second was refused
    // as out of order. Now the two keep their stored times.
    let third = 1.0f32 / 3.0;
    assert!(f64::from(third) > 1.0 / 3.0);
    let b = f32::from_bits(third.to_bits() - 1);
    let a = f32::from_bits(third.to_bits() - 2);
    assert!(f64::from(b) < 1.0 / 3.0);
    let dir = tempfile::tempdir().unwrap();
    let src = write(
        dir.path(),
        "ulp.gltf",
        &asset(
            &["n"],
            &[linear(0, &[0.0, a, b, 1.0], &[0.0, 0.5, 0.5, 1.0])],
        ),
    );
    let keys = dir.path().join("keys.json");
    ok(args!("convert", &src, "-o", &keys));
    let doc: Value = serde_json::from_slice(&std::fs::read(&keys).unwrap()).unwrap();
    let times: Vec<f64> = doc["keys"]
        .as_array()
        .or_else(|| doc["tracks"][0]["keys"].as_array())
        .unwrap()
        .iter()
        .map(|k| k["time"].as_f64().unwrap())
        .collect();
    assert_eq!(times, [0.0, f64::from(a), f64::from(b), 1.0]);
    ok(args!("interp", &src, "-o", &dir.path().join("f.csv")));
}

#[test]
fn track_errors_name_the_channel_key_and_time_never_nan() {
    let dir = tempfile::tempdir().unwrap();
    // Keys 1e-13 s apart: too close for a track (1e-12 s), located by the file's terms.
    let src = write(
        dir.path(),
        "close.gltf",
        &asset(
            &["n", "m"],
            &[
                linear(0, &[0.0, 1.0], &[0.0, 1.0]),
                linear(1, &[0.0, 1e-13], &[0.0, 1.0]),
            ],
        ),
    );
    let err = refused(args!("interp", &src, "-o", "-"));
    assert!(
        err.contains("close.gltf: animations[0].channels[1] key 1 (0.0000000000001 s)")
            && err.contains("at least 1e-12 s apart"),
        "{err}"
    );
    assert!(!err.contains("frame"), "{err}");
    // A CUBICSPLINE rotation through the zero 4-vector (from w = 1 to w = -1, no tangents): at
    // 0.5 s, frame 15 at 30 fps, it has no rotation.
    let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    let cubic = Chan {
        node: 0,
        interpolation: "CUBICSPLINE",
        times: vec![0.0, 1.0],
        values: vec![
            zero,
            DQuat::IDENTITY,
            zero,
            zero,
            DQuat::from_xyzw(0.0, 0.0, 0.0, -1.0),
            zero,
        ],
    };
    let src = write(dir.path(), "zero.gltf", &asset(&["n"], &[cubic]));
    for cmd in ["interp", "analyze", "plot"] {
        let svg = dir.path().join("z.svg");
        let mut a = vec![std::ffi::OsStr::new(cmd), src.as_os_str()];
        if cmd == "plot" {
            a.extend([std::ffi::OsStr::new("-o"), svg.as_os_str()]);
        }
        let err = refused(&a);
        assert!(
            err.contains("zero.gltf: animations[0].channels[0]: CUBICSPLINE keys 0 and 1"),
            "{cmd}: {err}"
        );
        assert!(
            !err.contains("NaN") && !err.contains("frame"),
            "{cmd}: {err}"
        );
        assert!(!svg.exists());
    }
}

#[test]
fn plot_of_a_one_key_track_finishes() {
    let dir = tempfile::tempdir().unwrap();
    let src = write(
        dir.path(),
        "pose.gltf",
        &asset(&["n"], &[linear(0, &[0.25], &[0.7])]),
    );
    for what in ["components", "speed", "energy"] {
        let svg = dir.path().join(format!("{what}.svg"));
        let start = Instant::now();
        ok(args!("plot", &src, "--what", what, "-o", &svg));
        assert!(start.elapsed() < Duration::from_secs(60));
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.starts_with("<svg") && !text.contains("NaN"), "{what}");
    }
    ok(args!("analyze", &src));
}

/// Found by the `gltf_reader` fuzz target: a 4 kB asset whose CUBICSPLINE key times run far
/// out was baked at every frame for `analyze`, `plot` and `reduce` (47 s and 10 GB); such bakes
/// are bounded in frames and refused at once.
#[test]
fn a_cubicspline_over_millions_of_frames_is_refused_before_baking() {
    let dir = tempfile::tempdir().unwrap();
    let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    let cubic = Chan {
        node: 0,
        interpolation: "CUBICSPLINE",
        // 200 000 s at 30 fps: 6 000 001 frames.
        times: vec![0.0, 200_000.0],
        values: vec![
            zero,
            DQuat::IDENTITY,
            zero,
            zero,
            DQuat::from_rotation_z(1.0),
            zero,
        ],
    };
    let src = write(dir.path(), "far.gltf", &asset(&["n"], &[cubic]));
    let runs: [&[&std::ffi::OsStr]; 2] = [
        args!("analyze", &src),
        args!("reduce", &src, "--tolerance", "1"),
    ];
    for a in runs {
        let cmd = a[0].to_string_lossy();
        let start = Instant::now();
        let err = refused(a);
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "{cmd}: {:?}",
            start.elapsed()
        );
        assert!(
            err.contains(
                "far.gltf: animations[0].channels[0]: CUBICSPLINE channels baked at 30 fps"
            ) && err.contains("this one spans 6000001"),
            "{cmd}: {err}"
        );
    }
}

/// A glTF bake whose new samplers would not fit a `.glb` (two LINEAR channels over 10⁶ s at
/// 200 fps: 2·10⁸ frames, 7.2 GB of float32) is refused before any frame is baked, whichever the
/// container, and nothing is written; before, every frame's rotation was held until the end.
#[test]
fn a_gltf_bake_larger_than_a_glb_can_hold_is_refused_before_baking() {
    let dir = tempfile::tempdir().unwrap();
    let json = asset(
        &["a", "b"],
        &[
            linear(0, &[0.0, 1e6], &[0.0, 1.0]),
            linear(1, &[0.0, 1e6], &[0.0, 2.0]),
        ],
    );
    let input = write(dir.path(), "long.gltf", &json);
    for out in ["out.glb", "out.gltf"] {
        let out = dir.path().join(out);
        let started = Instant::now();
        let err = refused(args!("interp", &input, "--fps", "200", "-o", &out));
        assert!(
            started.elapsed() < Duration::from_secs(20),
            "{:?}",
            started.elapsed()
        );
        assert!(
            err.contains("over the 4294967295 bytes a .glb can hold"),
            "{err}"
        );
        assert!(!out.exists());
    }
}
