//! Reading what users and the tool itself write (issue 12): interp's output read back in,
//! spreadsheet CSV, the key rate and the one precedence rule between a document's declarations
//! and the flags.

use crate::support::{bin, rot_angle};
use glam::DQuat;

fn root() -> &'static str {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../..")
}

/// Runs the binary; returns (exit code, stdout, stderr).
fn run(args: &[&str], stdin: Option<&[u8]>) -> (i32, Vec<u8>, String) {
    let mut cmd = bin();
    cmd.current_dir(root()).args(args);
    cmd.write_stdin(stdin.unwrap_or(b""));
    let out = cmd.output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        out.stdout,
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn ok(args: &[&str], stdin: Option<&[u8]>) -> Vec<u8> {
    let (code, out, err) = run(args, stdin);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// One frame as written: track name (empty when none), frame number, time, rotation.
type Row = (String, i64, f64, DQuat);

fn csv_rows(text: &[u8]) -> Vec<Row> {
    let mut rdr = csv::Reader::from_reader(text);
    let h = rdr.headers().unwrap().clone();
    let col = |n: &str| h.iter().position(|c| c == n);
    let (w, x, y, z) = (
        col("w").unwrap(),
        col("x").unwrap(),
        col("y").unwrap(),
        col("z").unwrap(),
    );
    let (frame, time, track) = (col("frame").unwrap(), col("time").unwrap(), col("track"));
    rdr.records()
        .map(|r| {
            let r = r.unwrap();
            let f = |i: usize| r[i].parse::<f64>().unwrap();
            (
                track.map(|i| r[i].to_string()).unwrap_or_default(),
                r[frame].parse().unwrap(),
                f(time),
                DQuat::from_xyzw(f(x), f(y), f(z), f(w)),
            )
        })
        .collect()
}

fn json_rows(text: &[u8]) -> Vec<Row> {
    let v: serde_json::Value = serde_json::from_slice(text).unwrap();
    let mut rows = Vec::new();
    for t in v["tracks"].as_array().unwrap() {
        let name = t["name"].as_str().unwrap_or("").to_string();
        for f in t["frames"].as_array().unwrap() {
            let q: Vec<f64> = f["quat"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            rows.push((
                name.clone(),
                f["frame"].as_i64().unwrap(),
                f["time"].as_f64().unwrap(),
                DQuat::from_xyzw(q[1], q[2], q[3], q[0]),
            ));
        }
    }
    rows
}

/// Same frames (numbers and times exactly, rotations within 1e-12 rad); track names are
/// compared only where the first output has one (interp's JSON leaves an unnamed track unnamed,
/// and a JSON track read without a name is called `track<i>`).
fn assert_same_frames(first: &[Row], again: &[Row], what: &str) {
    assert_eq!(first.len(), again.len(), "{what}: frame count");
    for (a, b) in first.iter().zip(again) {
        if !a.0.is_empty() {
            assert_eq!(a.0, b.0, "{what}: track");
        }
        assert_eq!((a.1, a.2), (b.1, b.2), "{what}: frame and time");
        let d = rot_angle(a.3, b.3);
        assert!(
            d <= 1e-12,
            "{what}: frame {} of {:?} moved {d:e} rad",
            a.1,
            a.0
        );
    }
}

#[test]
fn interp_output_fed_to_interp_at_the_same_rate_reproduces_itself() {
    let cases = [
        ("fixtures/interp/nonuniform.csv", "24"),
        ("fixtures/interp/gimbal_zyx.csv", "10"),
        ("fixtures/interp/multitrack.json", "30"),
        ("fixtures/interp/three_tracks.json", "10"),
        ("fixtures/interp/frames_ntsc.json", "30000/1001"),
    ];
    for (input, fps) in cases {
        for (format, rows) in [
            ("csv", csv_rows as fn(&[u8]) -> Vec<Row>),
            ("json", json_rows),
        ] {
            for velocity in [false, true] {
                let mut args = vec!["interp", input, "--fps", fps, "--output-format", format];
                if velocity {
                    args.push("--velocity");
                }
                let first = ok(&args, None);
                let what = format!("{input} at {fps} fps as {format} (velocity: {velocity})");
                // Read back from standard input (format sniffed) at the same rate; CSV also with
                // --key-fps, which checks every frame number against its time.
                let mut again_args = vec!["interp", "-", "--fps", fps, "--output-format", format];
                if velocity {
                    again_args.push("--velocity");
                }
                let again = ok(&again_args, Some(&first));
                assert_same_frames(&rows(&first), &rows(&again), &what);
                if format == "csv" {
                    again_args.extend(["--key-fps", fps]);
                    let again = ok(&again_args, Some(&first));
                    assert_same_frames(&rows(&first), &rows(&again), &what);
                } else {
                    // interp's JSON declares its rate: --fps may be left out.
                    let again = ok(&["interp", "-", "--output-format", "json"], Some(&first));
                    assert_same_frames(&rows(&first), &rows(&again), &what);
                }
            }
        }
    }
}

#[test]
fn interp_output_is_valid_input_of_every_command() {
    let csv = ok(
        &["interp", "fixtures/interp/nonuniform.csv", "--fps", "24"],
        None,
    );
    let json = ok(
        &[
            "interp",
            "fixtures/interp/multitrack.json",
            "--output-format",
            "json",
            "--velocity",
        ],
        None,
    );
    for (doc, fps) in [(&csv, "24"), (&json, "30")] {
        for cmd in ["convert", "analyze"] {
            ok(&[cmd, "-", "--key-fps", fps], Some(doc));
        }
        ok(&["plot", "-", "-o", "-"], Some(doc));
    }
    // convert keeps interp's times.
    let keys = ok(&["convert", "-", "--output-format", "csv"], Some(&csv));
    let text = String::from_utf8(keys).unwrap();
    assert!(text.starts_with("time,w,x,y,z\n0.0,"), "{text}");
}

#[test]
fn frame_and_time_must_agree_when_the_rate_is_known() {
    let csv = b"frame,time,w,x,y,z\n0,0,1,0,0,0\n1,0.5,0,0,0,1\n";
    // Without a rate the frame numbers are not checked: the time is used.
    let out = ok(&["convert", "-", "--to", "quat"], Some(csv));
    assert!(String::from_utf8(out).unwrap().starts_with("time,"));
    let (code, out, err) = run(&["convert", "-", "--key-fps", "24"], Some(csv));
    assert_eq!((code, out.is_empty()), (2, true));
    assert_eq!(
        err,
        "inbetween: error: <stdin>:3: columns \"frame\" and \"time\": expected frame 1 at 24 fps \
         (--key-fps) to be at time 0.5 s (within 1e-9 s), found 0.041666666666666664 s\n"
    );
    ok(&["convert", "-", "--key-fps", "2"], Some(csv));
    // JSON checks against its declared rate.
    let json = br#"{"fps": 2, "frames": [{"frame": 0, "time": 0, "quat": [1, 0, 0, 0]},
        {"frame": 1, "time": 0.6, "quat": [0, 0, 0, 1]}]}"#;
    let (code, _, err) = run(&["convert", "-"], Some(json));
    assert_eq!(code, 2);
    assert_eq!(
        err,
        "inbetween: error: <stdin>: frames[1]: \"frame\" and \"time\": expected frame 1 at 2 fps \
         (\"fps\") to be at time 0.6 s (within 1e-9 s), found 0.5 s\n"
    );
}

#[test]
fn frames_is_a_synonym_of_keys_and_angular_velocity_belongs_to_frames() {
    let key = r#"{"time": 0, "quat": [1, 0, 0, 0], "angular_velocity": [1, 2, 3]}"#;
    ok(
        &["convert", "-"],
        Some(format!(r#"{{"frames": [{key}]}}"#).as_bytes()),
    );
    ok(
        &["convert", "-"],
        Some(format!(r#"{{"tracks": [{{"frames": [{key}]}}]}}"#).as_bytes()),
    );
    let err = |doc: String| {
        let (code, out, err) = run(&["convert", "-"], Some(doc.as_bytes()));
        assert_eq!((code, out.is_empty()), (2, true), "{doc}");
        err
    };
    let plain = r#"{"time": 0, "quat": [1, 0, 0, 0]}"#;
    assert_eq!(
        err(format!(r#"{{"keys": [{plain}], "frames": [{plain}]}}"#)),
        "inbetween: error: <stdin>: expected \"keys\" or \"frames\", found both\n"
    );
    assert_eq!(
        err(format!(
            r#"{{"tracks": [{{"keys": [{plain}], "frames": [{plain}]}}]}}"#
        )),
        "inbetween: error: <stdin>: tracks[0]: expected \"keys\" or \"frames\", found both\n"
    );
    assert_eq!(
        err(format!(r#"{{"keys": [{key}]}}"#)),
        "inbetween: error: <stdin>: keys[0]: \"angular_velocity\": expected only in \"frames\" \
         (interp's output), found in \"keys\"\n"
    );
    assert_eq!(
        err(
            r#"{"frames": [{"time": 0, "quat": [1, 0, 0, 0], "angular_velocity": [1, 2]}]}"#.into()
        ),
        "inbetween: error: <stdin>: frames[0]: \"angular_velocity\": invalid length 2, expected \
         an array of length 3\n"
    );
}

#[test]
fn spreadsheet_csv_reads_like_plain_csv() {
    let plain = ok(
        &["interp", "-", "--fps", "4"],
        Some(b"time,w,x,y,z\n0,1,0,0,0\n1,0,0,0,1\n"),
    );
    for text in [
        &b"Time, W, X, Y, Z\n0, 1, 0, 0, 0\n1, 0, 0, 0, 1\n"[..],
        b"\xef\xbb\xbfTIME;W;X;Y;Z\r\n0;1;0;0;0\r\n1;0;0;0;1\r\n",
        b" time \t w \t x \t y \t z \n0\t1\t0\t0\t0\n1\t0\t0\t0\t1\n",
    ] {
        assert_eq!(ok(&["interp", "-", "--fps", "4"], Some(text)), plain);
    }
    // --delimiter overrides detection.
    let semi = b"time;w;x;y;z\n0;1;0;0;0\n1;0;0;0;1\n";
    assert_eq!(
        ok(
            &["interp", "-", "--fps", "4", "--delimiter", ";"],
            Some(semi)
        ),
        plain
    );
    let (code, _, err) = run(
        &["interp", "-", "--fps", "4", "--delimiter", ","],
        Some(semi),
    );
    assert_eq!(code, 2);
    assert!(err.ends_with("found time;w;x;y;z\n"), "{err}");
    let tab = b"time\tw\tx\ty\tz\n0\t1\t0\t0\t0\n1\t0\t0\t0\t1\n";
    assert_eq!(
        ok(
            &["interp", "-", "--fps", "4", "--delimiter", "tab"],
            Some(tab)
        ),
        plain
    );
    let (code, _, err) = run(&["interp", "-", "--delimiter", "|"], Some(semi));
    assert_eq!(code, 2);
    assert!(
        err.contains(
            "invalid value '|' for '--delimiter <C>': expected \",\", \";\", \"tab\" or \"space\", \
             found \"|\""
        ),
        "{err}"
    );
}

/// The first frame line of interp's CSV output and the warnings.
fn first_frame(args: &[&str], stdin: &[u8]) -> (String, String) {
    let (code, out, err) = run(args, Some(stdin));
    assert_eq!(code, 0, "{args:?}: {err}");
    let out = String::from_utf8(out).unwrap();
    (out.lines().nth(1).unwrap_or_default().to_string(), err)
}

#[test]
fn key_rate_numbers_the_frames_of_a_document_that_declares_none() {
    let maya = std::fs::read(format!("{}/fixtures/interp/maya_frames.csv", root())).unwrap();
    let euler = ["--from", "euler:xyz"];
    let warning = "inbetween: warning: <stdin>: frame numbers are read at the output rate, 60 \
                   fps, as the document declares no rate; give the keys' rate with --key-fps \
                   RATE\n";
    // Without a rate: read at the output rate, with a warning naming --key-fps.
    let (first, err) = first_frame(
        &[&["interp", "-", "--fps", "60"][..], &euler].concat(),
        &maya,
    );
    assert_eq!(
        (first.split(',').next(), err.as_str()),
        (Some("1"), warning)
    );
    // With --key-fps 24: frame 1 is at 1/24 s, the first 60 fps frame after it is frame 3.
    let args = [
        &["interp", "-", "--fps", "60", "--key-fps", "24"][..],
        &euler,
    ]
    .concat();
    let (first, err) = first_frame(&args, &maya);
    assert!(first.starts_with("3,0.05,"), "{first}");
    assert_eq!(err, "");
    // --key-fps stands in for the missing declaration: it is also the default output rate.
    let (first, _) = first_frame(
        &[&["interp", "-", "--key-fps", "24"][..], &euler].concat(),
        &maya,
    );
    assert!(first.starts_with("1,0.041666666666666664,"), "{first}");
    // No warning for keys in seconds, nor for a document that declares its rate.
    let (_, err) = first_frame(&["interp", "-"], b"time,w,x,y,z\n0,1,0,0,0\n1,0,0,0,1\n");
    assert_eq!(err, "");
    let declared = br#"{"fps": 24, "keys": [{"frame": 0, "quat": [1, 0, 0, 0]},
        {"frame": 24, "quat": [0, 0, 0, 1]}]}"#;
    let (_, err) = first_frame(&["interp", "-", "--fps", "60"], declared);
    assert_eq!(err, "");
    // A JSON document without "fps" takes --key-fps; one with it must agree.
    let undeclared = br#"{"keys": [{"frame": 0, "quat": [1, 0, 0, 0]},
        {"frame": 12, "quat": [0, 0, 0, 1]}]}"#;
    let out = ok(
        &["interp", "-", "--key-fps", "24", "--output-format", "csv"],
        Some(undeclared),
    );
    assert!(
        String::from_utf8(out)
            .unwrap()
            .ends_with("\n12,0.5,0.0,0.0,0.0,1.0\n")
    );
    ok(&["interp", "-", "--key-fps", "24"], Some(declared));
    let (code, _, err) = run(&["interp", "-", "--key-fps", "25"], Some(declared));
    assert_eq!(code, 2);
    assert_eq!(
        err,
        "inbetween: error: <stdin> declares \"fps\": 24 but --key-fps says 25\n"
    );
}

/// The precedence rule, one case per row, run through every command: a document's
/// declarations describe its own values; flags describe only what it leaves undeclared; a flag
/// that contradicts a declaration is an input error naming both; `--fps` is the output rate;
/// `--angles` is the output unit and, without `--input-angles`, the unit of undeclared input
/// angles.
#[test]
fn precedence_table() {
    // 90° about z, keyed at frame 24: at 1 s when the frames are read at 24 fps.
    const DECLARED: &str = r#"{"fps": 24, "rotation": "euler:ZYX", "angles": "rad", "keys": [
        {"frame": 0, "euler": [0, 0, 0]}, {"frame": 24, "euler": [1.5707963267948966, 0, 0]}]}"#;
    const UNDECLARED_DEG: &str =
        r#"[{"frame": 0, "euler": [0, 0, 0]}, {"frame": 24, "euler": [90, 0, 0]}]"#;
    const CSV_DEG: &str = "frame,e1,e2,e3\n0,0,0,0\n24,90,0,0\n";
    const CSV_RAD: &str = "frame,e1,e2,e3\n0,0,0,0\n24,1.5707963267948966,0,0\n";
    // (document, flags, Ok(time of the second key in s) or Err(message)); the second key is
    // always 90° about z when read as intended.
    let table: &[(&str, &[&str], Result<f64, &str>)] = &[
        // Declarations alone.
        (DECLARED, &[], Ok(1.0)),
        // Flags that agree with the declarations.
        (
            DECLARED,
            &[
                "--from",
                "euler:ZYX",
                "--input-angles",
                "rad",
                "--key-fps",
                "24",
            ],
            Ok(1.0),
        ),
        // Flags that contradict them: an error naming both.
        (
            DECLARED,
            &["--from", "euler:XYZ"],
            Err("<stdin> declares \"rotation\": \"euler:ZYX\" but --from says euler:XYZ"),
        ),
        (
            DECLARED,
            &["--from", "quat"],
            Err("<stdin> declares \"rotation\": \"euler:ZYX\" but --from says quat"),
        ),
        (
            DECLARED,
            &["--input-angles", "deg"],
            Err("<stdin> declares \"angles\": \"rad\" but --input-angles says deg"),
        ),
        (
            DECLARED,
            &["--key-fps", "30"],
            Err("<stdin> declares \"fps\": 24 but --key-fps says 30"),
        ),
        // --angles is the output unit: it never conflicts with a declaration.
        (DECLARED, &["--angles", "deg"], Ok(1.0)),
        // --fps is the output rate: the declared fps still numbers the document's frames.
        (DECLARED, &["--fps", "48"], Ok(1.0)),
        (DECLARED, &["--fps", "48", "--key-fps", "24"], Ok(1.0)),
        // Undeclared: the flags say.
        (
            UNDECLARED_DEG,
            &["--from", "euler:ZYX", "--key-fps", "24"],
            Ok(1.0),
        ),
        (
            UNDECLARED_DEG,
            &["--from", "euler:ZYX", "--fps", "24"],
            Ok(1.0),
        ),
        (
            UNDECLARED_DEG,
            &[
                "--from",
                "euler:ZYX",
                "--input-angles",
                "deg",
                "--angles",
                "rad",
                "--key-fps",
                "24",
            ],
            Ok(1.0),
        ),
        (
            CSV_DEG,
            &["--from", "euler:ZYX", "--key-fps", "24"],
            Ok(1.0),
        ),
        (
            CSV_RAD,
            &["--from", "euler:ZYX", "--angles", "rad", "--key-fps", "24"],
            Ok(1.0),
        ),
        (
            CSV_RAD,
            &[
                "--from",
                "euler:ZYX",
                "--input-angles",
                "rad",
                "--key-fps",
                "24",
            ],
            Ok(1.0),
        ),
        (
            CSV_RAD,
            &[
                "--from",
                "euler:ZYX",
                "--input-angles",
                "rad",
                "--angles",
                "deg",
                "--key-fps",
                "12",
            ],
            Ok(2.0),
        ),
    ];
    let quarter = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
    for (doc, flags, want) in table {
        let what = format!("{flags:?} on {}", &doc[..20]);
        let interp_args = [
            &["interp", "-", "--to", "quat", "--output-format", "csv"][..],
            flags,
        ]
        .concat();
        match want {
            Ok(time) => {
                let rows = csv_rows(&ok(&interp_args, Some(doc.as_bytes())));
                let last = rows.last().unwrap();
                assert_eq!(last.2, *time, "{what}: time of the last key");
                let d = rot_angle(last.3, quarter);
                assert!(d < 1e-12, "{what}: the last key is {d} rad off");
                for cmd in ["convert", "analyze"] {
                    ok(&[&[cmd, "-"][..], flags].concat(), Some(doc.as_bytes()));
                }
                ok(
                    &[&["plot", "-", "-o", "-"][..], flags].concat(),
                    Some(doc.as_bytes()),
                );
            }
            Err(message) => {
                for args in [
                    interp_args.clone(),
                    [&["convert", "-"][..], flags].concat(),
                    [&["analyze", "-"][..], flags].concat(),
                    [&["plot", "-", "-o", "-"][..], flags].concat(),
                ] {
                    let (code, out, err) = run(&args, Some(doc.as_bytes()));
                    assert_eq!((code, out.is_empty()), (2, true), "{what}: {args:?}");
                    assert_eq!(err, format!("inbetween: error: {message}\n"), "{args:?}");
                }
            }
        }
    }
    // The output unit is --angles, whatever the input's.
    let out = ok(
        &[
            "convert",
            "-",
            "--from",
            "euler:ZYX",
            "--input-angles",
            "rad",
            "--to",
            "euler:ZYX",
        ],
        Some(CSV_RAD.as_bytes()),
    );
    assert!(
        String::from_utf8(out)
            .unwrap()
            .ends_with("\n24,90.0,0.0,0.0\n")
    );
}
