//! Where output goes: standard output, or a file written atomically (a temporary file in the
//! target's directory, renamed over the target only when everything was written).

use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// An output destination. Call [`Output::commit`] after the last byte; dropping it uncommitted
/// leaves an existing target untouched and removes the temporary file.
pub enum Output {
    Stdout(BufWriter<io::Stdout>),
    File {
        writer: BufWriter<tempfile::NamedTempFile>,
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
