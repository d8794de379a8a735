//! The animations of a glTF asset as a keyframe [`Document`]: one track per rotation channel.
//!
//! A [`GltfClip`] is an asset with the animations chosen (`--animation NAME|INDEX`, default
//! all); [`GltfClip::document`] turns their rotation channels into tracks at a frame rate:
//!
//! - Names: the target node's name (`node<index>` for a node without one) when one animation is
//!   chosen, else `animation/node` with the animation's name (its index when it has none), made
//!   unique by `unique_names` with the node index (a later duplicate gets
//!   `#<node index>`, then `#<node index>#2`, …, never a name given or taken earlier). Names are
//!   labels: a track is mapped back to its channel through [`GltfClip::source_of`], a hash of
//!   these unique names, and [`GltfClip::source`] by position.
//! - Times: float32 seconds; a key within two float32 ulps of a frame time of the rate is on
//!   that frame (`snap_key_time`), so that keys exported at a rate come back exactly;
//!   when that would not keep the times strictly increasing (two keys near one frame), the
//!   keys involved keep their stored times (`snapped_times`).
//! - `LINEAR`: the values are the track's keys, for the scheme of the command.
//! - `STEP` and `CUBICSPLINE` ([`Mode::Frames`], [`Mode::Sampled`]): the sampler defines its
//!   own curve, which `interp` samples at every frame of the animation's span while writing
//!   ([`GltfClip::sampler`], [`inbetween::bake::bake_sampled`]; the track is marked
//!   [`TrackSource::baked`]). A `STEP` track is two keys per held value, on the first and last
//!   frame that hold it (a `STEP` frame holds the last key at or before it, on the snapped
//!   times), which slerp reproduces at every frame: bounded by the input, whatever the rate. A
//!   `CUBICSPLINE` track is, for `interp` ([`Mode::Sampled`]), its vertices `v_k` with the
//!   angular velocities of their tangents (`tangent_velocity`), and for `analyze`, `plot`
//!   and `reduce` ([`Mode::Frames`]) the curve at every frame. A `CUBICSPLINE` rotation whose
//!   4-vector comes near zero between two keys has no rotation there: an input error.
//! - [`Mode::Keys`] (for `convert`): every sampler's keys; a `CUBICSPLINE` key carries the
//!   angular velocity of its tangent and a `STEP` channel is written as its keys, with a
//!   warning that the hold is not kept.
//! - Translations: the translation channel of the same node in the same animation, if any. When
//!   its times are the rotation keys' (as float32), its values are the keys' positions;
//!   otherwise it is sampled (by its own interpolation) at the rotation keys, with a warning.
//!   `interp` samples it at every frame of a baked track.
//! - Keys are located in messages by what the file has: `animations[0].channels[2] key 3
//!   (0.5 s)` ([`KeyOrigin::Gltf`]).

use super::warnings::ChannelWarnings;
use super::{
    Animation, Asset, Channel, Interpolation, RotationChannel, TranslationChannel, snap_key_time,
};
use crate::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use glam::{DQuat, DVec3, DVec4};
use inbetween::clock::Fps;
use inbetween::error::{InputError, InputResult, Setting, shorten};
use inbetween::message;
use inbetween::rotation::Repr;
use std::collections::HashMap;

mod shared_times;
mod skeleton;

/// What the tracks are for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Interpolation (`analyze`, `plot`, `reduce`): `STEP` and `CUBICSPLINE` channels are their
    /// own curves: a `STEP` track is its held values (two keys each), a `CUBICSPLINE` track its
    /// curve sampled at every frame of the animation's span.
    Frames,
    /// `interp`: as [`Mode::Frames`], but a `CUBICSPLINE` track is its vertices (with their
    /// tangents' velocities); `interp` samples the channel at every frame while writing
    /// ([`GltfClip::sampler`]), never holding the frames.
    Sampled,
    /// The keys as stored (`convert`): `CUBICSPLINE` tangents as per-key angular velocities.
    Keys,
    /// World-space `reduce`: as [`Mode::Frames`], and where `LINEAR` tracks have different key
    /// times, every track at the union of them ([`GltfClip::on_shared_times`]), so that the
    /// skeleton is posed at each.
    Posed,
}

/// Where a track of the document comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackSource {
    /// The track's name.
    pub name: String,
    /// The track's position in the clip's tracks ([`GltfClip::sources`]).
    pub index: usize,
    /// The animation's position in [`GltfClip::animations`].
    pub animation: usize,
    /// The channel's index in the animation's `channels`.
    pub channel: usize,
    /// The sampler's interpolation.
    pub interpolation: Interpolation,
    /// The track is the sampler's own curve, sampled at every frame by `interp`
    /// ([`Mode::Frames`] with `STEP` or `CUBICSPLINE`; [`GltfClip::sampler`]).
    pub baked: bool,
}

/// The most frames [`GltfClip::document`] bakes for `CUBICSPLINE` channels in
/// [`Mode::Frames`] (`analyze`, `plot`, `reduce`), over all of them: about 600 MB of keys. A
/// 4 kB asset whose key times run to 10⁵ s took 47 s and 10 GB at 1000 fps (found by the
/// `gltf_reader` fuzz target).
pub(crate) const MAX_BAKED_FRAMES: u64 = 4_000_000;

/// An asset with its chosen animations, read and checked.
#[derive(Debug)]
pub struct GltfClip {
    asset: Asset,
    animations: Vec<Animation>,
    /// Per track: the animation's position and the channel's position in its `rotations()`.
    tracks: Vec<(usize, usize)>,
    /// Per track: the position of its node's translation channel in the animation's
    /// `translations()`, if any (the first).
    translations: Vec<Option<usize>>,
    names: Vec<String>,
    by_name: HashMap<String, usize>,
}

/// A baked track's curve: the rotation channel (`STEP` on its snapped times) and the node's
/// translation channel, sampled at any time ([`GltfClip::sampler`]).
#[derive(Debug, Clone)]
pub struct Sampler {
    rotation: RotationChannel,
    translation: Option<TranslationChannel>,
}

impl Sampler {
    /// The rotation (a unit quaternion) and the position at `t` seconds, as glTF 2.0 Appendix C
    /// evaluates the channels ([`RotationChannel::sample`]).
    pub fn at(&self, t: f64) -> (DQuat, Option<DVec3>) {
        (
            self.rotation.sample(t),
            self.translation.as_ref().map(|tr| tr.sample(t)),
        )
    }
}

impl GltfClip {
    /// The animations of `asset` chosen by `animation` (a name, else an index; `None`: all of
    /// them). Errors: an asset without animations, an animation that does not exist, no
    /// rotation channel in the chosen animations, and every error of [`Asset::animations`].
    pub fn new(asset: Asset, animation: Option<&str>) -> InputResult<GltfClip> {
        let src = asset.source().to_string();
        let all = asset.animations()?;
        if all.is_empty() {
            return Err(input_err!("{src}: the asset has no animations"));
        }
        let animations: Vec<Animation> = match animation {
            None => all
                .into_iter()
                .filter(|a| !a.rotations().is_empty())
                .collect(),
            Some(want) => {
                let found = all
                    .iter()
                    .position(|a| a.name() == Some(want))
                    .or_else(|| want.parse::<usize>().ok().filter(|&i| i < all.len()));
                let Some(i) = found else {
                    let list: Vec<String> = all
                        .iter()
                        .map(|a| match a.name() {
                            Some(n) => format!("{} (\"{}\")", a.index(), shorten(n)),
                            None => a.index().to_string(),
                        })
                        .collect();
                    return Err(InputError::new(message![
                        Setting::Animation,
                        format!(
                            " {}: no such animation in {src} (it has {})",
                            shorten(want),
                            list.join(", ")
                        )
                    ]));
                };
                let a = all.into_iter().nth(i).expect("found above");
                if a.rotations().is_empty() {
                    return Err(input_err!(
                        "{src}: animation {} has no rotation channels",
                        anim_label(&a)
                    ));
                }
                vec![a]
            }
        };
        if animations.is_empty() {
            return Err(input_err!(
                "{src}: no animation has a rotation channel (tracks are rotation channels)"
            ));
        }
        let several = animations.len() > 1;
        let mut given: Vec<String> = Vec::new();
        let mut ids: Vec<usize> = Vec::new();
        let mut tracks = Vec::new();
        let mut translations = Vec::new();
        for (a, anim) in animations.iter().enumerate() {
            let label = anim.label();
            let mut by_node: HashMap<usize, usize> = HashMap::new();
            for (j, tr) in anim.translations().iter().enumerate() {
                by_node.entry(tr.node()).or_insert(j);
            }
            for (c, ch) in anim.rotations().iter().enumerate() {
                given.push(if several {
                    format!("{label}/{}", ch.node_name())
                } else {
                    ch.node_name().to_string()
                });
                ids.push(ch.node());
                tracks.push((a, c));
                translations.push(by_node.get(&ch.node()).copied());
            }
        }
        let names = crate::names::unique_names(&given, &ids);
        let by_name = names
            .iter()
            .enumerate()
            .map(|(i, n)| (n.clone(), i))
            .collect();
        Ok(GltfClip {
            asset,
            animations,
            tracks,
            translations,
            names,
            by_name,
        })
    }

    /// The clip without its tracks' translations: for an output that writes the translation
    /// channels themselves (glTF), so that [`GltfClip::document`] neither samples them at the
    /// rotation keys nor warns that it does.
    pub fn without_translations(mut self) -> GltfClip {
        self.translations.fill(None);
        self
    }

    /// The asset as read.
    pub fn asset(&self) -> &Asset {
        &self.asset
    }

    /// The chosen animations (those with rotation channels when all were chosen).
    pub fn animations(&self) -> &[Animation] {
        &self.animations
    }

    /// The earliest and latest input time of animation `a` (a position in
    /// [`GltfClip::animations`]), each on a frame of `fps` when within two float32 ulps of it.
    pub fn span(&self, a: usize, fps: Fps) -> (f64, f64) {
        let (lo, hi) = self.animations[a].span().unwrap_or((0.0, 0.0));
        (snap_key_time(lo as f32, fps), snap_key_time(hi as f32, fps))
    }

    /// The frames of animation `a`'s span at `fps`, `(first, last)` inclusive (empty when
    /// `first > last`).
    pub fn frames(&self, a: usize, fps: Fps) -> (i64, i64) {
        let (lo, hi) = self.span(a, fps);
        if !fps.in_range(lo) || !fps.in_range(hi) {
            return (1, 0);
        }
        fps.frames_between(lo, hi)
    }

    /// The number of tracks (rotation channels of the chosen animations).
    pub fn len(&self) -> usize {
        self.tracks.len()
    }

    /// Whether the clip has no track (never: [`GltfClip::new`] refuses that).
    pub fn is_empty(&self) -> bool {
        self.tracks.is_empty()
    }

    /// The rotation channel of track `i`.
    fn channel(&self, i: usize) -> &RotationChannel {
        let (a, c) = self.tracks[i];
        &self.animations[a].rotations()[c]
    }

    /// The source of track `i` (its position in document order), for `mode`.
    pub fn source(&self, i: usize, mode: Mode) -> TrackSource {
        let ch = self.channel(i);
        let interpolation = ch.interpolation();
        TrackSource {
            name: self.names[i].clone(),
            index: i,
            animation: self.tracks[i].0,
            channel: ch.index(),
            interpolation,
            baked: mode != Mode::Keys && interpolation != Interpolation::Linear,
        }
    }

    /// The tracks' sources, in document order, for `mode`.
    pub fn sources(&self, mode: Mode) -> Vec<TrackSource> {
        (0..self.tracks.len())
            .map(|i| self.source(i, mode))
            .collect()
    }

    /// The source of the track named `name` (names are unique): a hash lookup.
    pub fn source_of(&self, name: &str, mode: Mode) -> Option<TrackSource> {
        self.by_name.get(name).map(|&i| self.source(i, mode))
    }

    /// A label for animation `a` and channel `c` in messages: `animation 0 ("Walk") channel 2`.
    pub fn channel_label(&self, a: usize, c: usize) -> String {
        format!("animation {} channel {c}", anim_label(&self.animations[a]))
    }

    /// The translation channel of track `i`'s node in its animation, if any (the first).
    fn translation(&self, i: usize) -> Option<&TranslationChannel> {
        let (a, _) = self.tracks[i];
        self.translations[i].map(|j| &self.animations[a].translations()[j])
    }

    /// The frames a baked track (`STEP`, `CUBICSPLINE`) is written on at `fps`, inclusive:
    /// those of its animation's span, or, when the span holds none, the frame nearest its first
    /// key (a pose).
    pub fn sampled_frames(&self, i: usize, fps: Fps) -> (i64, i64) {
        let (first, last) = self.frames(self.tracks[i].0, fps);
        let t0 = self.channel(i).times()[0];
        if first <= last {
            (first, last)
        } else if fps.in_range(t0) {
            let k = fps.nearest_frame(t0);
            (k, k)
        } else {
            (1, 0)
        }
    }

    /// Track `i`'s curve as its sampler defines it, for any time: a `STEP` frame holds the last
    /// key at or before it on the snapped key times, a `CUBICSPLINE` frame is Appendix C on the
    /// stored times; the translation channel likewise.
    pub fn sampler(&self, i: usize, fps: Fps) -> Sampler {
        Sampler {
            rotation: as_sampled(self.channel(i), fps),
            translation: self.translation(i).map(|tr| as_sampled(tr, fps)),
        }
    }

    /// The chosen animations' rotation channels as tracks at `fps` (see the module
    /// documentation). Findings (translations sampled, `STEP` keys written as keys, disagreeing
    /// `CUBICSPLINE` tangents) are the document's warnings. Errors: a `CUBICSPLINE` rotation
    /// whose 4-vector comes near zero ([`Mode::Frames`]).
    pub fn document(&self, fps: Fps, mode: Mode) -> InputResult<Document> {
        let src = self.asset.source();
        let mut tracks = Vec::with_capacity(self.tracks.len());
        let mut baked_frames = 0u64;
        // The reader's findings (channels ignored, rotations normalised) come first.
        let mut warnings = self.asset.warnings().to_vec();
        // The channels' findings, one line per kind (super::warnings).
        let mut found = ChannelWarnings::default();
        for anim in &self.animations {
            for (at, w) in anim.warnings() {
                found.add(at.clone(), w.clone());
            }
        }
        for i in 0..self.tracks.len() {
            let s = self.source(i, mode);
            let anim = &self.animations[s.animation];
            let ch = self.channel(i);
            let label = format!("{src}: {}", self.channel_label(s.animation, ch.index()));
            let origin = |keys: Vec<(usize, f32)>| KeyOrigin::Gltf {
                animation: anim.index(),
                channel: ch.index(),
                keys,
            };
            let translation = self.translation(i);
            let mut track = match (s.baked, ch.interpolation()) {
                (true, Interpolation::Step) => {
                    held(ch, translation, self.sampled_frames(i, fps), fps, origin)
                }
                (true, _) => {
                    // Its translations are sampled at its keys (interp samples them at every
                    // frame): no warning, as for a STEP channel.
                    check_cubic_norm(ch).map_err(|k| {
                        input_err!(
                            "{src}: animations[{}].channels[{}]: CUBICSPLINE keys {k} and {}: \
                             the rotation's 4-vector comes within 1e-9 of zero between them, \
                             where it has no direction (no rotation)",
                            anim.index(),
                            ch.index(),
                            k + 1
                        )
                    })?;
                    if mode == Mode::Sampled {
                        let mut t = keyed(
                            ch,
                            translation,
                            fps,
                            mode,
                            &label,
                            &mut ChannelWarnings::default(),
                            origin,
                        );
                        t.velocities = cubic_velocities(ch, None);
                        t
                    } else {
                        let (first, last) = self.sampled_frames(i, fps);
                        let count = u64::try_from(last - first + 1).unwrap_or(0);
                        baked_frames += count;
                        if baked_frames > MAX_BAKED_FRAMES {
                            return Err(input_err!(
                                "{src}: animations[{}].channels[{}]: CUBICSPLINE channels \
                                 baked at {fps} fps come to more than {MAX_BAKED_FRAMES} \
                                 frames (this one spans {count}); analyze, plot and reduce \
                                 evaluate them at every frame (interp streams them): choose \
                                 a lower rate or fewer animations",
                                anim.index(),
                                ch.index(),
                            ));
                        }
                        baked(ch, translation, (first, last), fps, origin)
                    }
                }
                _ => keyed(ch, translation, fps, mode, &label, &mut found, origin),
            };
            track.name = Some(s.name);
            tracks.push(track);
        }
        warnings.extend(found.into_lines());
        let doc = Document {
            rotation: Some(Repr::Quat),
            tracks,
            named_tracks: true,
            warnings,
            hierarchy: self.skeleton().map(std::sync::Arc::new),
            unit_meters: Some(1.0),
            ..Document::new(src.to_string())
        };
        if mode == Mode::Posed {
            return self.on_shared_times(doc, fps);
        }
        Ok(doc)
    }
}

/// `0` or `0 ("Walk")`.
fn anim_label(a: &Animation) -> String {
    match a.name() {
        Some(n) => format!("{} (\"{}\")", a.index(), shorten(n)),
        None => a.index().to_string(),
    }
}

/// The first frame `f` with `fps.time_of(f) >= t` (exactly, as [`RotationChannel::sample`]
/// compares times).
fn first_frame_at_or_after(fps: Fps, t: f64) -> i64 {
    let mut f = fps.nearest_frame(t);
    while fps.time_of(f) < t {
        f += 1;
    }
    while fps.time_of(f - 1) >= t {
        f -= 1;
    }
    f
}

/// A `STEP` channel over the frames `(first, last)` as keys that slerp reproduces at every one
/// of them: each held value on the first and the last frame that holds it (one key when one
/// frame does), a value no frame holds left out. The values are exactly the sampler's
/// ([`RotationChannel::sample`] on the snapped times), so `2n` keys at most for `n` glTF keys,
/// however many frames.
fn held(
    ch: &RotationChannel,
    translation: Option<&TranslationChannel>,
    (first, last): (i64, i64),
    fps: Fps,
    origin: impl FnOnce(Vec<(usize, f32)>) -> KeyOrigin,
) -> DocTrack {
    let snapped = as_sampled(ch, fps);
    let n = snapped.times.len();
    let mut frames: Vec<(i64, usize)> = Vec::new();
    if first > last {
        // Times beyond the frame numbers of the rate: the first key, which reading refuses.
        let keys = vec![Key {
            when: KeyTime::Seconds(snapped.times[0]),
            rot: snapped.sample(snapped.times[0]),
        }];
        return DocTrack::new(keys, origin(vec![(0, ch.times_f32()[0])]));
    }
    let mut from = first;
    for k in 0..n {
        let to = if k + 1 < n {
            (first_frame_at_or_after(fps, snapped.times[k + 1]) - 1).min(last)
        } else {
            last
        };
        if to >= from {
            frames.push((from, k));
            if to > from {
                frames.push((to, k));
            }
            from = to + 1;
        }
    }
    let stored = ch.times_f32();
    let at = frames.iter().map(|&(_, k)| (k, stored[k])).collect();
    let frames: Vec<i64> = frames.into_iter().map(|(f, _)| f).collect();
    at_frames(&snapped, translation, &frames, fps, origin(at))
}

/// The track of `rot`'s values at the frames `frames` of `fps`, each key at its frame's time,
/// with the translation channel's values there as its sampler gives them ([`as_sampled`]).
fn at_frames(
    rot: &RotationChannel,
    translation: Option<&TranslationChannel>,
    frames: &[i64],
    fps: Fps,
    origin: KeyOrigin,
) -> DocTrack {
    let keys = frames
        .iter()
        .map(|&f| {
            let t = fps.time_of(f);
            Key {
                when: KeyTime::Seconds(t),
                rot: rot.sample(t),
            }
        })
        .collect();
    let mut track = DocTrack::new(keys, origin);
    if let Some(tr) = translation.map(|tr| as_sampled(tr, fps)) {
        track.translations = frames
            .iter()
            .map(|&f| Some(tr.sample(fps.time_of(f))))
            .collect();
    }
    track
}

/// The channel's curve at every frame of `(first, last)` (none when `first > last`: times
/// beyond the rate's frame numbers, which reading refuses), with its translation channel's.
/// Each key is located at the sampler key at or before it.
fn baked(
    ch: &RotationChannel,
    translation: Option<&TranslationChannel>,
    (first, last): (i64, i64),
    fps: Fps,
    origin: impl FnOnce(Vec<(usize, f32)>) -> KeyOrigin,
) -> DocTrack {
    let frames: Vec<i64> = (first..=last).collect();
    let times = ch.times();
    let stored = ch.times_f32();
    let at = frames
        .iter()
        .map(|&k| {
            let i = times
                .partition_point(|&x| x <= fps.time_of(k))
                .saturating_sub(1);
            (i, stored[i])
        })
        .collect();
    at_frames(ch, translation, &frames, fps, origin(at))
}

/// The channel as its sampler is evaluated at `fps`'s frames: a `STEP` channel on its snapped
/// key times (a key within two float32 ulps of a frame holds from that frame), any other on its
/// stored times.
fn as_sampled<T: Copy>(ch: &Channel<T>, fps: Fps) -> Channel<T> {
    let mut out = ch.clone();
    if ch.interpolation() == Interpolation::Step {
        out.times = snapped_times(ch.times_f32(), fps);
    }
    out
}

/// Whether the `CUBICSPLINE` rotation's 4-vector stays away from zero: `Err(k)` names the first
/// segment `k → k + 1` along which it comes within about 1e-9 (relative to its size) of the
/// zero vector, where its normalisation has no direction. Each segment is a cubic Bézier in
/// 4-space (control points `p0`, `p0 + m0/3`, `p1 − m1/3`, `p1`); it is clear of zero when one
/// direction has a positive dot product with every control point (the convex hull leaves zero
/// out), else it is split in halves, down to 2⁻³² of the segment.
fn check_cubic_norm(ch: &RotationChannel) -> Result<(), usize> {
    let Some(tangents) = ch.tangents() else {
        return Ok(());
    };
    let (times, values) = (ch.times(), ch.values());
    for k in 0..values.len().saturating_sub(1) {
        let dt = times[k + 1] - times[k];
        let p0 = DVec4::from(values[k]);
        let p1 = DVec4::from(values[k + 1]);
        let m0 = dt * DVec4::from(tangents[k].1);
        let m1 = dt * DVec4::from(tangents[k + 1].0);
        let ctrl = [p0, p0 + m0 / 3.0, p1 - m1 / 3.0, p1];
        if !clear_of_zero(ctrl, 0) {
            return Err(k);
        }
    }
    Ok(())
}

/// Whether the cubic Bézier with control points `c` stays clear of the zero 4-vector (see
/// [`check_cubic_norm`]).
fn clear_of_zero(c: [DVec4; 4], depth: u32) -> bool {
    if c.iter().any(|p| !p.is_finite()) {
        return false;
    }
    let separated = |d: DVec4| d.length_squared() > 0.0 && c.iter().all(|p| p.dot(d) > 0.0);
    if [c[0], c[3], c[0] + c[3], c[1], c[2]]
        .into_iter()
        .any(separated)
    {
        return true;
    }
    if depth >= 32 {
        return false;
    }
    // de Casteljau at 1/2.
    let mid = |a: DVec4, b: DVec4| 0.5 * (a + b);
    let (a, b, c2) = (mid(c[0], c[1]), mid(c[1], c[2]), mid(c[2], c[3]));
    let (d, e) = (mid(a, b), mid(b, c2));
    let m = mid(d, e);
    clear_of_zero([c[0], a, d, m], depth + 1) && clear_of_zero([m, e, c2, c[3]], depth + 1)
}

/// A `CUBICSPLINE` channel's per-key angular velocities (the out-tangent's, the in-tangent's
/// at the last key); the first key where in and out disagree (a corner) goes to `corner`.
fn cubic_velocities(
    ch: &RotationChannel,
    mut corner: Option<&mut Option<usize>>,
) -> Vec<Option<DVec3>> {
    let Some(tangents) = ch.tangents() else {
        return Vec::new();
    };
    let n = ch.values().len();
    (0..n)
        .map(|k| {
            let v = ch.values()[k];
            let (a, b) = tangents[k];
            let out = tangent_velocity(v, b);
            let inw = tangent_velocity(v, a);
            let w = if k + 1 == n { inw } else { out };
            if let Some(c) = corner.as_deref_mut()
                && k > 0
                && k + 1 < n
                && c.is_none()
            {
                let scale = out.length().max(inw.length()).max(1.0);
                if (out - inw).length() > 1e-6 * scale {
                    *c = Some(k);
                }
            }
            Some(w)
        })
        .collect()
}

/// The channel's keys at their snapped times.
fn keyed(
    ch: &RotationChannel,
    translation: Option<&TranslationChannel>,
    fps: Fps,
    mode: Mode,
    label: &str,
    warnings: &mut ChannelWarnings,
    origin: impl FnOnce(Vec<(usize, f32)>) -> KeyOrigin,
) -> DocTrack {
    let times = snapped_times(ch.times_f32(), fps);
    let keys = times
        .iter()
        .zip(ch.values())
        .map(|(&t, &q)| Key {
            when: KeyTime::Seconds(t),
            rot: q.normalize(),
        })
        .collect();
    let stored = ch.times_f32().iter().copied().enumerate().collect();
    let mut track = DocTrack::new(keys, origin(stored));
    if mode == Mode::Keys && ch.interpolation() == Interpolation::Step {
        warnings.add(
            label.to_string(),
            "a STEP sampler's keys are written as keys; interpolating them does not hold each \
             key as the sampler does (interp bakes the step)"
                .into(),
        );
    }
    if mode == Mode::Keys && ch.tangents().is_some() {
        let mut corner = None;
        track.velocities = cubic_velocities(ch, Some(&mut corner));
        if let Some(k) = corner {
            warnings.add(
                label.to_string(),
                format!(
                    "CUBICSPLINE key {k}: the in- and out-tangents give different angular \
                     velocities (a corner); the key carries the out-tangent's"
                ),
            );
        }
    }
    if let Some(tr) = translation {
        if tr.times_f32() == ch.times_f32() {
            track.translations = tr.values().iter().map(|&p| Some(p)).collect();
        } else {
            // Posed: the track is played again at every channel's times (on_shared_times).
            if mode != Mode::Posed {
                warnings.add(
                    label.to_string(),
                    format!(
                        "translation channel {} has other key times than the rotation; its \
                         curve is sampled at the rotation's keys",
                        tr.index()
                    ),
                );
            }
            let mut snapped_tr = tr.clone();
            snapped_tr.times = snapped_times(tr.times_f32(), fps);
            track.translations = times.iter().map(|&t| Some(snapped_tr.sample(t))).collect();
        }
    }
    track
}

/// Each float32 time on its frame when within two ulps of it ([`snap_key_time`]), unless that
/// would not keep the times strictly increasing: of keys near one frame, the first takes it
/// and the later ones keep their stored times, and when a later one is stored before the
/// frame, the earlier ones keep theirs too (so keys 1 ulp apart just below a frame are both
/// kept as stored, in order).
pub(crate) fn snapped_times(times: &[f32], fps: Fps) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(times.len());
    for &t in times {
        let s = snap_key_time(t, fps);
        let s = if out.last().is_some_and(|&p| s <= p) {
            f64::from(t)
        } else {
            s
        };
        out.push(s);
        // Undo earlier snaps that the stored time comes before (stored times increase).
        let mut k = out.len() - 1;
        while k > 0 && out[k - 1] >= out[k] {
            let stored = f64::from(times[k - 1]);
            if out[k - 1] == stored {
                break; // cannot happen for strictly increasing stored times
            }
            out[k - 1] = stored;
            k -= 1;
        }
    }
    out
}

/// The world-frame angular velocity (rad/s) of the normalised curve `p(t)/|p(t)|` at a point
/// where `p = v` and `dp/dt = m`: `ω = 2·vec(m ⊗ v̄)/|v|²`.
///
/// Appendix C's Hermite segment from key `k` has `p'(t_k) = b_k` (the out-tangent; the
/// segment-duration factor of `m0 = (t_{k+1} − t_k)·b_k` cancels with `ds/dt`), and ends at
/// key `k + 1` with `p'(t_{k+1}) = a_{k+1}` (the in-tangent).
///
/// (Its example is a unit test: `tangent_velocity_example`.)
pub(crate) fn tangent_velocity(v: DQuat, m: DQuat) -> DVec3 {
    let (p, d) = (DVec4::from(v), DVec4::from(m));
    // m ⊗ conj(v), vector part (Hamilton product, x y z w).
    let (pv, dv) = (p.truncate(), d.truncate());
    let (pw, dw) = (p.w, d.w);
    let vec = -dv.cross(pv) + pw * dv - dw * pv;
    let vec = DVec3::new(vec.x, vec.y, vec.z);
    2.0 * vec / p.length_squared()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn clip(name: &str, animation: Option<&str>) -> InputResult<GltfClip> {
        let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
            .join("fixtures/gltf")
            .join(name);
        GltfClip::new(Asset::read_path(&path)?, animation)
    }

    #[test]
    fn names_for_one_and_several_animations() {
        let fps = Fps::new(30, 1).unwrap();
        let one = clip("minimal_linear.gltf", None).unwrap();
        let d = one.document(fps, Mode::Frames).unwrap();
        assert_eq!(d.tracks[0].name.as_deref(), Some("node0"));
        assert_eq!(d.tracks[0].translations.len(), 2);
        let all = clip("samplers.glb", None).unwrap();
        let names: Vec<_> = all
            .sources(Mode::Frames)
            .into_iter()
            .map(|s| (s.name, s.baked))
            .collect();
        assert!(names.contains(&("Mixed/step".to_string(), true)));
        assert!(names.contains(&("Mixed/byte".to_string(), false)));
        assert!(names.contains(&("Other/other".to_string(), false)));
        let mixed = clip("samplers.glb", Some("Mixed")).unwrap();
        assert_eq!(mixed.animations().len(), 1);
        assert_eq!(mixed.sources(Mode::Keys)[0].name, "step");
        assert_eq!(
            clip("samplers.glb", Some("1")).unwrap().animations()[0].label(),
            "Other"
        );
        let e = clip("samplers.glb", Some("Run")).unwrap_err();
        assert!(
            e.message().starts_with("animation Run: no such animation"),
            "{e}"
        );
        assert_eq!(
            e.parts().settings().collect::<Vec<_>>(),
            [inbetween::error::Setting::Animation]
        );
    }

    #[test]
    fn tangent_velocity_is_the_derivative_of_the_sampled_curve() {
        let c = clip("samplers.glb", Some("Mixed")).unwrap();
        let anim = &c.animations()[0];
        let ch = anim
            .rotations()
            .iter()
            .find(|r| r.interpolation() == Interpolation::CubicSpline)
            .unwrap();
        let b = ch.tangents().unwrap()[1].1;
        let t = ch.times()[1];
        let h = 1e-6;
        let q0 = DVec4::from(ch.sample(t));
        let q1 = DVec4::from(ch.sample(t + h));
        let q0 = DQuat::from_vec4(q0);
        let dq = DQuat::from_vec4((q1 - DVec4::from(q0)) / h);
        let want = tangent_velocity(q0, dq);
        let got = tangent_velocity(ch.values()[1], b);
        assert!((got - want).length() < 1e-4, "{got} vs {want}");
    }
}

#[cfg(test)]
mod examples {
    #[test]
    fn tangent_velocity_example() {
        use crate::gltf::document::tangent_velocity;
        use glam::{DQuat, DVec3};
        // q(t) = rotation about z by 2t: dq/dt at t = 0 is (0, 0, 1, 0) (x y z w).
        let w = tangent_velocity(DQuat::IDENTITY, DQuat::from_xyzw(0.0, 0.0, 1.0, 0.0));
        assert!((w - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-15);
    }
}
