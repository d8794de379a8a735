//! Tangents animators control (docs/spec.md §4.1–§4.2): per-key angular velocities,
//! Kochanek–Bartels tension/continuity/bias against the 1-D formula of their paper, and cyclic
//! tracks (C¹ across the seam, equal to the middle of the track played twice).

use glam::{DQuat, DVec3};
use inbetween::rotation::quat::rotation_angle_between as angle;
use inbetween::{Curve, CurveOptions, Ends, Scheme, Tcb, Track};

const SMOOTH: [Scheme; 3] = [Scheme::Hermite, Scheme::Bezier, Scheme::Squad];

fn opts(scheme: Scheme) -> CurveOptions {
    CurveOptions {
        scheme,
        ..CurveOptions::default()
    }
}

/// One-sided angular velocities at `t` (rad/s): chords of the curve just before and just after,
/// extrapolated to `t` (second order; the curve's own `angular_velocity` is the right side at
/// a key).
fn sides(curve: &Curve, t: f64) -> (DVec3, DVec3) {
    let h = 1e-4;
    let chord = |a: f64, b: f64| {
        let (qa, qb) = (curve.rotation(a), curve.rotation(b));
        let mut d = qb * qa.conjugate();
        if d.w < 0.0 {
            d = -d;
        }
        d.to_scaled_axis() / (b - a)
    };
    let side = |s: f64| {
        let near = chord(t.min(t + s * h), t.max(t + s * h));
        let far = chord(
            (t + s * h).min(t + 2.0 * s * h),
            (t + s * h).max(t + 2.0 * s * h),
        );
        (near * 3.0 - far) * 0.5
    };
    (side(-1.0), side(1.0))
}

/// Keys about z at `angles` (radians) and `times`.
fn about_z(times: &[f64], angles: &[f64]) -> Track {
    let q = angles.iter().map(|a| DQuat::from_rotation_z(*a)).collect();
    Track::new(times.to_vec(), q).unwrap()
}

#[test]
fn tcb_on_one_axis_is_kochanek_and_bartels_formula() {
    // On one axis rotations commute, so the S³ composition is their tangent exactly:
    // ω_out = 2(a_out·Δθ⁻ + b_out·Δθ⁺)/(t_{i+1} − t_{i−1}) per their unequal-spacing rule.
    let times = [0.0, 0.4, 1.3, 1.9, 3.0];
    let angles = [0.0, 0.5, 0.7, 1.6, 1.5];
    let track = about_z(&times, &angles);
    let tcb = Tcb {
        tension: 0.5,
        continuity: -0.5,
        bias: 0.3,
    };
    let (t, c, b) = (tcb.tension, tcb.continuity, tcb.bias);
    for scheme in [Scheme::Hermite, Scheme::Bezier] {
        let curve = Curve::new(
            &track,
            &CurveOptions {
                tcb,
                ..opts(scheme)
            },
        )
        .unwrap();
        for i in 1..times.len() - 1 {
            let (dm, dp) = (angles[i] - angles[i - 1], angles[i + 1] - angles[i]);
            let span = times[i + 1] - times[i - 1];
            // Destination (leaving) and source (arriving) derivatives of their eqs. 8-9.
            let out = (1.0 - t) * ((1.0 + b) * (1.0 + c) * dm + (1.0 - b) * (1.0 - c) * dp) / span;
            let inc = (1.0 - t) * ((1.0 + b) * (1.0 - c) * dm + (1.0 - b) * (1.0 + c) * dp) / span;
            let (left, right) = sides(&curve, times[i]);
            assert!(
                (right.z - out).abs() < 1e-5,
                "{scheme} key {i}: {} vs {out}",
                right.z
            );
            assert!(
                (left.z - inc).abs() < 1e-5,
                "{scheme} key {i}: {} vs {inc}",
                left.z
            );
            assert!(right.x.abs() + right.y.abs() < 1e-9);
        }
    }
}

#[test]
fn zero_tcb_is_todays_tangent_exactly_and_continuity_makes_a_corner() {
    let q = [
        DQuat::IDENTITY,
        DQuat::from_axis_angle(DVec3::new(0.0, 0.6, 0.8), 0.9),
        DQuat::from_euler(glam::EulerRot::ZYX, 0.9, -0.4, 1.3),
        DQuat::from_rotation_x(2.0),
    ];
    let track = Track::new(vec![0.0, 0.5, 1.25, 2.0], q.to_vec()).unwrap();
    let zeros = track
        .clone()
        .with_key_tcb(vec![Some(Tcb::ZERO); 4])
        .unwrap();
    for scheme in SMOOTH {
        let a = Curve::new(&track, &opts(scheme)).unwrap();
        let b = Curve::new(&zeros, &opts(scheme)).unwrap();
        for j in 0..=40 {
            let t = 2.0 * j as f64 / 40.0;
            assert_eq!(a.rotation(t), b.rotation(t), "{scheme} at {t}");
        }
        // A corner with continuity, smooth without.
        let corner = CurveOptions {
            tcb: Tcb {
                continuity: 0.8,
                ..Tcb::ZERO
            },
            ..opts(scheme)
        };
        let c = Curve::new(&track, &corner).unwrap();
        let (l, r) = sides(&c, 0.5);
        assert!((l - r).length() > 0.1, "{scheme}: {l} {r}");
        let (l, r) = sides(&a, 0.5);
        assert!((l - r).length() < 1e-4 * l.length(), "{scheme}: {l} {r}");
    }
}

#[test]
fn a_keys_own_velocity_is_the_curves_velocity_there() {
    let q = [
        DQuat::IDENTITY,
        DQuat::from_rotation_y(0.8),
        DQuat::from_axis_angle(DVec3::new(1.0, 0.0, 1.0).normalize(), 1.4),
        DQuat::from_rotation_z(0.3),
    ];
    let omega = DVec3::new(0.4, -1.2, 2.0);
    let track = Track::new(vec![0.0, 1.0, 1.5, 3.0], q.to_vec())
        .unwrap()
        .with_key_velocities(vec![
            None,
            Some(omega),
            None,
            Some(DVec3::new(0.0, 0.0, -1.0)),
        ])
        .unwrap();
    for scheme in SMOOTH {
        let curve = Curve::new(&track, &opts(scheme)).unwrap();
        let (l, r) = sides(&curve, 1.0);
        assert!(
            (l - omega).length() < 1e-5 && (r - omega).length() < 1e-5,
            "{scheme}: {l} {r}"
        );
        let end = curve.angular_velocity(3.0);
        assert!(
            (end - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-6,
            "{scheme}: {end}"
        );
    }
    // minaccel holds it at the key: the grid neighbours carry exactly that velocity.
    let curve = Curve::new(&track, &opts(Scheme::MinAccel)).unwrap();
    let (l, r) = sides(&curve, 1.0);
    assert!(
        (l - omega).length() < 1e-6 && (r - omega).length() < 1e-6,
        "minaccel: {l} {r}"
    );
}

/// A loop: four keys whose last is the first key's rotation (the quaternion negated).
fn a_loop() -> Track {
    let q = [
        DQuat::IDENTITY,
        DQuat::from_axis_angle(DVec3::new(0.0, 0.6, 0.8), 1.1),
        DQuat::from_euler(glam::EulerRot::ZYX, 0.9, -0.4, 1.3),
        -DQuat::IDENTITY,
    ];
    Track::new(vec![0.0, 0.5, 1.25, 2.0], q.to_vec()).unwrap()
}

#[test]
fn a_cyclic_track_is_the_middle_of_the_loop_played_three_times() {
    let track = a_loop();
    let (times, q) = (track.times(), track.rotations());
    // Three times end to end: the spline tangent's window reaches three keys each side, so the
    // middle copy's keys see the loop's neighbours on both sides.
    let mut t3 = times.to_vec();
    let mut q3 = q.to_vec();
    for c in 1..3 {
        for i in 1..4 {
            t3.push(times[i] + 2.0 * c as f64);
            q3.push(q[i]);
        }
    }
    let thrice = Track::new(t3, q3).unwrap();
    for scheme in SMOOTH {
        let cyclic = CurveOptions {
            ends: Ends::Cyclic.into(),
            ..opts(scheme)
        };
        let curve = Curve::new(&track, &cyclic).unwrap();
        let (l, _) = sides(&curve, 2.0);
        let (_, r) = sides(&curve, 0.0);
        assert!(
            (l - r).length() < 1e-5 * r.length(),
            "{scheme} seam: {l} vs {r}"
        );
        // Its first and last segments are the middle copy's segments beside its seams.
        let doubled = Curve::new(&thrice, &opts(scheme)).unwrap();
        for j in 0..=20 {
            let u = j as f64 / 20.0;
            for (t, t_twice) in [(0.5 * u, 2.0 + 0.5 * u), (1.25 + 0.75 * u, 3.25 + 0.75 * u)] {
                let d = angle(curve.rotation(t), doubled.rotation(t_twice));
                assert!(d < 1e-12, "{scheme} at {t}: {d}");
            }
        }
    }
}

#[test]
fn minaccels_seam_is_an_interior_key_of_the_loop_played_many_times() {
    let track = a_loop();
    let cyclic = CurveOptions {
        ends: Ends::Cyclic.into(),
        ..opts(Scheme::MinAccel)
    };
    let curve = Curve::new(&track, &cyclic).unwrap();
    assert!(curve.solver_report().unwrap().converged);
    // The loop played nine times with free ends: its middle copy is far (12 keys) from them.
    let (times, q) = (track.times(), track.rotations());
    let (mut t9, mut q9) = (vec![times[0]], vec![q[0]]);
    for c in 0..9 {
        let sign = if c % 2 == 0 { 1.0 } else { -1.0 };
        for i in 1..4 {
            t9.push(times[i] + 2.0 * c as f64);
            q9.push(q[i] * sign);
        }
    }
    let long = Curve::new(&Track::new(t9, q9).unwrap(), &opts(Scheme::MinAccel)).unwrap();
    for j in 0..=60 {
        let t = 2.0 * j as f64 / 60.0;
        let d = angle(curve.rotation(t), long.rotation(t + 8.0));
        assert!(d < 1e-5, "at {t}: {d}");
    }
    // No rougher at the seam than that interior key: the same jump of the angular velocity
    // across it (one grid step each side).
    let seam = (sides(&curve, 2.0).0 - sides(&curve, 0.0).1).length();
    let inside = (sides(&long, 8.0).0 - sides(&long, 8.0).1).length();
    assert!(
        (seam - inside).abs() < 1e-4 * inside,
        "seam {seam} vs {inside}"
    );
}

#[test]
fn what_cannot_be_is_refused() {
    let track = a_loop();
    let err = |track: &Track, o: CurveOptions| Curve::new(track, &o).unwrap_err().to_string();
    let open = Track::new(
        vec![0.0, 1.0],
        vec![DQuat::IDENTITY, DQuat::from_rotation_z(0.5)],
    )
    .unwrap();
    let cyclic = |scheme| CurveOptions {
        ends: Ends::Cyclic.into(),
        ..opts(scheme)
    };
    assert_eq!(
        err(&open, cyclic(Scheme::Bezier)),
        "ends cyclic: the last key is 28.64788975654116° from the first key's rotation (a loop \
         needs them equal within 1e-6 rad)"
    );
    let mut given = cyclic(Scheme::Bezier);
    given.ends.start = Some(DVec3::X);
    assert_eq!(
        err(&track, given),
        "ends cyclic: a loop has no ends, so start and end velocities do not apply"
    );
    let shaped = CurveOptions {
        tcb: Tcb {
            tension: 0.2,
            ..Tcb::ZERO
        },
        ..opts(Scheme::MinAccel)
    };
    assert!(err(&track, shaped).starts_with("minaccel has no tangents to shape"));
    let bad = CurveOptions {
        tcb: Tcb {
            bias: 1.5,
            ..Tcb::ZERO
        },
        ..opts(Scheme::Hermite)
    };
    assert!(err(&track, bad).contains("between -1 and 1"));
    assert!(track.clone().with_key_tcb(vec![None; 3]).is_err());
    assert!(
        track
            .with_key_velocities(vec![None, Some(DVec3::NAN), None, None])
            .is_err()
    );
}
