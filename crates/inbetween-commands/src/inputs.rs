//! The inputs of a batch (docs/spec.md §1, *Batch*, *What a batch reads*): files, folders and
//! glob patterns expanded to regular files, without leaving the folders the user named.
//!
//! - A folder is walked in name order, hidden entries (`.name`) left out. Its real files and
//!   folders come first; then its symbolic links, each followed at most once per target, and
//!   only when the target lies inside the named folder (as ripgrep, fd and find: a link out of
//!   the folder is not followed unless `--follow`). A folder already walked is not walked again
//!   (two links to `.` cannot make the walk endless), and a file found twice (a link and its
//!   target, a file named twice) is one input, found by its own name where it has one.
//! - FIFOs, sockets and devices are never opened: they are passed over with a reason, as are
//!   links that are broken or lead out of the folder.
//! - The folders and files in `exclude` (the output folder, the manifest) are not inputs.
//!
//! Every step is linear in the entries found (hash sets of file identities, no pairwise
//! comparison).

use crate::shown::shown;
use inbetween::{Error, InputError};
use std::collections::{HashMap, HashSet, VecDeque};
use std::fs::Metadata;
use std::path::{Path, PathBuf};

/// One input of a batch: its path and its path relative to where it was found.
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    /// The input file.
    pub input: PathBuf,
    /// Where it was found from: its path below the folder or the pattern's fixed part.
    pub relative: PathBuf,
}

/// An entry that is not read: why.
#[derive(Debug, Clone, PartialEq)]
pub struct Passed {
    /// The entry as found.
    pub path: PathBuf,
    /// Why it is passed over.
    pub reason: String,
}

/// What a batch's paths came to.
#[derive(Debug, Default)]
pub struct Found {
    /// The files to read, in the order found.
    pub jobs: Vec<Job>,
    /// Entries passed over (never opened), with their reason.
    pub passed: Vec<Passed>,
}

/// How paths are expanded.
#[derive(Debug, Default)]
pub struct Rules {
    /// Follow symbolic links out of the named folders.
    pub follow: bool,
    /// How the front end names that choice, for the reason a link out is passed over (the
    /// command line's `--follow`).
    pub follow_named: &'static str,
    /// Folders and files that are not inputs (the output folder, the manifest), if they exist.
    pub exclude: Vec<PathBuf>,
}

/// A file's identity: the same file under two names (links) is one input.
#[cfg(unix)]
type FileId = (u64, u64);
#[cfg(not(unix))]
type FileId = PathBuf;

#[cfg(unix)]
fn file_id(meta: &Metadata, _path: &Path) -> FileId {
    use std::os::unix::fs::MetadataExt;
    (meta.dev(), meta.ino())
}

#[cfg(not(unix))]
fn file_id(_meta: &Metadata, path: &Path) -> FileId {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

/// What kind of thing a non-regular, non-folder entry is, for its reason.
fn kind_of(meta: &Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        } else if t.is_socket() {
            return "a socket";
        } else if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
    }
    let _ = meta;
    "not a regular file"
}

/// The expansion's state: identities seen, so that nothing is read or walked twice.
struct Expander<'r> {
    rules: &'r Rules,
    excluded: HashSet<FileId>,
    dirs: HashSet<FileId>,
    files: HashSet<FileId>,
    found: Found,
}

/// A symbolic link met in a walk, followed after the folder's real entries.
struct Link {
    path: PathBuf,
    relative: PathBuf,
}

impl Expander<'_> {
    fn pass(&mut self, path: &Path, reason: impl Into<String>) {
        self.found.passed.push(Passed {
            path: path.to_path_buf(),
            reason: reason.into(),
        });
    }

    /// A regular file found at `path` (`relative` below its root), unless already an input.
    fn file(&mut self, path: &Path, relative: PathBuf, meta: &Metadata) {
        let id = file_id(meta, path);
        if self.excluded.contains(&id) || !self.files.insert(id) {
            return;
        }
        self.found.jobs.push(Job {
            input: path.to_path_buf(),
            relative,
        });
    }

    /// Walks the folder `root` (its real entries, then its links as the module says), adding
    /// the files whose relative path `keep` accepts.
    fn walk(&mut self, root: &Path, keep: &dyn Fn(&Path) -> bool) -> Result<(), Error> {
        let canonical = std::fs::canonicalize(root).map_err(|e| unreadable(root, e))?;
        let meta = std::fs::metadata(root).map_err(|e| unreadable(root, e))?;
        // A named folder is walked even when it is the output folder (whose outputs the
        // collision check then weighs against its inputs); only folders below it are left out.
        if !self.dirs.insert(file_id(&meta, root)) {
            return Ok(());
        }
        let mut links: VecDeque<Link> = VecDeque::new();
        self.walk_real(root, PathBuf::new(), keep, &mut links)?;
        while let Some(link) = links.pop_front() {
            let target = match std::fs::canonicalize(&link.path) {
                Ok(t) => t,
                Err(_) => {
                    if keep(&link.relative) {
                        self.pass(&link.path, "a broken symbolic link");
                    }
                    continue;
                }
            };
            if !self.rules.follow && !target.starts_with(&canonical) {
                if keep(&link.relative) {
                    let reason = format!(
                        "a symbolic link out of the folder, not followed ({} follows it)",
                        self.rules.follow_named
                    );
                    self.pass(&link.path, reason);
                }
                continue;
            }
            let Ok(meta) = std::fs::metadata(&link.path) else {
                continue;
            };
            if self.place(&link.path, &link.relative, &meta, keep) {
                self.walk_real(&link.path, link.relative, keep, &mut links)?;
            }
        }
        Ok(())
    }

    /// Takes an entry that is not a link (or a link's target) at `path`: a file `keep` accepts
    /// is an input, anything else but a folder is passed over; true for a folder to walk (one
    /// neither excluded nor walked before).
    fn place(
        &mut self,
        path: &Path,
        relative: &Path,
        meta: &Metadata,
        keep: &dyn Fn(&Path) -> bool,
    ) -> bool {
        if meta.is_dir() {
            let id = file_id(meta, path);
            return !self.excluded.contains(&id) && self.dirs.insert(id);
        }
        if !keep(relative) {
        } else if meta.is_file() {
            self.file(path, relative.to_path_buf(), meta);
        } else {
            let reason = format!("{} (never opened)", kind_of(meta));
            self.pass(path, reason);
        }
        false
    }

    /// The real (not linked) entries below `dir`, depth first in name order; links are queued.
    fn walk_real(
        &mut self,
        dir: &Path,
        relative: PathBuf,
        keep: &dyn Fn(&Path) -> bool,
        links: &mut VecDeque<Link>,
    ) -> Result<(), Error> {
        let mut stack: Vec<std::vec::IntoIter<(PathBuf, PathBuf)>> =
            vec![entries(dir, &relative)?.into_iter()];
        while let Some(top) = stack.last_mut() {
            let Some((path, rel)) = top.next() else {
                stack.pop();
                continue;
            };
            let Ok(meta) = std::fs::symlink_metadata(&path) else {
                continue;
            };
            if meta.file_type().is_symlink() {
                links.push_back(Link {
                    path,
                    relative: rel,
                });
            } else if self.place(&path, &rel, &meta, keep) {
                stack.push(entries(&path, &rel)?.into_iter());
            }
        }
        Ok(())
    }
}

/// The error for a folder that cannot be read.
fn unreadable(dir: &Path, e: std::io::Error) -> InputError {
    InputError::new(format!("{}: cannot read the folder: {e}", shown(dir)))
}

/// The entries of `dir` but hidden ones, in name order: (path, path relative to the walk's root).
fn entries(dir: &Path, relative: &Path) -> Result<Vec<(PathBuf, PathBuf)>, Error> {
    let read = std::fs::read_dir(dir).map_err(|e| unreadable(dir, e))?;
    let mut names: Vec<std::ffi::OsString> = read
        .filter_map(|e| e.ok().map(|e| e.file_name()))
        .filter(|n| !n.as_encoded_bytes().starts_with(b"."))
        .collect();
    names.sort();
    Ok(names
        .into_iter()
        .map(|n| (dir.join(&n), relative.join(&n)))
        .collect())
}

/// The inputs of `patterns`, in order: a file as itself (relative path: its name), a folder's
/// files recursively (see the module documentation), a pattern with `*`, `?` or `[` the files
/// below its fixed leading folders that match it (relative to them). A file found twice is one
/// input. Errors: a path that does not exist, a pattern that matches nothing, no inputs at all.
pub fn expand(patterns: &[&Path], rules: &Rules) -> Result<Found, Error> {
    let excluded = rules
        .exclude
        .iter()
        .filter_map(|p| std::fs::metadata(p).ok().map(|m| file_id(&m, p)))
        .collect();
    let mut ex = Expander {
        rules,
        excluded,
        dirs: HashSet::new(),
        files: HashSet::new(),
        found: Found::default(),
    };
    for &p in patterns {
        let text = p.to_string_lossy();
        if text.contains(['*', '?', '[']) {
            let (base, rest) = fixed_prefix(p);
            let rest = rest.to_string_lossy().replace('\\', "/");
            let before = (ex.found.jobs.len(), ex.found.passed.len());
            if base.is_dir() {
                // A pattern walks its base anew: the folders a folder argument walked do not
                // hide the files the pattern names.
                ex.dirs.clear();
                ex.walk(&base, &|rel| path_glob(&rest, &rel.to_string_lossy()))?;
            }
            if (ex.found.jobs.len(), ex.found.passed.len()) == before {
                return Err(
                    InputError::new(format!("{}: no file matches this pattern", shown(p))).into(),
                );
            }
        } else {
            match std::fs::metadata(p) {
                Ok(m) if m.is_dir() => {
                    ex.dirs.clear();
                    ex.walk(p, &|_| true)?;
                }
                Ok(m) if m.is_file() => {
                    let name = PathBuf::from(p.file_name().unwrap_or(p.as_os_str()));
                    ex.file(p, name, &m);
                }
                Ok(m) => {
                    let reason = format!("{} (never opened)", kind_of(&m));
                    ex.pass(p, reason);
                }
                Err(_) => {
                    return Err(
                        InputError::new(format!("{}: no such file or folder", shown(p))).into(),
                    );
                }
            }
        }
    }
    if ex.found.jobs.is_empty() && ex.found.passed.is_empty() {
        return Err(InputError::new(
            "no input files (folders are searched for .csv, .json, .bvh, .gltf, .glb, .fbx, .usda)",
        )
        .into());
    }
    Ok(ex.found)
}

/// The leading components of a pattern without glob characters, and the rest.
pub fn fixed_prefix(p: &Path) -> (PathBuf, PathBuf) {
    let mut base = PathBuf::new();
    let mut rest = PathBuf::new();
    let mut in_rest = false;
    for c in p.components() {
        let s = c.as_os_str().to_string_lossy();
        if !in_rest && !s.contains(['*', '?', '[']) {
            base.push(c);
        } else {
            in_rest = true;
            rest.push(c);
        }
    }
    if base.as_os_str().is_empty() {
        base.push(".");
    }
    (base, rest)
}

/// A relative path against a pattern of `/`-separated parts: `**` any number of folders, else
/// each part a glob of `*` and `?` for one component. Dynamic programming over (pattern part,
/// path part): linear in their product, however many `**` the pattern has.
pub fn path_glob(pattern: &str, path: &str) -> bool {
    let pat: Vec<&str> = pattern.split('/').filter(|s| !s.is_empty()).collect();
    let parts: Vec<&str> = path.split(['/', '\\']).filter(|s| !s.is_empty()).collect();
    // ok[j]: the pattern's parts so far match the path's first j parts.
    let mut ok = vec![false; parts.len() + 1];
    ok[0] = true;
    for p in &pat {
        let mut next = vec![false; parts.len() + 1];
        if *p == "**" {
            let mut any = false;
            for j in 0..=parts.len() {
                any |= ok[j];
                next[j] = any;
            }
        } else {
            for j in 0..parts.len() {
                next[j + 1] = ok[j] && crate::pattern::glob(p, parts[j]);
            }
        }
        ok = next;
    }
    ok[parts.len()]
}

/// The identity a write to `path` replaces: the canonical path of the file it names (through
/// links, as an output is written, `crate::output`), or, for a path that does not exist yet,
/// the canonical path of its nearest existing folder joined with the rest.
pub fn written_at(path: &Path) -> PathBuf {
    if let Ok(c) = std::fs::canonicalize(path) {
        return c;
    }
    let parts: Vec<std::path::Component> = path.components().collect();
    for k in (0..parts.len()).rev() {
        let head: PathBuf = parts[..k].iter().collect();
        let dir = if head.as_os_str().is_empty() {
            Path::new(".")
        } else {
            head.as_path()
        };
        if let Ok(mut c) = std::fs::canonicalize(dir) {
            // The rest does not exist yet: it is made as plain folders, so `..` is lexical.
            for part in &parts[k..] {
                match part {
                    std::path::Component::ParentDir => {
                        c.pop();
                    }
                    std::path::Component::CurDir => {}
                    other => c.push(other),
                }
            }
            return c;
        }
    }
    path.to_path_buf()
}

/// The files that `outputs` (each `(its input, the output)`) and `manifest` (its path and how
/// messages name it: the command line's `--manifest `) would write over, checked against
/// `inputs` and each other before anything is written: one line for each collision (an output
/// over an input, two inputs with one output, the manifest over either).
pub fn collisions(
    inputs: &[&Path],
    outputs: &[(&Path, &Path)],
    manifest: Option<(&Path, &str)>,
) -> Vec<String> {
    let input_at: HashMap<PathBuf, &Path> = inputs
        .iter()
        .map(|i| {
            (
                std::fs::canonicalize(i).unwrap_or_else(|_| i.to_path_buf()),
                *i,
            )
        })
        .collect();
    let mut output_at: HashMap<PathBuf, &Path> = HashMap::new();
    let mut lines = Vec::new();
    for &(input, output) in outputs {
        let at = written_at(output);
        if let Some(other) = input_at.get(&at) {
            lines.push(format!(
                "{}, the output of {}, would replace the input {}",
                shown(output),
                shown(input),
                shown(other)
            ));
        } else if let Some(first) = output_at.get(&at) {
            lines.push(format!(
                "{} would be the output of both {} and {}",
                shown(output),
                shown(first),
                shown(input)
            ));
        } else {
            output_at.insert(at, input);
        }
    }
    if let Some((m, named)) = manifest {
        let at = written_at(m);
        if let Some(input) = input_at.get(&at) {
            lines.push(format!("{named}{} is the input {}", shown(m), shown(input)));
        } else if let Some(input) = output_at.get(&at) {
            lines.push(format!(
                "{named}{} is the output of {}",
                shown(m),
                shown(input)
            ));
        }
    }
    lines
}

/// The skip rule of a batch and of Python's `process_file`: whether `output` is a regular file
/// (through links) modified after `input`, so that the input need not be done again. A folder,
/// device or FIFO at the output's path is never up to date: the command then refuses it.
pub fn up_to_date(output: &Path, input: &Path) -> bool {
    let time = |p: &Path, file: bool| {
        std::fs::metadata(p)
            .ok()
            .filter(|m| !file || m.is_file())
            .and_then(|m| m.modified().ok())
    };
    matches!((time(output, true), time(input, false)), (Some(o), Some(i)) if o > i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_globs() {
        assert!(path_glob("*.bvh", "a.bvh"));
        assert!(!path_glob("*.bvh", "sub/a.bvh"));
        assert!(path_glob("**/*.bvh", "sub/deeper/a.bvh"));
        assert!(path_glob("**/*.bvh", "a.bvh"));
        assert!(path_glob("sub/?.bvh", "sub/a.bvh"));
        assert!(!path_glob("sub/?.bvh", "sub/ab.bvh"));
        assert!(path_glob("a/**/b/**/c.bvh", "a/x/b/y/z/c.bvh"));
        assert!(!path_glob("a/**/b/**/c.bvh", "a/x/y/z/c.bvh"));
    }

    /// Many `**` against a deep path: a backtracking match takes exponential time here.
    #[test]
    fn path_globs_are_polynomial() {
        let pattern = vec!["**"; 40].join("/") + "/nomatch";
        let path = vec!["d"; 60].join("/");
        let t = std::time::Instant::now();
        assert!(!path_glob(&pattern, &path));
        assert!(t.elapsed().as_secs_f64() < 1.0);
    }

    /// A folder of 8n files is expanded in about 8x the time of n (a pairwise check of the
    /// files found, as before, took 32 s for 40 000 files).
    #[test]
    fn expansion_is_linear_in_the_files() {
        let dir = tempfile::tempdir().unwrap();
        let time = |n: usize| {
            let d = dir.path().join(format!("n{n}"));
            std::fs::create_dir_all(&d).unwrap();
            for i in 0..n {
                std::fs::write(d.join(format!("{i}.bvh")), "").unwrap();
            }
            (0..3)
                .map(|_| {
                    let t = std::time::Instant::now();
                    let found = expand(&[d.as_path()], &Rules::default()).unwrap();
                    assert_eq!(found.jobs.len(), n);
                    t.elapsed().as_secs_f64()
                })
                .fold(f64::INFINITY, f64::min)
        };
        let (small, large) = (time(1000), time(8000));
        assert!(
            large < 24.0 * small.max(1e-3),
            "1000 files {small} s, 8000 {large} s"
        );
    }

    #[test]
    fn fixed_prefixes() {
        let (b, r) = fixed_prefix(Path::new("clips/cmu/*.bvh"));
        assert_eq!(
            (b.as_path(), r.as_path()),
            (Path::new("clips/cmu"), Path::new("*.bvh"))
        );
        let (b, r) = fixed_prefix(Path::new("*/x.bvh"));
        assert_eq!(
            (b.as_path(), r.as_path()),
            (Path::new("."), Path::new("*/x.bvh"))
        );
    }

    #[test]
    fn a_path_not_yet_written_is_known_by_its_nearest_folder() {
        let dir = tempfile::tempdir().unwrap();
        let canonical = std::fs::canonicalize(dir.path()).unwrap();
        assert_eq!(
            written_at(&dir.path().join("new/deeper/x.json")),
            canonical.join("new/deeper/x.json")
        );
        std::fs::write(dir.path().join("a.json"), "{}").unwrap();
        assert_eq!(
            written_at(&dir.path().join("new/../a.json")),
            canonical.join("a.json")
        );
    }
}
