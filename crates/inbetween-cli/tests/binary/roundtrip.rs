//! `convert` round trips: every representation through CSV and JSON, single and multi-track,
//! from a file and from stdin, gives back the same rotations (1e-12 rad) and times.

use crate::support::rot_angle;
use assert_cmd::Command;
use glam::DQuat;
use std::path::Path;

fn convert(args: &[&str], stdin: Option<&[u8]>) -> Vec<u8> {
    let mut cmd = Command::cargo_bin("inbetween").unwrap();
    cmd.current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .arg("convert")
        .args(args);
    cmd.write_stdin(stdin.unwrap_or(b""));
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// (track, time, quaternion) rows of a CSV quaternion document.
fn quat_rows(csv_text: &[u8]) -> Vec<(String, f64, DQuat)> {
    let mut rdr = csv::Reader::from_reader(csv_text);
    let h = rdr.headers().unwrap().clone();
    let col = |n: &str| h.iter().position(|c| c == n).unwrap();
    let (w, x, y, z) = (col("w"), col("x"), col("y"), col("z"));
    let t = h.iter().position(|c| c == "time" || c == "frame").unwrap();
    let track = h.iter().position(|c| c == "track");
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            let f = |i: usize| r[i].parse::<f64>().unwrap();
            let name = track.map(|i| r[i].to_string()).unwrap_or_default();
            (name, f(t), DQuat::from_xyzw(f(x), f(y), f(z), f(w)))
        })
        .collect()
}

#[test]
fn every_representation_round_trips_through_csv_and_json() {
    let inputs = [
        "fixtures/convert/two_tracks.csv",
        "fixtures/convert/mixed.json",
        "fixtures/convert/euler_zyx.json",
    ];
    let reprs = [
        "quat",
        "matrix",
        "axis-angle",
        "rotvec",
        "euler:ZYX",
        "euler:xzx",
    ];
    for input in inputs {
        assert!(
            Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
                .join(input)
                .exists()
        );
        let reference = quat_rows(&convert(
            &[input, "--to", "quat", "--output-format", "csv"],
            None,
        ));
        assert!(reference.len() >= 4);
        for repr in reprs {
            for format in ["csv", "json"] {
                for angles in ["deg", "rad"] {
                    let mid = convert(
                        &[
                            input,
                            "--to",
                            repr,
                            "--output-format",
                            format,
                            "--angles",
                            angles,
                        ],
                        None,
                    );
                    // Back from stdin (format sniffed), CSV Euler needs --from.
                    let mut args = vec!["-", "--to", "quat", "--output-format", "csv"];
                    args.extend(["--angles", angles]);
                    if repr.starts_with("euler") {
                        args.extend(["--from", repr]);
                    }
                    let back = quat_rows(&convert(&args, Some(&mid)));
                    assert_eq!(back.len(), reference.len(), "{input} {repr} {format}");
                    for (a, b) in back.iter().zip(&reference) {
                        assert_eq!(a.0, b.0, "{input} {repr} {format}: track");
                        assert_eq!(a.1, b.1, "{input} {repr} {format}: time");
                        assert!(
                            rot_angle(a.2, b.2) < 1e-12,
                            "{input} {repr} {format} {angles}: {} vs {}",
                            a.2,
                            b.2
                        );
                        if repr == "quat" {
                            assert!((a.2 - b.2).length() < 1e-15, "sign kept: {} {}", a.2, b.2);
                        }
                    }
                }
            }
        }
    }
}

/// Rows `(time, w, x, y, z, wx, wy, wz)` of interp's CSV output with `--velocity`.
fn frame_rows(text: &[u8]) -> Vec<[f64; 8]> {
    let mut rdr = csv::Reader::from_reader(text);
    let h = rdr.headers().unwrap().clone();
    let cols: Vec<usize> = ["time", "w", "x", "y", "z", "wx", "wy", "wz"]
        .iter()
        .map(|n| h.iter().position(|c| c == *n).unwrap())
        .collect();
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            std::array::from_fn(|i| r[cols[i]].parse().unwrap())
        })
        .collect()
}

/// A dense `interp --velocity` output read back as keys (each frame a key carrying its
/// velocity) gives, at the same rate, the same curve and the same velocities — in CSV and JSON,
/// for every scheme with tangents.
#[test]
fn dense_output_with_velocities_reads_back_as_itself() {
    let dir = tempfile::tempdir().unwrap();
    let interp = |args: &[&str]| {
        crate::support::stdout_of(crate::support::bin().arg("interp").args(args)).into_bytes()
    };
    for scheme in ["hermite", "bezier", "squad"] {
        for ext in ["csv", "json"] {
            let dense = dir.path().join(format!("{scheme}.{ext}"));
            let dense = dense.to_str().unwrap();
            interp(&[
                "fixtures/interp/nonuniform.csv",
                "--fps",
                "24",
                "--scheme",
                scheme,
                "--velocity",
                "-o",
                dense,
            ]);
            // JSON declares its rate; CSV's output rate must be given again.
            let first = match ext {
                "json" => interp(&[
                    dense,
                    "--scheme",
                    scheme,
                    "--velocity",
                    "--output-format",
                    "csv",
                ]),
                _ => interp(&[dense, "--fps", "24", "--scheme", scheme, "--velocity"]),
            };
            let again = interp(&[
                dense,
                "--fps",
                "24",
                "--scheme",
                scheme,
                "--velocity",
                "--output-format",
                "csv",
            ]);
            let want = frame_rows(&interp(&[
                "fixtures/interp/nonuniform.csv",
                "--fps",
                "24",
                "--scheme",
                scheme,
                "--velocity",
            ]));
            for got in [frame_rows(&first), frame_rows(&again)] {
                assert_eq!(got.len(), want.len(), "{scheme} {ext}");
                for (g, w) in got.iter().zip(&want) {
                    assert_eq!(g[0], w[0]);
                    let (qg, qw) = (
                        DQuat::from_xyzw(g[2], g[3], g[4], g[1]),
                        DQuat::from_xyzw(w[2], w[3], w[4], w[1]),
                    );
                    assert!(rot_angle(qg, qw) <= 1e-12, "{scheme} {ext} at {}", g[0]);
                    for k in 5..8 {
                        assert!(
                            (g[k] - w[k]).abs() <= 1e-9 * w[k].abs().max(1.0),
                            "{scheme} {ext} at {}: {g:?} vs {w:?}",
                            g[0]
                        );
                    }
                }
            }
        }
    }
}

/// The binary's standard output for `args` (which must succeed).
fn stdout(args: &[&str]) -> Vec<u8> {
    crate::support::stdout_of(crate::support::bin().args(args)).into_bytes()
}

/// `reduce` as a user runs it: `reduce clip.csv --tolerance 0.5 -o keys.json && interp keys.json
/// --fps 30 -o back.csv` gives every frame of the clip within 0.5°, for every scheme (the same
/// `--scheme` both times), with and without velocities.
#[test]
fn reduce_then_interp_gives_every_frame_back() {
    let dir = tempfile::tempdir().unwrap();
    let run = stdout;
    let clip = dir.path().join("clip.csv");
    let clip = clip.to_str().unwrap();
    run(&[
        "interp",
        "fixtures/interp/nonuniform.csv",
        "--fps",
        "30",
        "-o",
        clip,
    ]);
    let want = frame_rows_q(&std::fs::read(clip).unwrap());
    for scheme in ["bezier", "hermite", "squad", "slerp", "minaccel"] {
        for extra in [
            &[][..],
            &["--no-velocities"][..],
            &["--method", "optimal"][..],
        ] {
            let keys = dir.path().join(format!("{scheme}.json"));
            let keys = keys.to_str().unwrap();
            let mut args = vec![
                "reduce",
                clip,
                "--tolerance",
                "0.5",
                "--scheme",
                scheme,
                "-o",
                keys,
            ];
            args.extend(extra);
            run(&args);
            let back = run(&[
                "interp",
                keys,
                "--fps",
                "30",
                "--scheme",
                scheme,
                "--output-format",
                "csv",
            ]);
            let got = frame_rows_q(&back);
            assert_eq!(got.len(), want.len(), "{scheme} {extra:?}");
            for (g, w) in got.iter().zip(&want) {
                assert_eq!(g.0, w.0);
                let e = rot_angle(g.1, w.1).to_degrees();
                assert!(e <= 0.5, "{scheme} {extra:?} at {}: {e}°", g.0);
            }
        }
    }
}

/// `reduce --path euler` keeps a spin's turns in its keys' Euler angles: two turns about z in 2 s
/// at constant speed (plus a wobble) are written as the input's own `euler:ZYX` triples, and
/// `interp --path euler` of them gives every frame back within the tolerance; slerp needs only
/// the two end keys where the shortest path needs one at least every half turn. Mixed
/// sequences and another `--to` are refused.
#[test]
fn reduce_with_path_euler_keeps_the_turns() {
    let dir = tempfile::tempdir().unwrap();
    let run = stdout;
    let clip = dir.path().join("spin.json");
    let clip = clip.to_str().unwrap();
    for (wobble, scheme) in [(0.0, "slerp"), (8.0, "bezier"), (8.0, "hermite")] {
        let angles: Vec<[f64; 3]> = (0..121)
            .map(|i| {
                let t = i as f64 / 60.0;
                [360.0 * t, wobble * (2.0 * t).sin(), 0.5 * wobble * t.cos()]
            })
            .collect();
        let keys: Vec<String> = angles
            .iter()
            .enumerate()
            .map(|(i, a)| {
                format!(
                    "{{\"frame\": {i}, \"euler\": [{}, {}, {}]}}",
                    a[0], a[1], a[2]
                )
            })
            .collect();
        let doc = format!(
            "{{\"fps\": 60, \"rotation\": \"euler:ZYX\", \"angles\": \"deg\", \"keys\": [{}]}}",
            keys.join(",")
        );
        std::fs::write(clip, doc).unwrap();
        let reduce = |path: &str| {
            let out = run(&[
                "reduce",
                clip,
                "--tolerance",
                "0.5",
                "--scheme",
                scheme,
                "--path",
                path,
            ]);
            serde_json::from_slice::<serde_json::Value>(&out).unwrap()
        };
        let (euler, shortest) = (reduce("euler"), reduce("shortest"));
        assert_eq!(euler["rotation"], "euler:ZYX");
        let written = euler["keys"].as_array().unwrap();
        for k in written {
            let i = k["frame"].as_u64().unwrap() as usize;
            let e: Vec<f64> = k["euler"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            // As given, to the round-off of degrees to radians and back.
            for (e, a) in e.iter().zip(angles[i]) {
                assert!(
                    (e - a).abs() <= 1e-12 * a.abs().max(1.0),
                    "{scheme}: key {i}: {e} vs {a}"
                );
            }
        }
        let n_short = shortest["keys"].as_array().unwrap().len();
        assert!(
            n_short >= 5,
            "{scheme}: {n_short} keys on the shortest path"
        );
        if scheme == "slerp" {
            assert_eq!(written.len(), 2, "{scheme}: two turns at constant speed");
        }
        let keys = dir.path().join("keys.json");
        std::fs::write(&keys, serde_json::to_vec(&euler).unwrap()).unwrap();
        let back = run(&[
            "interp",
            keys.to_str().unwrap(),
            "--fps",
            "60",
            "--scheme",
            scheme,
            "--path",
            "euler",
            "--output-format",
            "csv",
        ]);
        let got = frame_rows_q(&back);
        assert_eq!(got.len(), angles.len());
        for ((t, q), a) in got.iter().zip(&angles) {
            // glam's ZYX is intrinsic z, then y, then x (scipy's "ZYX").
            let [z, y, x] = a.map(f64::to_radians);
            let want = DQuat::from_euler(glam::EulerRot::ZYX, z, y, x);
            let e = rot_angle(*q, want).to_degrees();
            assert!(e <= 0.5, "{scheme} at {t}: {e}°");
        }
    }
    let refused = |args: &[&str], says: &str| {
        let out = crate::support::bin().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2));
        assert!(out.stdout.is_empty());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{err}");
    };
    refused(
        &[
            "reduce",
            clip,
            "--tolerance",
            "0.5",
            "--path",
            "euler",
            "--to",
            "euler:XYZ",
        ],
        "--to euler:XYZ: with --path euler",
    );
    refused(
        &[
            "reduce",
            "fixtures/bvh/mixed_orders.bvh",
            "--tolerance",
            "0.5",
            "--translation-tolerance",
            "0.1",
            "--path",
            "euler",
        ],
        "the tracks have euler:ZXY, euler:ZYX, euler:YXZ",
    );
}

/// (time, rotation) rows of interp's CSV output.
fn frame_rows_q(text: &[u8]) -> Vec<(f64, DQuat)> {
    let mut rdr = csv::Reader::from_reader(text);
    let h = rdr.headers().unwrap().clone();
    let c = |n: &str| h.iter().position(|x| x == n).unwrap();
    let (t, w, x, y, z) = (c("time"), c("w"), c("x"), c("y"), c("z"));
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            let f = |i: usize| r[i].parse::<f64>().unwrap();
            (f(t), DQuat::from_xyzw(f(x), f(y), f(z), f(w)))
        })
        .collect()
}

/// The same on real motion capture (CMU 01_01, 31 joints, 61 frames at 120 fps, with root
/// positions): `convert clip.bvh -o clip.csv`, `reduce clip.csv --tolerance 0.5
/// --translation-tolerance 0.01 --key-fps 120 -o keys.json` (a CSV cannot declare its rate), `interp keys.json --fps 120 -o back.csv`: every
/// frame of every joint within 0.5°, every position within 0.01.
#[test]
fn reduce_then_interp_on_real_motion_capture() {
    use std::collections::HashMap;
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&std::ffi::OsStr]| {
        crate::support::stdout_of(crate::support::bin().args(args));
    };
    let (clip, keys, back) = (
        dir.path().join("clip.csv"),
        dir.path().join("keys.json"),
        dir.path().join("back.csv"),
    );
    let bvh = crate::support::fixtures().join("bvh/cmu_01_01.bvh");
    let os = |s: &str| std::ffi::OsString::from(s);
    run(&[os("convert"), bvh.into(), os("-o"), clip.clone().into()]
        .iter()
        .map(|s| s.as_os_str())
        .collect::<Vec<_>>());
    // (track, frame) → (rotation, position)
    let table = |path: &Path| -> HashMap<(String, i64), (DQuat, [f64; 3])> {
        crate::support::read_table(path)
            .into_iter()
            .map(|r| {
                let f = |c: &str| r[c].parse::<f64>().unwrap();
                let q = DQuat::from_xyzw(f("x"), f("y"), f("z"), f("w"));
                let p = if r.get("tx").is_some_and(|s| !s.is_empty()) {
                    [f("tx"), f("ty"), f("tz")]
                } else {
                    [0.0; 3]
                };
                ((r["track"].clone(), r["frame"].parse().unwrap()), (q, p))
            })
            .collect()
    };
    let want = table(&clip);
    assert_eq!(want.len(), 31 * 61);
    for (scheme, method, shared) in ["bezier", "hermite", "slerp"]
        .into_iter()
        .flat_map(|s| ["greedy", "optimal"].map(move |m| (s, m)))
        .flat_map(|(s, m)| [(s, m, false), (s, m, true)])
    {
        {
            let mut args = vec![
                os("reduce"),
                clip.clone().into(),
                os("--tolerance"),
                os("0.5"),
                os("--translation-tolerance"),
                os("0.01"),
                os("--scheme"),
                os(scheme),
                os("--method"),
                os(method),
                os("--key-fps"),
                os("120"),
                os("-o"),
                keys.clone().into(),
            ];
            if shared {
                args.push(os("--shared-keys"));
            }
            run(&args.iter().map(|s| s.as_os_str()).collect::<Vec<_>>());
            if shared {
                // One set of key frames for every joint.
                let doc: serde_json::Value =
                    serde_json::from_slice(&std::fs::read(&keys).unwrap()).unwrap();
                let frames = |t: &serde_json::Value| -> Vec<u64> {
                    t["keys"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|k| k["frame"].as_u64().unwrap())
                        .collect()
                };
                let tracks = doc["tracks"].as_array().unwrap();
                assert_eq!(tracks.len(), 31);
                let first = frames(&tracks[0]);
                assert_eq!((first[0], first[first.len() - 1]), (0, 60));
                for t in tracks {
                    assert_eq!(frames(t), first, "{scheme} {method}: {}", t["name"]);
                }
            }
            let args = [
                os("interp"),
                keys.clone().into(),
                os("--fps"),
                os("120"),
                os("--scheme"),
                os(scheme),
                os("-o"),
                back.clone().into(),
            ];
            run(&args.iter().map(|s| s.as_os_str()).collect::<Vec<_>>());
            let got = table(&back);
            assert_eq!(got.len(), want.len(), "{scheme} {method}");
            for (k, (q, p)) in &want {
                let (gq, gp) = got[k];
                let d = rot_angle(gq, *q).to_degrees();
                assert!(d <= 0.5, "{scheme} {method} shared {shared} {k:?}: {d}°");
                for i in 0..3 {
                    assert!(
                        (gp[i] - p[i]).abs() <= 0.01 + 1e-9,
                        "{scheme} {method} {k:?}: position"
                    );
                }
            }
        }
    }
}

/// A random motion of `n` frames at 30 fps as a quaternion CSV: smooth angular velocity with
/// random coefficients, plus per-frame jitter of up to `noise` rad.
fn random_motion_csv(n: usize, c: [f64; 6], noise: f64, seed: u64) -> (String, Vec<DQuat>) {
    let mut s = seed;
    let mut rnd = move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    let mut text = String::from("time,w,x,y,z\n");
    let mut quats = Vec::new();
    for i in 0..n {
        let t = i as f64 / 30.0;
        let smooth = DQuat::from_euler(
            glam::EulerRot::ZYX,
            c[0] * t + c[1] * (2.0 * t).sin(),
            c[2] * (1.3 * t).cos(),
            c[3] * t * t + c[4] * t,
        );
        let jitter = DQuat::from_scaled_axis(glam::DVec3::new(rnd(), rnd(), rnd()) * (2.0 * noise));
        let q = jitter * smooth * DQuat::from_rotation_x(c[5]);
        text.push_str(&format!("{t:?},{:?},{:?},{:?},{:?}\n", q.w, q.x, q.y, q.z));
        quats.push(q);
    }
    (text, quats)
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 6, ..Default::default() })]

    /// The guarantee as the released binary gives it, over random smooth and noisy motions: for
    /// every scheme, method and with or without velocities, `reduce` keeps the first and last
    /// frame, `interp` of its keys at the clip's rate gives every frame back within the tolerance,
    /// and `optimal` keeps no more keys than `greedy`.
    #[test]
    fn reduce_then_interp_over_random_motions(
        c in proptest::array::uniform6(-1.5f64..1.5),
        noisy in proptest::prelude::any::<bool>(),
        seed in proptest::prelude::any::<u64>(),
        tol in 0.2f64..2.0,
    ) {
        let dir = tempfile::tempdir().unwrap();
        let noise = if noisy { 0.3f64.to_radians() } else { 0.0 };
        let (text, want) = random_motion_csv(46, c, noise, seed);
        let clip = dir.path().join("clip.csv");
        std::fs::write(&clip, text).unwrap();
        let clip = clip.to_str().unwrap();
        let tol_s = format!("{tol}");
        for scheme in ["bezier", "hermite", "squad", "slerp", "minaccel"] {
            for vel in [true, false] {
                let mut counts = Vec::new();
                for method in ["greedy", "optimal"] {
                    let keys = dir.path().join(format!("{scheme}-{vel}-{method}.json"));
                    let keys = keys.to_str().unwrap();
                    let mut args = vec![
                        "reduce", clip, "--tolerance", &tol_s, "--scheme", scheme, "--method",
                        method, "-o", keys,
                    ];
                    if !vel {
                        args.push("--no-velocities");
                    }
                    crate::support::stdout_of(crate::support::bin().args(&args));
                    let doc: serde_json::Value =
                        serde_json::from_slice(&std::fs::read(keys).unwrap()).unwrap();
                    // One track: the keys are at the top of the document.
                    let ks = doc["keys"].as_array().unwrap();
                    let n = ks.len();
                    proptest::prop_assert_eq!(ks[0]["time"].as_f64(), Some(0.0));
                    proptest::prop_assert_eq!(ks[n - 1]["time"].as_f64(), Some(45.0 / 30.0));
                    counts.push(n);
                    let back = crate::support::stdout_of(crate::support::bin().args([
                        "interp", keys, "--fps", "30", "--scheme", scheme, "--output-format", "csv",
                    ]));
                    let got = frame_rows_q(back.as_bytes());
                    proptest::prop_assert_eq!(got.len(), want.len());
                    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                        let e = rot_angle(g.1, *w).to_degrees();
                        proptest::prop_assert!(
                            e <= tol, "{} {} vel {}: frame {}: {}° > {}°", scheme, method, vel, i, e, tol
                        );
                    }
                }
                proptest::prop_assert!(counts[1] <= counts[0], "{} vel {}: {:?}", scheme, vel, counts);
            }
        }
    }
}

/// `reduce`'s refusals and defaults found by a user's review: a `--precision` whose rounding
/// alone misses the tolerance (3 digits of CMU's quaternions miss 0.1° by 0.054°) and a
/// tolerance below what can be verified are input errors with nothing written; a BVH input's
/// keys go out as JSON to an `-o` whose name does not say bvh.
#[test]
fn reduce_refuses_too_few_digits_and_unverifiable_tolerances() {
    let dir = tempfile::tempdir().unwrap();
    let clip = crate::support::fixtures().join("bvh/cmu_01_01.bvh");
    let clip = clip.to_str().unwrap();
    let refused = |extra: &[&str], says: &str| {
        let mut args = vec!["reduce", clip, "--translation-tolerance", "1"];
        args.extend(extra);
        let out = crate::support::bin().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        assert!(out.stdout.is_empty());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{extra:?}: {err}");
    };
    refused(
        &["--tolerance", "0.1", "--precision", "3"],
        "--precision 3: too few digits for --tolerance 0.1",
    );
    refused(&["--tolerance", "1e-15"], "give at least 5.7295779513082");
    refused(
        &["--tolerance", "1e-12", "--distance", "10"],
        "give at least 1e-8 length units",
    );
    let keys = dir.path().join("keys");
    stdout(&[
        "reduce",
        clip,
        "--tolerance",
        "1",
        "--translation-tolerance",
        "1",
        "-o",
        keys.to_str().unwrap(),
    ]);
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&keys).unwrap()).unwrap();
    assert_eq!(doc["tracks"].as_array().unwrap().len(), 31);
    // --shared-keys on tracks of different frame times names them.
    let two = dir.path().join("two.csv");
    std::fs::write(
        &two,
        "track,time,w,x,y,z\na,0,1,0,0,0\na,0.1,1,0,0,0\na,0.2,1,0,0,0\nb,0,1,0,0,0\nb,0.15,1,0,0,0\n",
    )
    .unwrap();
    let out = crate::support::bin()
        .args([
            "reduce",
            two.to_str().unwrap(),
            "--tolerance",
            "1",
            "--shared-keys",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(
            "track \"a\" (3 frames, 0 s to 0.2 s) and track \"b\" (2 frames, 0 s to 0.15 s)"
        ),
        "{err}"
    );
}

/// `reduce -v` reports each track's largest position error, and it is what `interp` of the keys
/// gives back (CMU 01_01's root, positions within 0.01).
#[test]
fn reduce_reports_the_position_error_interp_gives() {
    let dir = tempfile::tempdir().unwrap();
    let bvh = crate::support::fixtures().join("bvh/cmu_01_01.bvh");
    let bvh = bvh.to_str().unwrap();
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let (keys, back, frames) = (path("keys.json"), path("back.csv"), path("frames.csv"));
    let out = crate::support::bin()
        .args([
            "reduce",
            bvh,
            "--tolerance",
            "0.5",
            "--translation-tolerance",
            "0.01",
            "-v",
            "-o",
            &keys,
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let line = err.lines().find(|l| l.contains("track Hips:")).unwrap();
    let reported: f64 = line
        .split("max position error ")
        .nth(1)
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    stdout(&["interp", &keys, "--fps", "120", "-o", &back]);
    stdout(&["convert", bvh, "-o", &frames]);
    let hips = |p: &str| -> Vec<[f64; 3]> {
        crate::support::read_table(std::path::Path::new(p))
            .into_iter()
            .filter(|r| r["track"] == "Hips")
            .map(|r| ["tx", "ty", "tz"].map(|c| r[c].parse::<f64>().unwrap()))
            .collect()
    };
    let (got, want) = (hips(&back), hips(&frames));
    assert_eq!(got.len(), 61);
    let measured = got
        .iter()
        .zip(&want)
        .map(|(g, w)| (0..3).map(|i| (g[i] - w[i]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    assert!(measured > 0.0 && measured <= 0.01);
    // -v prints four significant digits.
    assert!(
        (reported - measured).abs() <= 1e-3 * measured,
        "{reported} vs {measured}"
    );
}
