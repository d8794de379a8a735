//! The optimal method: each frame's preferred estimate, then the shortest path over the frames
//! whose edges are the segments that meet the tolerances (slerp's exact early cut).

use super::*;

/// The longest segment (frames) the optimal method considers on a track whose greedy keys are
/// `greedy`: [`OPTIMAL_GREEDY_FACTOR`] times greedy's longest segment, at most
/// [`OPTIMAL_WINDOW`].
pub(crate) fn optimal_window(greedy: &[usize]) -> usize {
    let longest = greedy.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(1);
    (OPTIMAL_GREEDY_FACTOR * longest).min(OPTIMAL_WINDOW)
}

/// Each frame's preferred estimate for the optimal method: the one from which a segment starting
/// at the frame reaches farthest (up to `window` frames), the next key carrying its centred
/// estimate, searched as
/// [`greedy_step`] searches (the centred estimate first; another only when it meets the
/// tolerances one frame past the farthest so far). The last frame keeps its centred estimate.
pub(super) fn preferred_estimates(
    frames: &Frames,
    window: usize,
    opts: &ReduceOptions,
) -> InputResult<()> {
    let n = frames.quats.len();
    for b in 0..n - 1 {
        // The shortest path takes no segment longer than the window: reaching past it is
        // reaching it (on held motion every estimate does, and the search ends there).
        let end = (b + window).min(n - 1);
        let reach =
            |from: usize| farthest_by(end + 1, from, |x| frames.feasible_with(b, x, 0, opts));
        frames.choose(b, 0);
        let mut best = (reach(b + 1)?, 0);
        for c in 1..frames.choices {
            frames.choose(b, c);
            if best.0 < end && frames.feasible_with(b, best.0 + 1, 0, opts)? {
                best = (reach(best.0 + 1)?, c);
            }
        }
        frames.choose(b, best.1);
    }
    frames.choose(n - 1, 0);
    Ok(())
}

/// Optimal keys: the shortest path over the frames, an edge wherever the segment between two
/// frames (each carrying its preferred estimate, [`preferred_estimates`]) alone meets the
/// tolerances, for segments of at most `window` frames.
pub(super) fn optimal_keys(
    frames: &Frames,
    window: usize,
    opts: &ReduceOptions,
) -> InputResult<Vec<usize>> {
    if frames.choices > 1 {
        preferred_estimates(frames, window, opts)?;
    }
    let slerp = opts.curve.scheme == Scheme::Slerp && opts.curve.path == PathMode::Shortest;
    let mut speeds = SlerpSpeeds::new(0);
    shortest_path(frames.quats.len(), |a, b, improves, before| {
        if b == a + 1 {
            speeds = SlerpSpeeds::new(a);
            frames.before.set(before);
        }
        if slerp {
            if !speeds.admit(frames, b) {
                return Ok(Edge::Stop);
            }
        } else if b > a + window {
            return Ok(Edge::Stop);
        }
        Ok(
            if improves && (!slerp || speeds.allows(frames, b)) && frames.feasible(a, b, opts)? {
                Edge::Yes
            } else {
                Edge::No
            },
        )
    })
}

/// What [`shortest_path`] learns of the segment from one frame to a later one.
pub(super) enum Edge {
    /// The segment meets the tolerances.
    Yes,
    /// It does not (or it need not be tested).
    No,
    /// Neither it nor any longer segment from the same frame does.
    Stop,
}

/// The fewest keys from frame 0 to frame `n − 1` (`n ≥ 2`) over the edges `edge(a, b, improves,
/// before)` says meet the tolerances, the frames `b` tried in increasing order from each
/// reachable `a` (`improves`: an edge `a → b` would shorten the path to `b`, so it needs
/// testing; `before`: the key before `a` on the shortest path to it). Ties go to the earliest
/// predecessor.
pub(super) fn shortest_path(
    n: usize,
    mut edge: impl FnMut(usize, usize, bool, Option<usize>) -> InputResult<Edge>,
) -> InputResult<Vec<usize>> {
    let mut cost = vec![usize::MAX; n];
    let mut prev = vec![0usize; n];
    cost[0] = 0;
    for a in 0..n - 1 {
        if cost[a] == usize::MAX {
            continue;
        }
        for b in a + 1..n {
            let before = (a > 0).then(|| prev[a]);
            match edge(a, b, cost[a] + 1 < cost[b], before)? {
                Edge::Yes => {
                    cost[b] = cost[a] + 1;
                    prev[b] = a;
                }
                Edge::No => {}
                Edge::Stop => break,
            }
        }
    }
    let mut keys = vec![n - 1];
    while *keys.last().unwrap_or(&0) != 0 {
        let last = keys[keys.len() - 1];
        keys.push(prev[last]);
    }
    keys.reverse();
    Ok(keys)
}

/// Slerp's exact early cut. Slerp from key `a` to key `b` (the shorter way) turns at the constant
/// angular speed `ω = θ_ab / (t_b − t_a)`, so at a frame `k` between them it is `ω·(t_k − t_a)`
/// from `q_a`; if it is within the tolerance `T` of frame `k`, the triangle inequality of the
/// rotation angle gives `|θ_ak − ω·(t_k − t_a)| ≤ T`. Each frame inside the segment thus bounds
/// `ω` to an interval; the intervals of the frames after `a` only narrow as the segment grows,
/// and once they no longer meet, no segment from `a` reaching past them meets the tolerance.
pub(super) struct SlerpSpeeds {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) a: usize,
}

impl SlerpSpeeds {
    pub(super) fn new(a: usize) -> SlerpSpeeds {
        SlerpSpeeds {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            a,
        }
    }

    /// The tolerance on the angle, a hair wide (relative 1e-9, absolute 1e-12 rad, far above the
    /// rounding of the speeds) so that rounding never cuts a segment that meets it.
    pub(super) fn tol(frames: &Frames) -> f64 {
        frames.threshold.angle * (1.0 + 1e-9) + 1e-12
    }

    /// The speed of slerp from `a` to `k` and the time between them.
    pub(super) fn speed(&self, frames: &Frames, k: usize) -> (f64, f64) {
        let dt = frames.times[k] - frames.times[self.a];
        (
            rotation_angle_between(frames.quats[self.a], frames.quats[k]),
            dt,
        )
    }

    /// Frame `b − 1` joins the inside of the segment `a..b`; false when no segment from `a` to `b`
    /// or beyond can meet the tolerance.
    pub(super) fn admit(&mut self, frames: &Frames, b: usize) -> bool {
        if b >= self.a + 2 {
            let (d, dt) = self.speed(frames, b - 1);
            let tol = Self::tol(frames);
            self.lo = self.lo.max((d - tol) / dt);
            self.hi = self.hi.min((d + tol) / dt);
        }
        self.lo <= self.hi
    }

    /// Whether the speed of slerp from `a` to `b` is in every inside frame's interval (if not,
    /// the segment misses the tolerance).
    pub(super) fn allows(&self, frames: &Frames, b: usize) -> bool {
        let (d, dt) = self.speed(frames, b);
        (self.lo..=self.hi).contains(&(d / dt))
    }
}
