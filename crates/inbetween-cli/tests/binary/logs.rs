//! Timestamped robotics logs (issue 47): TUM, EuRoC and `rostopic echo -p` files read with
//! `--columns` presets give the keys of their plain CSV twins (both written by
//! `fixtures/logs/generate.py`, not by this tool); comments, blank-separated columns, integer
//! stamps read exactly, relative and absolute times; located errors, exit code 2, nothing
//! written.

use crate::support::bin;
use std::path::Path;

fn root() -> &'static str {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../..")
}

/// Runs the binary in the repository root; returns (exit code, stdout, stderr).
fn run(args: &[&str]) -> (i32, String, String) {
    let out = bin().current_dir(root()).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn ok(args: &[&str]) -> String {
    let (code, out, err) = run(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// The error of a run that must fail with exit code 2 and write nothing to `-o`.
fn refused(args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.csv");
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["-o", out.to_str().unwrap()]);
    let (code, stdout, err) = run(&all);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert!(stdout.is_empty() && !out.exists(), "{args:?} wrote output");
    err
}

/// A file in a fresh temporary folder (kept alive by the returned guard).
fn file(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    let path = path.to_str().unwrap().to_string();
    (dir, path)
}

const LOGS: &str = "fixtures/logs";

#[test]
fn presets_read_the_keys_of_the_plain_csv() {
    for (log, preset) in [
        ("tum_groundtruth.txt", "tum"),
        ("euroc_groundtruth.csv", "euroc"),
        ("euroc_vicon.csv", "euroc"),
        ("rostopic_pose.csv", "rostopic"),
        ("rostopic_imu.csv", "rostopic"),
    ] {
        let log = format!("{LOGS}/{log}");
        let plain = ok(&["convert", &format!("{log}.expected.csv")]);
        let read = ok(&["convert", &log, "--columns", preset]);
        assert_eq!(read, plain, "{log} --columns {preset}");
        assert!(read.lines().count() == 13, "{read}");
    }
    // The header stamp instead of the receipt time, over the preset.
    assert_eq!(
        ok(&[
            "convert",
            &format!("{LOGS}/rostopic_pose.csv"),
            "--columns",
            "rostopic,time=field.header.stamp"
        ]),
        ok(&[
            "convert",
            &format!("{LOGS}/rostopic_pose.stamp.expected.csv")
        ])
    );
}

#[test]
fn column_maps_by_number_and_by_name() {
    let tum = format!("{LOGS}/tum_groundtruth.txt");
    let plain = ok(&["convert", &format!("{tum}.expected.csv")]);
    assert_eq!(
        ok(&[
            "convert",
            &tum,
            "--columns",
            "time=1,tx=2,ty=3,tz=4,x=5,y=6,z=7,w=8"
        ]),
        plain
    );
    // Names of TUM's `# timestamp tx ty tz qx qy qz qw` comment line.
    assert_eq!(
        ok(&[
            "convert",
            &tum,
            "--columns",
            "time=timestamp,w=qw,x=qx,y=qy,z=qz,tx=tx,ty=ty,tz=tz"
        ]),
        plain
    );
    // EuRoC's names without their units, from its `#timestamp, …` header comment.
    let euroc = format!("{LOGS}/euroc_groundtruth.csv");
    assert_eq!(
        ok(&[
            "convert",
            &euroc,
            "--columns",
            "time=timestamp,w=q_RS_w,x=q_RS_x,y=q_RS_y,z=q_RS_z",
            "--time-unit",
            "ns"
        ]),
        ok(&["convert", &format!("{euroc}.expected.csv")])
            .lines()
            .map(|l| l.split(',').take(5).collect::<Vec<_>>().join(","))
            .collect::<Vec<_>>()
            .join("\n")
            + "\n"
    );
    // interp and reduce read the same keys.
    let frames = ok(&["interp", &euroc, "--columns", "euroc", "--fps", "1000"]);
    assert_eq!(frames.lines().count(), 1 + 51, "{frames}");
}

#[test]
fn comment_lines_are_skipped() {
    let (_d, path) = file(
        "k.csv",
        "# exported by a logger\n#  second comment\ntime,w,x,y,z\n0,1,0,0,0\n# mid-file\n1,0,0,0,1\n",
    );
    let out = ok(&["convert", &path]);
    assert_eq!(
        out,
        "time,w,x,y,z\n0.0,1.0,0.0,0.0,0.0\n1.0,0.0,0.0,0.0,1.0\n"
    );
    // Lines are still counted: the error is on line 6.
    let (_d, bad) = file("k.csv", "# c\ntime,w,x,y,z\n0,1,0,0,0\n# c\n\n1,a,0,0,1\n");
    assert_eq!(
        refused(&["convert", &bad]),
        format!("inbetween: error: {bad}:6: column \"w\": expected a number, found \"a\"\n")
    );
}

#[test]
fn whitespace_separated_columns() {
    let (_d, path) = file("k.txt", "time  w x  y z\n0 1 0 0 0\n  1   0 0\t0 1  \n");
    assert_eq!(
        ok(&["convert", &path]),
        "time,w,x,y,z\n0.0,1.0,0.0,0.0,0.0\n1.0,0.0,0.0,0.0,1.0\n"
    );
    // A tab in the header makes tab the delimiter, unless --delimiter says space.
    let (_d, tabbed) = file("k.txt", "time w x\ty z\n0 1 0\t0 0\n");
    assert!(ok(&["convert", &tabbed, "--delimiter", "space"]).ends_with("0.0,1.0,0.0,0.0,0.0\n"));
    // A log by column numbers, blank-separated, no header.
    let (_d, log) = file("log.txt", "10  1 0 0 0\n12\t0 0 0 1\n");
    assert_eq!(
        ok(&["convert", &log, "--columns", "time=1,w=2,x=3,y=4,z=5"]),
        "time,w,x,y,z\n0.0,1.0,0.0,0.0,0.0\n2.0,0.0,0.0,0.0,1.0\n"
    );
}

#[test]
fn integer_stamps_are_exact() {
    // 1 ns apart, 1.4e18 ns from the epoch: equal as f64, 1e-9 s apart read as integers.
    let (_d, ns) = file(
        "ns.csv",
        "stamp,qw,qx,qy,qz\n1403636579758555392,1,0,0,0\n1403636579758555393,0,0,0,1\n",
    );
    let map = "time=stamp,w=qw,x=qx,y=qy,z=qz";
    assert_eq!(
        ok(&["convert", &ns, "--columns", map, "--time-unit", "ns"]),
        "time,w,x,y,z\n0.0,1.0,0.0,0.0,0.0\n1e-9,0.0,0.0,0.0,1.0\n"
    );
    // Microseconds (PX4 ulog's timestamps): 1 µs apart at 1.4e15 µs.
    let (_d, us) = file(
        "us.csv",
        "stamp,qw,qx,qy,qz\n1403636579758555,1,0,0,0\n1403636579758556,0,0,0,1\n",
    );
    assert_eq!(
        ok(&["convert", &us, "--columns", map, "--time-unit", "us"]),
        "time,w,x,y,z\n0.0,1.0,0.0,0.0,0.0\n1e-6,0.0,0.0,0.0,1.0\n"
    );
}

#[test]
fn times_relative_by_default_or_absolute() {
    let tum = format!("{LOGS}/tum_groundtruth.txt");
    let rel = ok(&["convert", &tum, "--columns", "tum"]);
    assert!(rel.lines().nth(1).unwrap().starts_with("0.0,"), "{rel}");
    let abs = ok(&["convert", &tum, "--columns", "tum", "--times", "absolute"]);
    assert!(
        abs.lines().nth(1).unwrap().starts_with("1305031098.6659,"),
        "{abs}"
    );
    assert!(
        abs.lines().nth(2).unwrap().starts_with("1305031098.6759,"),
        "{abs}"
    );
    assert_eq!(
        ok(&["convert", &tum, "--columns", "tum", "--times", "relative"]),
        rel
    );
}

#[test]
fn bad_logs_are_located_errors() {
    let pose = format!("{LOGS}/rostopic_pose.csv");
    // A mapped column that is not there.
    assert_eq!(
        refused(&[
            "convert",
            &pose,
            "--columns",
            "rostopic,time=field.header.stmp"
        ]),
        format!(
            "inbetween: error: {pose}:1: no column \"field.header.stmp\" for field time (columns: \
             %time,field.header.seq,field.header.stamp,field.header.frame…)\n"
        )
    );
    let head = "%time,field.header.seq,field.header.stamp,field.header.frame_id,field.x,field.y,\
                field.z,field.w\n";
    // A stamp that is not a whole number of nanoseconds.
    let (_d, frac) = file(
        "f.csv",
        &format!("{head}1403636579758555392,0,0,w,0,0,0,1\n1403636579758555392.5,1,0,w,0,0,0,1\n"),
    );
    assert_eq!(
        refused(&["convert", &frac, "--columns", "rostopic"]),
        format!(
            "inbetween: error: {frac}:3: column \"%time\" (time): expected a whole number of \
             nanoseconds, found \"1403636579758555392.5\"\n"
        )
    );
    // Stamps that do not increase (1 ns back: f64 could not see it).
    let (_d, back) = file(
        "b.csv",
        &format!("{head}1403636579758555393,0,0,w,0,0,0,1\n1403636579758555392,1,0,w,0,0,0,1\n"),
    );
    assert_eq!(
        refused(&["convert", &back, "--columns", "rostopic"]),
        format!(
            "inbetween: error: {back}:3: column \"%time\" (time): expected stamps that increase, \
             found 1403636579758555392 after 1403636579758555393 (line 2)\n"
        )
    );
    // A TUM row short of its 8 columns.
    let (_d, short) = file(
        "s.txt",
        "# timestamp tx ty tz qx qy qz qw\n1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1\n",
    );
    assert_eq!(
        refused(&["convert", &short, "--columns", "tum"]),
        format!("inbetween: error: {short}:3: expected at least 8 fields, found 7\n")
    );
    // Options that need --columns, and --columns on what is not CSV.
    let err = refused(&["convert", &pose, "--time-unit", "ns"]);
    assert!(
        err.contains("--time-unit and --times describe the stamps of a log read with --columns"),
        "{err}"
    );
    let err = refused(&["convert", "fixtures/diff/turned.json", "--columns", "tum"]);
    assert!(
        err.contains("a column map reads CSV and text logs"),
        "{err}"
    );
    let err = refused(&[
        "convert",
        &pose,
        "--columns",
        "rostopic",
        "--from",
        "matrix",
    ]);
    assert!(err.contains("holds quaternions"), "{err}");
    let err = refused(&["convert", &pose, "--columns", "ros"]);
    assert!(
        err.contains("expected a preset (tum, euroc, rostopic)"),
        "{err}"
    );
    assert!(Path::new(root()).join(LOGS).join("generate.py").exists());
}
