//! Bad input: every case in `fixtures/bad/cases.json` must exit with code 2, print exactly
//! `inbetween: error: <message>` on stderr, write nothing to stdout, and leave `-o` untouched.

use assert_cmd::Command;
use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
struct Case {
    args: Vec<String>,
    stdin: Option<String>,
    message: String,
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn cases() -> Vec<Case> {
    let text = std::fs::read_to_string(root().join("fixtures/bad/cases.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn run(args: &[String], stdin: Option<&str>) -> std::process::Output {
    let mut cmd = Command::cargo_bin("inbetween").unwrap();
    cmd.current_dir(root()).args(args);
    match stdin {
        Some(s) => cmd.pipe_stdin(root().join(s)).unwrap(),
        None => cmd.write_stdin(""),
    };
    cmd.output().unwrap()
}

#[test]
fn bad_inputs_exit_2_with_the_message() {
    let mut failures = Vec::new();
    for case in cases() {
        let out = run(&case.args, case.stdin.as_deref());
        let stderr = String::from_utf8_lossy(&out.stderr);
        let want = format!("inbetween: error: {}\n", case.message);
        if out.status.code() != Some(2) || stderr != want || !out.stdout.is_empty() {
            failures.push(format!(
                "{:?}: exit {:?}\n  got:  {stderr}  want: {want}",
                case.args,
                out.status.code()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn bad_input_leaves_existing_output_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.csv");
    std::fs::write(&target, "precious\n").unwrap();
    for case in cases() {
        let mut args = case.args.clone();
        args.push("-o".into());
        args.push(target.to_str().unwrap().into());
        let out = run(&args, case.stdin.as_deref());
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "precious\n");
    }
    // No temporary files left behind.
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1);
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        vec!["convert", "--to", "euler:XXY"],
        vec!["convert", "--to", "quaternion"],
        vec!["convert", "--angles", "grad"],
        vec!["convert", "--fps", "0"],
        vec!["convert", "--precision", "99"],
        vec!["frobnicate"],
    ] {
        let out = Command::cargo_bin("inbetween")
            .unwrap()
            .args(&args)
            .write_stdin("")
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!out.stderr.is_empty());
    }
}

#[test]
fn quaternion_norm_warning_names_the_line() {
    let out = Command::cargo_bin("inbetween")
        .unwrap()
        .args(["convert", "-", "--input-format", "csv"])
        .write_stdin("time,w,x,y,z\n0,1,0,0,0\n1,1.01,0,0,0\n")
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "inbetween: warning: <stdin>:3: quaternion norm 1.01 is off 1 by more than 1e-3; normalized\n"
    );
}
