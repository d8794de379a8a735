//! Keyframe documents: tracks of keys, as read (with their source locations), and validated
//! tracks ready for interpolation (times in seconds, strictly increasing, at least two keys).

use crate::clock::Fps;
use crate::error::{InputResult, num};
use crate::input_err;
use crate::rotation::Repr;
use glam::{DQuat, DVec3};
use std::fmt;

/// Smallest accepted time between consecutive keys: closer keys would make the chord tangent
/// `log(q_{i+1} q_i⁻¹)/Δ` overflow (at denormal Δ) or meaningless; the frame tolerance is 1e-9 s.
pub const MIN_KEY_GAP: f64 = 1e-12;

/// Where a key came from, for error messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Loc {
    /// A CSV line (1-based; the header is line 1).
    Line(u64),
    /// A JSON key: `keys[i]`, or `tracks[t].keys[i]`.
    Json { track: Option<usize>, key: usize },
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Loc::Line(l) => write!(f, "{l}"),
            Loc::Json {
                track: Some(t),
                key,
            } => write!(f, " tracks[{t}].keys[{key}]"),
            Loc::Json { track: None, key } => write!(f, " keys[{key}]"),
        }
    }
}

/// Formats `source:line` (CSV) or `source: keys[3]` (JSON).
pub fn at(source: &str, loc: Loc) -> String {
    format!("{source}:{loc}")
}

/// When a key is: seconds, or a frame number at the document's rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KeyTime {
    Seconds(f64),
    Frame(f64),
}

/// One keyframe as read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Key {
    pub when: KeyTime,
    pub rot: DQuat,
    pub loc: Loc,
}

/// One track as read.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    pub name: Option<String>,
    pub keys: Vec<Key>,
    /// World-frame angular velocity at the first key, rad/s.
    pub start_velocity: Option<DVec3>,
    /// World-frame angular velocity at the last key, rad/s.
    pub end_velocity: Option<DVec3>,
}

/// A keyframe document as read from CSV or JSON.
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// File name for messages (`<stdin>` for standard input).
    pub source: String,
    /// The rate the document's own `frame` values are numbered at, if it says.
    pub fps: Option<Fps>,
    /// The representation the input used (the first key's, for JSON).
    pub rotation: Option<Repr>,
    pub tracks: Vec<Track>,
    /// The input named its tracks (CSV `track` column, JSON `tracks`).
    pub named_tracks: bool,
    /// Non-fatal findings, already located (e.g. a quaternion norm off 1).
    pub warnings: Vec<String>,
}

/// A track ready for interpolation.
#[derive(Debug, Clone, PartialEq)]
pub struct TimedTrack {
    pub name: Option<String>,
    /// Key times in seconds, finite and strictly increasing; at least two.
    pub times: Vec<f64>,
    /// Unit quaternions, signs as read.
    pub quats: Vec<DQuat>,
    pub start_velocity: Option<DVec3>,
    pub end_velocity: Option<DVec3>,
}

impl Document {
    /// Key times in seconds for one track, frames read at `frame_fps`; validated finite and
    /// strictly increasing, with at least `min_keys` keys.
    pub fn track_times(
        &self,
        track: &Track,
        frame_fps: Fps,
        min_keys: usize,
    ) -> InputResult<Vec<f64>> {
        let label = match &track.name {
            Some(n) => format!("{}: track \"{n}\"", self.source),
            None => self.source.clone(),
        };
        if track.keys.len() < min_keys {
            return Err(input_err!(
                "{label}: expected at least {min_keys} keys, found {}",
                track.keys.len()
            ));
        }
        let mut times = Vec::with_capacity(track.keys.len());
        for (i, key) in track.keys.iter().enumerate() {
            let t = match key.when {
                KeyTime::Seconds(t) => t,
                KeyTime::Frame(f) => frame_fps.frame_to_time(f),
            };
            let (field, raw) = match key.when {
                KeyTime::Seconds(t) => ("time", t),
                KeyTime::Frame(f) => ("frame", f),
            };
            if !t.is_finite() {
                return Err(input_err!("expected a finite number, found {raw}")
                    .at(format!("{}: {field}", at(&self.source, key.loc))));
            }
            if i > 0 && t <= times[i - 1] {
                let prev = times[i - 1];
                return Err(input_err!(
                    "expected times strictly increasing within a track, found {} s after {} s",
                    num(t),
                    num(prev)
                )
                .at(format!("{}: {field}", at(&self.source, key.loc))));
            }
            if i > 0 && t - times[i - 1] < MIN_KEY_GAP {
                let prev = times[i - 1];
                return Err(input_err!(
                    "expected keys at least 1e-12 s apart, found {} s only {:e} s after {} s \
                     (merge the two keys)",
                    num(t),
                    t - prev,
                    num(prev)
                )
                .at(format!("{}: {field}", at(&self.source, key.loc))));
            }
            times.push(t);
        }
        Ok(times)
    }

    /// Validated tracks for interpolation: `frame` keys at `frame_fps`, at least two keys.
    pub fn timed_tracks(&self, frame_fps: Fps) -> InputResult<Vec<TimedTrack>> {
        if self.tracks.is_empty() {
            return Err(input_err!(
                "{}: expected at least one track, found none",
                self.source
            ));
        }
        self.tracks
            .iter()
            .map(|track| {
                Ok(TimedTrack {
                    name: track.name.clone(),
                    times: self.track_times(track, frame_fps, 2)?,
                    quats: track.keys.iter().map(|k| k.rot).collect(),
                    start_velocity: track.start_velocity,
                    end_velocity: track.end_velocity,
                })
            })
            .collect()
    }
}
