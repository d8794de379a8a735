//! `inbetween interp`: keyframes in, every in-between frame out.

use crate::cli::InterpArgs;
use crate::interp::{Settings, run as interpolate};
use crate::io::OutputFormat;
use crate::io::npy::NpyWriter;
use crate::io::output::{Output, WriteBehind};
use crate::io::write::{FrameWriter, Style};
use std::io::Read;

/// Validated settings from the arguments and the document (command line wins, except that a
/// document's `fps` numbers its own `frame` values).
pub fn run(
    args: &InterpArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> anyhow::Result<()> {
    let (doc, in_format, tracks, opts) = super::read_curves(&args.input, &args.curve, stdin, warn)?;
    let unit = args.input.angles;
    let settings = Settings {
        fps: opts.fps,
        scheme: args.scheme.into(),
        blend: opts.blend,
        path: opts.path,
        ends: opts.ends,
        velocity: args.velocity,
        // Two generating threads pay only when the output is cheap to write (npy); with text,
        // formatting already uses the second core (measured: docs/performance.md).
        parallel: args.output.output_format == Some(OutputFormat::Npy),
    };
    let format = args
        .output
        .output_format
        .unwrap_or(OutputFormat::Doc(in_format));
    let style = Style {
        repr: args.output.to,
        angles: unit,
        quat_order: args.input.quat_order,
        num: args.output.num_format(),
    };
    let track_column = doc.named_tracks || tracks.len() > 1;
    let out = WriteBehind::new(Output::open(args.output.output.as_deref())?);
    // Input errors found while interpolating (minaccel's grid cap) name the file too.
    let locate = |e: anyhow::Error| match e.downcast::<crate::InputError>() {
        Ok(ie) => anyhow::Error::new(ie.at(&doc.source)),
        Err(e) => e,
    };
    let reports = if let OutputFormat::Doc(format) = format {
        let mut writer =
            FrameWriter::new(out, format, style, opts.fps, track_column, args.velocity);
        let reports = interpolate(&tracks, &settings, &mut writer, warn).map_err(locate)?;
        writer.into_inner().finish()?.commit()?;
        reports
    } else {
        let rows: u64 = tracks
            .iter()
            .map(|t| {
                let (a, b) = opts
                    .fps
                    .frames_between(t.times[0], t.times[t.times.len() - 1]);
                (b - a + 1).max(0) as u64
            })
            .sum();
        let mut writer = NpyWriter::new(out, style, rows, track_column, args.velocity);
        let reports = interpolate(&tracks, &settings, &mut writer, warn).map_err(locate)?;
        writer.into_inner().finish()?.commit()?;
        reports
    };
    if args.verbose {
        for (track, r) in tracks.iter().zip(&reports) {
            let name = track.name.as_deref().unwrap_or("-");
            eprintln!(
                "inbetween: minaccel: track {name}: {} points, {} iterations, E {:.6e} -> {:.6e}, \
                 projected gradient {:.3e} -> {:.3e} ({}converged)",
                r.points,
                r.iterations,
                r.energy_start,
                r.energy,
                r.gradient_start,
                r.gradient,
                if r.converged { "" } else { "not " }
            );
        }
    }
    Ok(())
}
