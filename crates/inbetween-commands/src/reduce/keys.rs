//! `reduce`'s kept keys as the output's document: its format, style and scheme, written.

use crate::args::ReduceArgs;
use crate::events::Events;
use crate::settings::output_format;
use inbetween::reduce::Reduced;
use inbetween::{Error, EulerSeq, Fps, InputError, PathMode, Repr, Scheme};
use inbetween_io::document::{DocTrack, Document, KeyOrigin};
use inbetween_io::write::write_keys;
use inbetween_io::write::{EulerMode, Style};
use inbetween_io::{Format, OutputFormat};
use std::path::PathBuf;

/// The output format of the keys for an input in `input` format: a keys document (CSV, JSON),
/// or glTF; a BVH input's keys default to JSON (on standard output, or to an `-o` whose name
/// does not say bvh: `-o keys`, `/dev/null`); npy and BVH are refused.
pub(super) fn keys_format(args: &ReduceArgs, input: Format) -> Result<OutputFormat, Error> {
    Ok(match output_format(&args.output, input) {
        OutputFormat::Bvh
            if args.output.output_format.is_none()
                && !args.output.output.as_deref().is_some_and(|p| {
                    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("bvh"))
                }) =>
        {
            OutputFormat::Doc(Format::Json)
        }
        f @ (OutputFormat::Gltf(_) | OutputFormat::Doc(_)) => f,
        OutputFormat::Usda => {
            if scheme(args, input) != Scheme::Slerp {
                return Err(InputError::new(
                    "--scheme: USD plays its samples by slerp (rotations) and linearly \
                     (translations), so keys reduced for another scheme would not play within \
                     the tolerance; use --scheme slerp (the default for USD output)",
                )
                .into());
            }
            if args.output.precision.is_some() {
                return Err(InputError::new(
                    "--precision: USD stores its values as float32, and reduce already tightens \
                     the tolerances by that rounding; drop --precision for .usda output",
                )
                .into());
            }
            if !args.shared_keys {
                return Err(InputError::new(
                    "USD samples every joint at the same times: give --shared-keys (the fewest \
                     key times shared by every track)",
                )
                .into());
            }
            OutputFormat::Usda
        }
        OutputFormat::Fbx => {
            let refused = if args.position_tolerance.is_some() {
                Some((
                    "--position-tolerance",
                    "FBX output verifies each joint's rotation (--tolerance) and translation \
                     (--translation-tolerance) as FBX plays them, not world positions",
                ))
            } else if args.distance.is_some() {
                Some((
                    "--distance",
                    "FBX output verifies each joint's rotation as an angle (--tolerance)",
                ))
            } else if args.output.precision.is_some() {
                Some(("--precision", "FBX stores its keys as float32"))
            } else {
                None
            };
            if let Some((flag, why)) = refused {
                return Err(InputError::new(format!("{flag}: {why}")).into());
            }
            OutputFormat::Fbx
        }
        other => {
            let name = match other {
                OutputFormat::Npy => "npy",
                OutputFormat::Npz => "npz",
                _ => "bvh (it holds every frame)",
            };
            return Err(InputError::new(format!(
                "reduce writes keys: csv, json, or glTF for a glTF input, not {name}"
            ))
            .into());
        }
    })
}

/// A track's kept keys as the input gave them (frame numbers or times, Euler angles,
/// positions), with their velocities.
pub(super) fn kept(d: &DocTrack, r: &Reduced) -> DocTrack {
    DocTrack {
        name: d.name.clone(),
        keys: r.keys.iter().map(|&i| d.keys[i]).collect(),
        start_velocity: None,
        end_velocity: None,
        origin: KeyOrigin::Frames,
        euler: d
            .euler
            .as_ref()
            .map(|(seq, a)| (*seq, r.keys.iter().map(|&i| a[i]).collect())),
        velocities: r
            .velocities
            .as_ref()
            .map(|w| w.iter().copied().map(Some).collect())
            .unwrap_or_default(),
        tcb: Vec::new(),
        translations: if d.translations.is_empty() {
            Vec::new()
        } else {
            r.keys.iter().map(|&i| d.translations[i]).collect()
        },
    }
}

/// Writes the kept keys `doc` in `format` and `style`, frame numbers at `frame_fps`; `input`
/// is the input's format and whether its keys come from a BVH clip, for CSV's rate warning.
pub(super) fn write(
    args: &ReduceArgs,
    doc: &Document,
    (format, style, frame_fps): (Format, Style, Fps),
    (input, skeleton): (Format, bool),
    reads: &[PathBuf],
    warn: &mut dyn Events,
) -> Result<(), Error> {
    if format == Format::Csv
        && let Some(w) = crate::settings::csv_rate_warning(doc, input, skeleton)
    {
        warn.warning(&w);
    }
    let mut out = crate::output::open_output(args.output.output.as_deref(), reads)?;
    if output_format(&args.output, input) == OutputFormat::Usda {
        inbetween_io::usd::keys::write_keys(&mut out, doc, frame_fps)?;
    } else if output_format(&args.output, input) == OutputFormat::Fbx {
        inbetween_io::fbx::keys::write_keys(&mut out, doc, frame_fps)?;
    } else {
        write_keys(&mut out, doc, format, style, frame_fps)?;
    }
    out.commit()?;
    Ok(())
}

/// The written keys' style. With `--path euler` a key's turns are in its Euler angles, so the
/// keys are written as the input gave them: its sequence (`--to` may only name it), each key's
/// own triple ([`EulerMode::AsGiven`]).
pub(super) fn keys_style(
    args: &ReduceArgs,
    path: PathMode,
    tracks: &[inbetween::Track],
    source: &str,
) -> Result<Style, Error> {
    let mut style = crate::settings::style(&args.input, &args.output);
    if path != PathMode::Euler {
        return Ok(style);
    }
    let mut seqs: Vec<EulerSeq> = Vec::new();
    for seq in tracks
        .iter()
        .filter_map(|t| t.euler_angles().map(|(seq, _)| seq))
    {
        if !seqs.contains(&seq) {
            seqs.push(seq);
        }
    }
    let [seq] = seqs[..] else {
        let names: Vec<String> = seqs.iter().map(|&s| Repr::Euler(s).to_string()).collect();
        return Err(InputError::new(format!(
            "{source}: --path euler writes the keys as the input's Euler angles, in one \
             sequence, but the tracks have {}; reduce them apart or use --path shortest",
            names.join(", ")
        ))
        .into());
    };
    match style.repr {
        Repr::Quat => {}
        Repr::Euler(s) if s == seq => {}
        other => {
            return Err(InputError::new(format!(
                "--to {other}: with --path euler the keys keep their turns in their Euler angles, \
                 so they are written as the input gave them ({})",
                Repr::Euler(seq)
            ))
            .into());
        }
    }
    style.repr = Repr::Euler(seq);
    style.euler = EulerMode::AsGiven;
    Ok(style)
}

/// The scheme of the keys: `--scheme`, else slerp for glTF output (its `LINEAR` samplers play
/// by slerp), else bezier; `input` is the input's format, which glTF output needs.
pub(super) fn scheme(args: &ReduceArgs, input: Format) -> Scheme {
    match (args.scheme, output_format(&args.output, input)) {
        (Some(s), _) => s.into(),
        (None, OutputFormat::Gltf(_) | OutputFormat::Usda | OutputFormat::Fbx) => Scheme::Slerp,
        (None, _) => Scheme::Bezier,
    }
}
