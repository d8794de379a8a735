//! `reduce` (docs/spec.md, reduce): over random smooth and noisy motions, every scheme and
//! method meets the tolerance at every frame (the curve rebuilt from the keys as `interp` builds
//! it), keeps the first and last frame, `optimal` never keeps more keys than `greedy`, and for
//! slerp `optimal` is the true minimum (brute force on short tracks, every segment tested on
//! longer ones).

use glam::{DQuat, DVec3};
use inbetween::reduce::{Method, ReduceOptions, reduce};
use inbetween::rotation::quat::rotation_angle_between as angle;
use inbetween::{Curve, CurveOptions, Fps, Scheme, Track};
use proptest::prelude::*;

/// A motion of `n` frames at 30 fps: smooth angular velocity with random coefficients, plus
/// per-frame noise of `noise` rad.
fn motion(n: usize, c: [f64; 6], noise: f64, seed: u64) -> (Vec<f64>, Vec<DQuat>) {
    let mut s = seed;
    let mut rnd = move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    let times: Vec<f64> = (0..n).map(|i| i as f64 / 30.0).collect();
    let quats = times
        .iter()
        .map(|&t| {
            let smooth = DQuat::from_euler(
                glam::EulerRot::ZYX,
                c[0] * t + c[1] * (2.0 * t).sin(),
                c[2] * (1.3 * t).cos(),
                c[3] * t * t + c[4] * t,
            );
            let jitter = DQuat::from_scaled_axis(DVec3::new(rnd(), rnd(), rnd()) * (2.0 * noise));
            jitter * smooth * DQuat::from_rotation_x(c[5])
        })
        .collect();
    (times, quats)
}

fn opts(scheme: Scheme, method: Method, velocities: bool, tol_deg: f64) -> ReduceOptions {
    ReduceOptions {
        curve: CurveOptions {
            scheme,
            grid_rate: Fps::new(30, 1).unwrap(),
            ..CurveOptions::default()
        },
        tolerance: tol_deg.to_radians(),
        distance: None,
        translation_tolerance: None,
        velocities,
        method,
    }
}

/// The largest error of the keys' curve over the frames, rebuilt independently of `reduce`.
fn replay(t: &[f64], q: &[DQuat], r: &inbetween::reduce::Reduced, o: &ReduceOptions) -> f64 {
    let kt: Vec<f64> = r.keys.iter().map(|&i| t[i]).collect();
    let kq: Vec<DQuat> = r.keys.iter().map(|&i| q[i]).collect();
    let mut track = Track::new(kt, kq).unwrap();
    if let Some(w) = &r.velocities {
        track = track
            .with_key_velocities(w.iter().copied().map(Some).collect())
            .unwrap();
    }
    let curve = Curve::new(&track, &o.curve).unwrap();
    t.iter()
        .zip(q)
        .map(|(&t, &q)| angle(curve.rotation(t), q))
        .fold(0.0, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    #[test]
    fn the_guarantee_holds(c in prop::array::uniform6(-1.5f64..1.5), noisy in any::<bool>(),
                           seed in any::<u64>(), tol in 0.1f64..2.0) {
        let noise = if noisy { 0.2f64.to_radians() } else { 0.0 };
        let (t, q) = motion(61, c, noise, seed);
        for scheme in Scheme::ALL {
            let velocities_options: &[bool] =
                if scheme == Scheme::MinAccel { &[true] } else { &[true, false] };
            for &velocities in velocities_options {
                let mut counts = Vec::new();
                for method in [Method::Greedy, Method::Optimal] {
                    let o = opts(scheme, method, velocities, tol);
                    let r = reduce(&t, &q, None, &o).unwrap();
                    prop_assert_eq!(r.keys[0], 0);
                    prop_assert_eq!(*r.keys.last().unwrap(), 60);
                    let e = replay(&t, &q, &r, &o);
                    prop_assert!(e <= o.tolerance, "{} {:?} {}: {} > {}", scheme, method, velocities, e, o.tolerance);
                    counts.push(r.keys.len());
                }
                prop_assert!(counts[1] <= counts[0], "{} optimal {} > greedy {}", scheme, counts[1], counts[0]);
            }
        }
    }
}

/// Whether slerp from frame `a` to frame `b` (the shorter way) is within `tol` of every frame
/// between them: slerp written out here, independently of the curve code.
fn slerp_segment_fits(t: &[f64], q: &[DQuat], a: usize, b: usize, tol: f64) -> bool {
    (a + 1..b).all(|k| {
        let u = (t[k] - t[a]) / (t[b] - t[a]);
        let qb = if q[a].dot(q[b]) < 0.0 { -q[b] } else { q[b] };
        let s = inbetween::rotation::quat::geodesic(q[a], qb, u);
        angle(s, q[k]) <= tol * (1.0 - 1e-9)
    })
}

/// The fewest keys from frame 0 to frame `n − 1` whose segments all `fit`: a shortest path over
/// every segment, each tested.
fn fewest_keys(n: usize, fits: impl Fn(usize, usize) -> bool) -> usize {
    let mut cost = vec![usize::MAX; n];
    cost[0] = 1;
    for b in 1..n {
        for a in 0..b {
            if cost[a] != usize::MAX && cost[a] + 1 < cost[b] && fits(a, b) {
                cost[b] = cost[a] + 1;
            }
        }
    }
    cost[n - 1]
}

/// Tracks of (times, rotations) as `reduce_shared`'s input.
fn track_frames(tracks: &[(Vec<f64>, Vec<DQuat>)]) -> Vec<inbetween::reduce::TrackFrames<'_>> {
    tracks
        .iter()
        .map(|(t, q)| inbetween::reduce::TrackFrames {
            times: t,
            rotations: q,
            positions: None,
            euler: None,
            key_times: None,
        })
        .collect()
}

#[test]
fn optimal_slerp_is_the_true_minimum() {
    for seed in 0..6u64 {
        let c = [1.2, -0.7, 0.9, 0.3, -1.1, 0.4];
        let (t, q) = motion(14, c, 0.3f64.to_radians(), seed);
        let o = opts(Scheme::Slerp, Method::Optimal, false, 1.5);
        let r = reduce(&t, &q, None, &o).unwrap();
        // Brute force: every subset of the 12 inner frames, smallest first.
        let feasible = |keys: &[usize]| {
            keys.windows(2)
                .all(|w| slerp_segment_fits(&t, &q, w[0], w[1], o.tolerance))
        };
        let best = (0u32..1 << 12)
            .filter_map(|mask| {
                let mut keys = vec![0];
                keys.extend((1..13).filter(|i| mask & (1 << (i - 1)) != 0));
                keys.push(13);
                feasible(&keys).then_some(keys.len())
            })
            .min()
            .unwrap();
        assert_eq!(r.keys.len(), best, "seed {seed}: {:?}", r.keys);
    }
}

/// Slerp's `optimal` has no window: on longer tracks (smooth and noisy, where segments are long and
/// short) its key count is that of a shortest path over every segment, computed here by testing
/// all of them.
#[test]
fn optimal_slerp_is_the_true_minimum_on_longer_tracks() {
    for (seed, noise, tol) in [
        (1u64, 0.0, 0.5),
        (2, 0.05, 1.0),
        (3, 0.3, 1.0),
        (4, 0.02, 2.0),
    ] {
        let c = [0.9, -0.5, 0.7, 0.2, -0.8, 0.3];
        let (t, q) = motion(90, c, f64::to_radians(noise), seed);
        let o = opts(Scheme::Slerp, Method::Optimal, false, tol);
        let r = reduce(&t, &q, None, &o).unwrap();
        let fewest = fewest_keys(t.len(), |a, b| {
            slerp_segment_fits(&t, &q, a, b, o.tolerance)
        });
        assert_eq!(r.keys.len(), fewest, "seed {seed}: {:?}", r.keys);
    }
}

/// A quaternion and its negation are the same rotation: under the default shortest path, the
/// frames' signs (alternating, random, all flipped) change neither the keys nor their
/// velocities.
#[test]
fn quaternion_signs_do_not_change_the_keys() {
    for (i, noise) in [0.0, 0.2f64.to_radians()].into_iter().enumerate() {
        let (t, mut q) = motion(61, [1.2, -0.7, 0.9, 0.3, -1.1, 0.4], noise, 7 + i as u64);
        // Sign-continuous first (the shortest path's rule), then flipped below.
        for k in 1..q.len() {
            if q[k - 1].dot(q[k]) < 0.0 {
                q[k] = -q[k];
            }
        }
        let signs: [fn(usize) -> bool; 3] = [
            |k| k % 2 == 1,
            |k| (k.wrapping_mul(2654435761) >> 7) & 1 == 1,
            |_| true,
        ];
        for flip in &signs {
            let flipped: Vec<DQuat> = q
                .iter()
                .enumerate()
                .map(|(k, &x)| if flip(k) { -x } else { x })
                .collect();
            for scheme in Scheme::ALL {
                for method in [Method::Greedy, Method::Optimal] {
                    let o = opts(scheme, method, true, 0.5);
                    let want = reduce(&t, &q, None, &o).unwrap();
                    let got = reduce(&t, &flipped, None, &o).unwrap();
                    assert_eq!(got.keys, want.keys, "{scheme} {method:?} noise {noise}");
                    let (w, g) = (want.velocities.unwrap(), got.velocities.unwrap());
                    for (a, b) in w.iter().zip(&g) {
                        assert!(
                            (*a - *b).length() < 1e-12,
                            "{scheme} {method:?}: {a} vs {b}"
                        );
                    }
                }
            }
        }
    }
}

/// `--shared-keys` (`reduce_shared`): over three random tracks on one clock, every scheme and
/// method, with and without velocities: one set of keys for all tracks, the first and last frame
/// kept, every track within the tolerance (replayed independently), `optimal` never more keys
/// than `greedy`, and no more keys than the union of the tracks' own keys would keep.
#[test]
fn shared_keys_meet_the_tolerance_on_every_track() {
    use inbetween::reduce::reduce_shared;
    for (seed, noise, tol) in [(11u64, 0.0f64, 0.5), (12, 0.1, 1.0), (13, 0.3, 2.0)] {
        let tracks: Vec<(Vec<f64>, Vec<DQuat>)> = [
            [1.2, -0.7, 0.9, 0.3, -1.1, 0.4],
            [-0.4, 1.1, 0.2, -0.9, 0.6, 1.3],
            [0.3, 0.2, -1.4, 0.5, 0.9, -0.6],
        ]
        .iter()
        .enumerate()
        .map(|(i, c)| motion(61, *c, noise.to_radians(), seed * 7 + i as u64))
        .collect();
        let frames = track_frames(&tracks);
        for scheme in Scheme::ALL {
            for velocities in [true, false] {
                let mut counts = Vec::new();
                for method in [Method::Greedy, Method::Optimal] {
                    let o = opts(scheme, method, velocities, tol);
                    let shared = reduce_shared(&frames, &o).unwrap();
                    let keys = &shared[0].keys;
                    assert_eq!((keys[0], *keys.last().unwrap()), (0, 60));
                    let mut union: Vec<usize> = Vec::new();
                    for ((t, q), r) in tracks.iter().zip(&shared) {
                        assert_eq!(&r.keys, keys);
                        let e = replay(t, q, r, &o);
                        assert!(e <= o.tolerance, "{scheme} {method:?} {velocities}: {e}");
                        union.extend(reduce(t, q, None, &o).unwrap().keys);
                    }
                    union.sort_unstable();
                    union.dedup();
                    assert!(
                        keys.len() <= union.len(),
                        "{scheme} {method:?} {velocities}: {} shared keys, union {}",
                        keys.len(),
                        union.len()
                    );
                    counts.push(keys.len());
                }
                assert!(counts[1] <= counts[0], "{scheme} {velocities}: {counts:?}");
            }
        }
    }
}

/// Slerp's shared `optimal` is the fewest keys that meet the tolerance on every track: a shortest
/// path over every segment, each tested on all tracks here.
#[test]
fn shared_optimal_slerp_is_the_true_minimum() {
    use inbetween::reduce::reduce_shared;
    for (seed, noise, tol) in [(21u64, 0.0, 0.5), (22, 0.1, 1.0), (23, 0.3, 1.0)] {
        let tracks: Vec<(Vec<f64>, Vec<DQuat>)> = (0..3)
            .map(|i| {
                let c = [0.9 - 0.4 * i as f64, -0.5, 0.7, 0.2 * i as f64, -0.8, 0.3];
                motion(70, c, f64::to_radians(noise), seed + 100 * i)
            })
            .collect();
        let frames = track_frames(&tracks);
        let o = opts(Scheme::Slerp, Method::Optimal, false, tol);
        let r = reduce_shared(&frames, &o).unwrap();
        let fewest = fewest_keys(70, |a, b| {
            tracks
                .iter()
                .all(|(t, q)| slerp_segment_fits(t, q, a, b, o.tolerance))
        });
        assert_eq!(r[0].keys.len(), fewest, "seed {seed}: {:?}", r[0].keys);
    }
}

/// End conditions apply at the ends of the whole curve only: `--start-velocity`, `--end-velocity`
/// and `--ends rest` keep at most half as many keys again as the default ends (the segment tests
/// once gave them to every segment, and kept most frames), and a loop (`--ends cyclic`, the
/// last frame the first's rotation) reduces; every result meets the tolerance replayed with the
/// same ends.
#[test]
fn end_conditions_apply_at_the_ends_only() {
    use inbetween::{EndConditions, Ends};
    let (t, q) = motion(121, [1.2, -0.7, 0.9, 0.3, -1.1, 0.4], 0.0, 5);
    // A loop: one period of a smooth closed motion.
    let period = t[120];
    let lq: Vec<DQuat> = t
        .iter()
        .map(|&t| {
            let a = std::f64::consts::TAU * t / period;
            DQuat::from_euler(
                glam::EulerRot::ZYX,
                0.8 * a.sin(),
                0.5 * (2.0 * a).cos(),
                0.3 * a.cos(),
            )
        })
        .collect();
    let spin = DVec3::new(0.0, 0.0, 5.0);
    for scheme in [Scheme::Bezier, Scheme::Hermite, Scheme::Squad] {
        for velocities in [true, false] {
            let plain = opts(scheme, Method::Greedy, velocities, 0.2);
            for (q, ends) in [
                (
                    &q,
                    EndConditions {
                        ends: Ends::Chord,
                        start: Some(spin),
                        end: None,
                    },
                ),
                (
                    &q,
                    EndConditions {
                        ends: Ends::Chord,
                        start: None,
                        end: Some(-spin),
                    },
                ),
                (&q, EndConditions::from(Ends::Rest)),
                (&lq, EndConditions::from(Ends::Cyclic)),
            ] {
                let base = reduce(&t, q, None, &plain).unwrap().keys.len();
                let mut o = plain;
                o.curve.ends = ends;
                let r = reduce(&t, q, None, &o).unwrap();
                assert!(
                    replay(&t, q, &r, &o) <= o.tolerance,
                    "{scheme} {velocities} {ends:?}"
                );
                assert!(
                    r.keys.len() <= base * 3 / 2 + 3,
                    "{scheme} {velocities} {ends:?}: {} keys, {base} with chord ends",
                    r.keys.len()
                );
            }
        }
    }
}
