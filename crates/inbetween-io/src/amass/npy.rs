//! Reading one NumPy `.npy` array (format versions 1.0, 2.0 and 3.0): its header dictionary
//! (`descr`, `fortran_order`, `shape`) and its data, checked to be exactly the bytes the shape
//! and the dtype say. Object arrays (`|O`, which only pickle can read) and structured dtypes are
//! refused; numbers are converted to f64 on demand ([`Array::floats`]), any other dtype is kept
//! as bytes to be copied.

use inbetween::error::InputResult;

/// The kind of an array's elements, from its `descr`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// IEEE floats (`f2`, `f4`, `f8`).
    Float,
    /// Signed integers (`i1` … `i8`).
    Int,
    /// Unsigned integers (`u1` … `u8`).
    Uint,
    /// Anything else that is plain bytes (`b1`, `U`, `S`, `c`, `M`, …): copied, never read.
    Other,
}

/// One array as read: its `descr` as written, its element kind and size, its shape, its order
/// and its data bytes (after the header).
#[derive(Debug, Clone, PartialEq)]
pub struct Array {
    /// The `descr` as written, e.g. `<f8` or `<U6`.
    pub descr: String,
    /// The element kind.
    pub kind: Kind,
    /// Bytes per element.
    pub item: usize,
    /// Big-endian elements (`>`).
    pub big_endian: bool,
    /// The shape (empty for a 0-d array).
    pub shape: Vec<u64>,
    /// Fortran (column-major) order.
    pub fortran: bool,
    /// The whole `.npy` entry, header included.
    pub bytes: Vec<u8>,
    /// Where the data starts in `bytes`.
    pub data_at: usize,
}

/// Reads an `.npy` entry; `what` names it in messages (`file: key "poses"`).
pub fn parse(bytes: Vec<u8>, what: &str) -> InputResult<Array> {
    let bad = |why: &str| input_err!("{what}: not a readable .npy array: {why}");
    if !bytes.starts_with(b"\x93NUMPY") || bytes.len() < 10 {
        return Err(bad("no NumPy magic (truncated?)"));
    }
    let (len, at) = match bytes[6] {
        1 => (
            usize::from(u16::from_le_bytes([bytes[8], bytes[9]])),
            10usize,
        ),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(bad(&format!("format version {v}, not 1, 2 or 3"))),
    };
    let data_at = at
        .checked_add(len)
        .filter(|&e| e <= bytes.len())
        .ok_or_else(|| bad("its header runs past the entry (truncated?)"))?;
    let header = std::str::from_utf8(&bytes[at..data_at]).map_err(|_| bad("a header not UTF-8"))?;
    let descr = dict_value(header, "descr").ok_or_else(|| bad("no 'descr' in its header"))?;
    let fortran = match dict_value(header, "fortran_order") {
        Some("True") => true,
        Some("False") => false,
        _ => return Err(bad("no 'fortran_order' True or False in its header")),
    };
    let shape = dict_value(header, "shape")
        .and_then(parse_shape)
        .ok_or_else(|| bad("no 'shape' tuple of integers in its header"))?;
    let Some(d) = descr.strip_prefix('\'').and_then(|d| d.strip_suffix('\'')) else {
        return Err(bad(&format!(
            "a structured dtype ({}); only plain arrays are read",
            inbetween::error::shorten(descr)
        )));
    };
    let (order, code) = match d.chars().next() {
        Some(c @ ('<' | '>' | '|' | '=')) => (c, &d[1..]),
        _ => ('|', d),
    };
    let letter = code.chars().next().unwrap_or(' ');
    if letter == 'O' {
        return Err(input_err!(
            "{what}: an object array (dtype {d}), which only pickle can read; not read (pickle \
             runs code): save the array with a numeric or string dtype"
        ));
    }
    let digits: usize = code[letter.len_utf8().min(code.len())..]
        .parse()
        .map_err(|_| bad(&format!("dtype {d} not understood")))?;
    let (kind, item) = match letter {
        'f' if matches!(digits, 2 | 4 | 8) => (Kind::Float, digits),
        'i' if matches!(digits, 1 | 2 | 4 | 8) => (Kind::Int, digits),
        'u' if matches!(digits, 1 | 2 | 4 | 8) => (Kind::Uint, digits),
        'U' => (
            Kind::Other,
            digits.checked_mul(4).ok_or_else(|| bad("dtype too wide"))?,
        ),
        'b' | 'S' | 'a' | 'c' | 'V' | 'M' | 'm' => (Kind::Other, digits),
        _ => return Err(bad(&format!("dtype {d} not understood"))),
    };
    let count = shape
        .iter()
        .try_fold(1u64, |n, &s| n.checked_mul(s))
        .and_then(|n| n.checked_mul(item as u64));
    let have = (bytes.len() - data_at) as u64;
    if count != Some(have) {
        return Err(bad(&format!(
            "shape {} of {d} needs {} data bytes, found {have} (truncated?)",
            shape_text(&shape),
            count.map_or_else(|| "more than 2^64".to_string(), |c| c.to_string())
        )));
    }
    Ok(Array {
        descr: d.to_string(),
        kind,
        item,
        big_endian: order == '>',
        shape,
        fortran,
        bytes,
        data_at,
    })
}

/// `(3, 156)` as Python writes it.
pub(crate) fn shape_text(shape: &[u64]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(u64::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The value of `'key':` in a Python dict literal as numpy writes it: up to the next top-level
/// comma or closing brace (a tuple or a list kept whole), trimmed.
fn dict_value<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let at = header.find(&format!("'{key}'"))? + key.len() + 2;
    let rest = header[at..].trim_start().strip_prefix(':')?;
    let mut depth = 0i32;
    let mut quoted = false;
    for (i, c) in rest.char_indices() {
        match c {
            '\'' => quoted = !quoted,
            '(' | '[' if !quoted => depth += 1,
            ')' | ']' if !quoted => depth -= 1,
            ',' | '}' if !quoted && depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    None
}

/// `()`, `(5,)`, `(3, 156)`.
fn parse_shape(s: &str) -> Option<Vec<u64>> {
    let inner = s.strip_prefix('(')?.strip_suffix(')')?;
    inner
        .split(',')
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .map(|p| p.trim_end_matches('L').parse().ok())
        .collect()
}

impl Array {
    /// The data bytes.
    pub fn data(&self) -> &[u8] {
        &self.bytes[self.data_at..]
    }

    /// The number of elements.
    pub fn len(&self) -> usize {
        self.data().len() / self.item.max(1)
    }

    /// Whether the array has no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The elements as f64 in C (row-major) order whatever the array's order; `None` for an
    /// array that is not numeric ([`Kind::Other`]).
    pub fn floats(&self) -> Option<Vec<f64>> {
        let item = self.item;
        let read = |c: &[u8]| -> f64 {
            let mut b = [0u8; 8];
            b[..item].copy_from_slice(c);
            if self.big_endian {
                b[..item].reverse();
            }
            match (self.kind, item) {
                (Kind::Float, 8) => f64::from_le_bytes(b),
                (Kind::Float, 4) => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                (Kind::Float, _) => half(u16::from_le_bytes([b[0], b[1]])),
                (Kind::Int, n) => {
                    let shift = 64 - 8 * n as u32;
                    ((i64::from_le_bytes(b) << shift) >> shift) as f64
                }
                _ => u64::from_le_bytes(b) as f64,
            }
        };
        if self.kind == Kind::Other {
            return None;
        }
        let values: Vec<f64> = self.data().chunks_exact(item).map(read).collect();
        Some(if self.fortran && self.shape.len() > 1 {
            c_order(&values, &self.shape)
        } else {
            values
        })
    }
}

/// An IEEE half float's value.
fn half(h: u16) -> f64 {
    let sign = if h >> 15 == 1 { -1.0 } else { 1.0 };
    let (e, m) = (i32::from((h >> 10) & 0x1F), f64::from(h & 0x3FF));
    sign * match e {
        0 => m * 2f64.powi(-24),
        31 if m == 0.0 => f64::INFINITY,
        31 => f64::NAN,
        _ => (1.0 + m / 1024.0) * 2f64.powi(e - 15),
    }
}

/// Column-major `values` of `shape` in row-major order.
fn c_order(values: &[f64], shape: &[u64]) -> Vec<f64> {
    let dims: Vec<usize> = shape.iter().map(|&d| d as usize).collect();
    let mut out = vec![0.0; values.len()];
    let mut index = vec![0usize; dims.len()];
    for slot in out.iter_mut() {
        // The Fortran offset of the current C index.
        let (mut off, mut stride) = (0, 1);
        for (i, d) in index.iter().zip(&dims) {
            off += i * stride;
            stride *= d;
        }
        *slot = values[off];
        for (i, d) in index.iter_mut().zip(&dims).rev() {
            *i += 1;
            if *i < *d {
                break;
            }
            *i = 0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy(descr: &str, fortran: bool, shape: &str, data: &[u8]) -> Vec<u8> {
        let dict = format!(
            "{{'descr': {descr}, 'fortran_order': {}, 'shape': {shape}, }}",
            if fortran { "True" } else { "False" }
        );
        let mut b = b"\x93NUMPY\x01\x00".to_vec();
        b.extend_from_slice(&(dict.len() as u16).to_le_bytes());
        b.extend_from_slice(dict.as_bytes());
        b.extend_from_slice(data);
        b
    }

    #[test]
    fn floats_of_every_width_and_order() {
        let data: Vec<u8> = [1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let a = parse(npy("'<f8'", false, "(2, 3)", &data), "x").unwrap();
        assert_eq!(a.floats().unwrap(), vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        // The same bytes in Fortran order are the transpose's.
        let f = parse(npy("'<f8'", true, "(2, 3)", &data), "x").unwrap();
        assert_eq!(f.floats().unwrap(), vec![1.0, 3.0, 5.0, 2.0, 4.0, 6.0]);
        let be: Vec<u8> = [1.5f32, -2.0]
            .iter()
            .flat_map(|x| x.to_be_bytes())
            .collect();
        let b = parse(npy("'>f4'", false, "(2,)", &be), "x").unwrap();
        assert_eq!(b.floats().unwrap(), vec![1.5, -2.0]);
        let h = parse(npy("'<f2'", false, "()", &0x3C00u16.to_le_bytes()), "x").unwrap();
        assert_eq!(h.floats().unwrap(), vec![1.0]);
        let i = parse(npy("'<i2'", false, "(1,)", &(-3i16).to_le_bytes()), "x").unwrap();
        assert_eq!(i.floats().unwrap(), vec![-3.0]);
    }

    #[test]
    fn strings_are_kept_and_objects_refused() {
        let u = parse(npy("'<U6'", false, "()", &[b'a', 0, 0, 0].repeat(6)), "g").unwrap();
        assert_eq!((u.kind, u.item, u.floats()), (Kind::Other, 24, None));
        let e = parse(npy("'|O'", false, "()", &[]), "f.npz: key \"gender\"").unwrap_err();
        assert!(
            e.message()
                .starts_with("f.npz: key \"gender\": an object array"),
            "{e}"
        );
    }

    #[test]
    fn data_must_be_exactly_what_the_shape_says() {
        let e = parse(npy("'<f8'", false, "(2, 3)", &[0; 40]), "p").unwrap_err();
        assert!(e.message().contains("needs 48 data bytes, found 40"), "{e}");
        let e = parse(npy("'<f8'", false, "(4294967296, 4294967296, 2)", &[]), "p").unwrap_err();
        assert!(e.message().contains("more than 2^64"), "{e}");
        let mut short = npy("'<f8'", false, "(1,)", &[0; 8]);
        short.truncate(20);
        let e = parse(short, "p").unwrap_err();
        assert!(
            e.message().contains("its header runs past the entry"),
            "{e}"
        );
        let e = parse(npy("[('a', '<f8')]", false, "(1,)", &[0; 8]), "p").unwrap_err();
        assert!(e.message().contains("structured dtype"), "{e}");
        assert!(parse(b"PK\x03\x04".to_vec(), "p").is_err());
    }
}
