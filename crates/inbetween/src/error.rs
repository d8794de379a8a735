//! Errors: a typed [`Error`] for the library (the user's input, or I/O), and [`InputError`], a
//! problem with the user's input or options, located.
//!
//! The binary maps [`InputError`] to exit code 2 and any other error to exit code 1. Every
//! input message names where the problem is (file, line or key, field), what was expected and
//! what was found, e.g. `keys.csv:14: column "w": expected a number, found "abc"`.

use std::borrow::Cow;
use std::fmt;
use std::io;

/// A problem with the user's input or options (exit code 2 in the binary).
///
/// ```
/// use inbetween::Fps;
///
/// let e = "abc".parse::<Fps>().unwrap_err().at("--fps");
/// assert_eq!(
///     e.to_string(),
///     "--fps: expected a positive frame rate such as 24, 29.97 or 30000/1001, found \"abc\""
/// );
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputError(String);

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

impl InputError {
    /// An error with this message (lowercase, naming what was expected and what was found).
    pub fn new(msg: impl Into<String>) -> Self {
        InputError(msg.into())
    }

    /// Prefixes the message with a location such as `keys.csv:14` or `keys.json: keys[3]`.
    pub fn at(self, location: impl fmt::Display) -> Self {
        InputError(format!("{location}: {}", self.0))
    }

    /// The message.
    pub fn message(&self) -> &str {
        &self.0
    }
}

/// An error of the library: the user's input, or I/O (reading, writing, a worker thread).
#[derive(Debug)]
pub enum Error {
    /// Bad input or options, located.
    Input(InputError),
    /// An I/O error.
    Io(io::Error),
    /// A check the library makes of its own result failed: a bug (the binary exits 1). Its
    /// message starts `internal error:`.
    Internal(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Input(e) => e.fmt(f),
            Error::Io(e) => e.fmt(f),
            Error::Internal(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Input(e) => Some(e),
            Error::Io(e) => Some(e),
            Error::Internal(_) => None,
        }
    }
}

impl From<InputError> for Error {
    fn from(e: InputError) -> Error {
        Error::Input(e)
    }
}

impl From<io::Error> for Error {
    fn from(e: io::Error) -> Error {
        Error::Io(e)
    }
}

/// A number for a message: plain digits for ordinary magnitudes (`0.5`, `1.01`, `-24`),
/// exponent notation with every significant digit for very small or large ones (`5e-324`,
/// `1e300`, `1.2345e-7`; Rust's `{}` would print 5e-324 with 323 zeros), `0` for ±0.
pub fn num(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else if (1e-4..1e15).contains(&x.abs()) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The most characters of a user's text (a field, a column or track name, a JSON string) that
/// a message quotes; longer text is cut by [`shorten`].
pub const MAX_QUOTED_CHARS: usize = 60;

/// `s` as a message quotes it: unchanged up to [`MAX_QUOTED_CHARS`] characters (Unicode scalar
/// values, not bytes), else its first [`MAX_QUOTED_CHARS`] characters followed by `…`. Never
/// splits a character; costs O(1) whatever the length of `s`.
///
/// ```
/// use inbetween::error::shorten;
///
/// assert_eq!(shorten("abc"), "abc");
/// let long = "é".repeat(61);
/// assert_eq!(shorten(&long), format!("{}…", "é".repeat(60)));
/// assert_eq!(shorten("\u{1b}[31mRED"), "\\u{1b}[31mRED");
/// ```
pub fn shorten(s: &str) -> Cow<'_, str> {
    let cut = match s.char_indices().nth(MAX_QUOTED_CHARS) {
        None => Cow::Borrowed(s),
        Some((end, _)) => Cow::Owned(format!("{}…", &s[..end])),
    };
    // Control characters (an escape sequence, a NUL) are shown escaped, never sent to the
    // terminal as they are.
    if cut.chars().any(char::is_control) {
        Cow::Owned(
            cut.chars()
                .flat_map(|c| {
                    let escaped: Vec<char> = if c.is_control() {
                        c.escape_default().collect()
                    } else {
                        vec![c]
                    };
                    escaped
                })
                .collect(),
        )
    } else {
        cut
    }
}

/// Shorthand for results whose error is an [`InputError`].
pub type InputResult<T> = Result<T, InputError>;

/// Builds an [`InputError`] with `format!` syntax.
macro_rules! input_err {
    ($($arg:tt)*) => { $crate::error::InputError::new(format!($($arg)*)) };
}
pub(crate) use input_err;

#[cfg(test)]
mod tests {
    use super::num;

    #[test]
    fn numbers_keep_their_digits() {
        assert_eq!(num(0.5), "0.5");
        assert_eq!(num(-24.0), "-24");
        assert_eq!(num(1.01), "1.01");
        assert_eq!(num(1e-4), "0.0001");
        assert_eq!(num(999999999999999.0), "999999999999999");
        assert_eq!(num(1e15), "1e15");
        assert_eq!(num(1e300), "1e300");
        assert_eq!(num(-1.2345e-7), "-1.2345e-7");
        assert_eq!(num(5e-324), "5e-324");
        assert_eq!(num(0.0), "0");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(f64::INFINITY), "inf");
    }
}
