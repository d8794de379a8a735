//! `reduce -o small.fbx`: the kept keys verified as an FBX player plays them (docs/spec.md §3,
//! *FBX output*). A player interpolates each Euler channel of a joint — and each coordinate of
//! its translation — linearly and on its own between float32 keys ([`Played`]), which no
//! quaternion scheme does; so the keys reduce found under its scheme (slerp by default, the
//! nearest to a linear path) are replayed that way at every input frame, and wherever a frame
//! misses the tolerance the worst frame of its segment becomes a key, until every frame of every
//! track is within it. With `--shared-keys` a frame added to one track is added to all.

use inbetween::reduce::Reduced;
use inbetween::{Error, Fps, InputError, Track};
use inbetween_io::document::Document;
use inbetween_io::fbx::keys::joint_orders;
use inbetween_io::fbx::play::Played;
use inbetween_io::fbx::write::time_tick;

/// What the replay must meet: the rotation tolerance (rad) and the translation tolerance
/// (length units) where translations are reduced.
pub(super) struct Bounds {
    pub rotation: f64,
    pub translation: Option<f64>,
}

/// The worst frame of each segment between keys that misses `bounds` as `played` plays the
/// track, and the track's largest and mean rotation error and largest position error.
fn misses(track: &Track, keys: &[usize], played: &Played, b: &Bounds) -> (Vec<usize>, [f64; 3]) {
    let (times, rots) = (track.times(), track.rotations());
    let positions = track.translations().filter(|_| b.translation.is_some());
    let (mut worst, mut sum, mut worst_p) = (0.0f64, 0.0, 0.0f64);
    let mut add = Vec::new();
    let last = keys.len().saturating_sub(2);
    for (s, w) in keys.windows(2).enumerate() {
        let mut seg: Option<(f64, usize)> = None;
        for f in w[0]..=w[1] {
            let e = played.rotation(times[f]).angle_between(rots[f]);
            let mut over = e / b.rotation;
            worst = worst.max(e);
            // Each frame counted once: a segment's end is the next one's start.
            if f < w[1] || s == last {
                sum += e;
            }
            if let (Some(p), Some(at)) = (positions, played.position(times[f])) {
                let d = (p[f] - at).length();
                worst_p = worst_p.max(d);
                over = over.max(d / b.translation.unwrap_or(f64::INFINITY));
            }
            if over > 1.0 && seg.is_none_or(|(o, _)| over > o) {
                seg = Some((over, f));
            }
        }
        if let Some((_, f)) = seg {
            add.push(f);
        }
    }
    let mean = sum / times.len().max(1) as f64;
    (add, [worst, mean, worst_p])
}

/// The keys of `reduced` (one per track of `tracks`, the tracks of `doc`) refined until FBX's
/// per-channel playback of them is within `bounds` at every frame (see the module
/// documentation); `fps` is the rate the keys' ticks are written at. Errors: a frame that misses
/// the bounds while it is a key itself (a tolerance below float32's reach).
pub(super) fn refine(
    doc: &Document,
    tracks: &[Track],
    mut reduced: Vec<Reduced>,
    bounds: &Bounds,
    shared: bool,
    fps: Fps,
) -> Result<Vec<Reduced>, Error> {
    let orders = joint_orders(doc);
    let joints = doc
        .hierarchy
        .as_ref()
        .map(|h| h.track_joints())
        .unwrap_or_default();
    let seq_of = |i: usize| joints.get(i).copied().flatten().map(|j| orders[j]);
    let frames: usize = tracks.iter().map(|t| t.times().len()).sum();
    // Each pass adds a key or ends: at most one pass per frame.
    for _ in 0..=frames {
        let mut added: Vec<Vec<usize>> = Vec::with_capacity(tracks.len());
        for (i, (track, r)) in tracks.iter().zip(&mut reduced).enumerate() {
            let Some(seq) = seq_of(i) else {
                return Err(Error::Internal(format!(
                    "internal error: track {i} has no joint"
                )));
            };
            let ticks = r
                .keys
                .iter()
                .map(|&k| time_tick(track.times()[k], fps))
                .collect();
            let rots: Vec<_> = r.keys.iter().map(|&k| track.rotations()[k]).collect();
            let pos: Option<Vec<_>> = track
                .translations()
                .filter(|_| bounds.translation.is_some())
                .map(|p| r.keys.iter().map(|&k| p[k]).collect());
            let played = Played::new(seq, ticks, &rots, pos.as_deref());
            let (add, [worst, mean, worst_p]) = misses(track, &r.keys, &played, bounds);
            if let Some(&f) = add.iter().find(|f| r.keys.binary_search(f).is_ok()) {
                return Err(InputError::new(format!(
                    "{}: frame {f} misses the tolerance as FBX plays its float32 key; give a \
                     larger tolerance",
                    doc.source
                ))
                .into());
            }
            r.max_error = worst;
            r.mean_error = mean;
            r.max_position_error = bounds.translation.map(|_| worst_p);
            added.push(add);
        }
        if added.iter().all(Vec::is_empty) {
            for r in &mut reduced {
                r.velocities = None;
            }
            return Ok(reduced);
        }
        if shared {
            let mut all: Vec<usize> = added.concat();
            all.sort_unstable();
            all.dedup();
            added = vec![all; tracks.len()];
        }
        for (r, add) in reduced.iter_mut().zip(added) {
            r.keys.extend(add);
            r.keys.sort_unstable();
            r.keys.dedup();
        }
    }
    Err(Error::Internal(
        "internal error: FBX keys not verified after a pass per frame".into(),
    ))
}
