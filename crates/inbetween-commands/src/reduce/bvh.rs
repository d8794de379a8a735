//! `reduce clip.bvh`'s lean path: the clip read in pieces into its values
//! ([`bvh::parse_reader`]), then one joint at a time (the joints shared among the cores) its
//! track built, reduced and dropped, only its kept keys held (see docs/performance.md). The
//! general path holds the file's text, the clip, a document of every key and the tracks made
//! from it at once: 6 to 9 times the file.

use super::keys::{kept, keys_format, scheme, write};
use super::report::report;
use super::tracks::reduce_options;
use crate::args::ReduceArgs;
use crate::events::Events;
use crate::settings::{curve_options, lean_bvh_clip, lean_bvh_path, tcb_flags};
use inbetween::Error;
use inbetween::reduce::{Reduced, TrackFrames, reduce_frames};
use inbetween_io::bvh::{document::joint_tracks, resample};
use inbetween_io::document::{DocTrack, Document};
use inbetween_io::{Format, OutputFormat};

/// One joint's result: its kept keys as read, what it was reduced to, its name and frames.
type JointDone = Result<(DocTrack, Reduced, Option<String>, usize), Error>;

/// `reduce` of a BVH file, one joint at a time, with exactly the general path's output,
/// warnings and errors. `None` when it does not apply — standard input, an option it does not
/// handle (`--tracks`, `--from`, `--animation`, `--snap-keys`, `--path euler`, end velocities,
/// `--shared-keys`, `--position-tolerance`), or anything wrong with the input or the options, which the general path
/// then reads again and reports exactly as always (nothing has been written: the keys are
/// written once every joint is done). Its warnings are held until it is done, so they are given
/// once, in the general path's order.
pub fn lean(args: &ReduceArgs, warn: &mut dyn Events) -> Option<Result<(), Error>> {
    let curve = &args.curve;
    let path = lean_bvh_path(&args.input, curve)?;
    if args.input.tracks.is_some()
        || args.shared_keys
        || args.scale_tolerance.is_some()
        || args.output.precision.is_some()
        || args.position_tolerance.is_some()
    {
        return None;
    }
    let OutputFormat::Doc(format) = keys_format(args, Format::Bvh).ok()? else {
        return None;
    };
    let (source, clip, warnings) = lean_bvh_clip(path, &args.input, None)?;
    let joints = resample::track_joints(&clip);
    let positions = joints
        .iter()
        .any(|&j| clip.joints()[j].position().is_some());
    if joints.is_empty() || (positions && args.translation_tolerance.is_none()) {
        return None;
    }
    // The general path's rates: frames at the clip's, the output (minaccel's grid) at --fps.
    let frame_fps = clip.fps();
    let fps = curve.fps.unwrap_or(frame_fps);
    resample::span(&clip).filter(|(a, b)| fps.in_range(*a) && fps.in_range(*b))?;
    let curves = curve_options(curve, scheme(args, Format::Bvh), fps, args.input.angles);
    let opts = reduce_options(args, curves, (0.0, 0.0), true).ok()?;
    let tcb = tcb_flags(curve);
    let done: Vec<JointDone> = inbetween::parallel::map(&joints, |&j| {
        let joint = &clip.joints()[j];
        let Some((doc_track, track)) = joint_tracks(&clip, joint, &source, tcb)? else {
            unreachable!("a track joint has a track");
        };
        let reduced = reduce_frames(&TrackFrames::of(&track), &opts)?;
        let name = track.name().map(str::to_string);
        Ok((kept(&doc_track, &reduced), reduced, name, track.len()))
    });
    let mut tracks = Vec::with_capacity(done.len());
    let mut reports = Vec::with_capacity(done.len());
    for d in done {
        match d {
            Ok((t, r, name, len)) => {
                tracks.push(t);
                reports.push((name, len, r));
            }
            // The general path reports it, located as always.
            Err(Error::Input(_)) => return None,
            Err(e) => return Some(Err(e)),
        }
    }
    let doc = Document {
        fps: Some(frame_fps),
        scheme: Some(curves.scheme),
        tracks,
        named_tracks: true,
        ..Document::new(source.clone())
    };
    for w in &warnings {
        warn.warning(w);
    }
    super::report::note_batch(args, reports.iter().map(|(_, len, r)| (*len, r)));
    if args.verbose {
        for (name, len, r) in &reports {
            report(args, name.as_deref(), *len, r, warn);
        }
    }
    let style = crate::settings::style(&args.input, &args.output);
    Some(write(
        args,
        &doc,
        (format, style, frame_fps),
        (Format::Bvh, true),
        &crate::settings::files_read(&args.input, &[], None),
        warn,
    ))
}
