//! Several inputs at once (docs/spec.md §1, *Batch*): `interp`, `convert` or `reduce` over files,
//! folders and glob patterns, each output written atomically under `--out-dir`, `--jobs` inputs
//! in parallel, a JSON Lines manifest appended as each finishes, inputs whose output is newer
//! skipped unless `--refresh`. A failed input never stops the others.

use crate::cli::BatchArgs;
use inbetween::{Error, InputError};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The extensions of the input formats (a folder's other files are failed inputs).
pub const INPUT_EXTENSIONS: [&str; 7] = ["csv", "json", "bvh", "gltf", "glb", "fbx", "usda"];

/// What one input came to, for its manifest line: set by the command run on it ([`note`]).
#[derive(Debug, Clone, Default)]
pub struct Stats {
    /// Frames: written (`interp`, all tracks together) or read (`reduce`).
    pub frames: Option<u64>,
    /// Tracks.
    pub tracks: Option<usize>,
    /// Keys: kept (`reduce`) or written (`convert`), all tracks together.
    pub keys: Option<usize>,
    /// `reduce`: the largest error of any track, in `--angles` units (with `--distance`, a
    /// length).
    pub largest_error: Option<f64>,
}

std::thread_local! {
    static STATS: std::cell::RefCell<Option<Stats>> = const { std::cell::RefCell::new(None) };
}

/// Records figures of the input being processed on this thread, when a batch runs it (else
/// nothing).
pub fn note(f: impl FnOnce(&mut Stats)) {
    STATS.with(|s| {
        if let Some(stats) = s.borrow_mut().as_mut() {
            f(stats)
        }
    });
}

/// The command on one input: `(input, output, warn)`.
pub type OneInput<'a> = dyn Fn(&Path, &Path, &mut dyn FnMut(&str)) -> Result<(), Error> + Sync + 'a;

/// One input of a batch: its path and its path relative to where it was found.
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    /// The input file.
    pub input: PathBuf,
    /// Where it was found from: its path below the folder or the pattern's fixed part.
    pub relative: PathBuf,
}

/// What finished inputs came to.
#[derive(Debug, Default)]
struct Tally {
    ok: usize,
    skipped: usize,
    refused: usize,
    internal: usize,
}

/// Runs `one(input, output, warn)` for every input of `first` and `batch.more` (see the module
/// documentation). `ext` gives an input's output extension. Exit: `Ok` when every input
/// succeeded or was skipped; an input error when one was refused; an internal error (exit 1)
/// when one failed otherwise.
pub fn run(
    first: Option<&Path>,
    batch: &BatchArgs,
    ext: &(dyn Fn(&Path) -> Result<String, Error> + Sync),
    one: &OneInput<'_>,
) -> Result<(), Error> {
    let Some(out_dir) = batch.out_dir.as_deref() else {
        return Err(InputError::new(
            "several inputs: give --out-dir DIR for their outputs (-o names one output)",
        )
        .into());
    };
    let mut patterns: Vec<&Path> = first.into_iter().collect();
    patterns.extend(batch.more.iter().map(PathBuf::as_path));
    if patterns.iter().any(|p| p.as_os_str() == "-") {
        return Err(InputError::new(
            "--out-dir: standard input (-) cannot be one of several inputs",
        )
        .into());
    }
    let jobs = expand(&patterns)?;
    let threads = batch
        .jobs
        .map(|n| n as usize)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .min(jobs.len().max(1));
    let manifest = match &batch.manifest {
        Some(path) => Some(Mutex::new(
            std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(path)
                .map_err(|e| InputError::new(format!("--manifest {}: {e}", path.display())))?,
        )),
        None => None,
    };
    // The largest files first, so that the threads end together (the longest-first rule); the
    // outputs do not depend on the order.
    let mut order: Vec<(u64, usize)> = jobs
        .iter()
        .enumerate()
        .map(|(i, j)| (std::fs::metadata(&j.input).map_or(0, |m| m.len()), i))
        .collect();
    order.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    // A progress bar on a terminal (files done of all, elapsed, rate); nothing otherwise.
    let bar = if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        let style = indicatif::ProgressStyle::with_template(
            "{bar:30} {pos}/{len} files, {elapsed_precise}, {per_sec}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
        indicatif::ProgressBar::new(jobs.len() as u64).with_style(style)
    } else {
        indicatif::ProgressBar::hidden()
    };
    let tally = Mutex::new(Tally::default());
    let next = AtomicUsize::new(0);
    let started = Instant::now();
    let work = || {
        crate::output::hold_commits();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(job) = order.get(i).map(|&(_, k)| &jobs[k]) else {
                break;
            };
            let t0 = Instant::now();
            let mut warnings: Vec<String> = Vec::new();
            let known = job
                .input
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| INPUT_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()));
            let format = if known {
                ext(&job.input)
            } else {
                Err(InputError::new(format!(
                    "{}: not an input format: a batch knows its inputs by their extension (.csv, \
                     .json, .bvh, .gltf, .glb, .fbx, .usda)",
                    job.input.display()
                ))
                .into())
            };
            let (status, output, error) = match format {
                Err(e) => ("failed", None, Some(e)),
                Ok(ext) => {
                    let output = out_dir.join(&job.relative).with_extension(ext);
                    if !batch.refresh && newer(&output, &job.input) {
                        ("skipped", Some(output), None)
                    } else {
                        let made = output
                            .parent()
                            .map_or(Ok(()), std::fs::create_dir_all)
                            .map_err(|e| {
                                Error::Input(InputError::new(format!(
                                    "--out-dir: cannot make the folder of {}: {e}",
                                    output.display()
                                )))
                            });
                        STATS.with(|s| *s.borrow_mut() = Some(Stats::default()));
                        let result = made.and_then(|()| {
                            inbetween::parallel::serially(|| {
                                one(&job.input, &output, &mut |w: &str| {
                                    warnings.push(w.to_string())
                                })
                            })
                        });
                        match result {
                            Ok(()) => ("ok", Some(output), None),
                            Err(e) => ("failed", Some(output), Some(e)),
                        }
                    }
                }
            };
            let seconds = t0.elapsed().as_secs_f64();
            let message = error.as_ref().map(crate::flags::error_text);
            bar.suspend(|| {
                for w in &warnings {
                    eprintln!("inbetween: warning: {w}");
                }
                if let Some(m) = &message {
                    eprintln!("inbetween: error: {m}");
                }
            });
            let mut record = serde_json::json!({
                "input": job.input.display().to_string(),
                "output": output.as_ref().map(|o| o.display().to_string()),
                "status": status,
                "seconds": (seconds * 1e3).round() / 1e3,
            });
            let stats = STATS
                .with(|s| s.borrow_mut().take())
                .filter(|_| error.is_none());
            if let Some(st) = stats {
                let mut put = |k: &str, v: Option<serde_json::Value>| {
                    if let Some(v) = v {
                        record[k] = v;
                    }
                };
                put("frames", st.frames.map(Into::into));
                put("tracks", st.tracks.map(Into::into));
                put("keys", st.keys.map(Into::into));
                put("largest_error", st.largest_error.map(Into::into));
            }
            if let Some(m) = message {
                record["error"] = serde_json::Value::from(m);
            }
            if let Some(f) = &manifest {
                // The line whole, in one write, under the lock a signal waits for.
                crate::output::hold_now();
                let mut f = f.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                let _ = f.write_all(format!("{record}\n").as_bytes());
                let _ = f.flush();
            }
            // The output and its line are both written: a signal may end the process now.
            crate::output::release_commit();
            bar.inc(1);
            let mut t = tally
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            match (&error, status) {
                (None, "skipped") => t.skipped += 1,
                (None, _) => t.ok += 1,
                (Some(Error::Input(_)), _) => t.refused += 1,
                (Some(_), _) => t.internal += 1,
            }
        }
    };
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(work);
        }
    });
    bar.finish_and_clear();
    let t = tally
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let failed = t.refused + t.internal;
    eprintln!(
        "inbetween: {} inputs: {} ok, {} skipped, {failed} failed ({:.2} s, {threads} jobs)",
        jobs.len(),
        t.ok,
        t.skipped,
        started.elapsed().as_secs_f64()
    );
    if t.internal > 0 {
        Err(Error::Internal(format!(
            "internal error: {} of {} inputs failed",
            t.internal,
            jobs.len()
        )))
    } else if t.refused > 0 {
        Err(InputError::new(format!(
            "{} of {} inputs were refused",
            t.refused,
            jobs.len()
        ))
        .into())
    } else {
        Ok(())
    }
}

/// Whether the command line asks for a batch: `--out-dir`, several inputs, or an option only a
/// batch has (which [`run`] then refuses without `--out-dir`).
pub fn wanted(batch: &BatchArgs) -> bool {
    batch.out_dir.is_some()
        || !batch.more.is_empty()
        || batch.jobs.is_some()
        || batch.manifest.is_some()
        || batch.refresh
}

/// The extension of an input's output: `--output-format`'s, else what the command writes for
/// that input without `-o` — `interp` the input's own format (FBX, which is not written: JSON),
/// `convert` and `reduce` keys as JSON for a BVH, FBX or USD input (`reduce` of glTF: glTF), a
/// keys document's own format otherwise.
pub fn extension(
    input: &Path,
    output: &crate::cli::OutputArgs,
    keys: bool,
) -> Result<String, Error> {
    use inbetween_io::gltf::ContainerFormat;
    use inbetween_io::{Format, OutputFormat};
    let ext = match output.output_format {
        Some(OutputFormat::Doc(Format::Csv)) => "csv",
        Some(OutputFormat::Doc(_)) => "json",
        Some(OutputFormat::Npy) => "npy",
        Some(OutputFormat::Npz) => "npz",
        Some(OutputFormat::Bvh) => "bvh",
        Some(OutputFormat::Gltf(ContainerFormat::Gltf)) => "gltf",
        Some(OutputFormat::Gltf(ContainerFormat::Glb)) => "glb",
        Some(OutputFormat::Usda) => "usda",
        None => {
            let own = input
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase)
                .unwrap_or_default();
            return Ok(match own.as_str() {
                "fbx" | "" => "json".into(),
                "bvh" | "usda" if keys => "json".into(),
                _ => own,
            });
        }
    };
    Ok(ext.into())
}

/// Whether `output` exists and was modified after `input`.
fn newer(output: &Path, input: &Path) -> bool {
    let time = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    matches!((time(output), time(input)), (Some(o), Some(i)) if o > i)
}

/// The inputs of `patterns`, in order: a file as itself (relative path: its name), a folder's
/// files recursively in name order (relative to the folder; hidden ones left out), a pattern
/// with `*`, `?` or `[` the files below its fixed leading folders that match it (relative to
/// them). A file found twice is processed once. Errors: a path that does not exist, a pattern
/// that matches nothing, no inputs at all.
pub fn expand(patterns: &[&Path]) -> Result<Vec<Job>, Error> {
    let mut jobs: Vec<Job> = Vec::new();
    for &p in patterns {
        let text = p.to_string_lossy();
        let found = if text.contains(['*', '?', '[']) {
            let (base, rest) = fixed_prefix(p);
            let mut files = Vec::new();
            if base.is_dir() {
                walk(&base, &mut files)?;
            }
            let rest = rest.to_string_lossy().replace('\\', "/");
            let matched: Vec<Job> = files
                .into_iter()
                .filter_map(|f| {
                    let rel = f.strip_prefix(&base).ok()?.to_path_buf();
                    path_glob(&rest, &rel.to_string_lossy()).then_some(Job {
                        input: f,
                        relative: rel,
                    })
                })
                .collect();
            if matched.is_empty() {
                return Err(
                    InputError::new(format!("{text}: no file matches this pattern")).into(),
                );
            }
            matched
        } else if p.is_dir() {
            let mut files = Vec::new();
            walk(p, &mut files)?;
            files
                .into_iter()
                .map(|f| Job {
                    relative: f.strip_prefix(p).unwrap_or(&f).to_path_buf(),
                    input: f,
                })
                .collect()
        } else if p.exists() {
            vec![Job {
                input: p.to_path_buf(),
                relative: PathBuf::from(p.file_name().unwrap_or(p.as_os_str())),
            }]
        } else {
            return Err(InputError::new(format!("{text}: no such file or folder")).into());
        };
        for j in found {
            if !jobs.iter().any(|k| k.input == j.input) {
                jobs.push(j);
            }
        }
    }
    if jobs.is_empty() {
        return Err(InputError::new(
            "no input files (folders are searched for .csv, .json, .bvh, .gltf, .glb, .fbx, .usda)",
        )
        .into());
    }
    Ok(jobs)
}

/// The leading components of a pattern without glob characters, and the rest.
fn fixed_prefix(p: &Path) -> (PathBuf, PathBuf) {
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

/// Every file below `dir` but hidden ones (names starting with `.`), sorted by path.
fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), Error> {
    let entries = std::fs::read_dir(dir)
        .map_err(|e| InputError::new(format!("{}: cannot read the folder: {e}", dir.display())))?;
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for p in paths {
        let hidden = p
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with('.'));
        if hidden {
            continue;
        }
        if p.is_dir() {
            walk(&p, out)?;
        } else {
            out.push(p);
        }
    }
    Ok(())
}

/// A relative path against a pattern of `/`-separated parts: `**` any number of folders, else
/// each part a glob of `*` and `?` for one component.
fn path_glob(pattern: &str, path: &str) -> bool {
    let pat: Vec<&str> = pattern.split('/').filter(|s| !s.is_empty()).collect();
    let parts: Vec<&str> = path.split(['/', '\\']).filter(|s| !s.is_empty()).collect();
    fn go(pat: &[&str], parts: &[&str]) -> bool {
        match pat.split_first() {
            None => parts.is_empty(),
            Some((&"**", rest)) => (0..=parts.len()).any(|k| go(rest, &parts[k..])),
            Some((p, rest)) => parts
                .split_first()
                .is_some_and(|(first, more)| super::settings::glob(p, first) && go(rest, more)),
        }
    }
    go(&pat, &parts)
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
}
