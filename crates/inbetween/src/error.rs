//! Errors: a typed [`Error`] for the library (the user's input, or I/O), and [`InputError`], a
//! problem with the user's input or options, located.
//!
//! The binary maps [`InputError`] to exit code 2 and any other error to exit code 1. Every
//! input message names where the problem is (file, line or key, field), what was expected and
//! what was found, e.g. `keys.csv:14: column "w": expected a number, found "abc"`.

use std::borrow::Cow;
use std::fmt;
use std::io;

/// An option of the library or of its formats crate that a message can name. [`Message`]'s
/// `Display` shows it as a term of the documents (`the key rate`); the command line shows it as
/// its flag (`--key-fps`), through [`Message::render`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Setting {
    /// The interpolation scheme ([`crate::Scheme`]).
    Scheme,
    /// The output frame rate.
    FrameRate,
    /// The rate of keys given as frame numbers.
    KeyRate,
    /// The rotation representation of the input (quaternions, an Euler sequence, …).
    Rotation,
    /// The unit of input angles (degrees or radians).
    InputAngles,
    /// Keys shared by every track (reduce).
    SharedKeys,
    /// The animation of a glTF asset to read.
    Animation,
    /// The skeleton BVH output is written against.
    Skeleton,
    /// The largest input accepted, in bytes.
    MaxInputBytes,
}

impl Setting {
    /// Every setting, in declaration order.
    pub const ALL: [Setting; 9] = [
        Setting::Scheme,
        Setting::FrameRate,
        Setting::KeyRate,
        Setting::Rotation,
        Setting::InputAngles,
        Setting::SharedKeys,
        Setting::Animation,
        Setting::Skeleton,
        Setting::MaxInputBytes,
    ];

    /// The setting as the documents name it, e.g. `key rate` (no article, so that it reads in
    /// place of a flag: `… but key rate says 25`, `use a lower frame rate`).
    pub fn term(self) -> &'static str {
        match self {
            Setting::Scheme => "scheme",
            Setting::FrameRate => "frame rate",
            Setting::KeyRate => "key rate",
            Setting::Rotation => "rotation representation",
            Setting::InputAngles => "input angle unit",
            Setting::SharedKeys => "shared keys",
            Setting::Animation => "animation",
            Setting::Skeleton => "BVH output on a skeleton",
            Setting::MaxInputBytes => "input size limit",
        }
    }
}

/// The text of an error or a warning, with the [`Setting`]s it names kept apart from its
/// words, so that a caller can show each setting in its own terms ([`Message::render`]).
///
/// ```
/// use inbetween::error::{Message, Setting};
///
/// let m = Message::from("k.json declares \"fps\": 24 but ")
///     .with(Setting::KeyRate)
///     .with(" says 25");
/// assert_eq!(m.to_string(), "k.json declares \"fps\": 24 but key rate says 25");
/// let flag = |s| if s == Setting::KeyRate { "--key-fps" } else { "?" };
/// assert_eq!(m.render(flag), "k.json declares \"fps\": 24 but --key-fps says 25");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Message {
    parts: Vec<Part>,
}

#[derive(Debug, Clone, PartialEq, Eq)]
enum Part {
    Text(String),
    Setting(Setting),
}

impl Message {
    /// The message followed by `part`: text, or a [`Setting`].
    pub fn with(mut self, part: impl Into<MessagePart>) -> Message {
        match part.into().0 {
            Part::Text(t) => match self.parts.last_mut() {
                Some(Part::Text(last)) => last.push_str(&t),
                _ => self.parts.push(Part::Text(t)),
            },
            p => self.parts.push(p),
        }
        self
    }

    /// The message followed by `other`.
    pub fn append(self, other: Message) -> Message {
        other
            .parts
            .into_iter()
            .fold(self, |m, p| m.with(MessagePart(p)))
    }

    /// The message with each setting shown as `name` gives it.
    pub fn render<'a>(&self, name: impl Fn(Setting) -> &'a str) -> String {
        let mut out = String::new();
        for p in &self.parts {
            match p {
                Part::Text(t) => out.push_str(t),
                Part::Setting(s) => out.push_str(name(*s)),
            }
        }
        out
    }

    /// The settings the message names, in order.
    pub fn settings(&self) -> impl Iterator<Item = Setting> + '_ {
        self.parts.iter().filter_map(|p| match p {
            Part::Setting(s) => Some(*s),
            Part::Text(_) => None,
        })
    }
}

/// A part of a [`Message`]: text (`&str`, `String`) or a [`Setting`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MessagePart(Part);

impl From<&str> for MessagePart {
    fn from(t: &str) -> MessagePart {
        MessagePart(Part::Text(t.to_string()))
    }
}

impl From<String> for MessagePart {
    fn from(t: String) -> MessagePart {
        MessagePart(Part::Text(t))
    }
}

impl From<Setting> for MessagePart {
    fn from(s: Setting) -> MessagePart {
        MessagePart(Part::Setting(s))
    }
}

impl<T: Into<MessagePart>> From<T> for Message {
    fn from(part: T) -> Message {
        Message::default().with(part)
    }
}

impl fmt::Display for Message {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(Setting::term))
    }
}

/// Builds a [`Message`] from parts: text (`&str`, `String`, e.g. `format!(…)`) and
/// [`Setting`]s, in order.
#[macro_export]
macro_rules! message {
    ($($part:expr),+ $(,)?) => {
        $crate::error::Message::default()$(.with($part))+
    };
}

/// A problem with the user's input or options (exit code 2 in the binary).
///
/// ```
/// use inbetween::Fps;
///
/// let e = "abc".parse::<Fps>().unwrap_err().at("frame rate");
/// assert_eq!(
///     e.to_string(),
///     "frame rate: expected a positive frame rate such as 24, 29.97 or 30000/1001, found \"abc\""
/// );
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputError(Message);

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for InputError {}

impl InputError {
    /// An error with this message (lowercase, naming what was expected and what was found): a
    /// `String`, a `&str`, or a [`Message`] that names settings.
    pub fn new(msg: impl Into<Message>) -> Self {
        InputError(msg.into())
    }

    /// Prefixes the message with a location such as `keys.csv:14` or `keys.json: keys[3]`.
    pub fn at(self, location: impl fmt::Display) -> Self {
        self.at_setting(format!("{location}"))
    }

    /// Prefixes the message with a location that may name a setting, and `: `.
    pub fn at_setting(self, location: impl Into<MessagePart>) -> Self {
        InputError(Message::from(location).with(": ").append(self.0))
    }

    /// The message, each setting shown as its term ([`Setting::term`]).
    pub fn message(&self) -> String {
        self.0.to_string()
    }

    /// The message with its settings apart, for a caller that names them its own way.
    pub fn parts(&self) -> &Message {
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
