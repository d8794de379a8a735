//! One module per subcommand: validated settings from the parsed arguments, then the library.

pub mod analyze;
pub mod convert;
pub mod curve;
pub mod interp;
pub mod plot;

use crate::cli::InputArgs;
use crate::error::InputError;
use crate::input_err;
use crate::io::{Format, ReadOptions};
use crate::keys::Document;
use std::io::Read;
use std::path::Path;

/// Reads the whole input (a file, or `stdin` for `-`/none) and parses it into a document.
/// Warnings found while reading go to `warn`.
pub fn read_input(
    args: &InputArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> Result<(Document, Format), InputError> {
    let from_stdin = match &args.input {
        None => true,
        Some(p) => p.as_os_str() == "-",
    };
    let (bytes, source) = if from_stdin {
        let mut b = Vec::new();
        stdin
            .read_to_end(&mut b)
            .map_err(|e| input_err!("<stdin>: cannot read: {e}"))?;
        (b, "<stdin>".to_string())
    } else {
        let p = args.input.as_deref().unwrap_or(Path::new("-"));
        let source = p.display().to_string();
        let b = std::fs::read(p).map_err(|e| input_err!("{source}: cannot read: {e}"))?;
        (b, source)
    };
    let text = String::from_utf8(bytes).map_err(|e| {
        input_err!(
            "{source}: expected UTF-8 text, found an invalid byte at offset {}",
            e.utf8_error().valid_up_to()
        )
    })?;
    let format = match (args.input_format, &args.input) {
        (Some(f), _) => f,
        (None, Some(p)) if !from_stdin => {
            Format::from_path(p).unwrap_or_else(|| Format::sniff(&text))
        }
        _ => Format::sniff(&text),
    };
    let opts = ReadOptions {
        from: args.from,
        angles: args.angles,
        quat_order: args.quat_order,
    };
    let doc = crate::io::read_document(&text, &source, format, &opts)?;
    for w in &doc.warnings {
        warn(w);
    }
    Ok((doc, format))
}
