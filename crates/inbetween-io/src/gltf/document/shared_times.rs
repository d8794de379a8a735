//! One set of times for a clip whose `LINEAR` channels have different key times (Blender's and
//! three.js's exports key each channel on its own): world-space measures pose the skeleton at
//! each time, so every track is played as glTF plays it (slerp, lerp for its translation) at
//! the union of all tracks' key times (docs/spec.md §4.7, *glTF channels with their own times*).

use super::{GltfClip, MAX_BAKED_FRAMES, snapped_times};
use crate::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use inbetween::clock::Fps;
use inbetween::error::InputResult;

/// Two key times this close (s) are one time of the union.
const SAME_TIME: f64 = 1e-9;

impl GltfClip {
    /// `doc` (the clip's [`Mode::Frames`](super::Mode::Frames) document) with every track at
    /// the union of the key times of the tracks' channels and of their nodes' translation and
    /// scale channels, when some differ and every track is a `LINEAR` channel: each key the channel's value there as glTF plays it (slerp between its
    /// keys, its end keys held outside them), its translation channel's likewise. Unchanged
    /// otherwise. Errors: a union of more than 4 000 000 keys over all tracks.
    pub fn on_shared_times(&self, mut doc: Document, fps: Fps) -> InputResult<Document> {
        let times_of = |t: &crate::document::DocTrack| -> Vec<f64> {
            t.keys
                .iter()
                .map(|k| match k.when {
                    KeyTime::Seconds(s) | KeyTime::Frame(s) => s,
                })
                .collect()
        };
        let linear = (0..doc.tracks.len())
            .all(|i| self.channel(i).interpolation() == super::Interpolation::Linear);
        if !linear || doc.tracks.len() != self.tracks.len() {
            return Ok(doc);
        }
        // Every channel's times: the tracks' (their rotation channels'), and those of their
        // nodes' translation and scale channels (played there too, as a player shows them).
        let mut union: Vec<f64> = doc.tracks.iter().flat_map(times_of).collect();
        for i in 0..doc.tracks.len() {
            let anim = &self.animations[self.tracks[i].0];
            let node = self.channel(i).node();
            // Snapped to the rate's frames as the tracks' own times are.
            if let Some(tr) = self.translation(i) {
                union.extend(snapped_times(tr.times_f32(), fps));
            }
            for sc in anim.scales().iter().filter(|c| c.node() == node) {
                union.extend(snapped_times(sc.times_f32(), fps));
            }
        }
        union.sort_by(f64::total_cmp);
        union.dedup_by(|b, a| *b - *a <= SAME_TIME);
        if doc.tracks.iter().all(|t| times_of(t) == union) {
            return Ok(doc);
        }
        let keys = (union.len() as u64).saturating_mul(doc.tracks.len() as u64);
        if keys > MAX_BAKED_FRAMES {
            return Err(input_err!(
                "{}: its {} tracks key {} different times; played at all of them (to pose the \
                 skeleton at each) they come to more than {MAX_BAKED_FRAMES} keys",
                doc.source,
                doc.tracks.len(),
                union.len()
            ));
        }
        for (i, track) in doc.tracks.iter_mut().enumerate() {
            let ch = self.channel(i);
            let (times, stored) = (ch.times(), ch.times_f32());
            // Each time located at the channel key at or before it (messages name that key).
            let at = union
                .iter()
                .map(|&t| {
                    let k = times.partition_point(|&x| x <= t).saturating_sub(1);
                    (k, stored[k])
                })
                .collect();
            let (animation, channel) = (self.animations[self.tracks[i].0].index(), ch.index());
            let mut shared = DocTrack::new(
                union
                    .iter()
                    .map(|&t| Key {
                        when: KeyTime::Seconds(t),
                        rot: ch.sample(t),
                    })
                    .collect(),
                KeyOrigin::Gltf {
                    animation,
                    channel,
                    keys: at,
                },
            );
            if let Some(tr) = self.translation(i) {
                shared.translations = union.iter().map(|&t| Some(tr.sample(t))).collect();
            }
            shared.name = track.name.take();
            *track = shared;
        }
        Ok(doc)
    }
}
