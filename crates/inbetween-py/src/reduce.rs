//! `reduce`: the fewest keys that the curve of a scheme turns back into dense frames within a
//! tolerance, verified on every frame (the library's [`inbetween::reduce`], as `inbetween
//! reduce` runs it), for (T, 4) or (T, J, 4) frames at an exact rate.

use crate::arrays::{self, Layout};
use crate::{input_error, options};
use inbetween::reduce::{Method, ReduceOptions, Reduced, TrackFrames, reduce_each, reduce_shared};
use numpy::{PyArray1, PyArray2, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Below this a tolerance cannot be verified (rad; the curve carries about 1e-15 rad of
/// round-off), as on the command line.
const MIN_TOLERANCE: f64 = 1e-9;

/// Each joint's reduction as a dict: `keys` (frame indices, int64), `velocities` ((k, 3) rad/s
/// or None), `max_error` and `mean_error` (rad, or length with a distance), and
/// `max_position_error` (or None).
#[pyfunction]
#[pyo3(signature = (
    rotations, fps, tolerance, *, scheme = "bezier", method = "greedy", distance = None,
    shared_keys = false, velocities = true, translations = None, translation_tolerance = None,
    ends = "chord", path = "shortest", scalar_first = true
))]
#[allow(clippy::too_many_arguments)]
pub fn reduce<'py>(
    py: Python<'py>,
    rotations: PyReadonlyArrayDyn<'py, f64>,
    fps: Bound<'py, PyAny>,
    tolerance: f64,
    scheme: &str,
    method: &str,
    distance: Option<f64>,
    shared_keys: bool,
    velocities: bool,
    translations: Option<PyReadonlyArrayDyn<'py, f64>>,
    translation_tolerance: Option<f64>,
    ends: &str,
    path: &str,
    scalar_first: bool,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let fps = options::rate("fps", &fps)?;
    let (layout, quats): (Layout, _) = arrays::quats(&rotations, "rotations", scalar_first)?;
    let positions = translations
        .as_ref()
        .map(|a| arrays::vectors(a, "translations", layout, "rotations"))
        .transpose()?;
    let floor = MIN_TOLERANCE * distance.unwrap_or(1.0);
    if tolerance.is_nan() || tolerance < floor || tolerance.is_infinite() {
        return Err(input_error(format!(
            "tolerance: {tolerance:e} is below what reduce can verify (rotations carry about \
             1e-15 rad of round-off); give at least {floor:e} (radians, or length with a \
             distance)"
        )));
    }
    if let Some(d) = distance.filter(|d| !(d.is_finite() && *d > 0.0)) {
        return Err(input_error(format!(
            "distance: expected a positive length, found {d}"
        )));
    }
    match (positions.is_some(), translation_tolerance) {
        (true, None) => {
            return Err(input_error(
                "translation_tolerance: the frames have translations: give their tolerance \
                 (length units)",
            ));
        }
        (_, Some(t)) if !(t.is_finite() && t > 0.0) => {
            return Err(input_error(format!(
                "translation_tolerance: expected a positive length, found {t}"
            )));
        }
        _ => {}
    }
    let opts = ReduceOptions {
        curve: options::curve(scheme, ends, path, fps)?,
        tolerance,
        distance,
        translation_tolerance: translation_tolerance.filter(|_| positions.is_some()),
        velocities,
        method: match method {
            "greedy" => Method::Greedy,
            "optimal" => Method::Optimal,
            _ => {
                return Err(input_error(format!(
                    "method: expected greedy or optimal, found {method:?}"
                )));
            }
        },
    };
    let times: Vec<f64> = (0..layout.rows as i64).map(|k| fps.time_of(k)).collect();
    let frames: Vec<TrackFrames> = quats
        .iter()
        .enumerate()
        .map(|(j, q)| TrackFrames {
            times: &times,
            rotations: q,
            positions: positions.as_ref().map(|p| &p[j][..]),
            euler: None,
            key_times: None,
        })
        .collect();
    let reduced = py
        .detach(|| match shared_keys {
            true => reduce_shared(&frames, &opts),
            false => reduce_each(&frames, &opts),
        })
        .map_err(crate::error)?;
    reduced.iter().map(|r| as_dict(py, r)).collect()
}

fn as_dict<'py>(py: Python<'py>, r: &Reduced) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let keys: Vec<i64> = r.keys.iter().map(|&k| k as i64).collect();
    d.set_item("keys", PyArray1::from_vec(py, keys))?;
    let velocities = r.velocities.as_ref().map(|v| {
        let rows: Vec<Vec<f64>> = v.iter().map(|w| w.to_array().to_vec()).collect();
        PyArray2::from_vec2(py, &rows)
    });
    match velocities {
        Some(Ok(v)) => d.set_item("velocities", v)?,
        Some(Err(e)) => return Err(pyo3::exceptions::PyRuntimeError::new_err(e.to_string())),
        None => d.set_item("velocities", py.None())?,
    }
    d.set_item("max_error", r.max_error)?;
    d.set_item("mean_error", r.mean_error)?;
    d.set_item("max_position_error", r.max_position_error)?;
    Ok(d)
}
