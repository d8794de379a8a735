//! `inbetween interp`: keyframes in, every in-between frame out.
//!
//! - `interp/bvh.rs`: the lean path of a BVH file, read into its motion values and baked one joint at
//!   a time.

mod bvh;

use super::settings::{output_format, read_curves_in, tracks_take_translations};
use crate::args::{CurveArgs, InterpArgs, SpanArg};
use crate::events::Events;
use crate::output::{Output, WriteBehind};
use crate::played::{self, TrackCurve};
use glam::{DQuat, DVec3};
use inbetween::bake::{Sampled, bake_sampled};
use inbetween::error::num;
use inbetween::{BakeOptions, Error, Fps, FrameSink, InputError, bake_over};
use inbetween_io::OutputFormat;
use inbetween_io::bvh::frames::BvhFrames;
use inbetween_io::fbx::frames::FbxFrames;
use inbetween_io::gltf::document::Mode;
use inbetween_io::gltf::frames::{GltfFrames, check_grid, edges as gltf_edges};
use inbetween_io::usd::frames::UsdFrames;
use inbetween_io::usd::write::Stage;
use inbetween_io::write::{EulerMode, FrameWriter, NpyWriter, NpzShape, NpzWriter};
use std::io::Read;

/// Runs `interp`: every track's curve baked at the output rate into the chosen writer.
///
/// Everything the input can get wrong is found before the first byte is written: the tracks,
/// the frame count (`--max-frames`), and every curve (minaccel's grid cap), so that only I/O can
/// fail once output has started.
pub fn run(args: &InterpArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    crate::settings::check_output_name(&args.output)?;
    if let Some(done) = bvh::lean(args, warn) {
        return done;
    }
    if crate::amass::writes_amass(args) {
        return crate::amass::interp(args, stdin);
    }
    // --skeleton: its Frame Time is the rate where --fps gives none.
    let template = args
        .skeleton
        .as_deref()
        .map(super::skeleton::read)
        .transpose()?;
    let with_rate;
    let curve_args = match &template {
        Some(t) if args.curve.fps.is_none() => {
            with_rate = CurveArgs {
                fps: Some(t.fps()),
                ..args.curve.clone()
            };
            &with_rate
        }
        _ => &args.curve,
    };
    let input = read_curves_in(
        (Mode::Sampled, tracks_take_translations(&args.output)),
        &args.input,
        curve_args,
        // The curves' scheme: `--scheme`, else the input format's own (each glTF sampler as glTF
        // plays it, LINEAR keys by slerp; STEP and CUBICSPLINE channels are their samplers
        // whatever the scheme), else bezier.
        &|f, recorded| played::scheme(args.scheme, f, recorded),
        stdin,
        warn,
    )?;
    let (doc, tracks, fps) = (&input.doc, &input.tracks, input.fps);
    // A glTF input: each track's source (a hash of the unique track names). A STEP or
    // CUBICSPLINE channel is its sampler's curve, sampled at every frame of its animation's
    // span while it is written (never baked into memory): its span is those frames.
    let gltf = input.gltf.as_deref();
    let sources = played::sources(&input, Mode::Sampled);
    let sampled = played::sampled_frames(&input, &sources);
    let own_span = |i: usize| match sampled[i] {
        Some((a, b)) => (fps.time_of(a), fps.time_of(b)),
        None => tracks[i].span(),
    };
    // The span each track is written over: the clip (the union of the tracks' key ranges, ends
    // held), or its own.
    let clip = (0..tracks.len()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
        (lo.min(own_span(i).0), hi.max(own_span(i).1))
    });
    // --skeleton writes BVH unless another format is asked for.
    let format = match (&template, &args.output.output_format, &args.output.output) {
        (Some(_), None, None) => OutputFormat::Bvh,
        _ => output_format(&args.output, input.format),
    };
    if template.is_some() {
        super::skeleton::check_output(format)?;
    }
    // A glTF input: each track's animation, whose span (every sampler's keys) the clip covers;
    // glTF output writes each animation over its own span.
    let clip = match gltf {
        Some(g) => (0..g.animations().len())
            .map(|a| g.span(a, fps))
            .fold(clip, |(lo, hi), (a, b)| (lo.min(a), hi.max(b))),
        None => clip,
    };
    let to_gltf = matches!(format, OutputFormat::Gltf(_));
    let span = |i: usize| {
        let animation = sources[i].as_ref().map(|s| s.animation);
        match (args.span, animation.filter(|_| to_gltf)) {
            (_, Some(a)) => gltf.map_or(clip, |g| g.span(a, fps)),
            (SpanArg::Clip, None) => clip,
            (SpanArg::Track, None) => own_span(i),
        }
    };
    // glTF output samples the ends of each animation's span, frames or not: no key is missed.
    for (i, t) in tracks.iter().enumerate().filter(|_| !to_gltf) {
        near_misses(&doc.source, t.name(), own_span(i), span(i), fps, warn);
    }
    let rows: u64 = (0..tracks.len())
        .map(|i| fps.frame_count(span(i).0, span(i).1))
        .fold(0, u64::saturating_add);
    crate::record::note(|s| {
        s.frames = Some(rows);
        s.tracks = Some(tracks.len());
    });
    if rows > args.max_frames {
        return Err(InputError::new(format!(
            "{}: interp would write {rows} frames at {fps} fps, more than --max-frames {}",
            doc.source, args.max_frames
        ))
        .into());
    }
    // Input errors found while building a curve (minaccel's grid cap) name the file too.
    // A glTF STEP or CUBICSPLINE channel is its sampler, written as the slerp curve through its
    // samples at the frames, which reproduces them.
    let baked = played::sampled_options(&input.opts);
    let curves = (0..tracks.len())
        .map(|i| played::curve(&input, i, &sources, &sampled))
        .collect::<Result<Vec<_>, Error>>()?;
    let bake_opts = BakeOptions {
        velocity: args.velocity,
        // Two generating threads pay only when the output is cheap to write (npy); with text,
        // formatting already uses the second core (measured: docs/performance.md).
        parallel: matches!(format, OutputFormat::Npy | OutputFormat::Npz),
    };
    let style = super::settings::style(&args.input, &args.output);
    let track_column = doc.named_tracks || tracks.len() > 1;
    let positions = tracks.iter().any(|t| t.translations().is_some());
    // An input with a skeleton gives the npz its tracks' tree (parents and rest offsets).
    let tree = doc
        .hierarchy
        .as_deref()
        .and_then(|s| inbetween_io::write::npz::Tree::of(s, tracks.len()));
    let npz = match format {
        OutputFormat::Npz => Some(npz_shape(
            args,
            tracks,
            &style,
            span,
            fps,
            (positions, tree.is_some()),
            &doc.source,
        )?),
        _ => None,
    };
    let skeleton = match format {
        OutputFormat::Bvh => {
            let Some(skeleton) = template.clone().or_else(|| doc.skeleton.clone()) else {
                return Err(InputError::new(format!(
                    "{}: BVH output is written on a skeleton: a BVH input's, or --skeleton \
                     clip.bvh's for keys of it (as reduce and convert write them); or write csv \
                     or json",
                    doc.source
                ))
                .into());
            };
            super::settings::check_carries(args, format)?;
            Some(skeleton)
        }
        _ => None,
    };
    // FBX output on --skeleton: the template's skeleton, its joints' channel orders.
    let on_template = template.clone().filter(|_| format == OutputFormat::Fbx);
    let usd = match format {
        OutputFormat::Fbx if on_template.is_some() => {
            super::settings::check_carries(args, format)?;
            None
        }
        OutputFormat::Usda | OutputFormat::Fbx => {
            Some(super::skeleton::usd_output(args, doc, format)?)
        }
        _ => None,
    };
    // The order the tracks are written in: the skeleton's joints' for BVH output, and for FBX
    // output on --skeleton.
    let order: Vec<usize> = match skeleton.as_ref().or(on_template.as_ref()) {
        Some(s) => {
            let named = args.skeleton.as_deref().map(|p| p.display().to_string());
            let label = named.as_deref().unwrap_or(&doc.source);
            let named: Vec<_> = tracks
                .iter()
                .map(|t| (t.name(), t.translations().is_some()))
                .collect();
            super::skeleton::joint_order(s, &named, &doc.source, label)?
        }
        None => (0..tracks.len()).collect(),
    };
    let gltf_out = match format {
        OutputFormat::Gltf(container) => {
            let Some(clip) = input.gltf.clone() else {
                return Err(InputError::new(format!(
                    "{}: glTF output is written into a glTF input's asset; this input is not \
                     glTF (write csv or json)",
                    doc.source
                ))
                .into());
            };
            super::settings::check_carries(args, format)?;
            for w in check_grid(&clip, fps)? {
                warn.warning(&w);
            }
            let container = super::settings::gltf_container(&args.output, container, &clip);
            Some((clip, container))
        }
        _ => None,
    };
    let mut reads = input.reads.clone();
    reads.extend(crate::output::files_read([args.skeleton.as_deref()], &[]));
    let out = WriteBehind::new(crate::output::open_output(
        args.output.output.as_deref(),
        &reads,
    )?);
    let mut sink: Box<dyn Sink> = match format {
        OutputFormat::Bvh => {
            let frames = BvhFrames::new(out, skeleton.expect("checked above"), fps);
            match args.output.euler_mode() {
                EulerMode::Wrapped => Box::new(frames.wrapped()),
                _ => Box::new(frames),
            }
        }
        OutputFormat::Gltf(_) => {
            let (clip, container) = gltf_out.expect("checked above");
            let frames = GltfFrames::new(out, clip, fps, container);
            // Written to a file: relative URIs are rewritten for its folder.
            match args.output.folder() {
                Some(dir) => Box::new(frames.in_folder(dir)),
                None => Box::new(frames),
            }
        }
        OutputFormat::Doc(format) => {
            let w = FrameWriter::new(out, format, style, fps, track_column, args.velocity);
            Box::new(if positions { w.with_positions() } else { w })
        }
        OutputFormat::Npy => {
            let w = NpyWriter::new(out, style, rows, track_column, args.velocity);
            Box::new(if positions { w.with_positions() } else { w })
        }
        OutputFormat::Npz => {
            let w = NpzWriter::new(out, style, fps, npz.expect("checked above"));
            Box::new(match tree {
                Some(tree) => w.with_tree(tree),
                None => w,
            })
        }
        OutputFormat::Fbx => match on_template {
            Some(t) => Box::new(
                FbxFrames::new(
                    out,
                    std::sync::Arc::new(t.skeleton()),
                    inbetween_io::fbx::keys::clip_orders(&t),
                    fps,
                    inbetween_io::fbx::keys::BVH_STAGE,
                )
                .on_channels(t),
            ),
            None => Box::new(FbxFrames::new(
                out,
                usd.expect("checked above"),
                inbetween_io::fbx::keys::joint_orders(doc),
                fps,
                inbetween_io::fbx::keys::stage(doc),
            )),
        },
        OutputFormat::Usda => Box::new(UsdFrames::new(
            out,
            usd.expect("checked above"),
            fps,
            Stage {
                meters_per_unit: doc.unit_meters.unwrap_or(0.01),
                z_up: doc.z_up == Some(true),
            },
        )),
    };
    for &i in &order {
        let (curve, track) = (&curves[i], &tracks[i]);
        // glTF output: the animation's first and last times, where they are not frames, are
        // sampled too (after the frames), so its first and last poses are kept.
        // USD output likewise: the clip's first and last times, where they are not frames.
        let edges = match (gltf.filter(|_| to_gltf), &sources[i]) {
            (Some(g), Some(s)) => gltf_edges(g, s.animation, fps),
            _ if format == OutputFormat::Usda => span_edges(span(i), fps),
            _ => [None, None],
        };
        match curve {
            TrackCurve::Curve(curve) => {
                bake_over(curve, fps, span(i), bake_opts, sink.as_mut(), &mut |m| {
                    warn.warning(&crate::flags::say(m))
                })?
            }
            TrackCurve::Sampled(sampler, frames) => {
                let sampled = Sampled {
                    name: track.name(),
                    frames: *frames,
                    sample: &|time| sampler.at(time),
                };
                bake_sampled(
                    &sampled,
                    &baked,
                    fps,
                    span(i),
                    bake_opts,
                    sink.as_mut(),
                    &mut |m| warn.warning(&crate::flags::say(m)),
                )?
            }
        }
        for t in edges.into_iter().flatten() {
            sink.edge(t, curve.rotation(t), curve.position(t))?;
        }
    }
    sink.finish()?;
    sink.into_output()?.commit()?;
    if args.verbose {
        let reports = curves.iter().filter_map(|c| match c {
            TrackCurve::Curve(c) => Some((c, c.solver_report()?)),
            TrackCurve::Sampled(..) => None,
        });
        for (curve, r) in reports {
            let name = inbetween::error::shorten(curve.name().unwrap_or("-"));
            warn.report(&format!(
                "inbetween: minaccel: track {name}: {} points, {} iterations, E {:.6e} -> {:.6e}, \
                 projected gradient {:.3e} -> {:.3e} ({}converged)",
                r.points,
                r.iterations,
                r.energy_start,
                r.energy,
                r.gradient_start,
                r.gradient,
                if r.converged { "" } else { "not " }
            ));
        }
    }
    Ok(())
}

/// The arrays of `.npz` output: every track on the same frames (its arrays are frames ×
/// tracks), and an archive a zip without ZIP64 holds; input errors otherwise, before anything
/// is written or held.
fn npz_shape(
    args: &InterpArgs,
    tracks: &[inbetween::Track],
    style: &inbetween_io::write::Style,
    span: impl Fn(usize) -> (f64, f64),
    fps: inbetween::Fps,
    (positions, tree): (bool, bool),
    source: &str,
) -> Result<NpzShape, Error> {
    let ranges: Vec<(i64, i64)> = (0..tracks.len())
        .map(|i| fps.frames_between(span(i).0, span(i).1))
        // Tracks without frames have the same (empty) frames.
        .map(|(a, b)| if b < a { (0, -1) } else { (a, b) })
        .collect();
    if let Some(i) = ranges.iter().position(|r| *r != ranges[0]) {
        let label = |i: usize| inbetween_io::document::track_label(source, tracks[i].name());
        return Err(InputError::new(format!(
            "--span track: npz output holds every track on the same frames (arrays of frames × \
             tracks), but {} spans frames {}..={} and {} frames {}..={}; use --span clip, or \
             write npy, csv or json",
            label(0),
            ranges[0].0,
            ranges[0].1,
            label(i),
            ranges[i].0,
            ranges[i].1
        ))
        .into());
    }
    let shape = NpzShape {
        frames: tracks
            .first()
            .map_or(0, |_| fps.frame_count(span(0).0, span(0).1)),
        tracks: tracks.len(),
        velocity: args.velocity,
        positions,
        tree,
    };
    let longest = tracks
        .iter()
        .map(|t| t.name().map_or(0, |n| n.chars().count()))
        .max()
        .unwrap_or(0);
    npz_fits(shape, longest, style.repr.width(), source)?;
    Ok(shape)
}

/// Whether an archive of `shape` (the longest track name `longest` characters, `width` rotation
/// values a frame) can be written: its names within [`MAX_NAMES_BYTES`], the whole within what
/// a zip without ZIP64 holds; an input error naming `source` otherwise.
///
/// [`MAX_NAMES_BYTES`]: inbetween_io::write::npz::MAX_NAMES_BYTES
fn npz_fits(shape: NpzShape, longest: usize, width: usize, source: &str) -> Result<(), Error> {
    let names = inbetween_io::write::npz::names_size(shape.tracks, longest);
    if names > inbetween_io::write::npz::MAX_NAMES_BYTES {
        return Err(InputError::new(format!(
            "{source}: npz output stores track names at the longest name's width ({longest} \
             characters), {names} bytes for {} tracks, more than {} bytes; shorten the names, \
             or write npy, csv or json",
            shape.tracks,
            inbetween_io::write::npz::MAX_NAMES_BYTES
        ))
        .into());
    }
    let size = inbetween_io::write::npz::npz_size(width, shape, longest);
    if size > inbetween_io::write::zip::MAX_BYTES {
        return Err(InputError::new(format!(
            "{source}: npz output of {} frames × {} tracks would take {size} bytes, more than a \
             zip without ZIP64 holds ({} bytes); write npy, or fewer frames (--fps, --tracks)",
            shape.frames,
            shape.tracks,
            inbetween_io::write::zip::MAX_BYTES
        ))
        .into());
    }
    Ok(())
}

/// Warns when an end of the written span `(lo, hi)` is a key (of the track `name` spanning
/// `(t0, t1)`) that misses a frame: only there can a key miss one; inside the clip it is held.
fn near_misses(
    source: &str,
    name: Option<&str>,
    (t0, t1): (f64, f64),
    (lo, hi): (f64, f64),
    fps: inbetween::Fps,
    warn: &mut dyn Events,
) {
    let (before, after) = fps.near_misses(t0, t1);
    let label = inbetween_io::document::track_label(source, name);
    for (k, key, which, side) in [
        (before.filter(|_| t0 == lo), t0, "first", "after"),
        (after.filter(|_| t1 == hi), t1, "last", "before"),
    ] {
        if let Some(k) = k {
            warn.warning(&format!(
                "{label}: the {which} key, at {} s, is {:.1e} s {side} frame {k} ({} s), which \
                 is therefore not written; --snap-keys 0.001 moves keys that close onto the grid",
                num(key),
                (key - fps.time_of(k)).abs(),
                num(fps.time_of(k))
            ));
        }
    }
}

/// An end of the span this close to a frame (s) is not sampled apart from it: a float32 key
/// time 13 units from 1/24 s (CesiumMan's) is that frame, not a pose of its own.
const EDGE_GAP: f64 = 1e-6;

/// The ends of `(lo, hi)` that are not frames at `fps` (an end within [`EDGE_GAP`] of a frame is
/// that frame): the first and last poses, which USD output samples at their fractional time
/// codes.
fn span_edges((lo, hi): (f64, f64), fps: Fps) -> [Option<f64>; 2] {
    let (first, last) = fps.frames_between(lo, hi);
    if first > last {
        return [Some(lo), (hi > lo).then_some(hi)];
    }
    [
        (fps.time_of(first) - lo > EDGE_GAP).then_some(lo),
        (hi - fps.time_of(last) > EDGE_GAP).then_some(hi),
    ]
}

/// A frame writer that hands back its output when done.
trait Sink: FrameSink {
    fn into_output(self: Box<Self>) -> std::io::Result<Output>;
    /// The current track's pose at an edge of its span that is not a frame ([`gltf_edges`],
    /// [`span_edges`]); only glTF and USD output have such samples.
    fn edge(&mut self, _time: f64, _q: DQuat, _p: Option<DVec3>) -> std::io::Result<()> {
        Err(std::io::Error::other(
            "internal error: an edge sample for output other than glTF",
        ))
    }
}

impl Sink for FrameWriter<WriteBehind> {
    fn into_output(self: Box<Self>) -> std::io::Result<Output> {
        self.into_inner().finish()
    }
}

impl Sink for BvhFrames<WriteBehind> {
    fn into_output(self: Box<Self>) -> std::io::Result<Output> {
        self.into_inner()?.finish()
    }
}

impl Sink for GltfFrames<WriteBehind> {
    fn into_output(self: Box<Self>) -> std::io::Result<Output> {
        self.into_inner()?.finish()
    }
    fn edge(&mut self, time: f64, q: DQuat, _p: Option<DVec3>) -> std::io::Result<()> {
        // Its translations are its translation channels' own samplers.
        GltfFrames::edge(self, time, q)
    }
}

impl Sink for UsdFrames<WriteBehind> {
    fn into_output(self: Box<Self>) -> std::io::Result<Output> {
        self.into_inner()?.finish()
    }
    fn edge(&mut self, time: f64, q: DQuat, p: Option<DVec3>) -> std::io::Result<()> {
        UsdFrames::edge(self, time, q, p)
    }
}

impl Sink for FbxFrames<WriteBehind> {
    fn into_output(self: Box<Self>) -> std::io::Result<Output> {
        self.into_inner()?.finish()
    }
}

impl Sink for NpzWriter<WriteBehind> {
    fn into_output(self: Box<Self>) -> std::io::Result<Output> {
        self.into_inner()?.finish()
    }
}

impl Sink for NpyWriter<WriteBehind> {
    fn into_output(self: Box<Self>) -> std::io::Result<Output> {
        self.into_inner().finish()
    }
}
