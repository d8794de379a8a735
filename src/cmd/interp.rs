//! `inbetween interp`: keyframes in, every in-between frame out.

use crate::cli::{BlendArg, EndsArg, InterpArgs, PathArg, SchemeArg};
use crate::clock::Fps;
use crate::curve::{Blend, Scheme};
use crate::interp::{Settings, run as interpolate};
use crate::io::output::Output;
use crate::io::write::{FrameWriter, Style};
use crate::tangent::{EndConditions, Ends, PathMode};
use glam::DVec3;
use std::io::Read;

/// Validated settings from the arguments and the document (command line wins, except that a
/// document's `fps` numbers its own `frame` values).
pub fn run(
    args: &InterpArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> anyhow::Result<()> {
    let (doc, in_format) = super::read_input(&args.input, stdin, warn)?;
    let default_fps = Fps::new(30, 1).expect("30 is valid");
    let frame_fps = doc.fps.or(args.fps).unwrap_or(default_fps);
    let fps = args.fps.or(doc.fps).unwrap_or(default_fps);
    let tracks = doc.timed_tracks(frame_fps)?;
    for t in &tracks {
        for &time in [t.times[0], t.times[t.times.len() - 1]].iter() {
            if !fps.in_range(time) {
                return Err(crate::input_err!(
                    "{}: time {time} s is beyond the frame numbers --fps {fps} supports (2^53)",
                    doc.source
                )
                .into());
            }
        }
    }
    let unit = args.input.angles;
    let omega = |v: Option<[f64; 3]>| v.map(|a| DVec3::from_array(a.map(|x| unit.to_rad(x))));
    let settings = Settings {
        fps,
        scheme: match args.scheme {
            SchemeArg::Hermite => Scheme::Hermite,
            SchemeArg::Squad => Scheme::Squad,
            SchemeArg::Bezier => Scheme::Bezier,
            SchemeArg::Slerp => Scheme::Slerp,
            SchemeArg::Minaccel => Scheme::MinAccel,
        },
        blend: match args.blend {
            BlendArg::Cubic => Blend::Cubic,
            BlendArg::Quadratic => Blend::Quadratic,
        },
        path: match args.path {
            PathArg::Shortest => PathMode::Shortest,
            PathArg::AsGiven => PathMode::AsGiven,
        },
        ends: EndConditions {
            ends: match args.ends {
                EndsArg::Chord => Ends::Chord,
                EndsArg::Rest => Ends::Rest,
            },
            start: omega(args.start_velocity),
            end: omega(args.end_velocity),
        },
    };
    let format = args.output.output_format.unwrap_or(in_format);
    let style = Style {
        repr: args.output.to,
        angles: unit,
        quat_order: args.input.quat_order,
        num: args.output.num_format(),
    };
    let track_column = doc.named_tracks || tracks.len() > 1;
    let out = Output::open(args.output.output.as_deref())?;
    let mut writer = FrameWriter::new(out, format, style, fps, track_column);
    let reports = interpolate(&tracks, &settings, &mut writer, warn)?;
    writer.into_inner().commit()?;
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
