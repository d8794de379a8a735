//! Wire formats: reading keyframe documents (CSV, JSON, BVH, glTF) and writing keys and frames
//! to any `std::io::Write`. The `inbetween-io` crate, on the maths of `inbetween`; where the bytes
//! go (standard output, a file replaced atomically) is the command line's.
//!
//! - [`document`]: a keyframe document as read, and its validation into [`crate::Track`]s.
//! - [`read`]: the CSV and JSON readers; [`parse_bytes`] and [`read_path`] choose between them.
//! - [`mod@write`]: frame and key writers (CSV, JSON, npy); [`num`]: their number formatting.
//! - [`bvh`] and [`clip`]: BVH files and the skeleton-and-motion clip they hold; [`gltf`]: glTF
//!   2.0 assets; [`fbx`]: FBX scenes, read into a clip.

#![warn(missing_docs, unreachable_pub)]

/// Builds an [`InputError`] with `format!` syntax.
macro_rules! input_err {
    ($($arg:tt)*) => { inbetween::error::InputError::new(format!($($arg)*)) };
}

pub mod amass;
pub mod bvh;
pub mod clip;
pub mod document;
pub mod fbx;
pub mod gltf;
pub mod names;
pub mod num;
pub mod read;
pub mod usd;
pub mod write;

use document::Document;
use inbetween::clock::Fps;
use inbetween::error::shorten;
use inbetween::error::{Error, InputError, InputResult, Setting};
use inbetween::message;
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};
#[allow(unused_imports)]
use inbetween::{EulerSeq, FrameSink, Track};
use std::io::Read;
use std::path::Path;

/// File format of a keyframe document or of the output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values with a header row.
    Csv,
    /// A JSON document.
    Json,
    /// A BVH motion-capture file (input; as output, [`OutputFormat::Bvh`]).
    Bvh,
    /// A glTF 2.0 asset, `.gltf` JSON or `.glb` binary (input; as output,
    /// [`OutputFormat::Gltf`]): its animations' rotation channels ([`gltf::document`]).
    Gltf,
    /// An FBX scene, binary or ASCII (input only): one animation stack as a clip on its node
    /// hierarchy ([`fbx`]), read as a BVH clip is from then on.
    Fbx,
    /// A USD layer, text (`.usda`), binary (`.usdc`) or packaged (`.usdz`; `.usd` names either
    /// syntax, told apart by the bytes): a UsdSkel skeleton's animation ([`usd::read`]).
    Usd,
    /// An AMASS motion file, a NumPy `.npz` archive of SMPL-H or SMPL-X poses ([`amass`]):
    /// input; as output, [`OutputFormat::Npz`] writes it back at the output rate.
    Amass,
}

impl Format {
    /// `csv`, `json`, `bvh`, `gltf`/`glb` (either container: it is recognised by its
    /// bytes), `fbx`, `usda`/`usdc`/`usdz`/`usd` (any USD syntax: it is recognised by its bytes)
    /// or `npz` (an AMASS motion file).
    pub fn parse(s: &str) -> InputResult<Format> {
        match s {
            "csv" => Ok(Format::Csv),
            "json" => Ok(Format::Json),
            "bvh" => Ok(Format::Bvh),
            "gltf" | "glb" => Ok(Format::Gltf),
            "fbx" => Ok(Format::Fbx),
            "usda" | "usdc" | "usdz" | "usd" => Ok(Format::Usd),
            "npz" => Ok(Format::Amass),
            _ => Err(input_err!(
                "expected \"csv\", \"json\", \"bvh\", \"gltf\", \"glb\", \"fbx\", \"usda\", \"usdc\", \"usdz\", \"usd\" or \"npz\", found \"{s}\""
            )),
        }
    }

    /// From a file extension (`.csv`, `.json`, `.bvh`, `.gltf`, `.glb`, `.fbx`, `.usda`,
    /// `.usdc`, `.usdz`, `.usd`, `.npz`, case-insensitive).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "csv" => Some(Format::Csv),
            "json" => Some(Format::Json),
            "bvh" => Some(Format::Bvh),
            "gltf" | "glb" => Some(Format::Gltf),
            "fbx" => Some(Format::Fbx),
            "usda" | "usd" | "usdc" | "usdz" => Some(Format::Usd),
            "npz" => Some(Format::Amass),
            _ => None,
        }
    }

    /// Sniffs content: the first non-blank character `{` or `[` means JSON, anything else CSV.
    pub fn sniff(text: &str) -> Format {
        let t = text.strip_prefix('\u{feff}').unwrap_or(text).trim_start();
        if t.starts_with('{') || t.starts_with('[') {
            Format::Json
        } else if t.starts_with("HIERARCHY") {
            Format::Bvh
        } else if t.starts_with("#usda") {
            Format::Usd
        } else {
            Format::Csv
        }
    }
}

/// Output format of a command: a document format, or NumPy `.npy` / `.npz` (interp's frames only).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    /// A keyframe-document format.
    Doc(Format),
    /// A NumPy `.npy` array of float64 rows.
    Npy,
    /// A NumPy `.npz` archive of named arrays (frames × tracks).
    Npz,
    /// A BVH file on the input's skeleton (BVH input only).
    Bvh,
    /// The input glTF asset with resampled rotation channels (glTF input only), in this
    /// container.
    Gltf(gltf::ContainerFormat),
    /// A USD layer in text form (`.usda`): a UsdSkel skeleton and its animation (input with a
    /// skeleton only: BVH, glTF, FBX).
    Usda,
    /// A binary FBX scene (7.4): the skeleton as LimbNode models and its motion as per-channel
    /// Euler curves ([`fbx::write`]; input with a skeleton only).
    Fbx,
}

impl OutputFormat {
    /// `csv`, `json`, `npy`, `npz`, `bvh`, `gltf`, `glb`, `usda` or `fbx`.
    pub fn parse(s: &str) -> InputResult<OutputFormat> {
        match s {
            "npy" => Ok(OutputFormat::Npy),
            "npz" => Ok(OutputFormat::Npz),
            "bvh" => Ok(OutputFormat::Bvh),
            "gltf" => Ok(OutputFormat::Gltf(gltf::ContainerFormat::Gltf)),
            "glb" => Ok(OutputFormat::Gltf(gltf::ContainerFormat::Glb)),
            "usda" => Ok(OutputFormat::Usda),
            "fbx" => Ok(OutputFormat::Fbx),
            "csv" | "json" => Format::parse(s).map(OutputFormat::Doc),
            _ => Err(input_err!(
                "expected \"csv\", \"json\", \"npy\", \"npz\", \"bvh\", \"gltf\", \"glb\", \"usda\" or \"fbx\", found \"{s}\""
            )),
        }
    }
}

/// How to interpret input values the data does not describe itself: the command line's
/// statements about the input, applied by the one precedence rule of [`settle`].
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct ReadOptions {
    /// `--from`: the representation when the data does not say (the Euler sequence of CSV
    /// `e1,e2,e3` columns and of JSON `euler` keys); contradicting a JSON `rotation` is an error.
    pub from: Option<Repr>,
    /// `--angles`: the unit of undeclared input angles when `input_angles` is absent (it never
    /// conflicts with a declaration).
    pub angles: AngleUnit,
    /// `--input-angles`: the unit of undeclared input angles; contradicting a JSON `angles` is an
    /// error.
    pub input_angles: Option<AngleUnit>,
    /// `--key-fps`: the rate of `frame` numbers when the document declares none; contradicting a
    /// JSON `fps` is an error.
    pub key_fps: Option<Fps>,
    /// `--quat-order`: component order of JSON quaternion arrays.
    pub quat_order: QuatOrder,
    /// `--delimiter`: the CSV field delimiter (`,`, `;` or tab); by default detected from the
    /// header line (`detect_delimiter`); `b' '` is runs of spaces and tabs.
    pub delimiter: Option<u8>,
    /// `--columns`: read CSV input as a timestamped log through this column map
    /// ([`read::log`]) instead of by its column names.
    pub columns: Option<read::log::ColumnMap>,
}

impl ReadOptions {
    /// The unit of input angles the document does not declare: `--input-angles`, else
    /// `--angles`.
    pub fn undeclared_angles(&self) -> AngleUnit {
        self.input_angles.unwrap_or(self.angles)
    }
}

/// The one precedence rule between a document's declaration and a flag (docs/spec.md §3,
/// *Precedence*): a declaration describes the document's own values and wins; a flag describes
/// only what the document leaves undeclared; a flag that contradicts a declaration is an input
/// error naming both: `keys.json declares "rotation": "euler:ZYX" but rotation
/// representation says euler:XYZ` (on the command line, `… but --from says euler:XYZ`).
///
/// `field` is the document's field, `declared` its value as written (`"euler:ZYX"`, `30`),
/// `setting` the option given. Returns the value that applies, if any.
pub fn settle<T: PartialEq + std::fmt::Display>(
    source: &str,
    field: &str,
    declared: Option<(T, &str)>,
    setting: Setting,
    given: Option<T>,
) -> InputResult<Option<T>> {
    match (declared, given) {
        (Some((d, written)), Some(g)) if d != g => Err(InputError::new(message![
            format!("{source} declares \"{field}\": {} but ", shorten(written)),
            setting,
            format!(" says {g}")
        ])),
        (Some((d, _)), _) => Ok(Some(d)),
        (None, g) => Ok(g),
    }
}

/// Whether bytes are a glTF asset: the format as given, else `path`'s extension, else the
/// bytes start with the GLB magic `glTF` or are a JSON object with a top-level `"asset"` (a
/// `.gltf` on standard input).
pub fn is_gltf(bytes: &[u8], path: Option<&Path>, format: Option<Format>) -> bool {
    format
        .or_else(|| path.and_then(Format::from_path))
        .map_or_else(
            || bytes.starts_with(b"glTF") || gltf::has_asset_member(bytes),
            |f| f == Format::Gltf,
        )
}

/// Parses a document from raw bytes: the format as given, else from `path`'s extension, else
/// sniffed. An `.npz` archive (a zip's bytes, `amass::is_npz`) is an AMASS motion file. A glTF asset (binary or JSON, [`is_gltf`]) is read with every animation, its keys
/// snapped to `--key-fps`, else 30 fps, a `STEP` channel as its held values on those frames
/// and a `CUBICSPLINE` one as its vertices ([`gltf::document`]); external buffers are looked up beside `path`. Anything else must be
/// UTF-8. `source` names the input in messages.
pub fn parse_bytes(
    bytes: Vec<u8>,
    source: &str,
    path: Option<&Path>,
    format: Option<Format>,
    opts: &ReadOptions,
) -> Result<(Document, Format), Error> {
    if is_gltf(&bytes, path, format) {
        if opts.columns.is_some() {
            return Err(columns_refused(source, Format::Gltf).into());
        }
        let dir = path.map(gltf_dir);
        let asset = gltf::Asset::from_slice(&bytes, source, dir.as_deref())?;
        let clip = gltf::document::GltfClip::new(asset, None)?;
        let fps = opts.key_fps.unwrap_or(Fps::DEFAULT);
        return Ok((
            clip.document(fps, gltf::document::Mode::Frames)?,
            Format::Gltf,
        ));
    }
    if is_fbx_input(&bytes, path, format) {
        if opts.columns.is_some() {
            return Err(columns_refused(source, Format::Fbx).into());
        }
        let fbx = fbx::read(&bytes, source, None)?;
        return Ok((fbx_document(fbx, source), Format::Fbx));
    }
    let declared = format.or_else(|| path.and_then(Format::from_path));
    // USD in any syntax: declared or named so (text, crate or package), else a crate's magic,
    // else (undeclared, unnamed: standard input) a zip whose first entry is a USD layer.
    let usd = match declared {
        Some(f) => f == Format::Usd,
        None => usd::is_binary_usd(&bytes),
    };
    if usd {
        return Ok((usd::read::read_bytes(&bytes, source)?, Format::Usd));
    }
    if amass::is_npz(&bytes, path, format) {
        let clip = amass::read(&bytes, source, opts.key_fps)?;
        return Ok((clip.document()?, Format::Amass));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        input_err!(
            "{source}: expected UTF-8 text, found an invalid byte at offset {}",
            e.utf8_error().valid_up_to()
        )
    })?;
    let format = format
        .or_else(|| path.and_then(Format::from_path))
        .unwrap_or_else(|| Format::sniff(&text));
    Ok((read_document(&text, source, format, opts)?, format))
}

/// The error of a column map given for input that is not CSV: a map says where a timestamped
/// log's fields are, and nothing else has columns.
pub fn columns_refused(source: &str, format: Format) -> InputError {
    input_err!(
        "{source}: a column map reads CSV and text logs (tum, euroc, rostopic), not {}",
        format!("{format:?}").to_ascii_uppercase()
    )
}

/// Whether bytes are FBX: the format as given, else `path`'s extension, else the bytes
/// (`is_fbx`).
pub fn is_fbx_input(bytes: &[u8], path: Option<&Path>, format: Option<Format>) -> bool {
    format
        .or_else(|| path.and_then(Format::from_path))
        .map_or_else(|| fbx::is_fbx(bytes), |f| f == Format::Fbx)
}

/// An FBX file's animation stack (`animation` names it when the scene has several) as a
/// document: its BVH clip's ([`bvh::document::document`]), with its warnings, unit and up axis.
pub fn read_fbx(bytes: &[u8], source: &str, animation: Option<&str>) -> Result<Document, Error> {
    Ok(fbx_document(fbx::read(bytes, source, animation)?, source))
}

/// An FBX clip as a document: its BVH clip's ([`bvh::document::document`]), with its warnings.
pub(crate) fn fbx_document(fbx: fbx::FbxClip, source: &str) -> Document {
    let (unit, z_up) = (fbx.unit_meters, fbx.z_up);
    let mut doc = bvh::document::document(fbx.clip, source, fbx.warnings);
    doc.unit_meters = (unit.is_finite() && unit > 0.0).then_some(unit);
    doc.z_up = Some(z_up);
    doc
}

/// The folder where the external buffers of the glTF file at `path` are: its parent.
pub fn gltf_dir(path: &Path) -> std::path::PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    }
}

/// The default limit on the size of an input: 1 GiB. A keyframe document larger than this is an
/// input error rather than an unbounded allocation (reading `/dev/zero` stops here).
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 1 << 30;

fn too_large(source: &str, limit: u64) -> InputError {
    InputError::new(message![
        format!("{source}: input larger than {limit} bytes ("),
        Setting::MaxInputBytes,
        ")"
    ])
}

/// Reads all of `reader` (standard input, a pipe, a file), at most `limit` bytes: one byte more
/// is an input error `<source>: input larger than <limit> bytes (input size limit)` (the
/// binary shows the setting as `--max-input-bytes`), and
/// reading stops there (it never reads more than `limit + 1` bytes).
pub fn read_limited(reader: &mut dyn Read, limit: u64, source: &str) -> InputResult<Vec<u8>> {
    read_limited_with_capacity(reader, limit, source, 0)
}

fn read_limited_with_capacity(
    reader: &mut dyn Read,
    limit: u64,
    source: &str,
    capacity: usize,
) -> InputResult<Vec<u8>> {
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(capacity)
        .map_err(|_| input_err!("{source}: cannot read: out of memory for {capacity} bytes"))?;
    reader
        .take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| input_err!("{source}: cannot read: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(too_large(source, limit));
    }
    Ok(bytes)
}

/// Reads and parses a keyframe file of at most [`DEFAULT_MAX_INPUT_BYTES`] (see
/// [`read_path_limited`]).
pub fn read_path(
    path: &Path,
    format: Option<Format>,
    opts: &ReadOptions,
) -> Result<(Document, Format), Error> {
    read_path_limited(path, format, opts, DEFAULT_MAX_INPUT_BYTES)
}

/// Reads and parses a keyframe file (see [`parse_bytes`]) of at most `limit` bytes, else the
/// input error of [`read_limited`]. A regular file larger than `limit` is refused before it is
/// read; anything else (a pipe, a device) is read up to `limit + 1` bytes.
pub fn read_path_limited(
    path: &Path,
    format: Option<Format>,
    opts: &ReadOptions,
    limit: u64,
) -> Result<(Document, Format), Error> {
    let bytes = read_bytes_limited(path, limit)?;
    parse_bytes(bytes, &path.display().to_string(), Some(path), format, opts)
}

/// The bytes of a file of at most `limit` bytes, else the input error of [`read_limited`]. A
/// regular file larger than `limit` is refused before it is read; anything else (a pipe, a
/// device) is read up to `limit + 1` bytes.
pub fn read_bytes_limited(path: &Path, limit: u64) -> InputResult<Vec<u8>> {
    let source = path.display().to_string();
    let cannot = |e: std::io::Error| input_err!("{source}: cannot read: {e}");
    let mut file = std::fs::File::open(path).map_err(cannot)?;
    // The size of a regular file, to refuse it unread or to read it into one allocation.
    let size = file
        .metadata()
        .ok()
        .filter(|m| m.is_file())
        .map(|m| m.len());
    if size.is_some_and(|n| n > limit) {
        return Err(too_large(&source, limit));
    }
    // One byte more than the size, so that a file that grew while being read is still caught
    // without a second allocation.
    let capacity = size.map_or(0, |n| usize::try_from(n.saturating_add(1)).unwrap_or(0));
    read_limited_with_capacity(&mut file, limit, &source, capacity)
}

/// Parses a document in the given format.
pub fn read_document(
    text: &str,
    source: &str,
    format: Format,
    opts: &ReadOptions,
) -> Result<Document, Error> {
    match format {
        Format::Csv => Ok(match &opts.columns {
            Some(map) => read::log::read(text, source, map, opts)?,
            None => read::csv::read(text, source, opts)?,
        }),
        _ if opts.columns.is_some() => Err(columns_refused(source, format).into()),
        Format::Json => Ok(read::json::read(text, source, opts)?),
        Format::Bvh => {
            let (clip, warnings) = bvh::parse(text, source)?;
            Ok(bvh::document::document(clip, source, warnings))
        }
        Format::Fbx => Ok(fbx_document(
            fbx::read(text.as_bytes(), source, None)?,
            source,
        )),
        Format::Usd => Ok(usd::read::read(text, source)?),
        Format::Amass => Ok(amass::read(text.as_bytes(), source, opts.key_fps)?.document()?),
        Format::Gltf => {
            let asset = gltf::Asset::from_slice(text.as_bytes(), source, None)?;
            let clip = gltf::document::GltfClip::new(asset, None)?;
            let fps = opts.key_fps.unwrap_or(Fps::DEFAULT);
            Ok(clip.document(fps, gltf::document::Mode::Frames)?)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settle_is_the_one_precedence_rule() {
        let zyx = Repr::parse("euler:ZYX").unwrap();
        let xyz = Repr::parse("euler:XYZ").unwrap();
        let settled = |declared: Option<Repr>, given: Option<Repr>| {
            settle(
                "k.json",
                "rotation",
                declared.map(|r| (r, "\"euler:ZYX\"")),
                Setting::Rotation,
                given,
            )
        };
        // Declared alone, given alone, neither, both agreeing.
        assert_eq!(settled(Some(zyx), None).unwrap(), Some(zyx));
        assert_eq!(settled(None, Some(xyz)).unwrap(), Some(xyz));
        assert_eq!(settled(None, None).unwrap(), None);
        assert_eq!(settled(Some(zyx), Some(zyx)).unwrap(), Some(zyx));
        // Contradicting: an error naming both.
        assert_eq!(
            settled(Some(zyx), Some(xyz)).unwrap_err().message(),
            "k.json declares \"rotation\": \"euler:ZYX\" but rotation representation says euler:XYZ"
        );
        let fps = settle(
            "k.json",
            "fps",
            Some((Fps::parse("24").unwrap(), "24")),
            Setting::KeyRate,
            Some(Fps::parse("30000/1001").unwrap()),
        );
        assert_eq!(
            fps.unwrap_err().message(),
            "k.json declares \"fps\": 24 but key rate says 30000/1001"
        );
    }

    #[test]
    fn gltf_is_read_from_bytes_before_the_utf8_check() {
        let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
            .join("fixtures/gltf/samplers.glb");
        let opts = ReadOptions::default();
        let (doc, format) = read_path(&path, None, &opts).unwrap();
        assert_eq!(format, Format::Gltf);
        assert_eq!(doc.tracks[0].name.as_deref(), Some("Mixed/step"));
        // Sniffed from the GLB magic, without a name.
        let bytes = std::fs::read(&path).unwrap();
        let (sniffed, format) = parse_bytes(bytes, "<stdin>", None, None, &opts).unwrap();
        assert_eq!(
            (sniffed.tracks.len(), format),
            (doc.tracks.len(), Format::Gltf)
        );
        assert_eq!(Format::parse("glb").unwrap(), Format::Gltf);
        assert_eq!(
            OutputFormat::parse("glb").unwrap(),
            OutputFormat::Gltf(gltf::ContainerFormat::Glb)
        );
    }

    #[test]
    fn input_angles_win_over_angles_for_undeclared_input() {
        let mut o = ReadOptions {
            angles: AngleUnit::Rad,
            ..ReadOptions::default()
        };
        assert_eq!(o.undeclared_angles(), AngleUnit::Rad);
        o.input_angles = Some(AngleUnit::Deg);
        assert_eq!(o.undeclared_angles(), AngleUnit::Deg);
    }
}
