//! Several inputs at once (docs/spec.md §1, *Batch*): `interp`, `convert` or `reduce` over files,
//! folders and glob patterns, each output written atomically under `--out-dir`, `--jobs` inputs
//! in parallel, a JSON Lines manifest appended as each finishes, inputs whose output is newer
//! skipped unless `--refresh`. A failed input never stops the others.

use crate::args::BatchArgs;
use crate::record::{Record, Status};
use inbetween::{Error, InputError};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use crate::events::{Collected, Events};
use crate::inputs;
pub use crate::inputs::Job;
use crate::shown::shown;

/// The extensions of the input formats (a folder's other files are failed inputs).
pub const INPUT_EXTENSIONS: [&str; 10] = [
    "csv", "json", "bvh", "gltf", "glb", "fbx", "usda", "usdc", "usdz", "usd",
];

/// Runs `one` on `input`, writing `output`, as a batch runs each of its inputs: skipped when
/// `output` is up to date ([`inputs::up_to_date`]) unless `refresh`, else the output's folder made and the
/// command run, its figures noted ([`note`](crate::record::note)) and what it tells kept in `told`. The record
/// (its `error` the error's text as the command line shows it), and the error.
pub fn run_job(
    input: &Path,
    output: &Path,
    refresh: bool,
    one: &OneInput<'_>,
    told: &mut Collected,
) -> (Record, Option<Error>) {
    let t0 = Instant::now();
    let mut record = Record::new(
        input.display().to_string(),
        Some(output.display().to_string()),
        Status::Ok,
    );
    if !refresh && inputs::up_to_date(output, input) {
        record.status = Status::Skipped;
        record.seconds = Some(0.0);
        record.reason = Some("its output is newer (--refresh redoes it)".into());
        return (record, None);
    }
    let made = output
        .parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .map_err(|e| {
            Error::Io(std::io::Error::new(
                e.kind(),
                format!("{}: cannot make its folder: {e}", shown(output)),
            ))
        });
    crate::record::collect_figures();
    let result = made.and_then(|()| inbetween::parallel::serially(|| one(input, output, told)));
    let figures = crate::record::collected_figures();
    record.seconds = Some((t0.elapsed().as_secs_f64() * 1e3).round() / 1e3);
    match result {
        Ok(()) => record.figures = figures,
        Err(e) => {
            record.status = Status::Failed;
            record.error = Some(crate::flags::error_text(&e));
            return (record, Some(e));
        }
    }
    (record, None)
}

/// What a batch tells as it goes, from its threads: the front end prints it (the command line's
/// progress bar and standard error); the library prints nothing.
pub trait Progress: Sync {
    /// The inputs are found: `inputs` will run.
    fn start(&self, inputs: usize);
    /// A warning about the batch itself (a file passed over).
    fn warning(&self, message: &str);
    /// An input finished: its record (its `error` when it failed) and what it told.
    fn finished(&self, record: &Record, told: &Collected);
    /// After the last input: how many came to what, and how long it took.
    fn summary(&self, line: &str);
}

/// The command on one input: `(input, output, warn)`.
pub type OneInput<'a> = dyn Fn(&Path, &Path, &mut dyn Events) -> Result<(), Error> + Sync + 'a;

/// What finished inputs came to.
#[derive(Debug, Default)]
struct Tally {
    ok: usize,
    skipped: usize,
    refused: usize,
    unwritten: usize,
    internal: usize,
}

/// Whether `path` has the extension of an input format.
fn known(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| INPUT_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

/// The output of `job` under `out_dir` (with `ext`'s extension), or why it has none.
fn output_of(
    job: &Job,
    out_dir: &Path,
    ext: &(dyn Fn(&Path) -> Result<String, Error> + Sync),
) -> Result<PathBuf, Error> {
    if !known(&job.input) {
        return Err(InputError::new(format!(
            "{}: not an input format: a batch knows its inputs by their extension (.csv, .json, \
             .bvh, .gltf, .glb, .fbx, .usda)",
            shown(&job.input)
        ))
        .into());
    }
    let ext = ext(&job.input)?;
    Ok(out_dir.join(&job.relative).with_extension(ext))
}

/// At most this many collisions are listed in the refusal.
const LISTED: usize = 10;

/// The manifest, appended a line at a time; the first error writing it.
struct Manifest {
    file: Option<Mutex<std::fs::File>>,
    path: Option<PathBuf>,
    error: Mutex<Option<std::io::Error>>,
}

impl Manifest {
    /// Opens `path` for appending: refused when it exists and is not a regular file (a FIFO
    /// would block, a device is not the user's log).
    fn open(path: Option<&Path>) -> Result<Manifest, Error> {
        let Some(path) = path else {
            return Ok(Manifest {
                file: None,
                path: None,
                error: Mutex::new(None),
            });
        };
        if let Ok(m) = std::fs::metadata(path)
            && !m.is_file()
        {
            return Err(InputError::new(format!(
                "--manifest {}: expected a regular file, found {}",
                shown(path),
                if m.is_dir() {
                    "a folder"
                } else {
                    "no regular file"
                }
            ))
            .into());
        }
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .map_err(|e| InputError::new(format!("--manifest {}: {e}", shown(path))))?;
        Ok(Manifest {
            file: Some(Mutex::new(file)),
            path: Some(path.to_path_buf()),
            error: Mutex::new(None),
        })
    }

    /// Appends `record` as one line in one write; the first failure is kept for the exit.
    fn write(&self, record: &serde_json::Value) {
        let Some(f) = &self.file else {
            return;
        };
        let mut f = f.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let written = f
            .write_all(format!("{record}\n").as_bytes())
            .and_then(|()| f.flush());
        if let Err(e) = written {
            let mut first = self
                .error
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            first.get_or_insert(e);
        }
    }

    /// The error of the first line that could not be written, naming the manifest.
    fn failure(self) -> Option<Error> {
        let e = self
            .error
            .into_inner()
            .unwrap_or_else(std::sync::PoisonError::into_inner)?;
        let path = self.path.as_deref().map(shown).unwrap_or_default();
        Some(Error::Io(std::io::Error::new(
            e.kind(),
            format!("--manifest {path}: cannot write: {e}"),
        )))
    }
}

/// Runs `one(input, output, warn)` for every input of `first` and `batch.more` (see the module
/// documentation). `ext` gives an input's output extension. Before anything is written, the
/// outputs and the manifest are checked against the inputs and each other: a collision refuses
/// the batch. Exit: `Ok` when every input succeeded or was skipped; an input error when one was
/// refused; an I/O error (exit 1) when an output or the manifest could not be written; an
/// internal error (exit 1) when one failed otherwise.
pub fn run(
    first: Option<&Path>,
    batch: &BatchArgs,
    ext: &(dyn Fn(&Path) -> Result<String, Error> + Sync),
    one: &OneInput<'_>,
    progress: &dyn Progress,
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
    // The output folder is no input, nor is a manifest of no input format found in a folder.
    let mut exclude = vec![out_dir.to_path_buf()];
    exclude.extend(batch.manifest.iter().filter(|m| !known(m)).cloned());
    let rules = inputs::Rules {
        follow: batch.follow,
        follow_named: "--follow",
        exclude,
    };
    let found = inputs::expand(&patterns, &rules)?;
    let jobs = found.jobs;
    let outputs: Vec<Result<PathBuf, Error>> =
        jobs.iter().map(|j| output_of(j, out_dir, ext)).collect();
    let clashes = inputs::collisions(
        &jobs.iter().map(|j| j.input.as_path()).collect::<Vec<_>>(),
        &jobs
            .iter()
            .zip(&outputs)
            .filter_map(|(j, o)| o.as_ref().ok().map(|o| (j.input.as_path(), o.as_path())))
            .collect::<Vec<_>>(),
        batch.manifest.as_deref().map(|m| (m, "--manifest ")),
    );
    if !clashes.is_empty() {
        let more = clashes.len().saturating_sub(LISTED);
        return Err(InputError::new(format!(
            "the batch would write over its own files, so nothing was written: {}{}; choose \
             another --out-dir (or --manifest), or name the inputs by a pattern",
            clashes[..clashes.len().min(LISTED)].join("; "),
            if more > 0 {
                format!("; and {more} more")
            } else {
                String::new()
            }
        ))
        .into());
    }
    let manifest = Manifest::open(batch.manifest.as_deref())?;
    for p in &found.passed {
        progress.warning(&format!("{}: {}, skipped", shown(&p.path), p.reason));
        let mut record = Record::new(p.path.display().to_string(), None, Status::Skipped);
        record.reason = Some(p.reason.to_string());
        manifest.write(&record.to_json());
    }
    let threads = batch
        .jobs
        .map(|n| n as usize)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .min(jobs.len().max(1));
    // The largest files first, so that the threads end together (the longest-first rule); the
    // outputs do not depend on the order.
    let mut order: Vec<(u64, usize)> = jobs
        .iter()
        .enumerate()
        .map(|(i, j)| (std::fs::metadata(&j.input).map_or(0, |m| m.len()), i))
        .collect();
    order.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    progress.start(jobs.len());
    let tally = Mutex::new(Tally::default());
    let next = AtomicUsize::new(0);
    let started = Instant::now();
    let work = || {
        crate::output::hold_commits();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some((job, planned)) = order.get(i).map(|&(_, k)| (&jobs[k], &outputs[k])) else {
                break;
            };
            let mut told = Collected::default();
            let (record, failed) = match planned {
                Err(e) => {
                    let mut record =
                        Record::new(job.input.display().to_string(), None, Status::Failed);
                    record.seconds = Some(0.0);
                    record.error = Some(crate::flags::error_text(e));
                    (record, None)
                }
                Ok(output) => run_job(&job.input, output, batch.refresh, one, &mut told),
            };
            // The error of the run, when it failed; a planned error is the plan's own.
            let error = failed.as_ref().or(planned.as_ref().err());
            progress.finished(&record, &told);
            // The line whole, in one write, under the lock a signal waits for.
            if manifest.file.is_some() {
                crate::output::hold_now();
                manifest.write(&record.to_json());
            }
            // The output and its line are both written: a signal may end the process now.
            crate::output::release_commit();
            let mut t = tally
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            match (&error, record.status) {
                (None, Status::Skipped) => t.skipped += 1,
                (None, _) => t.ok += 1,
                (Some(Error::Input(_)), _) => t.refused += 1,
                (Some(Error::Io(_)), _) => t.unwritten += 1,
                (Some(_), _) => t.internal += 1,
            }
        }
    };
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(work);
        }
    });
    let t = tally
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let skipped = t.skipped + found.passed.len();
    let failed = t.refused + t.unwritten + t.internal;
    let all = jobs.len() + found.passed.len();
    progress.summary(&format!(
        "{all} inputs: {} ok, {skipped} skipped, {failed} failed ({:.2} s, {threads} jobs)",
        t.ok,
        started.elapsed().as_secs_f64()
    ));
    if let Some(e) = manifest.failure() {
        Err(e)
    } else if t.internal > 0 {
        Err(Error::Internal(format!(
            "internal error: {} of {all} inputs failed",
            t.internal
        )))
    } else if t.unwritten > 0 {
        Err(Error::Io(std::io::Error::other(format!(
            "{} of {all} outputs could not be written",
            t.unwritten
        ))))
    } else if t.refused > 0 {
        Err(InputError::new(format!("{} of {all} inputs were refused", t.refused)).into())
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
/// that input without `-o` — `interp` the input's own format (FBX, binary and written only when named: JSON),
/// `convert` and `reduce` keys as JSON for a BVH, FBX or USD input (`reduce` of glTF: glTF), a
/// keys document's own format otherwise; `interp` of binary USD (`.usdc`, `.usdz`, `.usd`):
/// `.usda`, the USD the tool writes.
pub fn extension(
    input: &Path,
    output: &crate::args::OutputArgs,
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
        Some(OutputFormat::Fbx) => "fbx",
        None => {
            let own = input
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase)
                .unwrap_or_default();
            return Ok(match own.as_str() {
                "fbx" | "" => "json".into(),
                "bvh" | "usda" | "usdc" | "usdz" | "usd" if keys => "json".into(),
                // Binary USD is read, written as text.
                "usdc" | "usdz" | "usd" => "usda".into(),
                _ => own,
            });
        }
    };
    Ok(ext.into())
}

/// The long names of the options `command` (`interp`, `convert` or `reduce`) takes by keyword
/// ([`process_one`]); `None` for another command.
pub fn option_names(command: &str) -> Option<Vec<&'static str>> {
    use crate::keywords::Keywords;
    match command {
        "interp" => Some(crate::args::InterpArgs::names()),
        "convert" => Some(crate::args::ConvertArgs::names()),
        "reduce" => Some(crate::args::ReduceArgs::names()),
        _ => None,
    }
}

/// One input of `interp`, `convert` or `reduce` (Python's `process_file`), run as a batch runs
/// each of its inputs ([`run_job`]): `options` are `(long name, value)` pairs, a repeatable
/// option repeated, names as [`option_names`] lists them (`_` for `-` accepted). A value an
/// option refuses is a failed record (`invalid value 'x' for '--fps': …`) and an input error.
/// Standard input is never read: a path `-` is the file `./-`. Another command is a failed
/// record too.
pub fn process_one(
    command: &str,
    input: &Path,
    output: &Path,
    options: &[(String, String)],
    refresh: bool,
) -> (Record, Option<Error>, Collected) {
    use crate::args::{ConvertArgs, InterpArgs, ReduceArgs};
    use crate::keywords::Keywords;
    fn build<K: Keywords + Default>(options: &[(String, String)]) -> Result<K, String> {
        let mut k = K::default();
        for (name, text) in options {
            let name = name.replace('_', "-");
            match k.set(&name, text) {
                Ok(true) => {}
                Ok(false) => return Err(format!("--{name} is not an option of this command")),
                Err(e) => {
                    return Err(format!(
                        "invalid value '{}' for '--{name}': {e}",
                        crate::shown::printable(text)
                    ));
                }
            }
        }
        Ok(k)
    }
    /// A request of one of the three commands.
    enum Request {
        Convert(ConvertArgs),
        Interp(InterpArgs),
        Reduce(ReduceArgs),
    }
    let request = match command {
        "convert" => build(options).map(Request::Convert),
        "interp" => build(options).map(Request::Interp),
        "reduce" => build(options).map(Request::Reduce),
        _ => Err(format!(
            "command: expected interp, convert or reduce, found \"{}\"",
            crate::shown::printable(command)
        )),
    };
    let failed = |message: String| {
        let mut record = Record::new(
            input.display().to_string(),
            Some(output.display().to_string()),
            Status::Failed,
        );
        record.seconds = Some(0.0);
        record.error = Some(message.clone());
        (
            record,
            Some(InputError::new(message).into()),
            Collected::default(),
        )
    };
    let request = match request {
        Ok(r) => r,
        Err(message) => return failed(message),
    };
    // Every path a path: `-` is the file of that name, not standard input.
    let as_path = |p: &Path| -> PathBuf {
        if p.as_os_str().to_string_lossy().starts_with('-') {
            Path::new(".").join(p)
        } else {
            p.to_path_buf()
        }
    };
    // An output named for a format not written is refused before anything is made or skipped.
    let format_given = match &request {
        Request::Convert(a) => a.output.output_format.is_some(),
        Request::Interp(a) => a.output.output_format.is_some(),
        Request::Reduce(a) => a.output.output_format.is_some(),
    };
    if !format_given && let Err(e) = crate::settings::check_output_path(output) {
        return failed(e.to_string());
    }
    let one = |input: &Path, output: &Path, warn: &mut dyn Events| {
        let (input, output) = (Some(as_path(input)), Some(as_path(output)));
        let empty = &mut std::io::empty();
        match &request {
            Request::Convert(a) => {
                let mut a = a.clone();
                (a.input.input, a.output.output) = (input, output);
                crate::convert::run(&a, empty, warn)
            }
            Request::Interp(a) => {
                let mut a = a.clone();
                (a.input.input, a.output.output) = (input, output);
                crate::interp::run(&a, empty, warn)
            }
            Request::Reduce(a) => {
                let mut a = a.clone();
                (a.input.input, a.output.output) = (input, output);
                crate::reduce::run(&a, empty, warn)
            }
        }
    };
    let mut told = Collected::default();
    let (record, error) = run_job(input, output, refresh, &one, &mut told);
    (record, error, told)
}
