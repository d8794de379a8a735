//! `--to rot6d:rows` / `rot6d:columns` and reading them back: the values against the matrices of
//! 90° turns written out by hand (pytorch3d's rows, Zhou et al.'s columns), the round trip, a
//! network's non-orthonormal output read by Gram–Schmidt, and the refusals.

use crate::support::{bin, stderr_of, stdout_of};

const H: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Identity, 90° about x, 90° about z as `time,w,x,y,z` rows.
fn keys(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("q.csv");
    std::fs::write(
        &path,
        format!("time,w,x,y,z\n0,1,0,0,0\n1,{H},{H},0,0\n2,{H},0,0,{H}\n"),
    )
    .unwrap();
    path
}

fn rows(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').skip(1).map(|x| x.parse().unwrap()).collect())
        .collect()
}

fn close(got: &[Vec<f64>], want: &[[f64; 6]]) {
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(want) {
        for (a, b) in g.iter().zip(w) {
            assert!((a - b).abs() < 1e-15, "{g:?} against {w:?}");
        }
    }
}

/// The matrices, by hand: Rx(90°) = [[1,0,0],[0,0,−1],[0,1,0]], Rz(90°) = [[0,−1,0],[1,0,0],
/// [0,0,1]] (column vectors, v' = R v). Rows are pytorch3d's `matrix[..., :2, :]`; columns
/// Zhou et al.'s first two columns.
#[test]
fn rows_and_columns_are_the_matrix_s_and_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let q = keys(dir.path());
    let r = stdout_of(bin().arg("convert").arg(&q).args(["--to", "rot6d:rows"]));
    assert!(r.starts_with("time,r0x,r0y,r0z,r1x,r1y,r1z\n"), "{r}");
    close(
        &rows(&r),
        &[
            [1., 0., 0., 0., 1., 0.],
            [1., 0., 0., 0., 0., -1.],
            [0., -1., 0., 1., 0., 0.],
        ],
    );
    let c = stdout_of(bin().arg("convert").arg(&q).args(["--to", "rot6d:columns"]));
    assert!(c.starts_with("time,c0x,c0y,c0z,c1x,c1y,c1z\n"), "{c}");
    close(
        &rows(&c),
        &[
            [1., 0., 0., 0., 1., 0.],
            [1., 0., 0., 0., 0., 1.],
            [0., 1., 0., -1., 0., 0.],
        ],
    );
    // Back to quaternions, through CSV and through JSON (whose "rotation" names the
    // convention of its "rot6d" keys).
    for (to, ext) in [("rot6d:rows", "csv"), ("rot6d:columns", "json")] {
        let six = dir.path().join(format!("six.{ext}"));
        bin()
            .arg("convert")
            .arg(&q)
            .args(["--to", to, "-o"])
            .arg(&six)
            .assert()
            .success();
        let back = stdout_of(
            bin()
                .arg("convert")
                .arg(&six)
                .args(["--output-format", "csv"]),
        );
        let want = [[1., 0., 0., 0.], [H, H, 0., 0.], [H, 0., 0., H]];
        for (g, w) in rows(&back).iter().zip(want) {
            for (a, b) in g.iter().zip(w) {
                assert!((a - b).abs() < 1e-15, "{to}: {g:?} against {w:?}");
            }
        }
    }
}

/// A network's output is not orthonormal: `a1` scaled, `a2` leaning towards `a1`. Gram–Schmidt
/// reads the rotation whose first row (column) is along `a1` and whose second is `a2` made
/// orthogonal to it: here Rx(90°) again.
#[test]
fn a_network_s_output_is_read_by_gram_schmidt() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("net.csv");
    // Rx(90°)'s rows (1,0,0), (0,0,−1): a1 = 2·row0, a2 = row1 + 0.3·row0.
    std::fs::write(&path, "time,r0x,r0y,r0z,r1x,r1y,r1z\n0,2,0,0,0.3,0,-1\n").unwrap();
    let q = rows(&stdout_of(bin().arg("convert").arg(&path)));
    for (a, b) in q[0].iter().zip([H, H, 0., 0.]) {
        assert!((a - b).abs() < 1e-15, "{q:?}");
    }
}

#[test]
fn degenerate_pairs_and_unnamed_conventions_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (text, want) in [
        (
            "time,c0x,c0y,c0z,c1x,c1y,c1z\n0,0,0,0,0,1,0\n",
            ":2: columns c0x,c0y,c0z,c1x,c1y,c1z: expected two non-zero vectors (6D rotation), \
             found a zero vector",
        ),
        (
            "time,r0x,r0y,r0z,r1x,r1y,r1z\n0,1,0,0,-3,0,0\n",
            ":2: columns r0x,r0y,r0z,r1x,r1y,r1z: expected two non-parallel vectors (6D \
             rotation), found vectors 180° apart",
        ),
    ] {
        let path = dir.path().join("bad.csv");
        std::fs::write(&path, text).unwrap();
        let err = stderr_of(bin().arg("convert").arg(&path), 2);
        assert!(err.contains(want), "{err}");
    }
    let json = dir.path().join("k.json");
    std::fs::write(
        &json,
        r#"{"keys": [{"time": 0, "rot6d": [1, 0, 0, 0, 1, 0]}]}"#,
    )
    .unwrap();
    let err = stderr_of(bin().arg("convert").arg(&json), 2);
    assert!(
        err.contains("\"rot6d\": the convention is unknown"),
        "{err}"
    );
    let err = stderr_of(bin().arg("convert").arg(&json).args(["--to", "rot6d"]), 2);
    assert!(err.contains("expected rot6d:rows"), "{err}");
}
