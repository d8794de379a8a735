//! AMASS `.npz` motion files (fixtures/amass, made by `generate.py` with numpy): read as 52 or
//! 55 joint tracks, written back in their own layout at the output rate by `interp -o out.npz`,
//! and refused, exit 2, with the file and the key named when malformed. The expected rotations
//! are the source's rotation vectors turned into rotations here (glam's `from_scaled_axis`),
//! the expected times exact fractions of the output rate; crates/inbetween-py/tests/test_amass.py
//! checks the written files with numpy and scipy.

use crate::support::{bin, fixtures, rot_angle, stderr_of, stdout_of};
use glam::{DQuat, DVec3};
use inbetween_io::amass::{self, Amass, Kind};

fn load(path: &std::path::Path) -> Amass {
    let bytes = std::fs::read(path).unwrap();
    amass::read(&bytes, &path.display().to_string(), None).unwrap()
}

fn rot(v: [f64; 3]) -> DQuat {
    DQuat::from_scaled_axis(DVec3::from_array(v))
}

/// `interp <fixture> --fps 30 -o out.npz` and the same frames as CSV rotation vectors in radians.
fn resampled(name: &str) -> (Amass, Amass, Vec<Vec<String>>, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("amass").join(name);
    let out = dir.path().join("out.npz");
    stdout_of(
        bin()
            .args([
                "interp".as_ref(),
                src.as_os_str(),
                "--fps".as_ref(),
                "30".as_ref(),
            ])
            .arg("-o")
            .arg(&out),
    );
    let csv = stdout_of(bin().arg("interp").arg(&src).args([
        "--fps",
        "30",
        "--to",
        "rotvec",
        "--angles",
        "rad",
        "--output-format",
        "csv",
    ]));
    let rows = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (load(&src), load(&out), rows, dir)
}

/// Every written frame against the CSV frames of the same curves: the time of row k of a
/// track is k/30 s within 1e-9 s, and its rotation is the npz's row k within 1e-12 rad.
fn check_clock(out: &Amass, rows: &[Vec<String>]) {
    let joints = out.model().joint_count();
    assert_eq!(rows.len(), joints * out.frames());
    for (n, row) in rows.iter().enumerate() {
        let (j, k) = (n / out.frames(), n % out.frames());
        assert_eq!(row[1].parse::<usize>().unwrap(), k);
        let t: f64 = row[2].parse().unwrap();
        assert!((t - k as f64 / 30.0).abs() < 1e-9, "frame {k}: {t} s");
        let v: Vec<f64> = row[3..6].iter().map(|x| x.parse().unwrap()).collect();
        let angle = rot_angle(rot([v[0], v[1], v[2]]), rot(out.rotvec(k, j)));
        assert!(angle < 1e-12, "joint {j} frame {k}: {angle:e} rad");
    }
}

#[test]
fn resampled_120_to_30_keeps_every_fourth_frame_in_the_layout_amass_users_load() {
    let (src, out, rows, _dir) = resampled("smplh_120.npz");
    assert_eq!(
        (out.frames(), out.fps().num(), out.fps().den()),
        (16, 30, 1)
    );
    let keys = |a: &Amass| -> Vec<(String, String, Vec<u64>)> {
        a.arrays()
            .iter()
            .map(|(k, x)| (k.clone(), x.descr.clone(), x.shape.clone()))
            .collect()
    };
    let (mut want, got) = (keys(&src), keys(&out));
    for (k, _, shape) in &mut want {
        if ["poses", "trans", "dmpls"].contains(&k.as_str()) {
            shape[0] = 16;
        }
    }
    assert_eq!(got, want);
    for k in 0..16 {
        for j in 0..52 {
            let angle = rot_angle(rot(out.rotvec(k, j)), rot(src.rotvec(4 * k, j)));
            assert!(angle < 1e-12, "joint {j} frame {k}: {angle:e} rad");
        }
    }
    let floats = |a: &Amass, key: &str| {
        a.arrays()
            .iter()
            .find(|(k, _)| k == key)
            .unwrap()
            .1
            .floats()
            .unwrap()
    };
    let (t0, t1) = (floats(&src, "trans"), floats(&out, "trans"));
    assert!((0..16).all(|k| t1[3 * k..3 * k + 3] == t0[12 * k..12 * k + 3]));
    assert_eq!(floats(&out, "mocap_framerate"), vec![30.0]);
    let gender = |a: &Amass| {
        a.arrays()
            .iter()
            .find(|(k, _)| k == "gender")
            .unwrap()
            .1
            .clone()
    };
    assert_eq!(
        (gender(&out).kind, gender(&out).bytes),
        (Kind::Other, gender(&src).bytes)
    );
    check_clock(&out, &rows);
}

#[test]
fn resampled_5994_to_30_is_on_the_exact_clock_where_a_stride_of_two_drifts() {
    let (src, out, rows, _dir) = resampled("smplh_5994_compressed.npz");
    // 61 frames at 60000/1001 span 1.001 s: frames 0..=30 at 30 fps.
    assert_eq!((src.fps().num(), src.fps().den()), (60000, 1001));
    assert_eq!(out.frames(), 31);
    check_clock(&out, &rows);
    for j in 0..52 {
        assert!(rot_angle(rot(out.rotvec(0, j)), rot(src.rotvec(0, j))) < 1e-12);
    }
    // poses[::2] puts source frame 60 (1.001 s) where frame 30 (1 s) belongs: the turn the
    // motion makes in that millisecond, far above the clock's error.
    let drift = (0..52)
        .map(|j| rot_angle(rot(out.rotvec(30, j)), rot(src.rotvec(60, j))))
        .fold(0.0, f64::max);
    assert!(drift > 1e-4, "{drift}");
}

#[test]
fn smplx_files_keep_their_rate_key_and_split_arrays_from_the_curves() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("amass/smplx_60.npz");
    let out = dir.path().join("x.npz");
    stdout_of(
        bin()
            .arg("interp")
            .arg(&src)
            .args(["--fps", "30", "-o"])
            .arg(&out),
    );
    let (src, out) = (load(&src), load(&out));
    assert_eq!(
        (out.model(), out.frames(), out.rate_key()),
        (amass::Model::SmplX, 16, Some("mocap_frame_rate"))
    );
    let floats = |key: &str| {
        out.arrays()
            .iter()
            .find(|(k, _)| k == key)
            .unwrap()
            .1
            .floats()
            .unwrap()
    };
    let (hand, jaw) = (floats("pose_hand"), floats("pose_jaw"));
    for k in 0..16 {
        assert_eq!(&hand[90 * k..90 * k + 3], &out.rotvec(k, 25)[..]);
        assert_eq!(&jaw[3 * k..3 * k + 3], &out.rotvec(k, 22)[..]);
        assert!(rot_angle(rot(out.rotvec(k, 54)), rot(src.rotvec(2 * k, 54))) < 1e-12);
    }
}

#[test]
fn malformed_archives_are_refused_naming_the_file_and_the_key() {
    for (name, want) in [
        (
            "bad_truncated.npz",
            "bad_truncated.npz: not a readable zip archive (.npz): no end of central directory record (truncated?)",
        ),
        ("bad_no_poses.npz", "bad_no_poses.npz: no key \"poses\""),
        (
            "bad_shape.npz",
            "bad_shape.npz: key \"poses\": expected float rotation vectors of shape (frames, 156) (SMPL-H) or (frames, 165) (SMPL-X), found <f8 of shape (61, 72)",
        ),
        (
            "bad_object.npz",
            "bad_object.npz: key \"gender\": an object array (dtype |O), which only pickle can read",
        ),
    ] {
        let path = fixtures().join("amass").join(name);
        for out in ["o.npz", "o.csv"] {
            let dir = tempfile::tempdir().unwrap();
            let err = stderr_of(
                bin()
                    .arg("interp")
                    .arg(&path)
                    .arg("-o")
                    .arg(dir.path().join(out)),
                2,
            );
            assert!(err.contains(want), "{name}: {err}");
            assert!(!err.contains("panicked"));
        }
    }
}

#[test]
fn options_amass_output_cannot_carry_are_refused() {
    let src = fixtures().join("amass/smplh_120.npz");
    let err = stderr_of(
        bin()
            .arg("interp")
            .arg(&src)
            .args(["--tracks", "pelvis", "-o", "x.npz"]),
        2,
    );
    assert!(
        err.contains("--tracks: AMASS npz output writes every joint"),
        "{err}"
    );
    let err = stderr_of(
        bin()
            .arg("interp")
            .arg(&src)
            .args(["--key-fps", "60", "-o", "x.npz"]),
        2,
    );
    assert!(
        err.contains("declares \"mocap_framerate\": 120 but --key-fps says 60"),
        "{err}"
    );
}
