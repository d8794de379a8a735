//! The `inbetween` binary: the command line of the library ([`inbetween_cli::run`]), with the
//! signal handlers installed and standard error as its stream of messages.

use std::process::ExitCode;

fn main() -> ExitCode {
    inbetween_cli::install_signals();
    let mut stdin = std::io::stdin().lock();
    let code = inbetween_cli::run(std::env::args_os().collect(), &mut stdin, &mut |line| {
        eprintln!("{line}")
    });
    ExitCode::from(code)
}
