//! Shared keys: the methods on all tracks at once, a segment meeting the tolerances when it
//! meets them on every track.

use super::*;

/// Reduces several tracks to one set of key times (`--shared-keys`): the methods run on all
/// tracks at once, a segment meeting the tolerances when it meets them on every track (each
/// track's key carrying its own estimate; optimal is exactly the fewest shared keys for slerp),
/// then verification of every track on the keys until all meet the tolerances. The tracks must
/// have the same frame times.
pub fn reduce_shared(
    tracks: &[TrackFrames<'_>],
    opts: &ReduceOptions,
) -> Result<Vec<Reduced>, Error> {
    reduce_shared_each(tracks, &vec![*opts; tracks.len()])
}

/// [`reduce_shared`] with each track's own tolerances: `opts[t]` is track `t`'s, and all must
/// agree on everything but `tolerance` and `translation_tolerance` (the curve, the error's
/// measure, velocities, method).
pub(crate) fn reduce_shared_each(
    tracks: &[TrackFrames<'_>],
    opts: &[ReduceOptions],
) -> Result<Vec<Reduced>, Error> {
    let Some(times) = tracks.first().map(|t| t.times) else {
        return Ok(Vec::new());
    };
    if tracks.iter().any(|t| t.times != times) {
        return Err(crate::error::InputError::new(crate::message![
            crate::error::Setting::SharedKeys,
            ": the tracks have different frame times; shared keys need one grid"
        ])
        .into());
    }
    let same = |a: &ReduceOptions, b: &ReduceOptions| {
        ReduceOptions {
            tolerance: a.tolerance,
            translation_tolerance: a.translation_tolerance,
            ..*b
        } == *a
    };
    if opts.len() != tracks.len() || opts.iter().any(|o| !same(o, &opts[0])) {
        return Err(Error::Internal(format!(
            "internal error: reduce_shared_each takes one options per track ({} for {} tracks), \
             differing only in their tolerances",
            opts.len(),
            tracks.len()
        )));
    }
    let n = times.len();
    let frames: Vec<Frames> = tracks
        .iter()
        .zip(opts)
        .map(|(t, o)| Frames::new(t, o))
        .collect();
    if n < 2 {
        return tracks
            .iter()
            .zip(opts)
            .map(|(t, o)| reduce_frames(t, o))
            .collect();
    }
    let (keys, errors) = method_keys(
        &frames,
        opts,
        || shared_greedy_keys(&frames, opts),
        |window| shared_optimal_keys(&frames, window, opts),
    )?;
    frames
        .iter()
        .zip(errors)
        .zip(opts)
        .map(|((f, e), o)| reduced(f, keys.clone(), e, o))
        .collect()
}

/// Whether segment `a..b` meets the tolerances on every track, each track's frame `b` carrying
/// the first of its estimates with which it does (its choice set to it). `first` is the track
/// to test first: the one that missed last time (updated).
pub(super) fn shared_feasible(
    frames: &[Frames],
    a: usize,
    b: usize,
    first: &std::cell::Cell<usize>,
    opts: &[ReduceOptions],
) -> InputResult<bool> {
    let m = frames.len();
    for j in 0..m {
        let t = (first.get() + j) % m;
        let f = &frames[t];
        let mut ok = false;
        for c in 0..f.choices {
            if f.feasible_with(a, b, c, &opts[t])? {
                ok = true;
                break;
            }
        }
        if !ok {
            first.set(t);
            return Ok(false);
        }
    }
    Ok(true)
}

/// Greedy shared keys: from each key the farthest next key whose segment meets the tolerances on
/// every track ([`shared_feasible`], doubling then bisection), each track's key carrying the first
/// of its estimates that meets them there.
pub(super) fn shared_greedy_keys(
    frames: &[Frames],
    opts: &[ReduceOptions],
) -> InputResult<Vec<usize>> {
    let n = frames[0].quats.len();
    let first = std::cell::Cell::new(0);
    let mut keys = vec![0];
    let mut a = 0;
    while a < n - 1 {
        for f in frames {
            f.before.set(keys.len().checked_sub(2).map(|i| keys[i]));
        }
        let b = farthest_by(n, a + 1, |b| shared_feasible(frames, a, b, &first, opts))?;
        // The key's estimates: those of the test at `b` itself.
        shared_feasible(frames, a, b, &first, opts)?;
        keys.push(b);
        a = b;
    }
    Ok(keys)
}

/// Optimal shared keys: the shortest path over the frames with an edge `a → b` wherever the
/// segment meets the tolerances on every track ([`shared_feasible`]: each track's frame `b`
/// carrying the first of its estimates with which it does), each track's frame `a` carrying the
/// estimate of the edge by which the path reached `a`. Without estimates to choose (slerp, or
/// no velocities) that is the fewest shared keys with segments of at most `window` frames; slerp
/// has no window: the search from a key stops where any track's early cut ([`SlerpSpeeds`]) says
/// no longer segment can meet the tolerance on it, so its result is exactly the fewest.
pub(super) fn shared_optimal_keys(
    frames: &[Frames],
    window: usize,
    opts: &[ReduceOptions],
) -> InputResult<Vec<usize>> {
    let n = frames[0].quats.len();
    let slerp = opts[0].curve.scheme == Scheme::Slerp && opts[0].curve.path == PathMode::Shortest;
    let first = std::cell::Cell::new(0);
    let mut speeds: Vec<SlerpSpeeds> = Vec::new();
    // Each track's estimate at each frame, from the edge that reached it.
    let mut reached: Vec<Vec<u8>> = frames.iter().map(|_| vec![0; n]).collect();
    shortest_path(n, |a, b, improves, before| {
        if b == a + 1 {
            speeds = frames.iter().map(|_| SlerpSpeeds::new(a)).collect();
            for (f, r) in frames.iter().zip(&reached) {
                f.choose(a, usize::from(r[a]));
                f.before.set(before);
            }
        }
        if slerp {
            if !speeds.iter_mut().zip(frames).all(|(s, f)| s.admit(f, b)) {
                return Ok(Edge::Stop);
            }
        } else if b > a + window {
            return Ok(Edge::Stop);
        }
        if !improves || (slerp && !speeds.iter().zip(frames).all(|(s, f)| s.allows(f, b))) {
            return Ok(Edge::No);
        }
        if !shared_feasible(frames, a, b, &first, opts)? {
            return Ok(Edge::No);
        }
        for (f, r) in frames.iter().zip(&mut reached) {
            r[b] = f.choice[b].get();
        }
        Ok(Edge::Yes)
    })
    .inspect(|keys| {
        for (f, r) in frames.iter().zip(&reached) {
            for &k in keys {
                f.choose(k, usize::from(r[k]));
            }
        }
    })
}
