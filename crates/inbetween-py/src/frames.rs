//! `write` to `.npy` and `.npz`: a clip's keys on a frame grid handed to the formats crate's
//! frame writers (the arrays `inbetween interp -o frames.npz` writes), track by track.

use crate::input_error;
use inbetween::{Fps, FrameSink};
use inbetween_io::OutputFormat;
use inbetween_io::document::{Document, KeyTime};
use inbetween_io::write::Style;
use inbetween_io::write::npy::NpyWriter;
use inbetween_io::write::npz::{NpzShape, NpzWriter};
use pyo3::prelude::*;
use std::io::Write;

/// Writes `doc` (keys at frame numbers of `fps`) as `target` (npy or npz) to `out`. npz holds
/// every track on the same frames: tracks on other frames are an input error.
pub fn write<W: Write>(
    out: W,
    doc: &Document,
    target: OutputFormat,
    style: Style,
    (fps, tree): (Fps, Option<inbetween_io::write::npz::Tree>),
) -> PyResult<()> {
    let frame = |k: &inbetween_io::document::Key| match k.when {
        KeyTime::Frame(n) => n as i64,
        KeyTime::Seconds(t) => fps.nearest_frame(t),
    };
    let first: Vec<i64> = doc.tracks[0].keys.iter().map(frame).collect();
    let positions = doc.tracks.iter().any(|t| !t.translations.is_empty());
    let io = |e: std::io::Error| input_error(format!("{}: cannot write: {e}", doc.source));
    let mut sink: Box<dyn FrameSink> = match target {
        OutputFormat::Npz => {
            if let Some(i) = doc
                .tracks
                .iter()
                .position(|t| t.keys.iter().map(frame).ne(first.iter().copied()))
            {
                return Err(input_error(format!(
                    "tracks[{i}]: npz holds every track on the same frames (arrays of frames × \
                     tracks), but its frames differ from tracks[0]'s; write npy, csv or json"
                )));
            }
            let shape = NpzShape {
                frames: first.len() as u64,
                tracks: doc.tracks.len(),
                velocity: false,
                positions,
                tree: tree.is_some(),
            };
            let w = NpzWriter::new(out, style, fps, shape);
            Box::new(match tree {
                Some(tree) => w.with_tree(tree),
                None => w,
            })
        }
        _ => {
            let rows = doc.tracks.iter().map(|t| t.keys.len() as u64).sum();
            let w = NpyWriter::new(out, style, rows, doc.tracks.len() > 1, false);
            Box::new(if positions { w.with_positions() } else { w })
        }
    };
    for t in &doc.tracks {
        sink.begin_track(t.name.as_deref()).map_err(io)?;
        for (i, k) in t.keys.iter().enumerate() {
            let n = frame(k);
            let time = fps.time_of(n);
            match t.translations.get(i).copied().flatten() {
                Some(p) => sink.frame_at(n, time, k.rot, None, p),
                None => sink.frame(n, time, k.rot, None),
            }
            .map_err(io)?;
        }
        sink.end_track().map_err(io)?;
    }
    sink.finish().map_err(io)
}
