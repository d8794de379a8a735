//! Continuous Euler angles (`rotation::unwrap`): every triple rebuilds its rotation, it is the
//! nearest triple of that rotation, spins do not wrap at ±180°, and paths through gimbal lock stay
//! continuous — in all 24 sequences.

use crate::support::rot_angle;
use glam::DQuat;
use inbetween::rotation::EulerSeq;
use inbetween::rotation::unwrap::EulerUnwrap;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Every triple rebuilds its rotation to this many radians.
const ROT_TOL: f64 = 1e-12;

fn unit_quat() -> impl Strategy<Value = DQuat> {
    prop::array::uniform4(-1.0f64..1.0)
        .prop_filter("non-degenerate", |a| {
            a.iter().map(|x| x * x).sum::<f64>() > 1e-2
        })
        .prop_map(|a| DQuat::from_xyzw(a[0], a[1], a[2], a[3]).normalize())
}

/// The rule's triple of `q` after `prev`: the public unwrapper started at `prev`.
fn nearest_triple(seq: EulerSeq, q: DQuat, prev: [f64; 3]) -> [f64; 3] {
    EulerUnwrap::with_start(seq, prev).next(q)
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

fn proper(seq: EulerSeq) -> bool {
    let l = seq.as_str().as_bytes();
    l[0] == l[2]
}

/// The other solution of a triple, derived in the test from `R_i(π) R_j(β) = R_j(−β) R_i(π)` and
/// `R_i(π) R_k(π) = R_j(π)`; each candidate below is checked against `to_quat` anyway.
fn other_solution(seq: EulerSeq, [a, b, c]: [f64; 3]) -> [f64; 3] {
    let b2 = if proper(seq) { -b } else { PI - b };
    [a + PI, b2, c + PI]
}

/// Distance of a canonical middle angle from gimbal lock.
fn lock_distance(seq: EulerSeq, b: f64) -> f64 {
    if proper(seq) {
        b.abs().min(PI - b.abs())
    } else {
        FRAC_PI_2 - b.abs()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn every_triple_rebuilds_its_rotation(
        q in unit_quat(),
        prev in prop::array::uniform3(-20.0f64..20.0),
    ) {
        for seq in EulerSeq::all() {
            let t = nearest_triple(seq, q, prev);
            let d = rot_angle(q, seq.to_quat(t));
            prop_assert!(d < ROT_TOL, "{} {q} from {prev:?}: {t:?} off by {d:e}", seq.as_str());
        }
    }

    /// Brute force: both solutions × {−2, …, 2}·2π per angle. With the previous triple in
    /// [−2.5π, 2.5π]³ the nearest representative of every angle is among those.
    #[test]
    fn it_is_the_nearest_triple(
        q in unit_quat(),
        prev in prop::array::uniform3(-2.5 * PI..2.5 * PI),
    ) {
        for seq in EulerSeq::all() {
            let canonical = seq.from_quat(q);
            if lock_distance(seq, canonical[1]) < 1e-6 {
                continue;
            }
            let got = nearest_triple(seq, q, prev);
            let best = dist(got, prev);
            for solution in [canonical, other_solution(seq, canonical)] {
                prop_assert!(rot_angle(q, seq.to_quat(solution)) < ROT_TOL);
                for k in 0..125 {
                    let m = [k % 5, k / 5 % 5, k / 25].map(|m| (m as f64 - 2.0) * TAU);
                    let cand = [0, 1, 2].map(|i| solution[i] + m[i]);
                    prop_assert!(
                        dist(cand, prev) >= best - 1e-12,
                        "{} {q} from {prev:?}: {got:?} at {best}, {cand:?} at {}",
                        seq.as_str(), dist(cand, prev)
                    );
                }
            }
        }
    }

    /// Independent of any formula for the solutions: a triple `t` anywhere, its rotation, and
    /// any previous triple — the rule's triple is at least as near as `t`. Half of the triples
    /// sit exactly at gimbal lock, where `t` is a point of the free family.
    #[test]
    fn no_triple_of_the_rotation_is_nearer(
        t in prop::array::uniform3(-3.0 * PI..3.0 * PI),
        prev in prop::array::uniform3(-3.0 * PI..3.0 * PI),
        lock in prop::sample::select(vec![None, Some(0usize), Some(1)]),
    ) {
        for seq in EulerSeq::all() {
            let mut t = t;
            if let Some(which) = lock {
                t[1] = match (proper(seq), which) {
                    (true, 0) => 0.0,
                    (true, _) => PI,
                    (false, 0) => FRAC_PI_2,
                    (false, _) => -FRAC_PI_2,
                };
            }
            let q = seq.to_quat(t);
            let got = nearest_triple(seq, q, prev);
            prop_assert!(rot_angle(q, seq.to_quat(got)) < ROT_TOL);
            prop_assert!(
                dist(got, prev) <= dist(t, prev) + 1e-12,
                "{} {t:?} from {prev:?}: {got:?} at {}, t at {}",
                seq.as_str(), dist(got, prev), dist(t, prev)
            );
        }
    }
}

#[test]
fn a_spin_about_z_counts_up_to_720_degrees() {
    let mut track = EulerUnwrap::new(EulerSeq::parse("ZYX").unwrap());
    for k in 0..=72 {
        let deg = 10.0 * k as f64;
        let t = track.next(DQuat::from_rotation_z(deg.to_radians()));
        assert!((t[0].to_degrees() - deg).abs() < 1e-9, "{deg}: {t:?}");
        assert!(t[1].abs() < 1e-12 && t[2].abs() < 1e-12, "{deg}: {t:?}");
    }
}

/// The first angle runs 170°, 175°, …, 250° and the third −170°, −175°, …, −250°, the middle
/// held clear of gimbal lock: both cross ±180° and neither wraps, in every sequence.
#[test]
fn crossing_180_degrees_stays_continuous() {
    for seq in EulerSeq::all() {
        let b = if proper(seq) { 60.0 } else { 30.0 };
        let mut track = EulerUnwrap::new(seq);
        for k in 0..=16 {
            let want = [170.0 + 5.0 * k as f64, b, -170.0 - 5.0 * k as f64];
            let q = seq.to_quat(want.map(f64::to_radians));
            let got = track.next(q).map(f64::to_degrees);
            assert!(
                dist(got, want) < 1e-9,
                "{}: {got:?}, want {want:?}",
                seq.as_str()
            );
        }
    }
}

/// R = seq(0.3t, m(t), 0.2) with the middle angle m(t) = s − π/2 + t through a singular value s
/// at t = π/2, sampled at t = kπ/200 (the lock sample is a lock up to rounding).
///
/// Bound on one step: the path itself moves √(0.3² + 1)·h = 1.044h per step of h in t. At the
/// lock sample the rule puts (a, c) at the point of the lock line nearest the previous sample,
/// which moves a + σc by 0.3h, split equally: 0.15h off the path in a and in c, so the steps
/// into and out of that sample are at most √((0.3h + 0.15h)² + h² + (0.15h)²) = 1.107h. Bound
/// 1.2h; a flip to the other solution or a wrap would be a step of at least π.
#[test]
fn a_path_through_gimbal_lock_stays_continuous() {
    let h = PI / 200.0;
    for seq in EulerSeq::all() {
        let singular: &[f64] = if proper(seq) {
            &[0.0, PI]
        } else {
            &[FRAC_PI_2, -FRAC_PI_2]
        };
        for &s in singular {
            let path = |t: f64| [0.3 * t, s - FRAC_PI_2 + t, 0.2];
            let mut track = EulerUnwrap::with_start(seq, path(0.0));
            let mut prev: Option<[f64; 3]> = None;
            let mut off_path = 0;
            for k in 0..=200 {
                let t = k as f64 * h;
                let q = seq.to_quat(path(t));
                let got = track.next(q);
                let what = format!("{} through {s} at t = {t}: {got:?}", seq.as_str());
                assert!(rot_angle(q, seq.to_quat(got)) < ROT_TOL, "{what}");
                if let Some(p) = prev {
                    assert!(dist(got, p) < 1.2 * h, "{what} after {p:?}");
                }
                if dist(got, path(t)) > 1e-9 {
                    // Only the lock sample, and only along the lock line.
                    assert_eq!(k, 100, "{what}");
                    assert!((got[1] - path(t)[1]).abs() < 1e-12, "{what}");
                    off_path += 1;
                }
                prev = Some(got);
            }
            assert!(off_path <= 1);
        }
    }
}

/// The same path in ZYX with the samples shifted so that one lands at a distance d from the lock,
/// not on it: the regular formula gives that rotation's own angles, which lie on the path up to
/// the split's rounding noise (of order 1e-16/d rad), and the track follows the path.
#[test]
fn near_gimbal_lock_the_track_follows_the_path() {
    let zyx = EulerSeq::parse("ZYX").unwrap();
    let h = PI / 200.0;
    let path = |t: f64| [0.3 * t, t, 0.2];
    for d in [1e-12, 1e-9, 1e-6, 1e-3] {
        let mut track = EulerUnwrap::new(zyx);
        let mut prev = None;
        for k in -100..=100 {
            let t = FRAC_PI_2 - d + k as f64 * h;
            let q = DQuat::from_rotation_z(0.3 * t)
                * DQuat::from_rotation_y(t)
                * DQuat::from_rotation_x(0.2);
            let got = track.next(q);
            let what = format!("d = {d:e}, t = {t}: {got:?}");
            assert!(rot_angle(q, zyx.to_quat(got)) < ROT_TOL, "{what}");
            assert!(dist(got, path(t)) < 1e-9 + 1e-14 / d, "{what}");
            if let Some(p) = prev {
                assert!(dist(got, p) < 1.2 * h, "{what} after {p:?}");
            }
            prev = Some(got);
        }
    }
}
