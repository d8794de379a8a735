//! Keys written as BVH on a template skeleton (`convert keys.json --skeleton clip.bvh -o
//! out.bvh`): every track a joint of the template, all on one common grid of consecutive frames.

use super::Clip;
use crate::document::{Document, KeyTime};
use crate::write::EulerMode;
use inbetween::error::{InputError, InputResult, Setting};
use inbetween::message;
use inbetween::rotation::unwrap::EulerUnwrap;
use std::collections::HashMap;
use std::io::Write;

/// Writes `doc`'s keys as the motion of `skeleton` (its hierarchy text, its channel orders) at
/// `fps`: row `i` is key `i` of every track. Each joint with channels must have a track named
/// by its [`track_name`](super::Joint::track_name) (and translations where it has position
/// channels); every track must have the same keys
/// at consecutive frame numbers. Rotations are continuous Euler angles in each joint's own
/// order, from the first key's own triple when the keys were Euler angles in that sequence, or
/// with [`EulerMode::Wrapped`] each triple in scipy's ranges.
pub fn write_keys<W: Write>(
    out: W,
    doc: &Document,
    skeleton: &Clip,
    fps: inbetween::clock::Fps,
    euler: EulerMode,
) -> InputResult<()> {
    let layout = || {
        InputError::new(message![
            format!("{}: ", doc.source),
            Setting::Skeleton,
            " writes keys that are frames of one grid (every track keyed at the same consecutive \
             frame numbers); resample other keys with interp onto a BVH input"
        ])
    };
    let first = doc.tracks.first().ok_or_else(layout)?;
    let n = first.keys.len();
    let frames: Vec<f64> = first
        .keys
        .iter()
        .map(|k| match k.when {
            KeyTime::Frame(f) => Some(f),
            KeyTime::Seconds(t) => {
                let f = t * fps.as_f64();
                ((f - f.round()).abs() < 1e-6).then_some(f.round())
            }
        })
        .collect::<Option<_>>()
        .ok_or_else(layout)?;
    if frames.windows(2).any(|w| w[1] - w[0] != 1.0)
        || doc.tracks.iter().any(|t| {
            t.keys.len() != n
                || t.keys
                    .iter()
                    .zip(&first.keys)
                    .any(|(a, b)| a.when != b.when)
        })
    {
        return Err(layout());
    }
    let width = skeleton.channel_count();
    let mut values = vec![0.0; n * width];
    // Tracks by name (the first of a name, as a track selection finds it): one lookup a joint.
    let mut by_name: HashMap<&str, usize> = HashMap::with_capacity(doc.tracks.len());
    for (i, t) in doc.tracks.iter().enumerate() {
        if let Some(name) = t.name.as_deref() {
            by_name.entry(name).or_insert(i);
        }
    }
    for joint in skeleton.joints() {
        let (rotation, position) = (joint.rotation(), joint.position());
        if rotation.is_none() && position.is_none() {
            continue;
        }
        let track = by_name
            .get(joint.track_name())
            .map(|&i| &doc.tracks[i])
            .ok_or_else(|| {
                input_err!(
                    "{}: no track for joint \"{}\" of the skeleton",
                    doc.source,
                    inbetween::error::shorten(joint.track_name())
                )
            })?;
        if let Some((seq, cols)) = rotation {
            let mut unwrap = match &track.euler {
                // A start far beyond a few turns could not be unwrapped from (the spacing of
                // f64 there exceeds a turn).
                Some((s, angles))
                    if *s == seq
                        && angles.first().is_some_and(|e| {
                            e.abs().max_element() <= inbetween::rotation::magnitude::MAX_ANGLE
                        }) =>
                {
                    EulerUnwrap::with_start(seq, angles[0].to_array())
                }
                _ => EulerUnwrap::new(seq),
            };
            for (i, key) in track.keys.iter().enumerate() {
                let e = match euler {
                    EulerMode::Wrapped => seq.from_quat(key.rot),
                    _ => unwrap.next(key.rot),
                };
                let e = super::on_listed_axes(seq, &cols, key.rot, e);
                for (c, a) in cols.iter().zip(e) {
                    if let Some(c) = c {
                        values[i * width + c] = a.to_degrees();
                    }
                }
            }
        }
        if let Some(cols) = position {
            if track.translations.len() != n || track.translations.iter().any(Option::is_none) {
                return Err(input_err!(
                    "{}: track \"{}\": joint \"{}\" has position channels, so every key needs a \
                     translation",
                    doc.source,
                    inbetween::error::shorten(joint.track_name()),
                    inbetween::error::shorten(joint.name())
                ));
            }
            for (i, p) in track.translations.iter().flatten().enumerate() {
                for (c, x) in cols.iter().zip(p.to_array()) {
                    if let Some(c) = c {
                        values[i * width + c] = x;
                    }
                }
            }
        }
    }
    super::write(out, skeleton.hierarchy(), fps, width, &values)
        .map_err(|e| input_err!("{}: {e}", doc.source))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::read::tests::{least_of_runs, many_joints};
    use crate::bvh::{document::document, parse};

    /// Matching 8n joints to their tracks takes about 8 times as long as matching n, not 64
    /// (a linear search per joint: minutes for 100 000 joints). The bound (24) leaves room for
    /// noise on a shared machine on both sides (12 000 against 3000 joints measured 10.4× under
    /// load against a bound of 8); the names are long and of one length, which a search pays
    /// for in full.
    #[test]
    fn matching_joints_to_tracks_is_linear() {
        let time = |n: usize| {
            let (clip, _) = parse(&many_joints(n, 300), "many.bvh").unwrap();
            let fps = clip.fps();
            let doc = document(clip.clone(), "many.bvh", Vec::new());
            least_of_runs(|| {
                let mut out = Vec::new();
                write_keys(&mut out, &doc, &clip, fps, EulerMode::Continuous).unwrap();
                assert!(out.len() > 12 * n);
            })
        };
        let (small, large) = (time(3000), time(24_000));
        assert!(
            large < 24.0 * small,
            "{small} s for 3000 joints, {large} s for 24000"
        );
    }
}
