//! The lean BVH path of `interp` (a BVH file read in pieces, one joint at a time): the same
//! bytes and warnings as the general path (standard input takes the general path), the same
//! errors with nothing written, and numbers written as the source wrote them.

use std::path::Path;

const HIERARCHY: &str = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 35 0\n  CHANNELS 6 Xposition \
Yposition Zposition Zrotation Xrotation Yrotation\n  JOINT Chest\n  {\n    OFFSET 0 5 0\n    \
CHANNELS 3 Zrotation Yrotation Xrotation\n    JOINT Neck\n    {\n      OFFSET 0 5 0\n      \
CHANNELS 0\n      End Site\n      {\n        OFFSET 0 2 0\n      }\n    }\n  }\n  JOINT Leg\n  \
{\n    OFFSET 5 0 0\n    CHANNELS 3 Yrotation Xrotation Zrotation\n    End Site\n    {\n      \
OFFSET 10 0 0\n    }\n  }\n}\n";

/// A smooth clip of `frames` rows at 120 fps (`Frame Time: 0.008333`), every number written
/// with 6 decimals, the middle angles away from ±90°, nothing wrapped at ±180°.
pub(super) fn clip(frames: usize) -> String {
    let mut text = format!("{HIERARCHY}MOTION\nFrames: {frames}\nFrame Time: 0.008333\n");
    for i in 0..frames {
        let t = i as f64 / 120.0;
        let row = [
            10.0 * t,
            35.0 + (3.0 * t).sin(),
            -4.0 * t,
            170.0 * (0.7 * t).sin(),
            60.0 * (2.0 * t).sin(),
            -50.0 * (1.1 * t).cos(),
            40.0 * (1.5 * t).cos(),
            55.0 * (0.9 * t).sin(),
            -120.0 * (0.5 * t).sin(),
            10.0,
            -0.5 + 30.0 * (2.5 * t).sin(),
            150.0 * (0.3 * t).cos(),
        ];
        let cells: Vec<String> = row.iter().map(|x| format!("{x:.6}")).collect();
        text += &(cells.join(" ") + "\n");
    }
    text
}

/// What a run gave: exit status, standard error (the input's name as `SRC`), the `-o` file.
pub(super) type Run = (Option<i32>, String, Option<Vec<u8>>);

/// Runs `interp` on a file (the lean path) and on standard input (the general path) with the
/// same arguments; returns (status, stderr, output bytes) of each.
fn both(text: &str, args: &[&str], out_name: &str) -> [Run; 2] {
    both_of("interp", text, args, out_name)
}

/// [`both`] for the subcommand `command` (`interp`, `reduce`).
pub(super) fn both_of(command: &str, text: &str, args: &[&str], out_name: &str) -> [Run; 2] {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("clip.bvh");
    std::fs::write(&src, text).unwrap();
    let run = |lean: bool| {
        let out = dir.path().join(format!(
            "{}{out_name}",
            if lean { "lean" } else { "general" }
        ));
        let mut cmd = crate::support::bin();
        cmd.arg(command);
        if lean {
            cmd.arg(&src);
        } else {
            cmd.args(["-", "--input-format", "bvh"]).write_stdin(text);
        }
        let o = cmd.args(args).arg("-o").arg(&out).output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr).replace("<stdin>", "SRC");
        let stderr = stderr.replace(&src.display().to_string(), "SRC");
        (o.status.code(), stderr, std::fs::read(&out).ok())
    };
    [run(true), run(false)]
}

#[test]
fn the_lean_path_writes_what_the_general_path_writes() {
    let text = clip(400).replace("Frames: 400", "Frames: 401");
    for (args, name) in [
        (&["--fps", "60"][..], "out.bvh"),
        (&["--fps", "59.94", "--scheme", "hermite"], "out.bvh"),
        (&["--fps", "100", "--scheme", "minaccel"], "out.bvh"),
        (&["--scheme", "squad"], "out.bvh"),
        (&["--fps", "24"], "out.csv"),
        (&["--fps", "30", "--scheme", "slerp"], "out.json"),
    ] {
        let [lean, general] = both(&text, args, name);
        assert_eq!(lean.0, Some(0), "{args:?}: {}", lean.1);
        assert_eq!(lean, general, "{args:?}");
        // The Frames mismatch is warned once.
        assert_eq!(lean.1.matches("\"Frames: 401\"").count(), 1, "{}", lean.1);
    }
}

/// Issue 48: npy and npz output, `--tracks`, `--velocity` and `--euler wrapped` take the lean
/// path too (a few tracks must never cost more memory than all of them), with the general
/// path's bytes: the npz arrays (frame-major, filled one joint at a time) and its tree of the
/// chosen tracks (`parents.npy`: Leg's parent is Hips, the nearest chosen ancestor).
#[test]
fn arrays_and_chosen_tracks_are_the_general_paths() {
    let text = clip(300);
    for (args, name) in [
        (&[][..], "out.npz"),
        (
            &["--fps", "50", "--velocity", "--to", "euler:ZYX"],
            "out.npz",
        ),
        (&["--tracks", "Leg,Hips", "--scheme", "slerp"], "out.npz"),
        (
            &["--tracks", "Leg", "--to", "matrix", "--angles", "rad"],
            "out.npz",
        ),
        (&["--tracks", "Ch*", "--velocity"], "out.npy"),
        (&["--fps", "30"], "out.npy"),
        (&["--tracks", "Leg,Hips", "--velocity"], "out.csv"),
        (&["--to", "euler:XYZ", "--euler", "wrapped"], "out.json"),
        (
            &["--tracks", "Chest", "--fps", "24", "--scheme", "minaccel"],
            "out.json",
        ),
    ] {
        let [lean, general] = both(&text, args, name);
        assert_eq!(lean.0, Some(0), "{args:?}: {}", lean.1);
        assert!(lean.2.as_ref().is_some_and(|b| !b.is_empty()), "{args:?}");
        assert_eq!(lean, general, "{args:?}");
    }
    // The tree of the chosen tracks: Hips (-1) and Leg (0), in file order.
    let [lean, _] = both(&text, &["--tracks", "Leg,Hips"], "out.npz");
    let bytes = lean.2.unwrap();
    let at = bytes
        .windows(11)
        .position(|w| w == b"parents.npy")
        .expect("parents.npy");
    let data = &bytes[at + 11 + 128..at + 11 + 128 + 16];
    let parents: Vec<i64> = data
        .chunks(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(parents, [-1, 0]);
}

/// `--tracks` errors are the general path's, with nothing written; BVH output refuses it.
#[test]
fn track_choice_errors_are_the_general_paths() {
    let text = clip(20);
    for (args, name, want) in [
        (
            &["--tracks", "Arm"][..],
            "out.npz",
            "\"Arm\" matches no track of SRC",
        ),
        (
            &["--tracks", " , "],
            "out.csv",
            "--tracks: expected at least one name",
        ),
        (&["--tracks", "Leg"], "out.bvh", "--tracks:"),
        (&["--velocity"], "out.bvh", "--velocity:"),
    ] {
        let [lean, general] = both(&text, args, name);
        assert_eq!(lean.0, Some(2), "{args:?}: {}", lean.1);
        assert!(lean.1.contains(want), "{args:?}: {}", lean.1);
        assert_eq!(lean.2, None, "nothing written");
        assert_eq!(lean, general, "{args:?}");
    }
}

#[test]
fn errors_are_the_general_paths_and_nothing_is_written() {
    let good = clip(50);
    let short = {
        let mut lines: Vec<&str> = good.lines().collect();
        let last = lines.len() - 1;
        let cut = lines[last].rsplit_once(' ').unwrap().0;
        lines[last] = cut;
        lines.join("\n")
    };
    let cases = [
        (
            good.replace("0.000000 35.000000", "0.000000 nan"),
            "value 2",
        ),
        (short, "expected 12 values (one per channel), found 11"),
        (
            good.replace("Frame Time: 0.008333", "Frame Time: 0"),
            "positive frame time",
        ),
        (good.replace("JOINT Leg", "JOINT"), "expected a joint name"),
        (
            good.replace("MOTION", "MOTON"),
            "expected \"ROOT\" or \"MOTION\"",
        ),
    ];
    for (text, want) in cases {
        if text == good {
            panic!("case did not change the clip: {want}");
        }
        for name in ["out.bvh", "out.csv"] {
            let [lean, general] = both(&text, &["--fps", "60"], name);
            assert_eq!(lean.0, Some(2), "{want}: {}", lean.1);
            assert!(lean.1.contains(want), "{want}: {}", lean.1);
            assert!(lean.1.contains("SRC:"), "{}", lean.1);
            assert_eq!(lean.2, None, "nothing written");
            assert_eq!(lean, general);
        }
    }
}

/// The numbers of a BVH text's rows.
fn rows(text: &str) -> Vec<Vec<String>> {
    let body = text.split_once("Frame Time:").unwrap().1;
    body.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_ascii_whitespace().map(String::from).collect())
        .collect()
}

fn own_rate(path: &Path, out: &Path) -> String {
    let o = crate::support::bin()
        .arg("interp")
        .arg(path)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(out).unwrap()
}

#[test]
fn at_its_own_rate_a_clip_comes_back_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let (src, out) = (dir.path().join("clip.bvh"), dir.path().join("out.bvh"));
    let text = clip(600);
    std::fs::write(&src, &text).unwrap();
    let back = own_rate(&src, &out);
    assert!(back.starts_with(HIERARCHY));
    let (want, got) = (rows(&text), rows(&back));
    assert_eq!(got.len(), want.len());
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        for (c, (g, w)) in g.iter().zip(w).enumerate() {
            // The source's number, in its shortest form: `10` for `10.000000`, no noise digits.
            let x: f64 = w.parse().unwrap();
            assert_eq!(
                g.parse::<f64>().unwrap(),
                x + 0.0,
                "frame {i}, column {c}: {w} {g}"
            );
        }
    }
    // The fixture: every number as written (in its shortest form), except angles the source
    // wrapped at ±180°, which may come back unwrapped (the same angle, ±360°).
    let fixture = crate::support::fixtures().join("bvh/mixed_orders.bvh");
    let text = std::fs::read_to_string(&fixture).unwrap();
    let back = own_rate(&fixture, &out);
    for (g, w) in rows(&back).iter().zip(rows(&text)) {
        for (g, w) in g.iter().zip(w) {
            let (x, y): (f64, f64) = (w.parse().unwrap(), g.parse().unwrap());
            let turns = (y - x) / 360.0;
            if w.split_once('.').is_none_or(|(_, d)| d.len() <= 6) {
                let unwrapped = turns.round() != 0.0 && (turns - turns.round()).abs() < 1e-12;
                assert!(y == x + 0.0 || unwrapped, "source {w}, written {g}");
            }
        }
    }
}
