//! What the subcommands share: reading the input (every command through [`read_input`], so
//! that the one precedence rule between a document's declarations and the flags,
//! [`inbetween_io::settle`], applies to all of them), the rate rule (a document's `fps`, or
//! `--key-fps` standing in for it, numbers its `frame` values; `--fps` sets the output rate,
//! else the document's, else 30), and the curve options from the command line.

use crate::args::{
    BlendArg, CurveArgs, EndsArg, InputArgs, OutputArgs, PathArg, SchemeArg, TangentArg,
};
use crate::events::Events;
use glam::DVec3;
use inbetween::curve::piecewise::MAX_SPEED;
use inbetween::error::num;
use inbetween::rotation::{AngleUnit, Repr};
use inbetween::{
    Blend, CurveOptions, EndConditions, Ends, Fps, InputError, PathMode, Scheme, TangentRule, Tcb,
    Track,
};
use inbetween_io::document::{Document, KeyTime};
use inbetween_io::gltf::document::{GltfClip, Mode};
use inbetween_io::gltf::{Asset, ContainerFormat};
use inbetween_io::write::Style;
use inbetween_io::{Format, OutputFormat, ReadOptions};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl From<SchemeArg> for Scheme {
    fn from(s: SchemeArg) -> Scheme {
        match s {
            SchemeArg::Hermite => Scheme::Hermite,
            SchemeArg::Squad => Scheme::Squad,
            SchemeArg::Bezier => Scheme::Bezier,
            SchemeArg::Slerp => Scheme::Slerp,
            SchemeArg::Nlerp => Scheme::Nlerp,
            SchemeArg::Minaccel => Scheme::MinAccel,
        }
    }
}

/// The rates of a document: `(frame_fps, output_fps)`. A document's `fps` (declared, or given
/// by `--key-fps`, which stands in for a missing declaration) numbers its `frame` values; `--fps`
/// sets the output rate. Each falls back to the other, then to 30.
pub fn rates(doc: &Document, fps_arg: Option<Fps>) -> (Fps, Fps) {
    let frame_fps = doc.fps.or(fps_arg).unwrap_or(Fps::DEFAULT);
    let output_fps = fps_arg.or(doc.fps).unwrap_or(Fps::DEFAULT);
    (frame_fps, output_fps)
}

/// The warning for frame numbers read at the output rate because nothing gives their rate (the
/// document declares no `fps` and `--key-fps` is absent); `None` when no key is a frame number
/// or the rate is known.
pub fn key_rate_warning(doc: &Document, frame_fps: Fps) -> Option<String> {
    let framed = doc
        .tracks
        .iter()
        .any(|t| t.keys.iter().any(|k| matches!(k.when, KeyTime::Frame(_))));
    (doc.fps.is_none() && framed).then(|| {
        format!(
            "{}: frame numbers are read at the output rate, {frame_fps} fps, as the document \
             declares no rate; give the keys' rate with --key-fps RATE",
            doc.source
        )
    })
}

/// The warning for keys written to CSV as frame numbers whose rate the document has (a JSON
/// `"fps"`, a BVH Frame Time, `--key-fps`): CSV has no place for it. `None` when a key is at a
/// time in seconds (CSV then writes times) or the document has no rate to lose: a CSV input's
/// rate is the user's own `--key-fps`. `skeleton`: the keys come from a BVH clip, whose file
/// gives the rate back as `--skeleton`.
pub fn csv_rate_warning(doc: &Document, input: Format, skeleton: bool) -> Option<String> {
    let fps = doc.fps.filter(|_| input != Format::Csv)?;
    let all_frames = doc
        .tracks
        .iter()
        .flat_map(|t| &t.keys)
        .all(|k| matches!(k.when, KeyTime::Frame(_)));
    let or = if skeleton {
        " (or --skeleton with the BVH file, whose Frame Time is the rate)"
    } else {
        ""
    };
    all_frames.then(|| {
        format!(
            "CSV has no place for the rate: the frame numbers are written as they are, at {fps} \
             fps; read them back with --key-fps {fps}{or}"
        )
    })
}

/// Reads the whole input (a file, or `stdin` for `-`/none) and parses it into a document.
/// Warnings found while reading go to `warn`. A glTF input is read at `fps` (`--fps`, else 30:
/// its keys snap to that rate's frames and, for [`Mode::Frames`], its `STEP` and `CUBICSPLINE`
/// channels are baked at it), and its asset comes back for glTF output; without `translations`
/// (glTF output, which writes the translation channels itself) its tracks have none.
pub fn read_input(
    args: &InputArgs,
    fps: Option<Fps>,
    (mode, translations): (Mode, bool),
    stdin: &mut dyn Read,
    warn: &mut dyn Events,
) -> Result<(Document, Format, Option<Arc<GltfClip>>), inbetween::Error> {
    let opts = ReadOptions {
        from: args.from,
        angles: args.angles,
        input_angles: args.input_angles,
        key_fps: args.key_fps,
        quat_order: args.quat_order,
        delimiter: args.delimiter,
        columns: column_map(args)?,
    };
    let path = args.input.as_deref().filter(|p| p.as_os_str() != "-");
    let (bytes, source) = match path {
        Some(p) => (
            inbetween_io::read_bytes_limited(p, args.max_input_bytes)?,
            p.display().to_string(),
        ),
        None => (
            inbetween_io::read_limited(stdin, args.max_input_bytes, "<stdin>")?,
            "<stdin>".to_string(),
        ),
    };
    let (doc, format, clip) = if inbetween_io::is_gltf(&bytes, path, args.input_format) {
        let dir = path.map(inbetween_io::gltf_dir);
        let asset =
            Asset::from_slice_limited(&bytes, &source, dir.as_deref(), args.max_input_bytes)?;
        let mut clip = GltfClip::new(asset, args.animation.as_deref())?;
        if !translations {
            clip = clip.without_translations();
        }
        let doc = clip.document(fps.unwrap_or(Fps::DEFAULT), mode)?;
        (doc, Format::Gltf, Some(Arc::new(clip)))
    } else if inbetween_io::is_fbx_input(&bytes, path, args.input_format) {
        let doc = inbetween_io::read_fbx(&bytes, &source, args.animation.as_deref())?;
        (doc, Format::Fbx, None)
    } else {
        if args.animation.is_some() {
            return Err(InputError::new(format!(
                "--animation: {source} is neither glTF nor FBX; only a glTF asset's animations \
                 and an FBX scene's animation stacks can be chosen"
            ))
            .into());
        }
        let (doc, format) =
            inbetween_io::parse_bytes(bytes, &source, path, args.input_format, &opts)?;
        (doc, format, None)
    };
    if args.columns.is_some() && format != Format::Csv {
        return Err(inbetween_io::columns_refused(&source, format).into());
    }
    // A BVH joint declares its rotation order in CHANNELS and glTF stores quaternions: --from,
    // which says how CSV columns and JSON keys are written, would be silently ignored.
    if let (Some(r), Format::Bvh | Format::Gltf | Format::Fbx) = (args.from, format) {
        let what = match format {
            Format::Bvh => "a BVH file declares each joint's rotation order in its CHANNELS",
            Format::Fbx => "an FBX scene declares each node's rotation order",
            _ => "a glTF asset stores quaternions",
        };
        return Err(InputError::new(format!(
            "{source}: --from {r}: {what}; --from says how CSV and JSON keys are written"
        ))
        .into());
    }
    for w in &doc.warnings {
        warn.warning(w);
    }
    let doc = match &args.tracks {
        Some(patterns) => select_tracks(doc, patterns)?,
        None => doc,
    };
    Ok((doc, format, clip))
}

/// `--columns` with `--time-unit` and `--times` in it; either of those without `--columns` is an
/// error (they describe a log's stamps), and so is a `--from` other than quat (a log's columns
/// are a quaternion's).
fn column_map(args: &InputArgs) -> Result<Option<inbetween_io::read::log::ColumnMap>, InputError> {
    let Some(map) = &args.columns else {
        if args.time_unit.is_some() || args.times.is_some() {
            return Err(InputError::new(
                "--time-unit and --times describe the stamps of a log read with --columns; \
                 give --columns too (e.g. --columns tum)",
            ));
        }
        return Ok(None);
    };
    if let Some(r) = args.from.filter(|r| *r != Repr::Quat) {
        return Err(InputError::new(format!(
            "--from {r}: a log read with --columns holds quaternions (w, x, y, z)"
        )));
    }
    let mut map = map.clone();
    map.time_unit = args.time_unit.or(map.time_unit);
    map.times = args.times.unwrap_or(map.times);
    Ok(Some(map))
}

/// `--tracks`: the document's tracks whose names match one of the comma-separated patterns, in
/// document order. A pattern that matches nothing is an error listing the names there are.
fn select_tracks(mut doc: Document, patterns: &str) -> Result<Document, InputError> {
    let names: Vec<String> = doc
        .tracks
        .iter()
        .enumerate()
        .map(|(i, t)| t.name.clone().unwrap_or_else(|| format!("track{i}")))
        .collect();
    let keep = chosen_tracks(&names, patterns, &doc.source)?;
    if let Some(h) = &doc.hierarchy {
        doc.hierarchy = Some(Arc::new(h.retracked(&kept_indices(&keep))));
    }
    let mut i = 0;
    doc.tracks.retain(|_| {
        i += 1;
        keep[i - 1]
    });
    doc.named_tracks = true;
    Ok(doc)
}

/// Which of the tracks `names` (in document order; an unnamed track is `track<i>`) `--tracks
/// PATTERNS` chooses: a pattern that matches none, or no pattern, is an input error naming
/// `source`'s tracks. The rule of [`select_tracks`], for a reader that chooses before it
/// builds tracks (interp's lean BVH path).
pub(super) fn chosen_tracks(
    names: &[String],
    patterns: &str,
    source: &str,
) -> Result<Vec<bool>, InputError> {
    let patterns: Vec<&str> = patterns
        .split(',')
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .collect();
    for p in &patterns {
        if !names.iter().any(|n| glob(p, n)) {
            let shown: Vec<String> = names
                .iter()
                .take(20)
                .map(|n| format!("\"{}\"", inbetween::error::shorten(n)))
                .collect();
            let more = if names.len() > 20 { ", …" } else { "" };
            return Err(InputError::new(format!(
                "--tracks: \"{}\" matches no track of {source}; its tracks are {}{more}",
                inbetween::error::shorten(p),
                shown.join(", ")
            )));
        }
    }
    if patterns.is_empty() {
        return Err(InputError::new("--tracks: expected at least one name"));
    }
    Ok(names
        .iter()
        .map(|n| patterns.iter().any(|p| glob(p, n)))
        .collect())
}

/// Each track's index among the kept ones (`keep` from [`chosen_tracks`]), `None` for a track
/// left out: the map [`Skeleton::retracked`](inbetween::skeleton::Skeleton::retracked) takes.
fn kept_indices(keep: &[bool]) -> Vec<Option<usize>> {
    let mut next = 0;
    keep.iter()
        .map(|&k| {
            next += usize::from(k);
            k.then(|| next - 1)
        })
        .collect()
}

pub(super) use crate::pattern::glob;

/// `--span track`, `--velocity`, `--tracks` and `--precision` against what `format` carries
/// ([`capability::of`]), worded with the flags.
pub(super) fn check_carries(
    args: &crate::args::InterpArgs,
    format: OutputFormat,
) -> Result<(), inbetween::Error> {
    let can = crate::capability::of(format);
    let refusal = if let Some(why) = can
        .no_track_spans
        .filter(|_| args.span == crate::args::SpanArg::Track)
    {
        format!("--span track: {why}; use --span clip")
    } else if let Some(why) = can.no_velocities.filter(|_| args.velocity) {
        format!("--velocity: {why}; write csv or json")
    } else if let Some(why) = can
        .no_track_selection
        .filter(|_| args.input.tracks.is_some())
    {
        format!("--tracks: {why}; select tracks for csv or json output")
    } else if let Some(why) = can.no_precision.filter(|_| args.output.precision.is_some()) {
        format!("--precision: {why}; drop --precision")
    } else {
        return Ok(());
    };
    Err(inbetween::InputError::new(refusal).into())
}

/// The rule both lean BVH paths (`interp`'s and `reduce`'s) start from: the input is a named
/// BVH file, read with none of the options only the general path applies (`--animation`,
/// `--from`, `--snap-keys`, `--path euler`, end velocities). Its path, else `None` (the general
/// path). `--tracks` is each path's own to handle (interp's chooses joints; reduce's refuses it).
pub(super) fn lean_bvh_path<'a>(input: &'a InputArgs, curve: &CurveArgs) -> Option<&'a Path> {
    let path = input.input.as_deref().filter(|p| p.as_os_str() != "-")?;
    let plain = input.input_format.or_else(|| Format::from_path(path)) == Some(Format::Bvh)
        && input.animation.is_none()
        && input.from.is_none()
        && curve.snap_keys.is_none()
        && curve.path != PathArg::Euler
        && curve.start_velocity.is_none()
        && curve.end_velocity.is_none();
    plain.then_some(path)
}

/// A lean path's BVH file parsed as it is read, when it is a regular file within
/// `--max-input-bytes`: its name in messages, the clip (only the joints `choose` chooses, when
/// given) and the reader's warnings; else `None` (the general path reads it, and says what is
/// wrong).
pub(super) fn lean_bvh_clip(
    path: &Path,
    input: &InputArgs,
    choose: Option<inbetween_io::bvh::chosen::Choose>,
) -> Option<(String, inbetween_io::clip::Clip, Vec<String>)> {
    let file = std::fs::File::open(path).ok()?;
    let size = file.metadata().ok().filter(|m| m.is_file())?.len();
    if size > input.max_input_bytes {
        return None;
    }
    let source = path.display().to_string();
    let (clip, warnings) = match choose {
        Some(choose) => inbetween_io::bvh::parse_reader_chosen(file, &source, Some(size), choose),
        None => inbetween_io::bvh::parse_reader(file, &source, Some(size)),
    }
    .ok()?;
    Some((source, clip, warnings))
}

/// The input of interp, analyze and plot, read and validated.
pub struct Curves {
    /// The document as read.
    pub doc: Document,
    /// Its format.
    pub format: Format,
    /// Its tracks, validated (frames at the document's rate).
    pub tracks: Vec<Track>,
    /// The output rate (and minaccel's grid rate).
    pub fps: Fps,
    /// The curve options of the command line (scheme: `scheme` of the input's format).
    pub opts: CurveOptions,
    /// A glTF input's asset and chosen animations.
    pub gltf: Option<Arc<GltfClip>>,
    /// The files read ([`files_read`]), which no output may replace.
    pub reads: Vec<PathBuf>,
}

/// The files a command reads, which [`Output::open`](crate::output::Output::open) refuses to
/// replace: the input, `more` (a skeleton file, `diff`'s other input) and a glTF input's
/// buffers and images.
pub fn files_read(
    input: &InputArgs,
    more: &[Option<&Path>],
    gltf: Option<&GltfClip>,
) -> Vec<PathBuf> {
    let referenced = gltf.map_or(&[][..], |c| c.asset().referenced_files());
    let paths = std::iter::once(input.input.as_deref()).chain(more.iter().copied());
    crate::output::files_read(paths, referenced)
}

/// Reads the input and validates it into tracks, with the output rate and the curve options;
/// `scheme` gives the curves' scheme for the input's format and the scheme its document records
/// (a default may depend on them).
pub fn read_curves(
    input: &InputArgs,
    curve: &CurveArgs,
    scheme: &dyn Fn(Format, Option<Scheme>) -> Scheme,
    stdin: &mut dyn Read,
    warn: &mut dyn Events,
) -> Result<Curves, inbetween::Error> {
    read_curves_in((Mode::Frames, true), input, curve, scheme, stdin, warn)
}

/// [`read_curves`], a glTF input's tracks read for `mode` (interp: [`Mode::Sampled`]), with
/// their nodes' translations when `translations` (see [`read_input`]).
pub fn read_curves_in(
    mode: (Mode, bool),
    input: &InputArgs,
    curve: &CurveArgs,
    scheme: &dyn Fn(Format, Option<Scheme>) -> Scheme,
    stdin: &mut dyn Read,
    warn: &mut dyn Events,
) -> Result<Curves, inbetween::Error> {
    let (doc, format, gltf) = read_input(input, curve.fps, mode, stdin, warn)?;
    let (frame_fps, fps) = rates(&doc, curve.fps);
    if let Some(w) = key_rate_warning(&doc, frame_fps) {
        warn.warning(&w);
    }
    let mut tracks = doc.tracks_shaped(frame_fps, tcb_flags(curve))?;
    if let Some(eps) = curve.snap_keys {
        for t in &mut tracks {
            *t = snap_keys(t, fps, eps).map_err(|e| e.at(track_label(&doc.source, t)))?;
        }
    }
    if curve.path == PathArg::Euler {
        for (t, d) in tracks.iter().zip(&doc.tracks) {
            if t.len() > 1 && t.euler_angles().is_none() {
                let found = match (&d.euler, doc.rotation) {
                    (Some(_), _) => "Euler angles beyond ±1e15 rad".to_string(),
                    (None, Some(Repr::Euler(_))) => "keys in more than one representation".into(),
                    (None, Some(r)) => format!("{r} keys"),
                    (None, None) => "no keys".into(),
                };
                return Err(InputError::new(format!(
                    "{}: --path euler needs keys given as Euler angles in one sequence \
                     (--from euler:SEQ, or \"rotation\": \"euler:SEQ\" in JSON), found {found}",
                    track_label(&doc.source, t)
                ))
                .into());
            }
        }
    }
    for t in &tracks {
        let (t0, t1) = t.span();
        for time in [t0, t1] {
            if !fps.in_range(time) {
                return Err(InputError::new(format!(
                    "{}: time {} s is beyond the frame numbers --fps {fps} supports (2^53)",
                    doc.source,
                    num(time)
                ))
                .into());
            }
        }
    }
    // The end velocities of the command line are checked as the flags they are (the document's
    // own are checked with the curve, located in the file).
    let unit = input.angles;
    for (flag, v) in [
        ("--start-velocity", curve.start_velocity),
        ("--end-velocity", curve.end_velocity),
    ] {
        let speed = v.map(|v| unit.to_rad(inbetween::rotation::magnitude::length(v)));
        if let Some(speed) = speed.filter(|&s| s > MAX_SPEED) {
            let limit = match unit {
                AngleUnit::Rad => format!("{MAX_SPEED:e} rad/s"),
                AngleUnit::Deg => format!("{} deg/s", num(unit.from_rad(MAX_SPEED))),
            };
            return Err(InputError::new(format!(
                "{flag}: expected at most {limit}, found {} {}/s",
                num(unit.from_rad(speed)),
                unit.as_str()
            ))
            .into());
        }
    }
    let opts = curve_options(curve, scheme(format, doc.scheme), fps, input.angles);
    let reads = files_read(input, &[], gltf.as_deref());
    Ok(Curves {
        doc,
        format,
        tracks,
        fps,
        opts,
        gltf,
        reads,
    })
}

/// Whether a glTF input's tracks take their nodes' translations ([`read_input`]): not for glTF
/// output, which writes (bakes, keeps or reduces) the translation channels itself.
pub fn tracks_take_translations(args: &OutputArgs) -> bool {
    !matches!(output_format(args, Format::Gltf), OutputFormat::Gltf(_))
}

/// An output named for a format that is read but not written (binary USD `.usdc`, `.usdz`, and
/// `.usd`, which names either form) is refused unless the output format is given: the input's
/// format would otherwise go into a file whose name says another (a BVH's text in `x.usdc`).
/// Checked before anything is read. (`.fbx` is written since issue 50.)
pub fn check_output_name(args: &OutputArgs) -> Result<(), InputError> {
    match (&args.output, args.output_format) {
        (Some(path), None) => check_output_path(path),
        _ => Ok(()),
    }
}

/// [`check_output_name`] for an output path without `--output-format`: by the end of its file
/// name, in any case (`.usdc` alone too, which has no extension to `Path`).
pub fn check_output_path(path: &Path) -> Result<(), InputError> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let what = if name == ".fbx" {
        // A hidden file without an extension to `Path`: it would get the input's format.
        "FBX output needs a file name before .fbx (clip.fbx)"
    } else if [".usd", ".usdc", ".usdz"].iter().any(|e| name.ends_with(e)) {
        "USD is written as text only: name it .usda"
    } else {
        return Ok(());
    };
    Err(InputError::new(format!(
        "{}: {what}, or say what to write under this name with --output-format",
        path.display()
    )))
}

/// The output format: `--output-format`, else the extension of `-o` (`.csv`, `.json`, `.npy`,
/// any case), else the input's format.
pub fn output_format(args: &OutputArgs, input: Format) -> OutputFormat {
    let by_extension = || {
        let path = args.output.as_deref()?;
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        OutputFormat::parse(&ext).ok()
    };
    args.output_format
        .or_else(by_extension)
        .unwrap_or(match input {
            Format::Bvh => OutputFormat::Bvh,
            // interp writes the input's container (convert writes JSON keys).
            Format::Gltf => OutputFormat::Gltf(ContainerFormat::Glb),
            // FBX is binary, written only when named: JSON, which keeps the names and translations.
            Format::Fbx => OutputFormat::Doc(Format::Json),
            Format::Usd => OutputFormat::Usda,
            // An AMASS file is written back in its own shape at the output rate.
            Format::Amass => OutputFormat::Npz,
            f => OutputFormat::Doc(f),
        })
}

/// The container of glTF output: the one `--output-format` or the `-o` name (`.gltf`, `.glb`)
/// says, else the input asset's own (`container` is [`output_format`]'s, which falls back to GLB).
pub fn gltf_container(
    args: &OutputArgs,
    container: ContainerFormat,
    clip: &GltfClip,
) -> ContainerFormat {
    let named = args.output_format.is_some()
        || args
            .output
            .as_deref()
            .is_some_and(|p| ContainerFormat::from_path(p).is_some());
    if named {
        container
    } else {
        clip.asset().container()
    }
}

/// `file` or `file: track "name"`, for messages about a whole track.
pub fn track_label(source: &str, t: &Track) -> String {
    inbetween_io::document::track_label(source, t.name())
}

/// The track with every key within `eps` frame periods of a frame moved onto it (`--snap-keys`).
fn snap_keys(t: &Track, fps: Fps, eps: f64) -> Result<Track, InputError> {
    let times: Vec<f64> = t.times().iter().map(|&x| fps.snap(x, eps)).collect();
    if let Some(i) = (1..times.len()).find(|&i| times[i] <= times[i - 1]) {
        return Err(InputError::new(format!(
            "--snap-keys {eps}: keys at {} s and {} s would both move to frame {} ({} s); lower \
             EPS or merge the keys",
            num(t.times()[i - 1]),
            num(t.times()[i]),
            fps.nearest_frame(times[i]),
            num(times[i])
        )));
    }
    t.retimed(times).map_err(InputError::from)
}

/// The output style of the command line: `--to`, `--angles`, `--quat-order`, `--precision`,
/// `--euler`.
pub fn style(input: &InputArgs, output: &OutputArgs) -> Style {
    Style {
        repr: output.to,
        angles: input.angles,
        quat_order: input.quat_order,
        num: output.num_format(),
        euler: output.euler_mode(),
    }
}

/// `--tension`, `--continuity`, `--bias`.
pub fn tcb_flags(args: &CurveArgs) -> Tcb {
    Tcb {
        tension: args.tension,
        continuity: args.continuity,
        bias: args.bias,
    }
}

/// The curve options of the command line; given velocities are in `unit` per second.
pub fn curve_options(args: &CurveArgs, scheme: Scheme, fps: Fps, unit: AngleUnit) -> CurveOptions {
    let omega = |v: Option<[f64; 3]>| v.map(|a| DVec3::from_array(a.map(|x| unit.to_rad(x))));
    CurveOptions {
        scheme,
        blend: match args.blend {
            BlendArg::Cubic => Blend::Cubic,
            BlendArg::Quadratic => Blend::Quadratic,
        },
        path: match args.path {
            PathArg::Shortest => PathMode::Shortest,
            PathArg::AsGiven => PathMode::AsGiven,
            PathArg::Euler => PathMode::Euler,
        },
        ends: EndConditions {
            ends: match args.ends {
                EndsArg::Chord => Ends::Chord,
                EndsArg::Rest => Ends::Rest,
                EndsArg::Cyclic => Ends::Cyclic,
            },
            start: omega(args.start_velocity),
            end: omega(args.end_velocity),
        },
        grid_rate: fps,
        tcb: tcb_flags(args),
        tangent: args.tangent.map(|t| match t {
            TangentArg::Spline => TangentRule::Spline,
            TangentArg::NamKim => TangentRule::NamKim,
        }),
    }
}
