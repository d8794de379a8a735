//! `process_file`: one command of the command line on one file, in-process, as a batch of the
//! command line runs it (docs/python.md, *Many files*): the same code, so the same bytes, with
//! the GIL released — for Dask, joblib, Ray or a thread pool mapping it over a folder.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::ffi::OsString;

/// The commands that write a file.
const COMMANDS: [&str; 3] = ["interp", "convert", "reduce"];

/// Options of a batch of the command line, which one file does not take (`process_file`
/// names its own input and output).
const PER_BATCH: [&str; 8] = [
    "out-dir", "jobs", "manifest", "refresh", "follow", "output", "more", "input",
];

/// Runs `inbetween <command> <path> -o <out> <options>` and returns its record (the batch
/// manifest's: input, output, status, seconds, error, warnings). `options` maps a flag's name
/// (`fps`, `scheme`, `translation_tolerance`; `_` for `-`) to its value: `True` gives the bare
/// flag, `False` or `None` leaves it out, a list repeats it. An output newer than its input is
/// `skipped` unless `refresh`; its folder is made.
#[pyfunction]
#[pyo3(signature = (path, out, command, options=None, refresh=false))]
pub fn process_file<'py>(
    py: Python<'py>,
    path: &str,
    out: &str,
    command: &str,
    options: Option<&Bound<'py, PyDict>>,
    refresh: bool,
) -> PyResult<Bound<'py, PyDict>> {
    if !COMMANDS.contains(&command) {
        return Err(crate::input_error(format!(
            "command: expected \"interp\", \"convert\" or \"reduce\", found \"{command}\""
        )));
    }
    // Every path a path: a relative one that starts with `-` (`--help`, `-`) is written
    // `./--help`, so that it is never read as a flag or as standard input.
    let as_path = |p: &str| -> OsString {
        if p.starts_with('-') {
            format!("./{p}").into()
        } else {
            p.into()
        }
    };
    let mut args: Vec<OsString> = vec![
        "inbetween".into(),
        command.into(),
        as_path(path),
        "-o".into(),
        as_path(out),
    ];
    if let Some(options) = options {
        let known = inbetween_cli::option_names(command);
        for (k, v) in options.iter() {
            let name: String = k.extract()?;
            let long = name.replace('_', "-");
            if !known.contains(&long) || PER_BATCH.contains(&long.as_str()) {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "process_file: {} is not an option of {command}{}",
                    crate::shown(&name),
                    if PER_BATCH.contains(&long.as_str()) {
                        " one file at a time (a batch's own option)"
                    } else {
                        ""
                    }
                )));
            }
            let flag = format!("--{long}");
            if v.is_none() {
                continue;
            }
            if let Ok(b) = v.extract::<bool>() {
                if b {
                    args.push(flag.into());
                }
                continue;
            }
            let values: Vec<Bound<'py, PyAny>> = match v.extract::<Vec<Bound<'py, PyAny>>>() {
                Ok(list) if !v.is_instance_of::<pyo3::types::PyString>() => list,
                _ => vec![v],
            };
            // `--fps=-24`: a value is a value, whatever it starts with.
            for value in values {
                args.push(format!("{flag}={}", value.str()?).into());
            }
        }
    }
    let (line, code, told) = py.detach(move || inbetween_cli::process_one(args, refresh));
    // The manifest's line, with the paths as given (`--help`, not the `./--help` it was run as).
    let record = PyDict::new(py);
    if let serde_json::Value::Object(map) = line.to_json() {
        for (k, v) in map {
            match v {
                serde_json::Value::String(s) => record.set_item(k, s)?,
                serde_json::Value::Number(n) if n.is_f64() => record.set_item(k, n.as_f64())?,
                serde_json::Value::Number(n) => record.set_item(k, n.as_u64())?,
                _ => record.set_item(k, py.None())?,
            }
        }
    }
    record.set_item("input", path)?;
    record.set_item("output", out)?;
    record.set_item("exit_code", code)?;
    record.set_item("warnings", told.warnings)?;
    record.set_item("reports", told.reports)?;
    Ok(record)
}
