//! Usage errors as clap reports them: values echoed at most 60 characters; `-o -` means
//! standard output exactly as no `-o` does.

use crate::support::{bin, fixtures};

fn stderr_of_failure(args: &[&str]) -> String {
    let out = bin().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    assert!(out.stdout.is_empty(), "{args:?} wrote to stdout");
    String::from_utf8(out.stderr).unwrap()
}

#[test]
fn a_huge_option_value_is_quoted_shortened() {
    let input = fixtures().join("interp/cyclic_loop.csv");
    let input = input.to_str().unwrap();
    let huge = "7".repeat(100_000);
    let cut = format!("{}…", "7".repeat(60));
    for args in [
        vec!["interp", input, "--fps", &huge],
        vec!["interp", input, "--scheme", &huge],
    ] {
        let err = stderr_of_failure(&args);
        assert!(err.len() < 1000, "{} bytes on stderr", err.len());
        assert!(err.contains(&format!("'{cut}'")), "{err}");
    }
}

#[test]
fn an_unknown_huge_flag_is_quoted_shortened() {
    let flag = format!("--{}", "x".repeat(100_000));
    let err = stderr_of_failure(&["interp", "keys.csv", &flag]);
    assert!(err.len() < 1000, "{} bytes on stderr", err.len());
    assert!(err.contains("unexpected argument"), "{err}");
}

#[test]
fn dash_output_is_standard_output() {
    for input in [
        "gltf/samplers.glb",
        "gltf/minimal_linear.gltf",
        "bvh/mixed_orders.bvh",
    ] {
        let path = fixtures().join(input);
        for command in ["convert", "interp", "reduce"] {
            let tolerance: &[&str] = if command == "reduce" {
                &["--tolerance", "1"]
            } else {
                &[]
            };
            let run = |extra: &[&str]| {
                let mut cmd = bin();
                cmd.arg(command).arg(&path).args(tolerance).args(extra);
                cmd.output().unwrap()
            };
            let (plain, dash) = (run(&[]), run(&["-o", "-"]));
            assert_eq!(plain.status.code(), dash.status.code(), "{command} {input}");
            assert!(
                plain.stdout == dash.stdout,
                "{command} {input}: stdout differs"
            );
            assert_eq!(plain.stderr, dash.stderr, "{command} {input}");
        }
    }
}
