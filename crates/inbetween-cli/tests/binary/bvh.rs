//! BVH in and out (issue 14): a clip resampled at its own rate comes back with the hierarchy
//! byte for byte and every rotation and position; resampling 120 → 100 and 30 → 24 fps keeps the
//! duration (⌊duration·fps⌋ + 1 frames) and reproduces the frames both grids share; the output
//! is read back by an independent BVH reader (bvhio, `fixtures/bvh/read_bvh.py`).

use crate::support::rot_angle;
use glam::{DQuat, EulerRot};
use inbetween_io::bvh;

const HIERARCHY: &str = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 35 0\n  CHANNELS 6 Xposition \
Yposition Zposition Zrotation Xrotation Yrotation\n  JOINT Arm\n  {\n    OFFSET 5 0 0\n    \
CHANNELS 3 Yrotation Xrotation Zrotation\n    End Site\n    {\n      OFFSET 10 0 0\n    }\n  \
}\n}\n";

/// A smooth clip of `frames` rows at `frame_time` (as written), spinning past ±180°.
fn clip(frames: usize, rate: f64, frame_time: &str) -> String {
    let mut text = format!("{HIERARCHY}MOTION\nFrames: {frames}\nFrame Time: {frame_time}\n");
    for i in 0..frames {
        let t = i as f64 / rate;
        let row = [
            10.0 * t,
            35.0 + (3.0 * t).sin(),
            -4.0 * t * t,
            200.0 * t,
            30.0 * (2.0 * t).sin(),
            -50.0 * t,
            40.0 * (1.5 * t).cos(),
            80.0 * t,
            -20.0 * t,
        ];
        let cells: Vec<String> = row.iter().map(|x| format!("{x:.6}")).collect();
        text += &(cells.join(" ") + "\n");
    }
    text
}

/// (Hips rotation, Arm rotation, Hips position) of every frame, from our own parser.
fn poses(text: &str) -> (bvh::Clip, Vec<(DQuat, DQuat, [f64; 3])>) {
    let (clip, _) = bvh::parse(text, "x.bvh").unwrap();
    let rows = clip
        .rows()
        .map(|r| {
            let d = |x: f64| x.to_radians();
            let hips = DQuat::from_euler(EulerRot::ZXY, d(r[3]), d(r[4]), d(r[5]));
            let arm = DQuat::from_euler(EulerRot::YXZ, d(r[6]), d(r[7]), d(r[8]));
            (hips, arm, [r[0], r[1], r[2]])
        })
        .collect();
    (clip, rows)
}

fn interp(input: &std::path::Path, fps: Option<&str>, out: &std::path::Path) -> String {
    let mut cmd = crate::support::bin();
    cmd.arg("interp").arg(input).arg("-o").arg(out);
    if let Some(f) = fps {
        cmd.args(["--fps", f]);
    }
    let o = cmd.output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(out).unwrap()
}

#[test]
fn a_clip_at_its_own_rate_comes_back() {
    let dir = tempfile::tempdir().unwrap();
    let (src, out) = (dir.path().join("clip.bvh"), dir.path().join("out.bvh"));
    let text = clip(31, 30.0, "0.0333333");
    std::fs::write(&src, &text).unwrap();
    let back = interp(&src, None, &out);
    assert!(back.starts_with(HIERARCHY), "hierarchy byte for byte");
    assert!(back.contains("MOTION\nFrames: 31\nFrame Time: 0.0333333333\n"));
    let ((_, want), (_, got)) = (poses(&text), poses(&back));
    assert_eq!(got.len(), want.len());
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        assert!(rot_angle(g.0, w.0) < 1e-12, "frame {i} hips");
        assert!(rot_angle(g.1, w.1) < 1e-12, "frame {i} arm");
        assert_eq!(g.2, w.2, "frame {i} position");
    }
    // Continuous angles: the root's Z channel goes on past 180° as written.
    let last: Vec<f64> = back
        .lines()
        .last()
        .unwrap()
        .split(' ')
        .map(|x| x.parse().unwrap())
        .collect();
    assert!((last[3] - 200.0).abs() < 1e-9, "{last:?}");
}

#[test]
fn resampling_keeps_the_duration_and_the_shared_frames() {
    let dir = tempfile::tempdir().unwrap();
    for (frames, rate, time, fps, want_frames, every) in [
        (121, 120.0, "0.008333", "100", 101, (6, 5)),
        (31, 30.0, "0.0333333", "24", 25, (5, 4)),
    ] {
        let (src, out) = (dir.path().join("c.bvh"), dir.path().join("o.bvh"));
        let text = clip(frames, rate, time);
        std::fs::write(&src, &text).unwrap();
        let back = interp(&src, Some(fps), &out);
        let ((_, want), (clip_out, got)) = (poses(&text), poses(&back));
        assert_eq!(got.len(), want_frames, "{rate} → {fps}");
        assert_eq!(clip_out.fps().to_string(), fps);
        // Frames at times both grids share are the input's own.
        let (a, b) = every;
        for j in 0..(want.len() - 1) / a + 1 {
            let (w, g) = (&want[j * a], &got[j * b]);
            assert!(
                rot_angle(w.0, g.0) < 1e-12 && rot_angle(w.1, g.1) < 1e-12,
                "{fps}: {j}"
            );
            for k in 0..3 {
                assert!((w.2[k] - g.2[k]).abs() < 1e-12);
            }
        }
    }
}

/// A BVH file as bvhio (an independent library, `fixtures/bvh/read_bvh.py`) reads it.
struct Bvhio {
    frame_count: u64,
    frame_time: f64,
    /// Each joint's rotation order, e.g. `ZXY`.
    orders: Vec<String>,
    /// Per frame, per joint (float32 in bvhio).
    rotations: Vec<Vec<DQuat>>,
}

/// `path` as bvhio reads it, where the checkers' venv exists (CI builds it; set
/// INBETWEEN_REQUIRE_PYTHON_CHECKS to fail instead of skipping).
fn bvhio(path: &std::path::Path) -> Option<Bvhio> {
    let python = crate::support::checker_python("bvhio check")?;
    let doc = crate::support::python_json(&python, "fixtures/bvh/read_bvh.py", &[path.as_os_str()]);
    let quat = |r: &serde_json::Value| {
        let r: Vec<f64> = r
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        DQuat::from_xyzw(r[1], r[2], r[3], r[0]).normalize()
    };
    Some(Bvhio {
        frame_count: doc["frame_count"].as_u64().unwrap(),
        frame_time: doc["frame_time"].as_f64().unwrap(),
        orders: doc["joints"]
            .as_array()
            .unwrap()
            .iter()
            .map(|j| j["rotation_order"].as_str().unwrap().to_string())
            .collect(),
        rotations: doc["frames"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| {
                f.as_array()
                    .unwrap()
                    .iter()
                    .map(|j| quat(&j["rotation"]))
                    .collect()
            })
            .collect(),
    })
}

/// The output as bvhio reads it: channel orders, frame count and time, rotations.
#[test]
fn an_independent_reader_agrees() {
    let dir = tempfile::tempdir().unwrap();
    let (src, out) = (dir.path().join("c.bvh"), dir.path().join("o.bvh"));
    let text = clip(31, 30.0, "0.0333333");
    std::fs::write(&src, &text).unwrap();
    interp(&src, Some("24"), &out);
    let Some(theirs) = bvhio(&out) else {
        return;
    };
    assert_eq!(theirs.frame_count, 25);
    assert!((theirs.frame_time - 1.0 / 24.0).abs() < 1e-9);
    assert_eq!(theirs.orders, ["ZXY", "YXZ"]);
    let (_, ours) = poses(&std::fs::read_to_string(&out).unwrap());
    assert_eq!(theirs.rotations.len(), ours.len());
    for (i, frame) in theirs.rotations.iter().enumerate() {
        for (j, q) in [ours[i].0, ours[i].1].iter().enumerate() {
            // bvhio works in float32.
            assert!(rot_angle(frame[j], *q) < 1e-5, "frame {i} joint {j}");
        }
    }
}

/// `src` → `convert` → JSON keys → `convert keys.json --skeleton src` → BVH, in `dir`: the BVH
/// text that comes back.
fn through_keys(src: &std::path::Path, dir: &std::path::Path) -> String {
    through_keys_as(src, dir, "json").0
}

/// [`through_keys`] with the keys as `ext` (`json` or `csv`): the BVH text that comes back, and
/// what the first `convert` printed on stderr.
fn through_keys_as(src: &std::path::Path, dir: &std::path::Path, ext: &str) -> (String, String) {
    let (keys, out) = (dir.join(format!("keys.{ext}")), dir.join("back.bvh"));
    let mut stderr = String::new();
    let mut run = |args: &[&std::ffi::OsStr]| {
        let o = crate::support::bin().args(args).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        if stderr.is_empty() {
            stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        }
    };
    run(&[
        "convert".as_ref(),
        src.as_os_str(),
        "-o".as_ref(),
        keys.as_os_str(),
    ]);
    run(&[
        "convert".as_ref(),
        keys.as_os_str(),
        "--skeleton".as_ref(),
        src.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    (std::fs::read_to_string(&out).unwrap(), stderr)
}

/// BVH → `convert` → JSON keys → `convert --skeleton` → BVH gives back every rotation and
/// position of the file, on its hierarchy byte for byte; keys that are not one grid are refused.
#[test]
fn keys_go_back_onto_the_skeleton() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("clip.bvh");
    let text = clip(31, 30.0, "0.0333333");
    std::fs::write(&src, &text).unwrap();
    let back = through_keys(&src, dir.path());
    assert!(back.starts_with(HIERARCHY));
    let ((_, want), (_, got)) = (poses(&text), poses(&back));
    assert_eq!(got.len(), want.len());
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        assert!(
            rot_angle(g.0, w.0) < 1e-12 && rot_angle(g.1, w.1) < 1e-12,
            "frame {i}"
        );
        assert_eq!(g.2, w.2, "frame {i}");
    }
    // Keys at uneven times are not one grid.
    let o = crate::support::bin()
        .args(["convert", "-", "--input-format", "csv", "--skeleton"])
        .arg(&src)
        .arg("-o")
        .arg(dir.path().join("x.bvh"))
        .write_stdin("track,time,w,x,y,z\nHips,0,1,0,0,0\nHips,0.5,1,0,0,0\n")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr)
            .contains("--skeleton writes keys that are frames of one grid"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

// ---- a real clip: CMU subject 1, trial 1 (fixtures/bvh/cmu_01_01.bvh, 61 frames at 120 fps) ----

/// A BVH file as this test reads it, independently of `inbetween_io::bvh`: the text before
/// `MOTION`, each joint's channel names, `Frame Time` as written, and the rows.
struct Plain {
    hierarchy: String,
    joints: Vec<(String, Vec<String>)>,
    frame_time: String,
    rows: Vec<Vec<f64>>,
}

fn plain(text: &str) -> Plain {
    let (hierarchy, motion) = text.split_at(text.find("MOTION").unwrap());
    let mut joints = Vec::new();
    let mut name = String::new();
    for line in hierarchy.lines().map(str::trim) {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.first() {
            Some(&"ROOT") | Some(&"JOINT") => name = words[1].to_string(),
            Some(&"CHANNELS") => joints.push((
                name.clone(),
                words[2..].iter().map(|w| w.to_string()).collect(),
            )),
            _ => {}
        }
    }
    let mut lines = motion.lines().skip(1);
    let mut value = || {
        lines
            .next()
            .unwrap()
            .split_once(':')
            .unwrap()
            .1
            .trim()
            .to_string()
    };
    let frames: usize = value().parse().unwrap();
    let frame_time = value();
    let rows: Vec<Vec<f64>> = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), frames);
    Plain {
        hierarchy: hierarchy.to_string(),
        joints,
        frame_time,
        rows,
    }
}

impl Plain {
    /// Per frame, per joint: the rotation (intrinsic, in the listed order, degrees) and the
    /// position channels' values.
    fn poses(&self) -> Vec<Vec<(DQuat, Vec<f64>)>> {
        self.rows
            .iter()
            .map(|row| {
                let mut at = 0;
                self.joints
                    .iter()
                    .map(|(_, channels)| {
                        let (mut order, mut angles, mut position) =
                            (String::new(), Vec::new(), Vec::new());
                        for c in channels {
                            if c.ends_with("rotation") {
                                order.push_str(&c[..1]);
                                angles.push(row[at].to_radians());
                            } else {
                                position.push(row[at]);
                            }
                            at += 1;
                        }
                        let seq = match order.as_str() {
                            "ZYX" => EulerRot::ZYX,
                            "ZXY" => EulerRot::ZXY,
                            "YXZ" => EulerRot::YXZ,
                            "YZX" => EulerRot::YZX,
                            "XYZ" => EulerRot::XYZ,
                            "XZY" => EulerRot::XZY,
                            o => panic!("order {o}"),
                        };
                        (
                            DQuat::from_euler(seq, angles[0], angles[1], angles[2]),
                            position,
                        )
                    })
                    .collect()
            })
            .collect()
    }
}

fn cmu() -> (std::path::PathBuf, String) {
    let path = crate::support::fixtures().join("bvh/cmu_01_01.bvh");
    let text = std::fs::read_to_string(&path).unwrap();
    (path, text)
}

/// Frame `i` of `a` and frame `j` of `b` are the same pose: rotations to `tol` rad, positions
/// to 1e-9.
#[track_caller]
fn same_pose(a: &[(DQuat, Vec<f64>)], b: &[(DQuat, Vec<f64>)], tol: f64, what: &str) {
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        let d = rot_angle(x.0, y.0);
        assert!(d < tol, "{what}: joint {k}: {d:e} rad");
        for (p, q) in x.1.iter().zip(&y.1) {
            assert!(
                (p - q).abs() < 1e-9,
                "{what}: joint {k}: position {p} vs {q}"
            );
        }
    }
}

#[test]
fn a_real_clip_at_its_own_rate_comes_back() {
    let dir = tempfile::tempdir().unwrap();
    let (src, text) = cmu();
    let back = interp(&src, None, &dir.path().join("o.bvh"));
    let (a, b) = (plain(&text), plain(&back));
    assert_eq!(b.hierarchy, a.hierarchy, "hierarchy byte for byte");
    assert_eq!(b.rows.len(), 61);
    let (want, got) = (a.poses(), b.poses());
    for (i, (w, g)) in want.iter().zip(&got).enumerate() {
        same_pose(w, g, 1e-8, &format!("frame {i}"));
    }
}

/// 120 → 100 fps, and the same motion at 30 fps (every fourth row) → 24 fps: ⌊duration·fps⌋ + 1
/// frames, the exact Frame Time, and the frames both grids share are the input's own.
#[test]
fn a_real_clip_resampled_keeps_its_duration_and_shared_frames() {
    let dir = tempfile::tempdir().unwrap();
    let (_, text) = cmu();
    let a = plain(&text);
    let head = text.split("Frames:").next().unwrap();
    let mut at30 = format!("{head}Frames: 16\nFrame Time: .0333333\n");
    for line in text
        .lines()
        .skip_while(|l| !l.starts_with("Frame Time"))
        .skip(1)
        .step_by(4)
    {
        at30 += line;
        at30.push('\n');
    }
    let src30 = dir.path().join("cmu30.bvh");
    std::fs::write(&src30, &at30).unwrap();
    for (src, input, fps, frames, time, (every_in, every_out)) in [
        (cmu().0, a.poses(), "100", 51, "0.01", (6, 5)),
        (
            src30.clone(),
            plain(&at30).poses(),
            "24",
            13,
            "0.0416666667",
            (5, 4),
        ),
    ] {
        let back = plain(&interp(
            &src,
            Some(fps),
            &dir.path().join(format!("o{fps}.bvh")),
        ));
        assert_eq!(back.hierarchy, a.hierarchy);
        assert_eq!(back.rows.len(), frames, "{fps} fps");
        assert_eq!(back.frame_time, time);
        let got = back.poses();
        for j in 0..(input.len() - 1) / every_in + 1 {
            same_pose(
                &input[j * every_in],
                &got[j * every_out],
                1e-8,
                &format!("{fps} fps, shared frame {j}"),
            );
        }
    }
}

/// bvhio reads our 100 fps resample of the real clip: frame count and time, every joint's
/// channel order, and the rotations (float32 in bvhio).
#[test]
fn an_independent_reader_agrees_on_a_real_clip() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.bvh");
    let ours = plain(&interp(&cmu().0, Some("100"), &out)).poses();
    let Some(theirs) = bvhio(&out) else {
        return;
    };
    assert_eq!(theirs.frame_count, 51);
    assert!((theirs.frame_time - 0.01).abs() < 1e-12);
    let want: Vec<String> = plain(&cmu().1)
        .joints
        .iter()
        .map(|(_, c)| {
            c.iter()
                .filter(|c| c.ends_with("rotation"))
                .map(|c| &c[..1])
                .collect()
        })
        .collect();
    assert_eq!(theirs.orders, want);
    assert_eq!(theirs.rotations.len(), 51);
    for (i, (frame, pose)) in theirs.rotations.iter().zip(&ours).enumerate() {
        assert_eq!(frame.len(), want.len());
        for (j, (q, p)) in frame.iter().zip(pose).enumerate() {
            assert!(rot_angle(*q, p.0) < 1e-5, "frame {i} joint {j}");
        }
    }
}

/// BVH → `convert` → JSON → `convert --skeleton` → BVH on the real clip: every rotation and
/// position back, on the hierarchy byte for byte.
#[test]
fn a_real_clip_goes_through_keys_and_back() {
    let dir = tempfile::tempdir().unwrap();
    let (src, text) = cmu();
    let (a, b) = (plain(&text), plain(&through_keys(&src, dir.path())));
    assert_eq!(b.hierarchy, a.hierarchy);
    let (want, got) = (a.poses(), b.poses());
    assert_eq!(got.len(), 61);
    for (i, (w, g)) in want.iter().zip(&got).enumerate() {
        same_pose(w, g, 1e-8, &format!("frame {i}"));
    }
}

/// BVH → CSV keys → `convert --skeleton` → BVH keeps the clip's rate: CSV has no place for it, so
/// the first step warns and says how to read it back, and the skeleton's own Frame Time is the
/// keys' rate (1/120 s, where the default 30 fps made a clip 4× slow); every pose comes back.
#[test]
fn a_real_clip_through_csv_keys_keeps_its_rate() {
    let dir = tempfile::tempdir().unwrap();
    let (src, text) = cmu();
    let (back, stderr) = through_keys_as(&src, dir.path(), "csv");
    assert!(
        stderr.contains(
            "CSV has no place for the rate: the frame numbers are written as they are, at 120 \
             fps; read them back with --key-fps 120 (or --skeleton with the BVH file"
        ),
        "{stderr}"
    );
    let (a, b) = (plain(&text), plain(&back));
    let rate = |p: &Plain| 1.0 / p.frame_time.parse::<f64>().unwrap();
    assert!((rate(&a) - 120.0).abs() < 1e-2 && (rate(&b) - 120.0).abs() < 1e-7);
    let (want, got) = (a.poses(), b.poses());
    assert_eq!(got.len(), 61);
    for (i, (w, g)) in want.iter().zip(&got).enumerate() {
        same_pose(w, g, 1e-8, &format!("frame {i}"));
    }
}

/// `reduce` → JSON keys → `interp keys.json --skeleton clip.bvh` → BVH: the clip back at its own
/// rate (the keys' declared fps), every joint's rotation within the tolerance (0.5°) and every
/// position within the translation tolerance (0.01) of the original at every frame, read by
/// this test's own reader; keys that miss a joint are refused naming it.
#[test]
fn reduced_keys_go_back_onto_the_skeleton_through_interp() {
    let dir = tempfile::tempdir().unwrap();
    let (src, text) = cmu();
    let (keys, out) = (dir.path().join("keys.json"), dir.path().join("back.bvh"));
    let run =
        |args: &[&std::ffi::OsStr]| crate::support::stdout_of(crate::support::bin().args(args));
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    run(&[
        os("reduce"),
        src.as_os_str(),
        os("--tolerance"),
        os("0.5"),
        os("--translation-tolerance"),
        os("0.01"),
        os("-o"),
        keys.as_os_str(),
    ]);
    run(&[
        os("interp"),
        keys.as_os_str(),
        os("--skeleton"),
        src.as_os_str(),
        os("-o"),
        out.as_os_str(),
    ]);
    let (a, b) = (plain(&text), plain(&std::fs::read_to_string(&out).unwrap()));
    assert_eq!(b.hierarchy, a.hierarchy);
    let rate = |p: &Plain| 1.0 / p.frame_time.parse::<f64>().unwrap();
    assert!((rate(&b) - 120.0).abs() < 1e-7, "{}", b.frame_time);
    let (want, got) = (a.poses(), b.poses());
    assert_eq!(got.len(), want.len());
    let tol = 0.5f64.to_radians() * (1.0 + 1e-9);
    for (i, (w, g)) in want.iter().zip(&got).enumerate() {
        for (k, (x, y)) in w.iter().zip(g).enumerate() {
            let d = rot_angle(x.0, y.0);
            assert!(d <= tol, "frame {i} joint {k}: {} deg", d.to_degrees());
            for (p, q) in x.1.iter().zip(&y.1) {
                assert!(
                    (p - q).abs() <= 0.01 + 1e-9,
                    "frame {i} joint {k}: {p} vs {q}"
                );
            }
        }
    }
    // A document whose tracks are not the skeleton's joints is refused, naming the first joint.
    let o = crate::support::bin()
        .args(["interp", "-", "--skeleton"])
        .arg(&src)
        .write_stdin(
            r#"{"keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "quat": [1, 0, 0, 0]}]}"#,
        )
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("<stdin>: no track for joint \"Hips\""),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(o.stdout.is_empty());
}

/// BVH output with `--euler wrapped` writes each triple in scipy's ranges, so a clip whose
/// angles wrap at ±180° comes back as written at its own rate; the default (continuous) writes
/// the same rotations without the jump (−170° as 190°).
#[test]
fn wrapped_euler_output_keeps_a_wrapping_clip_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("spin.bvh");
    std::fs::write(
        &src,
        "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n\
         End Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 3\nFrame Time: 0.1\n\
         150 10 20\n170 10 20\n-170 10 20\n",
    )
    .unwrap();
    let motion = |euler: &str| {
        let out = dir.path().join(format!("{euler}.bvh"));
        crate::support::stdout_of(crate::support::bin().args([
            "interp".as_ref(),
            src.as_os_str(),
            "--euler".as_ref(),
            euler.as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ]));
        let text = std::fs::read_to_string(&out).unwrap();
        let rows: Vec<Vec<f64>> = text
            .split("Frame Time:")
            .nth(1)
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .collect();
        rows
    };
    let near = |a: &[Vec<f64>], b: &[[f64; 3]]| {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .all(|(r, w)| r.iter().zip(w).all(|(x, y)| (x - y).abs() < 1e-9))
    };
    let wrapped = motion("wrapped");
    assert!(
        near(
            &wrapped,
            &[
                [150.0, 10.0, 20.0],
                [170.0, 10.0, 20.0],
                [-170.0, 10.0, 20.0]
            ]
        ),
        "{wrapped:?}"
    );
    let continuous = motion("continuous");
    assert!(
        near(
            &continuous,
            &[
                [150.0, 10.0, 20.0],
                [170.0, 10.0, 20.0],
                [190.0, 10.0, 20.0]
            ]
        ),
        "{continuous:?}"
    );
}

/// A BVH file with CRLF line ends comes back with CRLF throughout (the hierarchy is kept as
/// written, so the motion follows it) and otherwise the bytes of the LF file's output; one whose
/// lines end in CR alone is refused with a message that says so, nothing written.
#[test]
fn line_ends_are_kept_and_cr_alone_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let (src, text) = cmu();
    let crlf = dir.path().join("crlf.bvh");
    std::fs::write(&crlf, text.replace('\n', "\r\n")).unwrap();
    let back = |input: &std::path::Path, name: &str| {
        let out = dir.path().join(name);
        crate::support::stdout_of(crate::support::bin().args([
            "interp".as_ref(),
            input.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ]));
        std::fs::read(&out).unwrap()
    };
    let (lf_out, crlf_out) = (back(&src, "lf.bvh"), back(&crlf, "crlf_out.bvh"));
    let lines = |b: &[u8]| b.iter().filter(|&&c| c == b'\n').count();
    let crlfs = crlf_out.windows(2).filter(|w| w == b"\r\n").count();
    assert_eq!(
        crlfs,
        lines(&crlf_out),
        "every line of the output ends in CRLF"
    );
    assert_eq!(
        String::from_utf8(crlf_out)
            .unwrap()
            .replace("\r\n", "\n")
            .into_bytes(),
        lf_out
    );
    let cr = dir.path().join("cr.bvh");
    std::fs::write(&cr, text.replace('\n', "\r")).unwrap();
    let out = dir.path().join("never.bvh");
    let o = crate::support::bin()
        .args([
            "interp".as_ref(),
            cr.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("cr.bvh: its lines end in CR alone"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!out.exists());
}
