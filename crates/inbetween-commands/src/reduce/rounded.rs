//! `reduce --precision N`: the guarantee for the keys as written. The keys, written with `N`
//! digits after the decimal point, are read back as `interp` reads them and their curve is
//! measured at every input frame; where rounding made it miss a tolerance, the tolerance is
//! tightened by twice the miss and the tracks are reduced again, until the written keys meet it
//! (docs/spec.md §4.7).

use super::report::{unit, unit_name};
use super::tracks::{reduce_options, reduce_tracks};
use crate::args::{InputArgs, ReduceArgs};
use crate::events::Events;
use crate::settings::{Curves, read_curves};
use inbetween::reduce::{Reduced, TrackFrames, curve_errors};
use inbetween::rotation::QuatOrder;
use inbetween::{Curve, Error, Fps, InputError};
use inbetween_io::Format;
use inbetween_io::write::Style;

/// Writes kept keys as the output's bytes.
pub(super) type Encode<'a> = dyn Fn(&[Reduced]) -> Result<Vec<u8>, Error> + 'a;

/// Most reductions before the precision is declared too coarse for the tolerance.
const MAX_TRIES: usize = 8;

/// The tracks of `input` reduced so that their keys, encoded by `encode` (in `format`, `style`,
/// frame numbers at `frame_fps`), meet the tolerances as written. Errors: keys that do not read
/// back (two times rounded to one), and a precision too coarse for the tolerance (the margin
/// reaches the tolerance, or [`MAX_TRIES`] reductions all miss), saying by how much.
pub(super) fn as_written(
    args: &ReduceArgs,
    input: &Curves,
    (format, style, frame_fps): (Format, Style, Fps),
    encode: &Encode<'_>,
    told: &mut dyn Events,
) -> Result<Vec<Reduced>, Error> {
    let digits = args.output.precision.unwrap_or_default();
    let exact = reduce_options(args, input.opts, (0.0, 0.0), true)?;
    let limits = (
        exact.tolerance,
        exact.translation_tolerance.unwrap_or(f64::INFINITY),
    );
    let mut margin = (0.0, 0.0);
    let mut miss = (0.0, 0.0);
    for _ in 0..MAX_TRIES {
        if margin.0 >= limits.0 || margin.1 >= limits.1 {
            break;
        }
        {
            let reduced = reduce_tracks(args, input, margin, (true, false), told)?;
            let bytes = encode(&reduced)?;
            let back = read_back(args, &bytes, format, style, frame_fps, digits)?;
            let errors = written_errors(args, input, &back)?;
            miss = (errors.0 - limits.0, errors.1 - limits.1);
            if miss.0 <= 0.0 && miss.1 <= 0.0 {
                if args.verbose {
                    told.report(&format!(
                        "inbetween: reduce: as written with --precision {digits}: max error \
                         {:.3e} ({}), tolerance tightened by {:.3e}",
                        unit(args, errors.0),
                        unit_name(args),
                        unit(args, margin.0)
                    ));
                }
                return Ok(reduced);
            }
            margin = (
                margin.0 + 2.0 * miss.0.max(0.0),
                margin.1 + 2.0 * miss.1.max(0.0),
            );
        }
    }
    let (what, by) = if miss.0 > 0.0 {
        (
            format!("--tolerance {}", args.tolerance.unwrap_or(f64::NAN)),
            format!("{:.3e} {}", unit(args, miss.0), unit_name(args)),
        )
    } else {
        (
            format!(
                "--translation-tolerance {}",
                args.translation_tolerance.unwrap_or_default()
            ),
            format!("{:.3e} length units", miss.1),
        )
    };
    Err(InputError::new(format!(
        "--precision {digits}: too few digits for {what}: the keys rounded to {digits} digits \
         miss it by {by} however it is tightened; give more digits or a larger tolerance"
    ))
    .into())
}

/// The written keys read back as `interp` reads a keys document given as standard input in
/// `format`, the rates, representation and units it was written with.
fn read_back(
    args: &ReduceArgs,
    bytes: &[u8],
    format: Format,
    style: Style,
    frame_fps: Fps,
    digits: usize,
) -> Result<Curves, Error> {
    let input = InputArgs {
        input: Some("-".into()),
        from: Some(style.repr),
        angles: args.input.angles,
        input_angles: Some(args.input.angles),
        key_fps: Some(frame_fps),
        delimiter: None,
        columns: None,
        time_unit: None,
        times: None,
        quat_order: QuatOrder::Wxyz,
        input_format: Some(format),
        animation: None,
        max_input_bytes: u64::MAX,
        tracks: None,
    };
    let scheme = |_, _| args.scheme.map_or(inbetween::Scheme::Bezier, Into::into);
    read_curves(
        &input,
        &args.curve,
        &scheme,
        &mut &bytes[..],
        &mut crate::events::Collected::default(),
    )
    .map_err(|e| match e {
        Error::Input(e) => InputError::new(format!(
            "--precision {digits}: the keys rounded to {digits} digits do not read back: {}",
            e.message()
        ))
        .into(),
        other => other,
    })
}

/// The largest rotation and position errors of the read-back keys' curves over the input's
/// frames.
fn written_errors(args: &ReduceArgs, input: &Curves, back: &Curves) -> Result<(f64, f64), Error> {
    let opts = reduce_options(args, input.opts, (0.0, 0.0), true)?;
    if back.tracks.len() != input.tracks.len() {
        return Err(Error::Internal(format!(
            "reduce --precision: {} tracks read back from {} written",
            back.tracks.len(),
            input.tracks.len()
        )));
    }
    let mut worst = (0.0f64, 0.0f64);
    for (t, b) in input.tracks.iter().zip(&back.tracks) {
        let curve = Curve::new(b, &input.opts)?;
        let (r, p) = curve_errors(&TrackFrames::of(t), &curve, &opts);
        worst = (worst.0.max(r), worst.1.max(p.unwrap_or(0.0)));
    }
    Ok(worst)
}
