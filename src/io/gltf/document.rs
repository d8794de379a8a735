//! The animations of a glTF asset as a keyframe [`Document`]: one track per rotation channel.
//!
//! A [`GltfClip`] is an asset with the animations chosen (`--animation NAME|INDEX`, default
//! all); [`GltfClip::document`] turns their rotation channels into tracks at a frame rate:
//!
//! - Names: the target node's name (`node<index>` for a node without one) when one animation is
//!   chosen, else `animation/node` with the animation's name (its index when it has none). A
//!   name used twice gets `#<node index>` appended.
//! - Times: float32 seconds; a key within two float32 ulps of a frame time of the rate is on
//!   that frame ([`super::snap_key_time`]), so that keys exported at a rate come back exactly.
//! - `LINEAR`: the values are the track's keys, for the scheme of the command.
//! - `STEP` and `CUBICSPLINE` ([`Mode::Frames`], for `interp`): the sampler already defines
//!   its curve, so the track is that curve baked at every frame of the animation's span at the
//!   rate (a `STEP` frame holds the last key at or before it, on the snapped times; a
//!   `CUBICSPLINE` frame is Appendix C's evaluation, [`super::RotationChannel::sample`]). The
//!   track is marked [`TrackSource::baked`]: whatever scheme reproduces it at its frames, and
//!   `interp` uses slerp.
//! - [`Mode::Keys`] (for `convert`): every sampler's keys; a `CUBICSPLINE` key carries the
//!   angular velocity of its tangent ([`tangent_velocity`]) and a `STEP` channel is written as
//!   its keys, with a warning that the hold is not kept.
//! - Translations: the translation channel of the same node in the same animation, if any. When
//!   its times are the rotation keys' (as float32), its values are the keys' positions;
//!   otherwise it is sampled (by its own interpolation) at the rotation keys, with a warning.
//!   A baked track samples it at every frame.

use super::{Animation, Asset, Interpolation, RotationChannel, TranslationChannel, snap_key_time};
use crate::clock::Fps;
use crate::error::{InputResult, input_err, shorten};
use crate::io::document::{DocTrack, Document, Key, KeyOrigin, KeyTime};
use crate::rotation::Repr;
use glam::{DQuat, DVec3, DVec4};

/// What the tracks are for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Interpolation (`interp`, `analyze`, `plot`): `STEP` and `CUBICSPLINE` channels baked at
    /// every frame.
    Frames,
    /// The keys as stored (`convert`): `CUBICSPLINE` tangents as per-key angular velocities.
    Keys,
}

/// Where a track of the document comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackSource {
    /// The track's name.
    pub name: String,
    /// The animation's position in [`GltfClip::animations`].
    pub animation: usize,
    /// The channel's index in the animation's `channels`.
    pub channel: usize,
    /// The sampler's interpolation.
    pub interpolation: Interpolation,
    /// The track is the sampler's curve baked at every frame ([`Mode::Frames`] with `STEP` or
    /// `CUBICSPLINE`).
    pub baked: bool,
}

/// An asset with its chosen animations, read and checked.
#[derive(Debug)]
pub struct GltfClip {
    asset: Asset,
    animations: Vec<Animation>,
    names: Vec<String>,
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
                    return Err(input_err!(
                        "--animation {}: no such animation in {src} (it has {})",
                        shorten(want),
                        list.join(", ")
                    ));
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
        let mut names: Vec<String> = Vec::new();
        for a in &animations {
            for ch in a.rotations() {
                let base = if several {
                    format!("{}/{}", a.label(), ch.node_name())
                } else {
                    ch.node_name().to_string()
                };
                let name = if names.contains(&base) {
                    format!("{base}#{}", ch.node())
                } else {
                    base
                };
                names.push(name);
            }
        }
        Ok(GltfClip {
            asset,
            animations,
            names,
        })
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

    /// The tracks' sources, in document order, for `mode`.
    pub fn sources(&self, mode: Mode) -> Vec<TrackSource> {
        let mut out = Vec::new();
        let mut names = self.names.iter();
        for (a, anim) in self.animations.iter().enumerate() {
            for ch in anim.rotations() {
                let i = ch.interpolation();
                out.push(TrackSource {
                    name: names.next().expect("a name per channel").clone(),
                    animation: a,
                    channel: ch.index(),
                    interpolation: i,
                    baked: mode == Mode::Frames && i != Interpolation::Linear,
                });
            }
        }
        out
    }

    /// The source of the track named `name`.
    pub fn source_of(&self, name: &str, mode: Mode) -> Option<TrackSource> {
        self.sources(mode).into_iter().find(|s| s.name == name)
    }

    /// A label for animation `a` and channel `c` in messages: `animation 0 ("Walk") channel 2`.
    pub fn channel_label(&self, a: usize, c: usize) -> String {
        format!("animation {} channel {c}", anim_label(&self.animations[a]))
    }

    /// The chosen animations' rotation channels as tracks at `fps` (see the module
    /// documentation). Findings (translations sampled, `STEP` keys written as keys, disagreeing
    /// `CUBICSPLINE` tangents) are the document's warnings.
    pub fn document(&self, fps: Fps, mode: Mode) -> Document {
        let src = self.asset.source();
        let mut tracks = Vec::new();
        // The reader's findings (channels ignored, rotations normalised) come first.
        let mut warnings = self.asset.warnings().to_vec();
        let sources = self.sources(mode);
        let mut sources = sources.iter();
        for (a, anim) in self.animations.iter().enumerate() {
            warnings.extend(anim.warnings().iter().cloned());
            for ch in anim.rotations() {
                let s = sources.next().expect("a source per channel");
                let label = format!("{src}: {}", self.channel_label(a, ch.index()));
                let translation = anim.translations().iter().find(|t| t.node() == ch.node());
                let mut track = if s.baked {
                    baked(ch, translation, self.frames(a, fps), fps)
                } else {
                    keyed(ch, translation, fps, mode, &label, &mut warnings)
                };
                track.name = Some(s.name.clone());
                tracks.push(track);
            }
        }
        Document {
            source: src.to_string(),
            fps: None,
            rotation: Some(Repr::Quat),
            tracks,
            named_tracks: true,
            warnings,
            skeleton: None,
        }
    }
}

/// `0` or `0 ("Walk")`.
fn anim_label(a: &Animation) -> String {
    match a.name() {
        Some(n) => format!("{} (\"{}\")", a.index(), shorten(n)),
        None => a.index().to_string(),
    }
}

fn new_track(keys: Vec<Key>) -> DocTrack {
    DocTrack {
        name: None,
        keys,
        start_velocity: None,
        end_velocity: None,
        origin: KeyOrigin::Frames,
        euler: None,
        velocities: Vec::new(),
        tcb: Vec::new(),
        translations: Vec::new(),
    }
}

/// The channel's curve at every frame of `(first, last)` (a single key at frame `first`'s
/// nearest when the span holds no frame). `STEP` is evaluated on the snapped key times,
/// `CUBICSPLINE` exactly as Appendix C on the stored times.
fn baked(
    ch: &RotationChannel,
    translation: Option<&TranslationChannel>,
    (first, last): (i64, i64),
    fps: Fps,
) -> DocTrack {
    let mut snapped = ch.clone();
    snapped.times = snapped_times(ch.times_f32(), fps);
    let curve = match ch.interpolation() {
        Interpolation::Step => &snapped,
        _ => ch,
    };
    let frames: Vec<i64> = if first <= last {
        (first..=last).collect()
    } else {
        vec![fps.nearest_frame(ch.times()[0])]
    };
    let keys = frames
        .iter()
        .map(|&k| {
            let t = fps.time_of(k);
            Key {
                when: KeyTime::Seconds(t),
                rot: curve.sample(t),
            }
        })
        .collect();
    let mut track = new_track(keys);
    if let Some(tr) = translation {
        let mut snapped_tr = tr.clone();
        snapped_tr.times = snapped_times(tr.times_f32(), fps);
        let tr = match tr.interpolation() {
            Interpolation::Step => &snapped_tr,
            _ => tr,
        };
        track.translations = frames
            .iter()
            .map(|&k| Some(tr.sample(fps.time_of(k))))
            .collect();
    }
    track
}

/// The channel's keys at their snapped times.
fn keyed(
    ch: &RotationChannel,
    translation: Option<&TranslationChannel>,
    fps: Fps,
    mode: Mode,
    label: &str,
    warnings: &mut Vec<String>,
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
    let mut track = new_track(keys);
    if mode == Mode::Keys && ch.interpolation() == Interpolation::Step {
        warnings.push(format!(
            "{label}: a STEP sampler's keys are written as keys; interpolating them does not \
             hold each key as the sampler does (interp bakes the step)"
        ));
    }
    if let Some(tangents) = ch.tangents() {
        let n = ch.values().len();
        let mut corner = None;
        track.velocities = (0..n)
            .map(|k| {
                let v = ch.values()[k];
                let (a, b) = tangents[k];
                let out = tangent_velocity(v, b);
                let inw = tangent_velocity(v, a);
                let w = if k + 1 == n { inw } else { out };
                if k > 0 && k + 1 < n && corner.is_none() {
                    let scale = out.length().max(inw.length()).max(1.0);
                    if (out - inw).length() > 1e-6 * scale {
                        corner = Some(k);
                    }
                }
                Some(w)
            })
            .collect();
        if let Some(k) = corner {
            warnings.push(format!(
                "{label}: CUBICSPLINE key {k}: the in- and out-tangents give different angular \
                 velocities (a corner); the key carries the out-tangent's"
            ));
        }
    }
    if let Some(tr) = translation {
        if tr.times_f32() == ch.times_f32() {
            track.translations = tr.values().iter().map(|&p| Some(p)).collect();
        } else {
            warnings.push(format!(
                "{label}: translation channel {} has other key times than the rotation; its \
                 curve is sampled at the rotation's keys",
                tr.index()
            ));
            let mut snapped_tr = tr.clone();
            snapped_tr.times = snapped_times(tr.times_f32(), fps);
            track.translations = times.iter().map(|&t| Some(snapped_tr.sample(t))).collect();
        }
    }
    track
}

/// Each float32 time on its frame when within two ulps of it ([`snap_key_time`]), unless that
/// would not keep the times strictly increasing (then the time as stored).
fn snapped_times(times: &[f32], fps: Fps) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(times.len());
    for &t in times {
        let s = snap_key_time(t, fps);
        let s = if out.last().is_some_and(|&p| s <= p) {
            f64::from(t)
        } else {
            s
        };
        out.push(s);
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
/// ```
/// use glam::{DQuat, DVec3};
/// use inbetween::io::gltf::document::tangent_velocity;
/// // q(t) = rotation about z by 2t: dq/dt at t = 0 is (0, 0, 1, 0) (x y z w).
/// let w = tangent_velocity(DQuat::IDENTITY, DQuat::from_xyzw(0.0, 0.0, 1.0, 0.0));
/// assert!((w - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-15);
/// ```
pub fn tangent_velocity(v: DQuat, m: DQuat) -> DVec3 {
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
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fixtures/gltf")
            .join(name);
        GltfClip::new(Asset::read_path(&path)?, animation)
    }

    #[test]
    fn names_for_one_and_several_animations() {
        let fps = Fps::new(30, 1).unwrap();
        let one = clip("minimal_linear.gltf", None).unwrap();
        let d = one.document(fps, Mode::Frames);
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
            e.message().contains("--animation Run: no such animation"),
            "{e}"
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
