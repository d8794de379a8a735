//! The 6D representation of networks, both ways, by the maths crate's `Repr` (one rule for the
//! command line and Python): `rot6d:rows` (pytorch3d) and `rot6d:columns` (Zhou et al.).

use crate::input_error;
use inbetween::rotation::{AngleUnit, MAX_WIDTH, Repr};
use numpy::ndarray::{ArrayD, Axis, IxDyn};
use numpy::{IntoPyArray, PyArrayDyn, PyReadonlyArrayDyn};
use pyo3::prelude::*;

/// Quaternions (..., 4) to 6D (..., 6) (`inverse = false`), or 6D (..., 6) to unit quaternions
/// (..., 4) by Gram–Schmidt (`inverse = true`); `convention` is `"rows"` or `"columns"`,
/// quaternions `[w, x, y, z]` when `scalar_first`, else `[x, y, z, w]`.
#[pyfunction]
#[pyo3(signature = (a, convention, inverse, scalar_first = true))]
pub fn rot6d<'py>(
    py: Python<'py>,
    a: PyReadonlyArrayDyn<'py, f64>,
    convention: &str,
    inverse: bool,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let repr = match convention.strip_prefix("rot6d:").unwrap_or(convention) {
        "rows" => Repr::Rot6dRows,
        "columns" => Repr::Rot6dColumns,
        _ => {
            return Err(input_error(format!(
                "convention: expected \"rows\" (pytorch3d's matrix_to_rotation_6d) or \
                 \"columns\" (Zhou et al.), or rot6d:rows, rot6d:columns, found \"{}\"",
                inbetween::error::shorten(convention)
            )));
        }
    };
    let (name, width_in, width_out) = match inverse {
        false => ("q", 4, 6),
        true => ("a", 6, 4),
    };
    let view = a.as_array();
    let shape = view.shape().to_vec();
    if shape.last() != Some(&width_in) {
        return Err(input_error(format!(
            "{name}: expected shape (..., {width_in}), found {shape:?}"
        )));
    }
    let rows = view
        .to_shape((view.len() / width_in, width_in))
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    let mut out = Vec::with_capacity(rows.len_of(Axis(0)) * width_out);
    let mut buf = [0.0; MAX_WIDTH];
    // The first quaternion normalised with a warning, and how many others (as arrays::quats).
    let mut warned: Option<(String, usize)> = None;
    for (i, r) in rows.axis_iter(Axis(0)).enumerate() {
        let r: Vec<f64> = r.iter().copied().collect();
        if let Some(bad) = r.iter().find(|x| !x.is_finite()) {
            return Err(input_error(format!(
                "{name}[{i}]: expected finite numbers, found {bad}"
            )));
        }
        if inverse {
            let (q, _) = repr
                .to_quat(&r, AngleUnit::Rad)
                .map_err(|e| input_error(format!("{name}[{i}]: {}", crate::message(&e))))?;
            out.extend_from_slice(&match scalar_first {
                true => [q.w, q.x, q.y, q.z],
                false => [q.x, q.y, q.z, q.w],
            });
        } else {
            let wxyz = match scalar_first {
                true => [r[0], r[1], r[2], r[3]],
                false => [r[3], r[0], r[1], r[2]],
            };
            let (q, warning) = Repr::Quat
                .to_quat(&wxyz, AngleUnit::Rad)
                .map_err(|e| input_error(format!("{name}[{i}]: {}", crate::message(&e))))?;
            match (&mut warned, warning) {
                (None, Some(w)) => warned = Some((format!("{name}[{i}]: {w}"), 0)),
                (Some((_, others)), Some(_)) => *others += 1,
                _ => {}
            }
            repr.from_quat(q, AngleUnit::Rad, &mut buf);
            out.extend_from_slice(&buf[..6]);
        }
    }
    if let Some((first, others)) = warned {
        let text = match others {
            0 => first,
            n => format!("{first} (and {n} other rows)"),
        };
        let message = std::ffi::CString::new(text).unwrap_or_default();
        PyErr::warn(
            py,
            &py.get_type::<pyo3::exceptions::PyUserWarning>(),
            &message,
            2,
        )?;
    }
    let mut shape = shape;
    *shape.last_mut().expect("checked above") = width_out;
    let array = ArrayD::from_shape_vec(IxDyn(&shape), out)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}
