//! `read`: any file the command line reads (CSV, JSON, BVH, glTF) as tracks of numpy arrays,
//! through the formats crate (`inbetween-io`): the same tracks, the same checks, the same
//! located errors.

use crate::arrays::quat_row;
use crate::{input_error, options};
use inbetween::rotation::{AngleUnit, QuatOrder, Repr};
use inbetween::{Fps, Tcb};
use inbetween_io::read::log::{Column, ColumnMap, Preset, TimeOrigin, TimeUnit};
use inbetween_io::{Format, ReadOptions};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::Path;

/// The file at `path` as a dict: `source`, `format`, `fps` (the rate its frames or frame numbers
/// are at, as text, or None), `names`, `tracks` (per track: times (K,), rotations (K, 4),
/// translations (K, 3) or None), and for BVH and glTF `parents` (each track's nearest ancestor that is
/// a track, -1 for none) and `offsets` (J, 3); for an AMASS `.npz`, `parents` of the SMPL-H or
/// SMPL-X tree (no offsets: they need the licensed body model). `rotation` says how CSV e1,e2,e3 columns and JSON
/// `euler` keys are written when the file does not say (`"euler:ZYX"`, …); `angles` the unit of
/// the file's angles, as the command line's `--input-angles` (a document that declares another
/// is an error, not silently read in its own; without it, undeclared angles are degrees);
/// `key_fps` the rate of frame numbers when the file declares none.
/// `columns` reads a timestamped log: a preset (`"tum"`, `"euroc"`, `"rostopic"`), the command
/// line's map (`"time=1,w=8,x=5,y=6,z=7"`), or a dict of fields to header names or column
/// numbers from 1 (`{"time": "%time", "w": "field.orientation.w", ...}`, a `"preset"` key
/// under them); `time_unit` (`"s"`, `"ms"`, `"us"`, `"ns"`) and `times` (`"relative"`,
/// `"absolute"`) as `--time-unit` and `--times`.
#[pyfunction]
#[pyo3(signature = (
    path, *, rotation = None, angles = None, key_fps = None, quat_order = "wxyz",
    scalar_first = true, max_bytes = inbetween_io::DEFAULT_MAX_INPUT_BYTES, columns = None,
    time_unit = None, times = None
))]
#[allow(clippy::too_many_arguments)]
pub fn read<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    rotation: Option<&str>,
    angles: Option<&str>,
    key_fps: Option<Bound<'py, PyAny>>,
    quat_order: &str,
    scalar_first: bool,
    max_bytes: u64,
    columns: Option<Bound<'py, PyAny>>,
    time_unit: Option<&str>,
    times: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let located = |e: inbetween::InputError| input_error(crate::message(&e));
    let opts = ReadOptions {
        from: rotation
            .map(Repr::parse)
            .transpose()
            .map_err(|e| input_error(format!("rotation: {}", crate::message(&e))))?,
        angles: AngleUnit::Deg,
        input_angles: angles
            .map(AngleUnit::parse)
            .transpose()
            .map_err(|e| input_error(format!("angles: {}", crate::message(&e))))?,
        key_fps: key_fps
            .as_ref()
            .map(|r| options::rate("key_fps", r))
            .transpose()?,
        quat_order: QuatOrder::parse(quat_order)
            .map_err(|e| input_error(format!("quat_order: {}", crate::message(&e))))?,
        delimiter: None,
        columns: column_map(columns.as_ref(), time_unit, times)?,
    };
    let (doc, format) = py
        .detach(|| {
            let bytes = inbetween_io::read_bytes_limited(&path, max_bytes)?;
            let source = path.display().to_string();
            inbetween_io::parse_bytes(bytes, &source, Some(Path::new(&path)), None, &opts)
        })
        .map_err(crate::error)?;
    let frame_fps = doc.fps.unwrap_or(Fps::DEFAULT);
    let tracks = doc.tracks_shaped(frame_fps, Tcb::ZERO).map_err(located)?;
    let d = PyDict::new(py);
    d.set_item("source", &doc.source)?;
    d.set_item("format", format_name(format))?;
    d.set_item("fps", doc.fps.map(|f| f.to_string()))?;
    let names: Vec<String> = tracks
        .iter()
        .enumerate()
        .map(|(i, t)| t.name().map_or_else(|| format!("track{i}"), str::to_string))
        .collect();
    d.set_item("names", &names)?;
    let mut out = Vec::with_capacity(tracks.len());
    for t in &tracks {
        let q: Vec<Vec<f64>> = t
            .rotations()
            .iter()
            .map(|&q| quat_row(q, scalar_first).to_vec())
            .collect();
        let p = t.translations().map(|p| {
            let rows: Vec<Vec<f64>> = p.iter().map(|v| v.to_array().to_vec()).collect();
            PyArray2::from_vec2(py, &rows)
        });
        let q = PyArray2::from_vec2(py, &q).map_err(runtime)?;
        let p = p.transpose().map_err(runtime)?;
        out.push((PyArray1::from_slice(py, t.times()), q, p));
    }
    d.set_item("tracks", out)?;
    // An AMASS file: the model's fixed tree (no offsets: they need the body model's files).
    let model = (format == Format::Amass)
        .then(|| inbetween_io::amass::Model::of_width(3 * tracks.len() as u64))
        .flatten();
    if let Some(m) = model {
        let parents: Vec<i64> = m
            .parents()
            .iter()
            .map(|p| p.map_or(-1, |t| t as i64))
            .collect();
        d.set_item("parents", PyArray1::from_vec(py, parents))?;
    }
    if let Some(skeleton) = doc
        .hierarchy
        .as_deref()
        .filter(|s| s.track_count() == tracks.len())
    {
        // Each track's nearest animated ancestor and its joint's rest translation (BVH OFFSET,
        // glTF node translation).
        let parents: Vec<i64> = skeleton
            .track_parents()
            .iter()
            .map(|p| p.map_or(-1, |t| t as i64))
            .collect();
        let joints = skeleton.track_joints();
        if joints.iter().all(Option::is_some) {
            let offsets: Vec<Vec<f64>> = joints
                .iter()
                .flatten()
                .map(|&j| skeleton.joints()[j].translation.to_array().to_vec())
                .collect();
            d.set_item("parents", PyArray1::from_vec(py, parents))?;
            d.set_item(
                "offsets",
                PyArray2::from_vec2(py, &offsets).map_err(runtime)?,
            )?;
        }
    }
    Ok(d)
}

/// The `columns`, `time_unit` and `times` keywords as a column map (`None` without `columns`;
/// `time_unit` or `times` without it is an error).
fn column_map(
    columns: Option<&Bound<'_, PyAny>>,
    time_unit: Option<&str>,
    times: Option<&str>,
) -> PyResult<Option<ColumnMap>> {
    let bad = |what: &str, e: inbetween::InputError| {
        input_error(format!("{what}: {}", crate::message(&e)))
    };
    let Some(columns) = columns else {
        if time_unit.is_some() || times.is_some() {
            return Err(input_error(
                "time_unit and times describe the stamps of a log read with columns; give \
                 columns too (e.g. columns=\"tum\")",
            ));
        }
        return Ok(None);
    };
    let mut map = if let Ok(text) = columns.extract::<String>() {
        ColumnMap::parse(&text).map_err(|e| bad("columns", e))?
    } else if let Ok(dict) = columns.cast::<PyDict>() {
        let mut map = ColumnMap::default();
        if let Some(p) = dict.get_item("preset")? {
            let name: String = p.extract()?;
            map.preset = Some(Preset::parse(&name).ok_or_else(|| {
                input_error(format!(
                    "columns: expected a preset tum, euroc or rostopic, found \"{}\"",
                    inbetween::error::shorten(&name)
                ))
            })?);
        }
        for (k, v) in dict.iter() {
            let field: String = k.extract()?;
            if field == "preset" {
                continue;
            }
            let column = match v.extract::<usize>() {
                Ok(n) => Column::parse(&n.to_string()),
                Err(_) => Ok(Column::Name(v.extract::<String>().map_err(|_| {
                    input_error(format!(
                        "columns[\"{field}\"]: expected a column name (str) or number from 1 (int)"
                    ))
                })?)),
            }
            .map_err(|e| bad(&format!("columns[\"{field}\"]"), e))?;
            map.set(&field, column).map_err(|e| bad("columns", e))?;
        }
        map
    } else {
        return Err(input_error(
            "columns: expected a preset or map (str) or a dict of fields to columns",
        ));
    };
    if let Some(u) = time_unit {
        map.time_unit = Some(TimeUnit::parse(u).map_err(|e| bad("time_unit", e))?);
    }
    if let Some(t) = times {
        map.times = TimeOrigin::parse(t).map_err(|e| bad("times", e))?;
    }
    Ok(Some(map))
}

fn runtime(e: impl std::fmt::Display) -> PyErr {
    pyo3::exceptions::PyRuntimeError::new_err(e.to_string())
}

fn format_name(f: Format) -> &'static str {
    match f {
        Format::Csv => "csv",
        Format::Json => "json",
        Format::Bvh => "bvh",
        Format::Gltf => "gltf",
        Format::Fbx => "fbx",
        Format::Usd => "usda",
        Format::Amass => "npz",
    }
}
