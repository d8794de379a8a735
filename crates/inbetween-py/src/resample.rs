//! `resample` and `frame_times`: dense frames at one exact rate onto another, as `interp`
//! writes them (every input frame a key, the output frames those of the exact output grid
//! inside the clip's span, baked by the library's [`inbetween::bake`]).

use crate::arrays::{self, Layout, quat_row};
use crate::curve::curve_error;
use crate::{input_error, options};
use glam::{DQuat, DVec3};
use inbetween::{BakeOptions, Fps, FrameSink};
use numpy::{PyArrayDyn, PyReadonlyArrayDyn};
use pyo3::prelude::*;

/// The times of the frames `resample` writes for `n` input frames at `fps_in` onto `fps_out`:
/// `k/fps_out` for every `k` from 0 to `⌊(n − 1)/fps_in · fps_out⌋` (within 1e-9 s, the frame
/// clock's rule), exact rationals rounded once.
#[pyfunction]
pub fn frame_times<'py>(
    py: Python<'py>,
    n: Bound<'py, PyAny>,
    fps_in: Bound<'py, PyAny>,
    fps_out: Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
    let Some(n) = crate::options::integer("n", &n, (i64::MIN, i64::MAX))? else {
        return Err(input_error(format!(
            "n: expected at least one frame and at most 2^63 - 1, found {}",
            n.str()?
        )));
    };
    if n < 1 {
        return Err(input_error(format!(
            "n: expected at least one frame, found {n}"
        )));
    }
    // At most i64::MAX: a usize on every platform a wheel is built for.
    let n = usize::try_from(n).unwrap_or(usize::MAX);
    let (fps_in, fps_out) = (
        options::rate("fps_in", &fps_in)?,
        options::rate("fps_out", &fps_out)?,
    );
    let (a, b) = grid(n, fps_in, fps_out)?;
    fits(b - a + 1, 1)?;
    let times: Vec<f64> = (a..=b).map(|k| fps_out.time_of(k)).collect();
    Ok(numpy::PyArray1::from_vec(py, times))
}

/// The most numbers a result of `resample` or `frame_times` may hold: 2²⁸ (2 GiB of float64),
/// so that a grid too large for memory is a `ValueError` before anything is allocated, never
/// an allocation failure that aborts the interpreter.
pub const MAX_VALUES: i64 = 1 << 28;

/// An error unless `frames` frames of `per_frame` numbers each fit in [`MAX_VALUES`].
fn fits(frames: i64, per_frame: i64) -> PyResult<()> {
    let values = frames.saturating_mul(per_frame);
    if frames < 0 || values > MAX_VALUES {
        return Err(input_error(format!(
            "the result would hold {frames} frames of {per_frame} numbers, more than the \
             {MAX_VALUES} numbers (2 GiB of float64) a result may hold: resample a shorter \
             span, fewer joints or a lower rate"
        )));
    }
    Ok(())
}

/// The output frames `(first, last)` for `n` input frames.
fn grid(n: usize, fps_in: Fps, fps_out: Fps) -> PyResult<(i64, i64)> {
    if n == 0 {
        return Err(input_error("n: expected at least one frame, found 0"));
    }
    let last = i64::try_from(n - 1).unwrap_or(i64::MAX);
    let end = fps_in.time_of(last);
    if !fps_out.in_range(end) || !fps_in.in_range(end) {
        return Err(input_error(format!(
            "{n} frames at {fps_in} fps span {end} s, beyond what the frame clock supports"
        )));
    }
    Ok(fps_out.frames_between(0.0, end))
}

/// Collects one track's baked rotations (and angular velocities) as output rows, in the
/// caller's quaternion order, sized for the frames to come.
struct Frames {
    rotations: Vec<[f64; 4]>,
    velocities: Vec<[f64; 3]>,
    /// The positions, for a track with translations.
    positions: Vec<[f64; 3]>,
    scalar_first: bool,
    /// Angular velocities in the body's axes (`frame="body"`), else the world's.
    body: bool,
}

impl FrameSink for Frames {
    #[inline]
    fn frame(&mut self, _k: i64, _t: f64, q: DQuat, omega: Option<DVec3>) -> std::io::Result<()> {
        self.rotations.push(quat_row(q, self.scalar_first));
        if let Some(w) = omega {
            let w = if self.body {
                crate::curve::body_rate(q, w)
            } else {
                w
            };
            self.velocities.push(w.to_array());
        }
        Ok(())
    }

    fn frame_at(
        &mut self,
        k: i64,
        time: f64,
        q: DQuat,
        omega: Option<DVec3>,
        position: DVec3,
    ) -> std::io::Result<()> {
        self.positions.push(position.to_array());
        self.frame(k, time, q, omega)
    }
}

/// Frames `rotations` (T, 4) or (T, J, 4) at `fps_in` resampled onto `fps_out`: (M, 4) or
/// (M, J, 4), M = ⌊(T − 1)/fps_in · fps_out⌋ + 1 frames; with `velocity`, also the angular
/// velocities (M, 3) or (M, J, 3), rad/s, world frame (`frame="body"`: the body's axes); with
/// `translations` (T, 3) or (T, J, 3), also the positions at the new frames (M, 3) or (M, J, 3),
/// last in the tuple, as `interp` writes a track's translations.
#[pyfunction]
#[pyo3(signature = (
    rotations, fps_in, fps_out, *, scheme = "bezier", ends = "chord", path = "shortest",
    scalar_first = true, velocity = false, frame = None, translations = None, tangent = None
))]
#[allow(clippy::too_many_arguments)]
pub fn resample<'py>(
    py: Python<'py>,
    rotations: PyReadonlyArrayDyn<'py, f64>,
    fps_in: Bound<'py, PyAny>,
    fps_out: Bound<'py, PyAny>,
    scheme: &str,
    ends: &str,
    path: &str,
    scalar_first: bool,
    velocity: bool,
    frame: Option<&str>,
    translations: Option<PyReadonlyArrayDyn<'py, f64>>,
    tangent: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let body = options::body_frame(frame)?;
    let (fps_in, fps_out) = (
        options::rate("fps_in", &fps_in)?,
        options::rate("fps_out", &fps_out)?,
    );
    let (layout, quats): (Layout, _) = arrays::quats(&rotations, "rotations", scalar_first)?;
    let positions = match &translations {
        Some(p) => {
            let v = arrays::vectors(p, "translations", layout, "rotations")?;
            arrays::finite(&v, "translations", layout)?;
            Some(v)
        }
        None => None,
    };
    let (first, last) = grid(layout.rows, fps_in, fps_out)?;
    let joints = layout.joints.unwrap_or(1) as i64;
    let width = 4 + if velocity { 3 } else { 0 } + if positions.is_some() { 3 } else { 0 };
    fits(last - first + 1, joints * width)?;
    let frames = usize::try_from(last - first + 1).unwrap_or(0);
    let times: Vec<f64> = (0..layout.rows as i64).map(|k| fps_in.time_of(k)).collect();
    let opts = options::with_tangent(options::curve(scheme, ends, path, fps_out)?, tangent)?;
    // Each joint's track and curve built on the cores without the GIL; errors as before: the
    // first joint whose keys are refused, else the first whose curve is.
    let per_joint: Vec<(usize, &[DQuat])> = quats.iter().map(Vec::as_slice).enumerate().collect();
    let built = py.detach(|| {
        inbetween::parallel::map(&per_joint, |&(j, q)| {
            let track = arrays::track(&times, q.to_vec());
            let track = match &positions {
                Some(p) => track.and_then(|t| t.with_translations(p[j].clone())),
                None => track,
            };
            track.map(|t| inbetween::Curve::new(&t, &opts))
        })
    });
    drop(quats);
    let located = |j: usize, what: &str| match layout.joints {
        Some(_) => format!("{what} (joint {j})"),
        None => what.to_string(),
    };
    if let Some((j, Err(e))) = built.iter().enumerate().find(|(_, b)| b.is_err()) {
        return Err(input_error(format!("{}: {e}", located(j, "rotations"))));
    }
    let curves = built
        .into_iter()
        .enumerate()
        .map(|(j, b)| match b {
            Ok(Ok(c)) => Ok(c),
            Ok(Err(e)) => Err(curve_error(j, &e, layout)),
            Err(_) => unreachable!("track errors were reported above"),
        })
        .collect::<PyResult<Vec<inbetween::Curve>>>()?;
    let bake = BakeOptions {
        velocity,
        parallel: false,
    };
    let baked = py.detach(|| {
        inbetween::parallel::map(&curves, |c| {
            let mut sink = Frames {
                rotations: Vec::with_capacity(frames),
                velocities: Vec::with_capacity(if velocity { frames } else { 0 }),
                positions: Vec::with_capacity(if positions.is_some() { frames } else { 0 }),
                scalar_first,
                body,
            };
            inbetween::bake(c, fps_out, bake, &mut sink, &mut |_| {}).map(|()| sink)
        })
    });
    let baked = baked
        .into_iter()
        .collect::<std::io::Result<Vec<Frames>>>()
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    let mut rows = Vec::with_capacity(baked.len());
    let mut w = Vec::with_capacity(baked.len());
    let mut p = Vec::with_capacity(baked.len());
    for f in baked {
        rows.push(f.rotations);
        w.push(f.velocities);
        p.push(f.positions);
    }
    let out: Bound<'py, PyArrayDyn<f64>> = arrays::output(py, &rows, layout.joints)?;
    let p = match positions {
        Some(_) => Some(arrays::output(py, &p, layout.joints)?),
        None => None,
    };
    match (velocity, p) {
        (false, None) => Ok(out.into_any()),
        (false, Some(p)) => Ok((out, p).into_pyobject(py)?.into_any()),
        (true, None) => {
            let w = arrays::output(py, &w, layout.joints)?;
            Ok((out, w).into_pyobject(py)?.into_any())
        }
        (true, Some(p)) => {
            let w = arrays::output(py, &w, layout.joints)?;
            Ok((out, w, p).into_pyobject(py)?.into_any())
        }
    }
}
