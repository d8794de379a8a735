//! `reduce` to glTF of translation and scale channels: with `--translation-tolerance` and
//! `--scale-tolerance` the LINEAR vector channels keep fewer keys, and the reduced asset, played
//! by the independent reference (`fixtures/gltf/playback_ref.py`: lerp, as glTF 2.0 Appendix C
//! plays them), stays within each tolerance of the original's own playback.

use crate::support::{bin, checker_python, fixtures, python_json};
use inbetween_io::gltf::{Asset, Interpolation, TranslationChannel};
use std::path::Path;

/// The independent playback of channel `c` of animation `a` of `asset` at `times`.
fn played(asset: &Path, a: usize, c: usize, times: &[f64]) -> Option<Vec<[f64; 3]>> {
    let python = checker_python("glTF playback reference check")?;
    let mut args: Vec<String> = vec![asset.display().to_string(), a.to_string(), c.to_string()];
    args.extend(times.iter().map(|t| format!("{t:?}")));
    let args: Vec<&std::ffi::OsStr> = args.iter().map(std::ffi::OsStr::new).collect();
    let doc = python_json(&python, "fixtures/gltf/playback_ref.py", &args);
    let values = doc["values"].as_array().unwrap().iter().map(|v| {
        let xs: Vec<f64> = v
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        [xs[0], xs[1], xs[2]]
    });
    Some(values.collect())
}

/// Every key time of `ch` and the midpoints between them.
fn probe_times(ch: &TranslationChannel) -> Vec<f64> {
    let t = ch.times();
    let mut probes = t.to_vec();
    probes.extend(t.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    probes
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// `reduce SRC --animation spawn --tolerance 0.5 EXTRA -o OUT`, which must succeed; OUT read.
fn reduce_spawn(src: &Path, extra: &[&str], out: &Path) -> Asset {
    let o = bin()
        .args(["reduce", "--animation", "spawn", "--tolerance", "0.5"])
        .args(extra)
        .arg(src)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    Asset::read_path(out).unwrap()
}

/// The `spawn` animation of the Blender-exported oak tree has 15-key LINEAR translation and
/// scale channels at 25 fps. Reduced at each tolerance, each keeps fewer keys (more for a
/// tighter one), stays LINEAR, and plays within the tolerance of the original at every key
/// time and between them; without the flags the channels are as read.
#[test]
fn translation_and_scale_channels_are_reduced_within_their_tolerances() {
    let dir = tempfile::tempdir().unwrap();
    let src = fixtures().join("gltf/real/oaktree.gltf");
    let input = Asset::read_path(&src).unwrap();
    let anim = &input.animations().unwrap()[1];
    let (translation, scale) = (&anim.translations()[0], &anim.scales()[0]);
    assert_eq!(translation.times().len(), 15);
    let mut kept_before = 0;
    for tol in ["0.05", "0.01", "0.002"] {
        let out = dir.path().join(format!("small{tol}.glb"));
        let tolerances = ["--translation-tolerance", tol, "--scale-tolerance", tol];
        let back = reduce_spawn(&src, &tolerances, &out);
        let reduced = &back.animations().unwrap()[1];
        let tol: f64 = tol.parse().unwrap();
        for (ch, got) in [
            (translation, &reduced.translations()[0]),
            (scale, &reduced.scales()[0]),
        ] {
            assert_eq!(got.interpolation(), Interpolation::Linear);
            assert!(got.times().len() <= ch.times().len());
            let times = probe_times(ch);
            let (Some(want), Some(have)) = (
                played(&src, 1, ch.index(), &times),
                played(&out, 1, got.index(), &times),
            ) else {
                return;
            };
            for ((t, w), h) in times.iter().zip(&want).zip(&have) {
                let d = distance(*w, *h);
                assert!(
                    d <= tol * (1.0 + 1e-9),
                    "channel {} at {t}: {d}",
                    ch.index()
                );
            }
        }
        let kept = reduced.scales()[0].times().len();
        assert!(kept < scale.times().len(), "{tol}: scale kept {kept}");
        assert!(
            kept >= kept_before,
            "{tol}: {kept} keys, {kept_before} at a looser one"
        );
        kept_before = kept;
        assert!(reduced.translations()[0].times().len() < 15);
    }
    // Without the flags, both channels keep their keys.
    let out = dir.path().join("rotations_only.glb");
    let back = reduce_spawn(&src, &[], &out);
    let kept = &back.animations().unwrap()[1];
    assert_eq!(kept.translations()[0].values(), translation.values());
    assert_eq!(kept.scales()[0].values(), scale.values());
}

/// `--scale-tolerance` has nothing to act on in a keys document: refused, nothing written.
#[test]
fn scale_tolerance_needs_gltf_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("keys.json");
    let o = bin()
        .args(["reduce", "--tolerance", "0.5", "--scale-tolerance", "0.01"])
        .arg(fixtures().join("gltf/real/oaktree.gltf"))
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("--scale-tolerance 0.01: only glTF output"),
        "{e}"
    );
    assert!(!out.exists());
}
