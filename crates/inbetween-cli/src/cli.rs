//! Command-line definitions (clap derive). Doc comments are the help text. Values are parsed
//! into validated library types here, so a bad value is a usage error (exit 2) naming the flag.

use clap::{Args, Parser, Subcommand};
use inbetween::Fps;
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};
use inbetween_io::num::{MAX_PRECISION, NumFormat};
use inbetween_io::write::EulerMode;
use inbetween_io::{Format, OutputFormat};
use std::path::PathBuf;

/// Keyframe in-betweener for 3D orientations: reads keyframes (quaternions, Euler angles,
/// matrices, axis-angle, rotation vectors) from CSV, JSON, BVH motion capture, glTF 2.0
/// (.gltf, .glb), FBX or USD (.usda) and writes every in-between frame as CSV, JSON, npy, npz,
/// BVH, glTF or USD.
#[derive(Debug, Parser)]
#[command(name = "inbetween", version, max_term_width = 100)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Smoothness report per track and scheme: speed, acceleration, jumps at keys, energy.
    ///
    /// Examples:
    ///   inbetween analyze keys.json
    ///   inbetween analyze keys.csv --scheme hermite,minaccel --output-format csv
    ///   inbetween analyze keys.json --scheme squad --fps 60 --angles rad --output-format json
    #[command(verbatim_doc_comment)]
    Analyze(AnalyzeArgs),

    /// Compare two motions with the same tracks: per track the largest and mean angle between
    /// them, and with a skeleton the largest world-space displacement of each joint.
    ///
    /// Examples:
    ///   inbetween diff clip.bvh small.json
    ///   inbetween diff golden.csv out.csv --max-angle 0.001
    ///   inbetween diff clip.bvh back.bvh --shell 3 --max-position 0.5 --output-format json
    #[command(verbatim_doc_comment)]
    Diff(DiffArgs),

    /// SVG chart of angular speed (or velocity components, or accumulated energy) over time,
    /// schemes side by side, keys marked.
    ///
    /// Examples:
    ///   inbetween plot keys.json -o speed.svg
    ///   inbetween plot keys.csv --scheme slerp,hermite,minaccel --what components -o w.svg
    ///   inbetween plot rig.json --track hip --what energy -o energy.svg
    #[command(verbatim_doc_comment)]
    Plot(PlotArgs),

    /// Interpolate keyframes: write every frame between the first and last key.
    ///
    /// Examples:
    ///   inbetween interp keys.json --fps 30
    ///   cat keys.csv | inbetween interp - --fps 24 --to euler:ZYX
    ///   inbetween interp keys.csv --fps 29.97 --scheme squad --ends rest -o frames.csv
    ///   inbetween interp keys.json --start-velocity 0,0,90 --path as-given --precision 9
    #[command(verbatim_doc_comment)]
    Interp(InterpArgs),

    /// Change representation and/or format of keyframes, without interpolating.
    ///
    /// Examples:
    ///   inbetween convert keys.csv --to euler:ZYX
    ///   cat keys.json | inbetween convert --to matrix --output-format csv
    ///   inbetween convert keys.csv --from euler:zxz --angles rad --to quat -o keys.json
    #[command(verbatim_doc_comment)]
    Convert(ConvertArgs),

    /// The fewest keys that interp turns back into the motion: every input frame within the
    /// tolerance, checked before writing.
    ///
    /// Examples:
    ///   inbetween reduce clip.csv --tolerance 0.5 -o keys.json
    ///   inbetween reduce clip.bvh --tolerance 1 --translation-tolerance 0.1 --shared-keys -o keys.json
    ///   inbetween reduce frames.csv --tolerance 0.2 --distance 50 --scheme slerp
    ///   inbetween reduce anim.glb --tolerance 0.5 --scheme slerp -o small.glb
    #[command(verbatim_doc_comment)]
    Reduce(ReduceArgs),
}

#[derive(Debug, Clone, Args)]
pub struct ReduceArgs {
    #[command(flatten)]
    pub input: InputArgs,

    #[command(flatten)]
    pub output: OutputArgs,

    #[command(flatten)]
    pub batch: BatchArgs,

    /// Largest rotation error of any input frame, in --angles units (with --distance, a length).
    /// Required unless --position-tolerance is given; with it, both hold.
    #[arg(long, value_name = "TOL", value_parser = parse_positive, allow_hyphen_values = true,
        required_unless_present = "position_tolerance")]
    pub tolerance: Option<f64>,

    /// Largest world-space displacement (length units) of every joint, End Site and --shell
    /// point, composed through the skeleton from the root, at every input frame (BVH and glTF
    /// inputs, which have a skeleton).
    #[arg(long, value_name = "LEN", value_parser = parse_positive)]
    pub position_tolerance: Option<f64>,

    /// With --position-tolerance, also keep the three points this far from each joint along its
    /// own axes within it (so that a twist about a bone counts; ACL's virtual vertices).
    #[arg(long, value_name = "D", value_parser = parse_positive, requires = "position_tolerance")]
    pub shell: Option<f64>,

    /// With --position-tolerance, another limit for the points of the joints the globs name:
    /// 'LeftFoot,RightFoot=0.2' (repeatable; a later one wins where several match).
    #[arg(long, value_name = "GLOBS=LEN", requires = "position_tolerance")]
    pub joint_tolerance: Vec<String>,

    /// The scheme the keys are for (interp's --scheme; use the same with interp). Default
    /// bezier; slerp for glTF output, whose LINEAR samplers play by slerp.
    #[arg(long, value_enum)]
    pub scheme: Option<SchemeArg>,

    #[command(flatten)]
    pub curve: CurveArgs,

    /// greedy (near-linear) or optimal (fewest keys by shortest path; never more than greedy).
    #[arg(long, value_enum, default_value = "greedy")]
    pub method: MethodArg,

    /// Measure the error as the displacement 2·D·sin(θ/2) of a point D length units from the
    /// joint (the tolerance is then a length).
    #[arg(long, value_name = "D", value_parser = parse_positive)]
    pub distance: Option<f64>,

    /// Largest position error (length units) for tracks with translations (required for them;
    /// glTF output: LINEAR translation channels are reduced under it, and kept without it).
    #[arg(long, value_name = "TOL", value_parser = parse_positive)]
    pub translation_tolerance: Option<f64>,

    /// glTF output: largest error of the animation's LINEAR scale channels (the length of the
    /// difference of the scale vectors), which are then reduced too; without it they are kept.
    #[arg(long, value_name = "TOL", value_parser = parse_positive)]
    pub scale_tolerance: Option<f64>,

    /// One set of key times for all tracks (pose keys), every track within the tolerance.
    #[arg(long)]
    pub shared_keys: bool,

    /// Write keys alone (interp estimates their tangents), not each key's angular velocity.
    #[arg(long)]
    pub no_velocities: bool,

    /// Report per track on stderr: frames in, keys out, ratio, max and mean error, max position
    /// error.
    #[arg(short, long)]
    pub verbose: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MethodArg {
    Greedy,
    Optimal,
}

fn parse_positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("expected a positive number, found \"{s}\"")),
    }
}

/// `inbetween diff A B`.
#[derive(Debug, Args)]
#[command(mut_arg("input", |a| a.required(true).index(1).value_name("A")
    .help("Motion A, the reference: CSV, JSON, BVH, glTF, FBX or USD; `-` reads standard input")))]
pub struct DiffArgs {
    /// Motion A, the reference (its options are those below; `-` reads standard input).
    #[command(flatten)]
    pub input: InputArgs,

    /// Motion B: CSV, JSON, BVH, glTF, FBX or USD, read with the same options as A.
    #[arg(value_name = "B", index = 2)]
    pub other: PathBuf,

    /// The scheme B is interpolated with at A's frame times (default bezier).
    #[arg(long, value_enum)]
    pub scheme: Option<SchemeArg>,

    #[command(flatten)]
    pub curve: CurveArgs,

    /// Compare only at the times where both have a key (within 1e-9 s), without interpolating.
    #[arg(long)]
    pub common_frames: bool,

    /// With a skeleton, also measure three points this far from each joint along its own axes
    /// (so that a twist about a bone counts).
    #[arg(long, value_name = "D", value_parser = parse_positive)]
    pub shell: Option<f64>,

    /// Exit 1 when any angle exceeds this (--angles units).
    #[arg(long, value_name = "ANGLE", value_parser = parse_positive)]
    pub max_angle: Option<f64>,

    /// Exit 1 when any world-space displacement, or any translation difference, exceeds this
    /// (length units).
    #[arg(long, value_name = "LEN", value_parser = parse_positive)]
    pub max_position: Option<f64>,

    /// text (an aligned table), csv or json; by default from the extension of -o (.csv,
    /// .json), else text.
    #[arg(long, value_enum)]
    pub output_format: Option<ReportFormat>,

    /// Output file, replaced atomically; default standard output.
    #[arg(short = 'o', long = "output", value_name = "PATH")]
    pub output: Option<PathBuf>,
}

/// Several inputs at once (docs/spec.md §1, *Batch*): more inputs, and where their outputs go.
#[derive(Debug, Clone, Default, Args)]
pub struct BatchArgs {
    /// More inputs: files, folders (read recursively, every file of a known extension), or glob
    /// patterns (`clips/*.bvh`, `**` for any folders); they need --out-dir.
    #[arg(value_name = "MORE", num_args = 0.., trailing_var_arg = false)]
    pub more: Vec<PathBuf>,

    /// Write each input's output under this folder, at the input's path relative to the folder
    /// or pattern it was found by, with the output format's extension; each written atomically.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,

    /// Inputs processed at once, each on one thread (default: the number of cores).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub jobs: Option<u32>,

    /// Append one JSON line per input to this file as each finishes: input, output, status (ok,
    /// skipped, failed), seconds, and the error of a failed input.
    #[arg(long, value_name = "FILE")]
    pub manifest: Option<PathBuf>,

    /// Redo inputs whose output is newer than the input (skipped by default).
    #[arg(long)]
    pub refresh: bool,

    /// Follow symbolic links that lead out of the folders named (by default they are skipped;
    /// links inside are followed, each target once).
    #[arg(long)]
    pub follow: bool,
}

/// Where the keys come from and how to read them.
#[derive(Debug, Clone, Args)]
pub struct InputArgs {
    /// Input file: CSV, JSON, BVH, glTF (.gltf, .glb), FBX (.fbx) or USD (.usda); `-` or
    /// nothing reads standard input.
    #[arg(value_name = "INPUT")]
    pub input: Option<PathBuf>,

    /// Input representation when the data does not say: the Euler sequence of CSV e1,e2,e3
    /// columns and of JSON "euler" keys (quat, euler:SEQ, matrix, axis-angle, rotvec). A JSON
    /// "rotation" it contradicts is an error.
    #[arg(long, value_name = "REPR", value_parser = parse_repr)]
    pub from: Option<Repr>,

    /// Unit of every angle written, and of input angles the document does not declare when
    /// --input-angles is absent (CSV; JSON without "angles").
    #[arg(long, value_name = "U", value_parser = parse_angles, default_value = "deg")]
    pub angles: AngleUnit,

    /// Unit of input angles the document does not declare (CSV; JSON without "angles"), so that
    /// radians can be read and degrees written. A JSON "angles" it contradicts is an error.
    #[arg(long, value_name = "U", value_parser = parse_angles)]
    pub input_angles: Option<AngleUnit>,

    /// Rate of the input's frame numbers when the document declares none (CSV always; JSON
    /// without "fps"): 24, 29.97, 30000/1001, ... A JSON "fps" it contradicts is an error.
    #[arg(long, value_name = "RATE", value_parser = parse_fps, allow_hyphen_values = true)]
    pub key_fps: Option<Fps>,

    /// CSV field delimiter: , ; or tab. Default: the one of the three found most often in the
    /// header line (outside quotes), a comma on a tie or when there is none.
    #[arg(long, value_name = "C", value_parser = parse_delimiter)]
    pub delimiter: Option<u8>,

    /// Component order of quaternions in JSON arrays (CSV columns are named).
    #[arg(long, value_name = "O", value_parser = parse_quat_order, default_value = "wxyz")]
    pub quat_order: QuatOrder,

    /// Input format (csv, json, bvh, gltf, glb, fbx, usda); by default from the file extension,
    /// and standard input is sniffed (`{` or `[` first means JSON).
    #[arg(long, value_name = "F", value_parser = parse_format)]
    pub input_format: Option<Format>,

    /// glTF input: the animation to read, by name, else by index; default every animation
    /// (tracks named animation/node). FBX input: the animation stack; default the first.
    #[arg(long, value_name = "NAME|INDEX")]
    pub animation: Option<String>,

    /// Refuse an input larger than this many bytes (a file from its size, standard input once
    /// it passes the limit).
    #[arg(long, value_name = "N", default_value_t = inbetween_io::DEFAULT_MAX_INPUT_BYTES)]
    pub max_input_bytes: u64,

    /// Only these tracks (joints), by name, comma-separated; `*` and `?` match any characters
    /// and one character (e.g. --tracks 'Left*,Hips'). A pattern that matches nothing is an
    /// error listing the names there are.
    #[arg(long, value_name = "NAME,NAME…")]
    pub tracks: Option<String>,
}

/// Where the output goes and how it is written.
#[derive(Debug, Clone, Args)]
pub struct OutputArgs {
    /// Output representation: quat, euler:SEQ (scipy letters: ZYX intrinsic, zyx extrinsic),
    /// matrix, axis-angle, rotvec.
    #[arg(long, value_name = "REPR", value_parser = parse_repr, default_value = "quat")]
    pub to: Repr,

    /// Output format: csv, json, or (interp only) npy, a NumPy array of float64 rows, or npz,
    /// named NumPy arrays (times, names, rotations, …); bvh, gltf/glb, usda (a UsdSkel
    /// animation) for input with a skeleton; by default the input's format.
    #[arg(long, value_name = "F", value_parser = parse_output_format)]
    pub output_format: Option<OutputFormat>,

    /// Output file, replaced atomically (nothing is written on error); default standard output.
    #[arg(short = 'o', long = "output", value_name = "PATH")]
    pub output: Option<PathBuf>,

    /// Euler output along a track: continuous (each triple the one of its rotation nearest the
    /// previous: no jump at ±180°, no flip at gimbal lock) or wrapped (scipy's ranges).
    #[arg(long, value_enum, default_value = "continuous")]
    pub euler: EulerArg,

    /// Digits after the decimal point (as printf %.Nf); default: the shortest digits that read
    /// back to the same number.
    #[arg(long, value_name = "N", value_parser = parse_precision)]
    pub precision: Option<usize>,
}

impl OutputArgs {
    /// The folder of the `-o` file (`.` for a bare name); `None` for standard output.
    pub fn folder(&self) -> Option<&std::path::Path> {
        let path = self.output.as_deref().filter(|p| p.as_os_str() != "-")?;
        Some(
            path.parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(".".as_ref()),
        )
    }

    pub fn num_format(&self) -> NumFormat {
        self.precision.map_or(NumFormat::Shortest, NumFormat::Fixed)
    }

    pub fn euler_mode(&self) -> EulerMode {
        match self.euler {
            EulerArg::Continuous => EulerMode::Continuous,
            EulerArg::Wrapped => EulerMode::Wrapped,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum EulerArg {
    Continuous,
    Wrapped,
}

#[derive(Debug, Clone, Args)]
pub struct ConvertArgs {
    #[command(flatten)]
    pub input: InputArgs,

    #[command(flatten)]
    pub output: OutputArgs,

    #[command(flatten)]
    pub batch: BatchArgs,

    /// Rate of `frame` values in documents that do not give one (JSON "fps" wins for its own
    /// frames): 24, 29.97, 30000/1001, ...
    #[arg(long, value_name = "RATE", value_parser = parse_fps, allow_hyphen_values = true)]
    pub fps: Option<Fps>,

    /// Write BVH on this BVH file's skeleton (its hierarchy and channel orders): every track a
    /// joint, keys on one grid of consecutive frames; frames with no declared rate (and no
    /// --fps) are at its Frame Time. Output is BVH unless -o or --output-format says otherwise.
    #[arg(long, value_name = "BVH")]
    pub skeleton: Option<PathBuf>,
}

#[derive(Debug, Clone, Args)]
pub struct InterpArgs {
    #[command(flatten)]
    pub input: InputArgs,

    #[command(flatten)]
    pub output: OutputArgs,

    #[command(flatten)]
    pub batch: BatchArgs,

    /// Interpolation scheme (bezier: third order, C¹, local; see docs/schemes.md). Default
    /// bezier; for glTF input, each sampler as glTF plays it (LINEAR by slerp), and a scheme
    /// given re-interpolates the LINEAR keys.
    #[arg(long, value_enum)]
    pub scheme: Option<SchemeArg>,

    #[command(flatten)]
    pub curve: CurveArgs,

    /// Add each frame's world-frame angular velocity: CSV columns wx,wy,wz (JSON
    /// "angular_velocity"), in --angles units per second.
    #[arg(long)]
    pub velocity: bool,

    /// Write BVH on this BVH file's skeleton (its hierarchy and channel orders; without --fps
    /// its Frame Time is the rate): a track per joint with channels, found by name, as reduce
    /// and convert write them. Output is BVH unless -o or --output-format says otherwise.
    #[arg(long, value_name = "BVH")]
    pub skeleton: Option<PathBuf>,

    /// Report on stderr what the minaccel solver did for each track (points, iterations, energy,
    /// projected gradient).
    #[arg(short, long)]
    pub verbose: bool,

    /// clip: every track over the union of all tracks' key ranges, holding its first key before
    /// its first time and its last key after its last (glTF's clamp); track: each track over its
    /// own keys' range.
    #[arg(long, value_enum, default_value = "clip")]
    pub span: SpanArg,

    /// Refuse, before writing anything, a run that would write more frames than this (all
    /// tracks together).
    #[arg(long, value_name = "N", default_value_t = 1_000_000_000)]
    pub max_frames: u64,
}

/// Options that shape the curve (shared by interp, analyze and plot).
#[derive(Debug, Clone, Args)]
pub struct CurveArgs {
    /// Output frame rate: 24, 25, 30, 60, 23.976, 29.97, 59.94 (the exact /1001 ratios),
    /// 30000/1001, any positive number or ratio. Default: the document's "fps", else 30.
    #[arg(long, value_name = "RATE", value_parser = parse_fps, allow_hyphen_values = true)]
    pub fps: Option<Fps>,

    /// Hermite blending function: cubic (3u²−2u³) or quadratic (2u², then 1−2(1−u)²).
    #[arg(long, value_enum, default_value = "cubic")]
    pub blend: BlendArg,

    /// End condition without a given velocity: chord (along the first/last chord), rest (zero
    /// velocity), or cyclic (a loop: the last key is the first key's rotation, and the tangent
    /// there is computed across the seam). minaccel's ends are free unless rest or a velocity
    /// is given.
    #[arg(long, value_enum, default_value = "chord")]
    pub ends: EndsArg,

    /// Kochanek–Bartels tension T in [-1, 1] at every interior key without its own (a `tension`
    /// column or field): 1 stops at the key, -1 doubles the tangent.
    #[arg(long, value_name = "T", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_unit_interval)]
    pub tension: f64,

    /// Kochanek–Bartels continuity C in [-1, 1]: non-zero gives the key a corner (different
    /// incoming and outgoing tangents).
    #[arg(long, value_name = "C", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_unit_interval)]
    pub continuity: f64,

    /// Kochanek–Bartels bias B in [-1, 1]: positive leans the tangent towards the incoming
    /// chord, negative towards the outgoing one.
    #[arg(long, value_name = "B", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_unit_interval)]
    pub bias: f64,

    /// World-frame angular velocity at the first key, X,Y,Z in --angles units per second
    /// (overrides the document's start_velocity).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub start_velocity: Option<[f64; 3]>,

    /// World-frame angular velocity at the last key, X,Y,Z in --angles units per second.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub end_velocity: Option<[f64; 3]>,

    /// shortest: flip each key into the hemisphere of the previous one (every step ≤ 180°);
    /// as-given: keep quaternion signs (a flipped key is reached the long way round); euler
    /// (Euler input only): keep the turns the Euler angles make between keys (0→720° spins
    /// twice).
    #[arg(long, value_enum, default_value = "shortest")]
    pub path: PathArg,

    /// Move every key within EPS frame periods of a frame of the output grid onto that frame
    /// before interpolating (for key times rounded by their writer, e.g. 0.0333333 s).
    #[arg(long, value_name = "EPS", value_parser = parse_snap)]
    pub snap_keys: Option<f64>,
}

#[derive(Debug, Args)]
pub struct AnalyzeArgs {
    #[command(flatten)]
    pub input: InputArgs,

    /// Schemes to compare: one, a comma-separated list, or all.
    #[arg(long, value_name = "S,S…|all", value_parser = parse_schemes, default_value = "all")]
    pub scheme: SchemeList,

    #[command(flatten)]
    pub curve: CurveArgs,

    /// text (an aligned table), csv or json; by default from the extension of -o (.csv,
    /// .json), else text.
    #[arg(long, value_enum)]
    pub output_format: Option<ReportFormat>,

    /// Output file, replaced atomically; default standard output.
    #[arg(short = 'o', long = "output", value_name = "PATH")]
    pub output: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct PlotArgs {
    #[command(flatten)]
    pub input: InputArgs,

    /// Schemes to draw: one, a comma-separated list, or all.
    #[arg(long, value_name = "S,S…|all", value_parser = parse_schemes, default_value = "all")]
    pub scheme: SchemeList,

    /// speed (|ω| over time), components (ωx, ωy, ωz), or energy (accumulated E).
    #[arg(long, value_enum, default_value = "speed")]
    pub what: WhatArg,

    /// The track to draw (default: the first).
    #[arg(long, value_name = "NAME")]
    pub track: Option<String>,

    #[command(flatten)]
    pub curve: CurveArgs,

    /// The SVG file to write (replaced atomically), or - for standard output.
    #[arg(short = 'o', long = "output", value_name = "FILE.svg")]
    pub output: PathBuf,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SpanArg {
    Clip,
    Track,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum WhatArg {
    Speed,
    Components,
    Energy,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ReportFormat {
    Text,
    Csv,
    Json,
}

/// A list of schemes (`--scheme hermite,squad` or `all`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SchemeList(pub Vec<SchemeArg>);

fn parse_schemes(s: &str) -> Result<SchemeList, String> {
    use clap::ValueEnum;
    if s == "all" {
        return Ok(SchemeList(SchemeArg::value_variants().to_vec()));
    }
    let mut out = Vec::new();
    for name in s.split(',').map(str::trim) {
        let v = SchemeArg::from_str(name, false).map_err(|_| {
            format!(
                "expected schemes from hermite, squad, bezier, slerp, minaccel (comma-separated) \
                 or all, found \"{name}\""
            )
        })?;
        if !out.contains(&v) {
            out.push(v);
        }
    }
    Ok(SchemeList(out))
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SchemeArg {
    Hermite,
    Squad,
    Bezier,
    Slerp,
    Minaccel,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BlendArg {
    Cubic,
    Quadratic,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum EndsArg {
    Chord,
    Rest,
    Cyclic,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PathArg {
    Shortest,
    AsGiven,
    Euler,
}

fn parse_unit_interval(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x.abs() <= 1.0 => Ok(x),
        _ => Err(format!("expected a number between -1 and 1, found \"{s}\"")),
    }
}

fn parse_vec3(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let bad = || format!("expected three finite numbers X,Y,Z such as 0,0,90, found \"{s}\"");
    if parts.len() != 3 {
        return Err(bad());
    }
    let mut v = [0.0; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        *slot = p.parse::<f64>().map_err(|_| bad())?;
        if !slot.is_finite() {
            return Err(bad());
        }
    }
    Ok(v)
}

fn parse_delimiter(s: &str) -> Result<u8, String> {
    match s {
        "," => Ok(b','),
        ";" => Ok(b';'),
        "tab" | "\t" => Ok(b'\t'),
        _ => Err(format!("expected \",\", \";\" or \"tab\", found \"{s}\"")),
    }
}

fn parse_repr(s: &str) -> Result<Repr, String> {
    Repr::parse(s).map_err(|e| e.message().to_string())
}

fn parse_angles(s: &str) -> Result<AngleUnit, String> {
    AngleUnit::parse(s).map_err(|e| e.message().to_string())
}

fn parse_quat_order(s: &str) -> Result<QuatOrder, String> {
    QuatOrder::parse(s).map_err(|e| e.message().to_string())
}

fn parse_output_format(s: &str) -> Result<OutputFormat, String> {
    OutputFormat::parse(s).map_err(|e| e.message().to_string())
}

fn parse_format(s: &str) -> Result<Format, String> {
    Format::parse(s).map_err(|e| e.message().to_string())
}

fn parse_fps(s: &str) -> Result<Fps, String> {
    Fps::parse(s).map_err(|e| e.message().to_string())
}

fn parse_snap(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if (0.0..=0.5).contains(&x) => Ok(x),
        _ => Err(format!(
            "expected a number of frame periods from 0 to 0.5, such as 0.001, found \"{s}\""
        )),
    }
}

fn parse_precision(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n <= MAX_PRECISION => Ok(n),
        _ => Err(format!(
            "expected a whole number from 0 to {MAX_PRECISION}, found \"{s}\""
        )),
    }
}

impl Command {
    /// One meaning per spelling: `-o -` is standard output exactly as no `-o` is (so that
    /// defaults which depend on "is there an output file" treat both alike).
    pub fn normalise(&mut self) {
        let output = match self {
            Command::Convert(a) => &mut a.output.output,
            Command::Interp(a) => &mut a.output.output,
            Command::Reduce(a) => &mut a.output.output,
            Command::Analyze(a) => &mut a.output,
            Command::Diff(a) => &mut a.output,
            Command::Plot(_) => return,
        };
        if output.as_deref().is_some_and(|p| p.as_os_str() == "-") {
            *output = None;
        }
    }
}

/// A usage message with every run of more than [`MAX_QUOTED_CHARS`] characters that are not
/// white space or quotes cut to that many and `…` (clap echoes a bad value whole, and the tip
/// for an unknown flag echoes it twice).
///
/// [`MAX_QUOTED_CHARS`]: inbetween::error::MAX_QUOTED_CHARS
pub fn bounded(msg: &str) -> String {
    let limit = inbetween::error::MAX_QUOTED_CHARS;
    let mut out = String::with_capacity(msg.len().min(4096));
    let mut run = 0usize;
    let mut cut = false;
    for c in msg.chars() {
        if c.is_whitespace() || c == '\'' || c == '"' {
            run = 0;
            cut = false;
            out.push(c);
        } else {
            run += 1;
            if run <= limit {
                out.push(c);
            } else if !cut {
                out.push('…');
                cut = true;
            }
        }
    }
    out
}

pub use inbetween_commands::shown::printable;

/// At most this many characters of a line of stderr; the rest is cut, saying how much.
pub const MAX_LINE_CHARS: usize = 2000;

/// A line for stderr: [`printable`], every run of more than 256 characters without a space or
/// quote cut to its first 100 (so a value quoted whole by mistake shows as its start), and at
/// most [`MAX_LINE_CHARS`] characters. Messages quote bounded parts of their input already;
/// this is the last guard, applied to every line the command line prints.
pub fn line(text: &str) -> String {
    let text = printable(text);
    let mut out = String::with_capacity(text.len().min(MAX_LINE_CHARS + 64));
    let mut run = String::new();
    let flush = |run: &mut String, out: &mut String| {
        if run.chars().count() > 256 {
            out.extend(run.chars().take(100));
            out.push('…');
        } else {
            out.push_str(run);
        }
        run.clear();
    };
    for c in text.chars() {
        if c.is_whitespace() || c == '\'' || c == '"' {
            flush(&mut run, &mut out);
            out.push(c);
        } else {
            run.push(c);
        }
    }
    flush(&mut run, &mut out);
    let count = out.chars().count();
    if count > MAX_LINE_CHARS {
        let cut: String = out.chars().take(MAX_LINE_CHARS).collect();
        return format!("{cut}… ({} more characters)", count - MAX_LINE_CHARS);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{MAX_LINE_CHARS, bounded, line};

    #[test]
    fn lines_escape_control_characters_and_cut_long_runs() {
        let long = "x".repeat(300_000);
        let l = line(&format!("k.json:1: bad value \"{long}\" here"));
        assert!(l.starts_with("k.json:1: bad value \"xxx"), "{l}");
        assert!(l.chars().count() < 200, "{}", l.len());
        assert!(l.ends_with("…\" here"), "{l}");
        let words = "word ".repeat(1000);
        let l = line(&words);
        assert!(l.ends_with("more characters)"), "{l}");
        assert!(l.chars().count() < MAX_LINE_CHARS + 40);
        // A path of 200 characters is not cut.
        let path = format!("/{}/x.bvh", "d".repeat(200));
        assert_eq!(line(&path), path);
    }

    #[test]
    fn long_runs_are_cut_and_quotes_kept() {
        let long = "7".repeat(100_000);
        let msg = format!("error: invalid value '{long}' for '--fps <RATE>': found {long}\n");
        let b = bounded(&msg);
        let cut = format!("{}…", "7".repeat(60));
        assert_eq!(
            b,
            format!("error: invalid value '{cut}' for '--fps <RATE>': found {cut}\n")
        );
    }

    #[test]
    fn short_messages_are_unchanged() {
        let msg = "error: unexpected argument '--frob' found\n\n  tip: try '--fps'\n";
        assert_eq!(bounded(msg), msg);
    }
}
