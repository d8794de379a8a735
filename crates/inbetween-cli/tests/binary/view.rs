//! `view A [B] -o page.html`: the page holds no request, its data decode to what `diff`
//! measures (its `--per-frame` figures, its largest displacement) and to the clip's own
//! numbers (the root's BVH position channels, B's key times), its size for a 1 900-frame
//! 22-joint pair, and refusals. The page in a browser: `view_browser.rs`.

use crate::support::{bin, fixtures, stdout_of};
use base64::Engine;
use serde_json::Value;
use std::path::Path;

const CLIP: &str = "fixtures/bvh/cmu_01_01.bvh";

/// The page's embedded data (the JSON of its `inbetween-data` script element).
pub(crate) fn page_data(html: &str) -> Value {
    let open = "<script type=\"application/json\" id=\"inbetween-data\">";
    let start = html.find(open).expect("the data element") + open.len();
    let end = start + html[start..].find("</script>").expect("its end");
    serde_json::from_str(&html[start..end]).expect("JSON data")
}

fn bytes(b64: &Value) -> Vec<u8> {
    base64::engine::general_purpose::STANDARD
        .decode(b64.as_str().expect("a base64 string"))
        .expect("base64")
}

pub(crate) fn f64s(b64: &Value) -> Vec<f64> {
    bytes(b64)
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

fn f32s(b64: &Value) -> Vec<f32> {
    bytes(b64)
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// `diff A B --per-frame` as CSV: each frame's time and largest world displacement.
pub(crate) fn per_frame(dir: &Path, a: &str, b: &Path) -> Vec<(f64, f64)> {
    let csv = dir.join("per_frame.csv");
    stdout_of(
        bin()
            .args(["diff", a])
            .arg(b)
            .args(["--per-frame", "-o"])
            .arg(&csv),
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("frame,time,max_world"));
    lines
        .enumerate()
        .map(|(i, l)| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f[0], i.to_string());
            (f[1].parse().unwrap(), f[2].parse().unwrap())
        })
        .collect()
}

/// A pair made from the CMU clip: the clip, and its keys reduced to 0.5 units in world space.
pub(crate) fn reduced_pair(dir: &Path) -> std::path::PathBuf {
    let keys = dir.join("small.json");
    stdout_of(
        bin()
            .args(["reduce", CLIP, "--position-tolerance", "0.5", "-o"])
            .arg(&keys),
    );
    keys
}

/// No address, no element that loads anything: the page works from a file, offline.
pub(crate) fn assert_self_contained(html: &str) {
    let lower = html.to_ascii_lowercase();
    for needle in [
        "http:",
        "https:",
        "//cdn",
        " src=",
        "<link",
        "url(",
        "@import",
        "fetch(",
        "xmlhttprequest",
        "websocket",
    ] {
        assert!(!lower.contains(needle), "the page holds {needle:?}");
    }
}

#[test]
fn the_curve_is_diffs_per_frame_displacement_and_the_page_requests_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let keys = reduced_pair(dir.path());
    let page = dir.path().join("page.html");
    stdout_of(
        bin()
            .args(["view", CLIP])
            .arg(&keys)
            .args(["--tolerance", "0.5", "-o"])
            .arg(&page),
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert_self_contained(&html);
    let data = page_data(&html);
    let cmp = &data["compared"];
    let errors = f64s(&cmp["errors"]);
    let times = f64s(&data["times"]);
    let want = per_frame(dir.path(), CLIP, &keys);
    assert_eq!(errors.len(), want.len());
    assert_eq!(data["frames"], 61);
    for (f, ((e, t), (wt, we))) in errors.iter().zip(&times).zip(&want).enumerate() {
        assert_eq!(
            (t, e),
            (wt, we),
            "frame {f}: the page against diff --per-frame"
        );
    }
    // The largest of the curve is diff's largest world displacement (its per-track report,
    // taken over the tracks' points), at its time.
    let report: Value = serde_json::from_str(&stdout_of(
        bin()
            .args(["diff", CLIP])
            .arg(&keys)
            .args(["--output-format", "json"]),
    ))
    .unwrap();
    let largest = errors.iter().copied().fold(0.0, f64::max);
    assert_eq!(largest, report["total"]["max_world"].as_f64().unwrap());
    assert_eq!(cmp["largest"].as_f64(), Some(largest));
    assert_eq!(cmp["largest_time"], report["total"]["max_world_time"]);
    assert!(largest > 0.1 && largest <= 0.5, "{largest}");
    // Keyed frames: the frames at a key time of some track of B (the keys document's times).
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&keys).unwrap()).unwrap();
    let fps = doc["fps"].as_f64().unwrap();
    let mut key_times: Vec<f64> = doc["tracks"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|t| t["keys"].as_array().unwrap().iter())
        .map(|k| k["frame"].as_f64().unwrap() / fps)
        .collect();
    key_times.sort_by(f64::total_cmp);
    let keyed: Vec<usize> = (0..times.len())
        .filter(|&f| key_times.iter().any(|k| (k - times[f]).abs() <= 1e-9))
        .collect();
    let page_keyed: Vec<usize> = cmp["keyed"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as usize)
        .collect();
    assert_eq!(page_keyed, keyed);
    assert!(keyed.len() > 2 && keyed.len() < 61, "{}", keyed.len());
    assert_eq!(cmp["keys"].as_u64(), Some(key_times.len() as u64));
    assert_eq!(data["tolerance"].as_f64(), Some(0.5));
}

#[test]
fn the_figures_are_the_clips_world_positions() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("a.html");
    stdout_of(bin().args(["view", CLIP, "-o"]).arg(&page));
    let data = page_data(&std::fs::read_to_string(&page).unwrap());
    // 31 joints and 7 End Sites, counted in the file.
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(CLIP),
    )
    .unwrap();
    let count = |word: &str| {
        text.lines()
            .filter(|l| l.trim_start().starts_with(word))
            .count()
    };
    let joints = count("ROOT") + count("JOINT");
    assert_eq!((joints, count("End Site")), (31, 7));
    assert_eq!(data["points"], 38);
    assert_eq!(data["joints"].as_array().unwrap().len(), 31);
    assert!(data["compared"].is_null(), "A alone: no curve");
    let figures = data["figures"].as_array().unwrap();
    assert_eq!(figures.len(), 1);
    let pos = f32s(&figures[0]["positions"]);
    assert_eq!(pos.len(), 61 * 38 * 3);
    // The root's origin is its position channels (they replace its OFFSET): each frame's first
    // three numbers.
    let motion = text.split("Frame Time:").nth(1).unwrap();
    for (f, row) in motion
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .enumerate()
    {
        let v: Vec<f64> = row
            .split_whitespace()
            .take(3)
            .map(|x| x.parse().unwrap())
            .collect();
        let got = &pos[f * 38 * 3..f * 38 * 3 + 3];
        for i in 0..3 {
            assert_eq!(got[i], v[i] as f32, "frame {f}");
        }
    }
    // Every bone of the first frame is drawn from a point before it, the root from none.
    let from = data["point_from"].as_array().unwrap();
    assert_eq!(from[0], -1);
    assert!(
        from.iter()
            .enumerate()
            .skip(1)
            .all(|(p, q)| (q.as_i64().unwrap() as usize) < p)
    );
}

/// A BVH of SMPL's 22 body joints (5 End Sites) and `frames` frames at 60 fps, every channel a
/// sine of its own phase.
fn smpl_like_bvh(frames: usize) -> String {
    // (name, parent, offset, end site)
    let joints: [(&str, Option<usize>, [f64; 3], bool); 22] = [
        ("pelvis", None, [0.0, 0.0, 0.0], false),
        ("left_hip", Some(0), [6.0, -8.0, 0.0], false),
        ("left_knee", Some(1), [2.0, -38.0, 0.0], false),
        ("left_ankle", Some(2), [0.0, -40.0, -4.0], false),
        ("left_foot", Some(3), [0.0, -6.0, 12.0], true),
        ("right_hip", Some(0), [-6.0, -8.0, 0.0], false),
        ("right_knee", Some(5), [-2.0, -38.0, 0.0], false),
        ("right_ankle", Some(6), [0.0, -40.0, -4.0], false),
        ("right_foot", Some(7), [0.0, -6.0, 12.0], true),
        ("spine1", Some(0), [0.0, 10.0, -2.0], false),
        ("spine2", Some(9), [0.0, 13.0, 1.0], false),
        ("spine3", Some(10), [0.0, 6.0, 0.0], false),
        ("neck", Some(11), [0.0, 21.0, -3.0], false),
        ("head", Some(12), [0.0, 9.0, 5.0], true),
        ("left_collar", Some(11), [7.0, 11.0, -2.0], false),
        ("left_shoulder", Some(14), [12.0, 4.0, -1.0], false),
        ("left_elbow", Some(15), [26.0, 0.0, -2.0], false),
        ("left_wrist", Some(16), [25.0, 1.0, 0.0], true),
        ("right_collar", Some(11), [-7.0, 11.0, -2.0], false),
        ("right_shoulder", Some(18), [-12.0, 4.0, -1.0], false),
        ("right_elbow", Some(19), [-26.0, 0.0, -2.0], false),
        ("right_wrist", Some(20), [-25.0, 1.0, 0.0], true),
    ];
    fn write(out: &mut String, j: usize, joints: &[(&str, Option<usize>, [f64; 3], bool)]) {
        let (name, parent, [x, y, z], end) = joints[j];
        let kind = if parent.is_none() { "ROOT" } else { "JOINT" };
        let channels = if parent.is_none() {
            "6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"
        } else {
            "3 Zrotation Xrotation Yrotation"
        };
        out.push_str(&format!(
            "{kind} {name}\n{{\nOFFSET {x} {y} {z}\nCHANNELS {channels}\n"
        ));
        for c in (0..joints.len()).filter(|&c| joints[c].1 == Some(j)) {
            write(out, c, joints);
        }
        if end {
            out.push_str("End Site\n{\nOFFSET 0 -3 4\n}\n");
        }
        out.push_str("}\n");
    }
    let mut out = "HIERARCHY\n".to_string();
    write(&mut out, 0, &joints);
    out.push_str(&format!(
        "MOTION\nFrames: {frames}\nFrame Time: 0.0166667\n"
    ));
    for f in 0..frames {
        let t = f as f64 / 60.0;
        let mut row = vec![20.0 * t, 90.0 + 2.0 * (3.0 * t).sin(), 0.0];
        for j in 0..22 {
            let p = j as f64;
            row.extend([
                15.0 * (2.1 * t + p).sin(),
                25.0 * (1.3 * t + 0.7 * p).sin(),
                10.0 * (0.9 * t + 1.9 * p).cos(),
            ]);
        }
        let row: Vec<String> = row.iter().map(|v| format!("{v:.4}")).collect();
        out.push_str(&row.join(" "));
        out.push('\n');
    }
    out
}

/// The size bound of docs/formats.md: 12 bytes of float32 per point, frame and figure (16 in
/// base64) and 16 per frame of times and displacements (about 22 in base64): a 1 900-frame
/// pair of 22 joints and 5 End Sites is 2·1900·27·16 + 1900·22 ≈ 1.68 MB of data (1.70 MB
/// measured, the page and B's keyed frames with it).
#[test]
fn a_1900_frame_22_joint_pair_is_under_2_mb() {
    let dir = tempfile::tempdir().unwrap();
    let clip = dir.path().join("smpl.bvh");
    std::fs::write(&clip, smpl_like_bvh(1900)).unwrap();
    let keys = dir.path().join("keys.json");
    stdout_of(
        bin()
            .arg("reduce")
            .arg(&clip)
            .args([
                "--tolerance",
                "1",
                "--translation-tolerance",
                "0.1",
                "--shared-keys",
                "-o",
            ])
            .arg(&keys),
    );
    let page = dir.path().join("pair.html");
    stdout_of(bin().arg("view").arg(&clip).arg(&keys).arg("-o").arg(&page));
    let size = std::fs::metadata(&page).unwrap().len();
    let data = page_data(&std::fs::read_to_string(&page).unwrap());
    assert_eq!(
        (data["frames"].as_u64(), data["points"].as_u64()),
        (Some(1900), Some(27))
    );
    assert_eq!(data["joints"].as_array().unwrap().len(), 22);
    eprintln!("note: a 1900-frame 22-joint pair's page: {size} bytes");
    assert!(size < 2_000_000, "{size} bytes");
    // Most of it is the positions: at least 2·1900·27·16 bytes of base64.
    assert!(size > 2 * 1900 * 27 * 16, "{size} bytes");
}

#[test]
fn view_refuses_what_it_cannot_draw_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name);
    // Not an HTML name, unless the format is said.
    let o = bin()
        .args(["view", CLIP, "-o"])
        .arg(out("page.txt"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("page.txt: view writes an HTML page: name it .html")
            && err.contains("--output-format html"),
        "{err}"
    );
    assert!(!out("page.txt").exists());
    stdout_of(
        bin()
            .args(["view", CLIP, "--output-format", "html", "-o"])
            .arg(out("page.txt")),
    );
    assert!(
        std::fs::read_to_string(out("page.txt"))
            .unwrap()
            .starts_with("<!DOCTYPE html>")
    );
    // Keys have no skeleton to draw.
    let o = bin()
        .args(["view", "fixtures/interp/uniform.json", "-o"])
        .arg(out("keys.html"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("fixtures/interp/uniform.json: view draws a skeleton"),
        "{err}"
    );
    assert!(!out("keys.html").exists());
    // A glTF read with all its animations has no skeleton (each animation poses the nodes
    // apart): the message says to choose one, and with --animation the page is drawn.
    let gltf = "fixtures/gltf/real/RiggedSimple.gltf";
    let o = bin()
        .args(["view", gltf, "-o"])
        .arg(out("all.html"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("its tracks come from 2 animations") && err.contains("--animation"),
        "{err}"
    );
    assert!(!err.contains("keys have none"), "{err}");
    assert!(!out("all.html").exists());
    stdout_of(
        bin()
            .args(["view", gltf, "--animation", "0", "-o"])
            .arg(out("one.html")),
    );
    assert!(out("one.html").exists());
    // B with other tracks: diff's own refusal, file and track named.
    let o = bin()
        .args(["view", CLIP, "fixtures/bvh/mixed_orders.bvh", "-o"])
        .arg(out("two.html"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is not a track of"));
    assert!(!out("two.html").exists());
    // A world position beyond float32's range: the file, joint, frame and position named (the
    // position short), nothing written; as B's figure too (posed on A's skeleton).
    let far = out("far.bvh");
    let bvh = std::fs::read_to_string(fixtures().join("bvh/mixed_orders.bvh")).unwrap();
    std::fs::write(
        &far,
        bvh.replacen("OFFSET 11.0 0.0 0.0", "OFFSET 1e300 0.0 0.0", 1),
    )
    .unwrap();
    for b in [None, Some("fixtures/bvh/mixed_orders.bvh")] {
        let o = bin()
            .arg("view")
            .arg(&far)
            .args(b)
            .arg("-o")
            .arg(out("far.html"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(
                "far.bvh: joint \"LeftArm\": its world position at frame 0 is not a finite \
                 float32 number (1e300, 40.71, 0.0)"
            ),
            "{err}"
        );
        assert!(!out("far.html").exists());
    }
    // Standard output by `-`.
    let html = stdout_of(bin().args(["view", CLIP, "-o", "-"]));
    assert!(html.starts_with("<!DOCTYPE html>") && html.ends_with("</html>\n"));
}

/// B on a skeleton of its own (the same joints, twice the offsets) is drawn and measured on A's,
/// as diff measures it: the page says so (beside diff's warning), and not for B on A's.
#[test]
fn b_on_another_skeleton_is_drawn_on_as_and_the_page_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let bvh = std::fs::read_to_string(fixtures().join("bvh/mixed_orders.bvh")).unwrap();
    let twice = bvh.replacen("OFFSET 5.5 0.0 0.0", "OFFSET 11.0 0.0 0.0", 1);
    assert_ne!(twice, bvh);
    let other = dir.path().join("other.bvh");
    std::fs::write(&other, twice).unwrap();
    let page = dir.path().join("page.html");
    let o = bin()
        .args(["view", "fixtures/bvh/mixed_orders.bvh"])
        .arg(&other)
        .arg("-o")
        .arg(&page)
        .output()
        .unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("B's skeleton differs from A's"));
    let html = std::fs::read_to_string(&page).unwrap();
    let cmp = &page_data(&html)["compared"];
    assert_eq!(cmp["b_skeleton_differs"], true);
    assert_eq!(cmp["largest"], 0.0, "the same rotations on A's skeleton");
    assert!(html.contains("B's own skeleton differs from A's: B is drawn and measured on A's"));
    let same = stdout_of(bin().args([
        "view",
        "fixtures/bvh/mixed_orders.bvh",
        "fixtures/bvh/mixed_orders.bvh",
        "-o",
        "-",
    ]));
    assert_eq!(page_data(&same)["compared"]["b_skeleton_differs"], false);
}

/// On a touch screen a drag on the figures turns them and one on the curve moves along it: the
/// browser does not take it to scroll (and a drag it cancels ends).
#[test]
fn a_touch_drag_on_the_canvases_is_the_pages() {
    let html = stdout_of(bin().args(["view", CLIP, "-o", "-"]));
    for canvas in ["#figures", "#curve"] {
        let rule = html
            .lines()
            .find(|l| l.starts_with(&format!("{canvas} {{")))
            .expect("the canvas's rule");
        assert!(rule.contains("touch-action: none"), "{rule}");
    }
    assert_eq!(
        html.matches("\"pointercancel\"").count(),
        2,
        "both drags end"
    );
}

#[test]
fn a_title_cannot_close_the_script_that_holds_it() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("t.html");
    let title = "</script><script>alert(1)</script> walk";
    stdout_of(
        bin()
            .args(["view", CLIP, "--title", title, "-o"])
            .arg(&page),
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert_eq!(
        html.matches("</script>").count(),
        2,
        "the data's and the code's"
    );
    assert_eq!(page_data(&html)["title"], title);
}

/// `diff --per-frame`, the curve's other reader: one row per compared frame in each report
/// format, and refused (exit 2, nothing written) where there are no world positions to measure.
#[test]
fn diff_per_frame_reports_the_curve_or_refuses() {
    let dir = tempfile::tempdir().unwrap();
    let keys = reduced_pair(dir.path());
    let csv = per_frame(dir.path(), CLIP, &keys);
    let json: Value =
        serde_json::from_str(&stdout_of(bin().args(["diff", CLIP]).arg(&keys).args([
            "--per-frame",
            "--output-format",
            "json",
        ])))
        .unwrap();
    let rows = json["frames"].as_array().unwrap();
    assert_eq!(rows.len(), 61);
    for (f, (row, (t, d))) in rows.iter().zip(&csv).enumerate() {
        assert_eq!(row["frame"], f);
        assert_eq!(
            (row["time"].as_f64(), row["max_world"].as_f64()),
            (Some(*t), Some(*d))
        );
    }
    let text = stdout_of(bin().args(["diff", CLIP]).arg(&keys).arg("--per-frame"));
    assert_eq!(text.lines().count(), 62, "a header and 61 rows");
    let out = dir.path().join("no.csv");
    let o = bin()
        .args([
            "diff",
            "fixtures/diff/turned.json",
            "fixtures/diff/turned_more.json",
            "--per-frame",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("diff: --per-frame reports world displacements, which fixtures/diff/turned.json does not give"),
        "{err}"
    );
    assert!(!out.exists());
}

/// B's figure is B as played: keys that every track shares (`reduce --shared-keys`) are the
/// capture's own frames, hit by the curve, so at a keyed frame B's figure is A's, point for
/// point, and the displacement 0 (to rounding); where the curve is largest, the figures part by
/// it.
#[test]
fn at_shared_keys_b_is_a_and_between_them_b_is_its_curve() {
    let dir = tempfile::tempdir().unwrap();
    let keys = dir.path().join("shared.json");
    stdout_of(
        bin()
            .args([
                "reduce",
                CLIP,
                "--tolerance",
                "2",
                "--translation-tolerance",
                "0.5",
            ])
            .args(["--shared-keys", "-o"])
            .arg(&keys),
    );
    let page = dir.path().join("shared.html");
    stdout_of(bin().args(["view", CLIP]).arg(&keys).arg("-o").arg(&page));
    let data = page_data(&std::fs::read_to_string(&page).unwrap());
    let cmp = &data["compared"];
    let errors = f64s(&cmp["errors"]);
    let figures = data["figures"].as_array().unwrap();
    let (a, b) = (
        f32s(&figures[0]["positions"]),
        f32s(&figures[1]["positions"]),
    );
    let frame = |pos: &[f32], f: usize| pos[f * 38 * 3..(f + 1) * 38 * 3].to_vec();
    let keyed: Vec<usize> = cmp["keyed"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as usize)
        .collect();
    assert!(keyed.len() > 2 && keyed.len() < 30, "{keyed:?}");
    // The keys are the frames' quaternions written and read back (normalised on reading):
    // equal to rounding, not to the bit.
    for &f in &keyed {
        let (pa, pb) = (frame(&a, f), frame(&b, f));
        let apart = pa
            .iter()
            .zip(&pb)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0f32, f32::max);
        assert!(apart <= 1e-5, "keyed frame {f}: the figures {apart} apart");
        assert!(errors[f] < 1e-12, "keyed frame {f}: {}", errors[f]);
    }
    // The largest displacement: the farthest pair of points of the two figures there.
    let (worst, largest) = errors
        .iter()
        .enumerate()
        .fold((0, 0.0f64), |m, (f, &e)| if e > m.1 { (f, e) } else { m });
    assert!(!keyed.contains(&worst) && largest > 0.0);
    let far = frame(&a, worst)
        .chunks_exact(3)
        .zip(frame(&b, worst).chunks_exact(3))
        .map(|(p, q)| {
            let d: f64 = (0..3)
                .map(|i| (f64::from(p[i]) - f64::from(q[i])).powi(2))
                .sum();
            d.sqrt()
        })
        .fold(0.0, f64::max);
    // The curve also measures points the figures do not draw (default ends at bone length), so
    // the drawn points part by at most the curve, and by most of it here (float32 aside).
    assert!(
        far <= largest + 1e-4 && far > 0.5 * largest,
        "{far} {largest}"
    );
}
