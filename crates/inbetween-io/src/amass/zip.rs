//! Reading a zip archive held in memory, the container of a NumPy `.npz` file: `np.savez`
//! stores its entries (method 0), `np.savez_compressed` deflates them (method 8).
//!
//! PKWARE APPNOTE 6.3.10: the end of central directory record (§4.3.16, within the last 65,557
//! bytes), with its ZIP64 counterpart when a field is saturated (§4.3.14–15); the central
//! directory (§4.3.12), whose sizes and offsets are authoritative (numpy writes each entry with
//! `force_zip64`, so a local header's own sizes are placeholders); each entry's local header
//! (§4.3.7) only for where its data starts. Every count, size and offset is checked against the
//! file before anything is allocated from it; the inflated bytes are bounded by the declared
//! size (and by [`MAX_INFLATED`] in all) and checked against the CRC-32 the directory declares.
//! Encrypted entries, other methods and archives spanning disks are refused.

use crate::write::zip::crc32;
use inbetween::error::InputResult;

/// The most bytes the entries of one archive may inflate to, together: 1 GiB, the default input
/// size limit, so that a small compressed file cannot claim an unbounded allocation.
pub(crate) const MAX_INFLATED: u64 = crate::DEFAULT_MAX_INPUT_BYTES;

const END_RECORD: usize = 22;
const ZIP64_LOCATOR: usize = 20;
const ZIP64_END: usize = 56;
const CENTRAL_HEADER: usize = 46;
const LOCAL_HEADER: usize = 30;

/// One entry of the archive: its name and its bytes as stored.
#[derive(Debug, Clone)]
pub(crate) struct Entry<'a> {
    /// The name as stored (numpy's: the array's key and `.npy`).
    pub(crate) name: String,
    method: u16,
    crc: u32,
    size: u64,
    stored: &'a [u8],
}

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

fn u64_at(b: &[u8], at: usize) -> Option<u64> {
    Some(u64::from_le_bytes(b.get(at..at + 8)?.try_into().ok()?))
}

/// The position of the end of central directory record: the last signature `PK\5\6` whose
/// comment length reaches exactly to the end of the file.
fn end_record(b: &[u8]) -> Option<usize> {
    let last = b.len().checked_sub(END_RECORD)?;
    let first = last.saturating_sub(usize::from(u16::MAX));
    (first..=last).rev().find(|&p| {
        u32_at(b, p) == Some(0x0605_4b50)
            && u16_at(b, p + 20).is_some_and(|c| p + END_RECORD + usize::from(c) == b.len())
    })
}

/// The central directory: `(entries, offset, size)` from the end record, or its ZIP64 record
/// when a field is saturated; `end` is where the directory must end.
fn directory(b: &[u8], source: &str) -> InputResult<(u64, u64, u64, usize)> {
    let bad = |what: &str| input_err!("{source}: not a readable zip archive (.npz): {what}");
    let Some(eocd) = end_record(b) else {
        return Err(bad(if b.len() < END_RECORD {
            "too short for a zip archive"
        } else {
            "no end of central directory record (truncated?)"
        }));
    };
    let field = |at: usize| u16_at(b, eocd + at).unwrap_or(0);
    if field(4) != 0 || field(6) != 0 {
        return Err(bad("an archive spanning several disks"));
    }
    let count = u64::from(field(10));
    let size = u64::from(u32_at(b, eocd + 12).unwrap_or(0));
    let offset = u64::from(u32_at(b, eocd + 16).unwrap_or(0));
    let saturated = count == 0xFFFF || size == 0xFFFF_FFFF || offset == 0xFFFF_FFFF;
    let locator = eocd.checked_sub(ZIP64_LOCATOR);
    let zip64 = locator.filter(|&l| saturated && u32_at(b, l) == Some(0x0706_4b50));
    let Some(l) = zip64 else {
        return Ok((count, offset, size, eocd));
    };
    let at = u64_at(b, l + 8).unwrap_or(u64::MAX);
    let rec = usize::try_from(at)
        .ok()
        .filter(|&r| r.checked_add(ZIP64_END).is_some_and(|e| e <= l))
        .filter(|&r| u32_at(b, r) == Some(0x0606_4b50))
        .ok_or_else(|| bad("a ZIP64 end record outside the file"))?;
    let read = |at: usize| u64_at(b, rec + at).unwrap_or(u64::MAX);
    Ok((read(32), read(48), read(40), rec))
}

/// The entries of the archive `b`, in directory order, checked against the file (see the
/// module documentation); `source` names the file in messages.
pub(crate) fn entries<'a>(b: &'a [u8], source: &str) -> InputResult<Vec<Entry<'a>>> {
    let bad = |what: String| input_err!("{source}: not a readable zip archive (.npz): {what}");
    let (count, offset, size, end) = directory(b, source)?;
    let start = usize::try_from(offset).ok();
    let cd = start
        .zip(usize::try_from(size).ok())
        .and_then(|(s, n)| Some((s, s.checked_add(n)?)))
        .filter(|&(_, e)| e <= end)
        .ok_or_else(|| {
            bad(format!(
                "its central directory ({size} bytes at offset {offset}) is outside the file \
                 ({} bytes; truncated?)",
                b.len()
            ))
        })?;
    let dir = &b[cd.0..cd.1];
    if count.saturating_mul(CENTRAL_HEADER as u64) > size {
        return Err(bad(format!(
            "{count} entries declared in a central directory of {size} bytes"
        )));
    }
    let mut out: Vec<Entry<'a>> = Vec::with_capacity(count as usize);
    let mut at = 0usize;
    let mut inflated = 0u64;
    for i in 0..count {
        let entry =
            central(b, dir, &mut at, cd.0).map_err(|what| bad(format!("entry {i}: {what}")))?;
        if entry.flags & 1 != 0 {
            return Err(bad(format!("entry \"{}\" is encrypted", entry.name)));
        }
        if entry.method != 0 && entry.method != 8 {
            return Err(bad(format!(
                "entry \"{}\" is compressed by method {}; only stored (np.savez) and deflated \
                 (np.savez_compressed) entries are read",
                entry.name, entry.method
            )));
        }
        if entry.method == 0 && entry.stored.len() as u64 != entry.size {
            return Err(bad(format!(
                "entry \"{}\" is stored with {} bytes but declares {} bytes",
                entry.name,
                entry.stored.len(),
                entry.size
            )));
        }
        inflated = inflated.saturating_add(entry.size);
        if inflated > MAX_INFLATED {
            return Err(input_err!(
                "{source}: its entries declare more than {MAX_INFLATED} bytes in all; not read"
            ));
        }
        if out.iter().any(|e| e.name == entry.name) {
            return Err(bad(format!("entry \"{}\" appears twice", entry.name)));
        }
        out.push(Entry {
            name: entry.name,
            method: entry.method,
            crc: entry.crc,
            size: entry.size,
            stored: entry.stored,
        });
    }
    Ok(out)
}

/// A central directory header as read, with its data located.
struct Central<'a> {
    name: String,
    flags: u16,
    method: u16,
    crc: u32,
    size: u64,
    stored: &'a [u8],
}

/// The central directory header at `dir[*at..]` (advancing `at`), its entry's data located in
/// `b` before `cd_start`.
fn central<'a>(
    b: &'a [u8],
    dir: &[u8],
    at: &mut usize,
    cd_start: usize,
) -> Result<Central<'a>, String> {
    let h = *at;
    if u32_at(dir, h) != Some(0x0201_4b50) || h + CENTRAL_HEADER > dir.len() {
        return Err("no central directory header where one should be".into());
    }
    let f16 = |o: usize| u16_at(dir, h + o).unwrap_or(0);
    let f32_ = |o: usize| u32_at(dir, h + o).unwrap_or(0);
    let (flags, method, crc) = (f16(8), f16(10), f32_(16));
    let (mut compressed, mut size) = (u64::from(f32_(20)), u64::from(f32_(24)));
    let (name_len, extra_len, comment_len) = (f16(28) as usize, f16(30) as usize, f16(32) as usize);
    let mut local = u64::from(f32_(42));
    let name_at = h + CENTRAL_HEADER;
    let extra_at = name_at + name_len;
    let next = extra_at + extra_len + comment_len;
    if next > dir.len() {
        return Err("a central directory header runs past the directory".into());
    }
    let name = String::from_utf8_lossy(&dir[name_at..extra_at]).into_owned();
    // The ZIP64 extra field: the saturated fields, in this order.
    let mut x = extra_at;
    while x + 4 <= extra_at + extra_len {
        let (id, len) = (
            u16_at(dir, x).unwrap_or(0),
            u16_at(dir, x + 2).unwrap_or(0) as usize,
        );
        let body = x + 4;
        if body + len > extra_at + extra_len {
            return Err(format!("\"{name}\": an extra field runs past its header"));
        }
        if id == 1 {
            let mut p = body;
            for v in [&mut size, &mut compressed, &mut local] {
                if *v == 0xFFFF_FFFF {
                    *v = (p + 8 <= body + len)
                        .then(|| u64_at(dir, p))
                        .flatten()
                        .ok_or_else(|| format!("\"{name}\": a ZIP64 extra field too short"))?;
                    p += 8;
                }
            }
        }
        x = body + len;
    }
    *at = next;
    let outside = || format!("\"{name}\": its data is outside the file (truncated?)");
    let lh = usize::try_from(local).map_err(|_| outside())?;
    if u32_at(b, lh) != Some(0x0403_4b50) {
        return Err(format!("\"{name}\": no local header at offset {local}"));
    }
    let skip = LOCAL_HEADER
        + u16_at(b, lh + 26).unwrap_or(0) as usize
        + u16_at(b, lh + 28).unwrap_or(0) as usize;
    let data = lh.checked_add(skip).ok_or_else(outside)?;
    let end = usize::try_from(compressed)
        .ok()
        .and_then(|c| data.checked_add(c))
        .filter(|&e| e <= cd_start)
        .ok_or_else(outside)?;
    Ok(Central {
        name,
        flags,
        method,
        crc,
        size,
        stored: &b[data..end],
    })
}

impl Entry<'_> {
    /// The entry's bytes: stored ones as they are, deflated ones inflated to exactly the
    /// declared size; either checked against the declared CRC-32.
    pub(crate) fn data(&self, source: &str) -> InputResult<std::borrow::Cow<'_, [u8]>> {
        let name = &self.name;
        let bytes = match self.method {
            0 => std::borrow::Cow::Borrowed(self.stored),
            _ => {
                let limit = usize::try_from(self.size).unwrap_or(usize::MAX);
                let out = miniz_oxide::inflate::decompress_to_vec_with_limit(self.stored, limit)
                    .map_err(|e| {
                        input_err!(
                            "{source}: entry \"{name}\": cannot inflate its deflated bytes \
                             ({:?}; truncated or corrupt?)",
                            e.status
                        )
                    })?;
                if out.len() as u64 != self.size {
                    return Err(input_err!(
                        "{source}: entry \"{name}\": inflates to {} bytes but declares {}",
                        out.len(),
                        self.size
                    ));
                }
                std::borrow::Cow::Owned(out)
            }
        };
        if crc32(0, &bytes) != self.crc {
            return Err(input_err!(
                "{source}: entry \"{name}\": its CRC-32 does not match its bytes (corrupt?)"
            ));
        }
        Ok(bytes)
    }
}
