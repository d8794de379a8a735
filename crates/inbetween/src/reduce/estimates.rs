//! The frames' angular velocities and the estimates a key may carry (finite differences of the
//! frames: centred, one-sided of first and second order, wide centred).

use super::*;

/// Each frame's angular velocity (rad/s, world frame): the derivative of the quadratic through
/// the frame and its two neighbours in the log map (second order, uneven spacing allowed), one-
/// sided at the first and last frame.
///
/// The quaternions are taken as the curve connects them: the motion from frame `i` to frame `j`
/// is `log(q_j q_i⁻¹)`, so a frame whose sign is flipped against its neighbour is reached the
/// long way round. For the shortest path, pass them each in the hemisphere of the one before
/// ([`crate::tangent::apply_path`]), as [`reduce`] does.
pub fn frame_velocities(times: &[f64], quats: &[DQuat]) -> Vec<DVec3> {
    let n = quats.len();
    if n < 2 {
        return vec![DVec3::ZERO; n];
    }
    let step = |a: usize, b: usize| log(quats[b] * quats[a].conjugate());
    if n == 2 {
        let w = step(0, 1) * (2.0 / (times[1] - times[0]));
        return vec![w, w];
    }
    let mut out = Vec::with_capacity(n);
    // One-sided: f(0) = 0, f(t1) = L01, f(t2) = L02 ⇒ f'(0) = (L01·t2² − L02·t1²)/(t1 t2 (t2 − t1)).
    let one_sided = |i: usize, j: usize, k: usize| {
        let (t1, t2) = (times[j] - times[i], times[k] - times[i]);
        let (l1, l2) = (step(i, j), step(i, k));
        (l1 * (t2 * t2) - l2 * (t1 * t1)) * (2.0 / (t1 * t2 * (t2 - t1)))
    };
    out.push(one_sided(0, 1, 2));
    for i in 1..n - 1 {
        let (hm, hp) = (times[i] - times[i - 1], times[i + 1] - times[i]);
        let (lm, lp) = (step(i - 1, i), step(i, i + 1));
        out.push((lp * (hm / ((hm + hp) * hp)) + lm * (hp / ((hm + hp) * hm))) * 2.0);
    }
    out.push(one_sided(n - 1, n - 2, n - 3));
    out
}

/// How many velocity estimates a key may choose from ([`velocity_estimates`]).
pub const ESTIMATES: usize = 6;

/// Each frame's angular velocity estimates (rad/s, world frame), the derivative at the frame of
/// the polynomial through the frame and neighbours in the log map, for six stencils, in order:
/// centred (the previous and next frame: [`frame_velocities`], one-sided at the ends), backward
/// and forward first order (the previous, the next frame), backward and forward second order
/// (the two previous, the two next frames), wide centred (the frames two before and two after,
/// which passes over the quantisation of a file's numbers). Where a stencil runs off the track,
/// the centred estimate stands in. On smooth motion they agree to first or second order; where
/// the motion turns sharply (a foot strike, a hit) the one-sided ones are the velocities arriving
/// and leaving, which let a key there start or end a long segment. The quaternions are taken as
/// the curve connects them, as in [`frame_velocities`].
pub fn velocity_estimates(times: &[f64], quats: &[DQuat]) -> Vec<[DVec3; ESTIMATES]> {
    let centred = frame_velocities(times, quats);
    let n = quats.len();
    // The derivative at t_i of f(t) = αt + βt² through f(0) = 0, f(t1) = L1, f(t2) = L2 (t1, t2
    // signed), doubled: the log map holds half angles.
    let second = |i: usize, j: usize, k: usize| {
        let (t1, t2) = (times[j] - times[i], times[k] - times[i]);
        let (l1, l2) = (
            log(quats[j] * quats[i].conjugate()),
            log(quats[k] * quats[i].conjugate()),
        );
        (l1 * (t2 * t2) - l2 * (t1 * t1)) * (2.0 / (t1 * t2 * (t2 - t1)))
    };
    let first =
        |i: usize, j: usize| log(quats[j] * quats[i].conjugate()) * (2.0 / (times[j] - times[i]));
    (0..n)
        .map(|i| {
            let c = centred[i];
            [
                c,
                if i >= 1 { first(i, i - 1) } else { c },
                if i + 1 < n { first(i, i + 1) } else { c },
                if i >= 2 { second(i, i - 1, i - 2) } else { c },
                if i + 2 < n {
                    second(i, i + 1, i + 2)
                } else {
                    c
                },
                if i >= 2 && i + 2 < n {
                    second(i, i - 2, i + 2)
                } else {
                    c
                },
            ]
        })
        .collect()
}
