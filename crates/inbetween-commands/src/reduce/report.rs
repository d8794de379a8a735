//! What `reduce` tells: the `-v` lines, in the unit of the command line, and a batch's figures.

use crate::args::ReduceArgs;
use crate::events::Events;
use crate::settings::Curves;
use inbetween::reduce::Reduced;

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
    crate::record::note(|s| {
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
