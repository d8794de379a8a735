//! A command's request: the options of `interp`, `convert`, `reduce`, `diff`, `view`,
//! `analyze` and `plot`, each value parsed into its library type (a bad value is refused naming
//! the option).
//! The command line parses them with clap (the `clap` feature derives its parsers; the doc
//! comments are the help text); Python sets them by name ([`crate::keywords`]). Defaults are
//! the command line's ([`Default`], checked against clap's by the command line's tests).

use inbetween::Fps;
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};
use inbetween_io::num::{MAX_PRECISION, NumFormat};
use inbetween_io::read::log::{ColumnMap, TimeOrigin, TimeUnit};
use inbetween_io::write::EulerMode;
use inbetween_io::{Format, OutputFormat};
use std::path::PathBuf;

/// A closed set of values named as the command line names them (clap's `ValueEnum` with the
/// `clap` feature): `NAMES` in the order of the help text, [`parse`](MethodArg::parse) by name.
macro_rules! named {
    ($name:ident { $($v:ident = $s:literal),+ $(,)? }) => {
        #[doc = concat!("The values of `--", stringify!($name), "`'s option, by name.")]
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        #[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
        pub enum $name {
            $(
                #[doc = concat!("`", $s, "`")]
                $v
            ),+
        }

        impl $name {
            /// Every value with its name.
            pub const NAMES: &[(&str, $name)] = &[$(($s, $name::$v)),+];

            /// The value named `s`.
            pub fn parse(s: &str) -> Result<Self, String> {
                Self::NAMES.iter().find(|n| n.0 == s).map(|n| n.1).ok_or_else(|| {
                    let names: Vec<&str> = Self::NAMES.iter().map(|n| n.0).collect();
                    format!("expected one of {}, found \"{}\"", names.join(", "), crate::shown::printable(s))
                })
            }
        }
    };
}

/// `inbetween reduce`: the fewest keys that interp turns back into the motion.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct ReduceArgs {
    /// Where the keys come from and how to read them.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub input: InputArgs,

    /// Where the output goes and how it is written.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub output: OutputArgs,

    /// Several inputs at once (empty for one).
    #[cfg_attr(feature = "clap", command(flatten))]
    pub batch: BatchArgs,

    /// Largest rotation error of any input frame, in --angles units (with --distance, a length).
    /// Required unless --position-tolerance is given; with it, both hold.
    #[cfg_attr(feature = "clap", arg(long, value_name = "TOL", value_parser = parse_positive, allow_hyphen_values = true,
        required_unless_present = "position_tolerance"))]
    pub tolerance: Option<f64>,

    /// Largest world-space displacement (length units) of every joint, End Site and --shell
    /// point, composed through the skeleton from the root, at every input frame (BVH and glTF
    /// inputs, which have a skeleton).
    #[cfg_attr(feature = "clap", arg(long, value_name = "LEN", value_parser = parse_positive))]
    pub position_tolerance: Option<f64>,

    /// With --position-tolerance, also keep the three points this far from each joint along its
    /// own axes within it (so that a twist about a bone counts; ACL's virtual vertices). Without
    /// it, a joint whose rotation moves no point (a leaf bone without an end) gets such points at
    /// its bone length; 0: no shell and none added.
    #[cfg_attr(feature = "clap", arg(long, value_name = "D", value_parser = parse_non_negative, requires = "position_tolerance"))]
    pub shell: Option<f64>,

    /// With --position-tolerance, another limit for the points of the joints the globs name:
    /// 'LeftFoot,RightFoot=0.2' (repeatable; a later one wins where several match).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "GLOBS=LEN", requires = "position_tolerance")
    )]
    pub joint_tolerance: Vec<String>,

    /// The scheme the keys are for (interp's --scheme; use the same with interp). Default
    /// bezier; slerp for glTF output, whose LINEAR samplers play by slerp. nlerp (normalised
    /// lerp of the keys' components) is how Blender plays LINEAR quaternion keys, and how
    /// ozz-animation and many engines play theirs: reduce for the player that plays the keys.
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub scheme: Option<SchemeArg>,

    /// The options that shape the curve.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub curve: CurveArgs,

    /// greedy (near-linear) or optimal (fewest keys by shortest path; never more than greedy).
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value = "greedy"))]
    pub method: MethodArg,

    /// Measure the error as the displacement 2·D·sin(θ/2) of a point D length units from the
    /// joint (the tolerance is then a length).
    #[cfg_attr(feature = "clap", arg(long, value_name = "D", value_parser = parse_positive))]
    pub distance: Option<f64>,

    /// Largest position error (length units) for tracks with translations (required for them;
    /// glTF output: LINEAR translation channels are reduced under it, and kept without it).
    #[cfg_attr(feature = "clap", arg(long, value_name = "TOL", value_parser = parse_positive))]
    pub translation_tolerance: Option<f64>,

    /// glTF output: largest error of the animation's LINEAR scale channels (the length of the
    /// difference of the scale vectors), which are then reduced too; without it they are kept.
    #[cfg_attr(feature = "clap", arg(long, value_name = "TOL", value_parser = parse_positive))]
    pub scale_tolerance: Option<f64>,

    /// One set of key times for all tracks (pose keys), every track within the tolerance.
    #[cfg_attr(feature = "clap", arg(long))]
    pub shared_keys: bool,

    /// Write keys alone (interp estimates their tangents), not each key's angular velocity.
    #[cfg_attr(feature = "clap", arg(long))]
    pub no_velocities: bool,

    /// Report per track on stderr: frames in, keys out, ratio, max and mean error, max position
    /// error.
    #[cfg_attr(feature = "clap", arg(short, long))]
    pub verbose: bool,
}

named! { MethodArg { Greedy = "greedy", Optimal = "optimal" } }

pub(crate) fn parse_non_negative(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("expected a number of at least 0, found \"{s}\"")),
    }
}

pub(crate) fn parse_positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("expected a positive number, found \"{s}\"")),
    }
}

/// `inbetween diff A B`.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(feature = "clap", command(mut_arg("input", |a| a.required(true).index(1).value_name("A")
    .help("Motion A, the reference: CSV, JSON, BVH, glTF, FBX or USD; `-` reads standard input"))))]
pub struct DiffArgs {
    /// Motion A, the reference (its options are those below; `-` reads standard input).
    /// Where the keys come from and how to read them.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub input: InputArgs,

    /// Motion B: CSV, JSON, BVH, glTF, FBX or USD, read with the same options as A.
    #[cfg_attr(feature = "clap", arg(value_name = "B", index = 2))]
    pub other: PathBuf,

    /// The scheme B is interpolated with at A's frame times. Default: as B's format plays it
    /// (glTF samplers as authored, LINEAR by slerp; USD by slerp; others bezier).
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub scheme: Option<SchemeArg>,

    /// The options that shape the curve.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub curve: CurveArgs,

    /// Compare only at the times where both have a key (within 1e-9 s), without interpolating.
    #[cfg_attr(feature = "clap", arg(long))]
    pub common_frames: bool,

    /// With a skeleton, also measure three points this far (length units, world space) from
    /// each joint along its own axes (so that a twist about a bone counts). Without it, a joint
    /// whose rotation moves no point gets such points at its bone length, as reduce
    /// --position-tolerance bounds them; 0: neither.
    #[cfg_attr(feature = "clap", arg(long, value_name = "D", value_parser = parse_non_negative))]
    pub shell: Option<f64>,

    /// Report per compared frame of A the largest world displacement of any point (the curve
    /// view draws) instead of per track; needs world positions (a skeleton).
    #[cfg_attr(feature = "clap", arg(long))]
    pub per_frame: bool,

    /// Exit 1 when any angle exceeds this (--angles units).
    #[cfg_attr(feature = "clap", arg(long, value_name = "ANGLE", value_parser = parse_positive))]
    pub max_angle: Option<f64>,

    /// Exit 1 when any world-space displacement, or any translation difference, exceeds this
    /// (length units).
    #[cfg_attr(feature = "clap", arg(long, value_name = "LEN", value_parser = parse_positive))]
    pub max_position: Option<f64>,

    /// text (an aligned table), csv or json; by default from the extension of -o (.csv,
    /// .json), else text.
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub output_format: Option<ReportFormat>,

    /// Output file, replaced atomically; default standard output.
    #[cfg_attr(
        feature = "clap",
        arg(short = 'o', long = "output", value_name = "PATH")
    )]
    pub output: Option<PathBuf>,
}

/// `inbetween view A [B] -o page.html`: a page that plays the motion (docs/spec.md §1,
/// *Options of `view`*).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[cfg_attr(feature = "clap", command(mut_arg("input", |a| a.required(true).index(1).value_name("A")
    .help("Motion A, with a skeleton: BVH, glTF, FBX or USD; `-` reads standard input"))))]
pub struct ViewArgs {
    /// Motion A (its options are those below; `-` reads standard input).
    /// Where the keys come from and how to read them.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub input: InputArgs,

    /// Motion B, drawn beside A on A's skeleton as diff plays it, with the world displacement
    /// per frame under both; read with the same options as A.
    #[cfg_attr(feature = "clap", arg(value_name = "B", index = 2))]
    pub other: Option<PathBuf>,

    /// The scheme B is interpolated with at A's frame times, as diff's --scheme. Default: as
    /// B's format plays it.
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub scheme: Option<SchemeArg>,

    /// The options that shape the curve.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub curve: CurveArgs,

    /// Show only the times where both have a key (within 1e-9 s), as diff's --common-frames.
    #[cfg_attr(feature = "clap", arg(long))]
    pub common_frames: bool,

    /// The points the displacement curve measures, as diff's --shell: three points this far
    /// (length units, world space) from each joint along its own axes. Without it, as diff: a
    /// joint whose rotation moves no point gets end points at its bone length; 0: neither.
    #[cfg_attr(feature = "clap", arg(long, value_name = "D", value_parser = parse_non_negative))]
    pub shell: Option<f64>,

    /// A world displacement (length units) drawn as a line across the curve, the frames beyond
    /// it marked (the --position-tolerance B was reduced with, say).
    #[cfg_attr(feature = "clap", arg(long, value_name = "LEN", value_parser = parse_positive))]
    pub tolerance: Option<f64>,

    /// The page's title. Default: A's file name, and B's.
    #[cfg_attr(feature = "clap", arg(long, value_name = "TEXT"))]
    pub title: Option<String>,

    /// Open the page with B drawn over A rather than beside it (the page has a toggle).
    #[cfg_attr(feature = "clap", arg(long))]
    pub overlay: bool,

    /// html, the only format view writes; by default from the extension of -o, which must
    /// then be .html or .htm.
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub output_format: Option<PageFormat>,

    /// The page to write (replaced atomically), or - for standard output.
    #[cfg_attr(
        feature = "clap",
        arg(short = 'o', long = "output", value_name = "FILE.html")
    )]
    pub output: PathBuf,
}

named! { PageFormat { Html = "html" } }

/// Several inputs at once (docs/spec.md §1, *Batch*): more inputs, and where their outputs go.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct BatchArgs {
    /// More inputs: files, folders (read recursively, every file of a known extension), or glob
    /// patterns (`clips/*.bvh`, `**` for any folders); they need --out-dir.
    #[cfg_attr(feature = "clap", arg(value_name = "MORE", num_args = 0.., trailing_var_arg = false))]
    pub more: Vec<PathBuf>,

    /// Write each input's output under this folder, at the input's path relative to the folder
    /// or pattern it was found by, with the output format's extension; each written atomically.
    #[cfg_attr(feature = "clap", arg(long, value_name = "DIR"))]
    pub out_dir: Option<PathBuf>,

    /// Inputs processed at once, each on one thread (default: the number of cores).
    #[cfg_attr(feature = "clap", arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024)))]
    pub jobs: Option<u32>,

    /// Append one JSON line per input to this file as each finishes: input, output, status (ok,
    /// skipped, failed), seconds, and the error of a failed input.
    #[cfg_attr(feature = "clap", arg(long, value_name = "FILE"))]
    pub manifest: Option<PathBuf>,

    /// Redo inputs whose output is newer than the input (skipped by default).
    #[cfg_attr(feature = "clap", arg(long))]
    pub refresh: bool,

    /// Follow symbolic links that lead out of the folders named (by default they are skipped;
    /// links inside are followed, each target once).
    #[cfg_attr(feature = "clap", arg(long))]
    pub follow: bool,
}

/// Where the keys come from and how to read them.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct InputArgs {
    /// Input file: CSV, JSON, BVH, glTF (.gltf, .glb), FBX (.fbx) or USD (.usda); `-` or
    /// nothing reads standard input.
    #[cfg_attr(feature = "clap", arg(value_name = "INPUT"))]
    pub input: Option<PathBuf>,

    /// Input representation when the data does not say: the Euler sequence of CSV e1,e2,e3
    /// columns and of JSON "euler" keys, the convention of "rot6d" keys (quat, euler:SEQ, matrix,
    /// axis-angle, rotvec, rot6d:rows, rot6d:columns). A JSON
    /// "rotation" it contradicts is an error.
    #[cfg_attr(feature = "clap", arg(long, value_name = "REPR", value_parser = parse_repr))]
    pub from: Option<Repr>,

    /// Unit of every angle written, and of input angles the document does not declare when
    /// --input-angles is absent (CSV; JSON without "angles").
    #[cfg_attr(feature = "clap", arg(long, value_name = "U", value_parser = parse_angles, default_value = "deg"))]
    pub angles: AngleUnit,

    /// Unit of input angles the document does not declare (CSV; JSON without "angles"), so that
    /// radians can be read and degrees written. A JSON "angles" it contradicts is an error.
    #[cfg_attr(feature = "clap", arg(long, value_name = "U", value_parser = parse_angles))]
    pub input_angles: Option<AngleUnit>,

    /// Rate of the input's frame numbers when the document declares none (CSV always; JSON
    /// without "fps"): 24, 29.97, 30000/1001, ... A JSON "fps" it contradicts is an error.
    #[cfg_attr(feature = "clap", arg(long, value_name = "RATE", value_parser = parse_fps, allow_hyphen_values = true))]
    pub key_fps: Option<Fps>,

    /// CSV field delimiter: , ; tab, or space (runs of spaces and tabs). Default: the one of
    /// the three found most often in the header line (outside quotes), a comma on a tie; space
    /// when there is none and the header has spaces.
    #[cfg_attr(feature = "clap", arg(long, value_name = "C", value_parser = parse_delimiter))]
    pub delimiter: Option<u8>,

    /// Read a timestamped log (one orientation per row, `#` comments): a preset (tum, euroc,
    /// rostopic) or FIELD=COLUMN items time=…,w=…,x=…,y=…,z=… (optional tx=…,ty=…,tz=…), each
    /// column a header name or a number from 1; items after a preset override its own
    /// (rostopic,time=field.header.stamp).
    #[cfg_attr(feature = "clap", arg(long, value_name = "PRESET|MAP", value_parser = parse_columns))]
    pub columns: Option<ColumnMap>,

    /// With --columns: the unit of the time stamps, s, ms, us or ns (us and ns whole numbers,
    /// read exactly). Default: the preset's (tum s; euroc and rostopic ns), else s.
    #[cfg_attr(feature = "clap", arg(long, value_name = "U", value_parser = parse_time_unit))]
    pub time_unit: Option<TimeUnit>,

    /// With --columns: key times relative (the first stamp is 0 s, the others their exact
    /// difference from it) or absolute (the stamps in seconds). Default relative.
    #[cfg_attr(feature = "clap", arg(long, value_name = "T", value_parser = parse_times))]
    pub times: Option<TimeOrigin>,

    /// Component order of quaternions in JSON arrays (CSV columns are named).
    #[cfg_attr(feature = "clap", arg(long, value_name = "O", value_parser = parse_quat_order, default_value = "wxyz"))]
    pub quat_order: QuatOrder,

    /// Input format (csv, json, bvh, gltf, glb, fbx, usda, usdc, usdz, usd); by default from the
    /// file extension, and standard input is sniffed (`{` or `[` first means JSON).
    #[cfg_attr(feature = "clap", arg(long, value_name = "F", value_parser = parse_format))]
    pub input_format: Option<Format>,

    /// glTF input: the animation to read, by name, else by index; default every animation
    /// (tracks named animation/node). FBX input: the animation stack; default the first.
    #[cfg_attr(feature = "clap", arg(long, value_name = "NAME|INDEX"))]
    pub animation: Option<String>,

    /// Refuse an input larger than this many bytes (a file from its size, standard input once
    /// it passes the limit).
    #[cfg_attr(feature = "clap", arg(long, value_name = "N", default_value_t = inbetween_io::DEFAULT_MAX_INPUT_BYTES))]
    pub max_input_bytes: u64,

    /// Only these tracks (joints), by name, comma-separated; `*` and `?` match any characters
    /// and one character (e.g. --tracks 'Left*,Hips'). A pattern that matches nothing is an
    /// error listing the names there are.
    #[cfg_attr(feature = "clap", arg(long, value_name = "NAME,NAME…"))]
    pub tracks: Option<String>,
}

/// Where the output goes and how it is written.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct OutputArgs {
    /// Output representation: quat, euler:SEQ (scipy letters: ZYX intrinsic, zyx extrinsic),
    /// matrix, axis-angle, rotvec, rot6d:rows (pytorch3d's 6D: the matrix's first two rows),
    /// rot6d:columns (Zhou et al.'s: its first two columns).
    #[cfg_attr(feature = "clap", arg(long, value_name = "REPR", value_parser = parse_repr, default_value = "quat"))]
    pub to: Repr,

    /// Output format: csv, json, or (interp only) npy, a NumPy array of float64 rows, or npz,
    /// named NumPy arrays (times, names, rotations, …); bvh, gltf/glb, usda (a UsdSkel
    /// animation), fbx (binary FBX 7.4) for input with a skeleton; by default the input's
    /// format.
    #[cfg_attr(feature = "clap", arg(long, value_name = "F", value_parser = parse_output_format))]
    pub output_format: Option<OutputFormat>,

    /// Output file, replaced atomically (nothing is written on error); default standard output.
    #[cfg_attr(
        feature = "clap",
        arg(short = 'o', long = "output", value_name = "PATH")
    )]
    pub output: Option<PathBuf>,

    /// Euler output along a track: continuous (each triple the one of its rotation nearest the
    /// previous: no jump at ±180°, no flip at gimbal lock) or wrapped (scipy's ranges).
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value = "continuous"))]
    pub euler: EulerArg,

    /// Digits after the decimal point (as printf %.Nf); default: the shortest digits that read
    /// back to the same number.
    #[cfg_attr(feature = "clap", arg(long, value_name = "N", value_parser = parse_precision))]
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

    /// How numbers are written: `--precision` digits, else the shortest that read back.
    pub fn num_format(&self) -> NumFormat {
        self.precision.map_or(NumFormat::Shortest, NumFormat::Fixed)
    }

    /// Euler output along a track: continuous or wrapped.
    pub fn euler_mode(&self) -> EulerMode {
        match self.euler {
            EulerArg::Continuous => EulerMode::Continuous,
            EulerArg::Wrapped => EulerMode::Wrapped,
        }
    }
}

named! { EulerArg { Continuous = "continuous", Wrapped = "wrapped" } }

/// `inbetween convert`: another representation or format of the keys, without interpolating.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct ConvertArgs {
    /// Where the keys come from and how to read them.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub input: InputArgs,

    /// Where the output goes and how it is written.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub output: OutputArgs,

    /// Several inputs at once (empty for one).
    #[cfg_attr(feature = "clap", command(flatten))]
    pub batch: BatchArgs,

    /// Rate of `frame` values in documents that do not give one (JSON "fps" wins for its own
    /// frames): 24, 29.97, 30000/1001, ...
    #[cfg_attr(feature = "clap", arg(long, value_name = "RATE", value_parser = parse_fps, allow_hyphen_values = true))]
    pub fps: Option<Fps>,

    /// Write BVH on this BVH file's skeleton (its hierarchy and channel orders): every track a
    /// joint, keys on one grid of consecutive frames; frames with no declared rate (and no
    /// --fps) are at its Frame Time. Output is BVH unless -o or --output-format says FBX (the
    /// same motion; each track at its own key times).
    #[cfg_attr(feature = "clap", arg(long, value_name = "BVH"))]
    pub skeleton: Option<PathBuf>,
}

/// `inbetween interp`: every frame between the first and last key.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct InterpArgs {
    /// Where the keys come from and how to read them.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub input: InputArgs,

    /// Where the output goes and how it is written.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub output: OutputArgs,

    /// Several inputs at once (empty for one).
    #[cfg_attr(feature = "clap", command(flatten))]
    pub batch: BatchArgs,

    /// Interpolation scheme (bezier: fourth order, C¹, local; nlerp: how Blender plays LINEAR
    /// quaternion keys, and ozz-animation and many engines theirs; see docs/schemes.md).
    /// Default bezier; for glTF input, each sampler as glTF plays it (LINEAR by slerp), and a
    /// scheme given re-interpolates the LINEAR keys.
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub scheme: Option<SchemeArg>,

    /// The options that shape the curve.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub curve: CurveArgs,

    /// Add each frame's world-frame angular velocity: CSV columns wx,wy,wz (JSON
    /// "angular_velocity"), in --angles units per second.
    #[cfg_attr(feature = "clap", arg(long))]
    pub velocity: bool,

    /// Write BVH on this BVH file's skeleton (its hierarchy and channel orders; without --fps
    /// its Frame Time is the rate): a track per joint with channels, found by name, as reduce
    /// and convert write them. Output is BVH unless -o or --output-format says FBX (the same
    /// motion on the same skeleton).
    #[cfg_attr(feature = "clap", arg(long, value_name = "BVH"))]
    pub skeleton: Option<PathBuf>,

    /// Report on stderr what the minaccel solver did for each track (points, iterations, energy,
    /// projected gradient).
    #[cfg_attr(feature = "clap", arg(short, long))]
    pub verbose: bool,

    /// clip: every track over the union of all tracks' key ranges, holding its first key before
    /// its first time and its last key after its last (glTF's clamp); track: each track over its
    /// own keys' range.
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value = "clip"))]
    pub span: SpanArg,

    /// Refuse, before writing anything, a run that would write more frames than this (all
    /// tracks together).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_name = "N", default_value_t = 1_000_000_000)
    )]
    pub max_frames: u64,
}

/// Options that shape the curve (shared by interp, analyze and plot).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct CurveArgs {
    /// Output frame rate: 24, 25, 30, 60, 23.976, 29.97, 59.94 (the exact /1001 ratios),
    /// 30000/1001, any positive number or ratio. Default: the document's "fps", else 30.
    #[cfg_attr(feature = "clap", arg(long, value_name = "RATE", value_parser = parse_fps, allow_hyphen_values = true))]
    pub fps: Option<Fps>,

    /// Hermite blending function: cubic (3u²−2u³) or quadratic (2u², then 1−2(1−u)²).
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value = "cubic"))]
    pub blend: BlendArg,

    /// End condition without a given velocity: chord (along the first/last chord), rest (zero
    /// velocity), or cyclic (a loop: the last key is the first key's rotation, and the tangent
    /// there is computed across the seam). minaccel's ends are free unless rest or a velocity
    /// is given.
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value = "chord"))]
    pub ends: EndsArg,

    /// Tangent of an interior key without its own velocity or TCB values: spline (the slope of
    /// the not-a-knot cubic spline through the seven keys around it, kept near nam-kim's;
    /// fourth order) or nam-kim (log(q₊ q₋⁻¹) over the two intervals; second order). Default:
    /// nam-kim for hermite, spline for the others.
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub tangent: Option<TangentArg>,

    /// Kochanek–Bartels tension T in [-1, 1] at every interior key without its own (a `tension`
    /// column or field): 1 stops at the key, -1 doubles the tangent.
    #[cfg_attr(feature = "clap", arg(long, value_name = "T", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_unit_interval))]
    pub tension: f64,

    /// Kochanek–Bartels continuity C in [-1, 1]: non-zero gives the key a corner (different
    /// incoming and outgoing tangents).
    #[cfg_attr(feature = "clap", arg(long, value_name = "C", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_unit_interval))]
    pub continuity: f64,

    /// Kochanek–Bartels bias B in [-1, 1]: positive leans the tangent towards the incoming
    /// chord, negative towards the outgoing one.
    #[cfg_attr(feature = "clap", arg(long, value_name = "B", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_unit_interval))]
    pub bias: f64,

    /// World-frame angular velocity at the first key, X,Y,Z in --angles units per second
    /// (overrides the document's start_velocity).
    #[cfg_attr(feature = "clap", arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true))]
    pub start_velocity: Option<[f64; 3]>,

    /// World-frame angular velocity at the last key, X,Y,Z in --angles units per second.
    #[cfg_attr(feature = "clap", arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true))]
    pub end_velocity: Option<[f64; 3]>,

    /// shortest: flip each key into the hemisphere of the previous one (every step ≤ 180°);
    /// as-given: keep quaternion signs (a flipped key is reached the long way round); euler
    /// (Euler input only): keep the turns the Euler angles make between keys (0→720° spins
    /// twice).
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value = "shortest"))]
    pub path: PathArg,

    /// Move every key within EPS frame periods of a frame of the output grid onto that frame
    /// before interpolating (for key times rounded by their writer, e.g. 0.0333333 s).
    #[cfg_attr(feature = "clap", arg(long, value_name = "EPS", value_parser = parse_snap))]
    pub snap_keys: Option<f64>,
}

/// `inbetween analyze`: a smoothness report per track and scheme.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct AnalyzeArgs {
    /// Where the keys come from and how to read them.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub input: InputArgs,

    /// Schemes to compare: one, a comma-separated list, or all.
    #[cfg_attr(feature = "clap", arg(long, value_name = "S,S…|all", value_parser = SchemeList::parse, default_value = "all"))]
    pub scheme: SchemeList,

    /// The options that shape the curve.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub curve: CurveArgs,

    /// text (an aligned table), csv or json; by default from the extension of -o (.csv,
    /// .json), else text.
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub output_format: Option<ReportFormat>,

    /// Output file, replaced atomically; default standard output.
    #[cfg_attr(
        feature = "clap",
        arg(short = 'o', long = "output", value_name = "PATH")
    )]
    pub output: Option<PathBuf>,
}

/// `inbetween plot`: an SVG chart of angular speed over time.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
pub struct PlotArgs {
    /// Where the keys come from and how to read them.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub input: InputArgs,

    /// Schemes to draw: one, a comma-separated list, or all.
    #[cfg_attr(feature = "clap", arg(long, value_name = "S,S…|all", value_parser = SchemeList::parse, default_value = "all"))]
    pub scheme: SchemeList,

    /// speed (|ω| over time), components (ωx, ωy, ωz), or energy (accumulated E).
    #[cfg_attr(feature = "clap", arg(long, value_enum, default_value = "speed"))]
    pub what: WhatArg,

    /// The track to draw (default: the first).
    #[cfg_attr(feature = "clap", arg(long, value_name = "NAME"))]
    pub track: Option<String>,

    /// The options that shape the curve.
    #[cfg_attr(feature = "clap", command(flatten))]
    pub curve: CurveArgs,

    /// The SVG file to write (replaced atomically), or - for standard output.
    #[cfg_attr(
        feature = "clap",
        arg(short = 'o', long = "output", value_name = "FILE.svg")
    )]
    pub output: PathBuf,
}

named! { SpanArg { Clip = "clip", Track = "track" } }

named! { WhatArg { Speed = "speed", Components = "components", Energy = "energy" } }

named! { ReportFormat { Text = "text", Csv = "csv", Json = "json" } }

/// A list of schemes (`--scheme hermite,squad` or `all`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SchemeList(pub Vec<SchemeArg>);

impl SchemeList {
    /// `all`, or schemes by name, comma-separated (each once, in the order given).
    pub fn parse(s: &str) -> Result<SchemeList, String> {
        if s == "all" {
            return Ok(SchemeList(SchemeArg::NAMES.iter().map(|n| n.1).collect()));
        }
        let mut out = Vec::new();
        for name in s.split(',').map(str::trim) {
            let v = SchemeArg::parse(name).map_err(|_| {
                format!(
                    "expected schemes from hermite, squad, bezier, slerp, nlerp, minaccel \
                 (comma-separated) or all, found \"{name}\""
                )
            })?;
            if !out.contains(&v) {
                out.push(v);
            }
        }
        Ok(SchemeList(out))
    }
}

named! { SchemeArg { Hermite = "hermite", Squad = "squad", Bezier = "bezier", Slerp = "slerp", Nlerp = "nlerp", Minaccel = "minaccel" } }

named! { BlendArg { Cubic = "cubic", Quadratic = "quadratic" } }

named! { EndsArg { Chord = "chord", Rest = "rest", Cyclic = "cyclic" } }
named! { TangentArg { Spline = "spline", NamKim = "nam-kim" } }

named! { PathArg { Shortest = "shortest", AsGiven = "as-given", Euler = "euler" } }

pub(crate) fn parse_unit_interval(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x.abs() <= 1.0 => Ok(x),
        _ => Err(format!("expected a number between -1 and 1, found \"{s}\"")),
    }
}

pub(crate) fn parse_vec3(s: &str) -> Result<[f64; 3], String> {
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

pub(crate) fn parse_delimiter(s: &str) -> Result<u8, String> {
    match s {
        "," => Ok(b','),
        ";" => Ok(b';'),
        "tab" | "\t" => Ok(b'\t'),
        "space" | " " => Ok(b' '),
        _ => Err(format!(
            "expected \",\", \";\", \"tab\" or \"space\", found \"{s}\""
        )),
    }
}

pub(crate) fn parse_columns(s: &str) -> Result<ColumnMap, String> {
    ColumnMap::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_time_unit(s: &str) -> Result<TimeUnit, String> {
    TimeUnit::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_times(s: &str) -> Result<TimeOrigin, String> {
    TimeOrigin::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_repr(s: &str) -> Result<Repr, String> {
    Repr::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_angles(s: &str) -> Result<AngleUnit, String> {
    AngleUnit::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_quat_order(s: &str) -> Result<QuatOrder, String> {
    QuatOrder::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_output_format(s: &str) -> Result<OutputFormat, String> {
    OutputFormat::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_format(s: &str) -> Result<Format, String> {
    Format::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_fps(s: &str) -> Result<Fps, String> {
    Fps::parse(s).map_err(|e| e.message().to_string())
}

pub(crate) fn parse_snap(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if (0.0..=0.5).contains(&x) => Ok(x),
        _ => Err(format!(
            "expected a number of frame periods from 0 to 0.5, such as 0.001, found \"{s}\""
        )),
    }
}

pub(crate) fn parse_precision(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n <= MAX_PRECISION => Ok(n),
        _ => Err(format!(
            "expected a whole number from 0 to {MAX_PRECISION}, found \"{s}\""
        )),
    }
}
