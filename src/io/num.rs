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

impl NumWriter {
    pub fn new(format: NumFormat) -> Self {
        NumWriter {
            format,
            zmij: zmij::Buffer::new(),
            itoa: itoa::Buffer::new(),
        }
    }

    /// Appends a finite float. (Non-finite values never reach output: inputs are validated and
    /// every curve point is finite; a non-finite value is written as JSON-invalid `NaN` so that a
    /// bug cannot pass silently as a number.)
    #[inline]
    pub fn float(&mut self, out: &mut Vec<u8>, x: f64) {
        match self.format {
            // `+ 0.0` turns −0 into 0: a sign on zero carries no information here.
            NumFormat::Shortest => out.extend_from_slice(self.zmij.format(x + 0.0).as_bytes()),
            NumFormat::Fixed(n) => {
                use std::io::Write;
                let _ = write!(out, "{x:.n$}");
            }
        }
    }

    #[inline]
    pub fn int(&mut self, out: &mut Vec<u8>, k: i64) {
        out.extend_from_slice(self.itoa.format(k).as_bytes());
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
    fn fixed_matches_printf() {
        assert_eq!(fmt(NumFormat::Fixed(3), 0.12345), "0.123");
        assert_eq!(fmt(NumFormat::Fixed(0), 2.5), "2");
        assert_eq!(fmt(NumFormat::Fixed(2), -0.001), "-0.00");
    }
}
