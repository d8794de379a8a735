//! Rotation conventions against `scipy.spatial.transform.Rotation` (tables generated offline by
//! `fixtures/scipy/generate.py`), and representation round trips for all 24 Euler sequences.

use crate::support::{fixtures, read_table, rot_angle};
use glam::DQuat;
use inbetween::rotation::{AngleUnit, EulerSeq, MAX_WIDTH, Repr};
use proptest::prelude::*;
use std::f64::consts::PI;

/// Round trips and agreement with scipy, in radians of rotation.
const ROT_TOL: f64 = 1e-12;
/// Agreement of angles with scipy's (away from gimbal lock), in the table's unit.
const ANGLE_TOL_RAD: f64 = 1e-9;

fn f(row: &std::collections::HashMap<String, String>, k: &str) -> f64 {
    row[k].parse().unwrap_or_else(|_| panic!("{k}: {}", row[k]))
}

fn quat_of(row: &std::collections::HashMap<String, String>) -> DQuat {
    DQuat::from_xyzw(f(row, "qx"), f(row, "qy"), f(row, "qz"), f(row, "qw"))
}

/// Difference of two angles in radians, wrapped to (−π, π].
fn wrapped(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    if d > std::f64::consts::PI {
        d - std::f64::consts::TAU
    } else {
        d
    }
}

#[test]
fn euler_agrees_with_scipy_in_all_24_sequences() {
    let rows = read_table(&fixtures().join("scipy/euler.csv"));
    assert!(rows.len() > 800, "table has {} rows", rows.len());
    let mut seqs = std::collections::HashSet::new();
    for row in &rows {
        let seq = EulerSeq::parse(&row["seq"]).unwrap();
        seqs.insert(row["seq"].clone());
        let unit = AngleUnit::parse(&row["unit"]).unwrap();
        let repr = Repr::Euler(seq);
        let input = [f(row, "a1"), f(row, "a2"), f(row, "a3")];
        let want = quat_of(row);
        // from_euler
        let (got, _) = repr.to_quat(&input, unit).unwrap();
        assert!(
            rot_angle(got, want) < ROT_TOL,
            "{row:?}: from_euler gives {got}, scipy {want}"
        );
        // as_euler: rebuilds the rotation; equals scipy's angles away from gimbal lock.
        let mut out = [0.0; MAX_WIDTH];
        repr.from_quat(want, unit, &mut out);
        let (back, _) = repr.to_quat(&out[..3], unit).unwrap();
        assert!(
            rot_angle(back, want) < ROT_TOL,
            "{row:?}: as_euler {:?} rebuilds {back}, off by {:e} rad",
            &out[..3],
            rot_angle(back, want)
        );
        if row["kind"] == "random" {
            for (i, k) in ["e1", "e2", "e3"].iter().enumerate() {
                let d = wrapped(unit.to_rad(out[i]), unit.to_rad(f(row, k)));
                assert!(d.abs() < ANGLE_TOL_RAD, "{row:?}: angle {k} = {}", out[i]);
            }
        }
    }
    assert_eq!(seqs.len(), 24);
}

#[test]
fn matrix_agrees_with_scipy() {
    let rows = read_table(&fixtures().join("scipy/matrix.csv"));
    assert!(rows.len() > 40);
    let cols = [
        "m00", "m01", "m02", "m10", "m11", "m12", "m20", "m21", "m22",
    ];
    for row in &rows {
        let want = quat_of(row);
        let m: Vec<f64> = cols.iter().map(|c| f(row, c)).collect();
        let (got, _) = Repr::Matrix.to_quat(&m, AngleUnit::Rad).unwrap();
        assert!(rot_angle(got, want) < ROT_TOL, "{row:?}: from_matrix {got}");
        assert!(got.w >= 0.0);
        let mut out = [0.0; MAX_WIDTH];
        Repr::Matrix.from_quat(want, AngleUnit::Rad, &mut out);
        for (i, c) in cols.iter().enumerate() {
            assert!(
                (out[i] - f(row, c)).abs() < 1e-14,
                "{row:?}: as_matrix {c} = {}",
                out[i]
            );
        }
    }
}

/// A unit quaternion from four normal-ish components (rejecting the tiny ones).
fn unit_quat() -> impl Strategy<Value = DQuat> {
    prop::array::uniform4(-1.0f64..1.0)
        .prop_filter("non-degenerate", |a| {
            a.iter().map(|x| x * x).sum::<f64>() > 1e-3
        })
        .prop_map(|a| DQuat::from_xyzw(a[0], a[1], a[2], a[3]).normalize())
}

fn round_trip(repr: Repr, q: DQuat, unit: AngleUnit) -> DQuat {
    let mut out = [0.0; MAX_WIDTH];
    repr.from_quat(q, unit, &mut out);
    repr.to_quat(&out[..repr.width()], unit).unwrap().0
}

proptest! {
    #[test]
    fn every_representation_round_trips(q in unit_quat(), seq_i in 0usize..24, deg in any::<bool>()) {
        let unit = if deg { AngleUnit::Deg } else { AngleUnit::Rad };
        let seq = EulerSeq::all()[seq_i];
        for repr in [Repr::Euler(seq), Repr::Quat, Repr::Matrix, Repr::AxisAngle, Repr::RotVec,
                     Repr::Rot6dRows, Repr::Rot6dColumns] {
            let back = round_trip(repr, q, unit);
            prop_assert!(rot_angle(back, q) < ROT_TOL, "{repr} {unit:?}: {q} -> {back}");
        }
    }

    #[test]
    fn euler_round_trips_at_gimbal_lock(a in -PI..PI, c in -PI..PI,
                                        seq_i in 0usize..24, which in 0usize..2,
                                        eps in prop::sample::select(vec![0.0, 1e-12, -1e-10, 1e-8])) {
        let seq = EulerSeq::all()[seq_i];
        let name = seq.as_str().to_ascii_uppercase();
        let proper = name.as_bytes()[0] == name.as_bytes()[2];
        let mid = match (proper, which) {
            (true, 0) => 0.0,
            (true, _) => std::f64::consts::PI,
            (false, 0) => std::f64::consts::FRAC_PI_2,
            (false, _) => -std::f64::consts::FRAC_PI_2,
        } + eps;
        let q = seq.to_quat([a, mid, c]);
        for unit in [AngleUnit::Deg, AngleUnit::Rad] {
            let back = round_trip(Repr::Euler(seq), q, unit);
            prop_assert!(rot_angle(back, q) < ROT_TOL, "{} {unit:?}: off by {:e}", seq.as_str(), rot_angle(back, q));
        }
    }
}
