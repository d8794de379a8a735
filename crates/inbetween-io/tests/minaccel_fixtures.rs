//! `minaccel` (issue 4) on the interp fixtures as the formats crate reads them: on every track,
//! under every end condition and path, the solved curve's energy is below every other scheme's
//! on the same grid (moved from the library's tests, crates/inbetween/tests/library/minaccel.rs,
//! as it reads the fixtures' CSV and JSON).

use glam::{DQuat, DVec3};
use inbetween::curve::minaccel::Problem;
use inbetween::tangent::Knots;
use inbetween::{Curve, CurveOptions, EndConditions, Ends, Fps, PathMode, Scheme, Track};
use inbetween_io::{Format, ReadOptions, read_document};
use std::path::{Path, PathBuf};

/// The repository's `fixtures/` directory.
fn fixtures() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("fixtures")
}

/// Every track of the interp fixtures, with the document's velocities.
fn fixture_tracks() -> Vec<(String, Track)> {
    let mut out = Vec::new();
    for name in [
        "uniform.json",
        "nonuniform.csv",
        "multitrack.json",
        "frames_ntsc.json",
        "long_way.csv",
    ] {
        let path = fixtures().join("interp").join(name);
        let text = std::fs::read_to_string(&path).unwrap();
        let format = Format::from_path(&path).unwrap();
        let doc = read_document(&text, name, format, &ReadOptions::default()).unwrap();
        let fps = doc.fps.unwrap_or(Fps::DEFAULT);
        for t in doc.tracks(fps).unwrap() {
            out.push((format!("{name} {:?}", t.name()), t));
        }
    }
    out
}

#[test]
fn energy_below_every_other_scheme_on_every_fixture() {
    let omega = DVec3::new(0.5, -1.0, 2.0);
    let variants = [
        EndConditions::default(),
        EndConditions {
            ends: Ends::Rest,
            ..Default::default()
        },
        EndConditions {
            ends: Ends::Chord,
            start: Some(omega),
            end: Some(-omega),
        },
    ];
    for (name, t) in fixture_tracks() {
        for ends in variants {
            for path in [PathMode::Shortest, PathMode::AsGiven] {
                let keys = Knots::new(&t, path, ends);
                let problem = Problem::new(&keys, 30.0).unwrap();
                let grid = problem.grid_times().to_vec();
                let sol = problem.clone().solve();
                assert!(sol.report.converged, "{name} {ends:?}: {:?}", sol.report);
                // Converged means ≤ 1e-9 of the start, or at the f64 floor when the start is
                // already the minimum (a geodesic, E ≈ 1e-26).
                if sol.report.energy_start > 1e-12 {
                    assert!(
                        sol.report.gradient <= 1e-9 * sol.report.gradient_start,
                        "{name}: {:?}",
                        sol.report
                    );
                }
                for scheme in [
                    Scheme::Hermite,
                    Scheme::Squad,
                    Scheme::Bezier,
                    Scheme::Slerp,
                ] {
                    let opts = CurveOptions {
                        scheme,
                        path,
                        ends,
                        ..CurveOptions::default()
                    };
                    let c = Curve::new(&t, &opts).unwrap();
                    let pts: Vec<DQuat> = grid.iter().map(|&tg| c.rotation(tg)).collect();
                    let e = problem.energy_of(&pts);
                    assert!(
                        // 1e-20: below that both energies are f64 rounding of a geodesic.
                        sol.report.energy <= e * (1.0 + 1e-12) + 1e-20,
                        "{name} {ends:?} {path:?}: minaccel E {} > {scheme:?} E {e}",
                        sol.report.energy
                    );
                }
            }
        }
    }
}
