//! A BVH joint with fewer than three rotation channels written back as BVH gets exactly its own
//! angles at its keys, also at the missing axis's gimbal lock (`Zrotation Xrotation` with X at
//! 90°, where the continuous triple would trade Z for the missing Y). Read back by a plain
//! reader written here; expected values are the file's own numbers.

use crate::support::bvh_rows as rows;

/// A root with `channels` (a hinge and a two-axis joint under it), one row per entry of `data`.
fn clip(channels: [&str; 2], data: &[[f64; 3]]) -> String {
    let n = |c: &str| c.split_whitespace().count();
    let mut text = format!(
        "HIERARCHY\nROOT Hips\n{{\n  OFFSET 0 0 0\n  CHANNELS {} {}\n  JOINT Arm\n  {{\n    \
         OFFSET 0 1 0\n    CHANNELS {} {}\n    End Site\n    {{\n      OFFSET 0 1 0\n    }}\n  \
         }}\n}}\nMOTION\nFrames: {}\nFrame Time: 0.0333333\n",
        n(channels[0]),
        channels[0],
        n(channels[1]),
        channels[1],
        data.len()
    );
    for r in data {
        text += &format!("{} {} {}\n", r[0], r[1], r[2]);
    }
    text
}

#[test]
fn two_rotation_channels_at_the_third_angles_gimbal_lock_come_back_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("lock.bvh");
    let out = dir.path().join("out.bvh");
    for second in [
        "Zrotation Xrotation",
        "Xrotation Zrotation",
        "Yrotation Xrotation",
    ] {
        for x in [90.0, 89.9999, -90.0, 90.0001] {
            // Root: a hinge about Z; the arm: two axes, the second held at (or near) 90°.
            let data: Vec<[f64; 3]> = [-170.0, -45.0, 0.0, 12.5, 30.0, 135.0, 179.0]
                .iter()
                .map(|&z| [z / 2.0, z, x])
                .collect();
            let text = clip(["Zrotation", second], &data);
            std::fs::write(&src, &text).unwrap();
            let want = rows(&text);
            for cmd in ["convert", "interp"] {
                let o = crate::support::bin()
                    .args([
                        cmd.as_ref(),
                        src.as_os_str(),
                        "-o".as_ref(),
                        out.as_os_str(),
                    ])
                    .output()
                    .unwrap();
                let stderr = String::from_utf8_lossy(&o.stderr);
                assert_eq!(o.status.code(), Some(0), "{cmd} {second} {x}: {stderr}");
                let got = rows(&std::fs::read_to_string(&out).unwrap());
                assert_eq!(got.len(), want.len());
                for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                    for c in 0..3 {
                        assert!(
                            (g[c] - w[c]).abs() <= 1e-9,
                            "{cmd} {second} x={x} row {i} column {c}: {} vs {}",
                            g[c],
                            w[c]
                        );
                    }
                }
            }
        }
    }
}
