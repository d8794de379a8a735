//! `inbetween plot`: an SVG chart of one track, schemes side by side.

use crate::cli::{PlotArgs, WhatArg};
use crate::curve::Scheme;
use crate::input_err;
use crate::io::output::Output;
use crate::plot::{What, svg};
use std::io::{Read, Write};

pub fn run(
    args: &PlotArgs,
    stdin: &mut dyn Read,
    warn: &mut dyn FnMut(&str),
) -> anyhow::Result<()> {
    let (doc, _, tracks, opts) = super::read_curves(&args.input, &args.curve, stdin, warn)?;
    let unit = args.input.angles;
    let track = match &args.track {
        None => &tracks[0],
        Some(name) => tracks
            .iter()
            .find(|t| t.name.as_deref() == Some(name.as_str()))
            .ok_or_else(|| {
                let names: Vec<&str> = tracks.iter().filter_map(|t| t.name.as_deref()).collect();
                input_err!(
                    "{}: --track: expected one of {}, found \"{name}\"",
                    doc.source,
                    if names.is_empty() {
                        "(no named tracks)".to_string()
                    } else {
                        names.join(", ")
                    }
                )
            })?,
    };
    let schemes: Vec<Scheme> = args.scheme.0.iter().map(|&s| s.into()).collect();
    let what = match args.what {
        WhatArg::Speed => What::Speed,
        WhatArg::Components => What::Components,
        WhatArg::Energy => What::Energy,
    };
    let text = svg(track, &schemes, what, &opts, unit).map_err(anyhow::Error::msg)?;
    let mut out = Output::open(Some(&args.output))?;
    out.write_all(text.as_bytes())?;
    out.commit()?;
    Ok(())
}
