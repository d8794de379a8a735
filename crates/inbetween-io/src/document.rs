//! Keyframe documents as read: tracks of keys with their source locations, before validation.
//!
//! The readers ([`super::read`]) build a [`Document`]; [`Document::tracks`] validates it into
//! [`Track`]s by the one time rule of [`inbetween::track`], with messages that name the file, the
//! line or key, and the field.

use glam::{DQuat, DVec3};
use inbetween::Tcb;
use inbetween::clock::Fps;
use inbetween::error::InputResult;
use inbetween::rotation::Repr;
use inbetween::track::{Track, TrackError, check_times};
use std::fmt;

/// Where a key came from, for error messages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Loc {
    /// A CSV line (1-based; the header is line 1).
    Line(u64),
    /// A JSON key: `keys[i]`, or `tracks[t].keys[i]` (`frames` for interp's output).
    Json {
        /// The track's index in `tracks`, when the document has `tracks`.
        track: Option<usize>,
        /// The key's index in its `keys`.
        key: usize,
        /// The list is called `frames` (interp's output) rather than `keys`.
        frames: bool,
    },
    /// A motion row of a BVH file: frame `i` (0-based).
    Frame(usize),
    /// A key of a glTF rotation channel: `animations[a].channels[c]`, its key index in the
    /// sampler and its time as stored (float32 seconds).
    Gltf {
        /// The animation's index in the asset's `animations`.
        animation: usize,
        /// The channel's index in the animation's `channels`.
        channel: usize,
        /// The key's index in the sampler's input.
        key: usize,
        /// The key's time as stored (`None` when not known).
        time: Option<f32>,
    },
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Loc::Line(l) => write!(f, "{l}"),
            Loc::Frame(i) => write!(f, " frame {i}"),
            Loc::Gltf {
                animation,
                channel,
                key,
                time,
            } => {
                write!(f, " animations[{animation}].channels[{channel}] key {key}")?;
                match time {
                    Some(t) => write!(f, " ({t} s)"),
                    None => Ok(()),
                }
            }
            Loc::Json {
                track: Some(t),
                key,
                frames,
            } => write!(f, " tracks[{t}].{}[{key}]", list_name(*frames)),
            Loc::Json {
                track: None,
                key,
                frames,
            } => write!(f, " {}[{key}]", list_name(*frames)),
        }
    }
}

/// `frames` or `keys`: the name of a JSON list of keys.
fn list_name(frames: bool) -> &'static str {
    if frames { "frames" } else { "keys" }
}

/// Formats `source:line` (CSV) or `source: keys[3]` (JSON).
pub fn at(source: &str, loc: Loc) -> String {
    format!("{source}:{loc}")
}

pub use inbetween::error::{MAX_QUOTED_CHARS, shorten};

/// `source` or `source: track "name"` (the name cut by [`shorten`]), for messages about a whole
/// track.
pub fn track_label(source: &str, name: Option<&str>) -> String {
    match name {
        Some(n) => format!("{source}: track \"{}\"", shorten(n)),
        None => source.to_string(),
    }
}

/// When a key is: seconds, or a frame number at the document's rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KeyTime {
    /// A time in seconds (`time`).
    Seconds(f64),
    /// A frame number at the document's rate (`frame`), possibly fractional.
    Frame(f64),
}

/// One keyframe as read (where it was read is its track's [`KeyOrigin`], kept apart so that a
/// key takes 48 bytes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Key {
    /// When the key is.
    pub when: KeyTime,
    /// Its rotation, a unit quaternion (converted from the input representation).
    pub rot: DQuat,
}

/// Where a track's keys were read, for messages: see [`DocTrack::loc`].
#[derive(Debug, Clone, PartialEq)]
pub enum KeyOrigin {
    /// CSV: the line of each key, in key order.
    Lines(Vec<u64>),
    /// BVH: key `i` is motion row (frame) `i`.
    Frames,
    /// JSON: key `i` is `keys[i]`, or `tracks[t].keys[i]` for `Some(t)` (`frames` for
    /// interp's output).
    Json {
        /// The track's index in `tracks`, when the document has `tracks`.
        track: Option<usize>,
        /// The list is called `frames`.
        frames: bool,
    },
    /// glTF: the channel `animations[animation].channels[channel]`, and for each key of the
    /// track the sampler's key it comes from (its index and stored time; a `STEP` channel's two
    /// keys per held value come from one).
    Gltf {
        /// The animation's index in the asset's `animations`.
        animation: usize,
        /// The channel's index in the animation's `channels`.
        channel: usize,
        /// Per key of the track: the sampler key's index and stored time.
        keys: Vec<(usize, f32)>,
    },
}

/// A track's keys as Euler angles: the sequence, and each key's triple as written (radians).
pub(crate) type EulerKeys = (inbetween::rotation::EulerSeq, Vec<DVec3>);

/// One track as read.
#[derive(Debug, Clone, PartialEq)]
pub struct DocTrack {
    /// The track's name, if the input gave one.
    pub name: Option<String>,
    /// Its keys, in input order.
    pub keys: Vec<Key>,
    /// World-frame angular velocity at the first key, rad/s.
    pub start_velocity: Option<DVec3>,
    /// World-frame angular velocity at the last key, rad/s.
    pub end_velocity: Option<DVec3>,
    /// Where its keys were read.
    pub origin: KeyOrigin,
    /// The keys' Euler angles as written (radians, not wrapped), when every key of the track was
    /// given as Euler angles in one sequence: `--path euler` and continuous Euler output start
    /// from them ([`Track::with_euler_angles`]).
    pub euler: Option<EulerKeys>,
    /// Each key's own angular velocity (rad/s, world frame), when any key has one (empty when
    /// none has).
    pub velocities: Vec<Option<DVec3>>,
    /// Each key's own tension, continuity and bias (each optional: a missing one takes the
    /// command line's), when any key has one (empty when none has).
    pub tcb: Vec<[Option<f64>; 3]>,
    /// Each key's position (CSV `tx,ty,tz`, JSON `translation`, BVH position channels), when any
    /// key has one (empty when none has); a track has them on every key or on none.
    pub translations: Vec<Option<DVec3>>,
}

impl DocTrack {
    /// A track of `keys` from `origin`: unnamed, no velocities, TCB values, Euler angles or
    /// translations (a reader fills in what its format has).
    pub fn new(keys: Vec<Key>, origin: KeyOrigin) -> DocTrack {
        DocTrack {
            name: None,
            keys,
            start_velocity: None,
            end_velocity: None,
            origin,
            euler: None,
            velocities: Vec::new(),
            tcb: Vec::new(),
            translations: Vec::new(),
        }
    }

    /// Records the just-pushed key's own velocity and TCB values (the lists stay empty until a
    /// key has one, then are filled for every key).
    pub(crate) fn push_shape(&mut self, velocity: Option<DVec3>, tcb: [Option<f64>; 3]) {
        push_shape(
            &mut self.velocities,
            &mut self.tcb,
            self.keys.len(),
            velocity,
            tcb,
        );
    }

    /// Records the just-pushed key's position (the list stays empty until a key has one).
    pub fn push_translation(&mut self, p: Option<DVec3>) {
        push_sparse(&mut self.translations, self.keys.len(), p);
    }

    /// Each key's position for a skeleton's output (USD, FBX), where the track has any: a key
    /// without one holds `rest`, its joint's rest translation.
    pub fn positions_or(&self, rest: Option<DVec3>) -> Option<Vec<DVec3>> {
        self.translations.iter().any(Option::is_some).then(|| {
            (0..self.keys.len())
                .map(|k| {
                    self.translations
                        .get(k)
                        .copied()
                        .flatten()
                        .or(rest)
                        .unwrap_or_default()
                })
                .collect()
        })
    }

    /// Where key `i` was read.
    pub fn loc(&self, i: usize) -> Loc {
        match &self.origin {
            KeyOrigin::Lines(lines) => Loc::Line(lines[i]),
            KeyOrigin::Frames => Loc::Frame(i),
            KeyOrigin::Json { track, frames } => Loc::Json {
                track: *track,
                key: i,
                frames: *frames,
            },
            KeyOrigin::Gltf {
                animation,
                channel,
                keys,
            } => {
                let (key, time) = keys.get(i).map_or((i, None), |&(k, t)| (k, Some(t)));
                Loc::Gltf {
                    animation: *animation,
                    channel: *channel,
                    key,
                    time,
                }
            }
        }
    }
}

/// Records key `n − 1`'s own velocity and TCB values in lists that stay empty until a key has
/// one ([`DocTrack::velocities`], [`DocTrack::tcb`]).
pub(crate) fn push_shape(
    velocities: &mut Vec<Option<DVec3>>,
    tcbs: &mut Vec<[Option<f64>; 3]>,
    n: usize,
    velocity: Option<DVec3>,
    tcb: [Option<f64>; 3],
) {
    if velocity.is_some() || !velocities.is_empty() {
        velocities.resize(n - 1, None);
        velocities.push(velocity);
    }
    if tcb.iter().any(Option::is_some) || !tcbs.is_empty() {
        tcbs.resize(n - 1, [None; 3]);
        tcbs.push(tcb);
    }
}

/// Records key `n − 1`'s optional value in a list that stays empty until a key has one.
pub(crate) fn push_sparse(list: &mut Vec<Option<DVec3>>, n: usize, value: Option<DVec3>) {
    if value.is_some() || !list.is_empty() {
        list.resize(n - 1, None);
        list.push(value);
    }
}

/// A keyframe document as read from CSV or JSON.
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// File name for messages (`<stdin>` for standard input).
    pub source: String,
    /// The rate the document's own `frame` values are numbered at: its declared `fps`, else the
    /// one `--key-fps` gives ([`crate::ReadOptions::key_fps`]), if any.
    pub fps: Option<Fps>,
    /// The representation the input used (the first key's, for JSON).
    pub rotation: Option<Repr>,
    /// The scheme the keys were made for (a JSON document's `"scheme"`, which `reduce`
    /// writes): how they are played unless `--scheme` says otherwise.
    pub scheme: Option<inbetween::Scheme>,
    /// The tracks, in input order.
    pub tracks: Vec<DocTrack>,
    /// The input named its tracks (CSV `track` column, JSON `tracks`).
    pub named_tracks: bool,
    /// Non-fatal findings, already located (e.g. a quaternion norm off 1).
    pub warnings: Vec<String>,
    /// The skeleton of a BVH input: what BVH output is written against.
    pub skeleton: Option<std::sync::Arc<crate::clip::Clip>>,
    /// The joints' hierarchy and rest pose, for world-space measures (a BVH clip's, a glTF
    /// animation's nodes): the tracks are its tracks, by index.
    pub hierarchy: Option<std::sync::Arc<inbetween::skeleton::Skeleton>>,
    /// The length unit in metres, where the input declares one (glTF: 1; FBX: its scene's
    /// unit); what USD output writes as `metersPerUnit`.
    pub unit_meters: Option<f64>,
    /// Whether the input declares Z up (FBX `UpAxis`, USD `upAxis`); `Some(false)` Y up, `None`
    /// no declaration (BVH, glTF and keys are Y up by convention); what USD output writes as
    /// `upAxis`.
    pub z_up: Option<bool>,
}

impl Document {
    /// An empty document from `source`: no rate, representation, scheme or tracks, unnamed
    /// tracks, no warnings, skeleton, hierarchy, unit or up axis; the readers fill in what
    /// their format says (`Document { fps, tracks, ..Document::new(source) }`).
    pub fn new(source: impl Into<String>) -> Document {
        Document {
            source: source.into(),
            fps: None,
            rotation: None,
            scheme: None,
            tracks: Vec::new(),
            named_tracks: false,
            warnings: Vec::new(),
            skeleton: None,
            hierarchy: None,
            unit_meters: None,
            z_up: None,
        }
    }

    /// The skeleton a skeleton's animation (`format`: "FBX", "USD") is written on, one joint
    /// per track: an input error naming the inputs that carry one when the document has none,
    /// an internal error when its tracks are not the skeleton's.
    pub fn output_skeleton(
        &self,
        format: &str,
    ) -> Result<&inbetween::skeleton::Skeleton, inbetween::Error> {
        let Some(skeleton) = self.hierarchy.as_deref() else {
            return Err(inbetween::InputError::new(format!(
                "{}: {format} output is a skeleton's animation; this input has no skeleton (BVH, \
                 glTF, FBX or USD input has one)",
                self.source
            ))
            .into());
        };
        if self.tracks.len() != skeleton.track_count() {
            return Err(inbetween::Error::Internal(format!(
                "internal error: {} tracks on a skeleton of {}",
                self.tracks.len(),
                skeleton.track_count()
            )));
        }
        Ok(skeleton)
    }

    /// Key times in seconds for one track, frames read at `frame_fps`; validated by
    /// [`check_times`] (finite, strictly increasing, at least 1e-12 s apart), with at least
    /// `min_keys` keys. Errors name the track, the line or key and the field.
    pub fn track_times(
        &self,
        track: &DocTrack,
        frame_fps: Fps,
        min_keys: usize,
    ) -> InputResult<Vec<f64>> {
        if track.keys.len() < min_keys {
            let label = track_label(&self.source, track.name.as_deref());
            return Err(input_err!(
                "{label}: expected at least {min_keys} keys, found {}",
                track.keys.len()
            ));
        }
        let times: Vec<f64> = track
            .keys
            .iter()
            .map(|key| match key.when {
                KeyTime::Seconds(t) => t,
                KeyTime::Frame(f) => frame_fps.frame_to_time(f),
            })
            .collect();
        check_times(&times).map_err(|e| {
            let i = e.index().unwrap_or(0);
            let key = &track.keys[i];
            let loc = track.loc(i);
            let (field, raw) = match key.when {
                KeyTime::Seconds(t) => ("time", t),
                KeyTime::Frame(f) => ("frame", f),
            };
            // A non-finite time is reported as written (a frame number, not its seconds).
            let e = match e {
                TrackError::NonFiniteTime { index, .. } => {
                    TrackError::NonFiniteTime { index, time: raw }
                }
                e => e,
            };
            // A glTF key is named by its channel, index and stored time (no field).
            match loc {
                Loc::Gltf { .. } => input_err!("{e}").at(at(&self.source, loc)),
                _ => input_err!("{e}").at(format!("{}: {field}", at(&self.source, loc))),
            }
        })?;
        Ok(times)
    }

    /// Validated tracks for interpolation: `frame` keys read at `frame_fps`, at least one key
    /// per track, at least one track; keys' own TCB values complete with zeros.
    pub fn tracks(&self, frame_fps: Fps) -> InputResult<Vec<Track>> {
        self.tracks_shaped(frame_fps, Tcb::ZERO)
    }

    /// [`Document::tracks`], a key's missing tension, continuity or bias (beside one it has)
    /// taken from `defaults` (the command line's).
    pub fn tracks_shaped(&self, frame_fps: Fps, defaults: Tcb) -> InputResult<Vec<Track>> {
        if self.tracks.is_empty() {
            return Err(input_err!(
                "{}: expected at least one track, found none",
                self.source
            ));
        }
        self.tracks
            .iter()
            .map(|track| {
                let times = self.track_times(track, frame_fps, 1)?;
                let quats: Vec<DQuat> = track.keys.iter().map(|k| k.rot).collect();
                let located = |e: TrackError| {
                    let loc = e
                        .index()
                        .map_or(self.source.clone(), |i| at(&self.source, track.loc(i)));
                    input_err!("{e}").at(loc)
                };
                let t = match times[..] {
                    [time] => Track::constant(time, quats[0]),
                    _ => Track::new(times, quats),
                }
                .and_then(|t| t.with_end_velocities(track.start_velocity, track.end_velocity))
                .map_err(located)?;
                let t = if track.velocities.is_empty() {
                    t
                } else {
                    let mut v = track.velocities.clone();
                    v.resize(track.keys.len(), None);
                    t.with_key_velocities(v).map_err(located)?
                };
                let t = if track.translations.is_empty() {
                    t
                } else {
                    let mut v = track.translations.clone();
                    v.resize(track.keys.len(), None);
                    if let Some(i) = v.iter().position(Option::is_none) {
                        return Err(input_err!(
                            "expected a translation on every key of the track or on none, \
                             found none on this key"
                        )
                        .at(format!("{}: translation", at(&self.source, track.loc(i)))));
                    }
                    t.with_translations(v.into_iter().flatten().collect())
                        .map_err(located)?
                };
                let t = if track.tcb.is_empty() {
                    t
                } else {
                    let mut v: Vec<Option<Tcb>> = track
                        .tcb
                        .iter()
                        .map(|k| {
                            k.iter().any(Option::is_some).then(|| Tcb {
                                tension: k[0].unwrap_or(defaults.tension),
                                continuity: k[1].unwrap_or(defaults.continuity),
                                bias: k[2].unwrap_or(defaults.bias),
                            })
                        })
                        .collect();
                    v.resize(track.keys.len(), None);
                    t.with_key_tcb(v).map_err(located)?
                };
                // Angles beyond ±1e15 rad (possible in degrees, which are reduced exactly)
                // are not kept: such a track has no Euler path.
                let t = match &track.euler {
                    Some((seq, angles)) => {
                        let kept = t.clone().with_euler_angles(*seq, angles.clone());
                        kept.unwrap_or(t)
                    }
                    None => t,
                };
                Ok(match &track.name {
                    Some(n) => t.with_name(n.clone()),
                    None => t,
                })
            })
            .collect()
    }
}
