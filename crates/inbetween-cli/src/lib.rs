//! The `inbetween` command line as a library: [`run`] parses arguments, runs the command and
//! maps errors to exit codes (0 success, 2 bad usage or input, 1 anything else; a closed stdout
//! is success) — what the binary does (`src/main.rs`), and what the Python package's
//! `process_file` runs in-process, so that both write the same bytes.

mod chart;
mod cli;
mod plot;
mod signals;
mod warnings;

use clap::Parser;
use cli::{Cli, Command};
use inbetween::Error;
use inbetween_commands::batch::Progress;
use inbetween_commands::events::{Collected, Events};
use inbetween_commands::record::Record;
use inbetween_commands::{analyze, batch, convert, diff, exit_code, flags, interp, reduce, view};
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

/// Installs the handlers that remove an unfinished output's temporary file on SIGINT, SIGTERM
/// and SIGHUP (the binary does; a host process such as Python keeps its own).
pub fn install_signals() {
    signals::install();
}

/// Runs a command over several inputs ([`batch::run`]): each input with its own `-o` under
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
            batch::run(
                args.input.input.as_deref(),
                &args.batch,
                &|input: &std::path::Path| batch::extension(input, &args.output, $keys),
                &|input: &std::path::Path, output: &std::path::Path, warn: &mut dyn Events| {
                    let mut one = args.clone();
                    one.input.input = Some(input.to_path_buf());
                    one.output.output = Some(output.to_path_buf());
                    one.batch = Default::default();
                    $run(&one, &mut std::io::empty(), warn)
                },
                &Bar::new(),
            )
        }
    }};
}

/// A batch's progress on the command line: a bar on a terminal (files done of all, elapsed,
/// rate; nothing otherwise), and on standard error what each input told and its error, and the
/// summary.
struct Bar(indicatif::ProgressBar);

impl Bar {
    fn new() -> Bar {
        Bar(indicatif::ProgressBar::hidden())
    }
}

impl Progress for Bar {
    fn start(&self, inputs: usize) {
        if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
            let style = indicatif::ProgressStyle::with_template(
                "{bar:30} {pos}/{len} files, {elapsed_precise}, {per_sec}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
            self.0.set_style(style);
            self.0.set_length(inputs as u64);
            self.0
                .set_draw_target(indicatif::ProgressDrawTarget::stderr());
        }
    }

    fn warning(&self, message: &str) {
        self.0
            .suspend(|| eprintln!("inbetween: warning: {}", cli::line(message)));
    }

    fn finished(&self, record: &Record, told: &Collected) {
        self.0.suspend(|| {
            for r in &told.reports {
                eprintln!("{}", cli::line(r));
            }
            for w in &told.warnings {
                eprintln!("inbetween: warning: {}", cli::line(w));
            }
            if let Some(m) = &record.error {
                eprintln!("inbetween: error: {}", cli::line(m));
            }
        });
        self.0.inc(1);
    }

    fn summary(&self, line: &str) {
        self.0.finish_and_clear();
        eprintln!("inbetween: {line}");
    }
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
        Command::Convert(a) if batch::wanted(&a.batch) => batch!(a, convert::run, true),
        Command::Interp(a) if batch::wanted(&a.batch) => batch!(a, interp::run, false),
        Command::Reduce(a) if batch::wanted(&a.batch) => batch!(a, reduce::run, true),
        Command::Convert(args) => convert::run(args, stdin, &mut warn),
        Command::Interp(args) => interp::run(args, stdin, &mut warn),
        Command::Analyze(args) => analyze::run(args, stdin, &mut warn),
        Command::Plot(args) => plot::run(args, stdin, &mut warn),
        Command::Reduce(args) => reduce::run(args, stdin, &mut warn),
        Command::View(args) => view::run(args, stdin, &mut warn),
        Command::Diff(args) => diff::run(args, stdin, &mut warn).map(|exceeded| {
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
            exit_code(&e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(exit_code(&e), 1);
    }
}
