//! `PathMode::Euler` (docs/spec.md §4.3): Euler keys keep their turns under every scheme — the
//! curve's own angle about the spin axis, followed densely, sweeps exactly the keys' angles —
//! and a track without Euler angles is refused.

use glam::{DQuat, DVec3};
use inbetween::{Curve, CurveOptions, EulerSeq, PathMode, Scheme, Track};

/// A track of single-axis keys: `channel` of `seq` takes `angles` (degrees) at `times`, the
/// other two channels fixed.
fn spin(seq: &str, channel: usize, times: &[f64], angles: &[f64]) -> Track {
    let seq = EulerSeq::parse(seq).unwrap();
    let e: Vec<DVec3> = angles
        .iter()
        .map(|a| {
            let mut e = [0.3, -0.2, 0.1];
            e[channel] = a.to_radians();
            DVec3::from_array(e)
        })
        .collect();
    let q = e.iter().map(|e| seq.to_quat(e.to_array())).collect();
    Track::new(times.to_vec(), q)
        .unwrap()
        .with_euler_angles(seq, e)
        .unwrap()
}

/// The angle (degrees) the curve turns from its start to `t`, followed through `n` samples per
/// second (each step well under half a turn), about the spin's fixed axis.
fn turned(curve: &Curve, t1: f64, n: usize) -> f64 {
    let (t0, _) = curve.span();
    let steps = ((t1 - t0) * n as f64).ceil() as usize;
    let mut total = 0.0;
    let mut prev = curve.rotation(t0);
    let axis = (1..=steps)
        .map(|j| {
            let q = curve.rotation(t0 + (t1 - t0) * j as f64 / steps as f64);
            let (ax, _) = (q * curve.rotation(t0).conjugate()).to_axis_angle();
            ax
        })
        .find(|a| a.is_finite() && a.length() > 0.5)
        .unwrap_or(DVec3::Z);
    for j in 1..=steps {
        let q = curve.rotation(t0 + (t1 - t0) * j as f64 / steps as f64);
        let mut d = q * prev.conjugate();
        if d.w < 0.0 {
            d = -d;
        }
        let v = DVec3::new(d.x, d.y, d.z);
        assert!(
            v.cross(axis).length() < 1e-9,
            "off the spin axis: step {v} vs axis {axis}"
        );
        total += 2.0 * v.dot(axis).atan2(d.w);
        prev = q;
    }
    total.to_degrees() * if axis.z < 0.0 { -1.0 } else { 1.0 }
}

#[test]
fn spins_keep_their_turns_under_every_scheme() {
    // (sequence, channel, key angles): the z channel of ZYX, an inner channel, an extrinsic one.
    let cases: [(&str, usize, [f64; 3]); 4] = [
        ("ZYX", 0, [0.0, 270.0, 300.0]),
        ("ZYX", 0, [0.0, 720.0, 720.0]),
        ("XYZ", 1, [10.0, -440.0, -490.0]),
        ("zxz", 2, [0.0, 360.0, 380.0]),
    ];
    for (seq, channel, angles) in cases {
        let track = spin(seq, channel, &[0.0, 1.0, 2.0], &angles);
        for scheme in Scheme::ALL {
            let opts = CurveOptions {
                scheme,
                path: PathMode::Euler,
                ..CurveOptions::default()
            };
            if scheme == Scheme::Nlerp {
                // A blend of two quaternions cannot keep a whole turn: refused.
                let err = Curve::new(&track, &opts).unwrap_err().to_string();
                assert!(err.contains("path euler: nlerp"), "{err}");
                continue;
            }
            let curve = Curve::new(&track, &opts).unwrap();
            for (t, want) in [(1.0, angles[1] - angles[0]), (2.0, angles[2] - angles[0])] {
                let got = turned(&curve, t, 2000);
                // The sign of the axis found is arbitrary: compare magnitudes, then the sense
                // against a short step.
                assert!(
                    (got.abs() - want.abs()).abs() < 1e-6,
                    "{seq} {angles:?} {scheme}: turned {got}° by {t} s, want {want}°"
                );
            }
        }
    }
}

#[test]
fn slerp_spin_is_linear_in_the_angle() {
    let track = spin("ZYX", 0, &[0.0, 1.5], &[0.0, -450.0]);
    let opts = CurveOptions {
        scheme: Scheme::Slerp,
        path: PathMode::Euler,
        ..CurveOptions::default()
    };
    let curve = Curve::new(&track, &opts).unwrap();
    let seq = EulerSeq::parse("ZYX").unwrap();
    for j in 0..=30 {
        let t = 1.5 * j as f64 / 30.0;
        let want = seq.to_quat([(-450.0 * t / 1.5f64).to_radians(), -0.2, 0.1]);
        let got = curve.rotation(t);
        assert!(
            got.dot(want).abs() > 1.0 - 1e-24 || (got.dot(want).abs() - 1.0).abs() < 1e-15,
            "t {t}: {got} vs {want}"
        );
        // Constant angular velocity: 300°/s about the world z axis (the first channel).
        let w = curve.angular_velocity(t);
        assert!((w - DVec3::new(0.0, 0.0, (-300f64).to_radians())).length() < 1e-9);
    }
}

#[test]
fn euler_path_needs_euler_angles() {
    let track = Track::new(
        vec![0.0, 1.0],
        vec![DQuat::IDENTITY, DQuat::from_rotation_z(1.0)],
    )
    .unwrap()
    .with_name("hip");
    let opts = CurveOptions {
        path: PathMode::Euler,
        ..CurveOptions::default()
    };
    let err = Curve::new(&track, &opts).unwrap_err();
    assert_eq!(
        err.to_string(),
        "track \"hip\": path euler: the track's keys carry no Euler angles \
         (Track::with_euler_angles)"
    );
    // Triples that are not the keys' rotations are refused, with the key.
    let zyx = EulerSeq::parse("ZYX").unwrap();
    let e = track
        .clone()
        .with_euler_angles(zyx, vec![DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0)])
        .unwrap_err();
    assert_eq!(e.index(), Some(1));
    let msg = e.to_string();
    let away: f64 = msg
        .strip_prefix("expected Euler angles of the key's rotation (within 1e-6 rad), found ")
        .and_then(|r| r.strip_suffix(" rad away"))
        .and_then(|r| r.parse().ok())
        .unwrap_or_else(|| panic!("{msg}"));
    assert!((away - 1.0).abs() < 1e-12, "{msg}");
}
