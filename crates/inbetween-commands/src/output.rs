//! Where output goes: standard output, or a file written atomically (a temporary file beside the
//! target, renamed over it only when everything was written), or a device or pipe written
//! directly.
//!
//! What an output `PATH` (the command line's `-o PATH`) is written as depends on what it is:
//!
//! - a regular file, or nothing yet: a temporary file `.inbetween-*.tmp` in the same directory,
//!   renamed over `PATH` by [`Output::commit`] (atomic; a replaced file keeps its mode, a new one
//!   gets 0666 less the umask);
//! - a symbolic link (or a chain of them): the link stays, and what it finally points to is
//!   treated as above (the temporary file goes beside the link's target);
//! - a character or block device, or a FIFO: opened for writing and written directly, never
//!   replaced (so not atomic);
//! - a directory, a socket, a loop of symbolic links, or a path whose directory does not exist
//!   or is not a directory: an input error naming `PATH`.
//! - a file the command reads (its input by any name, a skeleton file, a glTF input's buffers;
//!   the caller passes them, [`files_read`]): an input error naming `PATH` and that file.
//!
//! Temporary files of uncommitted outputs are listed process-wide so that a signal handler can
//! remove them with [`remove_temp_files`] before the process ends: the one process-wide state of
//! this crate, holding only the outputs open at the moment (an entry leaves with its output).

use inbetween::error::Error;

/// Builds an [`inbetween::InputError`] with `format!` syntax.
macro_rules! input_err {
    ($($arg:tt)*) => { inbetween::error::InputError::new(format!($($arg)*)) };
}
use std::cell::{Cell, RefCell};
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// An output destination: standard output, a temporary file renamed over the target by
/// [`Output::commit`], or a device or FIFO written directly. Dropping it uncommitted leaves an
/// existing target file untouched and removes the temporary file (bytes already written to a
/// device or FIFO stay written).
pub struct Output(Dest);

enum Dest {
    Stdout(BufWriter<io::Stdout>),
    Temp(TempOutput),
    /// Written in place; the user's path as messages show it.
    Direct(BufWriter<File>, String),
}

/// A temporary file, renamed over `target` on commit. `registered` is declared after `writer` so
/// that on drop the file is removed before it leaves the registry (the other order would leave a
/// moment in which a signal could not find it).
struct TempOutput {
    writer: BufWriter<tempfile::NamedTempFile>,
    registered: Registered,
    /// The file to replace: the user's path with symbolic links resolved.
    target: PathBuf,
    /// `target` as messages show it ([`shown`]).
    shown: String,
}

const BUF: usize = 1 << 16;

/// Paths of the temporary files of live, uncommitted outputs. `closed` once
/// [`remove_temp_files`] ran: no temporary file is created or renamed after that.
struct Registry {
    paths: Vec<PathBuf>,
    closed: bool,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    paths: Vec::new(),
    closed: false,
});

/// The files a command reads, as [`Output::open`] protects them: each of `paths` that is a
/// regular file (the input, a skeleton file; `None` and `-` are standard input, and a pipe or
/// device is not replaced by an output, so nothing to protect) and the
/// files an input references (`referenced`: a glTF asset's buffers and images, canonical, as
/// `inbetween_io::gltf::Asset::referenced_files` gives them).
pub fn files_read<'a>(
    paths: impl IntoIterator<Item = Option<&'a Path>>,
    referenced: &[PathBuf],
) -> Vec<PathBuf> {
    paths
        .into_iter()
        .flatten()
        .filter(|p| p.as_os_str() != "-" && p.is_file())
        .filter_map(|p| std::fs::canonicalize(p).ok())
        .chain(referenced.iter().cloned())
        .collect()
}

/// The file of `reads` that `target` is (through links or another name for it), if any.
fn protected(target: &Path, reads: &[PathBuf]) -> Option<PathBuf> {
    if reads.is_empty() {
        return None;
    }
    let canonical = std::fs::canonicalize(target).ok()?;
    #[cfg(unix)]
    let same = |p: &PathBuf| {
        use std::os::unix::fs::MetadataExt;
        match (std::fs::metadata(p), std::fs::metadata(&canonical)) {
            (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
            _ => *p == canonical,
        }
    };
    #[cfg(not(unix))]
    let same = |p: &PathBuf| *p == canonical;
    reads.iter().find(|p| same(p)).cloned()
}

fn registry() -> MutexGuard<'static, Registry> {
    REGISTRY.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A temporary file's place in the registry, left on drop or by `release`.
struct Registered(Option<PathBuf>);

impl Registered {
    fn release(&mut self, reg: &mut Registry) {
        if let Some(p) = self.0.take()
            && let Some(i) = reg.paths.iter().position(|q| *q == p)
        {
            reg.paths.swap_remove(i);
        }
    }
}

impl Drop for Registered {
    fn drop(&mut self) {
        if self.0.is_some() {
            self.release(&mut registry());
        }
    }
}

std::thread_local! {
    /// Set by [`hold_commits`]: a commit on this thread keeps the lock until [`release_commit`].
    static HOLD: Cell<bool> = const { Cell::new(false) };
    static HELD: RefCell<Option<MutexGuard<'static, Registry>>> = const { RefCell::new(None) };
}

/// For a batch: from now on a commit on this thread keeps the lock a signal handler takes
/// ([`remove_temp_files`]) until [`release_commit`], so that the output and the record that says
/// it is finished (the manifest line) are both there or neither when a signal ends the process.
pub fn hold_commits() {
    HOLD.with(|h| h.set(true));
}

/// Takes the lock a signal handler takes, until [`release_commit`], unless this thread holds it
/// already (a commit kept it): for a record that must be written whole or not at all.
pub fn hold_now() {
    HELD.with(|h| {
        let mut h = h.borrow_mut();
        if h.is_none() {
            *h = Some(registry());
        }
    });
}

/// Releases the lock a commit on this thread kept ([`hold_commits`]); nothing if none.
pub fn release_commit() {
    HELD.with(|h| drop(h.borrow_mut().take()));
}

/// Removes the temporary file of every uncommitted file [`Output`] of this process, for a signal
/// handler (SIGINT, SIGTERM, …) about to end the process. It holds the same lock as
/// [`Output::commit`]'s rename, so a target is either replaced whole or left untouched. From then
/// on no temporary file is created or renamed: [`Output::open`] of a file and
/// [`Output::commit`] of one fail with [`io::ErrorKind::Interrupted`]. Errors removing a file are
/// ignored.
pub fn remove_temp_files() {
    let mut reg = registry();
    reg.closed = true;
    for p in reg.paths.drain(..) {
        let _ = std::fs::remove_file(p);
    }
}

fn interrupted() -> io::Error {
    io::Error::new(
        io::ErrorKind::Interrupted,
        "output abandoned: the process is being interrupted",
    )
}

/// An I/O error about the output `shown` (its path as messages show it, [`shown`]). tempfile's
/// errors name the temporary file (`… at path "dir/.inbetween-XXXX.tmp"`); only their cause is
/// kept.
fn named(shown: &str, what: &str, e: io::Error) -> Error {
    let message = e.to_string();
    let cause = without_temp_path(&message);
    Error::Io(io::Error::new(
        e.kind(),
        format!("{shown}: {what}: {cause}"),
    ))
}

/// `path` as messages show it: after the caller's `label` (the command line's `-o `; empty for
/// a caller whose message says which path it is).
fn shown(label: &str, path: &Path) -> String {
    format!("{label}{}", path.display())
}

/// An error's text without the ` at path "dir/.inbetween-XXXX.tmp"` tempfile appends: the
/// message names the output, never its temporary file.
fn without_temp_path(message: &str) -> &str {
    match message.rsplit_once(" at path \"") {
        Some((cause, _)) => cause,
        None => message,
    }
}

/// Follows a chain of symbolic links to the path it ends at (which may not exist). Relative
/// links are relative to the link's directory; the kernel resolves any `..` when the result is
/// used.
fn resolve_links(path: &Path, label: &str) -> Result<PathBuf, Error> {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = std::fs::read_link(&p)
                    .map_err(|e| named(&shown(label, path), "cannot read the symbolic link", e))?;
                p = match p.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(input_err!(
        "{}: expected a file, found a loop of symbolic links",
        shown(label, path)
    )
    .into())
}

/// An error while writing the output `shown` ([`shown`]), naming it (not the temporary file)
/// and keeping the error's kind. An error that already names it, or is an interruption, passes
/// unchanged.
fn write_error(shown: &str, e: io::Error) -> io::Error {
    if e.kind() == io::ErrorKind::Interrupted || e.to_string().starts_with(&format!("{shown}: ")) {
        return e;
    }
    // The OS's words without the temporary file's name that tempfile adds.
    let why = e.raw_os_error().map_or_else(
        || without_temp_path(&e.to_string()).to_string(),
        |n| io::Error::from_raw_os_error(n).to_string(),
    );
    io::Error::new(e.kind(), format!("{shown}: cannot write: {why}"))
}

/// The directory `path` would be created in.
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// [`Output::open`] for a command's `-o PATH` (`None` or `-`: standard output), refusing the
/// files the command reads (`reads`); messages say `-o PATH`.
pub fn open_output(path: Option<&Path>, reads: &[PathBuf]) -> Result<Output, Error> {
    Output::open(path, reads, "-o ")
}

impl Output {
    /// Standard output (`None` or `-`), else the destination for `path` (see the [module
    /// documentation](self)). A directory, a socket, a loop of symbolic links, a missing
    /// directory, or one of the files the command reads (`reads`, [`files_read`]: writing it would
    /// destroy the input) is an [`Error::Input`] naming `path`; failing to create or open the file
    /// is an [`Error::Io`] naming it.
    ///
    /// Messages show the path after `label`: the command line passes `"-o "` (`-o out: expected
    /// a file, found a directory`), a caller whose message names the argument itself `""`.
    pub fn open(path: Option<&Path>, reads: &[PathBuf], label: &str) -> Result<Output, Error> {
        let stdout = || Output(Dest::Stdout(BufWriter::with_capacity(BUF, io::stdout())));
        let p = match path {
            Some(p) if p.as_os_str() != "-" => p,
            _ => return Ok(stdout()),
        };
        // Standard output by its device names is standard output itself: written through the
        // descriptor the shell set up, so `>> log` appends and a pipe works (following the link
        // would replace the file it points to, or find no file for a pipe).
        if ["/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"]
            .iter()
            .any(|n| p.as_os_str() == *n)
        {
            return Ok(stdout());
        }
        // Any other open descriptor (`/dev/stderr`, `/dev/fd/N`): opened and written in place.
        if p.as_os_str() == "/dev/stderr"
            || p.starts_with("/dev/fd")
            || p.starts_with("/proc/self/fd")
        {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(p)
                .map_err(|e| named(&shown(label, p), "cannot open", e))?;
            return Ok(Output(Dest::Direct(
                BufWriter::with_capacity(BUF, file),
                shown(label, p),
            )));
        }
        // `out/` names a directory, existing or not.
        if p.as_os_str().as_encoded_bytes().ends_with(b"/") && !p.is_dir() {
            return Err(input_err!(
                "{}: expected a file, found a directory name (ending in /)",
                shown(label, p)
            )
            .into());
        }
        let target = resolve_links(p, label)?;
        let user = shown(label, p);
        if let Some(input) = protected(&target, reads) {
            return Err(input_err!(
                "{}: expected a new file, found {}, which the command reads (writing it would \
                 destroy the input)",
                user,
                input.display()
            )
            .into());
        }
        let existing = match std::fs::symlink_metadata(&target) {
            Ok(meta) => Some(meta),
            Err(e) => {
                let dir = parent_dir(&target);
                match std::fs::metadata(dir) {
                    // A file or a loop of links somewhere in the directory's own path.
                    Err(d) if d.raw_os_error() == Some(20) => {
                        return Err(
                            input_err!("{}: {} is not a directory", user, dir.display()).into()
                        );
                    }
                    Err(d) if d.raw_os_error() == Some(40) => {
                        return Err(input_err!(
                            "{}: {} is a loop of symbolic links",
                            user,
                            dir.display()
                        )
                        .into());
                    }
                    Err(d) if d.kind() == io::ErrorKind::NotFound => {
                        return Err(input_err!(
                            "{}: directory {} does not exist",
                            user,
                            dir.display()
                        )
                        .into());
                    }
                    Ok(m) if !m.is_dir() => {
                        return Err(
                            input_err!("{}: {} is not a directory", user, dir.display()).into()
                        );
                    }
                    _ => {}
                }
                if e.kind() != io::ErrorKind::NotFound {
                    return Err(named(&user, "cannot write", e));
                }
                None
            }
        };
        if let Some(meta) = &existing {
            let kind = meta.file_type();
            if kind.is_dir() {
                return Err(input_err!("{user}: expected a file, found a directory").into());
            }
            #[cfg(unix)]
            {
                use std::os::unix::fs::FileTypeExt;
                if kind.is_socket() {
                    return Err(input_err!("{user}: expected a file, found a socket").into());
                }
            }
            if !kind.is_file() {
                // A device or a FIFO: written in place. Opening a FIFO waits for its reader.
                let file = std::fs::OpenOptions::new()
                    .write(true)
                    .open(&target)
                    .map_err(|e| named(&user, "cannot open", e))?;
                return Ok(Output(Dest::Direct(
                    BufWriter::with_capacity(BUF, file),
                    user,
                )));
            }
        }
        let dir = parent_dir(&target);
        let mut builder = tempfile::Builder::new();
        builder.prefix(".inbetween-").suffix(".tmp");
        // tempfile creates 0600 files; an output file should get what any program's output gets
        // (0666 less the umask), or keep the mode of the file it replaces.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o666));
        }
        // Created and registered under the lock, so that a signal finds every temporary file.
        let tmp = {
            let mut reg = registry();
            if reg.closed {
                return Err(named(&user, "cannot write", interrupted()));
            }
            let tmp = builder
                .tempfile_in(dir)
                .map_err(|e| named(&user, "cannot create a temporary file", e))?;
            reg.paths.push(tmp.path().to_path_buf());
            tmp
        };
        let registered = Registered(Some(tmp.path().to_path_buf()));
        if let Some(meta) = existing {
            tmp.as_file()
                .set_permissions(meta.permissions())
                .map_err(|e| named(&user, "cannot set the mode", e))?;
        }
        Ok(Output(Dest::Temp(TempOutput {
            writer: BufWriter::with_capacity(BUF, tmp),
            registered,
            shown: shown(label, &target),
            target,
        })))
    }

    /// Flushes and, for a temporary file, renames it over the target.
    pub fn commit(self) -> io::Result<()> {
        match self.0 {
            Dest::Stdout(mut w) => w.flush(),
            Dest::Direct(mut w, shown) => w.flush().map_err(|e| write_error(&shown, e)),
            Dest::Temp(TempOutput {
                writer,
                mut registered,
                target,
                shown,
            }) => {
                let tmp = writer
                    .into_inner()
                    .map_err(|e| write_error(&shown, e.into_error()))?;
                tmp.as_file().sync_all().ok();
                // Under the lock: a signal arriving now waits, then finds the target replaced
                // whole (or, if the rename failed, the temporary file already removed).
                let mut reg = registry();
                if reg.closed {
                    registered.release(&mut reg);
                    return Err(interrupted());
                }
                let renamed = tmp
                    .persist(&target)
                    .map(drop)
                    .map_err(|e| write_error(&shown, e.error));
                registered.release(&mut reg);
                if HOLD.with(Cell::get) {
                    HELD.with(|h| *h.borrow_mut() = Some(reg));
                }
                renamed
            }
        }
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.0 {
            Dest::Stdout(w) => w.write(buf),
            Dest::Temp(t) => t.writer.write(buf).map_err(|e| write_error(&t.shown, e)),
            Dest::Direct(w, shown) => w.write(buf).map_err(|e| write_error(shown, e)),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        match &mut self.0 {
            Dest::Stdout(w) => w.write_all(buf),
            Dest::Temp(t) => t
                .writer
                .write_all(buf)
                .map_err(|e| write_error(&t.shown, e)),
            Dest::Direct(w, shown) => w.write_all(buf).map_err(|e| write_error(shown, e)),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match &mut self.0 {
            Dest::Stdout(w) => w.flush(),
            Dest::Temp(t) => t.writer.flush().map_err(|e| write_error(&t.shown, e)),
            Dest::Direct(w, shown) => w.flush().map_err(|e| write_error(shown, e)),
        }
    }
}

/// Bytes handed to a second thread that writes them, so that the system calls (the kernel's copy
/// into the file or pipe) overlap the computation. Chunks of 1 MiB go through a channel bounded
/// to four chunks (recycled), so memory stays flat. [`WriteBehind::finish`] returns the destination for
/// [`Output::commit`]; a write error (a closed pipe included) is reported by the next write or
/// by `finish`.
pub struct WriteBehind {
    buf: Vec<u8>,
    chunks: Option<std::sync::mpsc::SyncSender<Vec<u8>>>,
    /// Written chunks come back for reuse (a fresh 1 MiB buffer page-faults on first use).
    empty: std::sync::mpsc::Receiver<Vec<u8>>,
    thread: Option<std::thread::JoinHandle<(Output, io::Result<()>)>>,
}

const CHUNK: usize = 1 << 20;

impl WriteBehind {
    /// Starts the writing thread for `out`.
    pub fn new(mut out: Output) -> WriteBehind {
        let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<u8>>(4);
        let (back, empty) = std::sync::mpsc::channel::<Vec<u8>>();
        let thread = std::thread::spawn(move || {
            for mut chunk in rx {
                if let Err(e) = out.write_all(&chunk) {
                    return (out, Err(e));
                }
                chunk.clear();
                let _ = back.send(chunk);
            }
            (out, Ok(()))
        });
        WriteBehind {
            buf: Vec::with_capacity(CHUNK),
            chunks: Some(tx),
            empty,
            thread: Some(thread),
        }
    }

    /// Ends the thread and returns its error, if it stopped on one.
    fn join(&mut self) -> io::Result<Output> {
        self.chunks = None;
        let thread = self
            .thread
            .take()
            .ok_or_else(|| io::Error::other("output thread already finished"))?;
        let (out, result) = thread
            .join()
            .map_err(|_| io::Error::other("the output thread panicked"))?;
        result.map(|()| out)
    }

    fn send(&mut self) -> io::Result<()> {
        let next = self
            .empty
            .try_recv()
            .unwrap_or_else(|_| Vec::with_capacity(CHUNK));
        let chunk = std::mem::replace(&mut self.buf, next);
        let sent = match &self.chunks {
            Some(tx) => tx.send(chunk).is_ok(),
            None => false,
        };
        if sent {
            Ok(())
        } else {
            // The thread stopped on an error: report it.
            self.join()
                .and(Err(io::Error::other("output thread stopped")))
        }
    }

    /// Writes what is left and returns the destination, ready for [`Output::commit`].
    pub fn finish(mut self) -> io::Result<Output> {
        if !self.buf.is_empty() {
            self.send()?;
        }
        self.join()
    }
}

impl Write for WriteBehind {
    fn write(&mut self, data: &[u8]) -> io::Result<usize> {
        self.write_all(data)?;
        Ok(data.len())
    }

    /// Large `data` (a whole npz array) goes on in pieces of at most a chunk, never copied whole.
    fn write_all(&mut self, mut data: &[u8]) -> io::Result<()> {
        while !data.is_empty() {
            let n = data.len().min(CHUNK.saturating_sub(self.buf.len()).max(1));
            self.buf.extend_from_slice(&data[..n]);
            data = &data[n..];
            if self.buf.len() >= CHUNK {
                self.send()?;
            }
        }
        Ok(())
    }

    /// Only hands over the bytes so far; the thread writes them in order.
    fn flush(&mut self) -> io::Result<()> {
        if !self.buf.is_empty() {
            self.send()?;
        }
        Ok(())
    }
}

impl Drop for WriteBehind {
    fn drop(&mut self) {
        self.chunks = None;
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A full disk while writing names the output, not the temporary file tempfile reports.
    #[test]
    fn write_errors_name_the_output_not_the_temporary_file() {
        let e = io::Error::new(
            io::ErrorKind::StorageFull,
            "No space left on device (os error 28) at path \"/d/.inbetween-Ab12.tmp\"",
        );
        let w = write_error("-o /d/out.json", e);
        assert_eq!(
            w.to_string(),
            "-o /d/out.json: cannot write: No space left on device (os error 28)"
        );
        assert_eq!(w.kind(), io::ErrorKind::StorageFull);
    }
}
