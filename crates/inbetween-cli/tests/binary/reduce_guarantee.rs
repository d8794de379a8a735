//! `reduce`'s guarantee as a user checks it: the keys it writes, played back the way they will be
//! played (`interp` at the frames' rate with the same options; a glTF player on the float32
//! times and rotations written), give every frame back within the tolerance.

use crate::support::{bin, rot_angle, stdout_of};
use glam::DQuat;

/// A spin of `deg` degrees per frame about z at 30 fps, `n` frames, as CSV text, and its
/// rotations.
fn spin_csv(deg: f64, n: usize) -> (String, Vec<DQuat>) {
    let mut text = String::from("time,w,x,y,z\n");
    let mut quats = Vec::with_capacity(n);
    for k in 0..n {
        let q = DQuat::from_rotation_z((deg * k as f64).to_radians());
        text.push_str(&format!(
            "{:?},{:?},{:?},{:?},{:?}\n",
            k as f64 / 30.0,
            q.w,
            q.x,
            q.y,
            q.z
        ));
        quats.push(q);
    }
    (text, quats)
}

/// The rotations of `interp`'s CSV output.
fn csv_rotations(text: &str) -> Vec<DQuat> {
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let h = rdr.headers().unwrap().clone();
    let c = |n: &str| h.iter().position(|x| x == n).unwrap();
    let (w, x, y, z) = (c("w"), c("x"), c("y"), c("z"));
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            let f = |i: usize| r[i].parse::<f64>().unwrap();
            DQuat::from_xyzw(f(x), f(y), f(z), f(w))
        })
        .collect()
}

/// Constant fast spins (up to 179° per frame): for every scheme, greedy and optimal, with and
/// without velocities, `interp` of `reduce`'s keys at the same rate and scheme reproduces every
/// frame within the tolerance. At these speeds hermite's and squad's blends pass antipodes, where
/// the geodesic between a blend's two points is barely defined and a direct evaluation and
/// `interp`'s forward differences part by up to half a turn: 9d68ad0 verified the one and wrote
/// keys the other missed frames of by 2–180°.
#[test]
fn fast_spins_play_back_within_the_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    let mut failures = Vec::new();
    for deg in [110.0, 130.0, 170.0, 179.0] {
        let (text, want) = spin_csv(deg, 61);
        let clip = dir.path().join(format!("spin{deg}.csv"));
        std::fs::write(&clip, text).unwrap();
        let clip = clip.to_str().unwrap();
        for tol in [2.0] {
            let tol_s = format!("{tol}");
            for scheme in ["hermite", "squad", "bezier", "slerp", "minaccel"] {
                for method in ["greedy", "optimal"] {
                    for vel in [true, false] {
                        let keys = dir.path().join("keys.json");
                        let keys = keys.to_str().unwrap();
                        let mut args = vec![
                            "reduce",
                            clip,
                            "--tolerance",
                            &tol_s,
                            "--scheme",
                            scheme,
                            "--method",
                            method,
                            "-o",
                            keys,
                        ];
                        if !vel {
                            args.push("--no-velocities");
                        }
                        stdout_of(bin().args(&args));
                        let back = stdout_of(bin().args([
                            "interp",
                            keys,
                            "--fps",
                            "30",
                            "--scheme",
                            scheme,
                            "--output-format",
                            "csv",
                        ]));
                        let got = csv_rotations(&back);
                        assert_eq!(got.len(), want.len());
                        let worst = got
                            .iter()
                            .zip(&want)
                            .map(|(g, w)| rot_angle(*g, *w).to_degrees())
                            .fold(0.0, f64::max);
                        if worst > tol {
                            failures.push(format!(
                                "{deg}°/frame, tolerance {tol}°, {scheme} {method} velocities \
                                 {vel}: {worst}°"
                            ));
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A glTF asset 4000 s into its timeline: one node, one LINEAR rotation channel with a key at
/// every frame of 30 fps (float32 times `4000 + k/30`) of a smooth turn of about 8° per second;
/// written as `anim.gltf` and `anim.bin` in `dir`. Returns the frames' rotations as the asset
/// holds them (float32, widened).
fn late_timeline_asset(dir: &std::path::Path, n: usize) -> Vec<DQuat> {
    let mut bin = Vec::new();
    let mut quats = Vec::with_capacity(n);
    for k in 0..n {
        bin.extend(((4000.0 + k as f64 / 30.0) as f32).to_le_bytes());
    }
    for k in 0..n {
        let s = k as f64 / 30.0;
        let q = DQuat::from_euler(
            glam::EulerRot::ZYX,
            0.1 * s,
            0.1 * (1.5 * s).sin(),
            0.004 * s * s,
        );
        let q32 = [q.x as f32, q.y as f32, q.z as f32, q.w as f32];
        for c in q32 {
            bin.extend(c.to_le_bytes());
        }
        let [x, y, z, w] = q32.map(f64::from);
        quats.push(DQuat::from_xyzw(x, y, z, w).normalize());
    }
    let (t_len, q_len) = (4 * n, 16 * n);
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "joint"}],
        "buffers": [{"uri": "anim.bin", "byteLength": t_len + q_len}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": t_len},
            {"buffer": 0, "byteOffset": t_len, "byteLength": q_len}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "SCALAR",
             "min": [4000.0f32], "max": [(4000.0 + (n - 1) as f64 / 30.0) as f32]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC4"}
        ],
        "animations": [{
            "channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}}],
            "samplers": [{"input": 0, "interpolation": "LINEAR", "output": 1}]
        }]
    });
    std::fs::write(dir.join("anim.bin"), bin).unwrap();
    std::fs::write(dir.join("anim.gltf"), json.to_string()).unwrap();
    quats
}

/// A GLB's rotation channel `0` of animation 0 decoded independently of the tool: its float32
/// key times (widened) and rotations, and its interpolation.
fn glb_rotation_keys(glb: &[u8]) -> (Vec<f64>, Vec<DQuat>, String) {
    let word = |at: usize| u32::from_le_bytes(glb[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(&glb[0..4], b"glTF");
    let json_len = word(12);
    let doc: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let bin_at = 20 + json_len;
    let bin = &glb[bin_at + 8..bin_at + 8 + word(bin_at)];
    let ch = &doc["animations"][0]["channels"][0];
    assert_eq!(ch["target"]["path"], "rotation");
    let sampler = &doc["animations"][0]["samplers"][ch["sampler"].as_u64().unwrap() as usize];
    let floats = |acc: u64, width: usize| -> Vec<f64> {
        let a = &doc["accessors"][acc as usize];
        assert_eq!(a["componentType"], 5126);
        let v = &doc["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        assert_eq!(v["buffer"], 0);
        let start = v["byteOffset"].as_u64().unwrap_or(0) as usize
            + a["byteOffset"].as_u64().unwrap_or(0) as usize;
        let stride = v["byteStride"].as_u64().map_or(4 * width, |s| s as usize);
        let count = a["count"].as_u64().unwrap() as usize;
        (0..count)
            .flat_map(|i| {
                (0..width).map(move |c| {
                    let at = start + i * stride + 4 * c;
                    f64::from(f32::from_le_bytes(bin[at..at + 4].try_into().unwrap()))
                })
            })
            .collect()
    };
    let times = floats(sampler["input"].as_u64().unwrap(), 1);
    let values = floats(sampler["output"].as_u64().unwrap(), 4);
    let quats = values
        .chunks(4)
        .map(|c| DQuat::from_xyzw(c[0], c[1], c[2], c[3]))
        .collect();
    let interp = sampler["interpolation"]
        .as_str()
        .unwrap_or("LINEAR")
        .to_string();
    (times, quats, interp)
}

/// glTF 2.0 Appendix C, LINEAR rotation: the keys either side of `t` (clamped outside them),
/// slerp along the shorter arc at `s = (t − t_k)/(t_{k+1} − t_k)`.
fn gltf_linear(times: &[f64], quats: &[DQuat], t: f64) -> DQuat {
    let n = times.len();
    if t <= times[0] {
        return quats[0].normalize();
    }
    if t >= times[n - 1] {
        return quats[n - 1].normalize();
    }
    let k = times.partition_point(|&x| x <= t) - 1;
    let s = (t - times[k]) / (times[k + 1] - times[k]);
    let (a, mut b) = (quats[k].normalize(), quats[k + 1].normalize());
    let mut d = a.dot(b);
    if d < 0.0 {
        b = -b;
        d = -d;
    }
    let theta = d.min(1.0).acos();
    if theta < 1e-12 {
        return a;
    }
    (a * ((1.0 - s) * theta).sin() + b * (s * theta).sin()) * (1.0 / theta.sin())
}

/// `reduce anim.gltf --scheme slerp -o out.glb` 4000 s into a timeline: a player evaluating the
/// written LINEAR keys at their float32 times (each up to 1.2e-4 s from its frame's) gives every
/// frame within the tolerance. 9d68ad0 verified the keys at their exact frame times and missed
/// frames by up to 0.014° over a 0.005° tolerance 1000 s in (more further in).
#[test]
fn gltf_keys_play_within_the_tolerance_far_into_the_timeline() {
    let dir = tempfile::tempdir().unwrap();
    let want = late_timeline_asset(dir.path(), 301);
    let out = dir.path().join("out.glb");
    stdout_of(bin().args([
        "reduce".as_ref(),
        dir.path().join("anim.gltf").as_os_str(),
        "--scheme".as_ref(),
        "slerp".as_ref(),
        "--tolerance".as_ref(),
        "0.005".as_ref(),
        "--fps".as_ref(),
        "30".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ] as [&std::ffi::OsStr; 10]));
    let (times, quats, interp) = glb_rotation_keys(&std::fs::read(&out).unwrap());
    assert_eq!(interp, "LINEAR");
    assert!(times.len() < want.len(), "{} keys", times.len());
    let tol = 0.005f64.to_radians();
    let mut worst = (0.0, 0);
    for (k, w) in want.iter().enumerate() {
        let e = rot_angle(gltf_linear(&times, &quats, 4000.0 + k as f64 / 30.0), *w);
        if e > worst.0 {
            worst = (e, k);
        }
    }
    assert!(
        worst.0 <= tol,
        "frame {}: {}° over {}° ({} keys)",
        worst.1,
        worst.0.to_degrees(),
        tol.to_degrees(),
        times.len()
    );
}

/// A held pose (40° about (1, 1, 0)) for a minute at 30 fps with one frame turned 170° about z
/// in the middle: `reduce --scheme minaccel` keeps the blip and its two neighbours, and `interp`
/// of its keys gives every frame back within the tolerance. Segment tests across the blip carry
/// velocities of about 90 rad/s, whose start curves needed grids of 7 000–20 000 points and the
/// whole Newton budget each: 87 s (release) before such segments were taken as not feasible
/// unsolved, 0.13 s after.
#[test]
fn a_held_pose_with_a_half_turn_blip_reduces_promptly_under_minaccel() {
    let dir = tempfile::tempdir().unwrap();
    let axis = glam::DVec3::new(1.0, 1.0, 0.0).normalize();
    let held = DQuat::from_axis_angle(axis, 40f64.to_radians());
    let blip = DQuat::from_rotation_z(170f64.to_radians()) * held;
    let want: Vec<DQuat> = (0..1800)
        .map(|k| if k == 900 { blip } else { held })
        .collect();
    let mut text = String::from("time,w,x,y,z\n");
    for (k, q) in want.iter().enumerate() {
        let t = k as f64 / 30.0;
        text.push_str(&format!("{t:?},{:?},{:?},{:?},{:?}\n", q.w, q.x, q.y, q.z));
    }
    let clip = dir.path().join("blip.csv");
    std::fs::write(&clip, text).unwrap();
    let keys = dir.path().join("keys.csv");
    let reduce = [
        "reduce",
        "--scheme",
        "minaccel",
        "--tolerance",
        "0.01",
        "-o",
    ];
    bin()
        .args(reduce)
        .args([&keys, &clip])
        .timeout(std::time::Duration::from_secs(60))
        .assert()
        .success();
    let written = std::fs::read_to_string(&keys).unwrap();
    assert_eq!(written.lines().count(), 1 + 5, "{written}");
    let back = stdout_of(bin().arg("interp").arg(&keys).args([
        "--fps",
        "30",
        "--scheme",
        "minaccel",
        "--output-format",
        "csv",
    ]));
    let got = csv_rotations(&back);
    assert_eq!(got.len(), want.len());
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert!(rot_angle(*g, *w).to_degrees() <= 0.01, "frame {k}");
    }
}

/// A wobble about two axes at 60 fps, `n` frames, as CSV text, and its rotations.
fn wobble_csv(n: usize) -> (String, Vec<DQuat>) {
    let mut text = String::from("time,w,x,y,z\n");
    let mut quats = Vec::with_capacity(n);
    for k in 0..n {
        let t = k as f64 / 60.0;
        let q = DQuat::from_rotation_z(1.3 * (2.1 * t).sin())
            * DQuat::from_rotation_x(0.7 * (3.4 * t + 0.5).sin());
        text.push_str(&format!("{t:?},{:?},{:?},{:?},{:?}\n", q.w, q.x, q.y, q.z));
        quats.push(q);
    }
    (text, quats)
}

/// `reduce --precision N`: the keys (rotations and velocities) are written with N digits after
/// the point, and those numbers (read back by `interp`, at the frames' rate) give every frame
/// back within the tolerance. With 4 digits the rounding alone (up to 5e-5 per quaternion
/// component, about 0.01°) would push bezier's keys at 0.02° and slerp's at 0.1° over it: `-v`
/// shows the tolerance was tightened. With 2 digits no tightening can help (the rounding alone
/// misses), an input error saying so.
#[test]
fn rounded_keys_meet_the_tolerance_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let (text, want) = wobble_csv(301);
    let clip = dir.path().join("wobble.csv");
    std::fs::write(&clip, text).unwrap();
    let keys = dir.path().join("keys.csv");
    for (scheme, tol) in [("bezier", 0.02), ("slerp", 0.1)] {
        let o = bin()
            .args([
                "reduce",
                "--tolerance",
                &tol.to_string(),
                "--precision",
                "4",
                "-v",
            ])
            .args(["--scheme", scheme])
            .arg(&clip)
            .arg("-o")
            .arg(&keys)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{err}");
        let tightened = err
            .lines()
            .find_map(|l| l.split("tightened by ").nth(1))
            .unwrap_or_else(|| panic!("{err}"));
        assert!(tightened.parse::<f64>().unwrap() > 0.0, "{err}");
        let written = std::fs::read_to_string(&keys).unwrap();
        // Every number but the time (always shortest round trip) has 4 digits at most.
        for field in written.lines().skip(1).flat_map(|l| l.split(',').skip(1)) {
            if let Some((_, decimals)) = field.split_once('.') {
                assert!(decimals.len() <= 4, "{field}");
            }
        }
        let mut interp = bin();
        interp
            .args(["interp", "--scheme", scheme, "--fps", "60"])
            .arg(&keys);
        let got = csv_rotations(&stdout_of(&mut interp));
        assert_eq!(got.len(), want.len());
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            let d = rot_angle(*g, *w).to_degrees();
            assert!(d <= tol, "{scheme}: frame {k}: {d} deg");
        }
    }
    let o = bin()
        .args(["reduce", "--tolerance", "0.02", "--precision", "2"])
        .arg(&clip)
        .arg("-o")
        .arg(&keys)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--precision 2: too few digits for --tolerance 0.02"),
        "{err}"
    );
}
