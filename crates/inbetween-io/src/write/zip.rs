//! A zip archive of stored (uncompressed) entries, the container of a NumPy `.npz` file.
//!
//! PKWARE APPNOTE 6.3.10: per entry a local file header (§4.3.7) and the bytes; then the central
//! directory (§4.3.12) and its end record (§4.3.16). Method 0 (stored), no data descriptor, no
//! ZIP64: every entry and the whole archive at most [`MAX_BYTES`]; the time stamp is fixed
//! (1980-01-01 00:00, the earliest a zip can say) so that the bytes depend on the data alone.

use std::io::{self, Write};

/// The largest entry, and the largest archive, a zip without ZIP64 holds (`u32::MAX` bytes).
pub const MAX_BYTES: u64 = u32::MAX as u64;

/// The fixed header sizes: local file header, central directory header, end record (without
/// the names).
pub(crate) const LOCAL_HEADER: u64 = 30;
const CENTRAL_HEADER: u64 = 46;
const END_RECORD: u64 = 22;

/// The bytes of an archive whose entries have these names and data sizes.
pub(crate) fn archive_size(entries: &[(usize, u64)]) -> u64 {
    entries
        .iter()
        .map(|&(name, data)| LOCAL_HEADER + CENTRAL_HEADER + 2 * name as u64 + data)
        .sum::<u64>()
        + END_RECORD
}

/// CRC-32 (ISO-HDLC: reflected polynomial 0xEDB88320, initial and final value 0xFFFFFFFF), as
/// zip stores it, continued from `crc` (0 to start) over `bytes`.
pub(crate) fn crc32(crc: u32, bytes: &[u8]) -> u32 {
    const TABLE: [u32; 256] = {
        let mut table = [0u32; 256];
        let mut i = 0;
        while i < 256 {
            let mut c = i as u32;
            let mut k = 0;
            while k < 8 {
                c = if c & 1 == 1 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
                k += 1;
            }
            table[i] = c;
            i += 1;
        }
        table
    };
    let mut c = !crc;
    for &b in bytes {
        c = TABLE[((c ^ u32::from(b)) & 0xFF) as usize] ^ (c >> 8);
    }
    !c
}

/// One entry already written: what the central directory repeats.
struct Entry {
    name: String,
    crc: u32,
    size: u32,
    offset: u32,
}

/// Writes stored entries one after another, then the central directory on [`ZipWriter::finish`].
pub(crate) struct ZipWriter<W: Write> {
    w: W,
    entries: Vec<Entry>,
    offset: u64,
}

/// DOS date of 1980-01-01 (day 1, month 1, year 0 from 1980); the time is 00:00:00.
const DOS_DATE: u16 = (1 << 5) | 1;

fn too_large(what: &str) -> io::Error {
    io::Error::other(format!(
        "internal error: zip {what} past {MAX_BYTES} bytes (the caller checks the size first)"
    ))
}

impl<W: Write> ZipWriter<W> {
    /// An archive written to `w`.
    pub(crate) fn new(w: W) -> Self {
        ZipWriter {
            w,
            entries: Vec::new(),
            offset: 0,
        }
    }

    /// Writes an entry `name` (ASCII) whose data is `parts`, one after another.
    pub(crate) fn entry(&mut self, name: &str, parts: &[&[u8]]) -> io::Result<()> {
        debug_assert!(name.is_ascii());
        let size: u64 = parts.iter().map(|p| p.len() as u64).sum();
        let crc = parts.iter().fold(0, |c, p| crc32(c, p));
        let (Ok(size32), Ok(offset)) = (u32::try_from(size), u32::try_from(self.offset)) else {
            return Err(too_large("entry"));
        };
        let mut h = Vec::with_capacity(LOCAL_HEADER as usize + name.len());
        h.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        h.extend_from_slice(&10u16.to_le_bytes()); // version needed: 1.0
        h.extend_from_slice(&0u16.to_le_bytes()); // flags
        h.extend_from_slice(&0u16.to_le_bytes()); // method: stored
        h.extend_from_slice(&0u16.to_le_bytes()); // time
        h.extend_from_slice(&DOS_DATE.to_le_bytes());
        h.extend_from_slice(&crc.to_le_bytes());
        h.extend_from_slice(&size32.to_le_bytes()); // compressed
        h.extend_from_slice(&size32.to_le_bytes()); // uncompressed
        h.extend_from_slice(&(name.len() as u16).to_le_bytes());
        h.extend_from_slice(&0u16.to_le_bytes()); // extra field length
        h.extend_from_slice(name.as_bytes());
        self.w.write_all(&h)?;
        for p in parts {
            self.w.write_all(p)?;
        }
        self.entries.push(Entry {
            name: name.to_string(),
            crc,
            size: size32,
            offset,
        });
        self.offset += h.len() as u64 + size;
        Ok(())
    }

    /// Writes the central directory and its end record; returns the writer.
    pub(crate) fn finish(mut self) -> io::Result<W> {
        let start = self.offset;
        let mut cd = Vec::new();
        for e in &self.entries {
            cd.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
            cd.extend_from_slice(&20u16.to_le_bytes()); // made by: MS-DOS, 2.0
            cd.extend_from_slice(&10u16.to_le_bytes()); // version needed
            cd.extend_from_slice(&0u16.to_le_bytes()); // flags
            cd.extend_from_slice(&0u16.to_le_bytes()); // method
            cd.extend_from_slice(&0u16.to_le_bytes()); // time
            cd.extend_from_slice(&DOS_DATE.to_le_bytes());
            cd.extend_from_slice(&e.crc.to_le_bytes());
            cd.extend_from_slice(&e.size.to_le_bytes());
            cd.extend_from_slice(&e.size.to_le_bytes());
            cd.extend_from_slice(&(e.name.len() as u16).to_le_bytes());
            cd.extend_from_slice(&[0; 8]); // extra, comment, disk number start, internal attributes
            cd.extend_from_slice(&0u32.to_le_bytes()); // external attributes
            cd.extend_from_slice(&e.offset.to_le_bytes());
            cd.extend_from_slice(e.name.as_bytes());
        }
        let (Ok(cd_size), Ok(cd_start)) = (u32::try_from(cd.len()), u32::try_from(start)) else {
            return Err(too_large("archive"));
        };
        if start + cd.len() as u64 + END_RECORD > MAX_BYTES {
            return Err(too_large("archive"));
        }
        let n = self.entries.len() as u16;
        cd.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
        cd.extend_from_slice(&[0; 4]); // this disk, the central directory's disk
        cd.extend_from_slice(&n.to_le_bytes());
        cd.extend_from_slice(&n.to_le_bytes());
        cd.extend_from_slice(&cd_size.to_le_bytes());
        cd.extend_from_slice(&cd_start.to_le_bytes());
        cd.extend_from_slice(&0u16.to_le_bytes()); // comment length
        self.w.write_all(&cd)?;
        self.w.flush()?;
        Ok(self.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_check_values() {
        // The CRC catalogue's check value for CRC-32/ISO-HDLC, and the empty input.
        assert_eq!(crc32(0, b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(0, b""), 0);
        // Continued over pieces, the same as at once.
        assert_eq!(crc32(crc32(0, b"1234"), b"56789"), 0xCBF4_3926);
    }

    #[test]
    fn an_archive_of_two_entries_has_the_documented_layout() {
        let mut z = ZipWriter::new(Vec::new());
        z.entry("a.npy", &[b"hello ", b"world"]).unwrap();
        z.entry("bb.npy", &[]).unwrap();
        let bytes = z.finish().unwrap();
        assert_eq!(bytes.len() as u64, archive_size(&[(5, 11), (6, 0)]));
        let u16_at = |i: usize| u16::from_le_bytes([bytes[i], bytes[i + 1]]);
        let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap());
        // First local header: signature, method, CRC, sizes, name, data.
        assert_eq!(u32_at(0), 0x0403_4b50);
        assert_eq!(u16_at(8), 0);
        assert_eq!(u32_at(14), crc32(0, b"hello world"));
        assert_eq!((u32_at(18), u32_at(22)), (11, 11));
        assert_eq!(&bytes[30..35], b"a.npy");
        assert_eq!(&bytes[35..46], b"hello world");
        // The second entry starts right after.
        assert_eq!(u32_at(46), 0x0403_4b50);
        assert_eq!(&bytes[76..82], b"bb.npy");
        // End record: two entries, the central directory's size and offset.
        let end = bytes.len() - 22;
        assert_eq!(u32_at(end), 0x0605_4b50);
        assert_eq!((u16_at(end + 8), u16_at(end + 10)), (2, 2));
        let (cd_size, cd_start) = (u32_at(end + 12) as usize, u32_at(end + 16) as usize);
        assert_eq!(cd_start, 82);
        assert_eq!(cd_start + cd_size, end);
        // The second central header points at the second local header.
        let second = cd_start + 46 + 5;
        assert_eq!(u32_at(second), 0x0201_4b50);
        assert_eq!(u32_at(second + 42), 46);
        assert_eq!(&bytes[second + 46..second + 52], b"bb.npy");
    }
}
