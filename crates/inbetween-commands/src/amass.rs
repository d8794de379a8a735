//! `interp clip.npz --fps 30 -o out.npz`: an AMASS motion file written back in its own shape
//! at the output rate (docs/formats.md, *AMASS*): the joints' curves give `poses` (and the split
//! rotation arrays), the other per-frame arrays are interpolated linearly, everything else is
//! copied ([`inbetween_io::amass::Amass::resample`]).
//!
//! This path is taken when the input is an AMASS `.npz` (by `--input-format npz` or its
//! extension) and the output is npz (by `--output-format`, the `-o` extension, or by default);
//! other outputs (CSV, JSON, npy, USD) take the general path with the file's joints as tracks.

use crate::args::{InterpArgs, PathArg};
use crate::settings::{curve_options, output_format, tcb_flags};
use inbetween::curve::Curve;
use inbetween::{Error, InputError};
use inbetween_io::{Format, OutputFormat};
use std::io::Read;

/// Whether `interp` writes an AMASS file back: the input is `.npz` (by `--input-format` or
/// the file's extension; standard input needs the former) and the output npz.
pub fn writes_amass(args: &InterpArgs) -> bool {
    let path = args.input.input.as_deref().filter(|p| p.as_os_str() != "-");
    let input = args
        .input
        .input_format
        .or_else(|| path.and_then(Format::from_path));
    input == Some(Format::Amass)
        && args.skeleton.is_none()
        && output_format(&args.output, Format::Amass) == OutputFormat::Npz
}

/// Runs `interp` from an AMASS file to an AMASS file (see the module documentation).
pub fn interp(args: &InterpArgs, stdin: &mut dyn Read) -> Result<(), Error> {
    let refuse = |what: &str| -> Result<(), Error> {
        Err(InputError::new(format!(
            "{what}: AMASS npz output writes every joint's poses as rotation vectors at the \
             output rate; write csv or json (-o out.csv) for that"
        ))
        .into())
    };
    if args.input.tracks.is_some() {
        return refuse("--tracks");
    }
    if args.velocity {
        return refuse("--velocity");
    }
    if args.input.from.is_some() {
        return refuse("--from");
    }
    if args.curve.path == PathArg::Euler {
        return refuse("--path euler");
    }
    if args.input.animation.is_some() {
        return refuse("--animation");
    }
    let path = args.input.input.as_deref().filter(|p| p.as_os_str() != "-");
    let (bytes, source) = match path {
        Some(p) => (
            inbetween_io::read_bytes_limited(p, args.input.max_input_bytes)?,
            p.display().to_string(),
        ),
        None => (
            inbetween_io::read_limited(stdin, args.input.max_input_bytes, "<stdin>")?,
            "<stdin>".to_string(),
        ),
    };
    let amass = inbetween_io::amass::read(&bytes, &source, args.input.key_fps)?;
    drop(bytes);
    let doc = amass.document()?;
    let fps = args.curve.fps.unwrap_or(amass.fps());
    let tracks = doc.tracks_shaped(amass.fps(), tcb_flags(&args.curve))?;
    let (a, b) = amass.frames_at(fps);
    let rows = (b - a + 1).max(0) as u64;
    crate::record::note(|s| {
        s.frames = Some(rows);
        s.tracks = Some(tracks.len());
    });
    if rows > args.max_frames {
        return Err(InputError::new(format!(
            "{source}: interp would write {rows} frames at {fps} fps, more than --max-frames {}",
            args.max_frames
        ))
        .into());
    }
    let scheme = crate::played::scheme(args.scheme, Format::Amass, None);
    let opts = curve_options(&args.curve, scheme, fps, args.input.angles);
    let curves = tracks
        .iter()
        .map(|t| Curve::new(t, &opts).map_err(|e| Error::Input(e.at(&source))))
        .collect::<Result<Vec<_>, Error>>()?;
    let resampled = amass.resample(fps, &|j, t| curves[j].rotation(t))?;
    let reads = crate::settings::files_read(&args.input, &[], None);
    let mut out = crate::output::open_output(args.output.output.as_deref(), &reads)?;
    resampled.write(&mut out)?;
    out.commit()?;
    Ok(())
}
