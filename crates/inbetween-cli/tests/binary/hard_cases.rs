//! Hard cases (issue 3): identical keys, 179.9° and exactly 180° steps, the log of −1, keys 1 µs
//! apart, 100 full turns, and the antipodal-blend warning of docs/spec.md §4.3.

use crate::support::{interpolate, rot_angle, settings, track};
use assert_cmd::Command;
use glam::{DQuat, DVec3};
use inbetween::{EndConditions, Ends, PathMode, Scheme};
use std::f64::consts::PI;

const SCHEMES: [Scheme; 4] = [
    Scheme::Hermite,
    Scheme::Squad,
    Scheme::Bezier,
    Scheme::Slerp,
];

fn all_sane(frames: &[(i64, f64, DQuat)]) {
    for (k, _, q) in frames {
        assert!(q.is_finite(), "frame {k}: {q}");
        assert!(
            (q.length() - 1.0).abs() < 1e-12,
            "frame {k}: |q| = {}",
            q.length()
        );
    }
}

#[test]
fn identical_keys_stay_put() {
    let a = DQuat::from_euler(glam::EulerRot::ZYX, 0.3, 0.2, 0.1);
    let t = track(vec![0.0, 0.5, 1.0], vec![a, a, a]);
    for scheme in SCHEMES {
        let (frames, warnings) = interpolate(&t, &settings(scheme, "30", EndConditions::default()));
        assert_eq!(frames.len(), 31);
        for (_, _, q) in &frames {
            assert!((*q - a).length() < 1e-15, "{scheme:?}: {q}");
        }
        assert!(warnings.is_empty());
    }
}

#[test]
fn identical_consecutive_keys_between_others() {
    let a = DQuat::IDENTITY;
    let b = DQuat::from_rotation_y(1.2);
    let t = track(vec![0.0, 0.4, 0.8, 1.5], vec![a, a, b, b]);
    for scheme in SCHEMES {
        let (frames, _) = interpolate(&t, &settings(scheme, "24", EndConditions::default()));
        all_sane(&frames);
    }
}

#[test]
fn step_of_179_9_and_180_1_degrees() {
    let a = DQuat::IDENTITY;
    for deg in [179.9f64, 180.1] {
        let b = DQuat::from_rotation_z(deg.to_radians());
        let t = track(vec![0.0, 1.0], vec![a, b]);
        let (frames, _) = interpolate(
            &t,
            &settings(Scheme::Slerp, "100", EndConditions::default()),
        );
        all_sane(&frames);
        // shortest: the turn is 179.9° either way (180.1° is taken as −179.9°).
        let travelled: f64 = frames.windows(2).map(|w| rot_angle(w[0].2, w[1].2)).sum();
        assert!(
            (travelled - 179.9f64.to_radians()).abs() < 1e-9,
            "{deg}: {travelled}"
        );
        let mid = frames[50].2;
        let want = DQuat::from_rotation_z(if deg < 180.0 { 89.95f64 } else { -89.95 }.to_radians());
        assert!(rot_angle(mid, want) < 1e-12, "{deg}: {mid}");
    }
}

#[test]
fn exactly_180_degree_step() {
    let a = DQuat::from_rotation_x(0.3);
    let b = DQuat::from_rotation_z(PI) * a;
    assert!(a.dot(b).abs() < 1e-15);
    let t = track(vec![0.0, 1.0, 2.0], vec![a, b, a]);
    for scheme in SCHEMES {
        let (frames, _) = interpolate(&t, &settings(scheme, "30", EndConditions::default()));
        all_sane(&frames);
    }
    let (frames, _) = interpolate(&t, &settings(Scheme::Slerp, "30", EndConditions::default()));
    let half = frames[15].2;
    assert!(rot_angle(half, DQuat::from_rotation_z(PI / 2.0) * a) < 1e-12);
}

#[test]
fn log_of_minus_one_turns_about_world_x() {
    // as-given keys q and −q: a full turn, whose axis the keys do not say; we turn about x.
    let t = track(vec![0.0, 1.0], vec![DQuat::IDENTITY, -DQuat::IDENTITY]);
    let mut s = settings(Scheme::Slerp, "8", EndConditions::default());
    s.path = PathMode::AsGiven;
    let (frames, _) = interpolate(&t, &s);
    all_sane(&frames);
    for (k, _, q) in &frames {
        let want = DQuat::from_rotation_x(2.0 * PI * *k as f64 / 8.0);
        assert!((*q - want).length() < 1e-14, "frame {k}: {q}");
    }
}

#[test]
fn keys_one_microsecond_apart() {
    let t = track(
        vec![0.0, 1e-6, 1.0],
        vec![
            DQuat::IDENTITY,
            DQuat::from_rotation_y(1e-4),
            DQuat::from_rotation_x(1.0),
        ],
    );
    for scheme in SCHEMES {
        for ends in [Ends::Chord, Ends::Rest] {
            let e = EndConditions {
                ends,
                ..Default::default()
            };
            let (frames, _) = interpolate(&t, &settings(scheme, "30", e));
            assert_eq!(frames.len(), 31);
            all_sane(&frames);
            // No wild excursion: the curve stays within the keys' neighbourhood.
            for (_, _, q) in &frames {
                assert!(
                    rot_angle(*q, DQuat::IDENTITY) < 1.5,
                    "{scheme:?} {ends:?}: {q}"
                );
            }
        }
    }
}

#[test]
fn hundred_full_turns_with_end_velocities() {
    // Two identical keys 1 s apart spinning at 100 turns/s about z: 36° per frame at 1000 fps.
    let t = track(vec![0.0, 1.0], vec![DQuat::IDENTITY, DQuat::IDENTITY]);
    let omega = DVec3::new(0.0, 0.0, 200.0 * PI);
    let e = EndConditions {
        ends: Ends::Chord,
        start: Some(omega),
        end: Some(omega),
    };
    let mut s = settings(Scheme::Hermite, "1000", e);
    s.path = PathMode::AsGiven;
    let (frames, warnings) = interpolate(&t, &s);
    assert_eq!(frames.len(), 1001);
    all_sane(&frames);
    assert!(warnings.is_empty(), "{warnings:?}");
    for w in frames.windows(2) {
        let step = rot_angle(w[0].2, w[1].2);
        assert!((step - 36f64.to_radians()).abs() < 1e-9, "step {step}");
    }
    // Bézier's middle control leg is a geodesic and squad's inner points alias: neither can carry
    // 100 turns in one segment. Their output stays finite and unit, and they say so.
    for (scheme, says) in [
        (Scheme::Bezier, "antipode"),
        (Scheme::Squad, "inner control point"),
    ] {
        let mut s = settings(scheme, "1000", e);
        s.path = PathMode::AsGiven;
        let (frames, warnings) = interpolate(&t, &s);
        all_sane(&frames);
        assert!(
            warnings.iter().any(|w| w.contains(says)),
            "{scheme:?}: {warnings:?}"
        );
    }
}

#[test]
fn antipodal_blend_is_reported() {
    // Identical keys with one turn per second at both ends: Hermite's C₁(u) = −C₂(u) everywhere.
    let out = Command::cargo_bin("inbetween")
        .unwrap()
        .args([
            "interp",
            "-",
            "--scheme",
            "hermite",
            "--fps",
            "10",
            "--start-velocity",
            "0,0,360",
            "--end-velocity",
            "0,0,360",
            "--input-format",
            "csv",
        ])
        .write_stdin("track,time,w,x,y,z\nhip,0,1,0,0,0\nhip,1,1,0,0,0\n")
        .output()
        .unwrap();
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with(
            "inbetween: warning: track \"hip\", segment 0 (0 s to 1 s): a blend of the hermite \
             curve comes within 0.0e0 of an antipode"
        ),
        "{stderr}"
    );
    assert!(stderr.contains("add keys or use --scheme minaccel"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(stdout.lines().count(), 12);
    assert!(!stdout.contains("NaN"));
}
