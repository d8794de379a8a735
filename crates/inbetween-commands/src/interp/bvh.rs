//! The lean path of `interp` for a BVH file: the file read in pieces into its motion values
//! only ([`bvh::parse_reader`](inbetween_io::bvh::parse_reader)), then one joint's track and
//! curve at a time ([`resample`]), into BVH, CSV, JSON, npy or npz output; see
//! docs/performance.md. `--tracks` chooses joints as the file is read (only their values are
//! kept: [`inbetween_io::bvh::chosen`]), so that a few tracks never cost more than all of them
//! (the general path holds a document of every key, and the tracks, and the curves).

use super::{near_misses, npz_fits};
use crate::args::{InterpArgs, SpanArg};
use crate::events::Events;
use crate::output::WriteBehind;
use crate::played;
use crate::settings::{
    chosen_tracks, curve_options, lean_bvh_clip, lean_bvh_path, output_format, tcb_flags,
};
use inbetween::{BakeOptions, Error, FrameSink};
use inbetween_io::bvh::chosen::Choose;
use inbetween_io::bvh::resample;
use inbetween_io::clip::Clip;
use inbetween_io::write::npz::Tree;
use inbetween_io::write::{EulerMode, FrameWriter, NpyWriter, NpzShape, NpzWriter};
use inbetween_io::{Format, OutputFormat};

/// `interp` of a BVH file through the lean path. `None` when it does not apply — an option it
/// does not handle, or anything wrong with the input or the options, which the general path
/// then reads again and reports exactly as always (nothing has been written: BVH and npz output
/// are written after every joint is done; CSV, JSON and npy only into a temporary `-o` file).
/// Its warnings are held until it is done, so they are given once, in the general path's order.
pub(super) fn lean(args: &InterpArgs, warn: &mut dyn Events) -> Option<Result<(), Error>> {
    let curve = &args.curve;
    let path = lean_bvh_path(&args.input, curve)?;
    let format = output_format(&args.output, Format::Bvh);
    let bvh_out = format == OutputFormat::Bvh;
    if args.skeleton.is_some()
        || args.verbose
        || args.span != SpanArg::Clip
        // BVH output: continuous Euler angles only, no velocities, every joint (the general
        // path refuses the last two).
        || (bvh_out
            && (args.output.euler_mode() == EulerMode::Wrapped
                || args.velocity
                || args.input.tracks.is_some()))
    {
        return None;
    }
    let to_file =
        args.output.output.as_deref().is_some_and(|p| {
            p.as_os_str() != "-" && !p.starts_with("/dev") && !p.starts_with("/proc")
        });
    match format {
        OutputFormat::Bvh | OutputFormat::Npz => {}
        OutputFormat::Doc(Format::Csv | Format::Json) | OutputFormat::Npy if to_file => {}
        _ => return None,
    }
    // --tracks: only the chosen joints' values are read (a pattern that matches none is the
    // general path's to report).
    let source = path.display().to_string();
    let patterns = args.input.tracks.as_deref();
    let choose = |names: &[String]| chosen_tracks(names, patterns.unwrap_or(""), &source);
    let choose = patterns.map(|_| &choose as Choose);
    let (source, clip, mut warnings) = lean_bvh_clip(path, &args.input, choose)?;
    let joints = resample::track_joints(&clip);
    let fps = curve.fps.unwrap_or(clip.fps());
    let span = resample::span(&clip).filter(|(a, b)| fps.in_range(*a) && fps.in_range(*b))?;
    let frames = fps.frame_count(span.0, span.1);
    let rows = frames.saturating_mul(joints.len() as u64);
    if joints.is_empty() || rows > args.max_frames {
        return None;
    }
    let style = crate::settings::style(&args.input, &args.output);
    let positions = joints
        .iter()
        .any(|&j| clip.joints()[j].position().is_some());
    // npz: the general path's shape, tree and checks (a failed check is its to report).
    let npz = match format {
        OutputFormat::Npz => {
            // The chosen joints are the clip's tracks: its skeleton's tree is theirs.
            let tree = Tree::of(&clip.skeleton(), joints.len());
            let shape = NpzShape {
                frames,
                tracks: joints.len(),
                velocity: args.velocity,
                positions,
                tree: tree.is_some(),
            };
            let longest = joints
                .iter()
                .map(|&j| clip.joints()[j].track_name().chars().count())
                .max()
                .unwrap_or(0);
            npz_fits(shape, longest, style.repr.width(), &source).ok()?;
            Some((shape, tree))
        }
        _ => None,
    };
    crate::record::note(|s| {
        s.frames = Some(rows);
        s.tracks = Some(joints.len());
    });
    let mut missed = crate::events::Collected::default();
    for &j in &joints {
        let name = Some(clip.joints()[j].track_name());
        near_misses(&source, name, span, span, fps, &mut missed);
    }
    warnings.extend(missed.warnings);
    let opts = resample::Options {
        fps,
        curve: curve_options(
            curve,
            played::scheme(args.scheme, Format::Bvh, None),
            fps,
            args.input.angles,
        ),
        tcb: tcb_flags(curve),
        threads: 0,
        bake: BakeOptions {
            velocity: args.velocity,
            // As the general path: two generating threads where writing is cheap.
            parallel: matches!(format, OutputFormat::Npy | OutputFormat::Npz),
        },
    };
    let reads = crate::settings::files_read(&args.input, &[args.skeleton.as_deref()], None);
    let open = || -> Result<WriteBehind, Error> {
        let out = crate::output::open_output(args.output.output.as_deref(), &reads)?;
        Ok(WriteBehind::new(out))
    };
    let baked = Baked {
        clip: &clip,
        joints: &joints,
        source: &source,
        opts: &opts,
        span,
    };
    let done = (|| -> Result<Option<()>, Error> {
        let mut add = |m: &inbetween::error::Message| warnings.push(crate::flags::say(m));
        match format {
            OutputFormat::Bvh => {
                let (frames, baked) = match resample::resample(&clip, &source, &opts) {
                    Err(Error::Input(_)) => return Ok(None),
                    r => r?,
                };
                baked.iter().for_each(&mut add);
                frames.write(open()?, &clip)?.finish()?.commit()?;
            }
            OutputFormat::Doc(doc_format) => {
                let w = FrameWriter::new(open()?, doc_format, style, fps, true, args.velocity);
                let mut w = if positions { w.with_positions() } else { w };
                if baked.bake_into(&mut w, &mut add)?.is_none() {
                    return Ok(None);
                }
                w.into_inner().finish()?.commit()?;
            }
            OutputFormat::Npy => {
                let w = NpyWriter::new(open()?, style, rows, true, args.velocity);
                let mut w = if positions { w.with_positions() } else { w };
                if baked.bake_into(&mut w, &mut add)?.is_none() {
                    return Ok(None);
                }
                w.into_inner().finish()?.commit()?;
            }
            OutputFormat::Npz => {
                let (shape, tree) = npz.ok_or_else(|| internal("npz shape"))?;
                let w = NpzWriter::new(open()?, style, fps, shape);
                let mut w = match tree {
                    Some(tree) => w.with_tree(tree),
                    None => w,
                };
                if baked.bake_into(&mut w, &mut add)?.is_none() {
                    return Ok(None);
                }
                w.into_inner()?.finish()?.commit()?;
            }
            _ => return Err(internal("output format")),
        }
        Ok(Some(()))
    })();
    match done {
        Ok(None) => None,
        Ok(Some(())) => {
            for w in &warnings {
                warn.warning(w);
            }
            Some(Ok(()))
        }
        Err(e) => Some(Err(e)),
    }
}

/// The chosen joints of a clip, to be baked into a frame writer.
struct Baked<'a> {
    clip: &'a Clip,
    joints: &'a [usize],
    source: &'a str,
    opts: &'a resample::Options,
    span: (f64, f64),
}

impl Baked<'_> {
    /// Bakes every joint into `sink` and finishes it; `Ok(None)` on an input error (the general
    /// path's to report: nothing has been committed).
    fn bake_into(
        &self,
        sink: &mut dyn FrameSink,
        add: &mut dyn FnMut(&inbetween::error::Message),
    ) -> Result<Option<()>, Error> {
        let (clip, joints, source) = (self.clip, self.joints, self.source);
        match resample::bake_tracks(clip, joints, source, self.opts, self.span, sink, add) {
            Err(Error::Input(_)) => return Ok(None),
            r => r?,
        }
        sink.finish()?;
        Ok(Some(()))
    }
}

fn internal(what: &str) -> Error {
    Error::Io(std::io::Error::other(format!(
        "internal error: interp's lean BVH path: no {what}"
    )))
}
