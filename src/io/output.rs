//! Where output goes: standard output, or a file written atomically (a temporary file in the
//! target's directory, renamed over the target only when everything was written).

use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// An output destination. Call [`Output::commit`] after the last byte; dropping it uncommitted
/// leaves an existing target untouched and removes the temporary file.
pub enum Output {
    /// Standard output, buffered.
    Stdout(BufWriter<io::Stdout>),
    /// A temporary file beside `target`, renamed over it by [`Output::commit`].
    File {
        /// The temporary file.
        writer: BufWriter<tempfile::NamedTempFile>,
        /// The file the user named.
        target: PathBuf,
    },
}

const BUF: usize = 1 << 16;

impl Output {
    /// Standard output (`None` or `-`), or a temporary file beside `path`.
    pub fn open(path: Option<&Path>) -> io::Result<Output> {
        match path {
            None => Ok(Output::Stdout(BufWriter::with_capacity(BUF, io::stdout()))),
            Some(p) if p.as_os_str() == "-" => {
                Ok(Output::Stdout(BufWriter::with_capacity(BUF, io::stdout())))
            }
            Some(p) => {
                let dir = match p.parent() {
                    Some(d) if !d.as_os_str().is_empty() => d,
                    _ => Path::new("."),
                };
                let mut builder = tempfile::Builder::new();
                builder.prefix(".inbetween-").suffix(".tmp");
                // tempfile creates 0600 files; an output file should get what any program's
                // output gets (0666 less the umask), or keep the mode of the file it replaces.
                #[cfg(unix)]
                {
                    use std::os::unix::fs::PermissionsExt;
                    builder.permissions(std::fs::Permissions::from_mode(0o666));
                }
                let tmp = builder.tempfile_in(dir)?;
                if let Ok(meta) = std::fs::metadata(p) {
                    tmp.as_file().set_permissions(meta.permissions())?;
                }
                Ok(Output::File {
                    writer: BufWriter::with_capacity(BUF, tmp),
                    target: p.to_path_buf(),
                })
            }
        }
    }

    /// Flushes and, for a file, renames the temporary file over the target.
    pub fn commit(self) -> io::Result<()> {
        match self {
            Output::Stdout(mut w) => w.flush(),
            Output::File { writer, target } => {
                let tmp = writer.into_inner().map_err(|e| e.into_error())?;
                tmp.as_file().sync_all().ok();
                tmp.persist(&target).map_err(|e| e.error)?;
                Ok(())
            }
        }
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Output::Stdout(w) => w.write(buf),
            Output::File { writer, .. } => writer.write(buf),
        }
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        match self {
            Output::Stdout(w) => w.write_all(buf),
            Output::File { writer, .. } => writer.write_all(buf),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self {
            Output::Stdout(w) => w.flush(),
            Output::File { writer, .. } => writer.flush(),
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

    fn write_all(&mut self, data: &[u8]) -> io::Result<()> {
        self.buf.extend_from_slice(data);
        if self.buf.len() >= CHUNK {
            self.send()?;
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
