//! Keys written as BVH on a template skeleton (`convert keys.json --skeleton clip.bvh -o
//! out.bvh`): every track a joint of the template, all on one common grid of consecutive frames.

use super::Clip;
use crate::error::{InputResult, input_err};
use crate::io::document::{Document, KeyTime};
use crate::rotation::unwrap::EulerUnwrap;
use std::io::Write;

/// Writes `doc`'s keys as the motion of `skeleton` (its hierarchy text, its channel orders) at
/// `fps`: row `i` is key `i` of every track. Each joint with channels must have a track of its
/// name (and translations where it has position channels); every track must have the same keys
/// at consecutive frame numbers. Rotations are continuous Euler angles in each joint's own
/// order, from the first key's own triple when the keys were Euler angles in that sequence.
pub fn write_keys<W: Write>(
    out: W,
    doc: &Document,
    skeleton: &Clip,
    fps: crate::clock::Fps,
) -> InputResult<()> {
    let layout = || {
        input_err!(
            "{}: --skeleton writes keys that are frames of one grid (every track keyed at the same \
             consecutive frame numbers); resample other keys with interp onto a BVH input",
            doc.source
        )
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
    for joint in skeleton.joints() {
        let (rotation, position) = (joint.rotation(), joint.position());
        if rotation.is_none() && position.is_none() {
            continue;
        }
        let track = doc
            .tracks
            .iter()
            .find(|t| t.name.as_deref() == Some(joint.name()))
            .ok_or_else(|| {
                input_err!(
                    "{}: no track for joint \"{}\" of the skeleton",
                    doc.source,
                    crate::error::shorten(joint.name())
                )
            })?;
        if let Some((seq, cols)) = rotation {
            let mut unwrap = match &track.euler {
                Some((s, angles)) if *s == seq => {
                    EulerUnwrap::with_start(seq, angles[0].to_array())
                }
                _ => EulerUnwrap::new(seq),
            };
            for (i, key) in track.keys.iter().enumerate() {
                let e = unwrap.next(key.rot);
                for (c, a) in cols.iter().zip(e) {
                    values[i * width + c] = a.to_degrees();
                }
            }
        }
        if let Some(cols) = position {
            if track.translations.len() != n || track.translations.iter().any(Option::is_none) {
                return Err(input_err!(
                    "{}: track \"{}\": joint \"{}\" has position channels, so every key needs a \
                     translation",
                    doc.source,
                    crate::error::shorten(joint.name()),
                    crate::error::shorten(joint.name())
                ));
            }
            for (i, p) in track.translations.iter().flatten().enumerate() {
                for (c, x) in cols.iter().zip(p.to_array()) {
                    values[i * width + c] = x;
                }
            }
        }
    }
    super::write(out, skeleton.hierarchy(), fps, width, &values)
        .map_err(|e| input_err!("{}: {e}", doc.source))
}
