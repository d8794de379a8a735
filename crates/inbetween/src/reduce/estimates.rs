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
pub(crate) fn frame_velocities(times: &[f64], quats: &[DQuat]) -> Vec<DVec3> {
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
pub(crate) const ESTIMATES: usize = 6;

/// Each frame's angular velocity estimates (rad/s, world frame), the derivative at the frame of
/// the polynomial through the frame and neighbours in the log map, for six stencils, in order:
/// centred (the previous and next frame: `frame_velocities`, one-sided at the ends), backward
/// and forward first order (the previous, the next frame), backward and forward second order
/// (the two previous, the two next frames), wide centred (the frames two before and two after,
/// which passes over the quantisation of a file's numbers). Where a stencil runs off the track,
/// the centred estimate stands in. On smooth motion they agree to first or second order; where
/// the motion turns sharply (a foot strike, a hit) the one-sided ones are the velocities arriving
/// and leaving, which let a key there start or end a long segment. The quaternions are taken as
/// the curve connects them, as in `frame_velocities`.
///
/// Each frame's four steps in the log map (to the frames one and two before and after) are
/// computed once and shared by the stencils that use them: the same values, to the bit, as
/// each stencil computing its own (tested).
pub(crate) fn velocity_estimates(times: &[f64], quats: &[DQuat]) -> Vec<[DVec3; ESTIMATES]> {
    let n = quats.len();
    if n < 3 {
        return direct_estimates(times, quats);
    }
    // The step from frame `i` to frame `j`, `log(q_j q_i⁻¹)`, as every stencil writes it.
    let step = |i: usize, j: usize| log(quats[j] * quats[i].conjugate());
    // The derivative at t_i of f(t) = αt + βt² through f(0) = 0, f(t1) = l1, f(t2) = l2 (t1,
    // t2 signed), doubled: the log map holds half angles. Frames `j`, `k` at `t1`, `t2`.
    let second = |i: usize, (j, l1): (usize, DVec3), (k, l2): (usize, DVec3)| {
        let (t1, t2) = (times[j] - times[i], times[k] - times[i]);
        (l1 * (t2 * t2) - l2 * (t1 * t1)) * (2.0 / (t1 * t2 * (t2 - t1)))
    };
    let first = |i: usize, (j, l): (usize, DVec3)| l * (2.0 / (times[j] - times[i]));
    let mut out = Vec::with_capacity(n);
    // The step from the frame before to this one (`step(i − 1, i)`), from the last iteration.
    let mut arriving = DVec3::ZERO;
    for i in 0..n {
        let ahead = (i + 1 < n).then(|| step(i, i + 1));
        let behind = (i >= 1).then(|| step(i, i - 1));
        let ahead2 = (i + 2 < n).then(|| step(i, i + 2));
        let behind2 = (i >= 2).then(|| step(i, i - 2));
        let c = match (behind, ahead) {
            (Some(_), Some(lp)) => {
                let (hm, hp) = (times[i] - times[i - 1], times[i + 1] - times[i]);
                let lm = arriving;
                (lp * (hm / ((hm + hp) * hp)) + lm * (hp / ((hm + hp) * hm))) * 2.0
            }
            // One-sided at the ends, as frame_velocities.
            (None, Some(l1)) => second(i, (i + 1, l1), (i + 2, ahead2.unwrap_or_default())),
            (Some(l1), None) => second(i, (i - 1, l1), (i - 2, behind2.unwrap_or_default())),
            (None, None) => unreachable!("three frames at least"),
        };
        out.push([
            c,
            behind.map_or(c, |l| first(i, (i - 1, l))),
            ahead.map_or(c, |l| first(i, (i + 1, l))),
            behind
                .zip(behind2)
                .map_or(c, |(l1, l2)| second(i, (i - 1, l1), (i - 2, l2))),
            ahead
                .zip(ahead2)
                .map_or(c, |(l1, l2)| second(i, (i + 1, l1), (i + 2, l2))),
            match (behind2, ahead2) {
                (Some(l1), Some(l2)) => second(i, (i - 2, l1), (i + 2, l2)),
                _ => c,
            },
        ]);
        arriving = ahead.unwrap_or_default();
    }
    out
}

/// [`velocity_estimates`], each stencil computing its own steps.
fn direct_estimates(times: &[f64], quats: &[DQuat]) -> Vec<[DVec3; ESTIMATES]> {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The shared steps give every estimate to the bit, on uneven times, sign flips, a held
    /// stretch and a half-turn jump, for every length from 0 frames.
    #[test]
    fn shared_steps_are_the_direct_estimates_to_the_bit() {
        let frame = |i: usize| {
            let t = i as f64 * 0.013 + 0.002 * ((i * i) % 7) as f64;
            let held = if (20..26).contains(&i) { 0.26 } else { t };
            let q = DQuat::from_euler(
                glam::EulerRot::ZXY,
                5.1 * held,
                1.3 * held.sin(),
                -0.7 * held,
            );
            let q = if i == 40 {
                q * DQuat::from_rotation_x(3.1)
            } else {
                q
            };
            (t, if i % 5 == 3 { -q } else { q })
        };
        for n in 0..60 {
            let (t, q): (Vec<f64>, Vec<DQuat>) = (0..n).map(frame).unzip();
            let bits = |e: Vec<[DVec3; ESTIMATES]>| -> Vec<[u64; 3 * ESTIMATES]> {
                e.iter()
                    .map(|a| {
                        let mut b = [0; 3 * ESTIMATES];
                        for (k, v) in a.iter().enumerate() {
                            for (c, x) in v.to_array().iter().enumerate() {
                                b[3 * k + c] = x.to_bits();
                            }
                        }
                        b
                    })
                    .collect()
            };
            assert_eq!(
                bits(velocity_estimates(&t, &q)),
                bits(direct_estimates(&t, &q)),
                "{n} frames"
            );
        }
    }
}
