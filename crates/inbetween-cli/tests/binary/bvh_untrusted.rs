//! BVH files as strangers write them: joints with one or two rotation channels (a hinge) or
//! some position channels, joints sharing a name, positions and angles near the largest float.
//! Nothing is lost or swapped, nothing overflows (the lookups' linearity is tested beside the
//! code: `io::bvh::keys`, `io::bvh::frames`). Expected values are the files' own numbers or
//! closed forms, read back by a plain reader written here (not `inbetween_io::bvh`).

use crate::support::bvh_rows as rows;
use std::path::Path;

/// Runs the binary with `args`; (exit code, stderr).
fn run(args: &[&std::ffi::OsStr]) -> (Option<i32>, String) {
    let o = crate::support::bin().args(args).output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Runs the binary with `args`, asserting success.
#[track_caller]
fn ok(args: &[&std::ffi::OsStr]) {
    let (code, stderr) = run(args);
    assert_eq!(code, Some(0), "{args:?}: {stderr}");
}

fn os(s: &str) -> &std::ffi::OsStr {
    s.as_ref()
}

/// A hinge (`CHANNELS 1 Xrotation`), a two-axis joint (`Zrotation Xrotation`), a joint with
/// positions and one rotation, one with a single position channel and a rotation: a root with
/// six channels above them.
const HINGES: &str = "HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Knee
  {
    OFFSET 0 -5 0
    CHANNELS 1 Xrotation
    JOINT Wrist
    {
      OFFSET 0 -5 0
      CHANNELS 2 Zrotation Xrotation
      End Site
      {
        OFFSET 0 -1 0
      }
    }
  }
  JOINT Slider
  {
    OFFSET 2 0 0
    CHANNELS 4 Xposition Yposition Zposition Yrotation
  }
  JOINT Lift
  {
    OFFSET -2 0 0
    CHANNELS 2 Yposition Zrotation
  }
}
";

/// Row `i` of the hinge clip: 15 channels, every number with at most 6 decimals. The hinge
/// turns 15° a frame (past 180°), the others move smoothly.
fn hinge_row(i: usize) -> Vec<f64> {
    let t = i as f64;
    let r = |x: f64| (x * 1e6).round() / 1e6;
    vec![
        // Hips: position, then Zrotation Xrotation Yrotation.
        r(0.5 * t),
        35.0,
        r(-0.25 * t),
        r(3.0 * t),
        r(2.0 * (0.3 * t).sin()),
        r(-t),
        // Knee: Xrotation.
        15.0 * t,
        // Wrist: Zrotation Xrotation.
        r(20.0 * (0.2 * t).sin()),
        r(-30.0 + 2.5 * t),
        // Slider: position, Yrotation.
        r(1.0 + 0.1 * t),
        2.0,
        r(-0.5 * t),
        r(7.0 - 4.0 * t),
        // Lift: Yposition, Zrotation.
        r(0.05 * t),
        r(10.0 - 4.0 * t),
    ]
}

fn hinge_clip(frames: usize) -> String {
    let mut text = format!("{HINGES}MOTION\nFrames: {frames}\nFrame Time: 0.0333333\n");
    for i in 0..frames {
        let cells: Vec<String> = hinge_row(i).iter().map(|x| x.to_string()).collect();
        text += &(cells.join(" ") + "\n");
    }
    text
}

#[track_caller]
fn assert_rows_eq(got: &[Vec<f64>], want: &[Vec<f64>], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: rows");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.len(), w.len(), "{what}: row {i} length");
        for (c, (a, b)) in g.iter().zip(w).enumerate() {
            assert!(
                (a - b).abs() <= 1e-9,
                "{what}: row {i} column {c}: {a} vs {b}"
            );
        }
    }
}

/// Every channel of a hinge, a two-axis joint and partial positions comes back as written:
/// through `interp` at the file's own rate (the lean path and the general one), through
/// `convert` to BVH, and through JSON keys and `convert --skeleton` — the hierarchy byte for
/// byte, each joint's own channels and nothing else.
#[test]
fn one_and_two_axis_joints_come_back_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("hinge.bvh");
    let text = hinge_clip(20);
    std::fs::write(&src, &text).unwrap();
    let want = rows(&text);
    assert_eq!(want[0].len(), 15);
    let out = dir.path().join("out.bvh");
    let s = src.as_os_str();
    for extra in [&[][..], &["--path", "euler"], &["--verbose"]] {
        let mut args = vec![os("interp"), s, os("-o"), out.as_os_str()];
        args.extend(extra.iter().map(|a| os(a)));
        ok(&args);
        let back = std::fs::read_to_string(&out).unwrap();
        assert!(back.starts_with(HINGES), "hierarchy byte for byte");
        assert_rows_eq(&rows(&back), &want, &format!("interp {extra:?}"));
    }
    ok(&[os("convert"), s, os("-o"), out.as_os_str()]);
    assert_rows_eq(
        &rows(&std::fs::read_to_string(&out).unwrap()),
        &want,
        "convert",
    );
    let keys = dir.path().join("keys.json");
    ok(&[os("convert"), s, os("-o"), keys.as_os_str()]);
    ok(&[
        os("convert"),
        keys.as_os_str(),
        os("--skeleton"),
        s,
        os("-o"),
        out.as_os_str(),
    ]);
    assert_rows_eq(
        &rows(&std::fs::read_to_string(&out).unwrap()),
        &want,
        "convert --skeleton",
    );
}

/// A hinge resampled by slerp at twice its rate turns about its own axis: each new frame is the
/// mean of its neighbours' angles (closed form), the other axes written nowhere.
#[test]
fn a_hinge_resampled_turns_about_its_axis() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("hinge.bvh");
    std::fs::write(&src, hinge_clip(9)).unwrap();
    let out = dir.path().join("out.bvh");
    ok(&[
        os("interp"),
        src.as_os_str(),
        os("--fps"),
        os("60"),
        os("--scheme"),
        os("slerp"),
        os("-o"),
        out.as_os_str(),
    ]);
    let got = rows(&std::fs::read_to_string(&out).unwrap());
    assert_eq!(got.len(), 17);
    for (k, row) in got.iter().enumerate() {
        let want = 15.0 * k as f64 / 2.0;
        assert!((row[6] - want).abs() < 1e-9, "frame {k}: knee {}", row[6]);
    }
    // Every scheme keeps the hinge on its axis: the angles BVH has no channel for are 0.
    let csv = dir.path().join("knee.csv");
    for scheme in ["slerp", "hermite", "squad", "bezier", "minaccel"] {
        ok(&[
            os("interp"),
            src.as_os_str(),
            os("--fps"),
            os("60"),
            os("--scheme"),
            os(scheme),
            os("--tracks"),
            os("Knee"),
            os("--to"),
            os("euler:XYZ"),
            os("-o"),
            csv.as_os_str(),
        ]);
        let text = std::fs::read_to_string(&csv).unwrap();
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
        let (e2, e3) = (col("e2"), col("e3"));
        for line in lines {
            let cells: Vec<&str> = line.split(',').collect();
            for c in [e2, e3] {
                let x: f64 = cells[c].parse().unwrap();
                assert!(x.abs() < 1e-12, "{scheme}: {line}");
            }
        }
    }
}

/// Three joints named `Arm` (and one `Arm#3`, the name a duplicate would get): each keeps its
/// own data in BVH output, and the tracks are named by the rule of spec §3.
#[test]
fn joints_sharing_a_name_keep_their_own_data() {
    let hierarchy = "HIERARCHY\nROOT Arm\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Zrotation Xrotation \
                     Yrotation\n  JOINT Arm\n  {\n    OFFSET 1 0 0\n    CHANNELS 3 Zrotation \
                     Xrotation Yrotation\n  }\n  JOINT Arm#3\n  {\n    OFFSET 2 0 0\n    \
                     CHANNELS 1 Yrotation\n  }\n  JOINT Arm\n  {\n    OFFSET 3 0 0\n    \
                     CHANNELS 1 Zrotation\n  }\n}\n";
    let mut text = format!("{hierarchy}MOTION\nFrames: 5\nFrame Time: 0.04\n");
    for i in 0..5 {
        let t = i as f64;
        text += &format!(
            "{} 1 2 {} -3 4 {} {}\n",
            10.0 * t,
            -20.0 * t,
            5.0 + t,
            -7.0 * t
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("arms.bvh");
    std::fs::write(&src, &text).unwrap();
    let want = rows(&text);
    let out = dir.path().join("out.bvh");
    let s = src.as_os_str();
    for extra in [&[][..], &["--path", "euler"]] {
        let mut args = vec![os("interp"), s, os("-o"), out.as_os_str()];
        args.extend(extra.iter().map(|a| os(a)));
        ok(&args);
        let back = std::fs::read_to_string(&out).unwrap();
        assert!(back.starts_with(hierarchy));
        assert_rows_eq(&rows(&back), &want, &format!("interp {extra:?}"));
    }
    let keys = dir.path().join("keys.json");
    ok(&[os("convert"), s, os("-o"), keys.as_os_str()]);
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&keys).unwrap()).unwrap();
    let names: Vec<&str> = doc["tracks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    // The second Arm is joint 1; the third, joint 3, would be Arm#3, which is taken.
    assert_eq!(names, ["Arm", "Arm#1", "Arm#3", "Arm#3#2"]);
    ok(&[
        os("convert"),
        keys.as_os_str(),
        os("--skeleton"),
        s,
        os("-o"),
        out.as_os_str(),
    ]);
    assert_rows_eq(
        &rows(&std::fs::read_to_string(&out).unwrap()),
        &want,
        "convert --skeleton",
    );
}

/// A root moving between ±1e308 (finite, so representable): resampled by every writer, the
/// positions are finite and are 1e308 times those of the same clip moving between ±1 (the
/// curves are linear in the keys); nothing overflows into an internal error.
#[test]
fn positions_near_the_largest_float_are_interpolated_without_overflow() {
    let clip = |scale: &str, neg: &str| {
        let mut text = "HIERARCHY\nROOT r\n{\n  OFFSET 0 0 0\n  CHANNELS 4 Xposition \
                        Yposition Zposition Zrotation\n}\nMOTION\nFrames: 4\nFrame Time: 0.1\n"
            .to_string();
        for i in 0..4 {
            let (a, b) = if i % 2 == 0 {
                (scale, neg)
            } else {
                (neg, scale)
            };
            text += &format!("{a} {b} 0 {}\n", 10 * i);
        }
        text
    };
    let dir = tempfile::tempdir().unwrap();
    let (big, unit) = (dir.path().join("big.bvh"), dir.path().join("unit.bvh"));
    std::fs::write(&big, clip("1e308", "-1e308")).unwrap();
    std::fs::write(&unit, clip("1", "-1")).unwrap();
    for scheme in ["slerp", "hermite", "squad"] {
        let out = |name: &str, input: &Path, ext: &str, extra: &[&str]| {
            let path = dir.path().join(format!("{name}-out.{ext}"));
            let mut args = vec![
                os("interp"),
                input.as_os_str(),
                os("--fps"),
                os("50"),
                os("--scheme"),
                os(scheme),
                os("-o"),
                path.as_os_str(),
            ];
            args.extend(extra.iter().map(|a| os(a)));
            let (code, stderr) = run(&args);
            assert_eq!(code, Some(0), "{scheme} {ext} {extra:?}: {stderr}");
            std::fs::read_to_string(path).unwrap()
        };
        // BVH (lean path and general path), CSV, JSON.
        for extra in [&[][..], &["--path", "euler"]] {
            let got = rows(&out("big", &big, "bvh", extra));
            let want = rows(&out("unit", &unit, "bvh", extra));
            assert_eq!(got.len(), 16);
            for (g, w) in got.iter().zip(&want) {
                for c in 0..3 {
                    assert!(g[c].is_finite());
                    assert!(
                        (g[c] - w[c] * 1e308).abs() <= 1e-9 * 1e308,
                        "{scheme}: {} vs {}e308",
                        g[c],
                        w[c]
                    );
                }
            }
        }
        for ext in ["csv", "json"] {
            let got = out("big", &big, ext, &["--path", "euler"]);
            assert!(
                !got.contains("inf") && !got.contains("NaN"),
                "{scheme} {ext}"
            );
            assert!(
                got.contains("e307") || got.contains("e+307"),
                "{scheme} {ext}"
            );
        }
    }
}

/// Angles beyond ±1e9° are reduced exactly modulo 360° (as CSV and JSON degrees are): the f64
/// read from `1e200`, an integer, is 128° (Python: `int(1e200) % 360`), its negative −128°, and
/// 360000000010° is 10°.
/// Written back, each row is its own rotation, continued from the previous (128, 232, 370),
/// where the radians of 1e200 left no room to tell one row from the next.
#[test]
fn angles_beyond_a_billion_degrees_are_reduced_exactly() {
    let text = "HIERARCHY\nROOT r\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Zrotation Xrotation \
                Yrotation\n}\nMOTION\nFrames: 3\nFrame Time: 0.1\n1e200 0 0\n-1e200 0 0\n\
                360000000010 0 0\n";
    let dir = tempfile::tempdir().unwrap();
    let (src, out) = (dir.path().join("spin.bvh"), dir.path().join("out.bvh"));
    std::fs::write(&src, text).unwrap();
    ok(&[os("convert"), src.as_os_str(), os("-o"), out.as_os_str()]);
    let got = rows(&std::fs::read_to_string(&out).unwrap());
    let z: Vec<f64> = got.iter().map(|r| r[0]).collect();
    for (g, w) in z.iter().zip([128.0, 232.0, 370.0]) {
        assert!((g - w).abs() < 1e-9, "{z:?}");
    }
    assert!(
        got.iter().all(|r| r[1].abs() < 1e-9 && r[2].abs() < 1e-9),
        "{got:?}"
    );
}
