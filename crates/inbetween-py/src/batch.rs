//! `process_file`: one command on one file, in-process, as a batch of the command line runs it
//! (docs/python.md, *Many files*): the same request and code (`inbetween_commands::batch`), so
//! the same bytes and the same record, with the GIL released — for Dask, joblib, Ray or a thread pool mapping it over a folder.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Options of a batch of the command line, which one file does not take (`process_file`
/// names its own input and output).
const PER_BATCH: [&str; 8] = [
    "out-dir", "jobs", "manifest", "refresh", "follow", "output", "more", "input",
];

/// Runs `command` on `path`, writing `out`, as `inbetween <command> <path> -o <out> <options>`
/// would, and returns its record (the batch
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
    let Some(known) = inbetween_commands::batch::option_names(command) else {
        return Err(crate::input_error(format!(
            "command: expected \"interp\", \"convert\" or \"reduce\", found \"{command}\""
        )));
    };
    let mut pairs: Vec<(String, String)> = Vec::new();
    if let Some(options) = options {
        for (k, v) in options.iter() {
            let name: String = k.extract()?;
            let long = name.replace('_', "-");
            if !known.contains(&long.as_str()) || PER_BATCH.contains(&long.as_str()) {
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
            if v.is_none() {
                continue;
            }
            if let Ok(b) = v.extract::<bool>() {
                if b {
                    pairs.push((long, "true".into()));
                }
                continue;
            }
            let values: Vec<Bound<'py, PyAny>> = match v.extract::<Vec<Bound<'py, PyAny>>>() {
                Ok(list) if !v.is_instance_of::<pyo3::types::PyString>() => list,
                _ => vec![v],
            };
            for value in values {
                pairs.push((long.clone(), value.str()?.to_string()));
            }
        }
    }
    let (input, output) = (PathBuf::from(path), PathBuf::from(out));
    let command = command.to_string();
    let (line, error, told) = py.detach(move || {
        inbetween_commands::batch::process_one(&command, &input, &output, &pairs, refresh)
    });
    let code = error.as_ref().map_or(0, inbetween_commands::exit_code);
    // The manifest's line, with the paths as given.
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
    let escaped = |lines: Vec<String>| -> Vec<String> {
        lines
            .iter()
            .map(|l| inbetween_commands::shown::line(l))
            .collect()
    };
    record.set_item("warnings", escaped(told.warnings))?;
    record.set_item("reports", escaped(told.reports))?;
    Ok(record)
}
