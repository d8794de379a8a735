//! Numbers near the largest float in world-space measures and USD rotations: never a wrong
//! answer with exit 0, never `inf` in a report. Inputs are generated here; expected values are
//! closed forms.

use crate::support::bin;

/// A two-joint BVH whose spine and its end lie `offset` above their parents, the spine turning
/// about two axes along 30 frames (not along a straight line: reduce must interpolate).
fn far_clip(offset: &str) -> String {
    let mut s = format!(
        "HIERARCHY\nROOT Hips\n{{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition \
         Zrotation Xrotation Yrotation\n  JOINT Spine\n  {{\n    OFFSET 0 {offset} 0\n    \
         CHANNELS 3 Zrotation Xrotation Yrotation\n    End Site\n    {{\n      OFFSET 0 {offset} \
         0\n    }}\n  }}\n}}\nMOTION\nFrames: 30\nFrame Time: 0.033333\n"
    );
    for i in 0..30 {
        let t = i as f64;
        s += &format!(
            "0 0 0 {:.4} 0 0 {:.4} {:.4} 0\n",
            30.0 * (t / 3.0).sin(),
            40.0 * (t / 4.0).cos(),
            5.0 * t.sin()
        );
    }
    s
}

/// World positions of 1e300 overflow when composed: `reduce --position-tolerance` refuses
/// (exit 2, naming the joint, nothing written) where it exited 0 with keys 180° off; the same
/// clip at a sane scale reduces.
#[test]
fn world_reduce_of_offsets_near_the_largest_float_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let far = dir.path().join("far.bvh");
    std::fs::write(&far, far_clip("1e300")).unwrap();
    let out = dir.path().join("keys.json");
    let err = crate::support::stderr_of(
        bin()
            .arg("reduce")
            .arg(&far)
            .args(["--position-tolerance", "1", "-o"])
            .arg(&out),
        2,
    );
    assert!(
        err.contains("joint \"Spine\": its world position at frame"),
        "{err}"
    );
    assert!(err.contains("not a finite number"), "{err}");
    assert!(!out.exists());
    let near = dir.path().join("near.bvh");
    std::fs::write(&near, far_clip("10")).unwrap();
    bin()
        .arg("reduce")
        .arg(&near)
        .args(["--position-tolerance", "1", "-o"])
        .arg(&out)
        .assert()
        .success();
}

/// `diff --shell 1e300` of a clip and its reduced keys: refused, the report not written (it
/// wrote `inf`).
#[test]
fn diff_with_a_shell_near_the_largest_float_writes_no_inf() {
    let dir = tempfile::tempdir().unwrap();
    let clip = dir.path().join("clip.bvh");
    std::fs::write(&clip, far_clip("10")).unwrap();
    let keys = dir.path().join("keys.json");
    bin()
        .arg("reduce")
        .arg(&clip)
        .args(["--tolerance", "2", "--translation-tolerance", "0.1", "-o"])
        .arg(&keys)
        .assert()
        .success();
    let report = dir.path().join("report.txt");
    let err = crate::support::stderr_of(
        bin()
            .arg("diff")
            .arg(&clip)
            .arg(&keys)
            .args(["--shell", "1e300", "-o"])
            .arg(&report),
        2,
    );
    assert!(
        err.contains("world displacement is not a finite number"),
        "{err}"
    );
    assert!(!report.exists());
    // A sane shell reports finite numbers.
    let out = crate::support::stdout_of(
        bin()
            .arg("diff")
            .arg(&clip)
            .arg(&keys)
            .args(["--shell", "5"]),
    );
    assert!(!out.contains("inf") && !out.contains("NaN"), "{out}");
}

/// A USD `quatd` of 1e300 (or 1e-300) is a rotation: (1e300, 0, 0, 1e300) is 90° about z. Its
/// norm overflowed to a zero quaternion and the run failed.
#[test]
fn usd_quaternions_near_the_float_limits_are_rotations() {
    let dir = tempfile::tempdir().unwrap();
    for (w, z) in [
        ("1e300", "1e300"),
        ("1e-300", "1e-300"),
        ("-1e308", "-1e308"),
    ] {
        let file = dir.path().join("q.usda");
        std::fs::write(
            &file,
            format!(
                "#usda 1.0\ndef SkelRoot \"R\" {{\n def Skeleton \"S\" {{\n uniform token[] joints \
                 = [\"a\"]\n rel skel:animationSource = </R/S/A>\n def SkelAnimation \"A\" {{\n \
                 uniform token[] joints = [\"a\"]\n quatd[] rotations.timeSamples = {{\n 0: \
                 [({w}, 0, 0, {z})],\n 4: [(1, 0, 0, 0)],\n }}\n }}\n }}\n}}\n"
            ),
        )
        .unwrap();
        let out = crate::support::stdout_of(bin().arg("convert").arg(&file).args(["--to", "quat"]));
        let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
        let q = &doc["tracks"][0]["keys"][0]["quat"];
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let sign = q[0].as_f64().unwrap().signum();
        assert!(
            (q[0].as_f64().unwrap() - sign * h).abs() < 1e-15,
            "{w}: {q}"
        );
        assert!(
            (q[3].as_f64().unwrap() - sign * h).abs() < 1e-15,
            "{w}: {q}"
        );
    }
}

/// A chain of 6 000 joints: world-space reduce would compose 18 million joints along its
/// points' chains (the root 1 deep, joint i i + 2 deep, the end site's point at the last joint:
/// 6001·6002/2 + 6001 = 18 015 002) (and hold them: quadratic in the joints); refused before they are built,
/// while per-joint reduce takes it.
#[test]
fn world_reduce_of_a_very_deep_chain_is_refused_up_front() {
    let n = 6000;
    let mut text = String::from(
        "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation \
         Xrotation Yrotation\n",
    );
    for i in 0..n {
        text +=
            &format!("JOINT j{i}\n{{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n");
    }
    text += "End Site\n{\nOFFSET 0 1 0\n}\n";
    text += &"}\n".repeat(n + 1);
    text += "MOTION\nFrames: 2\nFrame Time: 0.033333\n";
    for f in 0..2 {
        let mut row = vec!["0 0 0 0 0 0".to_string()];
        row.extend((0..n).map(|i| format!("{} 0 0", f * (i % 7))));
        text += &(row.join(" ") + "\n");
    }
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("deep.bvh");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("keys.json");
    let err = crate::support::stderr_of(
        bin()
            .arg("reduce")
            .arg(&file)
            .args(["--position-tolerance", "1000", "-o"])
            .arg(&out),
        2,
    );
    assert!(
        err.contains("lie up to 6001 joints deep: 18015002 joints along their chains"),
        "{err}"
    );
    assert!(!out.exists());
    bin()
        .arg("reduce")
        .arg(&file)
        .args(["--tolerance", "1", "--translation-tolerance", "1", "-o"])
        .arg(&out)
        .assert()
        .success();
}
