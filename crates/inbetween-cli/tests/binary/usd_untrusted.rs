//! `.usda` files as strangers write them: joints that share a last name, nesting deep enough to
//! overflow a recursive parser, tens of thousands of joints, Blender's asset paths. Layers are
//! generated here; expected values are the layers' own numbers.

use crate::support::{bin, fixtures};
use std::path::Path;

/// A layer whose Skeleton lists `joints` (paths) with one rotation sample each: joint `i` turned
/// `angles[i]` degrees about z.
fn layer(joints: &[&str], angles: &[f64]) -> String {
    let quoted: Vec<String> = joints.iter().map(|j| format!("\"{j}\"")).collect();
    let list = quoted.join(", ");
    let rots: Vec<String> = angles
        .iter()
        .map(|a| {
            let h = a.to_radians() / 2.0;
            format!("({}, 0, 0, {})", h.cos(), h.sin())
        })
        .collect();
    format!(
        "#usda 1.0\n(\n    timeCodesPerSecond = 24\n)\n\ndef SkelRoot \"R\"\n{{\n    def Skeleton \"S\"\n    {{\n        uniform token[] joints = [{list}]\n        rel skel:animationSource = </R/S/A>\n        def SkelAnimation \"A\"\n        {{\n            uniform token[] joints = [{list}]\n            quatf[] rotations.timeSamples = {{\n                0: [{r}],\n                10: [{r}],\n            }}\n        }}\n    }}\n}}\n",
        r = rots.join(", ")
    )
}

fn keys_of(path: &Path) -> serde_json::Value {
    let out = crate::support::stdout_of(bin().arg("convert").arg(path).args(["--to", "quat"]));
    serde_json::from_str(&out).unwrap()
}

/// `arm/hand` and `leg/hand` are two joints: two tracks, each with its own rotation, and a file
/// compared with itself differs by nothing (it reported 120° when both were "hand").
#[test]
fn joints_sharing_a_last_name_stay_two_tracks() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("hands.usda");
    let joints = [
        "root",
        "root/arm",
        "root/arm/hand",
        "root/leg",
        "root/leg/hand",
    ];
    std::fs::write(&file, layer(&joints, &[0.0, 10.0, 30.0, 20.0, 150.0])).unwrap();
    let doc = keys_of(&file);
    let tracks = doc["tracks"].as_array().unwrap();
    let names: Vec<&str> = tracks.iter().map(|t| t["name"].as_str().unwrap()).collect();
    assert_eq!(names, joints);
    for (t, want) in tracks.iter().zip([0.0f64, 10.0, 30.0, 20.0, 150.0]) {
        let q = &t["keys"][0]["quat"];
        let angle = 2.0 * q[3].as_f64().unwrap().atan2(q[0].as_f64().unwrap());
        assert!((angle.to_degrees() - want).abs() < 1e-4, "{t}");
    }
    let out = crate::support::stdout_of(
        bin()
            .arg("diff")
            .arg(&file)
            .arg(&file)
            .args(["--output-format", "json"]),
    );
    let report: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(report["total"]["max_angle"].as_f64(), Some(0.0), "{report}");
    // A joint path listed twice is an error naming both places.
    std::fs::write(&file, layer(&["a", "a/b", "a/b"], &[0.0; 3])).unwrap();
    let o = bin().arg("convert").arg(&file).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("joints[1] and joints[2] are both \"a/b\""),
        "{err}"
    );
}

/// USD written from USD keeps the joints' paths, so the two compare track by track.
#[test]
fn usd_written_from_usd_keeps_the_joint_paths() {
    let dir = tempfile::tempdir().unwrap();
    let first = dir.path().join("first.usda");
    let again = dir.path().join("again.usda");
    let clip = fixtures().join("bvh/cmu_01_01.bvh");
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
    let a = keys_of(&first);
    let b = keys_of(&again);
    let names = |d: &serde_json::Value| -> Vec<String> {
        d["tracks"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t["name"].as_str().unwrap().to_string())
            .collect()
    };
    assert_eq!(names(&a), names(&b));
    assert!(names(&a).iter().any(|n| n.contains('/')));
    let o = bin()
        .arg("diff")
        .arg(&first)
        .arg(&again)
        .args(["--max-angle", "0.001"])
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// 3 000 nested prims in a batch: that file fails with a located error, the batch and its
/// other file finish (a recursive parser overflowed the worker thread's stack and aborted the
/// whole process).
#[test]
fn deep_nesting_fails_one_file_not_the_batch() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir_all(&input).unwrap();
    let deep = format!(
        "#usda 1.0\n{}{}",
        "def \"a\" {\n".repeat(3000),
        "}\n".repeat(3000)
    );
    std::fs::write(input.join("deep.usda"), deep).unwrap();
    std::fs::write(
        input.join("good.usda"),
        layer(&["root", "root/arm"], &[0.0, 45.0]),
    )
    .unwrap();
    let out = dir.path().join("out");
    let o = bin()
        .arg("convert")
        .arg(&input)
        .arg("--out-dir")
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("deep.usda:258: nested deeper than 256 levels"),
        "{err}"
    );
    assert!(out.join("good.json").is_file());
    assert!(!out.join("deep.json").exists());
    // Lists nested a million deep, read alone.
    let values = format!(
        "#usda 1.0\ndef \"a\" {{\n float x = {}1{}\n}}\n",
        "[".repeat(1_000_000),
        "]".repeat(1_000_000)
    );
    let file = dir.path().join("lists.usda");
    std::fs::write(&file, values).unwrap();
    let o = bin().arg("convert").arg(&file).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("nested deeper than 256 levels"));
}

/// A Skeleton of 8n joints is read in about 8x the time of n (finding parents and the
/// animation's joints by a search of the joints before took n² comparisons).
#[test]
fn many_joints_are_read_in_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let time = |n: usize| {
        // A star: every joint a child of the root, named by its index.
        let paths: Vec<String> = std::iter::once("r".to_string())
            .chain((1..n).map(|i| format!("r/j{i}")))
            .collect();
        let refs: Vec<&str> = paths.iter().map(String::as_str).collect();
        let file = dir.path().join(format!("star{n}.usda"));
        std::fs::write(&file, layer(&refs, &vec![5.0; n])).unwrap();
        let out = dir.path().join(format!("star{n}.json"));
        let t = std::time::Instant::now();
        bin()
            .arg("convert")
            .arg(&file)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        t.elapsed().as_secs_f64()
    };
    let small = time(2_000);
    let large = time(16_000);
    assert!(
        large < 24.0 * small.max(0.02),
        "2 000 joints {small} s, 16 000 {large} s"
    );
}
