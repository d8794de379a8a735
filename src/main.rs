//! The `inbetween` binary: parse arguments, run the library, map errors to exit codes
//! (0 success, 2 bad usage or input, 1 anything else; a closed stdout is success).

mod cli;
mod cmd;
mod signals;
mod warnings;

use clap::Parser;
use cli::{Cli, Command};
use inbetween::Error;
use std::process::ExitCode;

fn main() -> ExitCode {
    signals::install();
    let cli = Cli::parse();
    let mut stdin = std::io::stdin().lock();
    let mut warnings = warnings::Warnings::default();
    let mut warn = |msg: &str| {
        if let Some(line) = warnings.note(msg) {
            eprintln!("{line}");
        }
    };
    let result = match &cli.command {
        Command::Convert(args) => cmd::convert::run(args, &mut stdin, &mut warn),
        Command::Interp(args) => cmd::interp::run(args, &mut stdin, &mut warn),
        Command::Analyze(args) => cmd::analyze::run(args, &mut stdin, &mut warn),
        Command::Plot(args) => cmd::plot::run(args, &mut stdin, &mut warn),
        Command::Reduce(args) => cmd::reduce::run(args, &mut stdin, &mut warn),
    };
    for line in warnings.summary() {
        eprintln!("{line}");
    }
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let io = match &e {
                Error::Io(io) => Some(io),
                Error::Input(_) => None,
            };
            if io.is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) {
                return ExitCode::SUCCESS;
            }
            eprintln!("inbetween: error: {e}");
            match e {
                Error::Input(_) => ExitCode::from(2),
                Error::Io(_) => ExitCode::from(1),
            }
        }
    }
}
