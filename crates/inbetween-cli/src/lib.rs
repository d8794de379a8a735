//! The `inbetween` command line as a library: [`run`] parses arguments, runs the command and
//! maps errors to exit codes (0 success, 2 bad usage or input, 1 anything else; a closed stdout
//! is success) — what the binary does (`src/main.rs`), and what the Python package's
//! `process_file` runs in-process, so that both write the same bytes.

mod chart;
mod cli;
pub use inbetween_commands::events::{Collected, Events};
pub use inbetween_commands::record::{Record, Status};
mod cmd;
mod flags;
mod output;
mod signals;
mod warnings;

use clap::Parser;
use cli::{Cli, Command};
use inbetween::Error;
use std::ffi::OsString;
use std::io::Read;

/// clap's own message (help and version as clap prints them), with every value it echoes cut
/// to 60 characters: a 100 kB `--fps` value is quoted once, shortened, never whole.
fn usage_error(e: &clap::Error, err: &mut dyn FnMut(&str)) -> u8 {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion)
        || e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    {
        // Help goes where clap sends it; only an unwritable stdout is a failure.
        return match e.print() {
            Ok(()) => u8::try_from(e.exit_code()).unwrap_or(2),
            Err(_) => 1,
        };
    }
    let text = cli::bounded(&e.render().to_string());
    err(text.trim_end_matches('\n'));
    2
}

/// The long options of `command` (`fps`, `translation-tolerance`, …), as the command line
/// spells them without their `--`: what `inbetween.process_file` accepts.
pub fn option_names(command: &str) -> Vec<String> {
    use clap::CommandFactory;
    Cli::command()
        .find_subcommand(command)
        .map(|c| {
            c.get_arguments()
                .filter_map(|a| a.get_long().map(str::to_string))
                .collect()
        })
        .unwrap_or_default()
}

/// One input of `interp`, `convert` or `reduce` run as a batch runs each input, for Python's
/// `process_file`: `args` is the command line (program name, command, input, `-o OUTPUT`,
/// options). Returns its record (the manifest line), the exit code the command line would give
/// and what it told (warnings and `-v` report lines, each escaped as on stderr). The input is skipped when its output is up to
/// date ([`inbetween_commands::inputs::up_to_date`]), unless `refresh`; an option the command line refuses is a failed
/// record with clap's message and exit code 2.
pub fn process_one(args: Vec<OsString>, refresh: bool) -> (Record, u8, Collected) {
    let mut cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            let text = cli::bounded(&e.render().to_string());
            let first = text
                .lines()
                .find(|l| !l.trim().is_empty())
                .unwrap_or_default();
            let mut record = Record::new(String::new(), None, Status::Failed);
            record.seconds = Some(0.0);
            record.error = Some(first.strip_prefix("error: ").unwrap_or(first).to_string());
            let told = Collected {
                warnings: text.lines().map(cli::line).collect(),
                reports: Vec::new(),
            };
            return (record, 2, told);
        }
    };
    cli.command.normalise();
    let (input, output) = match &cli.command {
        Command::Convert(a) => (a.input.input.clone(), a.output.output.clone()),
        Command::Interp(a) => (a.input.input.clone(), a.output.output.clone()),
        Command::Reduce(a) => (a.input.input.clone(), a.output.output.clone()),
        _ => (None, None),
    };
    let one = |_: &std::path::Path, _: &std::path::Path, warn: &mut dyn Events| match &cli.command {
        Command::Convert(a) => cmd::convert::run(a, &mut std::io::empty(), warn),
        Command::Interp(a) => cmd::interp::run(a, &mut std::io::empty(), warn),
        Command::Reduce(a) => cmd::reduce::run(a, &mut std::io::empty(), warn),
        _ => Err(inbetween::InputError::new(
            "command: expected interp, convert or reduce, which write a file",
        )
        .into()),
    };
    let (Some(input), Some(output)) = (input, output) else {
        let mut record = Record::new(String::new(), None, Status::Failed);
        record.error = Some("an input and an output are needed".to_string());
        return (record, 2, Collected::default());
    };
    let mut told = Collected::default();
    let (record, error) = cmd::batch::run_job(&input, &output, refresh, &one, &mut told);
    let code = error.as_ref().map_or(0, exit_status);
    let escaped = |lines: Vec<String>| lines.iter().map(|l| cli::line(l)).collect();
    let told = Collected {
        warnings: escaped(told.warnings),
        reports: escaped(told.reports),
    };
    (record, code, told)
}

/// Installs the handlers that remove an unfinished output's temporary file on SIGINT, SIGTERM
/// and SIGHUP (the binary does; a host process such as Python keeps its own).
pub fn install_signals() {
    signals::install();
}

/// Runs a command over several inputs ([`cmd::batch::run`]): each input with its own `-o` under
/// `--out-dir`, standard input empty, the batch options cleared.
macro_rules! batch {
    ($args:expr, $run:path, $keys:expr) => {{
        let args = $args;
        if args.output.output.is_some() {
            Err(inbetween::InputError::new(
                "-o names one output; with --out-dir each input's output is named after it",
            )
            .into())
        } else {
            cmd::batch::run(
                args.input.input.as_deref(),
                &args.batch,
                &|input: &std::path::Path| cmd::batch::extension(input, &args.output, $keys),
                &|input: &std::path::Path, output: &std::path::Path, warn: &mut dyn Events| {
                    let mut one = args.clone();
                    one.input.input = Some(input.to_path_buf());
                    one.output.output = Some(output.to_path_buf());
                    one.batch = Default::default();
                    $run(&one, &mut std::io::empty(), warn)
                },
            )
        }
    }};
}

/// What a command tells, on the command line's standard error: warnings through the limiter
/// (at most 10 of a kind, then a count), report lines as they are.
struct Told<'a> {
    warnings: warnings::Warnings,
    err: &'a mut dyn FnMut(&str),
}

impl Events for Told<'_> {
    fn warning(&mut self, message: &str) {
        if let Some(line) = self.warnings.note(message) {
            (self.err)(&line);
        }
    }

    fn report(&mut self, line: &str) {
        (self.err)(line);
    }
}

/// Runs the command line `args` (the program name first, as `std::env::args_os` gives it) with
/// `stdin` as standard input; every line meant for standard error goes to `err` (without its
/// line end). Returns the exit code.
pub fn run(args: Vec<OsString>, stdin: &mut dyn Read, err: &mut dyn FnMut(&str)) -> u8 {
    // Every line of stderr escaped and bounded (cli::line); a text of several lines (clap's
    // usage errors) line by line.
    let err = &mut |text: &str| {
        for l in text.split('\n') {
            err(&cli::line(l));
        }
    };
    let mut cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => return usage_error(&e, err),
    };
    cli.command.normalise();
    let mut warn = Told {
        warnings: warnings::Warnings::default(),
        err,
    };
    // `diff --max-angle/--max-position`: the limit a difference exceeds (exit 1, as diff(1)).
    let mut exceeds: Option<String> = None;
    let result = match &cli.command {
        Command::Convert(a) if cmd::batch::wanted(&a.batch) => batch!(a, cmd::convert::run, true),
        Command::Interp(a) if cmd::batch::wanted(&a.batch) => batch!(a, cmd::interp::run, false),
        Command::Reduce(a) if cmd::batch::wanted(&a.batch) => batch!(a, cmd::reduce::run, true),
        Command::Convert(args) => cmd::convert::run(args, stdin, &mut warn),
        Command::Interp(args) => cmd::interp::run(args, stdin, &mut warn),
        Command::Analyze(args) => cmd::analyze::run(args, stdin, &mut warn),
        Command::Plot(args) => cmd::plot::run(args, stdin, &mut warn),
        Command::Reduce(args) => cmd::reduce::run(args, stdin, &mut warn),
        Command::Diff(args) => cmd::diff::run(args, stdin, &mut warn).map(|exceeded| {
            exceeds = exceeded;
        }),
    };
    let err = warn.err;
    for line in warn.warnings.summary() {
        err(&line);
    }
    match result {
        Ok(()) => match exceeds {
            Some(what) => {
                err(&format!("inbetween: {what}"));
                1
            }
            None => 0,
        },
        Err(e) => {
            let io = match &e {
                Error::Io(io) => Some(io),
                Error::Input(_) | Error::Internal(_) => None,
            };
            if io.is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) {
                return 0;
            }
            err(&format!("inbetween: error: {}", flags::error_text(&e)));
            exit_status(&e)
        }
    }
}

/// The exit status of an error, by its kind: 2 for bad input or options, 1 for an I/O error or an
/// internal one (a check of the library's own result that failed: a bug).
fn exit_status(e: &Error) -> u8 {
    match e {
        Error::Input(_) => 2,
        Error::Io(_) | Error::Internal(_) => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_statuses_follow_the_error_kinds() {
        let input = Error::Input(inbetween::InputError::new("bad"));
        let internal = Error::Internal("internal error: reduce's keys miss a frame".into());
        let io = Error::Io(std::io::Error::other("disk full"));
        assert_eq!(
            [&input, &internal, &io].map(exit_status),
            [2, 1, 1],
            "input, internal, I/O"
        );
    }

    /// An internal error provoked through the library: BVH frames told of a track that is not
    /// the skeleton's next joint refuse it as the writer's own bug (not data in the wrong place),
    /// and the binary exits 1 on it, not 2.
    #[test]
    fn an_internal_error_of_the_library_exits_1() {
        use inbetween::bake::FrameSink;
        use std::sync::Arc;
        let text = "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 1 Zrotation\n}\n\
                    ROOT b\n{\nOFFSET 0 0 0\nCHANNELS 1 Zrotation\n}\n\
                    MOTION\nFrames: 1\nFrame Time: 0.04\n10 20\n";
        let clip = Arc::new(inbetween_io::bvh::parse(text, "a.bvh").unwrap().0);
        let mut sink =
            inbetween_io::bvh::frames::BvhFrames::new(Vec::new(), clip.clone(), clip.fps());
        let e: Error = sink.begin_track(Some("b")).unwrap_err().into();
        assert!(e.to_string().starts_with("internal error: track 0"), "{e}");
        assert_eq!(exit_status(&e), 1);
    }
}
