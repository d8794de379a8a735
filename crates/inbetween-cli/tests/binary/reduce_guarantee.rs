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
            for scheme in ["hermite", "squad", "bezier", "slerp", "nlerp", "minaccel"] {
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

/// A keys CSV's rows (`track,frame,w,x,y,z,…`) as `(track, frame, quaternion)`.
fn quat_rows(text: &str) -> Vec<(String, f64, DQuat)> {
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let h = rdr.headers().unwrap().clone();
    let c = |n: &str| h.iter().position(|x| x == n);
    let (track, frame) = (c("track"), c("frame").or(c("time")).unwrap());
    let [w, x, y, z] = ["w", "x", "y", "z"].map(|n| c(n).unwrap());
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            let f = |i: usize| r[i].parse::<f64>().unwrap();
            let name = track.map_or(String::new(), |i| r[i].to_string());
            (name, f(frame), DQuat::from_xyzw(f(x), f(y), f(z), f(w)))
        })
        .collect()
}

/// The player's nlerp, written here from its definition (not the library's): each key in the
/// hemisphere of the one before (`--path shortest`), the four components lerped between the two
/// keys around `t`, normalised.
fn nlerp_player(times: &[f64], keys: &[DQuat], t: f64) -> DQuat {
    let mut q = keys.to_vec();
    for i in 1..q.len() {
        if q[i].dot(q[i - 1]) < 0.0 {
            q[i] = -q[i];
        }
    }
    let i = times.partition_point(|&k| k <= t).clamp(1, times.len() - 1) - 1;
    let u = ((t - times[i]) / (times[i + 1] - times[i])).clamp(0.0, 1.0);
    let p = q[i] * (1.0 - u) + q[i + 1] * u;
    p / p.length()
}

/// The largest angle (degrees) between each frame and the keys played by [`nlerp_player`],
/// track by track, frames and keys matched by name.
fn worst_under_nlerp(frames: &str, keys: &str) -> (f64, usize) {
    let (frames, keys) = (quat_rows(frames), quat_rows(keys));
    let (mut worst, mut n): (f64, usize) = (0.0, 0);
    let mut names: Vec<&String> = frames.iter().map(|r| &r.0).collect();
    names.dedup();
    for name in names {
        let own: Vec<_> = keys.iter().filter(|r| &r.0 == name).collect();
        let (t, q): (Vec<f64>, Vec<DQuat>) = own.iter().map(|r| (r.1, r.2)).unzip();
        assert!(t.len() >= 2, "track {name}: {} keys", t.len());
        for (_, f, want) in frames.iter().filter(|r| &r.0 == name) {
            worst = worst.max(rot_angle(nlerp_player(&t, &q, *f), *want).to_degrees());
            n += 1;
        }
    }
    (worst, n)
}

/// Reduce for the player: the keys of `reduce --scheme nlerp` (a real capture, every joint),
/// played by an nlerp written here, meet the tolerance at every input frame; on a clip with
/// long segments, slerp's keys played by nlerp do not (so nlerp's guarantee is not slerp's).
#[test]
fn nlerp_keys_play_within_the_tolerance_under_an_independent_nlerp() {
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let bvh = crate::support::fixtures().join("bvh/cmu_01_01.bvh");
    let bvh = bvh.to_str().unwrap();
    let frames_csv = out("frames.csv");
    stdout_of(bin().args(["convert", bvh, "--to", "quat", "-o", &frames_csv]));
    let frames = std::fs::read_to_string(&frames_csv).unwrap();
    for tol in [0.25, 1.0] {
        let keys = out("keys.csv");
        let tol_s = tol.to_string();
        let args = [
            "reduce",
            bvh,
            "--scheme",
            "nlerp",
            "--tolerance",
            &tol_s,
            "--translation-tolerance",
            "0.01",
            "--to",
            "quat",
            "-o",
            &keys,
        ];
        for method in [&[][..], &["--method", "optimal"], &["--shared-keys"]] {
            stdout_of(bin().args(args).args(method));
            let (worst, n) = worst_under_nlerp(&frames, &std::fs::read_to_string(&keys).unwrap());
            eprintln!("nlerp {tol}° {method:?}: {n} frames, worst {worst:.6}°");
            assert!(n > 1000, "{n} frames compared");
            // The keys are written with every digit: only round-off separates the two nlerps.
            assert!(worst <= tol + 1e-9, "{tol}° {method:?}: {worst}°");
        }
    }

    // A constant spin, 2° a frame for 120°: slerp's keys are its two ends.
    let (text, _) = spin_csv(2.0, 61);
    let clip = out("spin.csv");
    std::fs::write(&clip, text).unwrap();
    let frames = std::fs::read_to_string(&clip).unwrap();
    let tol = 0.5;
    let worst_of = |scheme: &str| {
        let keys = out(&format!("{scheme}.csv"));
        stdout_of(bin().args([
            "reduce",
            &clip,
            "--scheme",
            scheme,
            "--tolerance",
            "0.5",
            "-o",
            &keys,
        ]));
        worst_under_nlerp(&frames, &std::fs::read_to_string(&keys).unwrap()).0
    };
    let (nlerp, slerp) = (worst_of("nlerp"), worst_of("slerp"));
    eprintln!("spin, 0.5°: nlerp's keys {nlerp:.4}°, slerp's keys {slerp:.4}° under nlerp");
    assert!(nlerp <= tol + 1e-9, "{nlerp}");
    assert!(
        slerp > tol,
        "slerp's keys happen to play within {tol}° under nlerp: {slerp}"
    );
}

/// glTF plays LINEAR rotations by slerp: keys reduced under nlerp are not written into a glTF
/// asset (exit 2, nothing written).
#[test]
fn nlerp_keys_are_not_written_to_gltf() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("x.glb");
    let src = crate::support::fixtures().join("gltf/samplers.glb");
    let err = crate::support::stderr_of(
        bin()
            .args([
                "reduce",
                src.to_str().unwrap(),
                "--scheme",
                "nlerp",
                "--tolerance",
                "1",
            ])
            .arg("-o")
            .arg(&glb),
        2,
    );
    assert!(err.contains("only --scheme slerp's keys"), "{err}");
    assert!(!glb.exists());
}
