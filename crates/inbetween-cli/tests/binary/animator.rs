//! Animator-safe conventions (issue 12): keys rounded off the frame grid, the output format
//! chosen by `-o`'s extension.

use crate::support::bin;

/// 195 keys at motion capture's rounded frame time 0.0333333 s: the last key is 6.5e-6 s short
/// of frame 194 at 30 fps.
fn rounded_keys(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("mocap.csv");
    let mut text = String::from("time,w,x,y,z\n");
    for i in 0..195 {
        let a = i as f64 * 0.01;
        text += &format!("{:.7},{},0,0,{}\n", i as f64 * 0.0333333, a.cos(), a.sin());
    }
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_frame_missed_by_a_rounded_key_time_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let keys = rounded_keys(dir.path());
    let out = bin()
        .args(["interp", "--fps", "30"])
        .arg(&keys)
        .output()
        .unwrap();
    assert!(out.status.success());
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.lines().last().unwrap().starts_with("193,"));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "inbetween: warning: {}: the last key, at 6.4666602 s, is 6.5e-6 s before frame 194 \
             (6.466666666666667 s), which is therefore not written; --snap-keys 0.001 moves keys \
             that close onto the grid\n",
            keys.display()
        )
    );
}

#[test]
fn snap_keys_moves_rounded_keys_onto_the_grid() {
    let dir = tempfile::tempdir().unwrap();
    let keys = rounded_keys(dir.path());
    let out = bin()
        .args(["interp", "--fps", "30", "--snap-keys", "0.001"])
        .arg(&keys)
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let last = stdout.lines().last().unwrap();
    // Frame 194 is the last key itself, the quaternion (cos 1.94, 0, 0, sin 1.94).
    let v: Vec<f64> = last.split(',').map(|x| x.parse().unwrap()).collect();
    assert_eq!(v[0], 194.0);
    assert!((v[2] - 1.94f64.cos()).abs() < 1e-12 && (v[5] - 1.94f64.sin()).abs() < 1e-12);
    // Too large an EPS merges keys: an error naming both.
    let two = dir.path().join("two.csv");
    std::fs::write(
        &two,
        "time,w,x,y,z\n0,1,0,0,0\n0.01,1,0,0,0\n0.02,1,0,0,0\n",
    )
    .unwrap();
    let out = bin()
        .args(["interp", "--fps", "30", "--snap-keys", "0.5"])
        .arg(&two)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "inbetween: error: {}: --snap-keys 0.5: keys at 0 s and 0.01 s would both move to \
             frame 0 (0 s); lower EPS or merge the keys\n",
            two.display()
        )
    );
}

#[test]
fn the_output_format_follows_the_extension_of_o() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("keys.json");
    let ok = bin()
        .args(["convert", "fixtures/convert/matrix.csv", "-o"])
        .arg(&json)
        .output()
        .unwrap();
    assert!(ok.status.success());
    let text = std::fs::read_to_string(&json).unwrap();
    assert!(
        serde_json::from_str::<serde_json::Value>(&text).is_ok(),
        "{text}"
    );
    // --output-format wins over the extension.
    let ok = bin()
        .args([
            "convert",
            "fixtures/convert/matrix.csv",
            "--output-format",
            "csv",
            "-o",
        ])
        .arg(&json)
        .output()
        .unwrap();
    assert!(ok.status.success());
    assert!(
        std::fs::read_to_string(&json)
            .unwrap()
            .starts_with("time,w,x,y,z\n")
    );
    // interp: .npy by extension.
    let npy = dir.path().join("frames.NPY");
    let ok = bin()
        .args(["interp", "fixtures/interp/uniform.json", "-o"])
        .arg(&npy)
        .output()
        .unwrap();
    assert!(ok.status.success());
    assert!(std::fs::read(&npy).unwrap().starts_with(b"\x93NUMPY"));
    // convert cannot write npy: the error names -o.
    let bad = dir.path().join("keys.npy");
    let out = bin()
        .args(["convert", "fixtures/convert/matrix.csv", "-o"])
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "inbetween: error: -o {}: convert writes keyframe documents (csv or json); npy is for \
             interp's frames\n",
            bad.display()
        )
    );
    assert!(!bad.exists());
}

#[test]
fn convert_says_which_rate_it_assumed_for_frame_numbers() {
    let out = bin()
        .args([
            "convert",
            "fixtures/interp/maya_frames.csv",
            "--from",
            "euler:xyz",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "inbetween: warning: fixtures/interp/maya_frames.csv: frame numbers are read at the \
         default rate, 30 fps, as the document declares no rate; give the keys' rate with \
         --key-fps RATE\n"
    );
    for given in [&["--key-fps", "24"][..], &["--fps", "24"][..]] {
        let out = bin()
            .args([
                "convert",
                "fixtures/interp/maya_frames.csv",
                "--from",
                "euler:xyz",
            ])
            .args(given)
            .output()
            .unwrap();
        assert!(out.status.success() && out.stderr.is_empty(), "{given:?}");
    }
}

#[test]
fn convert_to_csv_names_the_rate_it_cannot_write() {
    let out = bin()
        .args([
            "convert",
            "fixtures/interp/frames_ntsc.json",
            "--output-format",
            "csv",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "inbetween: warning: CSV has no place for the rate: the frame numbers are written as \
         they are, at 30000/1001 fps; read them back with --key-fps 30000/1001\n"
    );
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("frame,"));
}

#[test]
fn analyze_writes_the_format_of_the_o_extension() {
    let dir = tempfile::tempdir().unwrap();
    for (name, starts) in [
        ("a.json", "{"),
        ("a.csv", "track,scheme,"),
        ("a.txt", "track "),
    ] {
        let path = dir.path().join(name);
        let out = bin()
            .args([
                "analyze",
                "fixtures/interp/uniform.json",
                "--scheme",
                "slerp",
                "-o",
            ])
            .arg(&path)
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}");
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.starts_with(starts), "{name}: {text}");
    }
}

/// `--path euler`: a spin keyed in Euler angles keeps its turns; quaternion input is refused
/// with the track, what was found, and the remedy.
#[test]
fn euler_spins_turn_as_keyed_and_need_euler_keys() {
    let keys = "time,e1,e2,e3\n0,0,0,0\n1,720,0,0\n";
    let out = bin()
        .args([
            "interp",
            "-",
            "--input-format",
            "csv",
            "--from",
            "euler:ZYX",
            "--path",
            "euler",
            "--fps",
            "8",
            "--scheme",
            "slerp",
            "--to",
            "euler:ZYX",
        ])
        .write_stdin(keys)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let e1: Vec<f64> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect();
    let want: Vec<f64> = (0..=8).map(|k| 90.0 * k as f64).collect();
    assert_eq!(e1.len(), want.len());
    for (g, w) in e1.iter().zip(&want) {
        assert!((g - w).abs() < 1e-9, "{e1:?}");
    }
    // The shortest path has no motion at all between identical rotations.
    let out = bin()
        .args([
            "interp",
            "-",
            "--input-format",
            "csv",
            "--from",
            "euler:ZYX",
            "--fps",
            "8",
            "--scheme",
            "slerp",
            "--to",
            "euler:ZYX",
        ])
        .write_stdin(keys)
        .output()
        .unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.lines().skip(1).all(|l| l.ends_with(",0.0,0.0,0.0")),
        "{text}"
    );
    let out = bin()
        .args(["interp", "-", "--input-format", "csv", "--path", "euler"])
        .write_stdin("time,w,x,y,z\n0,1,0,0,0\n1,0,0,0,1\n")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "inbetween: error: <stdin>: --path euler needs keys given as Euler angles in one sequence \
         (--from euler:SEQ, or \"rotation\": \"euler:SEQ\" in JSON), found quat keys\n"
    );
}

/// Continuous Euler output starts from the first key's own triple when the keys are Euler
/// angles in the output's sequence (interp's frames and convert's keys), else from the canonical
/// triple.
#[test]
fn continuous_euler_starts_from_the_first_keys_own_triple() {
    let keys = "time,e1,e2,e3\n0,370,0,0\n1,380,0,0\n";
    let first = |args: &[&str]| {
        let out = bin().args(args).write_stdin(keys).output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let row = text.lines().nth(1).unwrap().to_string();
        let last = text.lines().last().unwrap().to_string();
        (row, last)
    };
    let base = ["-", "--input-format", "csv", "--from", "euler:ZYX"];
    let interp: Vec<&str> = ["interp"].iter().chain(&base).copied().collect();
    let (row, last) = first(&[&interp[..], &["--fps", "2", "--to", "euler:ZYX"]].concat());
    assert_eq!(
        (row.as_str(), last.as_str()),
        ("0,0.0,370.0,0.0,0.0", "2,1.0,380.0,0.0,0.0")
    );
    let convert: Vec<&str> = ["convert"].iter().chain(&base).copied().collect();
    let (row, last) = first(&[&convert[..], &["--to", "euler:ZYX"]].concat());
    assert_eq!(
        (row.as_str(), last.as_str()),
        ("0.0,370.0,0.0,0.0", "1.0,380.0,0.0,0.0")
    );
    // Another sequence starts from the canonical triple; so does --euler wrapped.
    let (row, _) = first(&[&interp[..], &["--fps", "2", "--to", "euler:XYZ"]].concat());
    assert!(row.starts_with("0,0.0,0.0,0.0,9.99999999999"), "{row}");
    let (row, _) = first(&[&interp[..], &["--to", "euler:ZYX", "--euler", "wrapped"]].concat());
    assert!(row.starts_with("0,0.0,9.99999999999"), "{row}");
}

/// `--tracks` keeps the named tracks (globs allowed) in every command, and names the tracks
/// there are when a pattern matches none.
#[test]
fn tracks_selects_by_name_and_glob() {
    let csv = "track,time,w,x,y,z\nLeftArm,0,1,0,0,0\nLeftArm,1,0,0,0,1\nRightArm,0,1,0,0,0\n\
               RightArm,1,0,1,0,0\nHips,0,1,0,0,0\nHips,1,0,0,1,0\n";
    let names = |args: &[&str]| {
        let out = bin().args(args).write_stdin(csv).output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let mut seen: Vec<String> = Vec::new();
        for l in text.lines().skip(1) {
            let n = l.split(',').next().unwrap().to_string();
            if !seen.contains(&n) {
                seen.push(n);
            }
        }
        seen
    };
    let base = ["--input-format", "csv", "--tracks", "Hips,*Arm"];
    let interp: Vec<&str> = ["interp", "-", "--fps", "2"]
        .iter()
        .chain(&base)
        .copied()
        .collect();
    assert_eq!(names(&interp), ["LeftArm", "RightArm", "Hips"]);
    let convert: Vec<&str> =
        ["convert", "-", "--input-format", "csv", "--tracks", "L?ft*"].to_vec();
    assert_eq!(names(&convert), ["LeftArm"]);
    let out = bin()
        .args(["interp", "-", "--input-format", "csv", "--tracks", "Spine"])
        .write_stdin(csv)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "inbetween: error: --tracks: \"Spine\" matches no track of <stdin>; its tracks are \
         \"LeftArm\", \"RightArm\", \"Hips\"\n"
    );
}
