//! One module per subcommand: validated settings from the parsed arguments, then the library.

pub mod analyze;
pub mod convert;
pub mod curve;
pub mod interp;
pub mod plot;

use crate::analyze::CurveOptions;
use crate::cli::InputArgs;
use crate::error::InputError;
use crate::input_err;
use crate::io::{Format, ReadOptions};
use crate::keys::{Document, TimedTrack};
use std::io::Read;

/// Reads the whole input (a file, or `stdin` for `-`/none) and parses it into a document.
/// Warnings found while reading go to `warn`.
pub fn read_input(
    args: &InputArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> Result<(Document, Format), InputError> {
    let opts = ReadOptions {
        from: args.from,
        angles: args.angles,
        quat_order: args.quat_order,
    };
    let (doc, format) = match args.input.as_deref() {
        Some(p) if p.as_os_str() != "-" => crate::io::read_path(p, args.input_format, &opts)?,
        _ => {
            let mut bytes = Vec::new();
            stdin
                .read_to_end(&mut bytes)
                .map_err(|e| input_err!("<stdin>: cannot read: {e}"))?;
            crate::io::parse_bytes(bytes, "<stdin>", None, args.input_format, &opts)?
        }
    };
    for w in &doc.warnings {
        warn(w);
    }
    Ok((doc, format))
}

/// The input, read and validated into tracks with the curve options (interp, analyze, plot):
/// the document, its format, the tracks and the options.
pub fn read_curves(
    input: &InputArgs,
    curve: &crate::cli::CurveArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> Result<(Document, Format, Vec<TimedTrack>, CurveOptions), InputError> {
    let (doc, format) = read_input(input, stdin, warn)?;
    let (tracks, opts) = curve::curve_setup(curve, &doc, input.angles)?;
    Ok((doc, format, tracks, opts))
}
