//! Several inputs at once: `--out-dir`, `--jobs`, `--manifest`, `--refresh`, and an interrupted
//! batch resumed.

use crate::support::{bin, fixtures};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A folder of good clips, a corrupt clip, an empty file and a file of an unknown format.
fn library(dir: &Path) -> PathBuf {
    let input = dir.join("in");
    std::fs::create_dir_all(input.join("sub")).unwrap();
    let f = fixtures();
    std::fs::copy(f.join("bvh/cmu_01_01.bvh"), input.join("walk.bvh")).unwrap();
    std::fs::copy(f.join("bvh/mixed_orders.bvh"), input.join("sub/mixed.bvh")).unwrap();
    std::fs::copy(
        f.join("interp/multitrack.json"),
        input.join("sub/keys.json"),
    )
    .unwrap();
    std::fs::write(input.join("broken.bvh"), "HIERARCHY\nROOT x\n{\n").unwrap();
    std::fs::write(input.join("empty.bvh"), "").unwrap();
    std::fs::write(input.join("notes.txt"), "not motion\n").unwrap();
    input
}

/// The manifest's complete lines (a line being written while the batch runs is left out).
fn manifest(path: &Path) -> Vec<Value> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let complete = &text[..text.rfind('\n').map_or(0, |i| i + 1)];
    complete
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn status_of<'a>(records: &'a [Value], name: &str) -> Vec<&'a str> {
    records
        .iter()
        .filter(|r| r["input"].as_str().unwrap().ends_with(name))
        .map(|r| r["status"].as_str().unwrap())
        .collect()
}

/// No temporary file anywhere below `dir`.
fn no_temporary_files(dir: &Path) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            no_temporary_files(&p);
        } else {
            assert!(
                !p.to_string_lossy().contains(".inbetween-"),
                "{}",
                p.display()
            );
        }
    }
}

#[test]
fn a_batch_writes_what_each_single_command_writes_and_lists_every_input() {
    let dir = tempfile::tempdir().unwrap();
    let input = library(dir.path());
    let out = dir.path().join("out");
    let list = dir.path().join("manifest.jsonl");
    let o = bin()
        .arg("interp")
        .arg(&input)
        .args([
            "--fps",
            "30",
            "--output-format",
            "csv",
            "--jobs",
            "2",
            "--out-dir",
        ])
        .arg(&out)
        .arg("--manifest")
        .arg(&list)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("inbetween: 6 inputs: 3 ok, 0 skipped, 3 failed"),
        "{err}"
    );
    // Each good input's output is the single command's, byte for byte.
    for (rel, name) in [
        ("walk.bvh", "walk.csv"),
        ("sub/mixed.bvh", "sub/mixed.csv"),
        ("sub/keys.json", "sub/keys.csv"),
    ] {
        let single = dir.path().join("single.csv");
        bin()
            .arg("interp")
            .arg(input.join(rel))
            .args(["--fps", "30", "-o"])
            .arg(&single)
            .assert()
            .success();
        assert_eq!(
            std::fs::read(out.join(name)).unwrap(),
            std::fs::read(&single).unwrap(),
            "{rel}"
        );
    }
    let records = manifest(&list);
    assert_eq!(records.len(), 6);
    let walk = records
        .iter()
        .find(|r| r["input"].as_str().unwrap().ends_with("walk.bvh"))
        .unwrap();
    // cmu_01_01: 31 joints, 61 frames at 120 fps → 16 frames at 30 fps each.
    assert_eq!(
        (walk["tracks"].as_u64(), walk["frames"].as_u64()),
        (Some(31), Some(31 * 16))
    );
    for (name, message) in [
        (
            "broken.bvh",
            "broken.bvh: expected \"OFFSET\", found the end of the file",
        ),
        (
            "empty.bvh",
            "empty.bvh: expected a BVH file starting with \"HIERARCHY\"",
        ),
        ("notes.txt", "notes.txt: not an input format"),
    ] {
        let r = records
            .iter()
            .find(|r| r["input"].as_str().unwrap().ends_with(name))
            .unwrap();
        assert_eq!(r["status"], "failed");
        assert!(r["error"].as_str().unwrap().contains(message), "{r}");
    }
    // No partial output: nothing for the failed inputs, no temporary file.
    assert!(!out.join("broken.csv").exists() && !out.join("empty.csv").exists());
    no_temporary_files(&out);

    // Again: the good inputs are skipped (their outputs are newer), the bad ones fail again.
    let again = bin()
        .arg("interp")
        .arg(&input)
        .args(["--fps", "30", "--output-format", "csv", "--out-dir"])
        .arg(&out)
        .arg("--manifest")
        .arg(&list)
        .output()
        .unwrap();
    assert_eq!(again.status.code(), Some(2));
    let records = manifest(&list);
    assert_eq!(status_of(&records, "walk.bvh"), ["ok", "skipped"]);
    assert_eq!(status_of(&records, "broken.bvh"), ["failed", "failed"]);
    // --refresh redoes them; on a stderr that is no terminal, no progress bar: the summary only.
    let refreshed = bin()
        .arg("interp")
        .arg(input.join("walk.bvh"))
        .arg(input.join("sub"))
        .args([
            "--fps",
            "30",
            "--output-format",
            "csv",
            "--refresh",
            "--out-dir",
        ])
        .arg(&out)
        .arg("--manifest")
        .arg(&list)
        .output()
        .unwrap();
    assert!(refreshed.status.success());
    let err = String::from_utf8_lossy(&refreshed.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("inbetween: 3 inputs: 3 ok, 0 skipped, 0 failed ("),
        "{err}"
    );
    let records = manifest(&list);
    assert_eq!(status_of(&records, "walk.bvh"), ["ok", "skipped", "ok"]);
    // reduce's records carry the keys kept and the largest error.
    let reduced = dir.path().join("reduced.jsonl");
    bin()
        .arg("reduce")
        .arg(input.join("walk.bvh"))
        .args([
            "--tolerance",
            "1",
            "--translation-tolerance",
            "0.1",
            "--out-dir",
        ])
        .arg(dir.path().join("r"))
        .arg("--manifest")
        .arg(&reduced)
        .assert()
        .success();
    let r = &manifest(&reduced)[0];
    assert_eq!(
        (r["frames"].as_u64(), r["tracks"].as_u64()),
        (Some(31 * 61), Some(31))
    );
    let keys = r["keys"].as_u64().unwrap();
    assert!((62..31 * 61).contains(&keys), "{r}");
    let e = r["largest_error"].as_f64().unwrap();
    assert!(e > 0.0 && e <= 1.0, "{r}");
    assert_eq!(status_of(&records, "keys.json"), ["ok", "skipped", "ok"]);
}

#[test]
fn batch_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let clip = fixtures().join("bvh/cmu_01_01.bvh");
    for (args, message) in [
        (vec!["--jobs", "2"], "several inputs: give --out-dir DIR"),
        (vec!["--out-dir", "x", "-o", "y.bvh"], "-o names one output"),
        (
            vec!["--out-dir", "x", "nothing/*.bvh"],
            "no file matches this pattern",
        ),
    ] {
        let o = bin()
            .current_dir(dir.path())
            .arg("convert")
            .arg(&clip)
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(message), "{args:?}: {err}");
    }
}

#[cfg(unix)]
#[test]
fn an_interrupted_batch_resumed_ends_as_an_uninterrupted_one() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir_all(&input).unwrap();
    for i in 0..24 {
        std::fs::copy(
            fixtures().join("bvh/cmu_01_01.bvh"),
            input.join(format!("c{i:02}.bvh")),
        )
        .unwrap();
    }
    let args = [
        "--fps",
        "960",
        "--scheme",
        "minaccel",
        "--jobs",
        "2",
        "--output-format",
        "json",
    ];
    let whole = dir.path().join("whole");
    bin()
        .arg("interp")
        .arg(&input)
        .args(args)
        .arg("--out-dir")
        .arg(&whole)
        .assert()
        .success();

    let out = dir.path().join("out");
    let list = dir.path().join("m.jsonl");
    let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("inbetween"))
        .arg("interp")
        .arg(&input)
        .args(args)
        .arg("--out-dir")
        .arg(&out)
        .arg("--manifest")
        .arg(&list)
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // SIGTERM once a few inputs are done.
    let t0 = std::time::Instant::now();
    while manifest(&list).len() < 3 && t0.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    // SAFETY: kill(2) on the child's pid, which has not been waited for.
    unsafe { libc::kill(child.id() as i32, libc::SIGTERM) };
    let status = child.wait().unwrap();
    let first = manifest(&list);
    assert!(
        first.len() < 24,
        "the batch was interrupted ({} done, {status:?})",
        first.len()
    );
    no_temporary_files(&out);
    bin()
        .arg("interp")
        .arg(&input)
        .args(args)
        .arg("--out-dir")
        .arg(&out)
        .arg("--manifest")
        .arg(&list)
        .assert()
        .success();
    // Every input ok exactly once over the two runs; the outputs those of the whole run.
    let records = manifest(&list);
    for i in 0..24 {
        let name = format!("c{i:02}.bvh");
        let s = status_of(&records, &name);
        assert_eq!(s.iter().filter(|&&x| x == "ok").count(), 1, "{name}: {s:?}");
        let json = format!("c{i:02}.json");
        assert_eq!(
            std::fs::read(out.join(&json)).unwrap(),
            std::fs::read(whole.join(&json)).unwrap()
        );
    }
}
