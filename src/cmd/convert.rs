//! `inbetween convert`: keys in, the same keys out in another representation and/or format.

use crate::cli::ConvertArgs;
use crate::clock::Fps;
use crate::io::OutputFormat;
use crate::io::output::Output;
use crate::io::write::{Style, write_keys};
use std::io::Read;

/// Runs `convert`. Keys must be finite with strictly increasing times per track; unlike
/// `interp`, a track of one key is fine.
pub fn run(
    args: &ConvertArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> anyhow::Result<()> {
    let (doc, in_format) = super::read_input(&args.input, stdin, warn)?;
    let frame_fps = doc
        .fps
        .or(args.fps)
        .unwrap_or(Fps::new(30, 1).expect("30 is valid"));
    for track in &doc.tracks {
        doc.track_times(track, frame_fps, 1)?;
    }
    let format = match args.output.output_format {
        None => in_format,
        Some(OutputFormat::Doc(f)) => f,
        Some(OutputFormat::Npy) => {
            return Err(crate::input_err!(
                "--output-format npy: convert writes keyframe documents (csv or json); npy is \
                 for interp's frames"
            )
            .into());
        }
    };
    if format == crate::io::Format::Csv
        && doc
            .tracks
            .iter()
            .any(|t| t.start_velocity.is_some() || t.end_velocity.is_some())
    {
        warn("CSV has no place for start_velocity/end_velocity; they are not written");
    }
    let style = Style {
        repr: args.output.to,
        angles: args.input.angles,
        quat_order: args.input.quat_order,
        num: args.output.num_format(),
    };
    let mut out = Output::open(args.output.output.as_deref())?;
    write_keys(&mut out, &doc, format, style, frame_fps)?;
    out.commit()?;
    Ok(())
}
