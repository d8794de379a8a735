//! The application under inbetween's front ends (the command line, Python): each command as a
//! request ([`args`]: its options, parsed) run against files, written once. [`interp`],
//! [`convert`], [`reduce`], [`diff`] and [`analyze`] read their input through one path
//! ([`settings`]), check what the output format can carry ([`capability`]), write atomically
//! ([`output`]: never a file the command reads) and tell warnings and report lines through the
//! caller's sink ([`events`]); [`batch`] runs one over many inputs, each coming to a
//! [`record`] (the manifest line and Python's `process_file` result). The library prints
//! nothing; its messages name the options as the command line spells them ([`flags`]), which is
//! also how Python's `process_file` takes them ([`keywords`]).

pub mod amass;
pub mod analyze;
pub mod args;
pub mod batch;
pub mod capability;
pub mod convert;
pub mod diff;
pub mod events;
pub mod flags;
pub mod inputs;
pub mod interp;
pub mod keywords;
pub mod output;
pub mod pattern;
pub mod played;
pub mod points;
pub mod record;
pub mod reduce;
pub mod settings;
pub mod shown;
pub mod skeleton;
pub mod table;
pub mod view;

use inbetween::Error;

/// The exit code of an error, by its kind: 2 for bad input or options, 1 for an I/O error or an
/// internal one (a check of the library's own result that failed: a bug).
pub fn exit_code(e: &Error) -> u8 {
    match e {
        Error::Input(_) => 2,
        Error::Io(_) | Error::Internal(_) => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_codes_follow_the_error_kinds() {
        let input = Error::Input(inbetween::InputError::new("bad"));
        let internal = Error::Internal("internal error: reduce's keys miss a frame".into());
        let io = Error::Io(std::io::Error::other("disk full"));
        assert_eq!(
            [&input, &internal, &io].map(exit_code),
            [2, 1, 1],
            "input, internal, I/O"
        );
    }
}
