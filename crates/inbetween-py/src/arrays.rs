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

/// The layout of `a` (named `name`), of shape (K, C) or (K, J, C) with `C = width`.
pub fn layout_of(a: &ArrayViewD<'_, f64>, name: &str, width: usize) -> PyResult<Layout> {
    let shape = a.shape();
    Ok(match *shape {
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
    })
}

/// The rows of `a` (named `name`), of shape (K, C) or (K, J, C) with `C = width`.
fn rows_of<'a>(
    a: &'a ArrayViewD<'a, f64>,
    name: &str,
    width: usize,
) -> PyResult<(Layout, Vec<ArrayViewD<'a, f64>>)> {
    let layout = layout_of(a, name, width)?;
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
            let r = [r[0], r[1], r[2], r[3]];
            let (q, warning) = read_quat(&r, scalar_first)
                .map_err(|e| input_error(format!("{}: {e}", place(k, j))))?;
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
        warn_rows(first, others)?;
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

/// One quaternion row (4 numbers in the caller's order) as [`quats`] takes it: unit to f64's
/// working precision as it is, anything else by the readers' rule (the rotation and its
/// warning, or the error's message).
#[inline]
fn read_quat(r: &[f64], scalar_first: bool) -> Result<(DQuat, Option<String>), String> {
    if let Some(q) = unit_quat(r, scalar_first) {
        return Ok((q, None));
    }
    let wxyz = match scalar_first {
        true => [r[0], r[1], r[2], r[3]],
        false => [r[3], r[0], r[1], r[2]],
    };
    Repr::Quat
        .to_quat(&wxyz, AngleUnit::Rad)
        .map_err(|e| e.message().to_string())
}

/// [`read_quat`]'s quaternion where the row is unit to f64's working precision as given (no
/// message, nothing to build), else `None` (NaN included): the rows of real data, read without
/// the general path's result.
#[inline]
fn unit_quat(r: &[f64], scalar_first: bool) -> Option<DQuat> {
    let given = match scalar_first {
        true => DQuat::from_xyzw(r[1], r[2], r[3], r[0]),
        false => DQuat::from_xyzw(r[0], r[1], r[2], r[3]),
    };
    ((given.length() - 1.0).abs() <= 1e-12).then_some(given)
}

/// A row's place, `(j, k)`: joint, then row.
type At = (usize, usize);

/// What [`Flat::scan`] finds a row to be.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Row {
    Fine,
    /// Read with a warning (normalised).
    Warned,
    Refused,
}

/// Rows of `width` numbers (K, C) or (K, J, C) read in place: C-contiguous `data`, row `(k, j)`
/// at `(k·J + j)·C` (J = 1 for (K, C)).
#[derive(Clone, Copy)]
pub struct Flat<'a> {
    pub data: &'a [f64],
    pub layout: Layout,
    pub width: usize,
}

impl Flat<'_> {
    /// The number of joints (1 for (K, C)).
    pub fn joints(&self) -> usize {
        self.layout.joints.unwrap_or(1)
    }

    /// Row `k` of joint `j`.
    #[inline]
    pub fn row(&self, k: usize, j: usize) -> &[f64] {
        let at = (k * self.joints() + j) * self.width;
        &self.data[at..at + self.width]
    }

    /// `name[k]` or `name[k, j]`, the place of a row in a message.
    fn place(&self, name: &str, k: usize, j: usize) -> String {
        match self.layout.joints {
            None => format!("{name}[{k}]"),
            Some(_) => format!("{name}[{k}, {j}]"),
        }
    }

    /// The first refused and the first warned row (in joint order, then row order, as `(j, k)`)
    /// by `class`, and the number of warned rows, scanning the rows in memory order on the cores.
    fn scan(&self, class: impl Fn(&[f64]) -> Row + Sync) -> (Option<At>, Option<At>, usize) {
        let joints = self.joints();
        let chunk = (1 << 16) * self.width;
        let chunks: Vec<(usize, &[f64])> = self.data.chunks(chunk).enumerate().collect();
        let found = inbetween::parallel::map(&chunks, |&(c, data)| {
            let (mut refused, mut warned, mut count) = (None::<At>, None, 0);
            for (i, r) in data.chunks_exact(self.width).enumerate() {
                let row = class(r);
                if row == Row::Fine {
                    continue;
                }
                let i = c * (chunk / self.width) + i;
                let at = (i % joints, i / joints);
                let first = if row == Row::Refused {
                    &mut refused
                } else {
                    count += 1;
                    &mut warned
                };
                *first = Some(first.map_or(at, |f: At| f.min(at)));
            }
            (refused, warned, count)
        });
        found
            .into_iter()
            .fold((None, None, 0), |(r, w, n), (r2, w2, n2)| {
                let min = |a: Option<At>, b: Option<At>| match (a, b) {
                    (Some(a), Some(b)) => Some(a.min(b)),
                    _ => a.or(b),
                };
                (min(r, r2), min(w, w2), n + n2)
            })
    }

    /// The first (in joint order, then row order) row for which `bad` is true, as `(j, k)`,
    /// scanning the rows in memory order on the cores ([`Flat::scan`]).
    fn first(&self, bad: impl Fn(&[f64]) -> bool + Sync) -> Option<At> {
        self.scan(|r| if bad(r) { Row::Refused } else { Row::Fine })
            .0
    }
}

/// `a`'s numbers in C order: the array's own memory when it is C-contiguous, else a copy.
pub fn standard<'a>(a: &'a ArrayViewD<'a, f64>) -> std::borrow::Cow<'a, [f64]> {
    match a.as_slice() {
        Some(s) => std::borrow::Cow::Borrowed(s),
        None => std::borrow::Cow::Owned(a.iter().copied().collect()),
    }
}

/// [`quats`]' checks on quaternions `q` read in place, without the GIL but for the warning:
/// the first row refused (in joint order) is the error, else the first row normalised is the
/// warning, with the count of the others.
pub fn check_quats(py: Python<'_>, q: Flat<'_>, name: &str, scalar_first: bool) -> PyResult<()> {
    // One pass in memory order on the cores: the first refused row, the first normalised one
    // and how many are (only rows not unit as given take the general path).
    let (refused, normalised) = py.detach(|| {
        let (refused, warned, count) = q.scan(|r| match unit_quat(r, scalar_first) {
            Some(_) => Row::Fine,
            None => match read_quat(r, scalar_first) {
                Err(_) => Row::Refused,
                Ok((_, Some(_))) => Row::Warned,
                Ok((_, None)) => Row::Fine,
            },
        });
        (
            refused,
            warned.filter(|_| refused.is_none()).map(|w| (w, count)),
        )
    });
    if let Some((j, k)) = refused {
        let e = read_quat(q.row(k, j), scalar_first)
            .err()
            .unwrap_or_default();
        return Err(input_error(format!("{}: {e}", q.place(name, k, j))));
    }
    if let Some(((j, k), count)) = normalised {
        let w = match read_quat(q.row(k, j), scalar_first) {
            Ok((_, Some(w))) => w,
            _ => String::new(),
        };
        warn_rows(format!("{}: {w}", q.place(name, k, j)), count - 1)?;
    }
    Ok(())
}

/// Joint `j`'s quaternions of `q` (checked by [`check_quats`]), normalised as [`quats`] does.
pub fn joint_quats(q: Flat<'_>, j: usize, scalar_first: bool) -> Result<Vec<DQuat>, String> {
    // Allocated once (a `collect` through `Result` cannot size its vector: it grew by copies).
    let mut out = Vec::with_capacity(q.layout.rows);
    for k in 0..q.layout.rows {
        let r = q.row(k, j);
        out.push(match unit_quat(r, scalar_first) {
            Some(q) => q,
            None => read_quat(r, scalar_first)?.0,
        });
    }
    Ok(out)
}

/// [`vectors`]' shape check and [`finite`]'s check on vectors read in place.
pub fn check_vectors(
    a: &ArrayViewD<'_, f64>,
    v: Flat<'_>,
    name: &str,
    like_name: &str,
) -> PyResult<()> {
    let layout = layout_of(a, name, 3)?;
    let like = v.layout;
    if layout != like {
        return Err(input_error(format!(
            "{name}: shape {:?} does not match {like_name}: expected {}",
            a.shape(),
            match like.joints {
                None => format!("({}, 3)", like.rows),
                Some(j) => format!("({}, {j}, 3)", like.rows),
            }
        )));
    }
    if let Some((j, k)) = v.first(|r| r.iter().any(|x| !x.is_finite())) {
        let bad = v.row(k, j).iter().copied().find(|x| !x.is_finite());
        return Err(input_error(format!(
            "{}: expected a finite number, found {}",
            v.place(name, k, j),
            bad.unwrap_or(f64::NAN)
        )));
    }
    Ok(())
}

/// Joint `j`'s vectors of `v`.
pub fn joint_vectors(v: Flat<'_>, j: usize) -> Vec<DVec3> {
    (0..v.layout.rows)
        .map(|k| {
            let r = v.row(k, j);
            DVec3::new(r[0], r[1], r[2])
        })
        .collect()
}

/// One Python `UserWarning`: `first`, and the count of the other rows.
fn warn_rows(first: String, others: usize) -> PyResult<()> {
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
    })
}

/// Times (N,) from a 1-d array, read in place when it is contiguous.
pub fn times_in_place<'a>(
    view: &'a ArrayViewD<'a, f64>,
    name: &str,
) -> PyResult<std::borrow::Cow<'a, [f64]>> {
    match view.shape() {
        [_] => Ok(standard(view)),
        shape => Err(input_error(format!(
            "{name}: expected a 1-d array of seconds, found shape {shape:?}"
        ))),
    }
}
