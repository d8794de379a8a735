//! What a usdc crate file claims, checked against its bytes before openusd reads it
//! (docs/spec.md §3, *USD input*). openusd 0.6 allocates what a count in the file says before it
//! reads the data the count describes, indexes its tables with numbers from the file, and walks
//! the path tree by the file's jumps; on hostile bytes that is an allocation the size of the
//! claim (an abort, not a panic), a panic, or a walk exponential in the entries. So the reader
//! first checks, on the bytes alone and in time linear in them:
//!
//! - the version is one openusd reads (0.4.0 to 0.12.0: older ones reach its `todo!()`s);
//! - every structural section (tokens, strings, fields, fieldsets, paths, specs) lies in the
//!   file, every LZ4 block is walked to the length it really decompresses to (one chunk: the
//!   chunked form is openusd's `todo!()`), and every count is one that length can hold;
//! - the path tree's jumps visit every entry at most once, its indices in range, and the paths
//!   openusd builds from it (each its parent's and a token more) fit the budget;
//! - each value the reader decodes (the few fields of a skeletal animation) is of a type it
//!   expects, its array lengths fit in the bytes after it (or its compressed block decompresses
//!   to what they need), and all values decoded together stay under [`decoded_budget`].
//!
//! What passes allocates at most what the file's bytes hold (LZ4 itself expands at most 255
//! times); the rest of openusd's hazards (an index out of its table, a malformed LZ4 block) are
//! panics or errors, which the reader turns into input errors.

/// The usdc value types by their crate type number (Pixar's `crateDataTypes.h`).
pub(crate) mod ty {
    pub(crate) const FLOAT: u8 = 8;
    pub(crate) const DOUBLE: u8 = 9;
    pub(crate) const TOKEN: u8 = 11;
    pub(crate) const MATRIX4D: u8 = 15;
    pub(crate) const QUATD: u8 = 16;
    pub(crate) const QUATF: u8 = 17;
    pub(crate) const QUATH: u8 = 18;
    pub(crate) const VEC3D: u8 = 23;
    pub(crate) const VEC3F: u8 = 24;
    pub(crate) const VEC3H: u8 = 25;
    pub(crate) const PATH_LIST_OP: u8 = 34;
    pub(crate) const PATH_VECTOR: u8 = 40;
    pub(crate) const TOKEN_VECTOR: u8 = 41;
    pub(crate) const TIME_SAMPLES: u8 = 46;
    pub(crate) const DOUBLE_VECTOR: u8 = 48;
}

/// A value's representation in the crate: type, flags, payload (offset or inline bits).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rep(pub(crate) u64);

impl Rep {
    pub(crate) fn ty(self) -> u8 {
        (self.0 >> 48) as u8
    }
    fn array(self) -> bool {
        self.0 >> 63 & 1 == 1
    }
    fn inlined(self) -> bool {
        self.0 >> 62 & 1 == 1
    }
    fn compressed(self) -> bool {
        self.0 >> 61 & 1 == 1
    }
    fn payload(self) -> u64 {
        self.0 & ((1 << 48) - 1)
    }
}

/// The most bytes of values one file may decode to: 64 times its size, and 64 MiB more. Time
/// samples may share one stored array (Pixar writes a repeated value once), so the decoded
/// values can outgrow the file; this bound keeps that growth to what a real clip needs.
pub(crate) fn decoded_budget(file_len: usize) -> u64 {
    64 * file_len as u64 + (64 << 20)
}

/// The crate being checked: its bytes and version.
pub(crate) struct Crate<'a> {
    b: &'a [u8],
    version: (u8, u8, u8),
    /// The length of each token (for the length of the paths openusd builds from them).
    token_lens: Vec<u64>,
    /// Bytes of values left to decode ([`decoded_budget`]).
    pub(crate) budget: u64,
}

type Check<T> = Result<T, String>;

impl<'a> Crate<'a> {
    fn bytes_at(&self, at: u64, n: usize) -> Check<&[u8]> {
        usize::try_from(at)
            .ok()
            .and_then(|at| self.b.get(at..at.checked_add(n)?))
            .ok_or_else(|| format!("an offset past the end ({at} of {} bytes)", self.b.len()))
    }

    fn u64_at(&self, at: u64) -> Check<u64> {
        let s = self.bytes_at(at, 8)?;
        Ok(u64::from_le_bytes(s.try_into().expect("8 bytes")))
    }

    fn u32_at(&self, at: u64) -> Check<u64> {
        let s = self.bytes_at(at, 4)?;
        Ok(u64::from(u32::from_le_bytes(
            s.try_into().expect("4 bytes"),
        )))
    }

    /// Bytes left from `at` to the end.
    fn left(&self, at: u64) -> u64 {
        (self.b.len() as u64).saturating_sub(at)
    }

    /// `count` elements of `size` bytes at `at` fit in the file.
    fn fits(&self, at: u64, count: u64, size: u64, what: &str) -> Check<()> {
        match count.checked_mul(size) {
            Some(n) if n <= self.left(at) => Ok(()),
            _ => Err(format!(
                "{what}: {count} entries of {size} bytes claimed, {} bytes left in the file",
                self.left(at)
            )),
        }
    }

    /// The compressed block at `at` (a u64 size, a chunk count byte, an LZ4 block): its end and
    /// the bytes it decompresses to.
    fn block(&self, at: u64, what: &str) -> Check<(u64, u64)> {
        let size = self.u64_at(at)?;
        self.fits(at + 8, size, 1, what)?;
        let start = (at + 8) as usize;
        let data = &self.b[start..start + size as usize];
        let Some((&chunks, body)) = data.split_first() else {
            return Err(format!("{what}: an empty compressed block"));
        };
        if chunks != 0 {
            return Err(format!(
                "{what}: a compressed block in {chunks} chunks (not read)"
            ));
        }
        let out = lz4(body, None).ok_or_else(|| format!("{what}: a corrupt LZ4 block"))?;
        Ok((at + 8 + size, out))
    }

    /// A block of `count` integers (Pixar's integer coding, then LZ4): its end. A count the
    /// block cannot hold (each integer takes at least two bits of it) is refused.
    fn ints(&self, at: u64, count: u64, what: &str) -> Check<u64> {
        let (end, out) = self.block(at, what)?;
        if count > 0 && (out < 4 || count > 4 * (out - 4)) {
            return Err(format!(
                "{what}: {count} integers claimed in {out} decompressed bytes"
            ));
        }
        Ok(end)
    }

    /// The bytes the compressed block at `at` decompresses to (walked first: what it really
    /// holds, no more), and its end.
    fn decompressed(&self, at: u64, what: &str) -> Check<(u64, Vec<u8>)> {
        let (end, _) = self.block(at, what)?;
        let mut buf = Vec::new();
        lz4(&self.b[(at + 9) as usize..end as usize], Some(&mut buf));
        Ok((end, buf))
    }

    /// The decoded integers of the block at `at` (for the path tree's jumps).
    fn decoded_ints(&self, at: u64, count: u64, what: &str) -> Check<(u64, Vec<i64>)> {
        let end = self.ints(at, count, what)?;
        let (_, buf) = self.decompressed(at, what)?;
        let ints = decode_ints(&buf, count as usize).ok_or_else(|| {
            format!("{what}: the integer coding ends before its {count} integers")
        })?;
        Ok((end, ints))
    }
}

/// The number of bytes an LZ4 block decompresses to, walking its sequences (LZ4 block format:
/// a token, literal length extensions, literals, a 2-byte offset within the output so far, match
/// length extensions), and the bytes themselves into `out` when given; `None` for a block that
/// is not well formed.
fn lz4(s: &[u8], mut out: Option<&mut Vec<u8>>) -> Option<u64> {
    let (mut i, mut len) = (0usize, 0u64);
    let ext = |i: &mut usize, mut n: u64| -> Option<u64> {
        if n == 15 {
            loop {
                let b = *s.get(*i)?;
                *i += 1;
                n += u64::from(b);
                if b != 255 {
                    break;
                }
            }
        }
        Some(n)
    };
    loop {
        let token = *s.get(i)?;
        i += 1;
        let lit = ext(&mut i, u64::from(token >> 4))?;
        let end = i.checked_add(usize::try_from(lit).ok()?)?;
        let literals = s.get(i..end)?;
        if let Some(o) = out.as_deref_mut() {
            o.extend_from_slice(literals);
        }
        i = end;
        len += lit;
        if i == s.len() {
            return Some(len);
        }
        let offset = u64::from(u16::from_le_bytes([*s.get(i)?, *s.get(i + 1)?]));
        i += 2;
        if offset == 0 || offset > len {
            return None;
        }
        let matched = ext(&mut i, u64::from(token & 15))? + 4;
        if let Some(o) = out.as_deref_mut() {
            let from = o.len() - offset as usize;
            for k in 0..matched as usize {
                o.push(o[from + k]);
            }
        }
        len += matched;
    }
}

/// Pixar's integer coding (`integerCoding.cpp`) of 32-bit integers: a common delta, two bits a
/// value saying its delta's width, the deltas; the running sums.
fn decode_ints(data: &[u8], count: usize) -> Option<Vec<i64>> {
    let common = i64::from(i32::from_le_bytes(data.get(..4)?.try_into().ok()?));
    let codes = data.get(4..4 + count.div_ceil(4))?;
    let mut at = 4 + codes.len();
    let (mut prev, mut out) = (0i64, Vec::with_capacity(count));
    for i in 0..count {
        let code = codes[i / 4] >> (2 * (i % 4)) & 3;
        let delta = match code {
            0 => common,
            1 => i64::from(*data.get(at)? as i8),
            2 => i64::from(i16::from_le_bytes(data.get(at..at + 2)?.try_into().ok()?)),
            _ => i64::from(i32::from_le_bytes(data.get(at..at + 4)?.try_into().ok()?)),
        };
        at += [0, 1, 2, 4][code as usize];
        prev = prev.wrapping_add(delta);
        out.push(i64::from(prev as i32));
    }
    Some(out)
}

/// Checks the structure of the crate `b` (see the module documentation).
pub(crate) fn check_structure(b: &[u8]) -> Check<Crate<'_>> {
    if b.len() < 88 || !b.starts_with(b"PXR-USDC") {
        return Err("not a usdc crate (too short for its header)".into());
    }
    let version = (b[8], b[9], b[10]);
    if version.0 != 0 || version.1 < 4 || version.1 > 12 {
        return Err(format!(
            "usdc version {}.{}.{}; versions 0.4.0 to 0.12.0 are read",
            version.0, version.1, version.2
        ));
    }
    let mut c = Crate {
        b,
        version,
        token_lens: Vec::new(),
        budget: decoded_budget(b.len()),
    };
    let toc = c.u64_at(16)?;
    let count = c.u64_at(toc)?;
    if count == 0 || count >= 64 {
        return Err(format!("{count} sections in the table of contents"));
    }
    c.fits(toc + 8, count, 32, "the table of contents")?;
    let section = |name: &str| -> Option<u64> {
        (0..count).find_map(|i| {
            let at = (toc + 8 + 32 * i) as usize;
            let n = &b[at..at + 16];
            let len = n.iter().position(|&x| x == 0).unwrap_or(16);
            (&n[..len] == name.as_bytes())
                .then(|| u64::from_le_bytes(b[at + 16..at + 24].try_into().expect("8 bytes")))
        })
    };
    if let Some(at) = section("TOKENS") {
        let count = c.u64_at(at)?;
        let size = c.u64_at(at + 8)?;
        let (_, out) = c.block(at + 16, "TOKENS")?;
        if out != size || count > size {
            return Err(format!(
                "TOKENS: {count} tokens in {size} bytes claimed, {out} decompressed"
            ));
        }
        let (_, text) = c.decompressed(at + 16, "TOKENS")?;
        let body = text.strip_suffix(&[0]).unwrap_or(&text);
        c.token_lens = if body.is_empty() {
            Vec::new()
        } else {
            body.split(|&x| x == 0).map(|t| t.len() as u64).collect()
        };
    }
    if let Some(at) = section("STRINGS") {
        let count = c.u64_at(at)?;
        c.fits(at + 8, count, 4, "STRINGS")?;
    }
    if let Some(at) = section("FIELDS") {
        let count = c.u64_at(at)?;
        let end = c.ints(at + 8, count, "FIELDS")?;
        let (_, out) = c.block(end, "FIELDS")?;
        if Some(out) != count.checked_mul(8) {
            return Err(format!(
                "FIELDS: {count} values claimed, {out} bytes decompressed"
            ));
        }
    }
    if let Some(at) = section("FIELDSETS") {
        let count = c.u64_at(at)?;
        c.ints(at + 8, count, "FIELDSETS")?;
    }
    if let Some(at) = section("PATHS") {
        paths(&mut c, at)?;
    }
    if let Some(at) = section("SPECS") {
        let count = c.u64_at(at)?;
        let mut end = at + 8;
        for _ in 0..3 {
            end = c.ints(end, count, "SPECS")?;
        }
    }
    Ok(c)
}

/// The PATHS section: its counts, and its tree walked as openusd walks it (children next,
/// siblings by jump), each entry visited at most once; the paths it builds, as long as their
/// parents' and a token more, within the budget (a chain of nested names would otherwise cost
/// memory quadratic in its length).
fn paths(c: &mut Crate, at: u64) -> Check<()> {
    let paths = c.u64_at(at)?;
    let count = c.u64_at(at + 8)?;
    let (end, index) = c.decoded_ints(at + 16, count, "PATHS")?;
    let (end, tokens) = c.decoded_ints(end, count, "PATHS")?;
    let (_, jumps) = c.decoded_ints(end, count, "PATHS")?;
    if paths > count.max(1) {
        return Err(format!("PATHS: {paths} paths claimed of {count} entries"));
    }
    let n = count as usize;
    let bad = |what: &str, i: usize| Err(format!("PATHS: entry {i}: {what}"));
    let mut seen = vec![false; n];
    let mut total = 0u64;
    // (entry, the length of its parent's path)
    let mut pending = if n > 0 {
        vec![(0usize, 0u64)]
    } else {
        Vec::new()
    };
    while let Some((mut i, mut parent)) = pending.pop() {
        loop {
            if i >= n || seen[i] {
                return bad("the tree reaches an entry twice or none", i);
            }
            seen[i] = true;
            if index[i] < 0 || index[i] as u64 >= paths {
                return bad("a path index out of range", i);
            }
            let len = if i == 0 {
                1
            } else {
                let Some(t) = c.token_lens.get(tokens[i].unsigned_abs() as usize) else {
                    return bad("a token index out of range", i);
                };
                parent + 1 + t
            };
            total += len;
            if total > c.budget {
                return bad("the paths are longer in all than the file can hold", i);
            }
            let (child, sibling) = (jumps[i] > 0 || jumps[i] == -1, jumps[i] >= 0);
            if child && sibling {
                pending.push((i.saturating_add(jumps[i] as usize), parent));
            }
            if !child && !sibling {
                break;
            }
            if child {
                parent = len;
            }
            // The next entry is the child (or, for a jump of 0, the sibling).
            i += 1;
        }
    }
    c.spend(2 * total, "PATHS")
}

impl Crate<'_> {
    /// Checks the value `rep` before openusd decodes it: a type in `allowed`, its lengths in
    /// the file, its decoded size within the budget. Time samples are checked with each sample.
    pub(crate) fn value(&mut self, rep: Rep, allowed: &[u8], what: &str) -> Check<()> {
        let t = rep.ty();
        if !allowed.contains(&t) {
            return Err(format!(
                "{what}: a value of crate type {t}, not one read here"
            ));
        }
        if t == ty::TIME_SAMPLES {
            if rep.inlined() || rep.compressed() {
                return Err(format!("{what}: malformed time samples"));
            }
            let at = rep.payload();
            let times_at = at.wrapping_add(self.u64_at(at)?);
            let times = Rep(self.u64_at(times_at)?);
            self.value(times, &[ty::DOUBLE, ty::DOUBLE_VECTOR], what)?;
            if times.ty() == ty::DOUBLE && !times.array() {
                return Err(format!("{what}: time codes that are no array"));
            }
            let after = times_at + 8;
            let reps_at = after.wrapping_add(self.u64_at(after)?);
            let count = self.u64_at(reps_at)?;
            self.fits(reps_at + 8, count, 8, what)?;
            let inner: Vec<u8> = allowed
                .iter()
                .copied()
                .filter(|&t| t != ty::TIME_SAMPLES)
                .collect();
            for k in 0..count {
                let r = Rep(self.u64_at(reps_at + 8 + 8 * k)?);
                self.value(r, &inner, what)?;
            }
            return Ok(());
        }
        if rep.inlined() {
            return Ok(());
        }
        let at = rep.payload();
        let (count, size, start) = match t {
            ty::TOKEN_VECTOR | ty::PATH_VECTOR => (self.u64_at(at)?, 4, at + 8),
            ty::PATH_LIST_OP => {
                // A header byte, then up to six lists (count, indices).
                let head = self.bytes_at(at, 1)?[0] & 0x7e;
                let mut pos = at + 1;
                let mut total = 0;
                for _ in 0..head.count_ones() {
                    let n = self.u64_at(pos)?;
                    self.fits(pos + 8, n, 4, what)?;
                    pos += 8 + 4 * n;
                    total += n;
                }
                return self.spend(total * 32, what);
            }
            _ if !rep.array() && t != ty::DOUBLE_VECTOR => return Ok(()),
            _ => {
                if at == 0 {
                    return Ok(());
                }
                let mut pos = at;
                if self.version.1 < 5 {
                    pos += 4;
                }
                let count = if self.version.1 < 7 {
                    self.u32_at(pos)?
                } else {
                    self.u64_at(pos)?
                };
                pos += if self.version.1 < 7 { 4 } else { 8 };
                let size = match t {
                    ty::FLOAT | ty::TOKEN => 4,
                    ty::DOUBLE | ty::DOUBLE_VECTOR | ty::QUATH => 8,
                    ty::VEC3H => 6,
                    ty::VEC3F => 12,
                    ty::QUATF => 16,
                    ty::VEC3D => 24,
                    ty::QUATD => 32,
                    ty::MATRIX4D => 128,
                    _ => return Err(format!("{what}: an array of crate type {t}")),
                };
                let float = matches!(t, ty::FLOAT | ty::DOUBLE | ty::DOUBLE_VECTOR);
                if float && rep.compressed() && self.version.1 >= 6 && count >= 4 {
                    match self.b.get(pos as usize) {
                        Some(b'i') => {
                            self.ints(pos + 1, count, what)?;
                        }
                        Some(b't') => {
                            let lut = self.u32_at(pos + 1)?;
                            self.fits(pos + 5, lut, size, what)?;
                            self.ints(pos + 5 + lut * size, count, what)?;
                        }
                        _ => return Err(format!("{what}: an unknown array compression")),
                    }
                    return self.spend(count * 8, what);
                }
                (count, size, pos)
            }
        };
        self.fits(start, count, size, what)?;
        // Decoded, a token or path index becomes a string (about 32 bytes).
        self.spend(count * size.max(32), what)
    }

    fn spend(&mut self, bytes: u64, what: &str) -> Check<()> {
        self.budget = self.budget.checked_sub(bytes).ok_or_else(|| {
            format!("{what}: the values decode to more than 64 times the file's size")
        })?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lz4_lengths_are_walked() {
        // Literals only.
        assert_eq!(lz4(&[0x30, b'a', b'b', b'c'], None), Some(3));
        // "ab" then a match of 6 at offset 2, then the last literal.
        let mut out = Vec::new();
        assert_eq!(
            lz4(&[0x22, b'a', b'b', 2, 0, 0x10, b'z'], Some(&mut out)),
            Some(2 + 6 + 1)
        );
        assert_eq!(
            out,
            b"abababab".iter().chain(b"z").copied().collect::<Vec<u8>>()
        );
        // An offset before the start, a truncated block.
        assert_eq!(lz4(&[0x22, b'a', b'b', 9, 0, 0x10, b'z'], None), None);
        assert_eq!(lz4(&[0x50, b'a'], None), None);
        assert_eq!(lz4(&[], None), None);
    }

    /// A compressed block of 32-bit integers as a crate holds it: a u64 size, no chunks, one
    /// literal-only LZ4 sequence of the integer coding (common delta 0, every delta 4 bytes).
    fn int_block(values: &[i64]) -> Vec<u8> {
        let mut coded = 0i32.to_le_bytes().to_vec();
        coded.extend(std::iter::repeat_n(0xffu8, values.len().div_ceil(4)));
        let mut prev = 0i64;
        for &v in values {
            coded.extend(((v - prev) as i32).to_le_bytes());
            prev = v;
        }
        let mut lz4 = vec![0xf0u8];
        let mut rest = coded.len() - 15;
        while rest >= 255 {
            lz4.push(255);
            rest -= 255;
        }
        lz4.push(rest as u8);
        lz4.extend(&coded);
        let mut out = ((lz4.len() + 1) as u64).to_le_bytes().to_vec();
        out.push(0);
        out.extend(lz4);
        out
    }

    /// A PATHS section of `jumps.len()` entries (entry i is path i, token 0) checked.
    fn check_paths(jumps: &[i64]) -> Check<()> {
        let n = jumps.len() as u64;
        let mut b = n.to_le_bytes().to_vec();
        b.extend(n.to_le_bytes());
        b.extend(int_block(&(0..n as i64).collect::<Vec<_>>()));
        b.extend(int_block(&vec![0; jumps.len()]));
        b.extend(int_block(jumps));
        let mut c = Crate {
            b: &b,
            version: (0, 8, 0),
            token_lens: vec![4],
            budget: decoded_budget(b.len()),
        };
        paths(&mut c, 0)
    }

    /// openusd walks the path tree by the file's jumps: 40 entries each with a child and a
    /// sibling at the next entry would be 2^40 steps there; here the second visit is refused.
    #[test]
    fn a_path_tree_reaching_an_entry_twice_is_refused() {
        // The root, a child with a sibling (jump 2), its child (a leaf), the sibling (a leaf).
        assert_eq!(check_paths(&[-1, 2, -2, -2]), Ok(()));
        let mut chain = vec![1; 39];
        chain.push(-2);
        let e = check_paths(&chain).unwrap_err();
        assert!(e.contains("reaches an entry twice"), "{e}");
        // A sibling past the end.
        assert!(check_paths(&[-1, 9, -2]).is_err());
    }

    #[test]
    fn integers_decode_as_pixar_codes_them() {
        // Common delta 1; codes: common, small (-3), medium (300), large (70000).
        let mut d = 1i32.to_le_bytes().to_vec();
        d.push(0b11_10_01_00);
        d.push((-3i8) as u8);
        d.extend(300i16.to_le_bytes());
        d.extend(70000i32.to_le_bytes());
        assert_eq!(decode_ints(&d, 4), Some(vec![1, -2, 298, 70298]));
        assert_eq!(decode_ints(&d[..6], 4), None);
    }
}
