//! Reading, sampling and writing the fixtures of `fixtures/gltf`, damaged inputs, and the
//! Khronos glTF Validator on what the writer produces.

use super::*;
use glam::DVec4;
use serde_json::Value;
use std::collections::HashSet;
use std::f64::consts::FRAC_PI_2;

/// Float32 resolution of a unit quaternion's components, as an angle: written and read back
/// rotations agree within this.
const F32_ANGLE: f64 = 1e-6;

fn fixture(name: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("fixtures/gltf")
        .join(name)
}

fn read(name: &str) -> Asset {
    Asset::read_path(&fixture(name)).unwrap()
}

/// The angle between two rotations, accurate near zero: `2·atan2(‖a − ±b‖, ‖a + ±b‖)`.
fn angle(a: DQuat, b: DQuat) -> f64 {
    let (a, b) = (DVec4::from(a).normalize(), DVec4::from(b).normalize());
    let b = if a.dot(b) < 0.0 { -b } else { b };
    2.0 * (a - b).length().atan2((a + b).length())
}

fn assert_rot(a: DQuat, b: DQuat, tol: f64, what: &str) {
    let angle = angle(a, b);
    assert!(
        angle <= tol,
        "{what}: {a:?} vs {b:?}: {angle:e} rad apart (tolerance {tol:e})"
    );
}

fn axis_angle(axis: [f64; 3], angle: f64) -> DQuat {
    DQuat::from_axis_angle(DVec3::from(axis).normalize(), angle)
}

#[test]
fn minimal_asset_names_and_channels() {
    let asset = read("minimal_linear.gltf");
    assert_eq!(asset.container(), ContainerFormat::Gltf);
    let anims = asset.animations().unwrap();
    assert_eq!(anims.len(), 1);
    let a = &anims[0];
    assert_eq!(
        (a.name(), a.label(), a.span()),
        (None, "0".to_string(), Some((0.0, 1.0)))
    );
    assert_eq!(a.rotations().len(), 1);
    let r = &a.rotations()[0];
    assert_eq!((r.node(), r.node_name(), r.index()), (0, "node0", 0));
    assert_eq!(r.interpolation(), Interpolation::Linear);
    assert_eq!(r.times_f32(), [0.0, 1.0]);
    assert_rot(
        r.sample(0.5),
        DQuat::from_rotation_z(FRAC_PI_2 / 2.0),
        F32_ANGLE,
        "midpoint",
    );
    let t = &a.translations()[0];
    assert_eq!(t.index(), 1);
    assert_eq!(t.sample(0.5), DVec3::new(0.5, 1.0, 1.5));
}

#[test]
fn gltf_with_external_bin_and_glb_read_the_same() {
    let a = read("samplers.gltf").animations().unwrap();
    let b = read("samplers.glb");
    assert_eq!(b.container(), ContainerFormat::Glb);
    assert_eq!(a, b.animations().unwrap());
    assert_eq!(a.len(), 2);
    assert_eq!(a[0].label(), "Mixed");
    assert_eq!(a[1].label(), "Other");
    // Spans cover every sampler, the scale one included.
    assert_eq!(a[0].span(), Some((0.0, 2.0)));
    assert_eq!(a[1].span(), Some((0.5, 3.0)));
    let names: Vec<_> = a[0].rotations().iter().map(|c| c.node_name()).collect();
    assert_eq!(names, ["step", "byte", "short", "sparse", "cubic"]);
    let kinds: Vec<_> = a[0].rotations().iter().map(|c| c.interpolation()).collect();
    use Interpolation::*;
    assert_eq!(kinds, [Step, Linear, Linear, Linear, CubicSpline]);
    assert_eq!(a[0].translations().len(), 1);
    assert_eq!(a[0].translations()[0].interpolation(), CubicSpline);
}

#[test]
fn an_asset_without_its_bin_is_an_error_naming_it() {
    let bytes = std::fs::read(fixture("samplers.gltf")).unwrap();
    let e = Asset::from_slice(&bytes, "s.gltf", None).unwrap_err();
    assert_eq!(
        e.message(),
        "s.gltf: buffers[0].uri (\"samplers.bin\"): an external file needs the asset's path to be found"
    );
    let e = Asset::from_slice(&bytes, "s.gltf", Some(Path::new("/nonexistent"))).unwrap_err();
    assert!(
        e.message().starts_with(
            "s.gltf: buffers[0].uri (\"samplers.bin\"): cannot read /nonexistent/samplers.bin"
        ),
        "{e}"
    );
}

#[test]
fn normalized_integer_rotations_decode_by_the_spec() {
    let a = read("samplers.glb").animations().unwrap();
    let (byte, short) = (&a[0].rotations()[1], &a[0].rotations()[2]);
    for (k, angle) in [0.0, 1.0, 2.5, 3.0].into_iter().enumerate() {
        let q = axis_angle([1.0, 0.0, 0.0], angle);
        // Rounded to 1/127 and 1/32767 per component.
        assert!(
            (DVec4::from(byte.values()[k]) - DVec4::from(q))
                .abs()
                .max_element()
                <= 0.5 / 127.0 + 1e-12
        );
        assert!(
            (DVec4::from(short.values()[k]) - DVec4::from(q))
                .abs()
                .max_element()
                <= 0.5 / 32767.0 + 1e-12
        );
        assert_rot(short.sample(byte.times()[k]), q, 1e-4, "short key");
    }
}

#[test]
fn sparse_outputs_substitute_their_keys() {
    let a = read("samplers.gltf").animations().unwrap();
    let c = &a[0].rotations()[3];
    let z = |x| axis_angle([0.0, 0.0, 1.0], x);
    let expected = [DQuat::IDENTITY, z(0.8), DQuat::IDENTITY, z(2.0)];
    for (k, q) in expected.into_iter().enumerate() {
        assert_rot(c.values()[k], q, F32_ANGLE, "sparse key");
    }
}

#[test]
fn step_channel_holds_each_key() {
    let a = read("samplers.gltf").animations().unwrap();
    let c = &a[0].rotations()[0];
    let y = |x| axis_angle([0.0, 1.0, 0.0], x);
    for (t, angle) in [
        (-1.0, 0.0),
        (0.49, 0.0),
        (0.5, 0.6),
        (0.99, 0.6),
        (1.2, 1.2),
        (9.0, 1.8),
    ] {
        assert_rot(c.sample(t), y(angle), F32_ANGLE, "step");
    }
}

/// `fixtures/gltf/cubicspline_ref.json` was written by `cubicspline_ref.py` (numpy and
/// pygltflib, its own accessor decoding and Appendix C evaluation):
/// `python fixtures/gltf/cubicspline_ref.py fixtures/gltf/samplers.gltf 0 4`.
#[test]
fn cubicspline_agrees_with_the_python_reference() {
    let text = std::fs::read_to_string(fixture("cubicspline_ref.json")).unwrap();
    let reference: serde_json::Value = serde_json::from_str(&text).unwrap();
    let (anim, chan) = (
        reference["animation"].as_u64().unwrap() as usize,
        reference["channel"].as_u64().unwrap() as usize,
    );
    for name in ["samplers.gltf", "samplers.glb"] {
        let a = read(name).animations().unwrap();
        let c = a[anim]
            .rotations()
            .iter()
            .find(|c| c.index() == chan)
            .unwrap();
        assert_eq!(c.interpolation(), Interpolation::CubicSpline);
        assert_eq!(c.node(), reference["node"].as_u64().unwrap() as usize);
        let times = reference["times"].as_array().unwrap();
        let rots = reference["rotations"].as_array().unwrap();
        assert!(times.len() > 90);
        let mut worst: f64 = 0.0;
        for (t, q) in times.iter().zip(rots) {
            let q: Vec<f64> = q
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let expected = DQuat::from_xyzw(q[0], q[1], q[2], q[3]);
            let got = c.sample(t.as_f64().unwrap());
            // Both evaluate the same float32 data in f64: agreement far inside float32.
            let d = (DVec4::from(got) - DVec4::from(expected))
                .abs()
                .max_element();
            worst = worst.max(d);
            assert!(d < 1e-7, "{name} t = {t}: {got:?} vs {expected:?}");
        }
        assert!(
            worst < 1e-12,
            "{name}: worst component difference {worst:e}"
        );
    }
}

#[test]
fn cubicspline_translation_is_hermite() {
    let a = read("samplers.gltf").animations().unwrap();
    let c = &a[0].translations()[0];
    // Keys: v_k = (k, k², 0.5), a_k = (0.1k, 0, 0), b_k = (0.2k, 0, 0); times 0, .25, .9, 1.2, 2.
    assert_eq!(c.sample(0.25), DVec3::new(1.0, 1.0, 0.5));
    let (t0, t1) = (f64::from(0.25f32), f64::from(0.9f32));
    let dt = t1 - t0;
    let s = 0.5;
    let x = (2.0 * s * s * s - 3.0 * s * s + 1.0) * 1.0
        + (s * s * s - 2.0 * s * s + s) * dt * 0.2
        + (-2.0 * s * s * s + 3.0 * s * s) * 2.0
        + (s * s * s - s * s) * dt * 0.2;
    let got = c.sample(t0 + s * dt);
    assert!((got.x - x).abs() < 1e-12, "{} vs {x}", got.x);
}

// ---- damaged inputs: errors naming where, never a panic ----

fn json_of(name: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(fixture(name)).unwrap()).unwrap()
}

fn read_edited(edit: impl FnOnce(&mut serde_json::Value)) -> InputResult<Vec<Animation>> {
    let mut v = json_of("samplers.gltf");
    edit(&mut v);
    let bytes = serde_json::to_vec(&v).unwrap();
    Asset::from_slice(&bytes, "s.gltf", Some(&fixture("")))?.animations()
}

#[test]
fn damaged_assets_are_located_errors() {
    type Edit = Box<dyn FnOnce(&mut serde_json::Value)>;
    let cases: Vec<(&str, Edit)> = vec![
        (
            "s.gltf: invalid glTF: animations[0].samplers[0].output: Index out of bounds",
            Box::new(|v| v["animations"][0]["samplers"][0]["output"] = 999.into()),
        ),
        (
            "s.gltf: animations[0].samplers[0].input (animation \"Mixed\"): accessors[0]: 4 elements of 4 bytes from byte 0 run past the end of its buffer view (12 bytes)",
            Box::new(|v| v["bufferViews"][0]["byteLength"] = 12.into()),
        ),
        (
            "s.gltf: buffers[0].byteLength: 9999, but \"samplers.bin\" has only 796 bytes",
            Box::new(|v| v["buffers"][0]["byteLength"] = 9999.into()),
        ),
        (
            "s.gltf: animations[0].channels[0] (animation \"Mixed\", node \"step\"): samplers[0].output: accessors[1].count: 3 elements, expected 4 for 4 keys (STEP)",
            Box::new(|v| v["accessors"][1]["count"] = 3.into()),
        ),
        (
            "s.gltf: animations[0].channels[4] (animation \"Mixed\", node \"cubic\"): samplers[4].output: accessors[6].count: 14 elements, expected 15 for 5 keys (CUBICSPLINE)",
            Box::new(|v| v["accessors"][6]["count"] = 14.into()),
        ),
        (
            "s.gltf: animations[0].channels[0] (animation \"Mixed\", node \"step\"): samplers[0].output: accessors[1].type: expected VEC4, found VEC3",
            Box::new(|v| v["accessors"][1]["type"] = "VEC3".into()),
        ),
        (
            "s.gltf: animations[0].channels[1] (animation \"Mixed\", node \"byte\"): samplers[1].output: accessors[2].componentType: expected FLOAT or normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT, found BYTE",
            Box::new(|v| v["accessors"][2]["normalized"] = false.into()),
        ),
        (
            "s.gltf: animations[0].samplers[0].input (animation \"Mixed\"): accessors[1].type: expected SCALAR, found VEC4",
            Box::new(|v| v["animations"][0]["samplers"][0]["input"] = 1.into()),
        ),
    ];
    for (expected, edit) in cases {
        let e = read_edited(edit).unwrap_err();
        assert_eq!(e.message(), expected);
    }
}

/// Rewrites float32 `index` of the buffer of `samplers.gltf` and reads the result.
fn read_with_float(byte_offset: usize, value: f32) -> InputResult<Vec<Animation>> {
    let mut bin = std::fs::read(fixture("samplers.bin")).unwrap();
    bin[byte_offset..byte_offset + 4].copy_from_slice(&value.to_le_bytes());
    let mut v = json_of("samplers.gltf");
    v["buffers"][0]["uri"] = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bin)
    )
    .into();
    let bytes = serde_json::to_vec(&v).unwrap();
    Asset::from_slice(&bytes, "s.gltf", None)?.animations()
}

use base64::Engine as _;

#[test]
fn bad_numbers_are_located_errors() {
    // Accessor 0 (times 0, .5, 1, 1.5) is at byte 0; accessor 1 (STEP rotations) follows.
    let e = read_with_float(8, 0.25).unwrap_err();
    assert_eq!(
        e.message(),
        "s.gltf: animations[0].samplers[0].input (animation \"Mixed\"): accessors[0]: time 2 is 0.25 after 0.5: expected strictly increasing times"
    );
    let e = read_with_float(4, f32::NAN).unwrap_err();
    assert_eq!(
        e.message(),
        "s.gltf: animations[0].samplers[0].input (animation \"Mixed\"): accessors[0]: time 1 is not a number: expected a finite number"
    );
    let e = read_with_float(16 + 4, f32::INFINITY).unwrap_err();
    assert_eq!(
        e.message(),
        "s.gltf: animations[0].channels[0] (animation \"Mixed\", node \"step\"): samplers[0].output: accessors[1]: key 0: component 1 is +infinity: expected finite components"
    );
    let mut zero = std::fs::read(fixture("samplers.bin")).unwrap();
    zero[16..32].fill(0);
    let mut v = json_of("samplers.gltf");
    v["buffers"][0]["uri"] = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&zero)
    )
    .into();
    let e = Asset::from_slice(&serde_json::to_vec(&v).unwrap(), "s.gltf", None)
        .unwrap()
        .animations()
        .unwrap_err();
    assert_eq!(
        e.message(),
        "s.gltf: animations[0].channels[0] (animation \"Mixed\", node \"step\"): samplers[0].output: accessors[1]: key 0: expected a unit quaternion, found zero"
    );
}

#[test]
fn every_truncation_and_byte_flip_of_a_glb_is_an_error_or_reads() {
    let bytes = std::fs::read(fixture("samplers.glb")).unwrap();
    for n in 0..bytes.len() {
        let r = Asset::from_slice(&bytes[..n], "t.glb", None);
        if let Ok(a) = r {
            let _ = a.animations();
        }
    }
    for i in 0..bytes.len() {
        let mut b = bytes.clone();
        b[i] ^= 0xa5;
        if let Some(anims) = Asset::from_slice(&b, "t.glb", None)
            .ok()
            .and_then(|a| a.animations().ok())
        {
            for c in anims.iter().flat_map(|a| a.rotations()) {
                let _ = c.sample(0.3);
            }
        }
    }
    let e = Asset::from_slice(&bytes[..100], "t.glb", None).unwrap_err();
    assert!(
        e.message().starts_with("t.glb: invalid GLB container: "),
        "{e}"
    );
}

// ---- writing ----

/// Each rotation channel of `asset` at its own key times (LINEAR) or at `fps` frames over the
/// animation's span (otherwise).
fn resample_all(asset: &Asset, fps: f64) -> Vec<Resampled> {
    asset
        .animations()
        .unwrap()
        .iter()
        .map(|a| {
            let (t0, t1) = a.span().unwrap();
            let n = ((t1 - t0) * fps).floor() as usize;
            let times: Vec<f64> = (0..=n).map(|k| t0 + k as f64 / fps).collect();
            Resampled {
                animation: a.index(),
                channels: a
                    .rotations()
                    .iter()
                    .map(|c| {
                        let qs = times.iter().map(|&t| c.sample(t)).collect();
                        (c.index(), Values::Rotations(qs))
                    })
                    .collect(),
                times,
            }
        })
        .collect()
}

fn write_to(asset: &Asset, r: &[Resampled], format: ContainerFormat) -> Vec<u8> {
    let mut out = Vec::new();
    asset.write(r, format, &mut out).unwrap();
    out
}

#[test]
fn written_rotations_read_back_and_everything_else_is_kept() {
    for input in ["samplers.gltf", "samplers.glb"] {
        let asset = read(input);
        let before = asset.animations().unwrap();
        let r = resample_all(&asset, 30.0);
        for format in [ContainerFormat::Glb, ContainerFormat::Gltf] {
            let bytes = write_to(&asset, &r, format);
            let what = format!("{input} -> {format:?}");
            let back = Asset::from_slice(&bytes, "out", Some(&fixture(""))).unwrap();
            assert_eq!(back.container(), format);
            let after = back.animations().unwrap();
            for (a, (b, req)) in after.iter().zip(before.iter().zip(&r)) {
                assert_eq!(a.label(), b.label());
                assert_eq!(a.rotations().len(), b.rotations().len());
                for (ca, (cb, (ci, qs))) in a
                    .rotations()
                    .iter()
                    .zip(b.rotations().iter().zip(&req.channels))
                {
                    assert_eq!((ca.index(), ca.node()), (*ci, cb.node()));
                    assert_eq!(ca.interpolation(), Interpolation::Linear);
                    assert_eq!(ca.times().len(), req.times.len());
                    // Sign-continuous unit quaternions, each the requested rotation.
                    let Values::Rotations(qs) = qs else {
                        panic!("rotations")
                    };
                    for (k, (&q, &want)) in ca.values().iter().zip(qs).enumerate() {
                        assert!((q.length() - 1.0).abs() < 1e-6, "{what}: not unit");
                        assert_rot(q, want, 1e-6, &what);
                        if k > 0 {
                            assert!(DVec4::from(q).dot(DVec4::from(ca.values()[k - 1])) >= 0.0);
                        }
                    }
                }
                // Translations and scales untouched (their samplers renumbered).
                let keys = |c: &TranslationChannel| {
                    let t = (c.index(), c.node(), c.interpolation(), c.times().to_vec());
                    (t, c.values().to_vec(), c.tangents().map(<[_]>::to_vec))
                };
                let all = |a: &Animation| {
                    let v = a.translations().iter().chain(a.scales());
                    v.map(keys).collect::<Vec<_>>()
                };
                assert_eq!(all(a), all(b), "{what}");
            }
            // The JSON outside the animations and their data is unchanged.
            let (old, new) = (&asset.json, &back.json);
            for key in ["nodes", "scenes", "scene", "extensionsUsed", "asset"] {
                assert_eq!(old[key], new[key], "{what}: {key}");
            }
            assert_eq!(new["nodes"][1]["extras"]["note"], "kept by writers");
            assert_eq!(
                new["nodes"][1]["extensions"]["EXT_inbetween_unknown"]["answer"],
                42
            );
            assert_eq!(new["animations"][1]["extras"]["take"], 2);
            // Every rotation channel of an animation on its one time accessor, with min and max;
            // the samplers the rotations had before are gone, the others renumbered.
            let anim = &new["animations"][0];
            let input = |c: usize| {
                let s = anim["channels"][c]["sampler"].as_u64().unwrap() as usize;
                anim["samplers"][s]["input"].clone()
            };
            let t_acc = &new["accessors"][input(0).as_u64().unwrap() as usize];
            assert_eq!(t_acc["type"], "SCALAR");
            assert_eq!(t_acc["min"][0], 0.0);
            assert_eq!(t_acc["max"][0], 2.0);
            let rotations = before[0].rotations().len();
            for c in 0..rotations {
                assert_eq!(input(c), input(0), "{what}: channel {c}");
            }
            let samplers = |j: &Value| j["animations"][0]["samplers"].as_array().unwrap().len();
            let used_by_rotations: HashSet<_> = (0..rotations)
                .map(|c| &old["animations"][0]["channels"][c]["sampler"])
                .collect();
            assert_eq!(
                samplers(new),
                samplers(old) - used_by_rotations.len() + rotations,
                "{what}"
            );
            for c in [5, 6] {
                let target = |j: &Value| j["animations"][0]["channels"][c]["target"].clone();
                assert_eq!(target(new), target(old));
            }
        }
    }
}

#[test]
fn linear_channels_round_trip_at_their_own_keys_to_float32() {
    let asset = read("samplers.glb");
    let anims = asset.animations().unwrap();
    let a = &anims[1];
    let c = &a.rotations()[0];
    let r = Resampled {
        animation: 1,
        times: c.times().to_vec(),
        channels: vec![(c.index(), Values::Rotations(c.values().to_vec()))],
    };
    let back = Asset::from_slice(&write_to(&asset, &[r], ContainerFormat::Glb), "o.glb", None)
        .unwrap()
        .animations()
        .unwrap();
    let d = &back[1].rotations()[0];
    assert_eq!(d.times_f32(), c.times_f32());
    for (p, q) in d.values().iter().zip(c.values()) {
        assert_rot(*p, *q, F32_ANGLE, "round trip");
    }
    // The other animation is untouched.
    assert_eq!(back[0], anims[0]);
}

#[test]
fn write_requests_are_checked() {
    let asset = read("samplers.gltf");
    let q = DQuat::IDENTITY;
    let bad = |r: Resampled| {
        asset
            .to_bytes(&[r], ContainerFormat::Glb)
            .unwrap_err()
            .message()
            .to_string()
    };
    let src = asset.source().to_string();
    let r = |animation, times: Vec<f64>, channels: Vec<(usize, Vec<DQuat>)>| Resampled {
        animation,
        times,
        channels: channels
            .into_iter()
            .map(|(c, qs)| (c, Values::Rotations(qs)))
            .collect(),
    };
    assert_eq!(
        bad(r(5, vec![0.0], vec![])),
        format!("{src}: no animation 5 to replace (the asset has 2)")
    );
    assert_eq!(
        bad(r(0, vec![0.0], vec![(6, vec![q])])),
        format!("{src}: animation 0: channel 6 targets Scale, not a rotation")
    );
    assert_eq!(
        bad(r(0, vec![0.0, 1.0], vec![(0, vec![q])])),
        format!("{src}: animation 0: channel 0: 1 rotations for 2 frame times")
    );
    assert_eq!(
        bad(r(0, vec![1.0, 1.0 + 1e-9], vec![(0, vec![q, q])])),
        format!(
            "{src}: animation 0: frame times 0 and 1 s are the same float32: expected strictly increasing float32 times"
        )
    );
    let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    assert!(bad(r(0, vec![0.0], vec![(0, vec![zero])])).contains("rotation 0 is"));
    assert!(bad(r(0, vec![0.0], vec![(0, vec![q]), (0, vec![q])])).contains("resampled twice"));
}

#[test]
fn container_from_extension() {
    assert_eq!(
        ContainerFormat::from_path(Path::new("a.GLB")),
        Some(ContainerFormat::Glb)
    );
    assert_eq!(
        ContainerFormat::from_path(Path::new("a.gltf")),
        Some(ContainerFormat::Gltf)
    );
    assert_eq!(ContainerFormat::from_path(Path::new("a.json")), None);
}

// ---- the Khronos glTF Validator ----

/// `node tools/gltf-validator/validate.js FILE`, when node and the validator's node_modules
/// are installed (`npm ci --prefix tools/gltf-validator`); `None` (and a note) otherwise.
fn validator() -> Option<PathBuf> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("tools/gltf-validator");
    let installed = dir.join("node_modules/gltf-validator").is_dir();
    let node = std::process::Command::new("node")
        .arg("--version")
        .output()
        .is_ok();
    if installed && node {
        Some(dir.join("validate.js"))
    } else {
        // CI installs it and sets this, so that a missing validator fails instead of skipping.
        assert!(
            std::env::var_os("INBETWEEN_REQUIRE_GLTF_VALIDATOR").is_none(),
            "the glTF Validator is required but not installed: npm ci --prefix tools/gltf-validator"
        );
        eprintln!(
            "note: glTF Validator test skipped: needs node and `npm ci --prefix tools/gltf-validator`"
        );
        None
    }
}

fn validate(script: &Path, file: &Path) {
    let out = std::process::Command::new("node")
        .arg(script)
        .arg(file)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}: the glTF Validator reports errors:\n{}\n{}",
        file.display(),
        String::from_utf8_lossy(&out.stderr),
        String::from_utf8_lossy(&out.stdout)
    );
}

#[test]
fn written_assets_pass_the_khronos_validator() {
    let Some(script) = validator() else { return };
    let dir = tempfile::tempdir().unwrap();
    for input in ["samplers.gltf", "samplers.glb", "minimal_linear.gltf"] {
        validate(&script, &fixture(input));
        let asset = read(input);
        let r = resample_all(&asset, 24.0);
        for format in [ContainerFormat::Glb, ContainerFormat::Gltf] {
            let ext = match format {
                ContainerFormat::Glb => "glb",
                ContainerFormat::Gltf => "gltf",
            };
            let path = dir.path().join(format!("{input}.out.{ext}"));
            std::fs::write(&path, write_to(&asset, &r, format)).unwrap();
            // External buffers stay beside the output.
            std::fs::copy(fixture("samplers.bin"), dir.path().join("samplers.bin")).unwrap();
            validate(&script, &path);
        }
    }
}

/// Found by the `gltf_reader` fuzz target: the `gltf` crate's validation indexes `accessors`
/// with a primitive's `POSITION` before checking it, and panicked.
#[test]
fn a_position_accessor_that_does_not_exist_is_an_error_not_a_panic() {
    let json = br#"{"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 5}}]}]}"#;
    let err = Asset::from_slice(json, "m.gltf", None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("meshes[0].primitives[0].attributes.POSITION: accessor 5 does not exist"),
        "{err}"
    );
}
