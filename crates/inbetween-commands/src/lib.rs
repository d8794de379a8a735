//! The application under inbetween's front ends (the command line, Python): what a command does
//! with files, written once. Today: where output goes ([`output`]: atomic files, never one the
//! command reads) and what one input came to ([`record`]: a batch's manifest line and Python's
//! `process_file` result). It names no flag and prints nothing; a front end names its own
//! options in its messages (the command line's `-o`; Python says which argument it is).

pub mod capability;
pub mod events;
pub mod inputs;
pub mod output;
pub mod pattern;
pub mod record;
pub mod shown;
