//! FBX files as strangers write them: a few hundred bytes that claim a stack of a million
//! seconds or thousands of layers, chains of tens of thousands of nodes. Files are written here
//! as ASCII FBX 7.4 (the layout of `fixtures/fbx/zup_inches_ascii.fbx`); the expected outcome
//! is what each file claims.

use crate::support::bin;
use std::time::{Duration, Instant};

/// FBX time units per second.
const TICKS: f64 = 46_186_158_000.0;

/// An ASCII FBX scene at 24 fps: `nodes` null nodes, each the child of the one before (a
/// chain) or of the first (a star), the last turned about x from 0° to 90° over `seconds`, in a
/// stack of `layers` animation layers (the curve in the first).
fn scene(nodes: usize, chain: bool, seconds: f64, layers: usize) -> String {
    let stop = (seconds * TICKS).round() as i64;
    let mut s = String::from(
        "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n\t\
         FBXVersion: 7400\n}\nGlobalSettings:  {\n\tVersion: 1000\n\tProperties70:  {\n\t\t\
         P: \"TimeMode\", \"enum\", \"\", \"\",11\n\t}\n}\nObjects:  {\n",
    );
    for i in 0..nodes {
        s += &format!(
            "\tModel: {}, \"Model::J{i}\", \"Null\" {{\n\t\tVersion: 232\n\t}}\n",
            1000 + i
        );
    }
    s += &format!(
        "\tAnimationStack: 200, \"AnimStack::Take1\", \"\" {{\n\t\tProperties70:  {{\n\t\t\t\
         P: \"LocalStart\", \"KTime\", \"Time\", \"\",0\n\t\t\tP: \"LocalStop\", \"KTime\", \
         \"Time\", \"\",{stop}\n\t\t}}\n\t}}\n"
    );
    for l in 0..layers {
        s += &format!(
            "\tAnimationLayer: {}, \"AnimLayer::L{l}\", \"\" {{ }}\n",
            300 + l
        );
    }
    s += "\tAnimationCurveNode: 100, \"AnimCurveNode::R\", \"\" {\n\t\tProperties70:  {\n\t\t\t\
          P: \"d|X\", \"Number\", \"\", \"A\",0\n\t\t}\n\t}\n";
    s += &format!(
        "\tAnimationCurve: 101, \"AnimCurve::\", \"\" {{\n\t\tDefault: 0\n\t\tKeyVer: 4009\n\t\t\
         KeyTime: *2 {{ a: 0,{stop} }}\n\t\tKeyValueFloat: *2 {{ a: 0,90 }}\n\t\t\
         KeyAttrFlags: *1 {{ a: 8452 }}\n\t\tKeyAttrDataFloat: *4 {{ a: 0,0,0,0 }}\n\t\t\
         KeyAttrRefCount: *1 {{ a: 2 }}\n\t}}\n"
    );
    s += "}\nConnections:  {\n";
    for i in 0..nodes {
        let parent = match i {
            0 => 0,
            _ if chain => 1000 + i - 1,
            _ => 1000,
        };
        s += &format!("\tC: \"OO\",{},{parent}\n", 1000 + i);
    }
    for l in 0..layers {
        s += &format!("\tC: \"OO\",{},200\n", 300 + l);
    }
    s += &format!(
        "\tC: \"OO\",100,300\n\tC: \"OP\",100,{}, \"Lcl Rotation\"\n\tC: \"OP\",101,100, \
         \"d|X\"\n}}\n",
        1000 + nodes - 1
    );
    s
}

/// Runs `convert FILE -o OUT` on `text`: (exit code, stderr, seconds).
fn convert(text: &str) -> (Option<i32>, String, f64) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scene.fbx");
    std::fs::write(&file, text).unwrap();
    let t = Instant::now();
    let o = bin()
        .arg("convert")
        .arg(&file)
        .arg("-o")
        .arg(dir.path().join("out.json"))
        .timeout(Duration::from_secs(120))
        .output()
        .unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        t.elapsed().as_secs_f64(),
    )
}

/// The generated scene is read as it says: a 2 s stack at 24 fps is 49 frames, the last node
/// at 90° at the end (so the refusals below are of the claims, not of a broken file).
#[test]
fn a_generated_scene_reads_as_it_claims() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scene.fbx");
    std::fs::write(&file, scene(3, true, 2.0, 1)).unwrap();
    let out =
        crate::support::stdout_of(bin().arg("convert").arg(&file).args(["--to", "euler:xyz"]));
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    let last = doc["tracks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["name"] == "J2")
        .unwrap();
    let keys = last["keys"].as_array().unwrap();
    assert_eq!(keys.len(), 49);
    let end = keys[48]["euler"][0].as_f64().unwrap();
    assert!((end - 90.0).abs() < 1e-4, "{end}");
}

/// A 1 kB file whose stack spans 930 000 s (22 million frames): refused before sampling, in
/// well under a second of work (58 s and 4.4 GB before).
#[test]
fn a_stack_spanning_a_million_seconds_is_refused_before_sampling() {
    let text = scene(1, true, 930_000.0, 1);
    assert!(text.len() < 2000);
    let (code, err, seconds) = convert(&text);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("22320001 frames at 24 fps"), "{err}");
    assert!(
        err.contains("more than the 4194304 samples this file may claim"),
        "{err}"
    );
    assert!(seconds < 20.0, "{seconds} s");
}

/// Thousands of layers multiply the work of every sample: counted before sampling.
#[test]
fn thousands_of_layers_are_counted_before_sampling() {
    let (code, err, seconds) = convert(&scene(1, true, 3000.0, 3000));
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("for 1 node(s) in 2999 layers: more than"),
        "{err}"
    );
    assert!(seconds < 20.0, "{seconds} s");
}

/// A chain of 8n nodes is read in about 8x the time of n nodes (the intermediate text indented
/// each line by its depth, and parents and children were found by searches of all nodes: a
/// 20 000-node chain took 4 GB).
#[test]
fn long_chains_are_read_in_linear_time() {
    let time = |n: usize| {
        let (code, err, seconds) = convert(&scene(n, true, 0.1, 1));
        assert_eq!(code, Some(0), "{err}");
        seconds
    };
    let small = time(1_000);
    let large = time(8_000);
    assert!(
        large < 24.0 * small.max(0.05),
        "1 000 nodes {small} s, 8 000 {large} s"
    );
}
