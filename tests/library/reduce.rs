//! `reduce` (docs/spec.md, reduce): over random smooth and noisy motions, every scheme and
//! method meets the tolerance at every frame (the curve rebuilt from the keys as `interp` builds
//! it), keeps the first and last frame, `optimal` never keeps more keys than `greedy`, and for
//! slerp `optimal` is the true minimum (brute force on short tracks).

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

#[test]
fn optimal_slerp_is_the_true_minimum() {
    for seed in 0..6u64 {
        let c = [1.2, -0.7, 0.9, 0.3, -1.1, 0.4];
        let (t, q) = motion(14, c, 0.3f64.to_radians(), seed);
        let o = opts(Scheme::Slerp, Method::Optimal, false, 1.5);
        let r = reduce(&t, &q, None, &o).unwrap();
        // Brute force: every subset of the 12 inner frames, smallest first.
        let feasible = |keys: &[usize]| {
            keys.windows(2).all(|w| {
                (w[0] + 1..w[1]).all(|k| {
                    let u = (t[k] - t[w[0]]) / (t[w[1]] - t[w[0]]);
                    let s = inbetween::rotation::quat::geodesic(
                        q[w[0]],
                        {
                            let b = q[w[1]];
                            if q[w[0]].dot(b) < 0.0 { -b } else { b }
                        },
                        u,
                    );
                    angle(s, q[k]) <= o.tolerance * (1.0 - 1e-9)
                })
            })
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
