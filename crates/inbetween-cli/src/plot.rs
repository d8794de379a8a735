//! `inbetween plot`: an SVG chart of one track, schemes side by side.

use crate::chart::{What, svg};
use inbetween::error::shorten;
use inbetween::{Error, InputError, Scheme};
use inbetween_commands::args::{PlotArgs, WhatArg};
use inbetween_commands::events::Events;
use inbetween_commands::settings::read_curves;
use std::io::{Read, Write};

/// Runs `plot`: one track's chart, schemes side by side.
pub fn run(args: &PlotArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    let input = read_curves(
        &args.input,
        &args.curve,
        &|_, _| Scheme::default(),
        stdin,
        warn,
    )?;
    let (doc, tracks) = (&input.doc, &input.tracks);
    let unit = args.input.angles;
    let track = match &args.track {
        None => &tracks[0],
        Some(name) => tracks
            .iter()
            .find(|t| t.name() == Some(name.as_str()))
            .ok_or_else(|| {
                let names: Vec<&str> = tracks.iter().filter_map(|t| t.name()).collect();
                InputError::new(format!(
                    "{}: --track: expected one of {}, found \"{}\"",
                    doc.source,
                    if names.is_empty() {
                        "(no named tracks)".to_string()
                    } else {
                        shorten(&names.join(", ")).into_owned()
                    },
                    shorten(name)
                ))
            })?,
    };
    let schemes: Vec<Scheme> = args.scheme.0.iter().map(|&s| s.into()).collect();
    let what = match args.what {
        WhatArg::Speed => What::Speed,
        WhatArg::Components => What::Components,
        WhatArg::Energy => What::Energy,
    };
    let text = svg(track, &schemes, what, &input.opts, input.fps, unit).map_err(|e| match e {
        Error::Input(e) => Error::Input(e.at(&doc.source)),
        e => e,
    })?;
    let mut out = inbetween_commands::output::open_output(Some(&args.output), &input.reads)?;
    out.write_all(text.as_bytes())?;
    out.commit()?;
    Ok(())
}
