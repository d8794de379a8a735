//! Every track reduced under the options the command line gives (tolerances tightened by a
//! margin where the keys are written rounded), per joint or in world space.

use crate::args::{MethodArg, ReduceArgs};
use crate::events::Events;
use crate::settings::Curves;
use inbetween::reduce::{Method, ReduceOptions, Reduced, TrackFrames, reduce_each, reduce_shared};
use inbetween::{CurveOptions, Error, InputError};

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
        return super::world::reduce(args, input, &posed, &opts, (translations, margin.0), told);
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
