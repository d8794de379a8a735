//! `inbetween reduce`: dense frames in, the fewest keys out that `interp` turns back into them
//! (the library's [`inbetween::reduce`]).

use super::settings::{Curves, output_format, rates, read_curves_in, tracks_take_translations};
use crate::cli::{MethodArg, ReduceArgs};
use inbetween::reduce::{Method, ReduceOptions, Reduced, TrackFrames, reduce_each, reduce_shared};
use inbetween::{CurveOptions, Error, EulerSeq, Fps, InputError, PathMode, Repr, Scheme};
use inbetween_commands::events::Events;
use inbetween_io::document::{DocTrack, Document, KeyOrigin};
use inbetween_io::gltf::document::Mode;
use inbetween_io::write::write_keys;
use inbetween_io::write::{EulerMode, Style};
use inbetween_io::{Format, OutputFormat};
use std::io::Read;
use std::path::PathBuf;

/// Runs `reduce`: every track reduced (or all on shared keys), verified, written as keys.
pub fn run(args: &ReduceArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    if let Some(done) = super::reduce_bvh::lean(args, warn) {
        return done;
    }
    let gltf_output = !tracks_take_translations(&args.output);
    super::reduce_world::check_options(args, gltf_output)?;
    // A position tolerance poses the skeleton with the tracks' translations, even where the
    // output keeps them.
    let input = read_curves_in(
        (
            Mode::Frames,
            !gltf_output || args.position_tolerance.is_some(),
        ),
        &args.input,
        &args.curve,
        &|f| scheme(args, f),
        stdin,
        warn,
    )?;
    let (doc, tracks) = (&input.doc, &input.tracks);
    let format = match keys_format(args, input.format)? {
        OutputFormat::Gltf(container) => {
            return super::reduce_gltf::to_gltf(args, &input, container, warn);
        }
        OutputFormat::Doc(f) => f,
        // USD keys are written from the kept keys as JSON's are (`write` sends them to USD).
        OutputFormat::Usda => Format::Json,
        _ => unreachable!("keys_format gives keys documents, glTF and USD"),
    };
    if let Some(s) = args.scale_tolerance {
        return Err(InputError::new(format!(
            "--scale-tolerance {s}: only glTF output (-o small.glb from a glTF input) has scale \
             channels to reduce; csv and json keys carry rotations and translations"
        ))
        .into());
    }
    if tracks.iter().any(|t| t.translations().is_some())
        && args.translation_tolerance.is_none()
        && args.position_tolerance.is_none()
    {
        return Err(InputError::new(format!(
            "{}: the tracks have translations: give their tolerance with --translation-tolerance \
             (length units)",
            doc.source
        ))
        .into());
    }
    let (frame_fps, _) = rates(doc, args.curve.fps);
    let style = keys_style(args, input.opts.path, tracks, &doc.source)?;
    // The kept keys, as the input gave them (frame numbers or times, Euler angles, positions).
    let doc_of = |reduced: &[Reduced]| Document {
        source: doc.source.clone(),
        fps: doc.fps,
        rotation: doc.rotation,
        tracks: doc
            .tracks
            .iter()
            .zip(reduced)
            .map(|(d, r)| kept(d, r))
            .collect(),
        named_tracks: doc.named_tracks,
        warnings: Vec::new(),
        skeleton: None,
        hierarchy: doc.hierarchy.clone(),
        unit_meters: doc.unit_meters,
        z_up: doc.z_up,
    };
    // USD stores float32 rotations and translations: the tolerances are tightened by what that
    // rounding can move a key (as for glTF output).
    let margin = if keys_format(args, input.format)? == OutputFormat::Usda {
        let largest = tracks
            .iter()
            .filter_map(|t| t.translations())
            .flatten()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        (FLOAT32_MARGIN, largest * f32::EPSILON as f64)
    } else {
        (0.0, 0.0)
    };
    let reduced = match args.output.precision {
        None => reduce_tracks(args, &input, margin, (true, false), warn)?,
        Some(_) => {
            let encode = |r: &[Reduced]| -> Result<Vec<u8>, Error> {
                let mut bytes = Vec::new();
                write_keys(&mut bytes, &doc_of(r), format, style, frame_fps)?;
                Ok(bytes)
            };
            super::reduce_rounded::as_written(
                args,
                &input,
                (format, style, frame_fps),
                &encode,
                warn,
            )?
        }
    };
    report_all(args, &input, &reduced, warn);
    let out_doc = doc_of(&reduced);
    let skeleton = doc.skeleton.is_some();
    write(
        args,
        &out_doc,
        (format, style, frame_fps),
        (input.format, skeleton),
        &input.reads,
        warn,
    )
}

/// The output format of the keys for an input in `input` format: a keys document (CSV, JSON),
/// or glTF; a BVH input's keys default to JSON (on standard output, or to an `-o` whose name
/// does not say bvh: `-o keys`, `/dev/null`); npy and BVH are refused.
pub(super) fn keys_format(args: &ReduceArgs, input: Format) -> Result<OutputFormat, Error> {
    Ok(match output_format(&args.output, input) {
        OutputFormat::Bvh
            if args.output.output_format.is_none()
                && !args.output.output.as_deref().is_some_and(|p| {
                    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("bvh"))
                }) =>
        {
            OutputFormat::Doc(Format::Json)
        }
        f @ (OutputFormat::Gltf(_) | OutputFormat::Doc(_)) => f,
        OutputFormat::Usda => {
            if scheme(args, input) != Scheme::Slerp {
                return Err(InputError::new(
                    "--scheme: USD plays its samples by slerp (rotations) and linearly \
                     (translations), so keys reduced for another scheme would not play within \
                     the tolerance; use --scheme slerp (the default for USD output)",
                )
                .into());
            }
            if args.output.precision.is_some() {
                return Err(InputError::new(
                    "--precision: USD stores its values as float32, and reduce already tightens \
                     the tolerances by that rounding; drop --precision for .usda output",
                )
                .into());
            }
            if !args.shared_keys {
                return Err(InputError::new(
                    "USD samples every joint at the same times: give --shared-keys (the fewest \
                     key times shared by every track)",
                )
                .into());
            }
            OutputFormat::Usda
        }
        other => {
            let name = match other {
                OutputFormat::Npy => "npy",
                OutputFormat::Npz => "npz",
                _ => "bvh (it holds every frame)",
            };
            return Err(InputError::new(format!(
                "reduce writes keys: csv, json, or glTF for a glTF input, not {name}"
            ))
            .into());
        }
    })
}

/// A track's kept keys as the input gave them (frame numbers or times, Euler angles,
/// positions), with their velocities.
pub(super) fn kept(d: &DocTrack, r: &Reduced) -> DocTrack {
    DocTrack {
        name: d.name.clone(),
        keys: r.keys.iter().map(|&i| d.keys[i]).collect(),
        start_velocity: None,
        end_velocity: None,
        origin: KeyOrigin::Frames,
        euler: d
            .euler
            .as_ref()
            .map(|(seq, a)| (*seq, r.keys.iter().map(|&i| a[i]).collect())),
        velocities: r
            .velocities
            .as_ref()
            .map(|w| w.iter().copied().map(Some).collect())
            .unwrap_or_default(),
        tcb: Vec::new(),
        translations: if d.translations.is_empty() {
            Vec::new()
        } else {
            r.keys.iter().map(|&i| d.translations[i]).collect()
        },
    }
}

/// Writes the kept keys `doc` in `format` and `style`, frame numbers at `frame_fps`; `input`
/// is the input's format and whether its keys come from a BVH clip, for CSV's rate warning.
pub(super) fn write(
    args: &ReduceArgs,
    doc: &Document,
    (format, style, frame_fps): (Format, Style, Fps),
    (input, skeleton): (Format, bool),
    reads: &[PathBuf],
    warn: &mut dyn Events,
) -> Result<(), Error> {
    if format == Format::Csv
        && let Some(w) = super::settings::csv_rate_warning(doc, input, skeleton)
    {
        warn.warning(&w);
    }
    let mut out = crate::output::open(args.output.output.as_deref(), reads)?;
    if output_format(&args.output, input) == OutputFormat::Usda {
        inbetween_io::usd::keys::write_keys(&mut out, doc, frame_fps)?;
    } else {
        write_keys(&mut out, doc, format, style, frame_fps)?;
    }
    out.commit()?;
    Ok(())
}

/// The written keys' style. With `--path euler` a key's turns are in its Euler angles, so the
/// keys are written as the input gave them: its sequence (`--to` may only name it), each key's
/// own triple ([`EulerMode::AsGiven`]).
pub(super) fn keys_style(
    args: &ReduceArgs,
    path: PathMode,
    tracks: &[inbetween::Track],
    source: &str,
) -> Result<Style, Error> {
    let mut style = super::settings::style(&args.input, &args.output);
    if path != PathMode::Euler {
        return Ok(style);
    }
    let mut seqs: Vec<EulerSeq> = Vec::new();
    for seq in tracks
        .iter()
        .filter_map(|t| t.euler_angles().map(|(seq, _)| seq))
    {
        if !seqs.contains(&seq) {
            seqs.push(seq);
        }
    }
    let [seq] = seqs[..] else {
        let names: Vec<String> = seqs.iter().map(|&s| Repr::Euler(s).to_string()).collect();
        return Err(InputError::new(format!(
            "{source}: --path euler writes the keys as the input's Euler angles, in one \
             sequence, but the tracks have {}; reduce them apart or use --path shortest",
            names.join(", ")
        ))
        .into());
    };
    match style.repr {
        Repr::Quat => {}
        Repr::Euler(s) if s == seq => {}
        other => {
            return Err(InputError::new(format!(
                "--to {other}: with --path euler the keys keep their turns in their Euler angles, \
                 so they are written as the input gave them ({})",
                Repr::Euler(seq)
            ))
            .into());
        }
    }
    style.repr = Repr::Euler(seq);
    style.euler = EulerMode::AsGiven;
    Ok(style)
}

/// The smallest tolerance `reduce` takes (rad, or D times this with `--distance D`): the
/// curve's evaluation carries round-off of about 1e-15 rad, so a tolerance near it cannot be
/// verified (every frame would end up a key and still miss).
const MIN_TOLERANCE: f64 = 1e-9;

/// How much a glTF output's tolerance is tightened (radians, or D times this with
/// `--distance D`): the keys are stored as float32 (about 2.4e-7 rad at most).
pub(super) const FLOAT32_MARGIN: f64 = 1e-6;

/// Every track reduced with the tolerances tightened by `margin` (rotation, in the tolerance's
/// own unit; position, in length units), translations reduced too when `translations`, and for
/// glTF output (`float32_times`) verified on the key times as written (float32) at the frame
/// times, as a player evaluates them.
pub(super) fn reduce_tracks(
    args: &ReduceArgs,
    input: &Curves,
    margin: (f64, f64),
    (translations, float32_times): (bool, bool),
    told: &mut dyn Events,
) -> Result<Vec<Reduced>, Error> {
    let (doc, tracks) = (&input.doc, &input.tracks);
    let opts = reduce_options(args, input.opts, margin, translations)?;
    let located = |e: InputError| e.at(&doc.source);
    let written: Vec<Option<Vec<f64>>> = tracks
        .iter()
        .map(|t| float32_times.then(|| t.times().iter().map(|&x| f64::from(x as f32)).collect()))
        .collect();
    let frames: Vec<TrackFrames> = tracks
        .iter()
        .zip(&written)
        .map(|(t, w)| TrackFrames {
            positions: t.translations().filter(|_| translations),
            key_times: w.as_deref(),
            ..TrackFrames::of(t)
        })
        .collect();
    if args.shared_keys
        && let Some(first) = tracks.first()
        && let Some(other) = tracks.iter().find(|t| t.times() != first.times())
    {
        let label = |t: &inbetween::Track| {
            let times = t.times();
            format!(
                "track \"{}\" ({} frames, {} s to {} s)",
                inbetween::error::shorten(t.name().unwrap_or("-")),
                times.len(),
                times[0],
                times[times.len() - 1]
            )
        };
        return Err(InputError::new(format!(
            "{}: --shared-keys needs one grid of frame times, but {} and {} differ",
            doc.source,
            label(first),
            label(other)
        ))
        .into());
    }
    if args.position_tolerance.is_some() {
        let posed: Vec<TrackFrames> = tracks
            .iter()
            .zip(&frames)
            .map(|(t, f)| TrackFrames {
                positions: t.translations(),
                ..*f
            })
            .collect();
        return super::reduce_world::reduce(
            args,
            input,
            &posed,
            &opts,
            (translations, margin.0),
            told,
        );
    }
    let reduced: Vec<Reduced> = if args.shared_keys {
        reduce_shared(&frames, &opts)
    } else {
        reduce_each(&frames, &opts)
    }
    .map_err(|e| match e {
        Error::Input(e) => Error::Input(located(e)),
        other => other,
    })?;
    Ok(reduced)
}

/// `-v`'s line for each track of `input` reduced to `reduced`.
pub(super) fn report_all(
    args: &ReduceArgs,
    input: &Curves,
    reduced: &[Reduced],
    told: &mut dyn Events,
) {
    note_batch(args, input.tracks.iter().map(|t| t.len()).zip(reduced));
    // A position tolerance reports its own lines, with the world figures.
    if args.verbose && args.position_tolerance.is_none() {
        for (t, r) in input.tracks.iter().zip(reduced) {
            report(args, t.name(), t.len(), r, told);
        }
    }
}

/// The options of the command line for curves `curve`, the tolerances tightened by `margin`
/// (rotation, in the tolerance's own unit; position, in length units), translations reduced
/// when `translations`; a tolerance that is too small is an input error.
pub(super) fn reduce_options(
    args: &ReduceArgs,
    curve: CurveOptions,
    (margin, position_margin): (f64, f64),
    translations: bool,
) -> Result<ReduceOptions, Error> {
    let tolerance = match args.tolerance {
        // --position-tolerance alone: no local bound.
        None => std::f64::consts::PI,
        Some(given) => local_tolerance(args, given, margin)?,
    };
    let opts = ReduceOptions {
        curve,
        tolerance,
        distance: args.distance,
        translation_tolerance: args
            .translation_tolerance
            .filter(|_| translations)
            .map(|t| t - position_margin),
        velocities: !args.no_velocities,
        method: match args.method {
            MethodArg::Greedy => Method::Greedy,
            MethodArg::Optimal => Method::Optimal,
        },
    };
    Ok(opts)
}

/// `--tolerance given` as reduce measures it (rad, or a length with `--distance`), tightened by
/// `margin`; a tolerance that is too small is an input error.
fn local_tolerance(args: &ReduceArgs, given: f64, margin: f64) -> Result<f64, Error> {
    let tolerance = match args.distance {
        Some(_) => given,
        None => args.input.angles.to_rad(given),
    } - margin;
    if tolerance <= 0.0 {
        return Err(InputError::new(format!(
            "--tolerance {}: too small for keys stored as float32; give more than {}",
            given,
            match args.distance {
                Some(_) => margin,
                None => args.input.angles.from_rad(margin),
            }
        ))
        .into());
    }
    let floor = MIN_TOLERANCE * args.distance.unwrap_or(1.0);
    if tolerance < floor {
        let (least, unit) = match args.distance {
            Some(_) => (floor, "length units"),
            None => (
                args.input.angles.from_rad(floor),
                args.input.angles.as_str(),
            ),
        };
        return Err(InputError::new(format!(
            "--tolerance {:e}: below what reduce can verify (rotations carry about 1e-15 rad of \
             round-off); give at least {least:e} {unit}",
            given
        ))
        .into());
    }
    Ok(tolerance)
}

/// An error `x` of the tolerance's measure (rad, or a length with `--distance`) in the unit the
/// command line shows it in: `--angles`, or length units.
pub(super) fn unit(args: &ReduceArgs, x: f64) -> f64 {
    match args.distance {
        Some(_) => x,
        None => args.input.angles.from_rad(x),
    }
}

/// The name of [`unit`]'s unit.
pub(super) fn unit_name(args: &ReduceArgs) -> &'static str {
    match args.distance {
        Some(_) => "length units",
        None => args.input.angles.as_str(),
    }
}

/// `-v`'s line for a track named `name` of `len` frames reduced to `r`.
/// A batch's figures of this input: the frames read, tracks, keys kept and largest error.
pub(super) fn note_batch<'a>(
    args: &ReduceArgs,
    tracks: impl IntoIterator<Item = (usize, &'a Reduced)>,
) {
    super::batch::note(|s| {
        let (mut frames, mut count, mut keys, mut largest) = (0u64, 0, 0, 0.0f64);
        for (len, r) in tracks {
            frames += len as u64;
            count += 1;
            keys += r.keys.len();
            largest = largest.max(unit(args, r.max_error));
        }
        s.frames = Some(frames);
        s.tracks = Some(count);
        s.keys = Some(keys);
        s.largest_error = Some(largest);
    });
}

pub(super) fn report(
    args: &ReduceArgs,
    name: Option<&str>,
    len: usize,
    r: &Reduced,
    told: &mut dyn Events,
) {
    let unit = |x: f64| unit(args, x);
    let unit_name = unit_name(args);
    let position = r
        .max_position_error
        .map_or(String::new(), |p| format!(", max position error {p:.3e}"));
    told.report(&format!(
        "inbetween: reduce: track {}: {} frames, {} keys ({:.1} %), max error {:.3e}, mean \
         {:.3e} ({unit_name}){position}",
        inbetween::error::shorten(name.unwrap_or("-")),
        len,
        r.keys.len(),
        100.0 * r.keys.len() as f64 / len as f64,
        unit(r.max_error),
        unit(r.mean_error)
    ));
}

/// The scheme of the keys: `--scheme`, else slerp for glTF output (its `LINEAR` samplers play
/// by slerp), else bezier; `input` is the input's format, which glTF output needs.
pub(super) fn scheme(args: &ReduceArgs, input: Format) -> Scheme {
    match (args.scheme, output_format(&args.output, input)) {
        (Some(s), _) => s.into(),
        (None, OutputFormat::Gltf(_) | OutputFormat::Usda) => Scheme::Slerp,
        (None, _) => Scheme::Bezier,
    }
}
