//! A batch over a folder someone else made: it reads only that folder (links out of it are not
//! followed, FIFOs never opened, link loops end), writes over none of its inputs or its own
//! outputs (checked before anything is written), and says so when its manifest cannot be
//! written. Folders are built here; the expected outcome is each case's own files.

use crate::support::fixtures;
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Runs the binary with `args`, killed after 60 s (a hang fails the test, not the suite).
fn run(args: &[&str]) -> Output {
    let program = std::env::var_os("CARGO_BIN_EXE_inbetween").expect("cargo test sets it");
    let child = Command::new(program)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id().to_string();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(child.wait_with_output().unwrap()));
    match rx.recv_timeout(Duration::from_secs(60)) {
        Ok(o) => o,
        Err(_) => {
            let _ = Command::new("kill").args(["-9", &pid]).status();
            panic!("{args:?}: still running after 60 s");
        }
    }
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn manifest(path: &Path) -> Vec<Value> {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A folder `in` with one clip, and a file outside it that is not motion.
fn dataset(dir: &Path) -> std::path::PathBuf {
    let input = dir.join("in");
    std::fs::create_dir_all(input.join("sub")).unwrap();
    std::fs::copy(
        fixtures().join("bvh/mixed_orders.bvh"),
        input.join("sub/walk.bvh"),
    )
    .unwrap();
    std::fs::create_dir_all(dir.join("elsewhere")).unwrap();
    std::fs::write(dir.join("elsewhere/secret.json"), "TOP-SECRET-CONTENT\n").unwrap();
    std::fs::copy(
        fixtures().join("bvh/mixed_orders.bvh"),
        dir.join("elsewhere/clip.bvh"),
    )
    .unwrap();
    input
}

#[cfg(unix)]
#[test]
fn links_out_of_the_folder_are_not_followed_unless_asked() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let input = dataset(dir.path());
    symlink(
        dir.path().join("elsewhere/secret.json"),
        input.join("secret.json"),
    )
    .unwrap();
    symlink(
        dir.path().join("elsewhere/clip.bvh"),
        input.join("clip.bvh"),
    )
    .unwrap();
    symlink(dir.path().join("elsewhere"), input.join("more")).unwrap();
    let (out, m) = (dir.path().join("out"), dir.path().join("m.jsonl"));
    let o = run(&[
        "convert",
        p(&input),
        "--out-dir",
        p(&out),
        "--manifest",
        p(&m),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(!err.contains("TOP-SECRET"), "{err}");
    assert!(!std::fs::read_to_string(&m).unwrap().contains("TOP-SECRET"));
    assert!(out.join("sub/walk.json").is_file());
    for name in ["secret.json", "clip.json", "more"] {
        assert!(!out.join(name).exists(), "{name} was written");
    }
    let records = manifest(&m);
    for name in ["secret.json", "clip.bvh", "more"] {
        let r = records
            .iter()
            .find(|r| r["input"].as_str().unwrap().ends_with(name))
            .unwrap_or_else(|| panic!("{name}: no record in {records:?}"));
        assert_eq!(r["status"], "skipped", "{r}");
        assert!(
            r["reason"].as_str().unwrap().contains("out of the folder"),
            "{r}"
        );
    }
    // Asked to follow, it does.
    let out2 = dir.path().join("out2");
    let o = run(&["convert", p(&input), "--out-dir", p(&out2), "--follow"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o)); // secret.json is no keys document
    // The linked folder's clip is the linked clip: one input, by the name found first.
    assert!(out2.join("clip.json").is_file());
    assert!(!out2.join("more/clip.json").exists());
}

#[cfg(unix)]
#[test]
fn links_inside_are_followed_once_and_loops_end() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let input = dataset(dir.path());
    symlink(".", input.join("loop1")).unwrap();
    symlink(".", input.join("loop2")).unwrap();
    symlink("..", input.join("sub/up")).unwrap();
    symlink("sub/walk.bvh", input.join("alias.bvh")).unwrap();
    symlink("sub", input.join("again")).unwrap();
    let (out, m) = (dir.path().join("out"), dir.path().join("m.jsonl"));
    let t = Instant::now();
    let o = run(&[
        "interp",
        p(&input),
        "--out-dir",
        p(&out),
        "--manifest",
        p(&m),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(t.elapsed() < Duration::from_secs(30));
    let records = manifest(&m);
    // One clip, read once, by its own name.
    assert_eq!(records.len(), 1, "{records:?}");
    assert!(
        records[0]["input"]
            .as_str()
            .unwrap()
            .ends_with("sub/walk.bvh")
    );
    assert!(out.join("sub/walk.bvh").is_file());
    assert!(!out.join("alias.bvh").exists() && !out.join("again").exists());
}

#[cfg(unix)]
#[test]
fn fifos_are_never_opened() {
    let dir = tempfile::tempdir().unwrap();
    let input = dataset(dir.path());
    let fifo = input.join("pipe.bvh");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let (out, m) = (dir.path().join("out"), dir.path().join("m.jsonl"));
    // Found in a folder, and named directly.
    for args in [
        vec![
            "convert",
            p(&input),
            "--out-dir",
            p(&out),
            "--manifest",
            p(&m),
        ],
        vec!["convert", p(&fifo), "--out-dir", p(&out)],
    ] {
        let o = run(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(0), "{err}");
        assert!(
            err.contains("pipe.bvh: a FIFO (never opened), skipped"),
            "{err}"
        );
    }
    assert!(!out.join("pipe.json").exists());
    let records = manifest(&m);
    assert!(records.iter().any(|r| r["status"] == "skipped"
        && r["input"].as_str().unwrap().ends_with("pipe.bvh")));
}

/// Whether the files of `dir` are still `before` (name → bytes).
fn unchanged(dir: &Path, before: &[(String, Vec<u8>)]) {
    for (name, bytes) in before {
        assert_eq!(
            &std::fs::read(dir.join(name)).unwrap(),
            bytes,
            "{name} changed"
        );
    }
}

#[test]
fn outputs_never_write_over_inputs_other_outputs_or_the_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir_all(&input).unwrap();
    std::fs::copy(
        fixtures().join("bvh/mixed_orders.bvh"),
        input.join("walk.bvh"),
    )
    .unwrap();
    std::fs::copy(
        fixtures().join("interp/multitrack.json"),
        input.join("walk.json"),
    )
    .unwrap();
    let before: Vec<(String, Vec<u8>)> = ["walk.bvh", "walk.json"]
        .iter()
        .map(|n| (n.to_string(), std::fs::read(input.join(n)).unwrap()))
        .collect();
    let listing = |d: &Path| {
        let mut v: Vec<_> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        v.sort();
        v
    };
    // The output folder is the input folder: walk.bvh's keys would replace walk.json.
    let o = run(&["convert", p(&input), "--out-dir", p(&input)]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("nothing was written"), "{err}");
    assert!(err.contains("walk.json, the output of"), "{err}");
    unchanged(&input, &before);
    assert_eq!(listing(&input).len(), 2);
    // Two inputs, one output: walk.bvh and walk.json both make out/walk.json.
    let out = dir.path().join("out");
    let o = run(&[
        "reduce",
        p(&input),
        "--out-dir",
        p(&out),
        "--tolerance",
        "1",
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("would be the output of both"), "{err}");
    assert!(
        err.contains("walk.bvh") && err.contains("walk.json"),
        "{err}"
    );
    assert!(!out.exists());
    // The manifest is an input.
    let m = input.join("walk.json");
    let o = run(&[
        "convert",
        p(&input),
        "--out-dir",
        p(&out),
        "--manifest",
        p(&m),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--manifest") && err.contains("is the input"),
        "{err}"
    );
    unchanged(&input, &before);
    // The manifest is an output.
    let m = out.join("walk.json");
    let o = run(&[
        "convert",
        p(&input.join("walk.bvh")),
        "--out-dir",
        p(&out),
        "--manifest",
        p(&m),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("is the output of"), "{err}");
    // Named twice (a file and its folder), walk.json still collides with walk.bvh's output.
    let inner = input.join("out");
    for _ in 0..2 {
        let o = run(&[
            "convert",
            p(&input.join("walk.bvh")),
            p(&input),
            "--out-dir",
            p(&inner),
            "--refresh",
        ]);
        // walk.json of the folder makes inner/walk.json as walk.bvh does: refused both times.
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    }
    unchanged(&input, &before);
}

#[test]
fn an_output_folder_inside_the_inputs_is_not_an_input() {
    let dir = tempfile::tempdir().unwrap();
    let input = dataset(dir.path());
    let out = input.join("converted");
    for _ in 0..2 {
        let o = run(&["convert", p(&input), "--out-dir", p(&out), "--refresh"]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
    assert!(out.join("sub/walk.json").is_file());
    assert!(!out.join("converted").exists());
}

#[test]
fn a_manifest_that_cannot_be_written_is_a_failure() {
    let dir = tempfile::tempdir().unwrap();
    let input = dataset(dir.path());
    let out = dir.path().join("out");
    // /dev/full accepts the open and fails every write.
    if !Path::new("/dev/full").exists() {
        return;
    }
    let o = run(&[
        "convert",
        p(&input),
        "--out-dir",
        p(&out),
        "--manifest",
        "/dev/full",
    ]);
    let err = stderr(&o);
    assert_ne!(o.status.code(), Some(0), "{err}");
    assert!(err.contains("--manifest /dev/full"), "{err}");
}

#[cfg(unix)]
#[test]
fn file_names_cannot_write_to_the_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let input = dataset(dir.path());
    std::fs::write(input.join("evil\u{1b}[2J\nname.bvh"), "HIERARCHY\n").unwrap();
    let out = dir.path().join("out");
    let o = run(&["convert", p(&input), "--out-dir", p(&out)]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(!err.contains('\u{1b}'), "{err:?}");
    assert!(err.contains(r"evil\u{1b}[2J\nname.bvh"), "{err}");
}

/// The folder walk is linear in its files: 8x the files in well under 8x8 the time.
#[test]
fn many_files_are_found_in_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let time = |n: usize| {
        let d = dir.path().join(format!("n{n}"));
        std::fs::create_dir_all(&d).unwrap();
        for i in 0..n {
            std::fs::write(d.join(format!("f{i}.txt")), "").unwrap();
        }
        // Every file fails (no input format) without being read: the time is the walk's.
        let t = Instant::now();
        let o = run(&[
            "convert",
            p(&d),
            "--out-dir",
            p(&dir.path().join("o")),
            "--jobs",
            "1",
        ]);
        assert_eq!(o.status.code(), Some(2));
        t.elapsed().as_secs_f64()
    };
    let small = time(500);
    let large = time(4000);
    assert!(
        large < 20.0 * small.max(0.05),
        "500 files {small} s, 4000 files {large} s"
    );
}
