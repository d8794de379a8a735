//! The `inbetween` binary: parse arguments, run the library, map errors to exit codes
//! (0 success, 2 bad usage or input, 1 anything else; a closed stdout is success).

use clap::Parser;
use inbetween::InputError;
use inbetween::cli::{Cli, Command};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let mut stdin = std::io::stdin().lock();
    let mut warn = |msg: &str| eprintln!("inbetween: warning: {msg}");
    let result = match &cli.command {
        Command::Convert(args) => inbetween::cmd::convert::run(args, &mut stdin, &mut warn),
        Command::Interp(args) => inbetween::cmd::interp::run(args, &mut stdin, &mut warn),
        Command::Analyze(args) => inbetween::cmd::analyze::run(args, &mut stdin, &mut warn),
        Command::Plot(args) => inbetween::cmd::plot::run(args, &mut stdin, &mut warn),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if let Some(io) = e.downcast_ref::<std::io::Error>()
                && io.kind() == std::io::ErrorKind::BrokenPipe
            {
                return ExitCode::SUCCESS;
            }
            eprintln!("inbetween: error: {e}");
            if e.downcast_ref::<InputError>().is_some() {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}
