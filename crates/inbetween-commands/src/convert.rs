//! `inbetween convert`: keys in, the same keys out in another representation and/or format.

use super::settings::{files_read, key_rate_warning, output_format, rates, read_input};
use crate::args::ConvertArgs;
use crate::events::Events;
use inbetween::{Error, InputError};
use inbetween_io::clip::Clip;
use inbetween_io::document::Document;
use inbetween_io::gltf::document::Mode;
use inbetween_io::write::write_keys;
use inbetween_io::{Format, OutputFormat};
use std::io::Read;
use std::path::PathBuf;
use std::sync::Arc;

/// `convert … --skeleton clip.bvh -o out.bvh`: the keys as the motion of the skeleton (of the
/// input itself when it is BVH).
fn write_bvh(
    args: &ConvertArgs,
    doc: &Document,
    template: Option<Arc<Clip>>,
    fps: inbetween::Fps,
    reads: &[PathBuf],
) -> Result<(), Error> {
    let skeleton = match (template, &doc.skeleton) {
        (Some(t), _) => t,
        (None, Some(own)) => own.clone(),
        (None, None) => {
            return Err(InputError::new(format!(
                "{}: BVH output needs a skeleton: --skeleton clip.bvh (its hierarchy and channel \
                 orders)",
                doc.source
            ))
            .into());
        }
    };
    let mut out = crate::output::open_output(args.output.output.as_deref(), reads)?;
    inbetween_io::bvh::keys::write_keys(&mut out, doc, &skeleton, fps, args.output.euler_mode())?;
    out.commit()?;
    Ok(())
}

/// Runs `convert`. Keys must be finite with strictly increasing times per track; unlike
/// `interp`, a track of one key is fine.
pub fn run(args: &ConvertArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    crate::settings::check_output_name(&args.output)?;
    let (doc, in_format, gltf) =
        read_input(&args.input, args.fps, (Mode::Keys, true), stdin, warn)?;
    let reads = files_read(&args.input, &[args.skeleton.as_deref()], gltf.as_deref());
    let template = args
        .skeleton
        .as_deref()
        .map(super::skeleton::read)
        .transpose()?;
    // Frames of keys that declare no rate, with no --fps, are at the skeleton's Frame Time: the
    // rate the clip they came from was captured at.
    let fps = args.fps.or(template.as_ref().map(|t| t.fps()));
    crate::record::note(|s| {
        let keys: usize = doc.tracks.iter().map(|t| t.keys.len()).sum();
        s.tracks = Some(doc.tracks.len());
        s.frames = Some(keys as u64);
        s.keys = Some(keys);
    });
    let (frame_fps, _) = rates(&doc, fps);
    for track in &doc.tracks {
        doc.track_times(track, frame_fps, 1)?;
    }
    // Frame numbers read at the default rate, unasked: the rate is written out (JSON "fps", or
    // times converted from frames), so say which.
    if fps.is_none()
        && let Some(w) = key_rate_warning(&doc, frame_fps)
    {
        warn.warning(&w.replace("at the output rate, ", "at the default rate, "));
    }
    let chosen = match (output_format(&args.output, in_format), in_format) {
        // Keys of a BVH input default to JSON (tracks = joints, with translations).
        (OutputFormat::Bvh, Format::Bvh)
            if args.output.output_format.is_none() && args.output.output.is_none() =>
        {
            OutputFormat::Doc(Format::Json)
        }
        // --skeleton writes BVH unless another format is asked for.
        (OutputFormat::Doc(_), _)
            if args.skeleton.is_some()
                && args.output.output_format.is_none()
                && args.output.output.is_none() =>
        {
            OutputFormat::Bvh
        }
        // A USD input's keys default to JSON too.
        (OutputFormat::Usda, Format::Usd)
            if args.output.output_format.is_none() && args.output.output.is_none() =>
        {
            OutputFormat::Doc(Format::Json)
        }
        // An AMASS input's keys default to JSON (tracks = joints, the pelvis' with `trans`).
        (OutputFormat::Npz, Format::Amass)
            if args.output.output_format.is_none() && args.output.output.is_none() =>
        {
            OutputFormat::Doc(Format::Json)
        }
        // A glTF input's keys default to JSON (tracks = rotation channels).
        (OutputFormat::Gltf(_), Format::Gltf)
            if args.output.output_format.is_none() && args.output.output.is_none() =>
        {
            OutputFormat::Doc(Format::Json)
        }
        (f, _) => f,
    };
    if args.skeleton.is_some() {
        super::skeleton::check_output(chosen)?;
    }
    let format = match chosen {
        OutputFormat::Doc(f) => f,
        OutputFormat::Bvh => return write_bvh(args, &doc, template, frame_fps, &reads),
        OutputFormat::Usda => {
            let mut out = crate::output::open_output(args.output.output.as_deref(), &reads)?;
            inbetween_io::usd::keys::write_keys(&mut out, &doc, frame_fps)?;
            out.commit()?;
            return Ok(());
        }
        OutputFormat::Fbx if let Some(t) = &template => {
            // On --skeleton: the template's joints, each found by its track's name as for BVH.
            let tracks: Vec<_> = doc
                .tracks
                .iter()
                .map(|t| {
                    (
                        t.name.as_deref(),
                        t.translations.iter().any(Option::is_some),
                    )
                })
                .collect();
            let named = args.skeleton.as_deref().map(|p| p.display().to_string());
            let label = named.as_deref().unwrap_or(&doc.source);
            let order = super::skeleton::joint_order(t, &tracks, &doc.source, label)?;
            let mut out = crate::output::open_output(args.output.output.as_deref(), &reads)?;
            inbetween_io::fbx::keys::write_keys_on(&mut out, &doc, t, &order, frame_fps)?;
            out.commit()?;
            return Ok(());
        }
        OutputFormat::Fbx => {
            let mut out = crate::output::open_output(args.output.output.as_deref(), &reads)?;
            inbetween_io::fbx::keys::write_keys(&mut out, &doc, frame_fps)?;
            out.commit()?;
            return Ok(());
        }
        OutputFormat::Gltf(_) => {
            return Err(InputError::new(
                "convert does not write glTF; resample a glTF asset's rotation channels into \
                 glTF with interp",
            )
            .into());
        }
        OutputFormat::Npy | OutputFormat::Npz => {
            let name = if chosen == OutputFormat::Npy {
                "npy"
            } else {
                "npz"
            };
            let what = match (&args.output.output_format, &args.output.output) {
                (None, Some(path)) => format!("-o {}", path.display()),
                _ => format!("--output-format {name}"),
            };
            return Err(InputError::new(format!(
                "{what}: convert writes keyframe documents (csv or json); {name} is for interp's \
                 frames"
            ))
            .into());
        }
    };
    if format == Format::Csv
        && doc
            .tracks
            .iter()
            .any(|t| t.start_velocity.is_some() || t.end_velocity.is_some())
    {
        warn.warning("CSV has no place for start_velocity/end_velocity; they are not written");
    }
    if format == Format::Csv
        && let Some(w) = super::settings::csv_rate_warning(&doc, in_format, doc.skeleton.is_some())
    {
        warn.warning(&w);
    }
    let style = super::settings::style(&args.input, &args.output);
    let mut out = crate::output::open_output(args.output.output.as_deref(), &reads)?;
    write_keys(&mut out, &doc, format, style, frame_fps)?;
    out.commit()?;
    Ok(())
}
