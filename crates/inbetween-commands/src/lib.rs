//! The application under inbetween's front ends (the command line, Python): what a command does
//! with files, written once. Today: where output goes ([`output`]: atomic files, never one the
//! command reads). It names no flag and prints nothing; a front end names its own options in its
//! messages (the command line's `-o`, Python's `path`).

pub mod output;
