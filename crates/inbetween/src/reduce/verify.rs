//! Verification: the whole curve through the chosen keys evaluated at every frame as `interp`
//! builds it, the worst frame of each segment that misses made a key, until none misses.

use super::*;

/// The rotation error over a track's frames: largest, and sum in frame order; and the largest
/// position error, where positions are reduced.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Errors {
    pub(super) max: f64,
    pub(super) sum: f64,
    pub(super) position: Option<f64>,
}

impl Errors {
    pub(super) fn add(&mut self, e: f64) {
        self.max = self.max.max(e);
        self.sum += e;
    }
}

/// Completes `keys` until the whole curve meets the tolerances at every frame: the worst frame
/// of each segment that misses becomes a key. Returns the keys and the rotation error of their
/// curve over every frame.
pub(super) fn verified(
    frames: &Frames,
    mut keys: Vec<usize>,
    opts: &ReduceOptions,
) -> InputResult<(Vec<usize>, Errors)> {
    loop {
        let curve = frames.curve(&keys, &opts.curve)?;
        let at_key = |k: usize| {
            let e = error(opts, curve.rotation(frames.times[k]), frames.quats[k]);
            // A key is its frame, unless it is written at another time (float32).
            if e > opts.tolerance * (1.0 - 1e-9) {
                return Err(key_time_miss(frames, k, e, opts));
            }
            Ok(e)
        };
        let mut errors = Errors::default();
        let mut added = Vec::new();
        for (piece, w) in keys.windows(2).enumerate() {
            errors.add(at_key(w[0])?);
            let (ok, worst) = frames.check(&curve, (piece, w[0], w[1]), opts, &mut errors);
            if !ok {
                added.push(worst);
            }
        }
        if let Some(&last) = keys.last() {
            errors.add(at_key(last)?);
        }
        if added.is_empty() {
            return Ok((keys, errors));
        }
        keys.extend(added);
        keys.sort_unstable();
        keys.dedup();
    }
}

/// The error for a key that misses its own frame: only a key written at another time than its
/// frame's ([`TrackFrames::key_times`]) can, when the motion in that time difference exceeds
/// the tolerance.
pub(super) fn key_time_miss(
    frames: &Frames,
    k: usize,
    e: f64,
    opts: &ReduceOptions,
) -> crate::error::InputError {
    let written = frames.key_times.map_or(frames.times[k], |t| t[k]);
    let unit = if opts.distance.is_some() { "" } else { " rad" };
    crate::error::input_err!(
        "frame {k} ({} s): its key is written at {written} s (float32), and the motion in those \
         {:.1e} s misses the frame by {e:.3e}{unit}, more than the tolerance {:.3e}{unit}; give a \
         larger tolerance or a timeline nearer 0",
        frames.times[k],
        (written - frames.times[k]).abs(),
        opts.tolerance
    )
}

/// [`verified`] on every track, until the keys meet the tolerances on all. Returns the keys and
/// each track's error over its frames.
pub(super) fn shared_verified(
    frames: &[Frames],
    mut keys: Vec<usize>,
    opts: &[ReduceOptions],
) -> InputResult<(Vec<usize>, Vec<Errors>)> {
    // Each track's errors and the number of keys they were measured on. Keys only grow, so a
    // track measured on as many keys as there are now was measured on the final keys.
    let mut measured: Vec<Option<(usize, Errors)>> = vec![None; frames.len()];
    for t in (0..frames.len()).cycle() {
        if measured
            .iter()
            .all(|m| m.is_some_and(|(n, _)| n == keys.len()))
        {
            break;
        }
        let (k, e) = verified(&frames[t], keys, &opts[t])?;
        keys = k;
        measured[t] = Some((keys.len(), e));
    }
    let errors = measured.into_iter().flatten().map(|(_, e)| e).collect();
    Ok((keys, errors))
}

/// The largest errors of `curve` over the frames of `track` at the frame times, measured as
/// [`reduce_frames`] measures them: the rotation error as `opts` defines it (the angle, or with
/// `distance` the displacement), and, where the track has positions and `opts` a translation
/// tolerance, the largest distance of the curve's position from the frame's (a NaN counts as
/// infinite). This checks keys that were changed after reducing, e.g. rounded for writing.
pub fn curve_errors(
    track: &TrackFrames<'_>,
    curve: &Curve,
    opts: &ReduceOptions,
) -> (f64, Option<f64>) {
    let worse = |max: f64, e: f64| {
        if e.is_nan() {
            f64::INFINITY
        } else {
            max.max(e)
        }
    };
    let mut max = 0.0;
    let mut position = None;
    for (k, &t) in track.times.iter().enumerate() {
        max = worse(max, error(opts, curve.rotation(t), track.rotations[k]));
        if let (Some(p), Some(_)) = (track.positions, opts.translation_tolerance) {
            let d = (curve.position(t).unwrap_or(DVec3::ZERO) - p[k]).length();
            position = Some(worse(position.unwrap_or(0.0), d));
        }
    }
    (max, position)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    /// A slerp curve through two keys 90° apart about z, measured against frames turned a
    /// further 1° about x: the error is that angle at every frame (closed form: the curve's
    /// rotation is `R_z(90° t)`, the frame's `R_z(90° t)·R_x(1°)`), 2·D·sin(θ/2) with a distance
    /// D, and the position error the frames' 0.25 offset.
    #[test]
    fn curve_errors_are_the_angle_and_distance_to_the_frames() {
        let keys = Track::new(
            vec![0.0, 1.0],
            vec![DQuat::IDENTITY, DQuat::from_rotation_z(FRAC_PI_2)],
        )
        .unwrap()
        .with_translations(vec![DVec3::ZERO, DVec3::X])
        .unwrap();
        let opts = ReduceOptions {
            curve: CurveOptions {
                scheme: Scheme::Slerp,
                ..CurveOptions::default()
            },
            translation_tolerance: Some(1.0),
            ..ReduceOptions::default()
        };
        let curve = Curve::new(&keys, &opts.curve).unwrap();
        let times: Vec<f64> = (0..=10).map(|k| f64::from(k) / 10.0).collect();
        let tilt = DQuat::from_rotation_x(1f64.to_radians());
        let frames: Vec<DQuat> = times
            .iter()
            .map(|&t| DQuat::from_rotation_z(FRAC_PI_2 * t) * tilt)
            .collect();
        let positions: Vec<DVec3> = times.iter().map(|&t| DVec3::new(t, 0.25, 0.0)).collect();
        let track = TrackFrames {
            times: &times,
            rotations: &frames,
            positions: Some(&positions),
            euler: None,
            key_times: None,
        };
        let (angle, position) = curve_errors(&track, &curve, &opts);
        assert!((angle - 1f64.to_radians()).abs() < 1e-12, "{angle}");
        assert!((position.unwrap() - 0.25).abs() < 1e-12, "{position:?}");
        let far = ReduceOptions {
            distance: Some(10.0),
            ..opts
        };
        let (d, _) = curve_errors(&track, &curve, &far);
        assert!((d - 20.0 * 0.5f64.to_radians().sin()).abs() < 1e-12, "{d}");
    }
}
