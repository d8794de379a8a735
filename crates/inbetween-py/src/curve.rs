//! `Curve`: the library's [`inbetween::Curve`] through keys (K, 4), or one per joint through
//! keys (K, J, 4) on shared key times; evaluated at many times at once, the GIL released.

use crate::arrays::{self, Layout, quat_row};
use crate::{input_error, options};
use glam::DVec3;
use inbetween::{CurveOptions, Tcb, Track};
use numpy::{PyArrayDyn, PyReadonlyArrayDyn};
use pyo3::prelude::*;

/// One curve per joint through keys at shared times (see `inbetween.Curve` in docs/python.md).
#[pyclass(module = "inbetween._inbetween", frozen)]
pub struct Curve {
    curves: Vec<inbetween::Curve>,
    layout: Layout,
    scalar_first: bool,
    opts: CurveOptions,
}

/// What `Curve.__init__` takes besides times, rotations and the scheme.
pub struct Keywords<'py> {
    velocities: Option<PyReadonlyArrayDyn<'py, f64>>,
    tcb: Option<PyReadonlyArrayDyn<'py, f64>>,
    start_velocity: Option<PyReadonlyArrayDyn<'py, f64>>,
    end_velocity: Option<PyReadonlyArrayDyn<'py, f64>>,
}

#[pymethods]
impl Curve {
    #[new]
    #[pyo3(signature = (
        times, rotations, scheme = "bezier", *, velocities = None, tcb = None, ends = "chord",
        start_velocity = None, end_velocity = None, path = "shortest", scalar_first = true,
        grid_rate = None, tangent = None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        times: PyReadonlyArrayDyn<'_, f64>,
        rotations: PyReadonlyArrayDyn<'_, f64>,
        scheme: &str,
        velocities: Option<PyReadonlyArrayDyn<'_, f64>>,
        tcb: Option<PyReadonlyArrayDyn<'_, f64>>,
        ends: &str,
        start_velocity: Option<PyReadonlyArrayDyn<'_, f64>>,
        end_velocity: Option<PyReadonlyArrayDyn<'_, f64>>,
        path: &str,
        scalar_first: bool,
        grid_rate: Option<Bound<'_, PyAny>>,
        tangent: Option<&str>,
    ) -> PyResult<Curve> {
        let times = arrays::times(&times, "times")?;
        let (layout, quats) = arrays::quats(&rotations, "rotations", scalar_first)?;
        if layout.rows == 0 {
            return Err(input_error(
                "rotations: expected at least 1 key (one key is a constant), found 0",
            ));
        }
        if times.len() != layout.rows {
            return Err(input_error(format!(
                "times: {} times for {} rotations",
                times.len(),
                layout.rows
            )));
        }
        let keywords = Keywords {
            velocities,
            tcb,
            start_velocity,
            end_velocity,
        };
        let tracks = tracks(&times, quats, layout, &keywords)?;
        let grid_rate = match &grid_rate {
            Some(r) => options::rate("grid_rate", r)?,
            None => inbetween::Fps::DEFAULT,
        };
        let opts = options::with_tangent(options::curve(scheme, ends, path, grid_rate)?, tangent)?;
        let curves = build(py, &tracks, &opts, layout)?;
        Ok(Curve {
            curves,
            layout,
            scalar_first,
            opts,
        })
    }

    /// The rotations at times `t` (N,) with `order=0`, (N, 4) or (N, J, 4) unit quaternions;
    /// `order=1` angular velocity and `order=2` angular acceleration, (N, 3) or (N, J, 3),
    /// rad/s and rad/s², in the world frame, or with `frame="body"` in the body's own axes:
    /// R(q)ᵀ ω and R(q)ᵀ α, where R(q)ᵀ α is also the time derivative of R(q)ᵀ ω (the term
    /// −R(q)ᵀ (ω × ω) of that derivative is zero). A time outside the keys' span (by more than
    /// 1e-9 s) is an error unless `outside="hold"`, which holds the end keys (at rest).
    #[pyo3(signature = (t, order = None, frame = None, outside = None))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArrayDyn<'py, f64>,
        order: Option<Bound<'py, PyAny>>,
        frame: Option<&str>,
        outside: Option<&str>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let body = options::body_frame(frame)?;
        let hold = match outside {
            None | Some("error") => false,
            Some("hold") => true,
            Some(other) => {
                return Err(input_error(format!(
                    "outside: expected \"error\" or \"hold\", found \"{}\"",
                    inbetween::error::shorten(other)
                )));
            }
        };
        let order = match order {
            None => 0,
            Some(o) => crate::options::integer("order", &o, (0, 2))?.ok_or_else(|| {
                input_error(format!(
                    "order: expected 0 (rotation), 1 (angular velocity) or 2 (angular \
                     acceleration), found {}",
                    o.str().map_or_else(|_| "?".to_string(), |s| s.to_string())
                ))
            })?,
        };
        let t_view = t.as_array();
        let t = arrays::times_in_place(&t_view, "t")?;
        // The checks without the GIL: a non-finite time, else one outside the span.
        let span = (!hold)
            .then(|| self.curves.first().map(inbetween::Curve::span))
            .flatten();
        let refused = py.detach(|| {
            if let Some(bad) = t.iter().find(|x| !x.is_finite()) {
                return Some(format!("t: expected finite times, found {bad}"));
            }
            let (lo, hi) = span?;
            t.iter()
                .enumerate()
                .find(|&(_, &x)| x < lo - 1e-9 || x > hi + 1e-9)
                .map(|(i, x)| {
                    format!(
                        "t[{i}]: {x} s is outside the keys' span [{lo}, {hi}] s; \
                         outside=\"hold\" holds the end keys there"
                    )
                })
        });
        if let Some(message) = refused {
            return Err(input_error(message));
        }
        let joints = self.layout.joints;
        let sf = self.scalar_first;
        let curves = &self.curves;
        match order {
            0 => {
                let data = py.detach(|| {
                    evaluate::<4>(curves, &t, |c, t, q, out| {
                        c.rotations(t, q);
                        for (row, &q) in out.iter_mut().zip(q.iter()) {
                            *row = quat_row(q, sf);
                        }
                    })
                });
                arrays::output_flat(py, data, 4, joints)
            }
            1 => {
                let data = py.detach(|| {
                    evaluate::<3>(curves, &t, |c, t, _, out| {
                        for (row, &x) in out.iter_mut().zip(t) {
                            *row = in_frame(c, x, c.angular_velocity(x), body);
                        }
                    })
                });
                arrays::output_flat(py, data, 3, joints)
            }
            // 2, the last of the range `integer` let through.
            _ => {
                let data = py.detach(|| {
                    evaluate::<3>(curves, &t, |c, t, _, out| {
                        for (row, &x) in out.iter_mut().zip(t) {
                            *row = in_frame(c, x, c.angular_acceleration(x), body);
                        }
                    })
                });
                arrays::output_flat(py, data, 3, joints)
            }
        }
    }

    /// The first and last key times, seconds.
    #[getter]
    fn span(&self) -> (f64, f64) {
        self.curves[0].span()
    }

    /// The number of joints, or `None` for keys of shape (K, 4).
    #[getter]
    fn joints(&self) -> Option<usize> {
        self.layout.joints
    }

    /// The scheme's name.
    #[getter]
    fn scheme(&self) -> &'static str {
        self.opts.scheme.name()
    }

    fn __repr__(&self) -> String {
        let (t0, t1) = self.curves[0].span();
        let joints = self
            .layout
            .joints
            .map_or(String::new(), |j| format!(", joints={j}"));
        format!(
            "Curve(scheme={:?}, keys={}{joints}, span=({t0}, {t1}))",
            self.opts.scheme.name(),
            self.layout.rows
        )
    }
}

/// A world-frame rate `v` of curve `c` at time `t` as a row: as it is, or with `body` in the
/// axes of the rotated body, R(q(t))ᵀ v (the inverse rotation of `v`).
#[inline]
fn in_frame(c: &inbetween::Curve, t: f64, v: DVec3, body: bool) -> [f64; 3] {
    if body {
        body_rate(c.rotation(t), v).to_array()
    } else {
        v.to_array()
    }
}

/// A world-frame rate `v` in the axes of a body turned by the unit quaternion `q`: R(q)ᵀ v,
/// that is q⁻¹ v q.
#[inline]
pub(crate) fn body_rate(q: glam::DQuat, v: DVec3) -> DVec3 {
    q.conjugate() * v
}

/// One track per joint: the keys, with the per-key velocities and TCB where given (a row of NaN
/// means none at that key) and the end velocities.
fn tracks(
    times: &[f64],
    quats: Vec<Vec<glam::DQuat>>,
    layout: Layout,
    kw: &Keywords<'_>,
) -> PyResult<Vec<Track>> {
    let per_key = |a: &Option<PyReadonlyArrayDyn<'_, f64>>, name: &str| {
        a.as_ref()
            .map(|a| arrays::vectors(a, name, layout, "rotations"))
            .transpose()
    };
    let velocities = per_key(&kw.velocities, "velocities")?;
    let tcb = per_key(&kw.tcb, "tcb")?;
    let ends = |a: &Option<PyReadonlyArrayDyn<'_, f64>>, name: &str| {
        a.as_ref()
            .map(|a| arrays::end_vectors(a, name, layout.joints))
            .transpose()
    };
    let start = ends(&kw.start_velocity, "start_velocity")?;
    let end = ends(&kw.end_velocity, "end_velocity")?;
    let given = |v: DVec3| (!v.is_nan()).then_some(v);
    let mut tracks = Vec::with_capacity(quats.len());
    for (j, q) in quats.into_iter().enumerate() {
        let at = |what: &str| match layout.joints {
            Some(_) => format!("{what} (joint {j})"),
            None => what.to_string(),
        };
        let fail = |what: &str, e: inbetween::TrackError| input_error(format!("{}: {e}", at(what)));
        let mut t = arrays::track(times, q).map_err(|e| fail("rotations", e))?;
        if let Some(v) = &velocities {
            let v = v[j].iter().map(|&v| given(v)).collect();
            t = t
                .with_key_velocities(v)
                .map_err(|e| fail("velocities", e))?;
        }
        if let Some(k) = &tcb {
            let k = k[j]
                .iter()
                .map(|&v| {
                    given(v).map(|v| Tcb {
                        tension: v.x,
                        continuity: v.y,
                        bias: v.z,
                    })
                })
                .collect();
            t = t.with_key_tcb(k).map_err(|e| fail("tcb", e))?;
        }
        if start.is_some() || end.is_some() {
            let (s, e) = (start.as_ref().map(|s| s[j]), end.as_ref().map(|e| e[j]));
            t = t
                .with_end_velocities(s, e)
                .map_err(|e| fail("start_velocity/end_velocity", e))?;
        }
        tracks.push(t);
    }
    Ok(tracks)
}

/// The curve of each track, built in parallel without the GIL; the first error, located by
/// joint.
pub(crate) fn build(
    py: Python<'_>,
    tracks: &[Track],
    opts: &CurveOptions,
    layout: Layout,
) -> PyResult<Vec<inbetween::Curve>> {
    let built = py.detach(|| inbetween::parallel::map(tracks, |t| inbetween::Curve::new(t, opts)));
    built
        .into_iter()
        .enumerate()
        .map(|(j, c)| c.map_err(|e| curve_error(j, &e, layout)))
        .collect()
}

/// Joint `j`'s curve refused: the message, located by joint when there are joints.
pub(crate) fn curve_error(j: usize, e: &inbetween::InputError, layout: Layout) -> PyErr {
    match layout.joints {
        Some(_) => input_error(format!("joint {j}: {}", crate::message(e))),
        None => input_error(crate::message(e).to_string()),
    }
}

/// Rows (times × joints) per piece of work: the times are cut into pieces of about this many
/// rows, so that one joint (or fewer joints than cores) still uses every core.
const PIECE: usize = 16_384;

/// Times handed to `f` at once (a buffer on the stack).
const SUB: usize = 256;

/// `f(curve, times, scratch, rows)` for every curve and run of at most [`SUB`] times (`scratch`
/// a buffer of as many quaternions), writing the rows
/// of `C` numbers straight into the (N, J, C) layout: the pieces of consecutive times (each a
/// contiguous stretch of the output, every joint of those times) shared among the cores.
fn evaluate<const C: usize>(
    curves: &[inbetween::Curve],
    t: &[f64],
    f: impl Fn(&inbetween::Curve, &[f64], &mut [glam::DQuat], &mut [[f64; C]]) + Sync,
) -> Vec<f64> {
    let joints = curves.len();
    let mut data = vec![0.0; t.len() * joints * C];
    if t.is_empty() || joints == 0 {
        return data;
    }
    let per_piece = (PIECE / joints).max(SUB);
    let pieces: Vec<std::sync::Mutex<(&[f64], &mut [f64])>> = t
        .chunks(per_piece)
        .zip(data.chunks_mut(per_piece * joints * C))
        .map(std::sync::Mutex::new)
        .collect();
    inbetween::parallel::map(&pieces, |piece| {
        let mut piece = piece.lock().unwrap_or_else(|e| e.into_inner());
        let (times, out) = &mut *piece;
        // Buffers filled once a piece, not once a run.
        let mut scratch = [glam::DQuat::IDENTITY; SUB];
        let mut rows = [[0.0; C]; SUB];
        for (s, sub) in times.chunks(SUB).enumerate() {
            if joints == 1 {
                // One joint: the rows are contiguous in the output, written there.
                let at = s * SUB * C;
                let (rows, _) = out[at..at + sub.len() * C].as_chunks_mut::<C>();
                f(&curves[0], sub, &mut scratch[..sub.len()], rows);
                continue;
            }
            for (j, c) in curves.iter().enumerate() {
                let rows = &mut rows[..sub.len()];
                f(c, sub, &mut scratch[..sub.len()], rows);
                for (r, row) in rows.iter().enumerate() {
                    let at = ((s * SUB + r) * joints + j) * C;
                    out[at..at + C].copy_from_slice(row);
                }
            }
        }
    });
    data
}
