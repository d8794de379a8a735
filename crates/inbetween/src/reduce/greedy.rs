//! The greedy method: from each key the farthest next key whose segment meets the tolerances
//! (doubling then bisection), over the estimates the next key may carry, with one step of
//! look-ahead.

use super::*;

/// From key `a` (its velocity chosen), the farthest next key `b ≥ from` whose segment alone meets
/// the tolerances with `b` carrying estimate `c`, given that `from` does ([`farthest_by`]).
pub(super) fn farthest(
    frames: &Frames,
    a: usize,
    from: usize,
    c: usize,
    opts: &ReduceOptions,
) -> InputResult<usize> {
    farthest_by(frames.quats.len(), from, |b| {
        frames.feasible_with(a, b, c, opts)
    })
}

/// The farthest frame `b ≥ from` (of `n`) that passes `test`, given that `from` does: doubling
/// past `from`, then bisection between the last frame that passes and the first that does not.
pub(super) fn farthest_by(
    n: usize,
    from: usize,
    mut test: impl FnMut(usize) -> InputResult<bool>,
) -> InputResult<usize> {
    let (mut good, mut step) = (from, 1);
    let mut bad = None;
    while good < n - 1 {
        let b = (good + step).min(n - 1);
        if test(b)? {
            good = b;
            step *= 2;
        } else {
            bad = Some(b);
            break;
        }
    }
    if let Some(mut hi) = bad {
        let mut lo = good;
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if test(mid)? {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        good = lo;
    }
    Ok(good)
}

/// One greedy step from key `a` (its velocity chosen) that goes past frame `floor`: the farthest
/// next key over the estimates it may carry ([`farthest`]; each estimate is searched only when it
/// meets the tolerances one frame past the farthest so far, or past `floor`), and the estimates
/// that reach that key; `None` when no estimate goes past `floor`. With `floor = a` there is
/// always a step (the next frame).
pub(super) fn greedy_step(
    frames: &Frames,
    a: usize,
    floor: usize,
    opts: &ReduceOptions,
) -> InputResult<Option<(usize, Vec<usize>)>> {
    let n = frames.quats.len();
    let mut best: Option<(usize, Vec<usize>)> = None;
    for c in 0..frames.choices {
        let far = best.as_ref().map_or(floor, |b| b.0);
        if far < n - 1 && frames.feasible_with(a, far + 1, c, opts)? {
            best = Some((farthest(frames, a, far + 1, c, opts)?, vec![c]));
        } else if let Some((far, reach)) = &mut best
            && frames.feasible_with(a, *far, c, opts)?
        {
            reach.push(c);
        }
    }
    Ok(best)
}

/// Of the estimates `reach` key `b` may carry, the one from which the next step goes farthest
/// (the first on a tie), with that step. Each estimate after the first is searched only past
/// the farthest step so far ([`greedy_step`]'s `floor`).
pub(super) fn look_ahead(
    frames: &Frames,
    b: usize,
    reach: &[usize],
    opts: &ReduceOptions,
) -> InputResult<(usize, (usize, Vec<usize>))> {
    let mut best: Option<(usize, (usize, Vec<usize>))> = None;
    for &c in reach {
        frames.choose(b, c);
        let floor = best.as_ref().map_or(b, |(_, (far, _))| *far);
        if let Some(next) = greedy_step(frames, b, floor, opts)? {
            best = Some((c, next));
        }
    }
    let (c, next) = best.unwrap_or((0, (b, Vec::new())));
    frames.choose(b, c);
    Ok((c, next))
}

/// Greedy keys: from each key the farthest next key whose segment alone meets the tolerances
/// ([`greedy_step`]). Where keys carry velocities and the scheme uses them, a key may carry any
/// of its frame's [`velocity_estimates`]: the farthest next key over them, and where several
/// estimates reach it, the one from which the step after goes farthest (one step of look-ahead;
/// the first frame likewise).
pub(super) fn greedy_keys(frames: &Frames, opts: &ReduceOptions) -> InputResult<Vec<usize>> {
    let n = frames.quats.len();
    let mut keys = vec![0];
    let all: Vec<usize> = (0..frames.choices).collect();
    frames.before.set(None);
    let (_, mut step) = look_ahead(frames, 0, &all, opts)?;
    loop {
        let (b, reach) = step;
        frames.before.set(keys.last().copied());
        keys.push(b);
        if b >= n - 1 {
            return Ok(keys);
        }
        step = if reach.len() > 1 {
            look_ahead(frames, b, &reach, opts)?.1
        } else {
            frames.choose(b, reach[0]);
            greedy_step(frames, b, b, opts)?.unwrap_or((b + 1, vec![0]))
        };
    }
}
