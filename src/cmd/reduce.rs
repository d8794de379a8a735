//! `inbetween reduce`: dense frames in, the fewest keys out that `interp` turns back into them
//! (the library's [`inbetween::reduce`]).

use super::settings::{output_format, rates, read_curves};
use crate::cli::{MethodArg, ReduceArgs};
use inbetween::io::OutputFormat;
use inbetween::io::document::{DocTrack, Document, KeyOrigin};
use inbetween::io::output::Output;
use inbetween::io::write::write_keys;
use inbetween::reduce::{Method, ReduceOptions, Reduced, reduce_each, reduce_shared};
use inbetween::{Error, InputError};
use std::io::Read;

/// Runs `reduce`: every track reduced (or all on shared keys), verified, written as keys.
pub fn run(
    args: &ReduceArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> Result<(), Error> {
    let input = read_curves(&args.input, &args.curve, args.scheme.into(), stdin, warn)?;
    let (doc, tracks) = (&input.doc, &input.tracks);
    let format = match output_format(&args.output, input.format) {
        OutputFormat::Doc(f) => f,
        // A BVH input's keys default to JSON; npy and BVH are not keyframe documents.
        OutputFormat::Bvh
            if args.output.output.is_none() && args.output.output_format.is_none() =>
        {
            inbetween::io::Format::Json
        }
        other => {
            let name = match other {
                OutputFormat::Npy => "npy",
                _ => "bvh",
            };
            return Err(InputError::new(format!(
                "reduce writes keyframe documents (csv or json), not {name}"
            ))
            .into());
        }
    };
    if tracks.iter().any(|t| t.translations().is_some()) && args.translation_tolerance.is_none() {
        return Err(InputError::new(format!(
            "{}: the tracks have translations: give their tolerance with --translation-tolerance \
             (length units)",
            doc.source
        ))
        .into());
    }
    let tolerance = match args.distance {
        Some(_) => args.tolerance,
        None => args.input.angles.to_rad(args.tolerance),
    };
    let opts = ReduceOptions {
        curve: input.opts,
        tolerance,
        distance: args.distance,
        translation_tolerance: args.translation_tolerance,
        velocities: !args.no_velocities,
        method: match args.method {
            MethodArg::Greedy => Method::Greedy,
            MethodArg::Optimal => Method::Optimal,
        },
    };
    let located = |e: InputError| e.at(&doc.source);
    let reduced: Vec<Reduced> = if args.shared_keys {
        let frames: Vec<_> = tracks
            .iter()
            .map(|t| (t.times(), t.rotations(), t.translations()))
            .collect();
        reduce_shared(&frames, &opts).map_err(located)?
    } else {
        let frames: Vec<_> = tracks
            .iter()
            .map(|t| (t.times(), t.rotations(), t.translations()))
            .collect();
        reduce_each(&frames, &opts).map_err(located)?
    };
    if args.verbose {
        for (t, r) in tracks.iter().zip(&reduced) {
            let unit = |x: f64| match args.distance {
                Some(_) => x,
                None => args.input.angles.from_rad(x),
            };
            eprintln!(
                "inbetween: reduce: track {}: {} frames, {} keys ({:.1} %), max error {:.3e}, mean \
                 {:.3e}",
                inbetween::error::shorten(t.name().unwrap_or("-")),
                t.len(),
                r.keys.len(),
                100.0 * r.keys.len() as f64 / t.len() as f64,
                unit(r.max_error),
                unit(r.mean_error)
            );
        }
    }
    // The kept keys, as the input gave them (frame numbers or times, Euler angles, positions).
    let out_doc = Document {
        source: doc.source.clone(),
        fps: doc.fps,
        rotation: doc.rotation,
        tracks: doc
            .tracks
            .iter()
            .zip(&reduced)
            .map(|(d, r)| DocTrack {
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
            })
            .collect(),
        named_tracks: doc.named_tracks,
        warnings: Vec::new(),
        skeleton: None,
    };
    let (frame_fps, _) = rates(doc, args.curve.fps);
    let style = super::settings::style(&args.input, &args.output);
    let mut out = Output::open(args.output.output.as_deref())?;
    write_keys(&mut out, &out_doc, format, style, frame_fps)?;
    out.commit()?;
    Ok(())
}
