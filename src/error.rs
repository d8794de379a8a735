//! Errors that the user caused (bad input, bad options) versus everything else.
//!
//! The binary maps [`InputError`] to exit code 2 and any other error to exit code 1. Every
//! message names where the problem is (file, line or key, field), what was expected and what was
//! found, e.g. `keys.csv:14: column "w": expected a number, found "abc"`.

use std::fmt;

/// A problem with the user's input or options. Exit code 2.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputError(pub String);

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

impl InputError {
    pub fn new(msg: impl Into<String>) -> Self {
        InputError(msg.into())
    }

    /// Prefixes the message with a location such as `keys.csv:14` or `keys.json: keys[3]`.
    pub fn at(self, location: impl fmt::Display) -> Self {
        InputError(format!("{location}: {}", self.0))
    }
}

/// A number for a message: plain digits for ordinary magnitudes, exponent notation for very small
/// or large ones (Rust's `{}` would print 5e-324 with 323 zeros).
pub fn num(x: f64) -> String {
    if x == 0.0 || (1e-4..1e15).contains(&x.abs()) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Shorthand for results whose error is an [`InputError`].
pub type InputResult<T> = Result<T, InputError>;

/// Builds an [`InputError`] with `format!` syntax.
#[macro_export]
macro_rules! input_err {
    ($($arg:tt)*) => { $crate::error::InputError(format!($($arg)*)) };
}
