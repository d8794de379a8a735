//! The bytes of an asset's buffers, and accessors decoded with every range checked.
//!
//! glTF 2.0 §3.6 (*Binary Data Storage*): a buffer is the GLB `BIN` chunk (§4.4.3), a `data:`
//! URI with base64 content, or a file beside the asset; an accessor is `count` elements of
//! `componentType` × `type` in a buffer view, `byteStride` apart (tightly packed when absent),
//! optionally sparse (§3.6.2.3). Nothing here trusts a length or offset it has not checked: a
//! truncated buffer or an accessor running past its view is an error, never a panic, and no
//! allocation is larger than the bytes that back it.
//!
//! An asset comes from a stranger, so a URI is untrusted ([`resolve`]): it is percent-decoded
//! first, then accepted only as a relative path that stays inside the asset's folder once
//! symbolic links are resolved, naming a regular file; at most `byteLength` bytes of it are
//! read, and they count against the asset's byte budget.

use base64::Engine;
use gltf::accessor::{DataType, Dimensions};
use inbetween::error::{Message, Setting};
use inbetween::message;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// Where buffers come from and how many bytes they may take.
pub(super) struct Sources<'a> {
    /// The GLB `BIN` chunk.
    pub blob: Option<&'a [u8]>,
    /// The folder relative URIs are resolved against (none for an asset read from bytes: then
    /// a file reference is an error).
    pub base_dir: Option<&'a Path>,
    /// The most bytes the asset may read in all, its own bytes included.
    pub limit: u64,
    /// The bytes read so far (the asset's own bytes, then each external buffer's).
    pub used: u64,
}

/// The buffers' bytes, and the files they were read from (canonical paths).
pub(super) struct Loaded {
    pub buffers: Vec<Vec<u8>>,
    pub files: Vec<PathBuf>,
}

/// The bytes of every buffer of `doc`, each exactly its declared `byteLength` long. Errors are
/// messages located by JSON path (`buffers[1].uri: …`), without the file name (the caller adds
/// it).
pub(super) fn load_buffers(doc: &gltf::Document, src: &mut Sources) -> Result<Loaded, Message> {
    let mut buffers = Vec::new();
    let mut files = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let len = buffer.length();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => {
                if i != 0 {
                    return Err(format!(
                        "buffers[{i}]: has no uri, but only buffers[0] may refer to the GLB BIN \
                         chunk (glTF 2.0 §4.4.3.3)"
                    )
                    .into());
                }
                let Some(b) = src.blob else {
                    return Err(
                        "buffers[0]: has no uri, so it refers to the GLB BIN chunk, but \
                                the file has none"
                            .into(),
                    );
                };
                if b.len() < len {
                    return Err(format!(
                        "buffers[0].byteLength: {len}, but the BIN chunk has only {} bytes",
                        b.len()
                    )
                    .into());
                }
                b[..len].to_vec()
            }
            gltf::buffer::Source::Uri(uri) => {
                let at = |e: String| {
                    format!(
                        "buffers[{i}].uri (\"{}\"): {e}",
                        inbetween::error::shorten(uri)
                    )
                };
                if let Some(rest) = uri.strip_prefix("data:") {
                    let mut data = decode_data_uri(rest).map_err(at)?;
                    if data.len() < len {
                        return Err(format!(
                            "buffers[{i}].byteLength: {len}, but its data: URI holds only {} \
                             bytes",
                            data.len()
                        )
                        .into());
                    }
                    data.truncate(len);
                    data
                } else {
                    let Some(dir) = src.base_dir else {
                        return Err(at(
                            "an external file needs the asset's path to be found".to_string()
                        )
                        .into());
                    };
                    let path = resolve(uri, dir).map_err(at)?;
                    let after = src.used.saturating_add(len as u64);
                    if after > src.limit {
                        return Err(message![
                            format!(
                                "buffers[{i}].byteLength: {len} bytes from \"{}\" would take \
                                 the input past {} bytes (",
                                inbetween::error::shorten(uri),
                                src.limit
                            ),
                            Setting::MaxInputBytes,
                            ")"
                        ]);
                    }
                    let data = read_file(&path, len).map_err(at)?;
                    if data.len() < len {
                        return Err(format!(
                            "buffers[{i}].byteLength: {len}, but \"{}\" has only {} bytes",
                            inbetween::error::shorten(uri),
                            data.len()
                        )
                        .into());
                    }
                    src.used = after;
                    files.push(path);
                    data
                }
            }
        };
        buffers.push(data);
    }
    Ok(Loaded { buffers, files })
}

/// The bytes of a base64 `data:` URI (what follows `data:`).
fn decode_data_uri(rest: &str) -> Result<Vec<u8>, String> {
    let Some((_, payload)) = rest.split_once(";base64,") else {
        return Err("expected a base64 data: URI".to_string());
    };
    base64::engine::general_purpose::STANDARD
        .decode(payload)
        .map_err(|e| format!("invalid base64 data: {e}"))
}

/// Whether `uri` starts with a scheme (RFC 3986 §3.1: a letter, then letters, digits, `+`, `-`
/// or `.`, then `:`), as `https:` or `data:` do.
pub(super) fn has_scheme(uri: &str) -> bool {
    uri.split_once(':').is_some_and(|(s, _)| {
        s.starts_with(|c: char| c.is_ascii_alphabetic())
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    })
}

/// The path a relative URI names inside `base_dir`, checked without touching the file system:
/// percent-decoded first (§3.6.1.1), then refused when it has a scheme, is absolute, holds a
/// NUL, or climbs out of the folder with `..`.
pub(super) fn relative_path(uri: &str) -> Result<PathBuf, String> {
    if has_scheme(uri) {
        return Err("expected a relative file name or a data: URI".to_string());
    }
    let name = percent_decode(uri)?;
    if name.is_empty() {
        return Err("expected a file name, found an empty URI".to_string());
    }
    if name.contains('\0') {
        return Err("the file name holds a NUL character".to_string());
    }
    if name.starts_with('/') || name.starts_with('\\') || has_scheme(&name) {
        return Err(format!(
            "\"{}\" is an absolute path: expected a file inside the asset's folder",
            inbetween::error::shorten(&name)
        ));
    }
    let path = PathBuf::from(&name);
    let mut depth = 0usize;
    for c in path.components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir if depth > 0 => depth -= 1,
            _ => {
                return Err(format!(
                    "\"{}\" leaves the asset's folder: expected a file inside it",
                    inbetween::error::shorten(&name)
                ));
            }
        }
    }
    Ok(path)
}

/// The canonical path of the file a relative URI names in `base_dir` ([`relative_path`]),
/// refused unless it is a regular file inside the folder once symbolic links are resolved (a
/// link pointing out, a device, a FIFO, a directory).
pub(super) fn resolve(uri: &str, base_dir: &Path) -> Result<PathBuf, String> {
    let rel = relative_path(uri)?;
    let joined = base_dir.join(&rel);
    let shown = || inbetween::error::shorten(&joined.display().to_string()).into_owned();
    let path =
        std::fs::canonicalize(&joined).map_err(|e| format!("cannot read {}: {e}", shown()))?;
    let base = std::fs::canonicalize(base_dir)
        .map_err(|e| format!("cannot resolve the asset's folder: {e}"))?;
    if !path.starts_with(&base) {
        return Err(format!(
            "{} leads to {}, outside the asset's folder (through a symbolic link): expected a \
             file inside it",
            shown(),
            inbetween::error::shorten(&path.display().to_string())
        ));
    }
    let meta = std::fs::metadata(&path).map_err(|e| format!("cannot read {}: {e}", shown()))?;
    if !meta.is_file() {
        return Err(format!(
            "{} is not a regular file (a directory, a device or a FIFO): expected a file",
            shown()
        ));
    }
    Ok(path)
}

/// At most the first `len` bytes of the regular file `path` (checked by [`resolve`]; checked
/// again once open, so that a file swapped for a FIFO or a device is not read).
pub(super) fn read_file(path: &Path, len: usize) -> Result<Vec<u8>, String> {
    let shown = || inbetween::error::shorten(&path.display().to_string()).into_owned();
    let cannot = |e: std::io::Error| format!("cannot read {}: {e}", shown());
    let file = std::fs::File::open(path).map_err(cannot)?;
    let meta = file.metadata().map_err(cannot)?;
    if !meta.is_file() {
        return Err(format!("{} is not a regular file", shown()));
    }
    // Room for what the file holds, never more than asked for.
    let room = usize::try_from(meta.len()).map_or(len, |n| n.min(len));
    let mut data = Vec::new();
    data.try_reserve_exact(room)
        .map_err(|_| format!("cannot read {}: out of memory for {room} bytes", shown()))?;
    file.take(len as u64)
        .read_to_end(&mut data)
        .map_err(cannot)?;
    Ok(data)
}

/// `%20` → space and so on (RFC 3986 percent-encoding, UTF-8).
fn percent_decode(s: &str) -> Result<String, String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| "invalid percent-encoding in the URI".to_string())?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "the URI is not UTF-8 once decoded".to_string())
}

/// How an accessor's components may be stored for a use (glTF 2.0 §3.11, the table of sampler
/// output types).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Storage {
    /// FLOAT only (times, translations).
    Float,
    /// FLOAT, or normalized BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT (rotations).
    FloatOrNormalized,
}

fn dims_name(d: Dimensions) -> &'static str {
    match d {
        Dimensions::Scalar => "SCALAR",
        Dimensions::Vec2 => "VEC2",
        Dimensions::Vec3 => "VEC3",
        Dimensions::Vec4 => "VEC4",
        Dimensions::Mat2 => "MAT2",
        Dimensions::Mat3 => "MAT3",
        Dimensions::Mat4 => "MAT4",
    }
}

fn type_name(t: DataType) -> &'static str {
    match t {
        DataType::I8 => "BYTE",
        DataType::U8 => "UNSIGNED_BYTE",
        DataType::I16 => "SHORT",
        DataType::U16 => "UNSIGNED_SHORT",
        DataType::U32 => "UNSIGNED_INT",
        DataType::F32 => "FLOAT",
    }
}

/// One component as f64: a float32 exactly; a normalized integer by the equations of glTF 2.0
/// §3.11 (*Animations*, and §3.6.2.2): `max(c / 127, −1)` for BYTE, `c / 255` for
/// UNSIGNED_BYTE, `max(c / 32767, −1)` for SHORT, `c / 65535` for UNSIGNED_SHORT.
fn component(t: DataType, b: &[u8]) -> f64 {
    match t {
        DataType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        DataType::I8 => (f64::from(b[0] as i8) / 127.0).max(-1.0),
        DataType::U8 => f64::from(b[0]) / 255.0,
        DataType::I16 => (f64::from(i16::from_le_bytes([b[0], b[1]])) / 32767.0).max(-1.0),
        DataType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
        DataType::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
    }
}

/// The elements of accessor `acc` as f64 components, `dims` each (`count × dims` numbers),
/// checking its type, storage and every byte range. Errors are messages naming the accessor.
pub(super) fn read(
    acc: &gltf::Accessor,
    buffers: &[Vec<u8>],
    dims: Dimensions,
    storage: Storage,
) -> Result<Vec<f64>, String> {
    let i = acc.index();
    let fail = |m: String| format!("accessors[{i}]: {m}");
    if acc.dimensions() != dims {
        return Err(format!(
            "accessors[{i}].type: expected {}, found {}",
            dims_name(dims),
            dims_name(acc.dimensions())
        ));
    }
    let t = acc.data_type();
    let allowed = match storage {
        Storage::Float => t == DataType::F32,
        Storage::FloatOrNormalized => {
            t == DataType::F32
                || (acc.normalized()
                    && matches!(
                        t,
                        DataType::I8 | DataType::U8 | DataType::I16 | DataType::U16
                    ))
        }
    };
    if !allowed {
        let found = if acc.normalized() {
            format!("normalized {}", type_name(t))
        } else {
            type_name(t).to_string()
        };
        let expected = match storage {
            Storage::Float => "FLOAT",
            Storage::FloatOrNormalized => {
                "FLOAT or normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"
            }
        };
        return Err(format!(
            "accessors[{i}].componentType: expected {expected}, found {found}"
        ));
    }
    let n = dims.multiplicity();
    let size = t.size();
    let count = acc.count();
    let total = count
        .checked_mul(n)
        .ok_or_else(|| format!("accessors[{i}].count: {count} is too large"))?;
    let mut out = match acc.view() {
        Some(view) => {
            let buffer = &buffers[view.buffer().index()];
            let bytes = view_bytes(&view, buffer).map_err(&fail)?;
            strided(bytes, acc.offset(), view.stride(), count, n, size, t).map_err(&fail)?
        }
        // No bytes back these zeros: the callers bound `count` first (by the keys a sampler
        // has), and a failed reservation is an error, not an abort.
        None => {
            let mut zeros = Vec::new();
            zeros
                .try_reserve_exact(total)
                .map_err(|_| format!("accessors[{i}].count: {count} is too large"))?;
            zeros.resize(total, 0.0);
            zeros
        }
    };
    if let Some(sparse) = acc.sparse() {
        let k = sparse.count();
        if k > count {
            return Err(format!(
                "accessors[{i}].sparse.count: {k} is larger than the accessor's count {count}"
            ));
        }
        let idx_view = sparse.indices().view();
        let idx_type = match sparse.indices().index_type() {
            gltf::accessor::sparse::IndexType::U8 => DataType::U8,
            gltf::accessor::sparse::IndexType::U16 => DataType::U16,
            gltf::accessor::sparse::IndexType::U32 => DataType::U32,
        };
        let idx_bytes = view_bytes(&idx_view, &buffers[idx_view.buffer().index()])
            .map_err(|e| format!("accessors[{i}].sparse.indices: {e}"))?;
        // Raw unsigned integers, never normalized.
        let idx_size = idx_type.size();
        let start = sparse.indices().offset();
        check_range(idx_bytes.len(), start, idx_size, k, idx_size)
            .map_err(|e| format!("accessors[{i}].sparse.indices: {e}"))?;
        let indices: Vec<f64> = (0..k)
            .map(|j| {
                let b = &idx_bytes[start + j * idx_size..];
                match idx_type {
                    DataType::U8 => f64::from(b[0]),
                    DataType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
                    _ => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                }
            })
            .collect();
        let val_view = sparse.values().view();
        let val_bytes = view_bytes(&val_view, &buffers[val_view.buffer().index()])
            .map_err(|e| format!("accessors[{i}].sparse.values: {e}"))?;
        let values = strided(val_bytes, sparse.values().offset(), None, k, n, size, t)
            .map_err(|e| format!("accessors[{i}].sparse.values: {e}"))?;
        let mut previous: Option<f64> = None;
        for (j, &index) in indices.iter().enumerate() {
            if previous.is_some_and(|p| index <= p) || index >= count as f64 {
                return Err(format!(
                    "accessors[{i}].sparse.indices: index {j} is {index}: expected strictly \
                     increasing indices below {count}"
                ));
            }
            previous = Some(index);
            let e = index as usize;
            out[e * n..(e + 1) * n].copy_from_slice(&values[j * n..(j + 1) * n]);
        }
    }
    Ok(out)
}

/// Checks that `count` elements of `elem` bytes, `stride` apart from `offset`, fit in `len`
/// bytes.
fn check_range(
    len: usize,
    offset: usize,
    stride: usize,
    count: usize,
    elem: usize,
) -> Result<(), String> {
    if count == 0 {
        return Ok(());
    }
    let end = (count - 1)
        .checked_mul(stride)
        .and_then(|x| x.checked_add(offset))
        .and_then(|x| x.checked_add(elem));
    match end {
        Some(end) if end <= len => Ok(()),
        _ => Err(format!(
            "{count} elements of {elem} bytes from byte {offset} run past the end of its \
             buffer view ({len} bytes)"
        )),
    }
}

/// The bytes of buffer view `view`, checked against the buffer's bytes.
fn view_bytes<'b>(view: &gltf::buffer::View, buffer: &'b [u8]) -> Result<&'b [u8], String> {
    let (offset, len) = (view.offset(), view.length());
    offset
        .checked_add(len)
        .and_then(|end| buffer.get(offset..end))
        .ok_or_else(|| {
            format!(
                "bufferViews[{}] (bytes {offset}..{}) runs past the end of buffers[{}] ({} bytes)",
                view.index(),
                offset.saturating_add(len),
                view.buffer().index(),
                buffer.len()
            )
        })
}

/// `count` elements of `n` components of type `t` (`size` bytes each) from `offset` in `bytes`,
/// `stride` bytes apart (tightly packed when `None`).
fn strided(
    bytes: &[u8],
    offset: usize,
    stride: Option<usize>,
    count: usize,
    n: usize,
    size: usize,
    t: DataType,
) -> Result<Vec<f64>, String> {
    let elem = n * size;
    let stride = stride.unwrap_or(elem);
    if stride < elem {
        return Err(format!(
            "byteStride {stride} is smaller than an element ({elem} bytes)"
        ));
    }
    check_range(bytes.len(), offset, stride, count, elem)?;
    let mut out = Vec::with_capacity(count * n);
    for e in 0..count {
        let at = offset + e * stride;
        for c in 0..n {
            out.push(component(t, &bytes[at + c * size..]));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalized_integers_follow_the_spec_equations() {
        assert_eq!(component(DataType::I8, &[127]), 1.0);
        assert_eq!(component(DataType::I8, &[0x81]), -1.0); // -127
        assert_eq!(component(DataType::I8, &[0x80]), -1.0); // -128 clamps
        assert_eq!(component(DataType::U8, &[255]), 1.0);
        assert_eq!(component(DataType::I16, &(-32768i16).to_le_bytes()), -1.0);
        assert_eq!(
            component(DataType::I16, &16384i16.to_le_bytes()),
            16384.0 / 32767.0
        );
        assert_eq!(component(DataType::U16, &65535u16.to_le_bytes()), 1.0);
        assert_eq!(
            component(DataType::F32, &0.1f32.to_le_bytes()),
            f64::from(0.1f32)
        );
    }

    #[test]
    fn percent_encoded_names() {
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
        assert!(percent_decode("a%2").is_err());
        assert!(percent_decode("a%zz").is_err());
    }

    #[test]
    fn strided_reads_are_range_checked() {
        let bytes: Vec<u8> = [1.0f32, 2.0, 3.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        assert_eq!(
            strided(&bytes, 0, None, 3, 1, 4, DataType::F32).unwrap(),
            [1.0, 2.0, 3.0]
        );
        assert_eq!(
            strided(&bytes, 0, Some(8), 2, 1, 4, DataType::F32).unwrap(),
            [1.0, 3.0]
        );
        assert!(strided(&bytes, 4, None, 3, 1, 4, DataType::F32).is_err());
        assert!(strided(&bytes, 0, Some(2), 1, 1, 4, DataType::F32).is_err());
        assert!(strided(&bytes, usize::MAX, None, 2, 1, 4, DataType::F32).is_err());
    }
}
