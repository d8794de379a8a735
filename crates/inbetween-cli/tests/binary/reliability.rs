//! Reliability (issue 7): input that is messy but valid, numeric extremes, output that is never
//! half-written, and a closed stdout.

use crate::support::{bake_frames, interpolate, settings, track};
use assert_cmd::Command;
use glam::{DQuat, DVec3};
use inbetween::{EndConditions, Ends, Scheme};
use std::io::Read;
use std::process::Stdio;

fn root() -> &'static str {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../..")
}

fn sane(frames: &[(i64, f64, DQuat)]) {
    for (k, t, q) in frames {
        assert!(t.is_finite() && q.is_finite(), "frame {k}");
        assert!(
            (q.length() - 1.0).abs() < 1e-9,
            "frame {k}: |q| = {}",
            q.length()
        );
    }
}

#[test]
fn bom_crlf_spaces_quotes_and_blank_lines_are_accepted() {
    let run = |f: &str| {
        let out = Command::cargo_bin("inbetween")
            .unwrap()
            .current_dir(root())
            .args(["interp", f, "--fps", "10"])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(out.stderr.is_empty());
        out.stdout
    };
    assert_eq!(run("fixtures/ok/messy.csv"), run("fixtures/ok/clean.csv"));
}

#[test]
fn a_million_keys() {
    let n = 1_000_000;
    let quats = (0..n)
        .map(|i| {
            DQuat::from_axis_angle(
                DVec3::new(1.0, (i % 7) as f64, 2.0).normalize(),
                0.001 * i as f64,
            )
        })
        .collect();
    let t = track((0..n).map(|i| i as f64 * 0.1).collect(), quats);
    let (frames, warnings) = interpolate(
        &t,
        &settings(Scheme::Hermite, "10", EndConditions::default()),
    );
    assert_eq!(frames.len(), n);
    assert!(warnings.is_empty());
    sane(&frames);
}

#[test]
fn ten_thousand_fps_and_durations_of_days() {
    let q = [
        DQuat::IDENTITY,
        DQuat::from_rotation_y(2.0),
        DQuat::from_rotation_x(1.0),
    ];
    // 10⁴ fps over 10 s.
    let t = track(vec![0.0, 4.0, 10.0], q.to_vec());
    let (frames, _) = interpolate(
        &t,
        &settings(Scheme::Squad, "10000", EndConditions::default()),
    );
    assert_eq!(frames.len(), 100_001);
    sane(&frames);
    // Three days at one frame per 100 s.
    let day = 86_400.0;
    let t = track(vec![0.0, day, 3.0 * day], q.to_vec());
    let (frames, _) = interpolate(
        &t,
        &settings(Scheme::Hermite, "0.01", EndConditions::default()),
    );
    assert_eq!(frames.len(), 2593);
    sane(&frames);
    // Frame numbers beyond 2³²: five days in, at 10⁴ fps.
    let t0 = 5.0 * day;
    let t = track(vec![t0, t0 + 0.5, t0 + 1.0], q.to_vec());
    for scheme in [Scheme::Hermite, Scheme::MinAccel] {
        let (frames, _) = interpolate(&t, &settings(scheme, "10000", EndConditions::default()));
        assert_eq!(frames.len(), 10_001);
        assert_eq!(frames[0].0, 4_320_000_000);
        assert!(frames[0].0 > 1 << 32);
        assert_eq!(frames[0].1, t0);
        assert_eq!(frames[10_000].1, t0 + 1.0);
        assert_eq!(frames[0].2, q[0]);
        sane(&frames);
    }
}

#[test]
fn end_velocities_of_a_thousand_turns_per_second() {
    let omega = DVec3::new(0.0, 0.0, 1000.0 * std::f64::consts::TAU);
    let t = track(
        vec![0.0, 1.0],
        vec![DQuat::IDENTITY, DQuat::from_rotation_x(0.5)],
    );
    let e = EndConditions {
        ends: Ends::Chord,
        start: Some(omega),
        end: Some(-omega),
    };
    for scheme in [
        Scheme::Hermite,
        Scheme::Squad,
        Scheme::Bezier,
        Scheme::Slerp,
        Scheme::MinAccel,
    ] {
        let (frames, _) = interpolate(&t, &settings(scheme, "30", e));
        assert_eq!(frames.len(), 31, "{scheme:?}");
        sane(&frames);
    }
}

#[test]
fn segments_of_a_nanosecond() {
    let t = track(
        vec![0.0, 1e-9, 0.5, 0.5 + 1e-9, 1.0],
        vec![
            DQuat::IDENTITY,
            DQuat::from_rotation_x(1e-6),
            DQuat::from_rotation_y(1.0),
            DQuat::from_rotation_y(1.0 + 1e-7),
            DQuat::from_rotation_z(0.3),
        ],
    );
    for scheme in [
        Scheme::Hermite,
        Scheme::Squad,
        Scheme::Bezier,
        Scheme::Slerp,
        Scheme::MinAccel,
    ] {
        let (frames, _) = interpolate(&t, &settings(scheme, "30", EndConditions::default()));
        assert_eq!(frames.len(), 31, "{scheme:?}");
        // Frame 0 is exactly key 0 (not key 1, 1 ns later).
        assert_eq!(frames[0].2, DQuat::IDENTITY, "{scheme:?}");
        sane(&frames);
    }
}

/// The second track fails after the first was streamed: the existing `-o` file is untouched and
/// no temporary file is left.
#[test]
fn failure_halfway_leaves_the_output_file_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("frames.csv");
    std::fs::write(&target, "precious\n").unwrap();
    let out = Command::cargo_bin("inbetween")
        .unwrap()
        .current_dir(root())
        .args([
            "interp",
            "fixtures/bad/minaccel_grid_too_large.json",
            "--scheme",
            "minaccel",
            "-o",
        ])
        .arg(&target)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("track \"spin\": minaccel would need"));
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "precious\n");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    // And a good run replaces it, with ordinary permissions.
    let ok = Command::cargo_bin("inbetween")
        .unwrap()
        .current_dir(root())
        .args(["interp", "fixtures/interp/uniform.json", "-o"])
        .arg(&target)
        .output()
        .unwrap();
    assert!(ok.status.success());
    // JSON keys in, `-o frames.csv`: the extension chooses CSV.
    assert!(
        std::fs::read_to_string(&target)
            .unwrap()
            .starts_with("frame,time,w,x,y,z\n")
    );
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // Replaced: the mode of the file it replaced, 0666 less the umask.
        let mode = std::fs::metadata(&target).unwrap().permissions().mode() & 0o777;
        let umask = std::process::Command::new("sh")
            .args(["-c", "umask"])
            .output()
            .unwrap();
        let umask = u32::from_str_radix(String::from_utf8(umask.stdout).unwrap().trim(), 8);
        assert_eq!(mode, 0o666 & !umask.unwrap(), "mode {mode:o}");
    }
}

/// `inbetween interp big.csv | head -1`: the reader goes away; the tool ends quietly.
#[test]
fn closed_stdout_ends_quietly() {
    let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("inbetween"))
        .current_dir(root())
        .args([
            "interp",
            "fixtures/interp/uniform.json",
            "--fps",
            "100000",
            "--output-format",
            "csv",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 64];
    stdout.read_exact(&mut first).unwrap();
    drop(stdout);
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    assert!(stderr.is_empty(), "{stderr}");
    assert!(status.success(), "{status:?}");
}

/// Keys closer together than one frame period: no frame to write, and no command panics.
#[test]
fn a_track_that_spans_no_frame() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("c.svg");
    let input = "time,w,x,y,z\n0.01,1,0,0,0\n0.02,0,1,0,0\n";
    for args in [
        vec!["interp"],
        vec!["interp", "--scheme", "minaccel"],
        vec!["analyze"],
        vec!["plot", "--what", "energy", "-o", svg.to_str().unwrap()],
        vec!["plot", "--what", "speed", "-o", svg.to_str().unwrap()],
    ] {
        let out = Command::cargo_bin("inbetween")
            .unwrap()
            .args(&args)
            .args(["-", "--input-format", "csv"])
            .write_stdin(input)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// `--output-format npy`: a valid .npy v1.0 header with the frame count and columns, rows equal
/// to the CSV output (shortest round-trip digits read back exactly).
#[test]
fn npy_reads_back_as_the_csv_values() {
    let dir = tempfile::tempdir().unwrap();
    let npy = dir.path().join("f.npy");
    let run = |args: &[&str]| {
        let out = Command::cargo_bin("inbetween")
            .unwrap()
            .current_dir(root())
            .args([
                "interp",
                "fixtures/interp/multitrack.json",
                "--velocity",
                "--to",
                "euler:ZYX",
            ])
            .args(args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        out.stdout
    };
    run(&["--output-format", "npy", "-o", npy.to_str().unwrap()]);
    let csv_out = run(&["--output-format", "csv"]);
    let bytes = std::fs::read(&npy).unwrap();
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
    let hlen = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!((10 + hlen) % 64, 0);
    let header = std::str::from_utf8(&bytes[10..10 + hlen]).unwrap();
    let mut rdr = csv::Reader::from_reader(csv_out.as_slice());
    let rows: Vec<Vec<f64>> = rdr
        .records()
        .map(|r| {
            let r = r.unwrap();
            // track name -> index in order of appearance
            let idx = if &r[0] == "hip" { 0.0 } else { 1.0 };
            std::iter::once(idx)
                .chain(r.iter().skip(1).map(|x| x.parse::<f64>().unwrap()))
                .collect()
        })
        .collect();
    let cols = rows[0].len();
    assert_eq!(cols, 1 + 2 + 3 + 3);
    assert_eq!(
        header.trim_end(),
        format!(
            "{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {cols}), }}",
            rows.len()
        )
    );
    let data: Vec<f64> = bytes[10 + hlen..]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(data.len(), rows.len() * cols);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(&data[i * cols..(i + 1) * cols], row.as_slice(), "row {i}");
    }
}

/// Found by the `interp_pipeline` fuzzer (a timeout under instrumentation): minaccel with a start
/// velocity of about 23 turns/s beside a 66 s segment. Far from any minimum, the solver crawls
/// along an ill-conditioned valley; within its budget it must still give finite unit frames and
/// say on stderr that it did not converge. (0.1 s in release.)
#[test]
fn regression_fuzz_minaccel_slow_start() {
    let out = Command::cargo_bin("inbetween")
        .unwrap()
        .current_dir(root())
        .args([
            "interp",
            "fixtures/ok/fuzz_minaccel_slow.csv",
            "--scheme",
            "minaccel",
            "--fps",
            "24",
            "--angles",
            "rad",
            "--start-velocity=-63.5,31.75,-127",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("minaccel did not converge in 100 iterations"),
        "{stderr}"
    );
    let mut rdr = csv::Reader::from_reader(out.stdout.as_slice());
    let mut n = 0;
    for rec in rdr.records() {
        let v: Vec<f64> = rec.unwrap().iter().map(|x| x.parse().unwrap()).collect();
        let norm = (v[2] * v[2] + v[3] * v[3] + v[4] * v[4] + v[5] * v[5]).sqrt();
        assert!((norm - 1.0).abs() < 1e-12, "frame {}", v[0]);
        n += 1;
    }
    assert_eq!(n, 67 * 24 + 1);
}

/// Long tracks are generated on two threads: the frames (bit for bit) and the warnings, in
/// order, are those of one thread.
#[test]
fn two_thread_generation_gives_the_same_frames() {
    let n = 260;
    let quats = (0..n)
        .map(|i| {
            let a = i as f64;
            DQuat::from_axis_angle(
                DVec3::new(a.sin(), 0.4, (0.3 * a).cos()).normalize(),
                0.7 * a,
            )
        })
        .collect();
    // 259 s at 1000 fps: 259 001 frames, above the two-thread threshold.
    let t = track((0..n).map(|i| i as f64).collect(), quats);
    for scheme in [Scheme::Hermite, Scheme::Bezier, Scheme::Slerp] {
        let mut s = settings(scheme, "1000", EndConditions::default());
        s.velocity = true;
        let (par, warn_par) = bake_frames(&t, &s);
        s.parallel = false;
        let (seq, warn_seq) = bake_frames(&t, &s);
        assert_eq!(par.len(), 259_001);
        assert_eq!(warn_par, warn_seq);
        // Rotations and velocities, bit for bit.
        assert!(par == seq, "{scheme:?}");
    }
}
