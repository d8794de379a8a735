//! Library messages in the command line's words: each [`Setting`] a message names is shown as
//! the flag that sets it. This is the only place the
//! library's messages add a flag's name (the command line's tests check that each is a flag).

use inbetween::Error;
use inbetween::error::{Message, Setting};

/// The flag that sets `s`.
pub fn flag(s: Setting) -> &'static str {
    match s {
        Setting::Scheme => "--scheme",
        Setting::FrameRate => "--fps",
        Setting::KeyRate => "--key-fps",
        Setting::Rotation => "--from",
        Setting::InputAngles => "--input-angles",
        Setting::SharedKeys => "--shared-keys",
        Setting::Animation => "--animation",
        Setting::Skeleton => "--skeleton",
        Setting::MaxInputBytes => "--max-input-bytes",
    }
}

/// A library message (a warning) with its settings shown as flags.
pub fn say(m: &Message) -> String {
    m.render(flag)
}

/// An error as the binary prints it: an input error with its settings shown as flags.
pub fn error_text(e: &Error) -> String {
    match e {
        Error::Input(e) => say(e.parts()),
        e => e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_are_shown_as_their_flags() {
        let m = inbetween::message!["keep one or pass ", Setting::Rotation];
        assert_eq!(say(&m), "keep one or pass --from");
        assert_eq!(m.to_string(), "keep one or pass rotation representation");
        let e = Error::Input(inbetween::InputError::new(m).at("k.csv:1"));
        assert_eq!(error_text(&e), "k.csv:1: keep one or pass --from");
    }
}
