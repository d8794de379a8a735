//! `minaccel` (issue 4): the geodesic for two keys, agreement with an independent dense
//! optimiser (offline scipy, `fixtures/minaccel/`), convergence, end velocities, and two full
//! turns. (Energy below every other scheme on the same grid, on every track of the interp
//! fixtures, which the formats crate reads: crates/inbetween-io/tests/minaccel_fixtures.rs.)

use crate::support::{fixtures, interpolate, rot_angle, settings, track};
use glam::{DQuat, DVec3};
use inbetween::curve::minaccel::solve;
use inbetween::tangent::Knots;
use inbetween::{EndConditions, Ends, PathMode, Scheme};
use serde::Deserialize;

#[derive(Deserialize)]
struct Reference {
    name: String,
    times: Vec<f64>,
    fps: f64,
    ends: String,
    path: String,
    quats: Vec<[f64; 4]>,
    start_velocity: Option<[f64; 3]>,
    end_velocity: Option<[f64; 3]>,
    energy: f64,
    grid_times: Vec<f64>,
    points: Vec<[f64; 4]>,
}

fn wxyz(a: [f64; 4]) -> DQuat {
    DQuat::from_xyzw(a[1], a[2], a[3], a[0])
}

#[test]
fn minaccel_matches_dense_reference() {
    let text = std::fs::read_to_string(fixtures().join("minaccel/reference.json")).unwrap();
    let cases: Vec<Reference> = serde_json::from_str(&text).unwrap();
    assert_eq!(cases.len(), 4);
    for c in cases {
        let quats: Vec<DQuat> = c.quats.iter().map(|q| wxyz(*q).normalize()).collect();
        let t = track(c.times.clone(), quats)
            .with_end_velocities(
                c.start_velocity.map(DVec3::from_array),
                c.end_velocity.map(DVec3::from_array),
            )
            .unwrap();
        let ends = EndConditions {
            ends: if c.ends == "rest" {
                Ends::Rest
            } else {
                Ends::Chord
            },
            start: None,
            end: None,
        };
        let path = if c.path == "shortest" {
            PathMode::Shortest
        } else {
            PathMode::AsGiven
        };
        let keys = Knots::new(&t, path, ends);
        let sol = solve(&keys, c.fps).unwrap();
        let r = sol.report;
        assert!(r.converged, "{}: {r:?}", c.name);
        assert!(r.points <= 62);
        let rel = (r.energy - c.energy).abs() / c.energy;
        assert!(
            rel < 1e-9,
            "{}: E {} vs reference {} (rel {rel:e})",
            c.name,
            r.energy,
            c.energy
        );
        // Same grid, same points (the reference includes phantom points at its ends).
        let off = usize::from(c.grid_times.len() > sol.times.len() && c.grid_times[0] < c.times[0]);
        for (i, (tg, p)) in sol.times.iter().zip(&sol.points).enumerate() {
            assert!(
                (tg - c.grid_times[i + off]).abs() < 1e-12,
                "{}: grid {i}",
                c.name
            );
            let want = wxyz(c.points[i + off]);
            assert!(
                (*p - want).length() < 1e-6,
                "{}: point {i}: {p} vs {want}",
                c.name
            );
        }
    }
}

#[test]
fn two_keys_without_velocities_give_slerp() {
    let q1 = DQuat::from_axis_angle(DVec3::new(2.0, -1.0, 2.0) / 3.0, 2.2);
    let t = track(vec![0.1, 1.3], vec![DQuat::IDENTITY, q1]);
    let (ma, _) = interpolate(
        &t,
        &settings(Scheme::MinAccel, "30", EndConditions::default()),
    );
    let (sl, _) = interpolate(&t, &settings(Scheme::Slerp, "30", EndConditions::default()));
    assert_eq!(ma.len(), sl.len());
    for (a, b) in ma.iter().zip(&sl) {
        assert_eq!(a.0, b.0);
        assert!(
            (a.2 - b.2).length() < 1e-9,
            "frame {}: {} vs {}",
            a.0,
            a.2,
            b.2
        );
    }
    let keys = Knots::new(&t, PathMode::Shortest, EndConditions::default());
    assert!(solve(&keys, 30.0).unwrap().report.energy < 1e-18);
}

/// The velocity at the first key, one-sided from the solved curve, against the constraint: the
/// error falls with the step (first order, as the phantom-point discretisation implies).
#[test]
fn end_velocity_holds_to_the_discretisation_order() {
    let omega = DVec3::new(0.0, 1.0, 2.0);
    let t = track(
        vec![0.0, 1.0, 2.0],
        vec![
            DQuat::IDENTITY,
            DQuat::from_rotation_x(1.0),
            DQuat::from_rotation_y(0.5),
        ],
    );
    let ends = EndConditions {
        ends: Ends::Chord,
        start: Some(omega),
        end: None,
    };
    let keys = Knots::new(&t, PathMode::Shortest, ends);
    let want = crate::support::pure_mul(omega * 0.5, keys.quats()[0]);
    let mut errors = Vec::new();
    for fps in [25.0, 50.0, 100.0, 200.0] {
        let sol = solve(&keys, fps).unwrap();
        assert!(sol.report.converged);
        let h = sol.times[1] - sol.times[0];
        let v = (sol.points[1] - sol.points[0]) / h;
        errors.push((v - want).length() / want.length());
    }
    for w in errors.windows(2) {
        assert!(w[1] < 0.6 * w[0], "errors {errors:?}");
    }
    assert!(errors[3] < 0.025, "errors {errors:?}");
}

#[test]
fn two_full_turns_between_keys() {
    // Identical keys 1 s apart, two turns per second at both ends about z: the minimum is the
    // uniform spin (zero tangential acceleration), 720° in all.
    let q = DQuat::from_rotation_x(0.4);
    let t = track(vec![0.0, 1.0], vec![q, q]);
    let omega = DVec3::new(0.0, 0.0, 4.0 * std::f64::consts::PI);
    let ends = EndConditions {
        ends: Ends::Chord,
        start: Some(omega),
        end: Some(omega),
    };
    let mut s = settings(Scheme::MinAccel, "60", ends);
    s.path = PathMode::AsGiven;
    let (frames, warnings) = interpolate(&t, &s);
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(frames.len(), 61);
    let travelled: f64 = frames.windows(2).map(|w| rot_angle(w[0].2, w[1].2)).sum();
    assert!(
        (travelled - 4.0 * std::f64::consts::PI).abs() < 1e-9,
        "{travelled}"
    );
    let keys = Knots::new(&t, PathMode::AsGiven, ends);
    let sol = solve(&keys, 60.0).unwrap();
    assert!(sol.report.energy < 1e-12, "{:?}", sol.report);
}
