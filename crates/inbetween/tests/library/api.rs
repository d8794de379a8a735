//! The crate-root API as a game engine would use it — no CSV, no `io`: off the grid a
//! [`Curve`]'s velocity and acceleration agree with finite differences of itself; tracks refuse
//! bad times with typed errors; baking over a clip holds the end keys. (That at frame times it
//! gives what `interp` writes is checked against the binary in
//! crates/inbetween-cli/tests/binary/api.rs.)

use crate::support::{
    Collect, api_keys as keys, api_options as options, api_track as track, assert_rot_close,
    assert_vec_close,
};
use glam::{DQuat, DVec3};
use inbetween::{
    BakeOptions, Curve, CurveOptions, EndConditions, Ends, Fps, Scheme, Track, TrackError,
};

#[test]
fn off_the_grid_derivatives_agree_with_finite_differences() {
    let track = track();
    // Irrational-ish times: off every frame grid and every key.
    let times: Vec<f64> = (1..60).map(|i| i as f64 * 0.0333 * 1.0041).collect();
    for scheme in Scheme::ALL {
        let curve = Curve::new(&track, &options(scheme, Fps::new(120, 1).unwrap())).unwrap();
        // minaccel is great arcs between grid points: smooth only within a grid interval.
        let h = if scheme == Scheme::MinAccel {
            1e-6
        } else {
            1e-5
        };
        for &t in &times {
            let what = format!("{scheme} at t = {t}");
            let q = curve.rotation(t);
            assert!(
                (q.length() - 1.0).abs() < 1e-12,
                "{what}: |q| = {}",
                q.length()
            );
            // ω = 2·(dq/dt)·q⁻¹, dq/dt by central differences of the rotation itself.
            let (a, b) = (curve.rotation(t - h), curve.rotation(t + h));
            let b = if a.dot(b) < 0.0 { -b } else { b };
            let p = (b - a) * (1.0 / (2.0 * h)) * q.conjugate();
            let fd = DVec3::new(p.x, p.y, p.z) * 2.0;
            assert_vec_close(curve.angular_velocity(t), fd, 1e-6, &what);
            if scheme != Scheme::MinAccel {
                let fd =
                    (curve.angular_velocity(t + h) - curve.angular_velocity(t - h)) / (2.0 * h);
                assert_vec_close(curve.angular_acceleration(t), fd, 1e-5, &what);
            }
        }
        // Through every key, exactly.
        for (tk, qk) in track.times().iter().zip(track.rotations()) {
            assert_eq!(curve.rotation(*tk), *qk, "{scheme} key at {tk}");
        }
    }
}

#[test]
fn tracks_refuse_bad_times_with_typed_errors() {
    let (_, q) = keys();
    let q3 = q[..3].to_vec();
    let new = |t: &[f64]| Track::new(t.to_vec(), q3.clone()).unwrap_err();
    assert_eq!(
        new(&[0.0, 1.0, 0.5]),
        TrackError::NotIncreasing {
            index: 2,
            time: 0.5,
            previous: 1.0
        }
    );
    assert_eq!(
        new(&[0.0, 0.5, 0.5]),
        TrackError::NotIncreasing {
            index: 2,
            time: 0.5,
            previous: 0.5
        }
    );
    assert!(matches!(
        new(&[0.0, f64::NAN, 1.0]),
        TrackError::NonFiniteTime { index: 1, .. }
    ));
    assert!(matches!(
        new(&[0.0, f64::INFINITY, 1.0]),
        TrackError::NonFiniteTime { index: 1, .. }
    ));
    assert_eq!(
        new(&[0.0, 0.5, 0.5 + 1e-13]),
        TrackError::TooClose {
            index: 2,
            time: 0.5 + 1e-13,
            previous: 0.5
        }
    );
    assert_eq!(
        Track::new(vec![0.0], vec![q[0]]).unwrap_err(),
        TrackError::TooFewKeys { found: 1 }
    );
    // The library's message is the binary's.
    assert_eq!(
        new(&[0.0, 1.0, 0.5]).to_string(),
        "expected times strictly increasing within a track, found 0.5 s after 1 s"
    );
}

#[test]
fn a_one_key_track_is_a_constant() {
    let q = DQuat::from_rotation_y(0.7);
    let track = Track::constant(0.5, q).unwrap();
    for scheme in Scheme::ALL {
        let curve = Curve::new(&track, &options(scheme, Fps::DEFAULT)).unwrap();
        assert!(curve.is_constant());
        for t in [-1.0, 0.5, 0.51, 3.0] {
            assert_eq!(curve.rotation(t), q, "{scheme} at {t}");
            assert_eq!(curve.angular_velocity(t), DVec3::ZERO);
            assert_eq!(curve.angular_acceleration(t), DVec3::ZERO);
        }
        // Baked over a clip of one second at 10 fps: eleven frames of the key, at rest.
        let mut sink = Collect::default();
        let opts = BakeOptions {
            velocity: true,
            parallel: false,
        };
        let fps = Fps::new(10, 1).unwrap();
        inbetween::bake_over(&curve, fps, (0.0, 1.0), opts, &mut sink, &mut |w| {
            panic!("{w}")
        })
        .unwrap();
        assert_eq!(sink.frames.len(), 11);
        assert!(
            sink.frames
                .iter()
                .all(|f| f.2 == q && f.3 == Some(DVec3::ZERO))
        );
    }
}

#[test]
fn bake_over_a_clip_holds_the_end_keys() {
    let track = track();
    let fps = Fps::new(10, 1).unwrap();
    let curve = Curve::new(&track, &options(Scheme::Hermite, fps)).unwrap();
    let mut sink = Collect::default();
    let opts = BakeOptions {
        velocity: true,
        parallel: false,
    };
    inbetween::bake_over(&curve, fps, (-0.3, 2.25), opts, &mut sink, &mut |_| {}).unwrap();
    let ks: Vec<i64> = sink.frames.iter().map(|f| f.0).collect();
    assert_eq!(ks, (-3..=22).collect::<Vec<_>>());
    let (first, last) = (track.rotations()[0], track.rotations()[4]);
    for f in &sink.frames {
        if f.1 < 0.0 {
            assert_eq!((f.2, f.3), (first, Some(DVec3::ZERO)), "frame {}", f.0);
        } else if f.1 > 2.0 {
            assert_eq!((f.2, f.3), (last, Some(DVec3::ZERO)), "frame {}", f.0);
        } else {
            assert_rot_close(f.2, curve.rotation(f.1), 1e-13, "inside");
        }
    }
}

/// A given end velocity of 10⁶ °/s over a 0.1 s segment (about 280 turns): the velocity reported
/// at the key is the given one to 1e-9 relative (the difference step shrinks with the turn).
#[test]
fn fast_given_spins_report_their_velocity() {
    let q = [
        DQuat::IDENTITY,
        DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
    ];
    let track = Track::new(vec![0.0, 0.1], q.to_vec()).unwrap();
    for deg_per_s in [1e5, 1e6, 1e7] {
        let w = DVec3::new(0.0, 0.0, f64::to_radians(deg_per_s));
        let opts = CurveOptions {
            ends: EndConditions {
                ends: Ends::Chord,
                start: Some(w),
                end: None,
            },
            // hermite follows a tangent of many turns per segment (bezier warns instead).
            scheme: Scheme::Hermite,
            ..CurveOptions::default()
        };
        let curve = Curve::new(&track, &opts).unwrap();
        assert_vec_close(
            curve.angular_velocity(0.0),
            w,
            1e-9,
            &format!("{deg_per_s} deg/s"),
        );
    }
}

#[test]
fn short_segments_are_checked_and_evaluated_as_long_ones() {
    // Identical keys half a second apart spinning at 100 turns/s at the ends (as given): the
    // Bézier's legs come near an antipode. At 4 and 6 fps a segment holds one or two frames
    // (evaluated four at a time, segments built in lanes), at 60 fps thirty (forward
    // differences): the same warnings, once per segment, in order, and frames on the curve.
    let q = DQuat::IDENTITY;
    let track = Track::new(vec![0.0, 0.5, 1.0, 1.5], vec![q; 4]).unwrap();
    let omega = DVec3::new(0.0, 0.0, 200.0 * std::f64::consts::PI);
    let mut opts = options(Scheme::Bezier, Fps::new(60, 1).unwrap());
    opts.path = inbetween::PathMode::AsGiven;
    opts.ends = EndConditions {
        ends: Ends::Chord,
        start: Some(omega),
        end: Some(omega),
    };
    let curve = Curve::new(&track, &opts).unwrap();
    let bake = |fps: Fps, velocity: bool| {
        let (mut sink, mut warnings) = (Collect::default(), Vec::new());
        let opts = BakeOptions {
            velocity,
            parallel: false,
        };
        inbetween::bake(&curve, fps, opts, &mut sink, &mut |w| {
            warnings.push(w.to_string())
        })
        .unwrap();
        (sink.frames, warnings)
    };
    let (_, dense) = bake(Fps::new(60, 1).unwrap(), false);
    assert!(!dense.is_empty() && dense.iter().all(|w| w.contains("antipode")));
    for rate in [4, 6] {
        let (frames, warnings) = bake(Fps::new(rate, 1).unwrap(), false);
        assert_eq!(warnings, dense, "{rate} fps");
        assert_eq!(frames.len(), 1 + 3 * rate as usize / 2);
        for (k, t, q, _) in &frames {
            let off = (*q - curve.rotation(*t)).length();
            assert!(
                off < 1e-12 && q.is_finite(),
                "{rate} fps, frame {k}: {off:e}"
            );
        }
        // With velocities: the same rotations, to the bit, and the curve's velocities.
        let (with, _) = bake(Fps::new(rate, 1).unwrap(), true);
        assert_eq!(with.len(), frames.len());
        for (a, b) in frames.iter().zip(&with) {
            assert_eq!(
                a.2.to_array().map(f64::to_bits),
                b.2.to_array().map(f64::to_bits)
            );
            let w = b.3.expect("a velocity");
            let off = (w - curve.angular_velocity(b.1)).length();
            assert!(
                off <= 1e-6 * w.length().max(1.0),
                "{rate} fps at {}: {off:e}",
                b.1
            );
        }
    }
}
