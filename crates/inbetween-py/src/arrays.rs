//! numpy arrays in and out. Inputs arrive as float64 arrays (the Python layer converts them);
//! here their shapes are checked, with messages that name the argument, and split per joint.
//! Outputs are built once in their final C-contiguous layout and handed to numpy without a copy.

use crate::input_error;
use glam::{DQuat, DVec3};
use inbetween::rotation::{AngleUnit, Repr};
use numpy::ndarray::{ArrayViewD, Axis, IxDyn};
use numpy::{IntoPyArray, PyArrayDyn, PyReadonlyArrayDyn};
use pyo3::prelude::*;

/// Keys of `K` rows, for one joint or for `J` (the array's second axis).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Rows (keys or frames).
    pub rows: usize,
    /// Joints: `None` for a (K, C) array, `Some(J)` for (K, J, C).
    pub joints: Option<usize>,
}

/// The rows of `a` (named `name`), of shape (K, C) or (K, J, C) with `C = width`.
fn rows_of<'a>(
    a: &'a ArrayViewD<'a, f64>,
    name: &str,
    width: usize,
) -> PyResult<(Layout, Vec<ArrayViewD<'a, f64>>)> {
    let shape = a.shape();
    let layout = match *shape {
        [k, c] if c == width => Layout {
            rows: k,
            joints: None,
        },
        [k, j, c] if c == width => Layout {
            rows: k,
            joints: Some(j),
        },
        _ => {
            return Err(input_error(format!(
                "{name}: expected shape (K, {width}) or (K, J, {width}), found {shape:?}"
            )));
        }
    };
    let joints = match layout.joints {
        None => vec![a.view()],
        Some(_) => a.axis_iter(Axis(1)).collect(),
    };
    Ok((layout, joints))
}

/// Quaternions (K, 4) or (K, J, 4) — `[w, x, y, z]` rows when `scalar_first`, else
/// `[x, y, z, w]` — per joint, normalised by the command line's rule (docs/spec.md §2: a norm
/// below 1e-6 is an error naming the row; a norm off 1 by more than 1e-3 is normalised with one
/// Python `UserWarning` naming the first such row and counting the others); a norm within 1e-12
/// of 1 is taken as it is.
pub fn quats(
    a: &PyReadonlyArrayDyn<'_, f64>,
    name: &str,
    scalar_first: bool,
) -> PyResult<(Layout, Vec<Vec<DQuat>>)> {
    let view = a.as_array();
    let (layout, joints) = rows_of(&view, name, 4)?;
    let place = |k: usize, j: usize| match layout.joints {
        None => format!("{name}[{k}]"),
        Some(_) => format!("{name}[{k}, {j}]"),
    };
    let mut warned: Option<(String, usize)> = None;
    let mut per_joint = Vec::with_capacity(joints.len());
    for (j, rows) in joints.iter().enumerate() {
        let mut out = Vec::with_capacity(layout.rows);
        for (k, r) in rows.axis_iter(Axis(0)).enumerate() {
            let wxyz = match scalar_first {
                true => [r[0], r[1], r[2], r[3]],
                false => [r[3], r[0], r[1], r[2]],
            };
            let given = DQuat::from_xyzw(wxyz[1], wxyz[2], wxyz[3], wxyz[0]);
            // Unit to f64's working precision (a clip `read` gave): taken as it is, so that it
            // is written back to the bit; anything else normalised by the readers' rule.
            if (given.length() - 1.0).abs() <= 1e-12 {
                out.push(given);
                continue;
            }
            let (q, warning) = Repr::Quat
                .to_quat(&wxyz, AngleUnit::Rad)
                .map_err(|e| input_error(format!("{}: {}", place(k, j), e.message())))?;
            if let Some(w) = warning {
                match &mut warned {
                    None => warned = Some((format!("{}: {w}", place(k, j)), 0)),
                    Some((_, others)) => *others += 1,
                }
            }
            out.push(q);
        }
        per_joint.push(out);
    }
    if let Some((first, others)) = warned {
        let text = match others {
            0 => first,
            n => format!("{first} (and {n} other rows)"),
        };
        Python::attach(|py| {
            let message = std::ffi::CString::new(text).unwrap_or_default();
            PyErr::warn(
                py,
                &py.get_type::<pyo3::exceptions::PyUserWarning>(),
                &message,
                2,
            )
        })?;
    }
    Ok((layout, per_joint))
}

/// A joint's track of `times` and `quats`: one key is a constant (a joint that does not move),
/// as the command line reads a track of one key (docs/spec.md §3).
pub fn track(times: &[f64], quats: Vec<DQuat>) -> Result<inbetween::Track, inbetween::TrackError> {
    match (times, &quats[..]) {
        ([t], [q]) => inbetween::Track::constant(*t, *q),
        _ => inbetween::Track::new(times.to_vec(), quats),
    }
}

/// Vectors (K, 3) or (K, J, 3) per joint, laid out as `like` (same K, same J or none).
pub fn vectors(
    a: &PyReadonlyArrayDyn<'_, f64>,
    name: &str,
    like: Layout,
    like_name: &str,
) -> PyResult<Vec<Vec<DVec3>>> {
    let view = a.as_array();
    let (layout, joints) = rows_of(&view, name, 3)?;
    if layout != like {
        return Err(input_error(format!(
            "{name}: shape {:?} does not match {like_name}: expected {}",
            view.shape(),
            match like.joints {
                None => format!("({}, 3)", like.rows),
                Some(j) => format!("({}, {j}, 3)", like.rows),
            }
        )));
    }
    Ok(joints
        .iter()
        .map(|j| {
            j.axis_iter(Axis(0))
                .map(|r| DVec3::new(r[0], r[1], r[2]))
                .collect()
        })
        .collect())
}

/// The first non-finite value of per-joint vectors from [`vectors`], as an error naming its
/// row (`name[k]`, or `name[k, j]` for (K, J, 3)).
pub fn finite(v: &[Vec<DVec3>], name: &str, layout: Layout) -> PyResult<()> {
    for (j, rows) in v.iter().enumerate() {
        for (k, r) in rows.iter().enumerate() {
            if let Some(bad) = r.to_array().into_iter().find(|x| !x.is_finite()) {
                let place = match layout.joints {
                    None => format!("{name}[{k}]"),
                    Some(_) => format!("{name}[{k}, {j}]"),
                };
                return Err(input_error(format!(
                    "{place}: expected a finite number, found {bad}"
                )));
            }
        }
    }
    Ok(())
}

/// One vector (3,) for every joint, or one per joint (J, 3).
pub fn end_vectors(
    a: &PyReadonlyArrayDyn<'_, f64>,
    name: &str,
    joints: Option<usize>,
) -> PyResult<Vec<DVec3>> {
    let view = a.as_array();
    let at = |i: usize| {
        let r = view.index_axis(Axis(0), i);
        DVec3::new(r[0], r[1], r[2])
    };
    match (view.shape(), joints) {
        ([3], _) => Ok(vec![
            DVec3::new(view[[0]], view[[1]], view[[2]]);
            joints.unwrap_or(1)
        ]),
        ([j, 3], Some(n)) if *j == n => Ok((0..n).map(at).collect()),
        (shape, _) => Err(input_error(format!(
            "{name}: expected shape (3,){}, found {shape:?}",
            joints.map_or(String::new(), |j| format!(" or ({j}, 3)"))
        ))),
    }
}

/// Times (N,) from a 1-d array.
pub fn times(a: &PyReadonlyArrayDyn<'_, f64>, name: &str) -> PyResult<Vec<f64>> {
    let view = a.as_array();
    match view.shape() {
        [_] => Ok(view.iter().copied().collect()),
        shape => Err(input_error(format!(
            "{name}: expected a 1-d array of seconds, found shape {shape:?}"
        ))),
    }
}

/// A C-contiguous float64 array of shape (N, C) or (N, J, C) from per-joint rows of `C`
/// numbers each (`per_joint[j][n]`), written once in its final layout.
pub fn output<'py, const C: usize>(
    py: Python<'py>,
    per_joint: &[Vec<[f64; C]>],
    joints: Option<usize>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let n = per_joint.first().map_or(0, Vec::len);
    let j = per_joint.len();
    let mut data = Vec::with_capacity(n * j * C);
    for row in 0..n {
        for joint in per_joint {
            data.extend_from_slice(&joint[row]);
        }
    }
    let shape: Vec<usize> = match joints {
        None => vec![n, C],
        Some(_) => vec![n, j, C],
    };
    let array = numpy::ndarray::ArrayD::from_shape_vec(IxDyn(&shape), data)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

/// A C-contiguous float64 array of shape (N, C) or (N, J, C) from its data, already in that
/// layout (`data.len() = N·J·C`, J = 1 for `joints = None`), without a copy.
pub fn output_flat<'py>(
    py: Python<'py>,
    data: Vec<f64>,
    width: usize,
    joints: Option<usize>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let j = joints.unwrap_or(1);
    let n = data.len() / (j * width).max(1);
    let shape: Vec<usize> = match joints {
        None => vec![n, width],
        Some(_) => vec![n, j, width],
    };
    let array = numpy::ndarray::ArrayD::from_shape_vec(IxDyn(&shape), data)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

/// A quaternion as `C = 4` numbers in the caller's order.
pub fn quat_row(q: DQuat, scalar_first: bool) -> [f64; 4] {
    match scalar_first {
        true => [q.w, q.x, q.y, q.z],
        false => [q.x, q.y, q.z, q.w],
    }
}
