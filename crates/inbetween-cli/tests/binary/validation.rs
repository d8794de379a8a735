//! Validate before the first byte (issue 11): everything the input can get wrong is found before
//! anything is written, so a failing run writes nothing at all; and warnings are bounded.

use crate::support::bin;

/// Two tracks: "big" writes about 18 MB of frames (past every buffer, so it would reach stdout or
/// the file), "spin" exceeds minaccel's grid cap.
fn two_tracks(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("two.json");
    std::fs::write(
        &path,
        r#"{"tracks": [
{"name": "big", "keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 300, "quat": [0, 1, 0, 0]}]},
{"name": "spin", "start_velocity": [0, 0, 1e15],
 "keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "quat": [0, 1, 0, 0]}]}]}"#,
    )
    .unwrap();
    path
}

#[test]
fn a_failing_second_track_writes_nothing_to_stdout() {
    let dir = tempfile::tempdir().unwrap();
    let keys = two_tracks(dir.path());
    let out = bin()
        .args(["interp", "--scheme", "minaccel", "--fps", "1000"])
        .arg(&keys)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(out.stdout.len(), 0, "bytes written before the error");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with(&format!(
            "inbetween: error: {}: track \"spin\": minaccel would need a grid of",
            keys.display()
        )),
        "{stderr}"
    );
    // Without the failing scheme the same run writes over 8 MiB (300 001 frames of "big" alone):
    // enough to have left every buffer had the tracks been streamed before checking.
    let big = bin()
        .args(["interp", "--fps", "1000", "--scheme", "slerp"])
        .arg(&keys)
        .output()
        .unwrap();
    assert!(big.status.success());
    assert!(big.stdout.len() > 8 << 20, "{} bytes", big.stdout.len());
}

#[test]
fn a_failing_second_track_leaves_the_file_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let keys = two_tracks(dir.path());
    let target = dir.path().join("frames.csv");
    std::fs::write(&target, "precious\n").unwrap();
    let out = bin()
        .args(["interp", "--scheme", "minaccel", "--fps", "1000", "-o"])
        .arg(&target)
        .arg(&keys)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "precious\n");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn too_many_frames_are_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    let keys = dir.path().join("long.csv");
    std::fs::write(&keys, "time,w,x,y,z\n0,1,0,0,0\n1e9,1,0,0,0\n").unwrap();
    let out = bin()
        .args(["interp", "--fps", "30"])
        .arg(&keys)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "inbetween: error: {}: interp would write 30000000001 frames at 30 fps, more than \
             --max-frames 1000000000\n",
            keys.display()
        )
    );
    // The limit is the user's to move: 31 frames allowed, 30 not.
    let short = dir.path().join("short.csv");
    std::fs::write(&short, "time,w,x,y,z\n0,1,0,0,0\n1,1,0,0,0\n").unwrap();
    let ok = bin()
        .args(["interp", "--max-frames", "31"])
        .arg(&short)
        .output()
        .unwrap();
    assert!(ok.status.success());
    let refused = bin()
        .args(["interp", "--max-frames", "30"])
        .arg(&short)
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(2));
}

#[test]
fn each_kind_of_warning_is_printed_ten_times_then_counted() {
    let dir = tempfile::tempdir().unwrap();
    let keys = dir.path().join("norms.csv");
    let mut text = String::from("time,w,x,y,z\n");
    for i in 0..1000 {
        text += &format!("{i},2,0,0,0\n");
    }
    std::fs::write(&keys, text).unwrap();
    let out = bin().arg("convert").arg(&keys).output().unwrap();
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 11, "{stderr}");
    assert_eq!(
        lines[0],
        format!(
            "inbetween: warning: {}:2: quaternion norm 2 is off 1 by more than 1e-3; normalized",
            keys.display()
        )
    );
    assert!(
        lines[10].starts_with("inbetween: warning: … and 990 more warnings like \""),
        "{}",
        lines[10]
    );
}
