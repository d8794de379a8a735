//! `inbetween reduce`: dense frames in, the fewest keys out that `interp` turns back into them
//! (the library's [`inbetween::reduce`]).

mod bvh;
mod fbx;
mod gltf;
mod keys;
mod report;
mod rounded;
mod tracks;
mod world;

use crate::args::ReduceArgs;
use crate::events::Events;
use crate::settings::{rates, read_curves_in, tracks_take_translations};
use inbetween::reduce::Reduced;
use inbetween::{Error, InputError};
use inbetween_io::document::Document;
use inbetween_io::gltf::document::Mode;
use inbetween_io::write::write_keys;
use inbetween_io::{Format, OutputFormat};
use keys::{kept, keys_format, keys_style, scheme, write};
use report::report_all;
use std::io::Read;
use tracks::{FLOAT32_MARGIN, reduce_tracks};

/// How much tighter than `--tolerance` FBX keys are verified (rad): the player's time fractions
/// are computed from integer ticks, which differ from the frames' exact times by under a tick.
const FBX_SLACK: f64 = 1e-9;

/// The options a request needs with others (the command line's parser refuses these first; a
/// request built by keyword meets them here).
fn needs(args: &ReduceArgs) -> Result<(), Error> {
    if args.tolerance.is_none() && args.position_tolerance.is_none() {
        return Err(InputError::new("reduce needs --tolerance or --position-tolerance").into());
    }
    let without = |set: bool, name: &str| {
        if set && args.position_tolerance.is_none() {
            Err(InputError::new(format!("{name} needs --position-tolerance")).into())
        } else {
            Ok(())
        }
    };
    without(args.shell.is_some(), "--shell")?;
    without(!args.joint_tolerance.is_empty(), "--joint-tolerance")
}

/// Runs `reduce`: every track reduced (or all on shared keys), verified, written as keys.
pub fn run(args: &ReduceArgs, stdin: &mut dyn Read, warn: &mut dyn Events) -> Result<(), Error> {
    crate::settings::check_output_name(&args.output)?;
    needs(args)?;
    if let Some(done) = bvh::lean(args, warn) {
        return done;
    }
    let gltf_output = !tracks_take_translations(&args.output);
    world::check_options(args, gltf_output)?;
    // A position tolerance poses the skeleton with the tracks' translations, even where the
    // output keeps them.
    let input = read_curves_in(
        (
            // World space poses the skeleton at each time: glTF channels on one set of times.
            if args.position_tolerance.is_some() {
                Mode::Posed
            } else {
                Mode::Frames
            },
            !gltf_output || args.position_tolerance.is_some(),
        ),
        &args.input,
        &args.curve,
        &|f, _| scheme(args, f),
        stdin,
        warn,
    )?;
    let (doc, tracks) = (&input.doc, &input.tracks);
    let format = match keys_format(args, input.format)? {
        OutputFormat::Gltf(container) => {
            return gltf::to_gltf(args, &input, container, warn);
        }
        OutputFormat::Doc(f) => f,
        // USD keys are written from the kept keys as JSON's are (`write` sends them to USD).
        OutputFormat::Usda => Format::Json,
        // FBX keys likewise, refined until FBX's per-channel playback is verified (`fbx`).
        OutputFormat::Fbx => Format::Json,
        _ => unreachable!("keys_format gives keys documents, glTF and USD"),
    };
    if let Some(s) = args.scale_tolerance {
        return Err(InputError::new(format!(
            "--scale-tolerance {s}: only glTF output (-o small.glb from a glTF input) has scale \
             channels to reduce; csv and json keys carry rotations and translations"
        ))
        .into());
    }
    if tracks.iter().any(|t| t.translations().is_some())
        && args.translation_tolerance.is_none()
        && args.position_tolerance.is_none()
    {
        return Err(InputError::new(format!(
            "{}: the tracks have translations: give their tolerance with --translation-tolerance \
             (length units)",
            doc.source
        ))
        .into());
    }
    let (frame_fps, _) = rates(doc, args.curve.fps);
    let style = keys_style(args, input.opts.path, tracks, &doc.source)?;
    // The kept keys, as the input gave them (frame numbers or times, Euler angles, positions).
    let doc_of = |reduced: &[Reduced]| Document {
        fps: doc.fps,
        rotation: doc.rotation,
        // The scheme the keys were verified under: a JSON document records it, so that
        // interp and diff play them that way.
        scheme: Some(input.opts.scheme),
        tracks: doc
            .tracks
            .iter()
            .zip(reduced)
            .map(|(d, r)| kept(d, r))
            .collect(),
        named_tracks: doc.named_tracks,
        hierarchy: doc.hierarchy.clone(),
        unit_meters: doc.unit_meters,
        z_up: doc.z_up,
        ..Document::new(doc.source.clone())
    };
    // USD stores float32 rotations and translations: the tolerances are tightened by what that
    // rounding can move a key (as for glTF output).
    let to_fbx = keys_format(args, input.format)? == OutputFormat::Fbx;
    let margin = if keys_format(args, input.format)? == OutputFormat::Usda || to_fbx {
        let largest = tracks
            .iter()
            .filter_map(|t| t.translations())
            .flatten()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        (FLOAT32_MARGIN, largest * f32::EPSILON as f64)
    } else {
        (0.0, 0.0)
    };
    let reduced = match args.output.precision {
        None => reduce_tracks(args, &input, margin, (true, false), warn)?,
        Some(_) => {
            let encode = |r: &[Reduced]| -> Result<Vec<u8>, Error> {
                let mut bytes = Vec::new();
                write_keys(&mut bytes, &doc_of(r), format, style, frame_fps)?;
                Ok(bytes)
            };
            rounded::as_written(args, &input, (format, style, frame_fps), &encode, warn)?
        }
    };
    let reduced = if to_fbx {
        let bounds = fbx::Bounds {
            rotation: args.input.angles.to_rad(args.tolerance.unwrap_or(180.0)) - FBX_SLACK,
            translation: args.translation_tolerance,
        };
        fbx::refine(doc, tracks, reduced, &bounds, args.shared_keys, frame_fps)?
    } else {
        reduced
    };
    report_all(args, &input, &reduced, warn);
    let out_doc = doc_of(&reduced);
    let skeleton = doc.skeleton.is_some();
    write(
        args,
        &out_doc,
        (format, style, frame_fps),
        (input.format, skeleton),
        &input.reads,
        warn,
    )
}
