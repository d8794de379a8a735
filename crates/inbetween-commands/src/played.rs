//! A track as its input's format plays it: `interp`'s curves, and `diff`'s B without
//! `--scheme` (docs/spec.md §1 *Options of `diff`*). Without `--scheme`, glTF `LINEAR` samplers
//! and USD's samples play by slerp (their translations by lerp), a glTF `STEP` or `CUBICSPLINE`
//! channel is its sampler's own curve (glTF 2.0 Appendix C), and every other format's keys or
//! frames play by bezier; with `--scheme`, the keys by that scheme (`interp` still plays a
//! `STEP` or `CUBICSPLINE` channel as its sampler).

use crate::args::SchemeArg;
use crate::settings::Curves;
use glam::{DQuat, DVec3};
use inbetween::bake::Sampled;
use inbetween::{Curve, CurveOptions, Error, Scheme};
use inbetween_io::Format;
use inbetween_io::gltf::document::{Mode, Sampler, TrackSource};

/// The scheme keys are played by: `given` (`--scheme`), else the one their document records
/// (`"scheme"` of a JSON document, which `reduce` writes), else the input format's own: glTF's
/// `LINEAR` samplers and USD's samples by slerp, every other format by bezier.
pub fn scheme(given: Option<SchemeArg>, input: Format, recorded: Option<Scheme>) -> Scheme {
    match (given, recorded, input) {
        (Some(s), _, _) => s.into(),
        (None, Some(s), _) => s,
        // glTF's LINEAR and USD's samples play by slerp.
        (None, None, Format::Gltf | Format::Usd) => Scheme::Slerp,
        (None, None, _) => Scheme::Bezier,
    }
}

/// A track's curve as its input plays it: built from its keys, or a glTF sampler's own curve
/// (`STEP`, `CUBICSPLINE`) with the frames `interp` writes it on.
pub enum TrackCurve {
    /// The curve of the track's keys under the input's curve options.
    Curve(Curve),
    /// The glTF channel's sampler (and its node's translation channel), and its frames at the
    /// input's rate, `(first, last)` inclusive.
    Sampled(Sampler, (i64, i64)),
}

impl TrackCurve {
    /// The rotation at `t` seconds.
    pub fn rotation(&self, t: f64) -> DQuat {
        match self {
            TrackCurve::Curve(c) => c.rotation(t),
            TrackCurve::Sampled(sampler, _) => sampler.at(t).0,
        }
    }

    /// The position at `t` seconds, where the track has positions.
    pub fn position(&self, t: f64) -> Option<DVec3> {
        match self {
            TrackCurve::Curve(c) => c.position(t),
            TrackCurve::Sampled(sampler, _) => sampler.at(t).1,
        }
    }
}

/// Each track's glTF source (read for `mode`), where the input is glTF.
pub fn sources(input: &Curves, mode: Mode) -> Vec<Option<TrackSource>> {
    let gltf = input.gltf.as_deref();
    input
        .tracks
        .iter()
        .map(|t| gltf.zip(t.name()).and_then(|(g, n)| g.source_of(n, mode)))
        .collect()
}

/// The frames at the input's rate of each track that is its glTF sampler's own curve (`STEP`,
/// `CUBICSPLINE`: its source is baked): its animation's span; `None` for every other track.
pub fn sampled_frames(input: &Curves, sources: &[Option<TrackSource>]) -> Vec<Option<(i64, i64)>> {
    sources
        .iter()
        .map(|s| {
            let s = s.as_ref().filter(|s| s.baked)?;
            input
                .gltf
                .as_deref()
                .map(|g| g.sampled_frames(s.index, input.fps))
        })
        .collect()
}

/// The options a glTF sampler's own curve is checked and written under: the input's, by slerp
/// (the slerp curve through its samples at its frames reproduces them).
pub fn sampled_options(opts: &CurveOptions) -> CurveOptions {
    CurveOptions {
        scheme: Scheme::Slerp,
        ..*opts
    }
}

/// Track `i`'s curve as its input plays it: with frames in `sampled` (see [`sampled_frames`]),
/// its glTF sampler (first checked as the slerp curve through its samples at those frames, as
/// `interp` writes it); otherwise the curve of its keys under the input's options. Input errors
/// found while building it (minaccel's grid cap) name the file.
pub fn curve(
    input: &Curves,
    i: usize,
    sources: &[Option<TrackSource>],
    sampled: &[Option<(i64, i64)>],
) -> Result<TrackCurve, Error> {
    let t = &input.tracks[i];
    let at_source = |e: inbetween::InputError| Error::Input(e.at(&input.doc.source));
    match (input.gltf.as_deref(), &sources[i], sampled[i]) {
        (Some(g), Some(s), Some(frames)) => {
            let sampler = g.sampler(s.index, input.fps);
            let check = Sampled {
                name: t.name(),
                frames,
                sample: &|time| sampler.at(time),
            };
            check
                .check(input.fps, &sampled_options(&input.opts))
                .map_err(at_source)?;
            Ok(TrackCurve::Sampled(sampler, frames))
        }
        _ => Curve::new(t, &input.opts)
            .map(TrackCurve::Curve)
            .map_err(at_source),
    }
}
