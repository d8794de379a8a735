//! Output as the command line names it: [`inbetween_commands::output`] with `-o ` before the
//! path in messages (`-o out: expected a file, found a directory`).

use inbetween::Error;
pub use inbetween_commands::output::{
    Output, WriteBehind, files_read, hold_commits, hold_now, release_commit, remove_temp_files,
};
use std::path::{Path, PathBuf};

/// [`Output::open`] for `-o PATH` (`None` or `-`: standard output), refusing the files the
/// command reads (`reads`).
pub fn open(path: Option<&Path>, reads: &[PathBuf]) -> Result<Output, Error> {
    Output::open(path, reads, "-o ")
}
