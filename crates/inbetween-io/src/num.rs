//! Number formatting for output: shortest round-trip (zmij, Schubfach) or fixed `%.Nf`.

/// How floats are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NumFormat {
    /// The shortest digits that read back to the same f64.
    #[default]
    Shortest,
    /// Exactly `N` digits after the decimal point, as printf `%.Nf`.
    Fixed(usize),
}

/// Largest `--precision` accepted.
pub const MAX_PRECISION: usize = 17;

/// Appends floats and integers to a byte buffer.
#[derive(Default)]
pub struct NumWriter {
    format: NumFormat,
    zmij: zmij::Buffer,
    itoa: itoa::Buffer,
}

impl Clone for NumWriter {
    /// A writer with the same format and fresh scratch buffers.
    fn clone(&self) -> Self {
        NumWriter::new(self.format)
    }
}

impl NumWriter {
    /// A writer in `format`.
    pub fn new(format: NumFormat) -> Self {
        NumWriter {
            format,
            zmij: zmij::Buffer::new(),
            itoa: itoa::Buffer::new(),
        }
    }

    /// Appends a finite float in the writer's format. Non-finite values must not reach it: the
    /// writers check every value they write (`is_finite`) and fail with an internal error
    /// instead; here one would come out as `NaN` or `inf`.
    #[inline]
    pub fn float(&mut self, out: &mut Vec<u8>, x: f64) {
        match self.format {
            NumFormat::Shortest => self.shortest(out, x),
            NumFormat::Fixed(n) => fixed(out, x, n, &mut self.itoa),
        }
    }

    /// Appends a finite float with the shortest digits that read back to it, whatever the
    /// writer's format (times: `--precision` applies to rotations and velocities only).
    #[inline]
    pub fn shortest(&mut self, out: &mut Vec<u8>, x: f64) {
        // `+ 0.0` turns −0 into 0: a sign on zero carries no information here.
        out.extend_from_slice(self.zmij.format(x + 0.0).as_bytes());
    }

    /// Appends an integer.
    #[inline]
    pub fn int(&mut self, out: &mut Vec<u8>, k: i64) {
        out.extend_from_slice(self.itoa.format(k).as_bytes());
    }
}

/// Appends `x` with exactly `n` digits after the point: the same bytes as `format!("{x:.n$}")`
/// (the exact binary value rounded half to even, `-` kept on negative values), without its
/// generic machinery — except that a value that rounds to zero has no sign (`-0.001` at two
/// digits is `0.00`, not `-0.00`; −0 is `0.00`).
///
/// `x = m·2^e` exactly (`m` < 2⁵³), so `x·10ⁿ = m·10ⁿ·2^e`; for `e < 0` and `n ≤ 17` the product
/// `m·10ⁿ < 2¹¹⁰` fits a `u128`, and the rounded quotient by `2^−e` is one shift and one
/// comparison. Other values (|x| ≥ 2⁵², non-finite) go through `format!`.
#[inline]
pub fn fixed(out: &mut Vec<u8>, x: f64, n: usize, ints: &mut itoa::Buffer) {
    const POW10: [u128; 18] = [
        1,
        10,
        100,
        1_000,
        10_000,
        100_000,
        1_000_000,
        10_000_000,
        100_000_000,
        1_000_000_000,
        10_000_000_000,
        100_000_000_000,
        1_000_000_000_000,
        10_000_000_000_000,
        100_000_000_000_000,
        1_000_000_000_000_000,
        10_000_000_000_000_000,
        100_000_000_000_000_000,
    ];
    let bits = x.to_bits();
    let exp_bits = ((bits >> 52) & 0x7ff) as i32;
    if n > 17 || exp_bits >= 1023 + 52 || exp_bits == 0x7ff {
        use std::io::Write;
        let start = out.len();
        let _ = write!(out, "{x:.n$}");
        // (Only with n > 17 can this be a rounded zero.)
        if out[start] == b'-' && out[start + 1..].iter().all(|&b| b == b'0' || b == b'.') {
            out.remove(start);
        }
        return;
    }
    let frac = bits & ((1u64 << 52) - 1);
    let (m, e) = if exp_bits == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), exp_bits - 1075)
    };
    // e < 0 here: x·10ⁿ = m·10ⁿ / 2^s.
    let s = (-e) as u32;
    let prod = m as u128 * POW10[n];
    let q = if s >= 128 {
        0
    } else {
        let q = prod >> s;
        let rem = prod & ((1u128 << s) - 1);
        let half = 1u128 << (s - 1);
        if rem > half || (rem == half && q & 1 == 1) {
            q + 1
        } else {
            q
        }
    };
    if x.is_sign_negative() && q != 0 {
        out.push(b'-');
    }
    // u128 division is a slow library call; every value that matters here fits a u64.
    let (int_part, frac_part) = match u64::try_from(q) {
        Ok(q) => (q / POW10[n] as u64, q % POW10[n] as u64),
        Err(_) => ((q / POW10[n]) as u64, (q % POW10[n]) as u64),
    };
    out.extend_from_slice(ints.format(int_part).as_bytes());
    if n > 0 {
        out.push(b'.');
        let digits = ints.format(frac_part).as_bytes();
        out.extend(std::iter::repeat_n(b'0', n - digits.len()));
        out.extend_from_slice(digits);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(f: NumFormat, x: f64) -> String {
        let mut out = Vec::new();
        NumWriter::new(f).float(&mut out, x);
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn shortest_round_trips() {
        for x in [0.1, 1.0 / 3.0, -2.5e-17, 1e300, 0.12345678901234568] {
            assert_eq!(fmt(NumFormat::Shortest, x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(fmt(NumFormat::Shortest, 0.5), "0.5");
    }

    #[test]
    fn fixed_matches_format_exactly() {
        // A deterministic spread: quaternion-like values, halfway cases, tiny and large
        // magnitudes, negative zero, subnormals.
        let mut vals = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            0.125,
            0.0625,
            1e-300,
            -1e-300,
            5e-324,
            4.5e15,
            -4.5e15,
            123456.789,
            std::f64::consts::FRAC_1_SQRT_2,
            -std::f64::consts::FRAC_1_SQRT_2,
            1e-10,
            0.05,
            0.15,
            0.25,
            0.35,
            9.9999999995,
            999999.9999999995,
        ];
        let mut state = 0x2545F4914F6CDD1Du64;
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mantissa = (state >> 11) as f64 / (1u64 << 53) as f64;
            let scale = 10f64.powi((state % 24) as i32 - 12);
            vals.push((mantissa - 0.5) * 2.0 * scale);
            vals.push(f64::from_bits(state >> 2));
        }
        let mut ints = itoa::Buffer::new();
        for &x in &vals {
            if !x.is_finite() {
                continue;
            }
            for n in 0..=17 {
                let mut out = Vec::new();
                fixed(&mut out, x, n, &mut ints);
                // std's bytes, without the sign of a rounded zero.
                let std = format!("{x:.n$}");
                let want = match std.strip_prefix('-') {
                    Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest,
                    _ => &std,
                };
                assert_eq!(String::from_utf8(out).unwrap(), want, "{x:e} n={n}");
            }
        }
    }

    #[test]
    fn fixed_matches_printf() {
        assert_eq!(fmt(NumFormat::Fixed(3), 0.12345), "0.123");
        assert_eq!(fmt(NumFormat::Fixed(0), 2.5), "2");
        assert_eq!(fmt(NumFormat::Fixed(2), -0.006), "-0.01");
    }

    #[test]
    fn fixed_never_writes_minus_zero() {
        // printf writes "-0.00" and "-0.0" for these; a sign on a written zero is noise.
        assert_eq!(fmt(NumFormat::Fixed(2), -0.001), "0.00");
        assert_eq!(fmt(NumFormat::Fixed(1), -1e-9), "0.0");
        assert_eq!(fmt(NumFormat::Fixed(0), -0.4), "0");
        assert_eq!(fmt(NumFormat::Fixed(3), -0.0), "0.000");
        assert_eq!(fmt(NumFormat::Fixed(0), -0.5), "0");
        assert_eq!(fmt(NumFormat::Fixed(0), -0.51), "-1");
        let mut out = Vec::new();
        fixed(&mut out, -1e-30, 20, &mut itoa::Buffer::new());
        assert_eq!(out, b"0.00000000000000000000");
    }

    #[test]
    fn shortest_ignores_the_precision() {
        let mut out = Vec::new();
        NumWriter::new(NumFormat::Fixed(1)).shortest(&mut out, 1.0 / 30.0);
        assert_eq!(out, b"0.03333333333333333");
    }
}
