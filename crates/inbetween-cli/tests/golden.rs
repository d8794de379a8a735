//! Golden files: each case in `fixtures/golden/cases.json` is a command line (and optionally a
//! file fed to stdin); its output must match `fixtures/golden/<name>` numerically (absolute
//! tolerance 1e-9), everything that is not a number exactly. `INBETWEEN_BLESS=1` rewrites the
//! golden files from the current binary. How each was checked independently:
//! `fixtures/README.md`.

mod support;

use assert_cmd::Command;
use serde::Deserialize;
use std::path::Path;
use support::fixtures;

const TOL: f64 = 1e-9;

#[derive(Deserialize)]
struct Case {
    name: String,
    args: Vec<String>,
    stdin: Option<String>,
}

/// Splits text into numbers and the text between them.
fn tokens(s: &str) -> Vec<Result<f64, String>> {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let mut text = String::new();
    while i < b.len() {
        let starts_number =
            b[i].is_ascii_digit() || (b[i] == b'-' && i + 1 < b.len() && b[i + 1].is_ascii_digit());
        let in_word = i > 0 && (b[i - 1].is_ascii_alphabetic() || b[i - 1] == b'_');
        if starts_number && !in_word {
            let mut j = i + 1;
            while j < b.len()
                && (b[j].is_ascii_digit()
                    || b[j] == b'.'
                    || b[j] == b'e'
                    || b[j] == b'E'
                    || ((b[j] == b'-' || b[j] == b'+') && (b[j - 1] == b'e' || b[j - 1] == b'E')))
            {
                j += 1;
            }
            if let Ok(x) = s[i..j].parse::<f64>() {
                if !text.is_empty() {
                    out.push(Err(std::mem::take(&mut text)));
                }
                out.push(Ok(x));
                i = j;
                continue;
            }
        }
        text.push(b[i] as char);
        i += 1;
    }
    if !text.is_empty() {
        out.push(Err(text));
    }
    out
}

/// Compares two outputs; returns the first difference.
pub fn compare(got: &str, want: &str) -> Result<(), String> {
    let (g, w) = (tokens(got), tokens(want));
    for (i, (a, b)) in g.iter().zip(&w).enumerate() {
        match (a, b) {
            (Ok(x), Ok(y)) if (x - y).abs() <= TOL => {}
            _ if a == b => {}
            _ => return Err(format!("token {i}: got {a:?}, want {b:?}")),
        }
    }
    if g.len() != w.len() {
        return Err(format!("got {} tokens, want {}", g.len(), w.len()));
    }
    Ok(())
}

fn run_case(case: &Case) -> String {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let mut cmd = Command::cargo_bin("inbetween").expect("binary");
    cmd.current_dir(root).args(&case.args);
    if let Some(stdin) = &case.stdin {
        cmd.pipe_stdin(root.join(stdin)).expect("stdin file");
    }
    let out = cmd.output().expect("run");
    assert!(
        out.status.success(),
        "{}: exit {:?}: {}",
        case.name,
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 output")
}

#[test]
fn golden_files() {
    let dir = fixtures().join("golden");
    let cases: Vec<Case> =
        serde_json::from_str(&std::fs::read_to_string(dir.join("cases.json")).unwrap()).unwrap();
    let bless = std::env::var_os("INBETWEEN_BLESS").is_some();
    let mut failures = Vec::new();
    let mut previous = Vec::new();
    for case in &cases {
        let got = run_case(case);
        let path = dir.join(&case.name);
        if bless {
            previous.push((path.clone(), std::fs::read(&path).ok()));
            std::fs::write(&path, &got).unwrap();
            continue;
        }
        let want = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("{}: {e} (bless with INBETWEEN_BLESS=1)", case.name));
        if let Err(e) = compare(&got, &want) {
            failures.push(format!("{}: {e}", case.name));
        }
    }
    if bless {
        keep_only_if_checked(&previous);
    }
    assert!(
        failures.is_empty(),
        "golden mismatches:\n{}",
        failures.join("\n")
    );
    assert!(cases.len() >= 10);
}

/// Blessing writes golden files only the independent checker accepts: it runs
/// `fixtures/golden/check.py` (Python from `INBETWEEN_PYTHON`, else `target/ci-venv`, the
/// environment `.ci/run` builds from `fixtures/requirements.txt`) and, if the checker fails or
/// cannot run, puts every file back as it was.
fn keep_only_if_checked(previous: &[(std::path::PathBuf, Option<Vec<u8>>)]) {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let python = std::env::var_os("INBETWEEN_PYTHON")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| root.join("target/ci-venv/bin/python"));
    let checked = std::process::Command::new(&python)
        .arg(root.join("fixtures/golden/check.py"))
        .current_dir(root)
        .output();
    let verdict = match &checked {
        Ok(out) if out.status.success() => return,
        Ok(out) => format!(
            "the independent checker rejected them:\n{}",
            String::from_utf8_lossy(&out.stdout)
        ),
        Err(e) => format!(
            "the independent checker could not run ({}: {e}); create its environment with \
             `python3 -m venv target/ci-venv && target/ci-venv/bin/pip install -r \
             fixtures/requirements.txt`, or set INBETWEEN_PYTHON",
            python.display()
        ),
    };
    for (path, old) in previous {
        match old {
            Some(bytes) => std::fs::write(path, bytes).unwrap(),
            None => std::fs::remove_file(path).unwrap(),
        }
    }
    panic!("golden files not blessed (restored as they were): {verdict}");
}

#[test]
fn compare_catches_differences() {
    assert!(compare("a,1.0\n", "a,1.0000000001\n").is_ok());
    assert!(compare("a,1.0\n", "a,1.00001\n").is_err());
    assert!(compare("a,1.0\n", "b,1.0\n").is_err());
    assert!(compare("m00,1e-3", "m00,0.001").is_ok());
    assert!(compare("1,2", "1,2,3").is_err());
}
