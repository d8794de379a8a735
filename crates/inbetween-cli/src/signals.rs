//! SIGINT, SIGTERM and SIGHUP: remove the temporary file of an unfinished `-o` output, then end
//! by the same signal, as without a handler (a shell reports 128 + the signal's number: 130,
//! 143, 129), so that a script or a shell loop sees the interruption.
//!
//! A signal that is ignored when the tool starts (`nohup` ignores SIGHUP; a non-interactive
//! shell's `&` ignores SIGINT) stays ignored.

/// Starts the thread that waits for the signals. If they cannot be registered the tool runs
/// without it, as before (a temporary file may then be left behind on a signal). Unix only.
pub fn install() {
    #[cfg(unix)]
    unix();
}

#[cfg(unix)]
fn unix() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    use signal_hook::iterator::Signals;
    let wanted: Vec<i32> = [SIGINT, SIGTERM, SIGHUP]
        .into_iter()
        .filter(|&sig| !ignored(sig))
        .collect();
    let Ok(mut signals) = Signals::new(&wanted) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(sig) = signals.forever().next() {
            inbetween_commands::output::remove_temp_files();
            // Restores the default action and raises the signal again: the process ends by it.
            let _ = signal_hook::low_level::emulate_default_handler(sig);
            // Not reached for these signals; in case it is, the conventional exit code.
            std::process::exit(128 + sig);
        }
    });
}

/// Whether `sig`'s action is "ignore" (inherited from the parent).
#[cfg(unix)]
fn ignored(sig: i32) -> bool {
    // SAFETY: with a null new action, sigaction only writes the current action into `old`, a
    // plain C struct for which all zero bytes are a valid value.
    unsafe {
        let mut old: libc::sigaction = std::mem::zeroed();
        libc::sigaction(sig, std::ptr::null(), &mut old) == 0 && old.sa_sigaction == libc::SIG_IGN
    }
}
