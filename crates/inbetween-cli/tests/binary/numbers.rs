//! Numbers at the edges (issue 11): values whose squares overflow or underflow, angles that lose
//! their fraction of a turn, rates in exponent notation, times and zeros under `--precision`,
//! and the writers' refusal to write NaN. Expected rotations are closed forms (cos/sin of the
//! half angle); reductions of huge degree values are Python's exact integer arithmetic
//! (`int(1e200) % 360 == 128`).

use crate::support::bin;
use glam::DQuat;

/// Runs the binary with `args` on `stdin`; returns (exit code, stdout, stderr).
fn run(args: &[&str], stdin: &str) -> (i32, String, String) {
    let out = bin().args(args).write_stdin(stdin).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// Asserts an input error: exit 2, exactly this message, nothing on stdout.
#[track_caller]
fn assert_input_error(args: &[&str], stdin: &str, message: &str) {
    let (code, stdout, stderr) = run(args, stdin);
    assert_eq!(stderr, format!("inbetween: error: {message}\n"), "{args:?}");
    assert_eq!(code, 2, "{args:?}");
    assert_eq!(stdout, "", "{args:?}");
}

/// The quaternion of the first row of a CSV output with columns `w,x,y,z`.
fn first_quat(stdout: &str) -> DQuat {
    let mut lines = stdout.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| -> f64 {
        let i = header.iter().position(|c| *c == name).unwrap();
        row[i].parse().unwrap()
    };
    DQuat::from_xyzw(col("x"), col("y"), col("z"), col("w"))
}

/// The rotation by `deg` degrees about the unit axis `(x, y, z)`, by the closed form.
fn closed_form(axis: [f64; 3], deg: f64) -> DQuat {
    let h = deg.to_radians() / 2.0;
    DQuat::from_xyzw(
        axis[0] * h.sin(),
        axis[1] * h.sin(),
        axis[2] * h.sin(),
        h.cos(),
    )
}

#[track_caller]
fn assert_quat_close(got: DQuat, want: DQuat) {
    assert!(
        (got - want).length() < 1e-15 || (got + want).length() < 1e-15,
        "{got} vs {want}"
    );
}

// --- 1. Overflow-safe numerics -----------------------------------------------------------

#[test]
fn huge_rotation_vector_is_an_input_error() {
    // It used to write NaN rows (bare NaN in JSON), or stop on "found norm NaN".
    let csv = "time,rx,ry,rz\n0,1e300,0,0\n1,0,1,0\n";
    let msg = "<stdin>:2: columns rx,ry,rz: expected a rotation vector no longer than 1e15 deg, \
               found length 1e300";
    for args in [
        &["interp", "-", "--fps", "2"][..],
        &["interp", "-", "--fps", "2", "--output-format", "json"],
        &["convert", "-"],
        &["analyze", "-"],
    ] {
        assert_input_error(args, csv, msg);
    }
    assert_input_error(
        &["interp", "-", "--fps", "2", "--angles", "rad"],
        "time,rx,ry,rz\n0,0,1e200,0\n1,0,1,0\n",
        "<stdin>:2: columns rx,ry,rz: expected a rotation vector no longer than 1e15 rad, \
         found length 1e200",
    );
}

#[test]
fn huge_radian_angles_are_input_errors() {
    assert_input_error(
        &["convert", "-", "--angles", "rad"],
        "time,ax,ay,az,angle\n0,1,0,0,1e300\n1,1,0,0,0\n",
        "<stdin>:2: columns ax,ay,az,angle: expected an angle within ±1e15 rad, found 1e300",
    );
    assert_input_error(
        &["convert", "-", "--from", "euler:ZYX", "--angles", "rad"],
        "time,e1,e2,e3\n0,0,0,-1e300\n1,0,0,0\n",
        "<stdin>:2: columns e1,e2,e3: expected Euler angles within ±1e15 rad, found e3 = -1e300",
    );
    assert_input_error(
        &["convert", "-"],
        r#"{"angles": "rad", "keys": [{"time": 0, "axis_angle": [0, 1, 0, 2e15]}]}"#,
        "<stdin>: keys[0]: \"axis_angle\": expected an angle within ±1e15 rad, found 2e15",
    );
}

#[test]
fn huge_degree_angles_are_reduced_exactly() {
    // 1e200° ≡ 128° (int(1e200) % 360 == 128): about z, and as the Y angle of ZYX.
    let (code, stdout, stderr) = run(
        &["convert", "-"],
        "time,ax,ay,az,angle\n0,0,0,5,1e200\n1,0,0,1,0\n",
    );
    assert_eq!((code, stderr.as_str()), (0, ""));
    assert_quat_close(first_quat(&stdout), closed_form([0.0, 0.0, 1.0], 128.0));
    let (code, stdout, _) = run(
        &["convert", "-", "--from", "euler:ZYX"],
        "time,e1,e2,e3\n0,0,1e200,0\n1,0,0,0\n",
    );
    assert_eq!(code, 0);
    assert_quat_close(first_quat(&stdout), closed_form([0.0, 1.0, 0.0], 128.0));
}

#[test]
fn huge_quaternion_is_normalised() {
    // It came out as 0,0,0,0 after a "normalized" warning that gave the norm as inf.
    let (code, stdout, stderr) = run(
        &["convert", "-"],
        "time,w,x,y,z\n0,1e200,0,0,0\n1,1,0,0,0\n",
    );
    assert_eq!(code, 0);
    assert_eq!(
        stdout,
        "time,w,x,y,z\n0.0,1.0,0.0,0.0,0.0\n1.0,1.0,0.0,0.0,0.0\n"
    );
    assert_eq!(
        stderr,
        "inbetween: warning: <stdin>:2: quaternion norm 1e200 is off 1 by more than 1e-3; \
         normalized\n"
    );
}

#[test]
fn huge_and_tiny_axes_are_normalised() {
    // (1e200, 0, 0) with 90° silently became the identity; (1e-320, 0, 0) an "axis (0, 0, 0)"
    // error.
    for axis in ["1e200,0,0", "1e-320,0,0"] {
        let (code, stdout, stderr) = run(
            &["convert", "-"],
            &format!("time,ax,ay,az,angle\n0,{axis},90\n1,1,0,0,0\n"),
        );
        assert_eq!((code, stderr.as_str()), (0, ""), "{axis}");
        assert_quat_close(first_quat(&stdout), closed_form([1.0, 0.0, 0.0], 90.0));
    }
    // Through interp too: frame 0 is the key.
    let (code, stdout, _) = run(
        &["interp", "-", "--fps", "2"],
        "time,ax,ay,az,angle\n0,1e200,0,0,90\n1,1,0,0,0\n",
    );
    assert_eq!(code, 0);
    assert_quat_close(first_quat(&stdout), closed_form([1.0, 0.0, 0.0], 90.0));
}

#[test]
fn tiny_and_huge_numbers_keep_their_digits_in_messages() {
    // The norm of (1e-300, 0, 0, 0) underflowed and was printed as 0e0.
    assert_input_error(
        &["convert", "-"],
        "time,w,x,y,z\n0,1e-300,0,0,0\n1,1,0,0,0\n",
        "<stdin>:2: columns w,x,y,z: expected a quaternion of non-zero length, found norm 1e-300",
    );
    // 1e200·I: ‖RᵀR − I‖ = √3·1e400 (it was inf).
    assert_input_error(
        &["convert", "-"],
        "time,m00,m01,m02,m10,m11,m12,m20,m21,m22\n0,1e200,0,0,0,1e200,0,0,0,1e200\n",
        "<stdin>:2: columns m00,m01,m02,m10,m11,m12,m20,m21,m22: expected an orthonormal \
         rotation matrix (‖RᵀR − I‖ ≤ 1e-3), found ‖RᵀR − I‖ = 1.732e400",
    );
    // diag(−1e-200, 1e-200, 1e-200): a reflection of determinant −1e-600 (it underflowed to 0,
    // and the sign was lost).
    assert_input_error(
        &["convert", "-"],
        "time,m00,m01,m02,m10,m11,m12,m20,m21,m22\n0,-1e-200,0,0,0,1e-200,0,0,0,1e-200\n",
        "<stdin>:2: columns m00,m01,m02,m10,m11,m12,m20,m21,m22: expected a rotation matrix, \
         found a reflection (determinant -1e-600)",
    );
}

// --- 2. Output never holds NaN, infinity or a zero quaternion ------------------------------

#[test]
fn a_non_finite_frame_is_never_written_and_leaves_the_output_untouched() {
    // An end velocity of 1e300 rad/s (not bounded on input) makes the curve non-finite; it used
    // to be written as NaN. Whatever the input rule becomes, the output must hold no NaN and an
    // existing -o file must survive.
    let doc = r#"{"keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "quat": [1, 0, 0, 0]}]}"#;
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out.json");
    std::fs::write(&target, "precious\n").unwrap();
    for format in ["csv", "json", "npy"] {
        let args = [
            "interp",
            "-",
            "--fps",
            "4",
            "--angles",
            "rad",
            "--start-velocity",
            "1e300,0,0",
            "--output-format",
            format,
        ];
        let out = bin().args(args).write_stdin(doc).output().unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(!out.status.success(), "{format}");
        assert!(
            !stdout.contains("NaN") && !stdout.contains("inf"),
            "{stdout}"
        );
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(stderr.starts_with("inbetween: error: "), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        let out = bin()
            .args(args)
            .args(["-o", target.to_str().unwrap()])
            .write_stdin(doc)
            .output()
            .unwrap();
        assert!(!out.status.success(), "{format}");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "precious\n");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

// --- 3. Consistency ------------------------------------------------------------------------

#[test]
fn rates_parse_the_same_in_every_spelling() {
    // Keys 1e-6 s apart: 11 frames at 1e7 fps.
    let csv = "time,w,x,y,z\n0,1,0,0,0\n0.000001,0,1,0,0\n";
    let (code, plain, stderr) = run(&["interp", "-", "--fps", "10000000"], csv);
    assert_eq!((code, stderr.as_str()), (0, ""));
    assert_eq!(plain.lines().count(), 12);
    for spelling in ["1e7", "1E7", "1e+7", "10e6", "0.1e8"] {
        let (code, out, stderr) = run(&["interp", "-", "--fps", spelling], csv);
        assert_eq!((code, stderr.as_str()), (0, ""), "{spelling}");
        assert_eq!(out, plain, "{spelling}");
    }
    // 1.2e-1 is the exact decimal 0.12 = 3/25.
    let (code, out, _) = run(
        &["interp", "-", "--fps", "1.2e-1", "--output-format", "json"],
        "time,w,x,y,z\n0,1,0,0,0\n100,1,0,0,0\n",
    );
    assert_eq!(code, 0);
    assert!(out.starts_with("{\"fps\": \"3/25\", "), "{out}");
    // Out of range in any spelling: the range message, the value as written.
    for spelling in ["1e8", "10000001", "1.5e7"] {
        let (code, _, stderr) = run(&["interp", "-", "--fps", spelling], csv);
        assert_eq!(code, 2);
        assert_eq!(
            stderr.lines().next().unwrap(),
            format!(
                "error: invalid value '{spelling}' for '--fps <RATE>': expected a frame rate \
                 between 1e-6 and 1e7 frames per second, found {spelling}"
            )
        );
    }
}

#[test]
fn a_zero_ratio_is_quoted_once() {
    // It read `'0/0' for '--fps <RATE>': "0/0": expected …`.
    let (code, _, stderr) = run(
        &["interp", "-", "--fps", "0/0"],
        "time,w,x,y,z\n0,1,0,0,0\n1,1,0,0,0\n",
    );
    assert_eq!(code, 2);
    assert_eq!(
        stderr.lines().next().unwrap(),
        "error: invalid value '0/0' for '--fps <RATE>': expected a positive frame rate, found 0/0"
    );
}

#[test]
fn precision_applies_to_rotations_not_times_and_never_writes_minus_zero() {
    // With --precision 1 the times 1/30 and 2/30 were written 0.0 and 0.1, and x = −1e-9 as -0.0.
    let csv = "time,w,x,y,z\n0,1,0,0,0\n0.1,1,-1e-9,0,0\n";
    let (code, out, _) = run(&["interp", "-", "--precision", "1"], csv);
    assert_eq!(code, 0);
    assert_eq!(
        out,
        "frame,time,w,x,y,z\n\
         0,0.0,1.0,0.0,0.0,0.0\n\
         1,0.03333333333333333,1.0,0.0,0.0,0.0\n\
         2,0.06666666666666667,1.0,0.0,0.0,0.0\n\
         3,0.1,1.0,0.0,0.0,0.0\n"
    );
    // convert: key times too.
    let (code, out, _) = run(
        &["convert", "-", "--precision", "2"],
        "time,w,x,y,z\n0.125,1,-1e-9,0,0\n",
    );
    assert_eq!(code, 0);
    assert_eq!(out, "time,w,x,y,z\n0.125,1.00,0.00,0.00,0.00\n");
}
