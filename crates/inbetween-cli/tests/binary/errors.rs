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
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
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

/// Bad option values: exit 2 and a first line that names the option and the value.
#[test]
fn bad_option_values_name_option_and_value() {
    let cases: [(&[&str], &str); 11] = [
        (
            &["--to", "quaternion"],
            "error: invalid value 'quaternion' for '--to <REPR>': expected one of quat, euler:SEQ (e.g. euler:ZYX), matrix, axis-angle, rotvec, rot6d:rows, rot6d:columns, found \"quaternion\"",
        ),
        (
            &["--to", "euler:XXY"],
            "error: invalid value 'euler:XXY' for '--to <REPR>': expected an Euler sequence of three letters from xyz (extrinsic) or XYZ (intrinsic) with no axis twice in a row, such as ZYX or zxz, found \"XXY\"",
        ),
        (
            &["--fps", "0"],
            "error: invalid value '0' for '--fps <RATE>': expected a positive frame rate, found 0",
        ),
        (
            &["--fps", "-24"],
            "error: invalid value '-24' for '--fps <RATE>': expected a positive frame rate such as 24, 29.97 or 30000/1001, found \"-24\"",
        ),
        (
            &["--fps", "1e9"],
            "error: invalid value '1e9' for '--fps <RATE>': expected a frame rate between 1e-6 and 1e7 frames per second, found 1e9",
        ),
        (
            &["--fps", "50000000"],
            "error: invalid value '50000000' for '--fps <RATE>': expected a frame rate between 1e-6 and 1e7 frames per second, found 50000000",
        ),
        (
            &["--scheme", "foo"],
            "error: invalid value 'foo' for '--scheme <SCHEME>'",
        ),
        (
            &["--precision", "99"],
            "error: invalid value '99' for '--precision <N>': expected a whole number from 0 to 17, found \"99\"",
        ),
        (
            &["--start-velocity", "1,2"],
            "error: invalid value '1,2' for '--start-velocity <X,Y,Z>': expected three finite numbers X,Y,Z such as 0,0,90, found \"1,2\"",
        ),
        (
            &["--angles", "grad"],
            "error: invalid value 'grad' for '--angles <U>': expected \"deg\" or \"rad\", found \"grad\"",
        ),
        (
            &["--output-format", "xml"],
            "error: invalid value 'xml' for '--output-format <F>': expected \"csv\", \"json\", \"npy\", \"npz\", \"bvh\", \"gltf\", \"glb\", \"usda\" or \"fbx\", found \"xml\"",
        ),
    ];
    for (args, first_line) in cases {
        let out = Command::cargo_bin("inbetween")
            .unwrap()
            .current_dir(root())
            .args(["interp", "fixtures/interp/uniform.json"])
            .args(args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(stderr.lines().next(), Some(first_line), "{args:?}");
        assert!(out.stdout.is_empty());
    }
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
