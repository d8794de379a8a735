//! The README's examples, run as written: every `inbetween` command line of its `sh` blocks (and
//! the `cat … | inbetween …` pipes), by bash with `pipefail`, in a folder that has the repository's `fixtures/`,
//! in the README's order (later examples read what earlier ones wrote). Each must exit 0; the
//! files they name are checked where the README says what they hold.

use std::path::Path;
use std::process::Command;

/// The command lines of the README's `sh` blocks that run `inbetween` (cargo's, which build
/// and test the checkout, are left to CI itself).
fn examples(readme: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut in_sh = false;
    for line in readme.lines() {
        if line.starts_with("```") {
            in_sh = line == "```sh";
            continue;
        }
        let line = line.trim();
        if in_sh && (line.starts_with("inbetween ") || line.starts_with("cat ")) {
            lines.push(line.to_string());
        }
    }
    lines
}

#[test]
fn readme_examples_run_as_written() {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let lines = examples(&readme);
    assert!(lines.len() >= 20, "{} examples found", lines.len());
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(root.join("fixtures"), dir.path().join("fixtures")).unwrap();
    std::fs::create_dir(dir.path().join("docs")).unwrap();
    let bin = assert_cmd::cargo::cargo_bin("inbetween");
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for line in &lines {
        let out = Command::new("bash")
            .args(["-o", "pipefail", "-c", line])
            .current_dir(dir.path())
            .env("PATH", &path)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{line}: exit {:?}: {}",
            out.status.code(),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let size = |name: &str| std::fs::metadata(dir.path().join(name)).unwrap().len();
    assert!(size("small.glb") < size("rigged60.glb"));
    for written in [
        "frames.csv",
        "keys.json",
        "keys4.json",
        "poses.json",
        "clip60.bvh",
    ] {
        assert!(size(written) > 0, "{written}");
    }
    assert!(size("keys4.json") < size("keys.json"));
    let npz = std::fs::read(dir.path().join("frames.npz")).unwrap();
    assert!(npz.starts_with(b"PK\x03\x04"), "a zip");
}
